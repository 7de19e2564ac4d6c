/* fem_contact.h - frictional contact as an assembly contributor (fem_contrib.h).
 *
 * Node-to-surface penalty contact with Coulomb friction (Wriggers, Computational Contact
 * Mechanics, 2006, ch. 5 and 6; Laursen 2002, ch. 5). One FemContact pairs the nodes of a
 * slave surface of the mesh with ONE target:
 *   - a master surface of the mesh (another body: large sliding, the closest master face is
 *     searched again at every evaluation, i.e. every Newton iterate and line-search trial;
 *     tri6 faces are split into their 4 flat sub-triangles for the geometry; the reactions go
 *     to the sub-triangle's nodes or, with master_quadratic, to the face's 6 nodes);
 *   - a rigid plane (point, normal pointing into the side where the slave lives);
 *   - a rigid cylinder wall (axis point, axis direction, radius, axial extent; the slave lives
 *     inside, e.g. the fill in the barrel).
 * Per slave node k with reference tributary area A_k (slave_weights: by default a third of
 * each adjacent (sub-)triangle):
 *   gap g (signed distance to the target, < 0 = penetration), outward target normal n,
 *   normal pressure  t_N = eps_N <-g>            [Pa], eps_N the penalty [Pa/m],
 *   tangential trial t_T = -eps_T P (x - a)      (a: the stick anchor, P = I - n n),
 *   return map       |t_T| <= mu t_N: stick;  else slip, t_T <- mu t_N t_T / |t_T|,
 *   force on node k  A_k (t_N n + t_T); the master nodes get minus that, distributed with the
 *   shape functions of the contact point.
 * The anchor is history: it is committed when the solver accepts a step (FemContributor
 * commit hook) and lies on the target (on a mesh master: a convected point, face + barycentric
 * coordinates, moving with the master). Eval computes every trial from the committed anchors.
 *
 * Tangent: exact linearisation for the rigid targets (including the curvature of the
 * cylinder); for a mesh master the 3x3 blocks of each active pair are central differences of
 * the pair's force function with its discrete state (face, active, stick/slip) frozen, step
 * 1e-7 of the face size (truncation ~1e-14, round-off ~1e-9 relative). With friction in slip
 * the tangent is unsymmetric: the solver's AUTO choice then factorises with UMFPACK.
 *
 * Penalty scale: eps_N = alpha E / h (E the softer body's Young's modulus, h its element size)
 * makes the contact layer as stiff as alpha elements; the penetration under pressure p is
 * p / eps_N. docs/contact.md gives the measured effect of alpha.
 *
 * Failure: a penetration deeper than max_penetration (when > 0) or a non-finite position make
 * eval return SA_ERR_DOMAIN (> 0, recoverable: the line search backtracks, then the substep is
 * cut). No abort, no exit. A slave node with no master triangle (empty master) is simply not
 * in contact. fem_contact_create may leave a partial object in *out on failure: destroy it.
 *
 * Lifecycle: fem_contact_create(mesh, slave surface, params) -> one of set_master / set_plane /
 * set_cylinder -> fem_contact_attach(solver) (before or after setup) -> solves ->
 * read-back (state at the last accepted step) -> fem_contact_destroy(&c) after the solver. */
#ifndef FEM_CONTACT_H
#define FEM_CONTACT_H

#include "fem.h"

typedef struct FemContact FemContact;

