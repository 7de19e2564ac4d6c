/* fem_continuation.c - the load path: targets set between solves (pressure or cavity volume,
 * nodal/coupling forces, gravity, prescribed displacements), and the ramp from the committed
 * loads to the targets with a ramp parameter lambda: 0 -> 1 in adaptive substeps (grow after an
 * easy substep, cut and retry from the last converged state after a failed one), commit of
 * converged substeps, and the limit-point diagnosis when the increment falls below dl_min
 * (docs/fem.md "Adaptive load stepping"). Each substep is one Newton solve (fem_newton.c); a
 * dynamic ramp is the same with a time step (fem_dynamics.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_solver_priv.h"
#include "sa_error.h"
#include "sa_log.h"

/* Dead loads and prescribed displacements at ramp parameter lam. */
void fem_cont_apply_loads(FemSolver *s, double lam) {
  s->ct.lam_eval = lam;
  for (int A = 0; A < s->N; A++)
    for (int c = 0; c < 3; c++) {
      int d = 3 * A + c;
      double g = s->ct.g_c[c] + lam * (s->ct.g_t[c] - s->ct.g_c[c]);
      s->as.fdead[d] = s->ct.fn_c[d] + lam * (s->ct.fn_t[d] - s->ct.fn_c[d]) + s->as.mlump[A] * g;
      if (s->dm.eq[d] < 0) {
        s->u[d] = s->ct.up_c[d] + lam * (s->ct.up_t[d] - s->ct.up_c[d]);
        s->x[d] = s->m->xyz[d] + s->u[d];
      }
    }
  if (s->ct.control == FEM_CONTROL_LOAD) s->p = s->ct.p_c + lam * (s->ct.p_t - s->ct.p_c);
  else s->ct.V_goal = s->ct.V_c + lam * (s->ct.V_t - s->ct.V_c);
}

int fem_solver_set_control(FemSolver *s, FemControl control) {
  if (control == FEM_CONTROL_VOLUME)
    SA_REQUIRE(s->as.npf > 0, SA_ERR_INPUT, "volume control needs a pressure surface");
  s->ct.control = control;
  s->ct.V_c = s->ct.V_t = s->V;
  s->ct.p_c = s->ct.p_t = s->p;
  return 0;
}

int fem_solver_set_pressure(FemSolver *s, double p) {
  SA_REQUIRE(isfinite(p), SA_ERR_INPUT, "pressure %g is not finite", p);
  s->ct.p_t = p;
  return 0;
}

int fem_solver_set_volume(FemSolver *s, double volume) {
  SA_REQUIRE(isfinite(volume) && volume > 0, SA_ERR_INPUT, "cavity volume %g must be > 0", volume);
  s->ct.V_t = volume;
  return 0;
}

int fem_solver_set_prescribed(FemSolver *s, int n, const int *nodes, int comp, double value) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "prescribed displacements are set after setup");
  SA_REQUIRE(comp >= 0 && comp < 3, SA_ERR_INPUT, "component %d not in 0..2", comp);
  for (int k = 0; k < n; k++) {
    int d = 3 * nodes[k] + comp;
    SA_REQUIRE(nodes[k] >= 0 && nodes[k] < s->N && s->dm.eq[d] < 0, SA_ERR_INPUT,
               "node %d component %d is not fixed", nodes[k], comp);
    s->ct.up_t[d] = value;
  }
  return 0;
}

int fem_solver_set_nodal_forces(FemSolver *s, int n, const int *nodes, const double *f) {
  for (int k = 0; k < n; k++) {
    int A = nodes[k];
    if (A < 0 || A >= s->N) return SA_ERROR(SA_ERR_INPUT, "node %d out of range", A);
    s->ct.fn_t[3 * A] = f[3 * k];
    s->ct.fn_t[3 * A + 1] = f[3 * k + 1];
    s->ct.fn_t[3 * A + 2] = f[3 * k + 2];
  }
  return 0;
}

