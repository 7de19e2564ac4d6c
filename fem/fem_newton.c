/* fem_newton.c - one load substep by Newton-Raphson (docs/fem.md "Newton-Raphson").
 *
 *   R(u, p) = f_int(u) + f_c(u) - f_dead - p q(u)          (fem_assemble.c)
 *   K du = -R                                               load control
 *   K a = -R,  K b = q,  dp = -(c + g.a)/(g.b),  du = a + dp b,  c = V(u) - V_goal,  g = dV/du
 *                                                           volume control (bordered system)
 * Dynamic substeps add the HHT inertia terms (fem_dynamics.c).
 *
 * Pieces: the predictor and the factor-reuse plan (decided before the tangent is assembled:
 * a reused direction assembles no tangent and solves with the values its factors came from),
 * lazy backtracking on domain errors (inverted element, a law's failed return mapping, the
 * user's domain hook), NaN or merit blow-up, the direction (plain or bordered), and the
 * stopping tests, each ending with a FemNewtonReason (fem.h) and its message. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_solver_priv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"

const char *fem_newton_reason_string(FemNewtonReason r) {
  switch (r) {
  case FEM_NEWTON_ITERATING: return "iterating";
  case FEM_CONVERGED_RESIDUAL: return "converged: residual";
  case FEM_CONVERGED_UPDATE: return "converged: update";
  case FEM_DIVERGED_MAX_ITER: return "diverged: iteration limit";
  case FEM_DIVERGED_STALLED: return "diverged: stalled";
  case FEM_DIVERGED_GROWTH: return "diverged: residual growth";
  case FEM_DIVERGED_DOMAIN: return "diverged: outside the domain (inverted element, law, hook)";
  case FEM_DIVERGED_NAN: return "diverged: not a number";
  case FEM_DIVERGED_LINEAR_SOLVE: return "diverged: linear solve";
  case FEM_DIVERGED_BORDERED: return "diverged: bordered system singular";
  }
  return "unknown";
}

void fem_solver_set_domain_check(FemSolver *s, FemDomainCheck fn, void *ctx) {
  s->nw.domain_check = fn;
  s->nw.domain_ctx = ctx;
}

/* Residual on free dofs at the last assembled state; returns ||R||, and the force scale fref
 * (max of the internal-force norm incl. reactions and the external-force norm). */
static double residual(FemSolver *s, const StepKind *sk, double *fref) {
  if (sk->dynamic) return fem_dyn_residual(s, sk, fref);
  const double *fcon = s->as.ncontrib ? s->as.fcon : NULL;
  double fe2 = 0, fi2 = 0, r2 = 0;
  for (int d = 0; d < s->ndof; d++) {
    double fext = s->as.fdead[d] + s->p * s->as.q[d];
    double fi = s->as.fint[d];
    if (fcon) fi += fcon[d];
    double r = fi - fext;
    fi2 += fi * fi;
    int k = s->dm.eq[d];
    if (k < 0) continue;
    fe2 += fext * fext;
    s->nw.R[k] = r;
    r2 += r * r;
  }
  *fref = fmax(sqrt(fi2), sqrt(fe2));
  return sqrt(r2);
}

/* CHOLMOD-only attempt (symmetric = 2); > 0 when not positive definite. */
static int try_cholesky(FemSolver *s) {
  double t0 = sa_time_now();
  int rc = fem_linsolve_factorize(s->dm.lin, s->as.val, 2);
  s->st.t_factor += sa_time_now() - t0;
  if (rc == SA_ERR_NOT_SPD) s->st.n_not_pd++;
  return rc;
}

/* FEM_INDEFINITE_MODIFY: Cholesky of the consistent tangent, else of K_int + beta p K_q with
 * beta = p_last/p (the converged pressure's load stiffness: at the converged state this is
 * its own equilibrium tangent, positive definite on a stable path), else beta = 0. A positive
 * definite approximation of the Hessian of the potential gives a descent direction that the
 * energy line search can damp. Returns 0 (CHOLMOD factors of val), SA_ERR_NOT_SPD when every
 * attempt failed (val restored to the consistent tangent), < 0 on a library error. */
