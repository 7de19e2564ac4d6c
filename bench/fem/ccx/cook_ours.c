/* cook_ours.c - our FEM solver (fem.h) on Cook's membrane, the problem ccx_cook hands to
 * CalculiX: nearly incompressible neo-Hookean, plane strain, dead shear load.
 *
 * Geometry (mm): the bilinear map of the unit cube's (a, b) onto the quadrilateral (0,0),
 * (48,44), (48,60), (0,44), z in [0, 1]; structured n x n x 1 cells, 6 tetrahedra each
 * (tests/fem/solver/smesh.c), tet10 (--order 2, default) or tet4. u_z = 0 at every node (plane
 * strain), left edge clamped, dead load F = 32 N in +y as a uniform traction F / 16 on the right
 * edge x = 48, applied as the consistent nodal forces of each flat face: the 3-point rule at the
 * edge midpoints integrates quadratics on a triangle exactly, and there the tri6 shape functions
 * are 1 at the matching mid-node and 0 elsewhere, so a face of area A gets A/3 t at each
 * mid-node and nothing at the corners; a tri3 face gets A/3 t at each corner. The total is
 * checked against F. Material FEM_MAT_NEOHOOKE: W = mu/2 (I1b - 3) + kappa/2 (J - 1)^2,
 * mu = 80.194 MPa, kappa = 400889.8 MPa by default (K/mu ~ 5000).
 *
 * usage: cook_ours --n N [--order 1|2] [--mu MU] [--kappa K | --kappa-ratio R] [--force F]
 *                  [--mix-alpha A] [--threads T] [--dl-init F] [--verbose]
 * prints one line:
 *   ours: n N order O nodes N dof N elems N kappa K uy U newton N substeps N cuts N
 *         setup_s T solve_s T wall_s T */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_error.h"
#include "sa_log.h"
#include "smesh.h"

static void map_cook(const double xi[3], const void *ctx, double X[3])
{
  (void)ctx;
  static const double P[4][2] = {{0, 0}, {48, 44}, {48, 60}, {0, 44}};
  const double a = xi[0], b = xi[1];
  const double w[4] = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
  X[0] = X[1] = 0;
  for (int k = 0; k < 4; ++k) {
    X[0] += w[k] * P[k][0];
    X[1] += w[k] * P[k][1];
  }
  X[2] = xi[2];
}

