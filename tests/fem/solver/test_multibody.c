/* test_multibody - several bodies in one model, joined by a contributor (springs), and the
 * rebuildable pattern.
 *
 * Two bars (tet4, 1 x 0.2 x 0.2, E = 1000, nu = 0: uniaxial stress is exact with a clamped end)
 * share no node: A at x in [0, 1] clamped at x = 0, B at x in [1.1, 2.1]. Springs join each
 * node of A's end face to the node of B's start face with the same (y, z), k_i = kbar A_i
 * (A_i: the node's tributary area, a third of its faces' areas), so a uniform traction t gives
 * the same jump t / kbar at every node. B's far face carries the nodal forces t A_i of a uniform
 * traction t. Hand solution (linear elasticity; tet4 reproduces the linear field exactly):
 *   u_x = t x / E on A,  u_x = t / E + t / kbar + t (x - 1.1) / E on B,  u_y = u_z = 0.
 * At strain t / E = 1e-5 the finite-strain solution differs by O(1e-5) relative: checked to
 * 1e-3 of the largest displacement.
 * 1. springs added before setup: pattern built with the pairs, no rebuild;
 * 2. springs added after setup: the first tangent assembly of the solve meets pairs outside the
 *    pattern, rebuilds once (n_pattern_rebuilds == 1) and gives the same displacements as 1
 *    (to 1e-12 relative: same equations, same pattern);
 * 3. without springs B is a floating body: setup says so (fem_solver_floating_bodies == 1), and
 *    ground springs (b = -1) on B make it held (0);
 * 4. an interface surface between two regions, selected by side (fem_mesh_add_surface_side):
 *    outward normals of each side point out of its region (tri6 mid-nodes follow). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static void map_bar(const double xi[3], const void *ctx, double X[3]) {
  double x0 = *(const double *)ctx;
  X[0] = x0 + xi[0];
  X[1] = 0.2 * xi[1];
  X[2] = 0.2 * xi[2];
}

/* Tributary area of every node of surface f [out] N (zero elsewhere). */
static void tributary(const FemMesh *m, const FemSurface *f, double *A) {
  memset(A, 0, sizeof(double) * m->nnodes);
  for (int k = 0; k < f->nfaces; k++) {
    const int *c = f->faces + 3 * k;
    const double *a = m->xyz + 3 * c[0], *b = m->xyz + 3 * c[1], *d = m->xyz + 3 * c[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; i++) A[c[i]] += area / 3;
  }
}

static const double E = 1000.0, T = 1e-2, KBAR = 2000.0; /* t/E = 1e-5, jump t/kbar = 5e-6 */

typedef struct {
  const FemMesh *m;
  int n, *a, *b; /* spring pairs */
  double *k;
  double *Aload;
} Model;

static int add_springs(FemSolver *s, const Model *md) {
  for (int i = 0; i < md->n; i++) TU_CHECK(fem_solver_add_spring(s, md->a[i], md->b[i], md->k[i]));
  return 0;
}