typedef struct {
  double penalty;         /* eps_N [Pa/m] (> 0) */
  double penalty_tangent; /* eps_T [Pa/m]; 0: = penalty */
  double friction;        /* Coulomb coefficient mu (>= 0) */
  double max_penetration; /* [m]; deeper = recoverable failure (0: no limit) */
  double search_radius;   /* [m] mesh master: candidate pairs of the reference configuration
                           * within this distance enter the pattern at setup (0: none) */
  int smooth_normals;     /* mesh master: 1 = the normal at the contact point interpolates the
                           * master's area-weighted vertex normals (continuous across master
                           * edges; the faceted normal jumps by the facet angle there and a slave
                           * node crossing an edge makes Newton chatter); its dependence on the
                           * master's nodes is left out of the tangent. 0 = facet normal */
  int slave_weights;      /* FemContactWeights: how a slave node's area A_k is taken from its
                           * faces (0 = FEM_CONTACT_WEIGHTS_LUMPED, the default) */
  int master_quadratic;   /* mesh master with tri6 faces: 1 = a slave node's reaction goes to
                           * the 6 nodes of the face with its quadratic shape functions at the
                           * contact point (the face's own interpolation); 0 (default) = to the
                           * 3 nodes of the flat sub-triangle, linearly. The geometry (closest
                           * point, gap, normal) is the flat sub-triangle's either way */
} FemContactParams;

/* Slave tributary areas A_k. On tri3 faces both give A/3 per node. On tri6 faces:
 *   LUMPED      each face's 4 flat sub-triangles share their area 1/3 to their vertices:
 *               corners A/12, mid-nodes A/4 (positive everywhere, but not the loads a
 *               uniform pressure puts on a quadratic face, so a tet10 slave under a uniform
 *               pressure is not in uniform stress: tests/fem/solver/test_contact_patch_tet10.c);
 *   CONSISTENT  A_k = int N_k dA over the reference face (tri6 shape functions, the 6-point
 *               rule): on a flat face corners 0, mid-nodes A/3, the consistent nodal loads
 *               of a uniform pressure (a curved face's negative values are set to 0 and the
 *               face's weights scaled back to its area). A corner node then carries no
 *               contact force: nothing stops it penetrating where its mid-nodes do not (a
 *               slave corner at the edge of the contact zone; on the non-matching patch test
 *               corners penetrate 1-2e-8 m whatever the penalty). */
typedef enum {
  FEM_CONTACT_WEIGHTS_LUMPED = 0,
  FEM_CONTACT_WEIGHTS_CONSISTENT = 1
} FemContactWeights;

FemContactParams fem_contact_params_default(void); /* penalty 0 (must be set), mu 0 */

/* mesh [borrowed]; slave: name of a surface of mesh. */
int fem_contact_create(const FemMesh *mesh, const char *slave, const FemContactParams *prm,
                       FemContact **out);
/* Target: master surface of the mesh (a node of the slave never contacts a face it belongs to). */
int fem_contact_set_master(FemContact *c, const char *master);
/* Target: rigid plane through point p [in] 3 with unit normal n [in] 3 pointing to the slave's
 * side. May be called again between solves to move the plane (anchors keep their points). */
int fem_contact_set_plane(FemContact *c, const double p[3], const double n[3]);
/* Move the plane to pass through p [in] 3 during the next solve: its point follows the solver's
 * ramp parameter from the committed position (fem_solver_load_factor), so substeps and
 * cut-backs move it with the loads (a prescribed piston). set_plane places it at once. */
int fem_contact_move_plane(FemContact *c, const double p[3]);
/* Target: rigid cylinder wall, axis through p [in] along a [in] (normalised here), radius R,
 * active for axial coordinate s = (x - p).a in [smin, smax]; the slave lives inside. */
int fem_contact_set_cylinder(FemContact *c, const double p[3], const double a[3], double R,
                             double smin, double smax);
/* Register the contributor on s [borrowed: c must outlive the solves, s must outlive c's use]. */
int fem_contact_attach(FemContact *c, FemSolver *s);

/* Change mu between solves (the anchors stay: a node committed on the slip surface is in
 * strict stick for a larger mu, strict slip for a smaller one). */
int fem_contact_set_friction(FemContact *c, double mu);

typedef struct {
  int n_active, n_slip;   /* slave nodes in contact / slipping */
  double max_penetration; /* [m] */
  double force[3];        /* total force the target exerts on the slave [N] */
  double normal_force;    /* sum of A t_N [N] */
  double tangent_force;   /* |sum of A t_T| [N] */
  double tangent_slack;   /* sum of A |t_T - P lT| / eps_T [m^3]: the tangential motion from the
                           * step's stick points that the penalty still needs to carry t_T (the
                           * tangential Uzawa residual; 0 once the multipliers carry it) */
} FemContactStats;

