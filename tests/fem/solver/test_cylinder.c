/* test_cylinder - inflation of a thick-walled, (nearly) incompressible neo-Hookean cylinder in
 * plane strain, against the closed-form solution.
 *
 * Reference (derived in docs/fem.md): incompressible plane strain maps radius R to r with
 * r^2 - a^2 = R^2 - A^2; the hoop stretch is lambda = r/R, radial 1/lambda, and
 * sigma_tt - sigma_rr = mu (lambda^2 - lambda^-2). Integrating d(sigma_rr)/dr =
 * (sigma_tt - sigma_rr)/r from a (sigma_rr = -p) to b (sigma_rr = 0) with
 * dr/r = -d(lambda) / (lambda (lambda^2 - 1)) gives
 *     p = mu [ ln(lambda_a / lambda_b) + (1/lambda_b^2 - 1/lambda_a^2) / 2 ],
 *     lambda_b^2 = 1 + (lambda_a^2 - 1) A^2 / B^2.
 * Mesh: quarter annulus A = 1, B = 2 (symmetry planes x = 0, y = 0), one layer in z with every
 * node's z fixed (plane strain), tet10 mean-dilatation element, kappa = 2000 mu.
 * Check: at each applied pressure the measured inner stretch lambda_a (mean over the inner
 * surface nodes) gives back the applied pressure through the formula within 1 %: the
 * compressibility error is O(mu/kappa) = 5e-4 and the quadratic-element discretisation error
 * on this 4 x 8 mesh is a few 1e-3 (halving it changed the error by < 0.2 %). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "smesh.h"
#include "sa_log.h"
#include "tutil.h"

static const double A = 1.0, B = 2.0, H = 0.25;

static void map_annulus(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  double r = A + xi[0] * (B - A), t = xi[1] * 2.0 * atan(1.0);
  X[0] = r * cos(t);
  X[1] = r * sin(t);
  X[2] = xi[2] * H;
}

static double p_exact(double la, double mu) {
  double lb = sqrt(1.0 + (la * la - 1.0) * (A * A) / (B * B));
  return mu * (log(la / lb) + 0.5 * (1.0 / (lb * lb) - 1.0 / (la * la)));
}

int main(int argc, char **argv) {
  if (getenv("SA_TEST_DEBUG")) sa_log_set_level(SA_LOG_DEBUG);
  int nr = argc > 1 ? atoi(argv[1]) : 4, nt = argc > 2 ? atoi(argv[2]) : 8;
  SmeshBlock blk = {{nr, nt, 1}, map_annulus, NULL,
                    {"inner", "outer", "sym_y", "sym_x", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  const double mu = 1.0;
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = mu / 2, .kappa = 2000 * mu, .rho = 1.0};
  FemSolverParams prm = fem_solver_params_default();
  if (getenv("SA_TEST_NOLS")) prm.line_search = 0;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "sym_y", FEM_Y));
  TU_CHECK(fem_solver_fix_surface(s, "sym_x", FEM_X));
  int *all = malloc(sizeof(int) * m->nnodes);
  for (int i = 0; i < m->nnodes; i++) all[i] = i;
  TU_CHECK(fem_solver_fix_nodes(s, m->nnodes, all, FEM_Z));
  TU_CHECK(fem_solver_add_pressure_surface(s, "inner"));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *in = fem_mesh_find_surface(m, "inner");
  int fails = 0;
  if (getenv("SA_TEST_DEBUG")) {
    double err;
    TU_CHECK(fem_solver_check_tangent(s, 1e-6, &err));
    printf("tangent check at u=0: %g\n", err);
    TU_CHECK(fem_solver_set_pressure(s, 0.01));
    TU_CHECK(fem_solver_solve(s));
    TU_CHECK(fem_solver_check_tangent(s, 1e-6, &err));
    printf("tangent check at p=0.01: %g\n", err);
  }
  double las[] = {1.1, 1.3, 1.6, 2.0}; /* target stretches; the pressure is set from them */
  for (int k = 0; k < 4; k++) {
    double p = p_exact(las[k], mu);
    TU_CHECK(fem_solver_set_pressure(s, p));
    TU_CHECK(fem_solver_solve(s));
    const double *x = fem_solver_positions(s);
    double la = 0;
    for (int i = 0; i < in->nnodes; i++) {
      const double *xi = x + 3 * in->nodes[i];
      la += hypot(xi[0], xi[1]) / A;
    }
    la /= in->nnodes;
    double pe = p_exact(la, mu);
    char what[64];
    snprintf(what, sizeof what, "pressure at lambda_a = %.4f", la);
    fails += tu_close(what, p, pe, 0.0, 0.01);
    if (getenv("SA_TEST_VERBOSE"))
      printf("lambda_a %.6f  p_fem %.6f  p_exact %.6f  rel.err %.2e\n", la, p, pe,
             (p - pe) / pe);
  }
  if (getenv("SA_TEST_DEBUG")) {
    double err;
    TU_CHECK(fem_solver_check_tangent(s, 1e-6, &err));
    printf("tangent check at the end: %g\n", err);
  }
  fem_solver_destroy(&s);
  smesh_free(&m);
  free(all);
  return fails ? 1 : 0;
}