static int build(const Model *md, int springs_before, FemSolver **out) {
  FemMaterial mat = fem_material_from_e_nu(E, 0.0, 1.0);
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-9; /* round-off floor ~5e-10 of the force scale */
  FemSolver *s;
  TU_CHECK(fem_solver_create(md->m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clampA", FEM_XYZ));
  if (springs_before) TU_CHECK(add_springs(s, md));
  TU_CHECK(fem_solver_setup(s));
  if (!springs_before) TU_CHECK(add_springs(s, md));
  const FemSurface *ld = fem_mesh_find_surface(md->m, "loadB");
  double *f = calloc((size_t)3 * ld->nnodes, sizeof *f);
  for (int k = 0; k < ld->nnodes; k++) f[3 * k] = T * md->Aload[ld->nodes[k]];
  TU_CHECK(fem_solver_set_nodal_forces(s, ld->nnodes, ld->nodes, f));
  free(f);
  TU_CHECK(fem_solver_solve(s));
  *out = s;
  return 0;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  double x0a = 0.0, x0b = 1.1;
  SmeshBlock blk[2] = {
      {{5, 2, 2}, map_bar, &x0a, {"clampA", "endA", NULL, NULL, NULL, NULL}},
      {{5, 2, 2}, map_bar, &x0b, {"startB", "loadB", NULL, NULL, NULL, NULL}}};
  FemMesh *m;
  TU_CHECK(smesh_build(2, blk, 1, 1e-9, &m));
  int N = m->nnodes, fails = 0;
  const FemSurface *ea = fem_mesh_find_surface(m, "endA"), *sb = fem_mesh_find_surface(m, "startB");
  double *Aend = malloc(sizeof(double) * N), *Aload = malloc(sizeof(double) * N);
  tributary(m, ea, Aend);
  tributary(m, fem_mesh_find_surface(m, "loadB"), Aload);
  Model md = {m, 0, malloc(sizeof(int) * ea->nnodes), malloc(sizeof(int) * ea->nnodes),
              malloc(sizeof(double) * ea->nnodes), Aload};
  for (int i = 0; i < ea->nnodes; i++) {
    int a = ea->nodes[i];
    for (int j = 0; j < sb->nnodes; j++) {
      int b = sb->nodes[j];
      if (fabs(m->xyz[3 * a + 1] - m->xyz[3 * b + 1]) < 1e-9 &&
          fabs(m->xyz[3 * a + 2] - m->xyz[3 * b + 2]) < 1e-9) {
        md.a[md.n] = a, md.b[md.n] = b, md.k[md.n] = KBAR * Aend[a];
        md.n++;
      }
    }
  }
  if (md.n != ea->nnodes) fprintf(stderr, "matched %d of %d nodes\n", md.n, ea->nnodes), fails++;

  /* 1. springs in the pattern from setup: hand solution */
  FemSolver *s1, *s2;
  TU_CHECK(build(&md, 1, &s1));
  const double *u1 = fem_solver_displacements(s1);
  double umax = T / E * 2 + T / KBAR, err = 0;
  for (int i = 0; i < N; i++) {
    double X = m->xyz[3 * i];
    double ux = X < 1.05 ? T * X / E : T / E + T / KBAR + T * (X - 1.1) / E;
    err = fmax(err, fabs(u1[3 * i] - ux));
    err = fmax(err, fmax(fabs(u1[3 * i + 1]), fabs(u1[3 * i + 2])));
  }
  fails += tu_close("two bars joined by springs: max |u - u_hand|", err, 0.0, 1e-3 * umax, 0.0);
  FemSolverStats st1, st2;
  fem_solver_stats(s1, &st1);
  if (st1.n_pattern_rebuilds != 0) fprintf(stderr, "rebuild without need\n"), fails++;
  if (fem_solver_floating_bodies(s1) != 0) fprintf(stderr, "held body called floating\n"), fails++;

  /* 2. springs added after setup: one rebuild during the solve, same answer */
  TU_CHECK(build(&md, 0, &s2));
  fem_solver_stats(s2, &st2);
  if (st2.n_pattern_rebuilds != 1) {
    fprintf(stderr, "%d pattern rebuilds, expected 1\n", st2.n_pattern_rebuilds);
    fails++;
  }
  if (st2.nnz_k != st1.nnz_k) {
    fprintf(stderr, "rebuilt pattern nnz %ld, built-in %ld\n", st2.nnz_k, st1.nnz_k);
    fails++;
  }
  const double *u2 = fem_solver_displacements(s2);
  double d = 0;
  for (int i = 0; i < 3 * N; i++) d = fmax(d, fabs(u2[i] - u1[i]));
  fails += tu_close("rebuild mid-solve vs pair from the start: max |du|", d, 0.0, 1e-12 * umax,
                    0.0);
  fem_solver_destroy(&s1);
  fem_solver_destroy(&s2);

  /* 3. floating body diagnosis, and weak ground springs that hold it */
  FemMaterial mat = fem_material_from_e_nu(E, 0.0, 1.0);
  FemSolver *s3;
  TU_CHECK(fem_solver_create(m, &mat, NULL, &s3));
  TU_CHECK(fem_solver_fix_surface(s3, "clampA", FEM_XYZ));
  TU_CHECK(fem_solver_setup(s3));
  if (fem_solver_floating_bodies(s3) != 1) {
    fprintf(stderr, "floating bodies: %d, expected 1\n", fem_solver_floating_bodies(s3));
    fails++;
  }
  fem_solver_destroy(&s3);
  TU_CHECK(fem_solver_create(m, &mat, NULL, &s3));
  TU_CHECK(fem_solver_fix_surface(s3, "clampA", FEM_XYZ));
  for (int j = 0; j < sb->nnodes; j++) TU_CHECK(fem_solver_add_spring(s3, sb->nodes[j], -1, 1e-6));
  TU_CHECK(fem_solver_setup(s3));
  if (fem_solver_floating_bodies(s3) != 0) fprintf(stderr, "ground springs ignored\n"), fails++;
  TU_CHECK(fem_solver_solve(s3)); /* no load: must solve (weak springs hold B) */
  fem_solver_destroy(&s3);

  /* 4. an interface surface selected by side: two blocks sharing the face x = 1 (merged
   *    nodes), regions a and b; the group is stored oriented out of a (+x) */
  smesh_free(&m);
  double x0c = 1.0;
  SmeshBlock blk2[2] = {
      {{3, 2, 2}, map_bar, &x0a, {NULL, "iface", NULL, NULL, NULL, NULL}},
      {{3, 2, 2}, map_bar, &x0c, {NULL, NULL, NULL, NULL, NULL, NULL}}};
  TU_CHECK(smesh_build(2, blk2, 2, 1e-9, &m));
  char(*rn)[64] = realloc(m->region_names, 2 * sizeof *rn);
  if (!rn) return 1;
  m->region_names = rn;
  strcpy(rn[0], "a"), strcpy(rn[1], "b");
  m->nregions = 2;
  for (int e = 0; e < m->nelem; e++) {
    double xc = 0;
    for (int a = 0; a < 4; a++) xc += 0.25 * m->xyz[3 * m->conn[(size_t)e * m->nen + a]];
    m->region[e] = xc > 1.0;
  }
  TU_CHECK(fem_mesh_add_surface_side(m, "iface", "b", "iface_b"));
  TU_CHECK(fem_mesh_add_surface_side(m, "iface", "a", "iface_a"));
  for (int side = 0; side < 2; side++) {
    const FemSurface *f = fem_mesh_find_surface(m, side ? "iface_b" : "iface_a");
    int bad = f->nfaces == 0;
    for (int k = 0; k < f->nfaces; k++) {
      const int *c = f->faces + (size_t)k * f->nfn;
      const double *p0 = m->xyz + 3 * c[0], *p1 = m->xyz + 3 * c[1], *p2 = m->xyz + 3 * c[2];
      double nx = (p1[1] - p0[1]) * (p2[2] - p0[2]) - (p1[2] - p0[2]) * (p2[1] - p0[1]);
      if ((side ? -nx : nx) <= 0 || m->region[f->face_elem[k]] != side) bad = 1;
      /* mid-node 3 lies on edge 01 */
      for (int i = 0; i < 3; i++)
        if (fabs(m->xyz[3 * c[3] + i] - 0.5 * (p0[i] + p1[i])) > 1e-12) bad = 1;
    }
    if (bad) fprintf(stderr, "interface side %s: wrong orientation or element\n", side ? "b" : "a"), fails++;
  }
  sa_error_clear();
  if (fem_mesh_add_surface_side(m, "clampA", "b", "x") == 0) fails++; /* no such surface */
  sa_error_clear();

  free(Aend);
  free(Aload);
  free(md.a);
  free(md.b);
  free(md.k);
  smesh_free(&m);
  return fails != 0;
}