int fem_solver_set_static_interval(FemSolver *s, double dt) {
  SA_REQUIRE(dt >= 0 && isfinite(dt), SA_ERR_INPUT, "static interval %g must be >= 0", dt);
  s->ct.static_dt = dt;
  return 0;
}

void fem_solver_clear_nodal_forces(FemSolver *s) {
  memset(s->ct.fn_t, 0, (size_t)s->ndof * sizeof *s->ct.fn_t);
}

void fem_solver_set_monitor(FemSolver *s, FemMonitor fn, void *ctx) {
  s->ct.mon = fn;
  s->ct.mon_ctx = ctx;
}

/* Only the pressure is ramped in this solve (dead loads, gravity, prescribed values fixed). */
static int only_pressure(const FemSolver *s) {
  for (int c = 0; c < 3; c++)
    if (s->ct.g_t[c] != s->ct.g_c[c]) return 0;
  for (int d = 0; d < s->ndof; d++)
    if (s->ct.fn_t[d] != s->ct.fn_c[d] || s->ct.up_t[d] != s->ct.up_c[d]) return 0;
  return 1;
}

static void restore_last(FemSolver *s) {
  memcpy(s->u, s->u_last, (size_t)s->ndof * sizeof *s->u);
  fem_dyn_restore(s);
  s->p = s->ct.p_last;
  fem_set_x(s);
}

static void commit_substep(FemSolver *s, double dt) {
  memcpy(s->u_prev, s->u_last, (size_t)s->ndof * sizeof *s->u);
  memcpy(s->u_last, s->u, (size_t)s->ndof * sizeof *s->u);
  fem_dyn_commit(s);
  double dV = s->V - s->ct.V_last, dP = s->p - s->ct.p_last;
  if (s->as.npf > 0 && fabs(dV) > 1e-12 * s->V_ref && s->ct.slope0 == 0.0 && dP != 0.0)
    s->ct.slope0 = dP / dV;
  s->ct.p_prev = s->ct.p_last;
  s->ct.p_last = s->p;
  s->ct.V_prev = s->ct.V_last;
  s->ct.V_last = s->V;
  double *h = s->as.hist_c;
  s->as.hist_c = s->as.hist_t;
  s->as.hist_t = h;
  s->time += dt;
  s->ct.fail_not_pd = 0;
  for (int c = 0; c < s->as.ncontrib; c++)
    if (s->as.contrib[c].commit) s->as.contrib[c].commit(s->as.contrib[c].ctx, s->x);
}

/* Loads reached at ramp parameter lam become the committed loads. */
static void commit_loads(FemSolver *s, double lam) {
  for (int d = 0; d < s->ndof; d++) {
    s->ct.fn_c[d] += lam * (s->ct.fn_t[d] - s->ct.fn_c[d]);
    s->ct.up_c[d] += lam * (s->ct.up_t[d] - s->ct.up_c[d]);
  }
  for (int c = 0; c < 3; c++) s->ct.g_c[c] += lam * (s->ct.g_t[c] - s->ct.g_c[c]);
  if (s->ct.control == FEM_CONTROL_LOAD) s->ct.p_c += lam * (s->ct.p_t - s->ct.p_c);
  else {
    s->ct.V_c += lam * (s->ct.V_t - s->ct.V_c);
    s->ct.p_c = s->ct.p_t = s->p;
  }
  s->ct.lam_total += lam;
}