static int factorize_modified(FemSolver *s, double p_asm, int at_iterate, int step_back) {
  int rc = try_cholesky(s);
  if (rc <= 0) return rc;
  /* Away from the converged state (at_iterate) K_int + beta p K_q is no equilibrium tangent,
   * and on the actuator ramp every consistent tangent that failed there had K_int indefinite
   * too (docs/fem_time_to_accuracy.md): while the caller can still step back toward the last
   * accepted iterate it does so at once (step_back), else K_int alone is tried. Each saved
   * attempt is a factorisation. */
  if (step_back) {
    s->nw.saw_not_pd = 1;
    s->nw.have_factors = s->nw.fact_converged = 0; /* lin holds a failed factorisation */
    s->nw.indef_step = 1;
    return SA_ERR_NOT_SPD;
  }
  /* without a follower pressure (p_asm = 0: dead loads, e.g. the grains' wall forces) the
   * consistent tangent is K_int already: nothing to reduce, no second attempt */
  double betas[2] = {0.0, 0.0}, cur = 1.0;
  int nb = 0;
  if (!at_iterate && s->ct.p_last > 0 && s->ct.p_last < p_asm) betas[nb++] = s->ct.p_last / p_asm;
  if (p_asm > 0) betas[nb++] = 0.0;
  for (int i = 0; i < nb; i++) {
    if (sa_interrupted()) break; /* each attempt is a factorisation (seconds) */
    fem_asm_add_load_stiffness(s, s->x, (betas[i] - cur) * p_asm);
    cur = betas[i];
    rc = try_cholesky(s);
    if (rc <= 0) {
      if (rc == 0) {
        s->st.n_modified++;
        sa_log(SA_LOG_DEBUG, "fem", "tangent not positive definite: Cholesky of K_int + %.3g p K_q",
               cur);
      }
      return rc;
    }
  }
  fem_asm_add_load_stiffness(s, s->x, (1.0 - cur) * p_asm);
  if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted between factorisations");
  return SA_ERR_NOT_SPD;
}

/* p_asm: the pressure whose load stiffness the assembled tangent holds. */
static int factorize(FemSolver *s, const StepKind *sk, double p_asm, int eff_done,
                     int at_iterate, int step_back) {
  if (sk->dynamic && !eff_done) fem_dyn_effective_tangent(s, sk);
  /* CHOLMOD at every iteration: a tangent that is indefinite at the first iteration of a
   * substep (the load increment applied to the converged state) is usually positive definite
   * again near the new equilibrium, and a failed CHOLMOD attempt costs at most one Cholesky
   * (quick return at the first non-positive pivot), ~6x less than the LU it would replace. */
  /* The laws' flags decide first (a non-associated plastic region makes the tangent
   * unsymmetric as soon as it yields); with symmetric laws the measured asymmetry still guards
   * against an unsymmetric contributor (e.g. frictional contact). */
  int sym = s->prm.linsolver == FEM_LINSOLVER_AUTO && !s->nw.laws_unsym;
  if (sym) {
    double asym = fem_linsolve_asymmetry(s->dm.lin, s->as.val);
    s->st.asymmetry = asym;
    if (asym > s->prm.sym_tol) {
      sym = 0;
      sa_log(s->nw.last_sym ? SA_LOG_INFO : SA_LOG_DEBUG, "fem",
             "tangent not symmetric (max|K-K^T|/max|K| = %.2e > %.0e): UMFPACK LU", asym,
             s->prm.sym_tol);
    }
  }
  int rc;
  s->nw.indef_step = 0;
  /* Under load control (static or dynamic, with or without a follower pressure) an indefinite
   * tangent means the iterate or the increment went too far: step back or cut, never LU.
   * Volume control keeps the LU: there an indefinite tangent past a limit point is the path. */
  if (sym && s->prm.indefinite == FEM_INDEFINITE_MODIFY && s->ct.control == FEM_CONTROL_LOAD) {
    rc = factorize_modified(s, p_asm, at_iterate, step_back);
    if (rc > 0 && s->nw.indef_step) /* step back (not a K_int failure: no limit-point flag) */
      return SA_ERROR(SA_ERR_NOT_SPD, "tangent not positive definite at iteration past the "
                      "first: step back");
    if (rc == 0) {
      s->st.n_factor++;
      s->st.n_chol++;
      s->nw.last_sym = 1;
      s->nw.have_factors = 1;
      return 0;
    }
    if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    /* even K_int is not positive definite at this iterate: the increment carried it too far
     * (or the path is at a limit point); cut the increment rather than take an LU direction
     * that need not descend (cheaper: LU costs ~6 Cholesky; measured in
     * docs/fem_time_to_accuracy.md). A limit point is still diagnosed: fail_not_pd is set. */
    s->nw.saw_not_pd = s->ct.fail_not_pd = 1;
    s->nw.have_factors = s->nw.fact_converged = 0; /* lin holds a failed factorisation */
    s->nw.indef_step = 1;
    return SA_ERROR(SA_ERR_NOT_SPD, "tangent not positive definite even without the load "
                    "stiffness (indefinite = modify): increment too large or limit point");
  }
  double t0 = sa_time_now();
  rc = fem_linsolve_factorize(s->dm.lin, s->as.val, sym);
  s->st.t_factor += sa_time_now() - t0;
  s->st.n_factor++;
  FemLinInfo li;
  fem_linsolve_info(s->dm.lin, &li);
  if (li.not_pd) {
    s->st.n_not_pd++;
    sa_log(s->nw.saw_not_pd ? SA_LOG_DEBUG : SA_LOG_INFO, "fem",
           "tangent not positive definite (CHOLMOD): UMFPACK LU for this iteration");
    s->nw.saw_not_pd = s->ct.fail_not_pd = 1;
  }
  if (rc == 0 && li.kind == FEM_LIN_UMFPACK) {
    s->nw.lu_substep++;
    s->ct.rep.lu_fallbacks++;
    s->st.n_lu++;
  } else if (rc == 0) {
    s->st.n_chol++;
  }
  s->nw.last_sym = (rc == 0 && li.kind == FEM_LIN_CHOLMOD);
  s->nw.have_factors = rc == 0;
  return rc;
}

