/* test_cook - Cook's membrane, nearly incompressible neo-Hookean, plane strain: mesh
 * convergence without volumetric locking.
 *
 * Geometry (mm): quadrilateral (0,0), (48,44), (48,60), (0,44), thickness 1, left edge clamped,
 * a dead shear load F = 32 N (uniform traction 2 N/mm^2 over the 16 mm right edge) in +y,
 * plane strain (every node's z fixed). Neo-Hookean mu = 80.194 MPa, kappa = 400889.8 MPa
 * (nu = 0.4999, kappa/mu = 5000), the usual nonlinear version of the benchmark.
 * Quantity: vertical displacement of the top-right corner (48, 60).
 * Reference: Richardson extrapolation of the tet10 (mean-dilatation mixed) results on n x n
 * meshes, n = 4, 8, 16, 32, with the observed order (the last three). Checks:
 *  - tet10: displacements increase with n (a too-stiff displacement-type discretisation
 *    converges from below) and the n = 32 value is within 1 % of the extrapolated limit;
 *    the observed order is > 1 (a locking element would show order ~0 at these sizes);
 *  - tet4 (constant J per element: mean dilatation = pure displacement, which locks): at n = 32
 *    it is still more than 20 % below the limit -- the locking the mixed tet10 removes.
 * Usage: test_fem_cook [nmax] prints the table with SA_TEST_VERBOSE=1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static void map_cook(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  const double P[4][2] = {{0, 0}, {48, 44}, {48, 60}, {0, 44}};
  double a = xi[0], b = xi[1];
  double w[4] = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
  X[0] = X[1] = 0;
  for (int k = 0; k < 4; k++) {
    X[0] += w[k] * P[k][0];
    X[1] += w[k] * P[k][1];
  }
  X[2] = xi[2] * 1.0;
}

static int cook(int n, int order, double *uy) {
  SmeshBlock blk = {{n, n, 1}, map_cook, NULL, {"clamp", "load", "bottom", "top", "back", "front"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, order, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 80.194 / 2, .kappa = 400889.8, .rho = 1e-9};
  FemSolverParams prm = fem_solver_params_default();
  prm.dl_init = 0.25;
  prm.threads = 1; /* small meshes: a second thread only waits (test_sphere.c) */
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  int *all = malloc(sizeof(int) * m->nnodes);
  for (int i = 0; i < m->nnodes; i++) all[i] = i;
  TU_CHECK(fem_solver_fix_nodes(s, m->nnodes, all, FEM_Z));
  TU_CHECK(fem_solver_setup(s));
  /* consistent nodal forces of a uniform traction ty on flat faces: tri3 A/3 per corner;
   * tri6 0 at corners and A/3 per mid-node */
  const FemSurface *ld = fem_mesh_find_surface(m, "load");
  double *f = calloc(3 * (size_t)m->nnodes, sizeof *f), ty = 32.0 / 16.0, total = 0;
  for (int k = 0; k < ld->nfaces; k++) {
    const int *c = ld->faces + (size_t)k * ld->nfn;
    const double *p0 = m->xyz + 3 * c[0], *p1 = m->xyz + 3 * c[1], *p2 = m->xyz + 3 * c[2];
    double u[3], v[3];
    for (int i = 0; i < 3; i++) u[i] = p1[i] - p0[i], v[i] = p2[i] - p0[i];
    double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
    double A = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    for (int a = ld->nfn == 3 ? 0 : 3; a < ld->nfn; a++) f[3 * c[a] + 1] += ty * A / 3;
    total += ty * A;
  }
  if (fabs(total - 32.0) > 1e-9) {
    fprintf(stderr, "cook: load surface area gives %.12g N, expected 32\n", total);
    return 1;
  }
  TU_CHECK(fem_solver_set_nodal_forces(s, m->nnodes, all, f));
  TU_CHECK(fem_solver_solve(s));
  int corner = -1;
  for (int i = 0; i < m->nnodes; i++) {
    const double *X = m->xyz + 3 * i;
    if (fabs(X[0] - 48) < 1e-9 && fabs(X[1] - 60) < 1e-9 && fabs(X[2]) < 1e-9) corner = i;
  }
  *uy = fem_solver_displacements(s)[3 * corner + 1];
  fem_solver_destroy(&s);
  smesh_free(&m);
  free(all);
  free(f);
  return 0;
}

int main(int argc, char **argv) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_WARN);
  int nmax = argc > 1 ? atoi(argv[1]) : 32, fails = 0;
  double u10[8], u4[8];
  int ns[8], nn = 0;
  for (int n = 4; n <= nmax; n *= 2, nn++) {
    ns[nn] = n;
    TU_CHECK(cook(n, 2, &u10[nn]));
    TU_CHECK(cook(n, 1, &u4[nn]));
  }
  double d1 = u10[nn - 2] - u10[nn - 3], d2 = u10[nn - 1] - u10[nn - 2];
  double order = log2(d1 / d2), uext = u10[nn - 1] + d2 / (pow(2.0, order) - 1.0);
  if (getenv("SA_TEST_VERBOSE")) {
    printf("   n   tet10 (mixed)   tet4 (locks)\n");
    for (int k = 0; k < nn; k++) printf("%4d   %12.6f   %12.6f\n", ns[k], u10[k], u4[k]);
    printf("Richardson (tet10, order %.2f): %.6f\n", order, uext);
  }
  for (int k = 1; k < nn; k++)
    if (!(u10[k] > u10[k - 1])) {
      fprintf(stderr, "tet10 not monotone from below: n=%d %.6f, n=%d %.6f\n", ns[k - 1],
              u10[k - 1], ns[k], u10[k]);
      fails++;
    }
  if (!(order > 1.0)) {
    fprintf(stderr, "tet10 observed order %.3f <= 1\n", order);
    fails++;
  }
  fails += tu_close("tet10 finest vs Richardson limit", u10[nn - 1], uext, 0.0, 0.01);
  if (!(u4[nn - 1] < 0.8 * uext)) {
    fprintf(stderr, "tet4 at n=%d: %.6f not locked (limit %.6f)\n", ns[nn - 1], u4[nn - 1], uext);
    fails++;
  }
  return fails ? 1 : 0;
}
