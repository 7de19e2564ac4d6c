/* fem_contrib.h - assembly contributors: the open end of the FEM assembly.
 *
 * The residual the Newton driver drives to zero is a sum of contributions,
 *   R(u) = f_int(u)  [bodies: element kernels]  - p q(u)  [follower pressure]
 *        - f_dead    [nodal/coupling forces + gravity]   + sum_c f_c(u)  [contributors]
 * with the tangent K = dR/du summed the same way. Bodies, pressure and dead loads are built in
 * (fem_assemble.c, with their threaded / specialised paths); everything else - springs (built
 * in as one contributor, fem_solver_add_spring), contact, coupling penalties, a user's load -
 * is a FemContributor. A contributor adds nodal forces f_c (sign: as an internal force, i.e.
 * what the body exerts on its surroundings; an external load F is added as -F) and, when asked,
 * the 3x3 blocks dF_A/du_B of its stiffness.
 *
 * A contributor may couple nodes that share no element. The pattern is built in setup from the
 * elements plus every contributor's candidate pairs; a block for a pair outside it (a contact
 * pair that appeared, a contributor added after setup) makes the assembly rebuild the pattern,
 * the symbolic analysis and the linear solver once, and assemble again
 * (FemSolverStats.n_pattern_rebuilds counts it; factors of the old pattern are dropped).
 *
 * History: a contributor whose forces depend on the load path (friction) keeps a committed
 * state, updated by the commit hook when a step is accepted.
 *
 * Lifecycle: fem_solver_add_contributor before or after setup; the descriptor is copied, ctx is
 * [borrowed] and must outlive the solver. eval runs serially (after the threaded element loop),
 * on the Newton iterate, on line-search trial states and for read-back; it must not allocate in
 * a coupling loop. */
#ifndef FEM_CONTRIB_H
#define FEM_CONTRIB_H

#include "fem_mesh.h"

typedef struct FemSolver FemSolver;
typedef struct FemAsmView FemAsmView; /* the assembly a contributor adds to (opaque) */
typedef struct FemPairSink FemPairSink;

typedef struct {
  const char *name; /* for messages */
  /* Candidate node pairs (may be NULL): call fem_pairs_add for each pair (A, B) the contributor
   * may ever couple, so that the pattern contains them from setup. */
  int (*candidates)(void *ctx, const FemMesh *m, FemPairSink *sink);
  /* Add the contribution at the state of v. Returns 0; > 0 recoverable (the state is outside
   * the contributor's domain: the line search backtracks); < 0 fatal. */
  int (*eval)(void *ctx, FemAsmView *v);
  void *ctx;
  /* Step accepted (may be NULL): called once per converged substep (static) / step (dynamic),
   * after the solver committed it, with the converged positions x [in] 3 * nnodes, before the
   * monitor. A contributor with history (contact: the stick anchors) commits it here; eval
   * must compute its trial state from the committed history only, so a failed, cut substep
   * needs no restore. */
  void (*commit)(void *ctx, const double *x);
} FemContributor;

int fem_solver_add_contributor(FemSolver *s, const FemContributor *c);

void fem_pairs_add(FemPairSink *sink, int a, int b);

/* Inside eval. */
const FemMesh *fem_asm_mesh(const FemAsmView *v);
const double *fem_asm_positions(const FemAsmView *v); /* current x [borrowed] 3 * nnodes */
double fem_asm_time(const FemAsmView *v);             /* [s] of the state being assembled */
double fem_asm_load_factor(const FemAsmView *v);      /* ramp parameter, fem_solver_load_factor */
int fem_asm_wants_tangent(const FemAsmView *v);
/* f [in] 3: force on node a (internal-force sign, see above). */
void fem_asm_add_force(FemAsmView *v, int a, const double f[3]);
/* K [in] 3x3 row-major: d f_a / d u_b. Ignored unless fem_asm_wants_tangent. */
void fem_asm_add_block(FemAsmView *v, int a, int b, const double K[9]);

#endif