static int linsolve(FemSolver *s, const double *b, double *x) {
  double t0 = sa_time_now();
  int rc = fem_linsolve_solve(s->dm.lin, b, x);
  s->st.t_solve += sa_time_now() - t0;
  s->st.n_solve++;
  return rc;
}

/* Preconditioned CG on K x = b (K: the tangent values in val, full pattern; preconditioner:
 * the factors held by lin, those of an earlier iterate). Returns 0 when |K x - b| <= rtol |b|
 * within maxit iterations, 1 when not (limit, or p.Kp <= 0: the tangent is not positive
 * definite along p and CG's minimisation breaks down), < 0 on a solve error. */
static int pcg(FemSolver *s, const double *b, double *x, int maxit, double rtol, int *its) {
  const int n = s->dm.nfree;
  const int *cp = s->dm.colptr, *ri = s->dm.rowind;
  const double *K = s->as.val;
  double *r = s->nw.kr, *z = s->nw.kz, *p = s->nw.kp, *q = s->nw.kq;
  memset(x, 0, (size_t)n * sizeof *x);
  memcpy(r, b, (size_t)n * sizeof *r);
  double bn = fem_nrm2(b, n);
  *its = 0;
  if (bn == 0.0) return 0;
  SA_CHECK(linsolve(s, r, z));
  memcpy(p, z, (size_t)n * sizeof *p);
  double rz = fem_dot(r, z, n);
  for (int it = 1; it <= maxit; it++) {
    *its = it;
    memset(q, 0, (size_t)n * sizeof *q);
    for (int j = 0; j < n; j++) {
      double pj = p[j];
      for (int k = cp[j]; k < cp[j + 1]; k++) q[ri[k]] += K[k] * pj;
    }
    double pq = fem_dot(p, q, n);
    if (!(pq > 0.0)) return 1;
    double a = rz / pq;
    for (int i = 0; i < n; i++) {
      x[i] += a * p[i];
      r[i] -= a * q[i];
    }
    double rel = fem_nrm2(r, n) / bn;
    if (rel <= rtol) return 0;
    /* Abandon early when the mean reduction per iteration so far, continued to maxit, would
     * still miss rtol by 10x: an attempt that fails costs maxit products and factor solves,
     * about half a factorisation at maxit = 10 (32 of 92 attempts on the actuator ramp failed
     * after all 10; docs/fem_time_to_accuracy.md). PCG converges at least as fast later, so
     * the test errs toward going on. */
    if (it >= 3 && it < maxit && rel * pow(rel, (double)(maxit - it) / it) > 10.0 * rtol) return 1;
    SA_CHECK(linsolve(s, r, z));
    double rz1 = fem_dot(r, z, n), be = rz1 / rz;
    rz = rz1;
    for (int i = 0; i < n; i++) p[i] = z[i] + be * p[i];
  }
  return 1;
}

/* GMRES' preconditioner: a solve with the held factors. */
static int precond(void *ctx, const double *r, double *z) {
  FemSolver *s = ctx;
  double t0 = sa_time_now();
  int rc = fem_linsolve_solve_factors(s->dm.lin, r, z);
  s->st.t_solve += sa_time_now() - t0;
  s->st.n_solve++;
  return rc;
}

/* The tangent in s->as.val is symmetric: no law declares otherwise and its measured asymmetry
 * is within sym_tol (as factorize() decides). */
static int tangent_symmetric(FemSolver *s) {
  if (s->nw.laws_unsym) return 0;
  return fem_linsolve_asymmetry(s->dm.lin, s->as.val) <= s->prm.sym_tol;
}

enum { LS_MEMORY_MAX = 8 }; /* largest ls_memory (fem.h) */

/* Iteration state of one substep. */
typedef struct {
  int vol, it, ls, stall, nfresh, have_fact, fresh_last, reuse, krylov_last;
  double r_prev, r_first, merit_prev, step_len, dp, gb, du_norm, qnorm, p_pred;
  int emerit;       /* the energy merit applies to this substep */
  int ls_exhausted; /* the last energy line search found no sufficient decrease */
  int stepped_back; /* the current direction was stepped back (indefinite tangent) */
  int since_best;   /* iterations since |R| last fell below half its best since it 1 */
  double r_best;
  double p_asm;     /* pressure of the load stiffness in the assembled tangent */
  double pi_hist[LS_MEMORY_MAX]; /* potential at the last accepted iterates (non-monotone) */
  int n_hist;
  double pi_ref;     /* reference of the Armijo test: max of pi_hist (Pi(0) when monotone) */
  double pi, pi_prev, pi_scale, slope; /* potential now / at the accepted iterate, its scale,
                                        * Pi'(0) = R.du along the last direction */
} Iter;

