/* test_dynamics - implicit dynamics (fem_solver_step_dynamic) against two independent references.
 *
 * A cantilever bar L x b x h = 1 x 0.2 x 0.1 clamped at x = 0 (tet10, 10 x 2 x 1 cells,
 * compressible neo-Hookean mu = 1, kappa = 13/6 (nu = 0.3), rho = 1), HHT alpha = 0 (the
 * trapezoidal Newmark rule, beta = 1/4, gamma = 1/2: no numerical damping), no damping.
 *
 * Reference mode: the lowest eigenpair of K phi = w^2 M phi (K the tangent at rest, M the lumped
 * mass, computed here from fem_element_lumped_mass) by inverse iteration, where each K^-1 is a
 * STATIC solve of the solver under the nodal load c M phi_k at small amplitude (tip 1e-3 L:
 * geometric nonlinearity changes w^2 by O(strain^2) ~ 1e-7). Rayleigh quotient
 * w^2 = (z.M phi)/(z.M z), z = K^-1 M phi. b = 2h, so the lowest (z-bending) mode is an octave
 * below the y-bending mode and inverse iteration converges by ~1/4 per iteration.
 *
 * The bar is released from the static deflection under c M phi (= the mode shape, v = 0) and
 * integrated for 3 periods with 40 steps per period. Checks:
 *  1. period from the zero crossings of the tip z-displacement (linear interpolation) against
 *     the trapezoidal rule's exact discrete period for that mode,
 *     w_d = (2/dt) atan(w dt / 2) (period elongation ~ (w dt)^2/12 = 0.2 % here, so an
 *     integrator of the wrong kind or order fails). Tolerance rtol 2e-4: linear interpolation
 *     of the crossing times errs by <= (w dt)^3/48 ~ 1e-4 rad at each end of a 3-period
 *     (19 rad) span -> 1e-5; the eigenvalue is converged to 1e-10; nonlinearity 1e-7.
 *  2. conservation of the total energy E = 1/2 v.M v + sum of element energies (computed here
 *     with fem_element_tl) from the first step on: the trapezoidal rule conserves
 *     1/2 v.M v + 1/2 u.K u exactly for a linear system without load. The first step is
 *     excluded: the solver starts with a = 0, consistent with the load that is released during
 *     that step. Tolerance 1e-6 E: the Newton tolerance (rtol 1e-10 of the force scale) and the
 *     cubic strain-energy terms (strain ~ 3e-4 -> relative 3e-4 of the nonlinearity of the
 *     energy, which the trapezoidal rule does not conserve exactly, bounded by (w dt)^2 of it).
 *  3. the whole tip history, for alpha = 0 and for HHT alpha = -0.1 (numerical dissipation),
 *     against the published HHT-alpha recursion for one degree of freedom q'' + w^2 q = 0
 *     (Hilber, Hughes & Taylor 1977; scalar code here, independent of the solver), started as
 *     the solver is: q0 = 1, v0 = 0, a0 = 0, the static load (k q0) present at t0 and gone at
 *     t1. The released state is the mode shape, so z_n = z_0 q_n up to the mode purity
 *     (1e-10), the Newton tolerance and the nonlinearity: the geometric frequency shift
 *     O((z_0/L)^2) = 1e-6 accumulates over the 19 rad of phase to ~2e-5 (measured 1.9e-5 for
 *     both alphas): tolerance 1e-4 z_0, against a 0.2 % period error (1 % of the amplitude
 *     after 3 periods) for a wrong beta/gamma and the 0.35 % energy loss of alpha = -0.1.
 *     With alpha = -0.1 the energy must also decrease (dissipation), by less than 5 %.
 *  4. sanity: w within 6 % of the Euler-Bernoulli value 1.8751^2 sqrt(E I / (rho A L^4))
 *     (the 3D bar with b = 2h lies between the beam (E) and the plate (E/(1-nu^2), +4.9 %)
 *     and is softened by shear by ~ (h/L)^2 ~ 1 %; the 10-cell tet10 discretisation error of
 *     the first mode is far below that).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_element.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

#define L_BAR 1.0
#define B_BAR 0.2
#define H_BAR 0.1

static void map_bar(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  X[0] = L_BAR * xi[0];
  X[1] = B_BAR * xi[1];
  X[2] = H_BAR * xi[2];
}

/* Sum of element energies at current coordinates x (hyperelastic: no history). */
static double strain_energy(const FemMesh *m, const FemMaterial *mat, const double *x) {
  double W = 0.0, X[30], xe[30];
  static FemElemOut out;
  for (int e = 0; e < m->nelem; e++) {
    const int *c = m->conn + (size_t)e * m->nen;
    for (int a = 0; a < m->nen; a++)
      for (int k = 0; k < 3; k++) {
        X[3 * a + k] = m->xyz[3 * c[a] + k];
        xe[3 * a + k] = x[3 * c[a] + k];
      }
    if (fem_element_tl(m->etype, X, xe, mat, NULL, NULL, 0, &out)) return NAN;
    W += out.energy;
  }
  return W;
}

