/* test_checkpoint - fem_solver_write_state / fem_solver_read_state: a run resumed from a
 * checkpoint equals the run that went on, bit for bit.
 *
 * A cantilever bar (tet10, 6 x 2 x 1 cells, compressible neo-Hookean, HHT alpha = -0.05,
 * mass damping) is pushed by a tip load that changes every step (as the DEM wall forces do),
 * with the REUSE predictor and modified Newton (the factorisation is part of the state that
 * is not stored: writing drops it, so both runs refactorise at the next step). Steps 1-4,
 * checkpoint, steps 5-10 -> A. A second solver built from scratch reads the checkpoint and
 * takes steps 5-10 -> B. Reference: A itself, since the resumed run must take the same
 * floating-point path; any field left out of the checkpoint (velocity, acceleration, r_n,
 * committed loads, time) changes B at the first step after the resume (checked: the test
 * fails when the velocities are zeroed after reading). Also: a truncated stream and a
 * checkpoint of another mesh are refused with SA_ERR_INPUT.
 * Snapshot/rollback (the iterated FEM-DEM step): after step 10, snapshot; step 11 under load
 * k = 11 -> u1; roll back (displacements and velocities must equal the snapshot's bit for
 * bit); step 11 under another load; roll back; step 11 under load 11 again -> u1'. The factors
 * are kept across a rollback (modified Newton from other factors), so u1' equals u1 to the
 * Newton tolerance (rtol 1e-9: checked to 1e-7 of max|u|), not bitwise; the other load must
 * have moved the bar (else the rollback would be untested). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_error.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static void map_bar(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  X[0] = xi[0], X[1] = 0.2 * xi[1], X[2] = 0.1 * xi[2];
}

static int make(FemMesh *m, FemSolver **out) {
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 13.0 / 6.0, .rho = 1};
  FemSolverParams prm = fem_solver_params_default();
  prm.hht_alpha = -0.05;
  prm.mass_damping = 0.5;
  prm.predictor = FEM_PREDICT_REUSE;
  prm.reuse_rate = 0.5;
  prm.rtol = 1e-9;
  prm.threads = 1;
  SA_CHECK(fem_solver_create(m, &mat, &prm, out));
  SA_CHECK(fem_solver_fix_surface(*out, "clamp", FEM_XYZ));
  SA_CHECK(fem_solver_setup(*out));
  return 0;
}

static int step(FemSolver *s, const int *tipn, int ntip, int k) {
  double f[3 * 64];
  for (int i = 0; i < ntip; i++)
    f[3 * i] = 0, f[3 * i + 1] = 1e-4 * sin(0.7 * k), f[3 * i + 2] = -2e-3 * (1 + 0.3 * cos(k));
  SA_CHECK(fem_solver_set_nodal_forces(s, ntip, tipn, f));
  return fem_solver_step_dynamic(s, 0.05);
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_WARN);
  SmeshBlock blk = {{6, 2, 1}, map_bar, NULL, {"clamp", "end", "s2", "s3", "s4", "s5"}};
  FemMesh *m, *m2;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  int tipn[64], ntip = 0;
  for (int A = 0; A < m->nnodes && ntip < 64; A++)
    if (fabs(m->xyz[3 * A] - 1.0) < 1e-12) tipn[ntip++] = A;
  FemSolver *a = NULL, *b = NULL;
  TU_CHECK(make(m, &a));
  for (int k = 1; k <= 4; k++) TU_CHECK(step(a, tipn, ntip, k));
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  TU_CHECK(fem_solver_write_state(a, f));
  fclose(f);
  for (int k = 5; k <= 10; k++) TU_CHECK(step(a, tipn, ntip, k));

  TU_CHECK(make(m, &b));
  f = fmemopen(buf, len, "rb");
  TU_CHECK(fem_solver_read_state(b, f, "memory"));
  fclose(f);
  for (int k = 5; k <= 10; k++) TU_CHECK(step(b, tipn, ntip, k));
  int fails = 0, n = 3 * m->nnodes;
  const double *ua = fem_solver_displacements(a), *ub = fem_solver_displacements(b);
  const double *va = fem_solver_velocities(a), *vb = fem_solver_velocities(b);
  double du = 0, dv = 0, umax = 0;
  for (int i = 0; i < n; i++) {
    du = fmax(du, fabs(ua[i] - ub[i])), dv = fmax(dv, fabs(va[i] - vb[i]));
    umax = fmax(umax, fabs(ua[i]));
  }
  if (du != 0 || dv != 0 || fem_solver_time(a) != fem_solver_time(b)) {
    printf("resumed run differs: |du| %.3g (of %.3g), |dv| %.3g, time %.17g vs %.17g\n", du,
           umax, dv, fem_solver_time(a), fem_solver_time(b));
    fails++;
  }
  if (umax < 1e-4) {
    printf("the load moved the bar by only %.3g: the test exercises nothing\n", umax);
    fails++;
  }
  /* snapshot and rollback */
  {
    FemSnapshot *snap = NULL;
    double *u0 = malloc(sizeof(double) * n), *v0 = malloc(sizeof(double) * n);
    double *u1 = malloc(sizeof(double) * n);
    TU_CHECK(!(u0 && v0 && u1));
    memcpy(u0, ua, sizeof(double) * n), memcpy(v0, va, sizeof(double) * n);
    double t0 = fem_solver_time(a);
    TU_CHECK(fem_solver_snapshot(a, &snap));
    TU_CHECK(step(a, tipn, ntip, 11));
    memcpy(u1, fem_solver_displacements(a), sizeof(double) * n);
    TU_CHECK(fem_solver_rollback(a, snap));
    double d0 = 0;
    for (int i = 0; i < n; i++)
      d0 = fmax(d0, fmax(fabs(fem_solver_displacements(a)[i] - u0[i]),
                         fabs(fem_solver_velocities(a)[i] - v0[i])));
    if (d0 != 0 || fem_solver_time(a) != t0) {
      printf("rollback does not restore the snapshot: max diff %.3g, time %.17g vs %.17g\n", d0,
             fem_solver_time(a), t0);
      fails++;
    }
    TU_CHECK(step(a, tipn, ntip, 14)); /* another load */
    double dother = 0;
    for (int i = 0; i < n; i++) dother = fmax(dother, fabs(fem_solver_displacements(a)[i] - u1[i]));
    TU_CHECK(fem_solver_rollback(a, snap));
    TU_CHECK(step(a, tipn, ntip, 11));
    double d1 = 0;
    for (int i = 0; i < n; i++) d1 = fmax(d1, fabs(fem_solver_displacements(a)[i] - u1[i]));
    if (d1 > 1e-7 * umax || dother < 1e-3 * umax) {
      printf("repeated step after rollback: |u1' - u1| %.3g (limit %.3g), other load moved %.3g\n",
             d1, 1e-7 * umax, dother);
      fails++;
    }
    fem_snapshot_destroy(&snap);
    free(u0), free(v0), free(u1);
  }
  /* a truncated checkpoint and one of another mesh are refused */
  f = fmemopen(buf, len / 2, "rb");
  if (fem_solver_read_state(b, f, "half") != SA_ERR_INPUT) {
    printf("a truncated checkpoint was accepted\n");
    fails++;
  }
  fclose(f);
  sa_error_clear();
  SmeshBlock blk2 = {{5, 2, 1}, map_bar, NULL, {"clamp", "end", "s2", "s3", "s4", "s5"}};
  FemSolver *c = NULL;
  TU_CHECK(smesh_build(1, &blk2, 2, 1e-9, &m2));
  TU_CHECK(make(m2, &c));
  f = fmemopen(buf, len, "rb");
  if (fem_solver_read_state(c, f, "other") != SA_ERR_INPUT) {
    printf("a checkpoint of another mesh was accepted\n");
    fails++;
  }
  fclose(f);
  sa_error_clear();
  free(buf);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);
  fem_solver_destroy(&c);
  smesh_free(&m);
  smesh_free(&m2);
  return fails ? 1 : 0;
}