static double tri_area(const double *p0, const double *p1, const double *p2)
{
  double u[3], v[3];
  for (int q = 0; q < 3; ++q) u[q] = p1[q] - p0[q], v[q] = p2[q] - p0[q];
  double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

static int run(int argc, char **argv)
{
  int n = 0, order = 2;
  double mu = 80.194, kappa = 400889.8, kratio = 0, force = 32.0, mix_alpha = 0;
  FemSolverParams prm = fem_solver_params_default();
  prm.dl_init = 0.25;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define OPT(name) (!strcmp(a, name) && v && ++i)
    if (OPT("--n")) n = atoi(v);
    else if (OPT("--order")) order = atoi(v);
    else if (OPT("--mu")) mu = atof(v);
    else if (OPT("--kappa")) kappa = atof(v);
    else if (OPT("--kappa-ratio")) kratio = atof(v);
    else if (OPT("--force")) force = atof(v);
    else if (OPT("--mix-alpha")) mix_alpha = atof(v);
    else if (OPT("--threads")) prm.threads = atoi(v);
    else if (OPT("--dl-init")) prm.dl_init = atof(v);
    else if (!strcmp(a, "--verbose")) sa_log_set_level(SA_LOG_INFO);
    else return SA_ERROR(SA_ERR_INPUT, "unknown or incomplete option %s", a);
#undef OPT
  }
  SA_REQUIRE(n >= 1 && n <= 256 && (order == 1 || order == 2), SA_ERR_INPUT,
             "usage: cook_ours --n N [--order 1|2] [...]");
  if (kratio > 0) kappa = kratio * mu;

  double t0 = sa_time_now();
  SmeshBlock blk = {{n, n, 1}, map_cook, NULL, {"clamp", "load", "bottom", "top", "back", "front"}};
  FemMesh *m = NULL;
  SA_CHECK(smesh_build(1, &blk, order, 1e-9, &m));
  FemMaterial mat;
  memset(&mat, 0, sizeof mat);
  mat.kind = FEM_MAT_NEOHOOKE;
  mat.c10 = 0.5 * mu;
  mat.kappa = kappa;
  mat.rho = 1e-9;
  mat.mix_alpha = mix_alpha;
  FemSolver *s = NULL;
  int *all = NULL, corner = -1, rc = 0;
  double *f = NULL, total = 0, t1 = 0, t2 = 0;
  const FemSurface *ld = fem_mesh_find_surface(m, "load");
  all = malloc(sizeof *all * (size_t)m->nnodes);
  f = calloc(3 * (size_t)m->nnodes, sizeof *f);
  if (!all || !f) rc = SA_ERROR(SA_ERR_MEMORY, "out of memory");
  if (!rc && !ld) rc = SA_ERROR(SA_ERR_INTERNAL, "mesh has no surface 'load'");
  for (int i = 0; !rc && i < m->nnodes; ++i) {
    all[i] = i;
    const double *X = m->xyz + 3 * (size_t)i;
    if (fabs(X[0] - 48) < 1e-9 && fabs(X[1] - 60) < 1e-9 && fabs(X[2]) < 1e-9) corner = i;
  }
  if (!rc && corner < 0) rc = SA_ERROR(SA_ERR_INTERNAL, "no node at (48, 60, 0)");
  const double ty = force / 16.0;
  for (int k = 0; !rc && k < ld->nfaces; ++k) {
    const int *c = ld->faces + (size_t)k * ld->nfn;
    double A = tri_area(m->xyz + 3 * (size_t)c[0], m->xyz + 3 * (size_t)c[1],
                        m->xyz + 3 * (size_t)c[2]);
    int first = ld->nfn == 6 ? 3 : 0; /* tri6: mid-nodes 3..5 carry the load */
    for (int q = first; q < first + 3; ++q) f[3 * (size_t)c[q] + 1] += ty * A / 3.0;
    total += ty * A;
  }
  if (!rc && fabs(total - force) > 1e-9 * force)
    rc = SA_ERROR(SA_ERR_INTERNAL, "load surface gives %.12g N, expected %.12g", total, force);
  if (!rc) rc = fem_solver_create(m, &mat, &prm, &s);
  if (!rc) rc = fem_solver_fix_surface(s, "clamp", FEM_XYZ);
  if (!rc) rc = fem_solver_fix_nodes(s, m->nnodes, all, FEM_Z);
  if (!rc) rc = fem_solver_setup(s);
  t1 = sa_time_now();
  if (!rc) rc = fem_solver_set_nodal_forces(s, m->nnodes, all, f);
  if (!rc) rc = fem_solver_solve(s);
  t2 = sa_time_now();
  if (!rc) {
    FemSolveReport rep;
    FemSolverStats st;
    fem_solver_report(s, &rep);
    fem_solver_stats(s, &st);
    printf("ours: n %d order %d nodes %d dof %d elems %d kappa %.12g uy %.9f newton %d substeps %d "
           "cuts %d setup_s %.3f solve_s %.3f wall_s %.3f\n",
           n, order, m->nnodes, st.nfree, m->nelem, kappa, fem_solver_displacements(s)[3 * corner + 1],
           rep.newton_iters, rep.substeps, rep.cuts, t1 - t0, t2 - t1, t2 - t0);
  }
  fem_solver_destroy(&s);
  smesh_free(&m);
  free(all);
  free(f);
  return rc;
}

int main(int argc, char **argv)
{
  sa_log_set_level(SA_LOG_WARN);
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
