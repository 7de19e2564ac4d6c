/* test_interrupt - a signal stops a FEM solve at the next Newton iteration, not at the end of
 * the load step (which takes a minute on the actuator's coarse mesh), and leaves the solver at
 * its last converged state (the state a caller then reports or checkpoints).
 *
 * Cantilever bar (tet10, neo-Hookean), clamped at x = 0, end load: a first solve converges;
 * then SIGTERM is raised (handlers installed, so it only sets the flag) and the load doubled:
 * the second solve must return SA_ERR_INTERRUPTED after 0 Newton iterations with the
 * displacements of the first solve, bit for bit. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_log.h"
#include "sa_output.h"
#include "smesh.h"
#include "tutil.h"

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  SmeshBlock blk = {{6, 2, 2}, smesh_map_bar, NULL,
                    {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 50, .rho = 1};
  FemSolverParams prm = fem_solver_params_default();
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc((size_t)3 * end->nnodes, sizeof *f);
  if (!f) return 1;
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] = -1e-3 / end->nnodes;
  TU_CHECK(fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f));
  TU_CHECK(fem_solver_solve(s));
  int n = 3 * m->nnodes, fail = 0;
  double *u1 = malloc(sizeof(double) * (size_t)n);
  if (!u1) return 1;
  memcpy(u1, fem_solver_displacements(s), sizeof(double) * (size_t)n);

  sa_signals_install();
  raise(SIGTERM);
  if (!sa_interrupted()) {
    fprintf(stderr, "SIGTERM did not set the interrupt flag\n");
    return 1;
  }
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] *= 2;
  TU_CHECK(fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f));
  int rc = fem_solver_solve(s);
  FemSolveReport rep;
  fem_solver_report(s, &rep);
  if (rc != SA_ERR_INTERRUPTED) {
    fprintf(stderr, "solve after SIGTERM returned %d (%s), expected SA_ERR_INTERRUPTED (%d)\n", rc,
            rc ? sa_error_message() : "converged", SA_ERR_INTERRUPTED);
    fail = 1;
  }
  if (rep.newton_iters != 0) {
    fprintf(stderr, "%d Newton iterations after SIGTERM, expected 0\n", rep.newton_iters);
    fail = 1;
  }
  const double *u = fem_solver_displacements(s);
  for (int i = 0; i < n; i++)
    if (u[i] != u1[i]) {
      fprintf(stderr, "u[%d] = %.17g after the interrupted solve, last converged %.17g\n", i,
              u[i], u1[i]);
      fail = 1;
      break;
    }
  sa_error_clear();
  free(u1);
  free(f);
  fem_solver_destroy(&s);
  smesh_free(&m);
  return fail;
}