/* Total potential of a static, load-controlled state without contributors: stored energy minus
 * the work of the follower pressure (a potential with the rim clamped: p V(u)) and of the dead
 * loads. pi_scale: the size of its terms, for the round-off allowance of the Armijo test. */
static double potential(const FemSolver *s, double *pi_scale) {
  double wd = 0.0;
  for (int d = 0; d < s->ndof; d++) wd += s->as.fdead[d] * s->u[d];
  *pi_scale = fabs(s->as.energy) + fabs(s->p * s->V) + fabs(wd);
  return s->as.energy - s->p * s->V - wd;
}

/* The energy merit needs p V(u) to be the pressure's potential on the free dofs: dV/du = q
 * there (true when the rim of the pressure surface is fixed or lies on planes through the
 * origin: docs/fem.md). Checked at the first assembly of every substep, O(ndof). */
static int potential_consistent(const FemSolver *s) {
  double dmax = 0.0, qmax = 0.0;
  for (int d = 0; d < s->ndof; d++) {
    if (s->dm.eq[d] < 0) continue;
    dmax = fmax(dmax, fabs(s->as.gv[d] - s->as.q[d]));
    qmax = fmax(qmax, fabs(s->as.q[d]));
  }
  return dmax <= 1e-8 * qmax;
}

/* Assembly of the trial state (residual only when the plan is to reuse factors), the domain
 * hook, residual and merit. Returns the assembly code (0, SA_ERR_INVERTED, SA_ERR_DOMAIN, or
 * < 0 fatal). */
static int evaluate(FemSolver *s, const StepKind *sk, Iter *t, int plan_reuse, double *rnorm,
                    double *fref, double *c, double *merit) {
  double p_asm = t->it == 0 ? t->p_pred : s->p;
  int rc = fem_asm_newton(s, s->x, p_asm, !plan_reuse);
  if (!plan_reuse) t->p_asm = p_asm;
  if (rc == 0 && s->nw.domain_check && s->nw.domain_check(s, s->x, s->nw.domain_ctx)) {
    sa_error_clear();
    rc = SA_ERR_DOMAIN;
  }
  *fref = 0, *rnorm = INFINITY, *c = 0, *merit = INFINITY;
  if (rc == 0) {
    *rnorm = residual(s, sk, fref);
    if (t->vol) *c = s->V - s->ct.V_goal;
    /* merit: |R| plus, under volume control, the constraint violation in force units
     * (|q| |c| / (g.b): the pressure error that c implies, times the load per pressure) */
    *merit = *rnorm;
    if (t->vol && t->gb != 0.0) *merit += t->qnorm * fabs(*c) / fabs(t->gb);
    if (t->emerit) t->pi = potential(s, &t->pi_scale);
  }
  return rc;
}

/* Stopping tests at an accepted iterate: > 0 converged, < 0 diverged, 0 go on. */
static FemNewtonReason stop_test(FemSolver *s, Iter *t, double rnorm, double fref, double c) {
  if (t->it <= 1) t->r_first = fmax(t->r_first, rnorm); /* it 0 may be ~0 under volume control */
  /* converged: residual below tolerance, or (round-off floor of a stiff, nearly
   * incompressible problem) the last update negligible against the displacement */
  int vol_ok = !t->vol || fabs(c) <= s->prm.vtol * s->V_ref;
  if (rnorm <= s->prm.rtol * fref + s->prm.atol && vol_ok) return FEM_CONVERGED_RESIDUAL;
  if (t->it > 0 && t->ls == 0 && t->du_norm <= s->prm.utol * fem_nrm2(s->u, s->ndof) && vol_ok)
    return FEM_CONVERGED_UPDATE;
  if (t->nfresh >= s->prm.max_iter || t->it >= 4 * s->prm.max_iter) {
    SA_ERROR(SA_ERR_NOT_CONVERGED, "no convergence in %d iterations (|R| %.3e, %.3e x "
             "tolerance)", t->it, rnorm, rnorm / (s->prm.rtol * fref + s->prm.atol));
    return FEM_DIVERGED_MAX_ITER;
  }
  /* Stalled: under the energy merit, no sufficient decrease of the potential along the last
   * descent direction (its line search exhausted); the residual norm is not the merit there
   * and rises and falls by 10x between iterations that all decrease the potential (measured:
   * a 15 kPa substep of the actuator was declared stalled at |R| 10 -> 8 -> 7.5 -> 5.5 -> 4.8
   * -> 2.8, then cut and redone as two; docs/fem_time_to_accuracy.md). Otherwise: |R| not
   * halved. A retry of the same direction after a step-back is no new iteration here.
   * Backstop under the energy merit (past a limit point the potential is unbounded below and
   * every line search succeeds): |R| not below half its best since iteration 1 in
   * 4 max_stall iterations (the longest such run on the actuator ramp was 11). */
  int em = t->emerit && t->slope < 0.0;
  if (!t->stepped_back) {
    if (em)
      t->stall = t->ls_exhausted ? t->stall + 1 : 0;
    else
      t->stall = (t->it > 1 && rnorm > 0.5 * t->r_prev) ? t->stall + 1 : 0;
    if (t->it >= 1 && (t->r_best < 0 || rnorm < 0.5 * t->r_best)) {
      t->r_best = rnorm;
      t->since_best = 0;
    } else if (t->it >= 1) {
      t->since_best++;
    }
  }
  if (t->stall >= s->prm.max_stall) {
    if (em)
      SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton stalled (no sufficient decrease of the potential "
               "in %d line searches, |R| %.3e)", t->stall, rnorm);
    else
      SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton stalled (|R| %.3e not halved in %d iterations)",
               rnorm, t->stall);
    return FEM_DIVERGED_STALLED;
  }
  if (em && t->since_best >= 4 * s->prm.max_stall) {
    SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton stalled (|R| %.3e not below half its best %.3e in "
             "%d iterations)", rnorm, t->r_best, t->since_best);
    return FEM_DIVERGED_STALLED;
  }
  if (t->it >= 3 && rnorm > 1e6 * t->r_first) {
    SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton diverging (|R| grew from %.3e to %.3e)", t->r_first,
             rnorm);
    return FEM_DIVERGED_GROWTH;
  }
  return FEM_NEWTON_ITERATING;
}