static int diagnose_failure(FemSolver *s, double lam) {
  double slope = (s->ct.V_last != s->ct.V_prev) ? (s->ct.p_last - s->ct.p_prev) / (s->ct.V_last - s->ct.V_prev) : NAN;
  int flat = s->as.npf > 0 && s->ct.slope0 > 0 && isfinite(slope) && slope < 0.05 * s->ct.slope0;
  commit_loads(s, lam);
  if (s->ct.control == FEM_CONTROL_LOAD && (s->ct.fail_not_pd || flat)) {
    snprintf(s->ct.rep.reason, sizeof s->ct.rep.reason,
             "limit point under load control at p = %.6g Pa, V = %.6g m^3: increment cut below "
             "%.1e; %s%s dp/dV = %.3g Pa/m^3 (initially %.3g); continue with volume control",
             s->ct.p_last, s->ct.V_last, s->prm.dl_min,
             s->ct.fail_not_pd ? "tangent lost positive definiteness (CHOLMOD); " : "",
             flat ? "pressure-volume curve flat:" : "", slope, s->ct.slope0);
    return SA_ERROR(SA_ERR_LIMIT_POINT, "%s", s->ct.rep.reason);
  }
  snprintf(s->ct.rep.reason, sizeof s->ct.rep.reason,
           "increment cut below %.1e at ramp parameter %.6g (p = %.6g Pa); last failure: %s",
           s->prm.dl_min, lam, s->ct.p_last, s->ct.last_fail);
  return SA_ERROR(SA_ERR_STEP_TOO_SMALL, "%s", s->ct.rep.reason);
}

/* After a static solve standing for the interval static_dt: the mean velocity over the solve,
 * v = (u - u_start) / dt, becomes the state's velocity (the read-back and the start of a later
 * dynamic step), a = 0, and time advances by dt. */
static void static_velocities(FemSolver *s) {
  for (int d = 0; d < s->ndof; d++) {
    s->dy.v[d] = s->dy.v_last[d] = (s->u[d] - s->u_start[d]) / s->ct.static_dt;
    s->dy.acc[d] = s->dy.a_last[d] = 0.0;
  }
  s->time += s->ct.static_dt;
}

/* FEM_PREDICT_EXTRAPOLATE: free dofs u = u_n + r (u_n - u_n-1) with r = (p - p_n)/(p_n - p_n-1),
 * the secant through the last two converged states in the pressure, when both are static and
 * load controlled with only the pressure changing (0 < r <= 4). Judged by iterations to converge
 * and increments accepted, not by the first residual, which the extrapolated state makes
 * larger (docs/fem_time_to_accuracy.md). Returns 1 when applied. */
static int extrapolate(FemSolver *s) {
  if (s->prm.predictor != FEM_PREDICT_EXTRAPOLATE || s->ct.control != FEM_CONTROL_LOAD) return 0;
  double dp0 = s->ct.p_last - s->ct.p_prev;
  if (dp0 == 0.0 || s->ct.n_static_commits < 2) return 0;
  double r = (s->p - s->ct.p_last) / dp0;
  if (!(r > 0.0 && r <= 4.0)) return 0;
  for (int d = 0; d < s->ndof; d++)
    if (s->dm.eq[d] >= 0) s->u[d] = s->u_last[d] + r * (s->u_last[d] - s->u_prev[d]);
  fem_set_x(s);
  return 1;
}