static double kinetic(int n, const double *ml, const double *v) {
  double T = 0;
  for (int A = 0; A < n; A++)
    T += 0.5 * ml[A] * (v[3 * A] * v[3 * A] + v[3 * A + 1] * v[3 * A + 1] + v[3 * A + 2] * v[3 * A + 2]);
  return T;
}

#define NSTEPS 120

typedef struct {
  double period, E1, dEmax, Eend, u0, z[NSTEPS + 1];
  int ncross;
} RunOut;

/* HHT-alpha for q'' + w^2 q = 0 (unit mass): q0 = 1, v0 = a0 = 0, load w^2 q0 at t0 only.
 * beta = (1 - alpha)^2 / 4, gamma = 1/2 - alpha; equation of motion at t_{n+1}:
 * a_{n+1} + (1 + alpha) w^2 q_{n+1} - alpha (w^2 q_n - f_n) = 0. q [out] nsteps + 1. */
static void hht_sdof(double w, double dt, double alpha, int nsteps, double *q) {
  double b = 0.25 * (1 - alpha) * (1 - alpha), g = 0.5 - alpha, k = w * w;
  double qn = 1, vn = 0, an = 0, fn = k;
  q[0] = 1;
  for (int n = 1; n <= nsteps; n++) {
    /* q1 = qp + b dt^2 a1, qp = qn + dt vn + dt^2 (1/2 - b) an */
    double qp = qn + dt * vn + dt * dt * (0.5 - b) * an;
    double a1 = -((1 + alpha) * k * qp - alpha * (k * qn - fn)) / (1 + (1 + alpha) * k * b * dt * dt);
    double q1 = qp + b * dt * dt * a1;
    vn += dt * ((1 - g) * an + g * a1);
    qn = q1;
    an = a1;
    fn = 0;
    q[n] = qn;
  }
}

/* Release from the current (static) state: clear the loads and integrate nsteps of dt. */
static int release(FemSolver *s, const FemMesh *m, const FemMaterial *mat, const double *ml,
                   int tip, double dt, int nsteps, RunOut *o) {
  fem_solver_clear_nodal_forces(s);
  memset(o, 0, sizeof *o);
  const double *u = fem_solver_displacements(s);
  double zprev = u[3 * tip + 2], tfirst = -1, tlast = -1;
  o->u0 = o->z[0] = zprev;
  for (int n = 1; n <= nsteps; n++) {
    TU_CHECK(fem_solver_step_dynamic(s, dt));
    double z = o->z[n] = u[3 * tip + 2];
    double E = kinetic(m->nnodes, ml, fem_solver_velocities(s)) +
               strain_energy(m, mat, fem_solver_positions(s));
    if (n == 1) o->E1 = E;
    o->dEmax = fmax(o->dEmax, fabs(E - o->E1));
    o->Eend = E;
    if ((zprev < 0) != (z < 0)) {
      double tc = (n - 1) * dt + dt * zprev / (zprev - z);
      if (tfirst < 0) tfirst = tc;
      tlast = tc;
      o->ncross++;
    }
    zprev = z;
  }
  o->period = o->ncross > 1 ? 2 * (tlast - tfirst) / (o->ncross - 1) : NAN;
  return 0;
}

/* Inverse iteration with static solves; leaves s in static equilibrium under c M phi with tip
 * amplitude ~amp. Returns w^2 in *w2. */
static int lowest_mode(FemSolver *s, const FemMesh *m, const double *ml, const int *fixed,
                       double amp, double *w2) {
  int N = m->nnodes, n3 = 3 * N;
  double *phi = calloc(n3, sizeof *phi), *f = calloc(n3, sizeof *f), *z = calloc(n3, sizeof *z);
  int *all = malloc(sizeof(int) * N);
  for (int A = 0; A < N; A++) {
    all[A] = A;
    double xr = m->xyz[3 * A] / L_BAR;
    phi[3 * A + 2] = fixed[A] ? 0 : xr * xr;
  }
  double c = 0.03 * amp, w2_old = 0; /* Euler-Bernoulli guess w^2 ~ 0.027 */
  *w2 = 0;
  for (int it = 0; it < 60; it++) {
    for (int d = 0; d < n3; d++) f[d] = c * ml[d / 3] * phi[d];
    TU_CHECK(fem_solver_set_nodal_forces(s, N, all, f));
    TU_CHECK(fem_solver_solve(s));
    const double *u = fem_solver_displacements(s);
    double zmz = 0, zmp = 0, zmax = 0;
    for (int d = 0; d < n3; d++) {
      z[d] = fixed[d / 3] ? 0 : u[d] / c;
      zmz += z[d] * ml[d / 3] * z[d];
      zmp += z[d] * ml[d / 3] * phi[d];
      if (fabs(z[d]) > fabs(zmax)) zmax = z[d];
    }
    *w2 = zmp / zmz;
    for (int d = 0; d < n3; d++) phi[d] = z[d] / zmax;
    c = *w2 * amp;
    if (it > 3 && fabs(*w2 - w2_old) <= 1e-12 * *w2) break;
    w2_old = *w2;
  }
  /* final static state exactly under c M phi for the converged phi */
  for (int d = 0; d < n3; d++) f[d] = c * ml[d / 3] * phi[d];
  TU_CHECK(fem_solver_set_nodal_forces(s, N, all, f));
  TU_CHECK(fem_solver_solve(s));
  free(phi);
  free(f);
  free(z);
  free(all);
  return 0;
}