/* Newton direction du (and dp under volume control) with fresh or reused factors, then the
 * full step. Returns 0, or the failure code with *why set. */
static int direction(FemSolver *s, const StepKind *sk, Iter *t, int plan_reuse, double rnorm,
                     double rate, double c, double merit, FemNewtonReason *why) {
  const int nf = s->dm.nfree;
  int use_old = t->it == 0 ? t->reuse
                           : (s->prm.reuse_rate > 0 && t->have_fact && t->ls == 0 &&
                              (t->fresh_last || rate <= s->prm.reuse_rate));
  int rc = 0;
  if (!use_old && plan_reuse) { /* tentative reuse rejected: the tangent at this iterate */
    rc = fem_asm_newton(s, s->x, s->p, 1);
    t->p_asm = s->p;
    if (rc) {
      *why = FEM_DIVERGED_DOMAIN;
      if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
      return SA_ERROR(SA_ERR_INVERTED, "%d element(s) inverted at iteration %d",
                      s->as.n_inverted, t->it);
    }
  }
  /* Krylov on the last factors (krylov_max > 0): the tangent of this iterate is assembled,
   * the factors are of an earlier one; to krylov_rtol, else refactorise. PCG when both are
   * symmetric (Cholesky factors, a tangent symmetric to sym_tol), GMRES otherwise (LU
   * factors, or a tangent made unsymmetric by friction or non-associated flow). */
  int krylov = 0, eff_done = 0;
  if (!use_old && s->prm.krylov_max > 0 && s->nw.have_factors && !t->vol && t->it > 0) {
    if (sk->dynamic) fem_dyn_effective_tangent(s, sk);
    eff_done = 1;
    for (int k = 0; k < nf; k++) s->nw.rhs[k] = -s->nw.R[k];
    int its = 0, prc;
    double t0 = sa_time_now();
    if (s->nw.last_sym && tangent_symmetric(s)) { /* the O(nnz) scan only with Cholesky factors */
      prc = pcg(s, s->nw.rhs, s->nw.da, s->prm.krylov_max, s->prm.krylov_rtol, &its);
    } else {
      prc = fem_gmres_solve(&s->nw.gm, s->dm.colptr, s->dm.rowind, s->as.val, s->nw.rhs,
                            s->nw.da, s->prm.krylov_max, s->prm.krylov_rtol, precond, s, &its);
      s->st.n_gmres++;
    }
    sa_timing_add("fem krylov", sa_time_now() - t0);
    if (prc < 0) return sa_error_push(prc, __func__, __FILE__, __LINE__);
    s->st.n_krylov_it += its;
    if (prc == 0) {
      krylov = 1;
      s->st.n_krylov++;
    } else {
      s->st.n_krylov_fail++;
    }
  }
  rc = use_old || krylov ? 0 : factorize(s, sk, t->p_asm, eff_done, t->it > 0,
                                          t->it > 0 && t->ls < 10);
  if (!use_old && !krylov) t->nfresh++;
  else if (use_old) s->st.n_reuse++;
  t->fresh_last = !use_old && !krylov;
  t->krylov_last = krylov;
  t->have_fact = rc == 0;
  if (rc) {
    *why = FEM_DIVERGED_LINEAR_SOLVE;
    if (rc > 0 && s->dm.nfloating)
      return SA_ERROR(rc, "tangent singular: %d floating body/bodies (%s); fix dofs or hold "
                      "them with weak springs (fem_solver_add_spring(s, node, -1, k))",
                      s->dm.nfloating, s->dm.floating_msg);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  for (int k = 0; k < nf; k++) s->nw.rhs[k] = -s->nw.R[k];
  if (!krylov) SA_CHECK(linsolve(s, s->nw.rhs, s->nw.da));
  if (t->vol) {
    for (int d = 0; d < s->ndof; d++)
      if (s->dm.eq[d] >= 0) {
        s->nw.qf[s->dm.eq[d]] = s->as.q[d];
        s->nw.gf[s->dm.eq[d]] = s->as.gv[d];
      }
    SA_CHECK(linsolve(s, s->nw.qf, s->nw.db));
    t->gb = fem_dot(s->nw.gf, s->nw.db, nf);
    if (t->gb == 0.0 || !isfinite(t->gb)) {
      *why = FEM_DIVERGED_BORDERED;
      return SA_ERROR(SA_ERR_NOT_CONVERGED, "volume control: dV/dp = 0 (bordered system "
                      "singular)");
    }
    t->dp = -(c + fem_dot(s->nw.gf, s->nw.da, nf)) / t->gb;
    t->qnorm = fem_nrm2(s->nw.qf, nf);
    merit = rnorm + t->qnorm * fabs(c) / fabs(t->gb);
    for (int k = 0; k < nf; k++) s->nw.du[k] = s->nw.da[k] + t->dp * s->nw.db[k];
  } else {
    t->dp = 0.0;
    memcpy(s->nw.du, s->nw.da, (size_t)nf * sizeof *s->nw.du);
  }
  t->du_norm = fem_nrm2(s->nw.du, nf);
  t->slope = t->emerit ? fem_dot(s->nw.R, s->nw.du, nf) : 0.0;
  t->pi_prev = t->pi_ref = t->pi;
  t->stepped_back = 0;
  if (t->emerit) { /* the reference of the non-monotone Armijo test: max over ls_memory iterates */
    if (t->ls_exhausted) t->n_hist = 0; /* an uphill step taken as it was: restart the memory */
    int mem = s->prm.ls_memory < 1               ? 1
              : s->prm.ls_memory > LS_MEMORY_MAX ? LS_MEMORY_MAX
                                                 : s->prm.ls_memory;
    t->pi_hist[t->n_hist % mem] = t->pi;
    t->n_hist++;
    int k = t->n_hist < mem ? t->n_hist : mem;
    for (int i = 0; i < k; i++) t->pi_ref = fmax(t->pi_ref, t->pi_hist[i]);
  }
  memcpy(s->nw.u_it, s->u, (size_t)s->ndof * sizeof *s->u);
  s->nw.p_it = s->p;
  t->merit_prev = merit;
  t->r_prev = rnorm;
  t->ls = 0;
  t->step_len = 1.0;
  for (int d = 0; d < s->ndof; d++)
    if (s->dm.eq[d] >= 0) s->u[d] += s->nw.du[s->dm.eq[d]];
  s->p += t->dp;
  fem_set_x(s);
  t->it++;
  return 0;
}

/* The trial iterate at step length a along the last direction from the accepted iterate. */
static void step_to(FemSolver *s, Iter *t, double a) {
  t->step_len = a;
  for (int d = 0; d < s->ndof; d++)
    if (s->dm.eq[d] >= 0) s->u[d] = s->nw.u_it[d] + a * s->nw.du[s->dm.eq[d]];
  s->p = s->nw.p_it + a * t->dp;
  fem_set_x(s);
}

/* The extrapolated start was refused (outside the domain, or too far for K_int): halve the
 * extrapolation, and at the fourth refusal start from u_n. */
static void pull_back_extrapolation(FemSolver *s, Iter *t) {
  t->ls++;
  double f = t->ls < 4 ? 0.5 : 0.0;
  for (int d = 0; d < s->ndof; d++)
    if (s->dm.eq[d] >= 0) s->u[d] = s->u_last[d] + f * (s->u[d] - s->u_last[d]);
  fem_set_x(s);
}

/* One substep: Newton from the current u (the predictor is applied by the caller) to
 * equilibrium with the loads already applied. Lazy backtracking: a full step is taken; if the
 * next assembly finds a domain error, a NaN or a larger merit (residual norm, plus the
 * volume-constraint violation in force units), the step is halved (up to 6 times).
 * Returns 0, > 0 (recoverable: caller cuts the increment) or < 0 (fatal); s->nw.reason says
 * why it stopped. */
int fem_newton_substep(FemSolver *s, const StepKind *sk, int step, int *iters) {
  Iter t = {.vol = s->ct.control == FEM_CONTROL_VOLUME, .r_prev = -1, .r_first = -1,
            .r_best = -1,
            .merit_prev = INFINITY, .step_len = 1.0};
  t.emerit = s->prm.merit == FEM_MERIT_ENERGY && s->prm.line_search && !sk->dynamic && !t.vol &&
             s->as.ncontrib == 0;
  *iters = 0;
  s->nw.reason = FEM_NEWTON_ITERATING;
  s->as.dt_eval = sk->dynamic ? sk->dt : sk->law_dt;
  s->as.t_eval = s->time + s->as.dt_eval; /* laws see the end of the substep */
  /* Predictor (it 0), FemPredictor: NEW_LOAD (default) factorises the converged state with the
   * new pressure's load stiffness, K(u_n, p_n+1); EQUILIBRIUM uses K(u_n, p_n), the
   * equilibrium path's tangent (on the actuator K(u_n, p_n+1) is indefinite above ~4 kPa of
   * increment: no stress yet carries the extra pressure); REUSE takes the factors of the last
   * iteration of the previous substep (no factorisation: meant for many small coupled
   * solves). Measured on the default scene (docs/fem.md): NEW_LOAD needs the fewest
   * factorisations and LU fallbacks, although its first tangent is often indefinite. */
  t.reuse = s->prm.predictor == FEM_PREDICT_REUSE && s->nw.fact_converged &&
            s->nw.fact_dynamic == sk->dynamic &&
            (!sk->dynamic || (s->nw.fact_dt == sk->dt && s->nw.fact_alpha == sk->alpha));
  t.p_pred = s->prm.predictor == FEM_PREDICT_NEW_LOAD || s->prm.predictor == FEM_PREDICT_EXTRAPOLATE
                 ? s->p
                 : s->ct.p_last;
  /* reuse_rate > 0 (modified Newton): a direction from fresh factors is followed by one that
   * reuses them (assembly + triangular solves): for a nearly incompressible solid a full
   * Newton step leaves a volumetric residual ~ kappa |grad du|^2 (|R| jumps x10-100) that one
   * more solve with the same factors mostly removes. Reuse goes on while |R| falls by
   * reuse_rate per iteration, else fresh factors. Off by default: on the default scene it
   * saved a third of the factorisations but not time (docs/fem.md). */
  t.have_fact = t.reuse;
  for (;;) {
    /* a load step of a fine mesh takes minutes, one iteration (assembly + factorisation)
     * seconds at most: a signal is answered here */
    if (sa_interrupted()) {
      *iters = t.it;
      return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at step %d, Newton iteration %d", step, t.it);
    }
    if (sk->dynamic) fem_dyn_kinematics(s, sk);
    /* Reuse is planned before the assembly, so a direction from reused factors builds no
     * tangent and the values the factors were computed from (incl. the dynamic mass term) stay
     * in val for UMFPACK's iterative refinement. Certain: the REUSE predictor at it 0, and the
     * iteration after fresh factors; tentative: continued reuse, confirmed by the rate (if
     * rejected, direction() assembles the tangent then). */
    int plan_reuse = t.it == 0 ? t.reuse : (s->prm.reuse_rate > 0 && t.have_fact && t.ls == 0);
    double fref, rnorm, c, merit;
    int rc = evaluate(s, sk, &t, plan_reuse, &rnorm, &fref, &c, &merit);
    if (rc < 0) {
      *iters = t.it;
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    int bad = rc != 0 || !isfinite(rnorm);
    if (t.it == 0 && t.emerit && !bad && !potential_consistent(s)) {
      t.emerit = 0;
      sa_log(SA_LOG_DEBUG, "fem", "energy merit off: dV/du differs from the pressure load q "
             "(the pressure surface's rim is neither fixed nor on planes through the origin)");
    }
    /* Backtrack on domain errors / non-finite residuals, and on a residual blow-up by more
     * than ls_growth. Not on any increase: for a nearly incompressible solid the full Newton
     * step changes the volume to second order and kappa times that makes the residual norm
     * jump although the next iterations converge quadratically (docs/fem.md). */
    /* Energy merit on a descent direction (Pi'(0) = R.du < 0): Armijo sufficient decrease,
     * the next step length from the quadratic through Pi(0), Pi'(0) and Pi(a), kept in
     * [0.1, 0.5] a; up to 10 backtracks, then the step is taken as it is. The round-off
     * allowance (1e-13 of the potential's terms) lets converged iterates pass. */
    int energy_ls = t.it > 0 && t.emerit && t.slope < 0.0;
    t.ls_exhausted = 0;
    if (energy_ls && !bad) {
      double a = t.step_len, dpi = t.pi - t.pi_prev;
      int decrease = t.pi - t.pi_ref <= s->prm.armijo * a * t.slope + 1e-13 * t.pi_scale;
      if (!decrease && t.ls >= 10) t.ls_exhausted = 1;
      if (!decrease && t.ls < 10) {
        double den = 2.0 * (dpi - t.slope * a);
        double an = den > 0.0 ? -t.slope * a * a / den : 0.5 * a;
        t.ls++;
        s->st.n_ls_energy++;
        step_to(s, &t, fmin(fmax(an, 0.1 * a), 0.5 * a));
        continue;
      }
    }
    if (t.it > 0 && s->prm.line_search && t.ls < (energy_ls ? 10 : 6) &&
        (bad || (!energy_ls && merit > s->prm.ls_growth * t.merit_prev))) {
      t.ls++;
      step_to(s, &t, 0.5 * t.step_len);
      continue;
    }
    if (t.it == 0 && bad && s->nw.extrapolated && t.ls < 4) {
      pull_back_extrapolation(s, &t); /* the extrapolated start is outside the domain */
      continue;
    }
    if (bad) {
      *iters = t.it;
      if (rc == SA_ERR_INVERTED) {
        s->nw.reason = FEM_DIVERGED_DOMAIN;
        return SA_ERROR(SA_ERR_INVERTED, "%d element(s) inverted at iteration %d",
                        s->as.n_inverted, t.it);
      }
      if (rc == SA_ERR_DOMAIN) {
        s->nw.reason = FEM_DIVERGED_DOMAIN;
        return SA_ERROR(SA_ERR_DOMAIN, "state outside the model's domain at iteration %d (%d "
                        "law evaluation(s) failed%s)", t.it, s->as.n_domain,
                        s->nw.domain_check ? ", or the domain hook refused it" : "");
      }
      s->nw.reason = FEM_DIVERGED_NAN;
      return SA_ERROR(SA_ERR_NAN, "residual is not finite at iteration %d", t.it);
    }
    double rate = t.r_prev > 0 ? rnorm / t.r_prev : 0.0;
    const char *lsn = t.ls ? "  (line search)" : "";
    const char *ren = t.it == 0 || t.fresh_last ? ""
                      : t.krylov_last           ? "  (Krylov on earlier factors)"
                                                : "  (reused factors)";
    if (t.vol)
      sa_log(SA_LOG_DEBUG, "fem", "step %d it %2d |R| %.3e |du| %.3e rate %.3f  p %.6g dV %.2e%s%s",
             step, t.it, rnorm, t.du_norm, rate, s->p, c, lsn, ren);
    else
      sa_log(SA_LOG_DEBUG, "fem", "step %d it %2d |R| %.3e |du| %.3e rate %.3f%s%s", step, t.it,
             rnorm, t.du_norm, rate, lsn, ren);
    FemNewtonReason why = stop_test(s, &t, rnorm, fref, c);
    if (why != FEM_NEWTON_ITERATING) {
      *iters = t.it;
      s->nw.reason = why;
      return why > 0 ? 0 : SA_ERR_NOT_CONVERGED;
    }
    rc = direction(s, sk, &t, plan_reuse, rnorm, rate, c, merit, &why);
    if (rc == SA_ERR_NOT_SPD && s->nw.indef_step && t.it > 0 && t.ls < 10) {
      /* the tangent is indefinite here (the consistent one; K_int too once the line-search
       * budget is spent): the last step carried the iterate too far. Step back toward the
       * last accepted iterate (halve) instead of failing the whole substep and its
       * iterations (docs/fem_time_to_accuracy.md, "Step-back"). */
      sa_error_clear();
      s->st.n_indef_backtrack++;
      t.stepped_back = 1;
      t.ls++;
      step_to(s, &t, 0.5 * t.step_len);
      continue;
    }
    if (rc == SA_ERR_NOT_SPD && s->nw.indef_step && t.it == 0 && s->nw.extrapolated &&
        t.ls < 4) {
      sa_error_clear(); /* the extrapolated start is too far for even K_int */
      s->st.n_indef_backtrack++;
      pull_back_extrapolation(s, &t);
      continue;
    }
    if (rc) {
      *iters = t.it;
      s->nw.reason = why;
      return rc;
    }
  }
}

int fem_newton_alloc(FemSolver *s) {
  int nf = s->dm.nfree;
  double **v[] = {&s->nw.R, &s->nw.da, &s->nw.db, &s->nw.du, &s->nw.rhs, &s->nw.qf, &s->nw.gf,
                  &s->nw.kr, &s->nw.kz, &s->nw.kp, &s->nw.kq};
  for (size_t i = 0; i < sizeof v / sizeof *v; i++) SA_CALLOC(*v[i], nf);
  SA_CALLOC(s->nw.u_it, s->ndof);
  /* restart length: at most 40 vectors (memory 41 nfree doubles); the scenes' krylov_max is
   * 10-30, so one cycle */
  if (s->prm.krylov_max > 0)
    SA_CHECK(fem_gmres_alloc(&s->nw.gm, nf, s->prm.krylov_max < 40 ? s->prm.krylov_max : 40));
  int nreg = s->m->nregions > 0 ? s->m->nregions : 1;
  s->nw.laws_unsym = 0;
  for (int r = 0; r < nreg; r++)
    if (!fem_material_symmetric(&s->mats[r])) s->nw.laws_unsym = 1;
  if (s->nw.laws_unsym && s->prm.linsolver == FEM_LINSOLVER_AUTO)
    sa_log(SA_LOG_INFO, "fem", "a region's law has an unsymmetric tangent: UMFPACK LU");
  return 0;
}

void fem_newton_free(FemNewton *nw) {
  void *p[] = {nw->R, nw->da, nw->db, nw->du, nw->rhs, nw->qf, nw->gf, nw->u_it,
               nw->kr, nw->kz, nw->kp, nw->kq};
  for (size_t i = 0; i < sizeof p / sizeof *p; i++) free(p[i]);
  fem_gmres_free(&nw->gm);
}