int fem_cont_ramp(FemSolver *s, int dynamic, double dt_total) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_setup must be called before solving");
  SA_REQUIRE(!dynamic || s->ct.control == FEM_CONTROL_LOAD, SA_ERR_INPUT,
             "implicit dynamics supports load control only");
  memset(&s->ct.rep, 0, sizeof s->ct.rep);
  double lam = 0.0, dl = s->ct.dl_keep > 0 ? s->ct.dl_keep : s->prm.dl_init;
  s->ct.fail_not_pd = 0;
  memcpy(s->u_start, s->u_last, (size_t)s->ndof * sizeof *s->u);
  if (!dynamic) fem_dyn_rest(s);
  while (lam < 1.0 - 1e-12) {
    double dl_try = dl;
    if (dl > 1.0 - lam || 1.0 - lam - dl < 1e-9) dl = 1.0 - lam;
    double lam_b = lam + dl;
    fem_cont_apply_loads(s, lam_b);
    /* No extrapolation predictor: for a nearly incompressible solid a linearly extrapolated
     * displacement changes element volumes to second order and kappa times that gives a far
     * worse start than the last converged state (measured: residual x 600). The first Newton
     * iteration from the converged state is the tangent predictor. */
    StepKind sk = {0};
    if (dynamic) sk = fem_dyn_step_kind(s, dl * dt_total);
    else sk.law_dt = dl * s->ct.static_dt;
    s->nw.extrapolated = !dynamic && extrapolate(s);
    int iters = 0;
    s->ct.step_count++;
    s->nw.saw_not_pd = 0;
    s->nw.lu_substep = 0;
    int rc = fem_newton_substep(s, &sk, s->ct.step_count, &iters);
    s->ct.rep.newton_reason = s->nw.reason;
    if (s->nw.saw_not_pd)
      sa_log(SA_LOG_DEBUG, "fem", "step %d: %d of %d factorisations by UMFPACK LU",
             s->ct.step_count, s->nw.lu_substep, iters);
    s->ct.rep.newton_iters += iters;
    s->ct.rep.last_dl = dl;
    if (rc == 0) {
      commit_substep(s, sk.dt);
      /* the secant predictor needs two static, pressure-only converged states in a row */
      s->ct.n_static_commits = dynamic || !only_pressure(s) ? 0 : s->ct.n_static_commits + 1;
      /* iters == 0: the factors are still those of the state before; none after a pattern
       * rebuild in the last assembly */
      if (iters > 0 && s->nw.have_factors) {
        s->nw.fact_converged = 1;
        s->nw.fact_dynamic = sk.dynamic;
        s->nw.fact_dt = sk.dt;
        s->nw.fact_alpha = sk.alpha;
      }
      lam = lam_b;
      s->ct.rep.substeps++;
      s->ct.rep.lambda = lam;
      sa_log(SA_LOG_DEBUG, "fem", "step %d converged: lambda %.4f (dl %.3g), %d iterations, "
             "p %.6g Pa, V %.6g m^3", s->ct.step_count, lam, dl, iters, s->p, s->V);
      dl = dl_try; /* a cropped last increment does not shrink the next ramp's */
      if (iters <= s->prm.easy_iter) dl = fmin(dl * s->prm.grow, s->prm.dl_max);
      s->ct.dl_keep = dl;
      if (s->ct.mon) {
        int mrc = s->ct.mon(s, s->ct.mon_ctx);
        if (mrc) {
          commit_loads(s, lam);
          return sa_error_push(mrc, __func__, __FILE__, __LINE__);
        }
      }
      continue;
    }
    if (rc == SA_ERR_INTERRUPTED) {
      /* leave the solver at the last converged state: the caller reports it (summary,
       * checkpoint), not the abandoned iterate */
      restore_last(s);
      fem_cont_apply_loads(s, lam);
    }
    if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    snprintf(s->ct.last_fail, sizeof s->ct.last_fail, "%s", sa_error_message());
    sa_error_clear();
    restore_last(s);
    s->nw.fact_converged = 0; /* the factors belong to a failed iterate */
    s->ct.rep.cuts++;
    dl *= s->prm.cut;
    s->ct.dl_keep = dl;
    sa_log(SA_LOG_INFO, "fem", "step %d failed (%s): increment cut to %.3g", s->ct.step_count,
           s->ct.last_fail, dl);
    if (dl < s->prm.dl_min) {
      fem_cont_apply_loads(s, lam);
      return diagnose_failure(s, lam);
    }
  }
  commit_loads(s, 1.0);
  if (!dynamic && s->ct.static_dt > 0) static_velocities(s);
  s->ct.rep.lambda = 1.0;
  snprintf(s->ct.rep.reason, sizeof s->ct.rep.reason,
           "converged: targets reached in %d substep(s), %d cut(s), %d Newton iterations",
           s->ct.rep.substeps, s->ct.rep.cuts, s->ct.rep.newton_iters);
  return 0;
}

int fem_solver_solve(FemSolver *s) {
  SA_CHECK(fem_cont_ramp(s, 0, 0.0));
  return 0;
}

void fem_solver_report(const FemSolver *s, FemSolveReport *rep) { *rep = s->ct.rep; }

double fem_solver_load_factor(const FemSolver *s) { return s->ct.lam_eval; }

void fem_cont_free(FemContinuation *ct) {
  free(ct->fn_c);
  free(ct->fn_t);
  free(ct->up_c);
  free(ct->up_t);
}