int main(void) {
  int verbose = getenv("SA_TEST_VERBOSE") != NULL;
  if (!verbose) sa_log_set_level(SA_LOG_WARN);
  SmeshBlock blk = {{10, 2, 1}, map_bar, NULL, {"clamp", "end", "s2", "s3", "s4", "s5"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 13.0 / 6.0, .rho = 1};
  int N = m->nnodes, fails = 0;
  double *ml = calloc(N, sizeof *ml);
  int *fixed = calloc(N, sizeof *fixed);
  for (int e = 0; e < m->nelem; e++) {
    const int *c = m->conn + (size_t)e * m->nen;
    double X[30], mm[10];
    for (int a = 0; a < m->nen; a++)
      for (int k = 0; k < 3; k++) X[3 * a + k] = m->xyz[3 * c[a] + k];
    fem_element_lumped_mass(m->etype, X, mat.rho, mm);
    for (int a = 0; a < m->nen; a++) ml[c[a]] += mm[a];
  }
  int tip = 0;
  double best = INFINITY;
  for (int A = 0; A < N; A++) {
    const double *X = m->xyz + 3 * A;
    double d = hypot(hypot(X[0] - L_BAR, X[1] - 0.5 * B_BAR), X[2] - 0.5 * H_BAR);
    if (d < best) best = d, tip = A;
    if (X[0] < 1e-12) fixed[A] = 1;
  }
  double amp = 1e-3 * L_BAR, pi = 4 * atan(1.0);

  for (int pass = 0; pass < 2; pass++) {
    double alpha = pass == 0 ? 0.0 : -0.1;
    FemSolverParams prm = fem_solver_params_default();
    prm.hht_alpha = alpha;
    prm.mass_damping = 0.0;
    prm.rtol = 1e-10;
    prm.atol = 1e-30;
    prm.threads = 1;
    FemSolver *s;
    TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
    TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
    TU_CHECK(fem_solver_setup(s));
    double w2;
    TU_CHECK(lowest_mode(s, m, ml, fixed, amp, &w2));
    double w = sqrt(w2), T = 2 * pi / w, dt = T / 40;
    double wd = 2.0 / dt * atan(0.5 * w * dt), Td = 2 * pi / wd;
    RunOut o;
    if (release(s, m, &mat, ml, tip, dt, NSTEPS, &o)) return 1;
    double q[NSTEPS + 1], dz = 0;
    hht_sdof(w, dt, alpha, NSTEPS, q);
    for (int n = 0; n <= NSTEPS; n++) dz = fmax(dz, fabs(o.z[n] - o.u0 * q[n]));
    if (verbose)
      printf("alpha %.2f: w %.8g (T %.8g, discrete %.8g), measured period %.8g (%d crossings), "
             "tip u0 %.3e, E1 %.8e, max|E-E1|/E1 %.2e, E_end/E1 - 1 = %.3e, max|z - z0 q_sdof|/z0 %.2e\n", alpha, w, T,
             Td, o.period, o.ncross, o.u0, o.E1, o.dEmax / o.E1, o.Eend / o.E1 - 1, dz / o.u0);
    char what[80];
    snprintf(what, sizeof what, "tip history vs HHT SDOF recursion (alpha %.2f)", alpha);
    fails += tu_close(what, dz, 0, 1e-4 * fabs(o.u0), 0);
    if (pass == 0) {
      double E = 9 * 2 * mat.c10 * mat.kappa / (3 * mat.kappa + 2 * mat.c10), I = B_BAR * pow(H_BAR, 3) / 12;
      double web = 1.8751 * 1.8751 * sqrt(E * I / (mat.rho * B_BAR * H_BAR * pow(L_BAR, 4)));
      if (verbose) printf("Euler-Bernoulli w %.6g, FE/EB - 1 = %.4f\n", web, w / web - 1);
      fails += tu_close("first bending frequency vs Euler-Bernoulli", w, web, 0, 0.06);
      if (o.ncross < 5) {
        fprintf(stderr, "only %d zero crossings in 3 periods\n", o.ncross);
        fails++;
      }
      fails += tu_close("period (trapezoidal, zero crossings)", o.period, Td, 0, 2e-4);
      fails += tu_close("energy conservation (alpha = 0)", o.dEmax, 0, 1e-6 * o.E1, 0);
    } else {
      double loss = 1 - o.Eend / o.E1;
      if (!(loss > 0 && loss < 0.05)) {
        fprintf(stderr, "HHT alpha = -0.1: relative energy loss %.3g, expected in (0, 0.05)\n",
                loss);
        fails++;
      }
    }
    fem_solver_destroy(&s);
  }
  free(ml);
  free(fixed);
  smesh_free(&m);
  return fails ? 1 : 0;
}