/* Augmented Lagrangian (Uzawa; Wriggers 2006 sec. 6.3, Laursen 2002 sec. 5.3): each slave
 * node carries a normal pressure multiplier lam >= 0 and t_N = <lam - eps_N g>. After a
 * converged solve, fem_contact_augment sets lam to the pressure each node carried at the
 * committed state; solving again at the same loads then needs less penetration to carry it,
 * and repeating drives the gaps to zero with a penalty that only sets the rate (the error
 * contracts by about K / (K + eps_N) per update, K the structure's stiffness per area), not the
 * answer. Returns the largest penetration [m] and the overlap volume sum A <-g> [m^3] of the
 * committed state BEFORE the update (the caller's stopping test; with friction also
 * FemContactStats.tangent_slack). With friction the tangential traction is augmented the same
 * way: each node's multiplier lT (3) becomes the traction t_T it carried, the stick trial is
 * P lT - eps_T d (d the tangential motion from the stick point, P = I - n n), so repeated
 * updates drive the stick nodes' elastic slip t_T / eps_T to zero (exact stick); the Coulomb
 * limit mu t_N uses the augmented t_N. The update is the next solve's target: that solve moves the multipliers from
 * the committed values to it with its load factor (like a moving plane), so the solver's
 * substep cuts take a smaller part of a large change; a completed solve commits them.
 * Multipliers start at 0 (pure penalty) and are not part of the solver's snapshot: call
 * between solves only. */
int fem_contact_augment(FemContact *c, double *max_penetration, double *overlap_volume);
/* Damp the pending update of fem_contact_augment: every target multiplier (normal and
 * tangential) becomes committed + omega (target - committed), omega in (0, 1]. A shorter Uzawa
 * step for a solve that failed with the whole one (the Uzawa iteration converges for any step
 * up to the full one, only more slowly). */
int fem_contact_augment_damp(FemContact *c, double omega);
/* With friction the solves of an augmentation loop must not each commit a slip: slip is
 * irreversible, so a first solve with the penalty's penetration would leave the nodes where it
 * slid them and the answer would depend on the penalty. fem_contact_mark keeps the stick
 * anchors at the start of a load step; fem_contact_restore_mark before each augmented solve
 * puts them back, so the step's friction is one backward-Euler increment from the mark to the
 * final state, whatever the number of updates. */
void fem_contact_mark(FemContact *c);
void fem_contact_restore_mark(FemContact *c);
/* Back to the state at fem_contact_mark: stick anchors, committed plane point and committed
 * multipliers (normal and tangential), keeping the targets (plane target, multiplier targets
 * set by fem_contact_augment). With the solver rolled back to the same moment
 * (fem_solver_rollback), the next solve is the whole load step again, its ramp moving the
 * plane and the multipliers from the step's start to the targets (cut-backs included). */
void fem_contact_rewind(FemContact *c);
/* The committed contact state (anchors, multipliers, read-back, stats, plane) in memory, to go
 * with fem_solver_snapshot / fem_solver_rollback: a failed solve commits its substeps into the
 * contact, so rolling back the solver alone would leave the contact at a state the solver no
 * longer has. restore also drops a pending multiplier update. */
int fem_contact_save(FemContact *c);
int fem_contact_restore(FemContact *c);

/* At the last accepted step (zeros before the first). */
void fem_contact_stats(const FemContact *c, FemContactStats *st);
/* Per slave node (committed): nslave [out]; node, area, gap, pressure t_N, traction t_T [3],
 * normal n [3] [borrowed arrays, any out pointer may be NULL]. */
int fem_contact_slaves(const FemContact *c, const int **node, const double **area,
                       const double **gap, const double **tn, const double **tt,
                       const double **normal);
void fem_contact_destroy(FemContact **c);

#endif
