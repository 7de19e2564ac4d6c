/* fem_dynamics.c - implicit HHT-alpha / Newmark dynamics with the lumped mass (docs/fem.md
 * "Dynamics"): alpha in [-1/3, 0], beta = (1 - alpha)^2 / 4, gamma = 1/2 - alpha.
 *   kinematics   a = (u - u_n - dt v_n)/(beta dt^2) - (1/(2 beta) - 1) a_n,
 *                v = v_n + dt ((1 - gamma) a_n + gamma a)
 *   residual     M (a + c_M v) + (1 + alpha) r(u, t_n+1) - alpha r(u_n, t_n),  r = f_int - f_ext
 *   tangent      (1 + alpha) K + (1/(beta dt^2) + c_M gamma/(beta dt)) M
 * The load ramp and substepping are the continuation's (fem_continuation.c), run with a time
 * step; this file owns the inertia terms and the velocity/acceleration state. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem_solver_priv.h"
#include "sa_error.h"

StepKind fem_dyn_step_kind(const FemSolver *s, double dt) {
  StepKind sk = {0};
  sk.dynamic = 1;
  sk.dt = dt;
  sk.alpha = fmin(0.0, fmax(-1.0 / 3.0, s->prm.hht_alpha));
  sk.beta = 0.25 * (1 - sk.alpha) * (1 - sk.alpha);
  sk.gamma = 0.5 - sk.alpha;
  return sk;
}

/* Newmark kinematics of the current u from the substep start state. */
void fem_dyn_kinematics(FemSolver *s, const StepKind *sk) {
  double dt = sk->dt, b = sk->beta, g = sk->gamma;
  FemDynamics *dy = &s->dy;
  for (int d = 0; d < s->ndof; d++) {
    double a = (s->u[d] - s->u_last[d] - dt * dy->v_last[d]) / (b * dt * dt) -
               (0.5 / b - 1.0) * dy->a_last[d];
    dy->acc[d] = a;
    dy->v[d] = dy->v_last[d] + dt * ((1 - g) * dy->a_last[d] + g * a);
  }
}

/* HHT residual on the free dofs (s->nw.R); ||R|| and the force scale as the static one. */
double fem_dyn_residual(FemSolver *s, const StepKind *sk, double *fref) {
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
    double M = s->as.mlump[d / 3];
    /* HHT: M a + C v + (1 + alpha) r_{n+1} - alpha r_n, alpha in [-1/3, 0] */
    r = M * (s->dy.acc[d] + s->prm.mass_damping * s->dy.v[d]) + (1 + sk->alpha) * r -
        sk->alpha * s->dy.res_n[d];
    s->nw.R[k] = r;
    r2 += r * r;
  }
  *fref = fmax(sqrt(fi2), sqrt(fe2));
  return sqrt(r2);
}

/* Turn the assembled K (s->as.val) into the effective tangent, in place (the factors are then
 * computed from, and refined against, exactly these values). */
void fem_dyn_effective_tangent(FemSolver *s, const StepKind *sk) {
  double cm = 1.0 / (sk->beta * sk->dt * sk->dt) +
              s->prm.mass_damping * sk->gamma / (sk->beta * sk->dt);
  for (long k = 0; k < s->dm.nnz; k++) s->as.val[k] *= 1 + sk->alpha;
  for (int d = 0; d < s->ndof; d++)
    if (s->dm.eq[d] >= 0) s->as.val[s->dm.diag[s->dm.eq[d]]] += cm * s->as.mlump[d / 3];
}

/* A static ramp has no inertia: v = a = 0 inside it. */
void fem_dyn_rest(FemSolver *s) {
  size_t nb = (size_t)s->ndof * sizeof *s->dy.v;
  memset(s->dy.v, 0, nb);
  memset(s->dy.acc, 0, nb);
  memset(s->dy.v_last, 0, nb);
  memset(s->dy.a_last, 0, nb);
}

/* Converged substep: its velocity/acceleration and r(u_n, t_n) become the step start. */
void fem_dyn_commit(FemSolver *s) {
  FemDynamics *dy = &s->dy;
  memcpy(dy->v_last, dy->v, (size_t)s->ndof * sizeof *dy->v);
  memcpy(dy->a_last, dy->acc, (size_t)s->ndof * sizeof *dy->acc);
  const double *fcon = s->as.ncontrib ? s->as.fcon : NULL;
  for (int d = 0; d < s->ndof; d++) {
    dy->res_n[d] = s->as.fint[d] - s->as.fdead[d] - s->p * s->as.q[d];
    if (fcon) dy->res_n[d] += fcon[d];
  }
}

void fem_dyn_restore(FemSolver *s) {
  memcpy(s->dy.v, s->dy.v_last, (size_t)s->ndof * sizeof *s->dy.v);
  memcpy(s->dy.acc, s->dy.a_last, (size_t)s->ndof * sizeof *s->dy.acc);
}

int fem_solver_step_dynamic(FemSolver *s, double dt) {
  SA_REQUIRE(dt > 0 && isfinite(dt), SA_ERR_INPUT, "time step %g must be > 0", dt);
  SA_CHECK(fem_cont_ramp(s, 1, dt));
  return 0;
}

const double *fem_solver_velocities(const FemSolver *s) { return s->dy.v; }

void fem_dyn_free(FemDynamics *dy) {
  free(dy->v);
  free(dy->acc);
  free(dy->v_last);
  free(dy->a_last);
  free(dy->res_n);
}
