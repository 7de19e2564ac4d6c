/* fem.h - public interface of the fem module: the nonlinear solid solver and the module glue.
 *
 * FemSolver: total-Lagrangian finite elements (tet4/tet10, mean-dilatation mixed element from
 * fem_element.h) with Newton-Raphson, consistent tangent, backtracking line search and adaptive
 * load stepping. Linear systems: CHOLMOD supernodal Cholesky (METIS ordering, symbolic analysis
 * once in setup) with a stated UMFPACK LU fallback when the tangent is not positive definite or
 * not symmetric. Formulation and definitions: docs/fem.md.
 *
 * Lifecycle (handle first, outputs last; destroy accepts NULL):
 *   fem_solver_create(mesh, mats, params)       mesh [borrowed], mats [in] copied, one per region
 *                                               (laws: fem_law.h; mesh and laws are validated)
 *   fem_solver_fix_surface / fix_nodes / add_pressure_surface / set_gravity      (before setup)
 *   fem_solver_add_spring / add_contributor (fem_contrib.h) / set_domain_check   (any time)
 *   fem_solver_setup                            ALL symbolic work and every allocation (a
 *                                               contributor pair outside the pattern later
 *                                               rebuilds it once: FemSolverStats)
 *   loop: set_pressure | set_volume | set_nodal_forces | set_prescribed -> solve | step_dynamic
 *         -> positions / velocities / pressure / cavity_volume
 *   fem_solver_destroy(&s)
 *
 * Loads are TARGETS: solve() ramps every load from the last converged (committed) state to its
 * target with adaptive substeps (load parameter 0 -> 1), so a coupling call that changes the
 * wall forces a little costs one substep of a few Newton iterations, with no re-analysis and no
 * allocation in solver code. On failure the solver is left at the last converged substep
 * (fem_solver_report says how far it got). */
#ifndef FEM_H
#define FEM_H

#include <stdio.h>

#include "fem_material.h"
#include "fem_mesh.h"
#include "sa_module.h"

/* The module the CLI registers (trigger section [mesh]). */
extern const SaModule fem_module;

typedef struct FemSolver FemSolver;

/* Component masks for boundary conditions. */
enum { FEM_X = 1, FEM_Y = 2, FEM_Z = 4, FEM_XYZ = 7 };

typedef enum {
  FEM_CONTROL_LOAD = 0,  /* pressure (and every other load) prescribed */
  FEM_CONTROL_VOLUME = 1 /* cavity volume prescribed, pressure unknown (bordered system) */
} FemControl;

typedef enum { FEM_LINSOLVER_AUTO = 0, FEM_LINSOLVER_LU = 1 } FemLinSolverChoice;

/* Tangent of the first Newton iteration of a substep (the predictor). */
typedef enum {
  FEM_PREDICT_NEW_LOAD = 0,    /* converged state with the new pressure's load stiffness (default) */
  FEM_PREDICT_EQUILIBRIUM = 1, /* tangent at the converged state and its loads (Euler predictor) */
  FEM_PREDICT_REUSE = 2,       /* the last factors of the converged state when there are such
                                * (no factorisation), else EQUILIBRIUM */
  FEM_PREDICT_EXTRAPOLATE = 3  /* static load control: u_n + r (u_n - u_n-1), r the ratio of
                                * the pressure increments (secant predictor), then NEW_LOAD;
                                * pulled back toward u_n if it inverts an element */
} FemPredictor;

/* Line-search merit (docs/fem_time_to_accuracy.md). */
typedef enum {
  FEM_MERIT_LAZY = 0,  /* backtrack only on a domain error, NaN or |R| growth > ls_growth */
  FEM_MERIT_ENERGY = 1 /* Armijo backtracking (quadratic interpolation) on the total potential
                        * Pi = W(u) - p V(u) - f_dead.u when it is one (static, load control,
                        * no contributors) and the direction descends; else LAZY. Stalled
                        * then means max_stall exhausted line searches in a row, not a
                        * residual norm that fails to halve (it is no merit there) */
} FemMerit;

/* What a Newton iteration does when CHOLMOD finds the tangent not positive definite. */
typedef enum {
  FEM_INDEFINITE_LU = 0,       /* UMFPACK LU of the consistent tangent */
  FEM_INDEFINITE_MODIFY = 1    /* Cholesky of K_int + beta p K_q, beta = p_last/p then 0 (the
                                * load stiffness of the converged pressure, then none). At a
                                * Newton iterate past the first, a consistent tangent that is
                                * not positive definite means the iterate went too far: the
                                * step to it is halved (up to the line search's limit; then
                                * K_int alone is tried). If even that fails, or at the first
                                * iterate, the substep fails (recoverable:
                                * the increment is cut; a limit point is diagnosed as before).
                                * Any load-controlled solve, static or dynamic; without a
                                * follower pressure K_int is the consistent tangent itself.
                                * Volume control always takes the LU. */
} FemIndefinite;

typedef struct {
  double rtol;       /* residual norm relative to the internal-force norm (incl. reactions) */
  double atol;       /* absolute residual norm [N] */
  double utol;       /* or: last full Newton update <= utol |u| (residual at round-off floor) */
  double vtol;       /* volume-constraint tolerance relative to the reference cavity volume */
  int max_iter;      /* Newton iterations per substep before it counts as diverged */
  int max_stall;     /* consecutive iterations that fail to halve |R| before giving up */
  int line_search;   /* backtracking on inverted elements, NaN, residual growth > ls_growth */
  double ls_growth;  /* residual growth factor that triggers backtracking */
  double dl_init;    /* first load-parameter increment (fraction of the ramp) */
  double dl_min;     /* below this the ramp fails (limit point / step too small) */
  double dl_max;     /* largest increment */
  int easy_iter;     /* a substep converged in <= easy_iter iterations grows the next one */
  double grow;       /* growth factor after an easy substep */
  double cut;        /* cut factor after a failed substep */
  int threads;       /* element-loop threads and BLAS threads (>= 1) */
  FemLinSolverChoice linsolver; /* AUTO: CHOLMOD, UMFPACK when needed; LU: always UMFPACK */
  double sym_tol;    /* tangent treated as symmetric when max|K-K^T|/max|K| <= sym_tol */
  double hht_alpha;  /* implicit dynamics: HHT alpha in [-1/3, 0] (0 = trapezoidal Newmark) */
  double mass_damping; /* Rayleigh mass-proportional damping coefficient [1/s] */
  FemPredictor predictor; /* tangent of the first iteration of a substep */
  double reuse_rate; /* modified Newton: after a step with fresh factors the next direction
                      * reuses them, and keeps reusing while |R| falls by this factor per
                      * iteration (0, the default = full Newton: fresh factors every iteration) */
  FemMerit merit;    /* line-search merit */
  double armijo;     /* energy merit: sufficient decrease Pi(a) <= Pi(0) + armijo a Pi'(0) */
  int ls_memory;     /* energy merit: Pi(0) above is the largest potential of the last
                      * ls_memory accepted iterates (1 = monotone; > 1 non-monotone, Grippo,
                      * Lampariello and Lucidi 1986; at most 8) */
  FemIndefinite indefinite; /* not positive definite tangent: LU or modified Cholesky */
  int krylov_max;    /* > 0: a Newton direction is first sought by a Krylov method on the
                      * current tangent with the last factors as preconditioner, up to
                      * krylov_max iterations, before refactorising (0 = off): PCG on Cholesky
                      * factors of a symmetric tangent, GMRES otherwise (fem_gmres.h) */
  double krylov_rtol; /* Krylov stop: |K du + R| <= krylov_rtol |R| (inexact Newton) */
} FemSolverParams;

FemSolverParams fem_solver_params_default(void);

/* Why the last Newton substep stopped (as PETSc's SNESConvergedReason): > 0 converged,
 * < 0 diverged. fem_newton_reason_string gives the name. */
typedef enum {
  FEM_NEWTON_ITERATING = 0,
  FEM_CONVERGED_RESIDUAL = 1,      /* |R| <= rtol max(|f_int|, |f_ext|) + atol (and volume) */
  FEM_CONVERGED_UPDATE = 2,        /* |du| <= utol |u| (round-off floor of a stiff problem) */
  FEM_DIVERGED_MAX_ITER = -1,      /* max_iter factorisations (4 max_iter iterations) */
  FEM_DIVERGED_STALLED = -2,       /* |R| not halved in max_stall consecutive iterations */
  FEM_DIVERGED_GROWTH = -3,        /* |R| above 1e6 times its first value */
  FEM_DIVERGED_DOMAIN = -4,        /* inverted element / law or domain hook out of its domain
                                    * after the line search */
  FEM_DIVERGED_NAN = -5,           /* non-finite residual after the line search */
  FEM_DIVERGED_LINEAR_SOLVE = -6,  /* tangent singular for CHOLMOD and UMFPACK */
  FEM_DIVERGED_BORDERED = -7       /* volume control: dV/dp = 0 */
} FemNewtonReason;

const char *fem_newton_reason_string(FemNewtonReason r);

/* Outcome of the last solve()/step_dynamic(). */
typedef struct {
  FemNewtonReason newton_reason; /* of the last Newton substep (converged or the last failure) */
  int substeps;      /* converged substeps */
  int cuts;          /* failed substeps (retried with a smaller increment) */
  int newton_iters;  /* total Newton iterations incl. failed substeps */
  int lu_fallbacks;  /* factorisations done by UMFPACK instead of CHOLMOD */
  double lambda;     /* ramp parameter reached (1 = targets reached) */
  double last_dl;    /* last attempted increment */
  char reason[512];  /* converged: why; failed: diagnosis */
} FemSolveReport;

/* Solver statistics (accumulated since setup). */
typedef struct {
  int nnodes, nelem, ndof, nfree;
  long nnz_k;               /* entries of the (full) free-dof tangent */
  double nnz_l;             /* entries of the Cholesky factor */
  double t_assemble, t_factor, t_solve, t_symbolic; /* seconds */
  int n_assemble, n_factor, n_solve;                /* calls (assembly incl. residual-only) */
  int n_assemble_tangent;   /* Newton assemblies that built the tangent (a direction from
                             * reused factors needs none) */
  int n_chol, n_lu;
  int n_reuse;              /* Newton directions from reused factors (incl. REUSE predictors) */
  int n_interface;          /* elements scattered serially after the threaded slabs */
  double asymmetry;         /* max|K-K^T|/max|K| of the last tangent checked */
  int n_pattern_rebuilds;   /* pattern + analysis rebuilt because a contributor coupled a node
                             * pair outside it */
  int n_modified;           /* factorisations of a modified (load stiffness reduced) tangent */
  int n_not_pd;             /* CHOLMOD attempts that found a tangent not positive definite */
  int n_ls_energy;          /* backtracks on the energy merit */
  int n_indef_backtrack;    /* step-backs: the tangent at an iterate was indefinite (modify) */
  int n_krylov;             /* Newton directions from PCG on the last factors */
  int n_krylov_it;          /* PCG iterations (each a product with K and a factor solve) */
  int n_krylov_fail;        /* Krylov attempts abandoned (limit, negative curvature, too slow) */
  int n_gmres;              /* of the Krylov attempts, GMRES ones (unsymmetric tangent or LU
                             * factors; the others PCG) */
} FemSolverStats;

/* mesh [borrowed, must outlive the solver]; mats [in] one per mesh region (copied). */
int fem_solver_create(const FemMesh *mesh, const FemMaterial *mats, const FemSolverParams *prm,
                      FemSolver **out);
/* Fix the components in mask of every node of a surface / of nodes [in]. Before setup. */
int fem_solver_fix_surface(FemSolver *s, const char *surface, int mask);
int fem_solver_fix_nodes(FemSolver *s, int n, const int *nodes, int mask);
/* Follower pressure acts on this surface (may be called for several surfaces); its faces also
 * define the cavity volume. Before setup. */
int fem_solver_add_pressure_surface(FemSolver *s, const char *surface);
/* Gravity target g [in] 3 [m/s^2] (lumped-mass body force, ramped like the other loads). */
int fem_solver_set_gravity(FemSolver *s, const double g[3]);
/* Pattern, element colouring, CHOLMOD analysis, all work arrays. */
int fem_solver_setup(FemSolver *s);

/* Targets for the next solve. */
int fem_solver_set_control(FemSolver *s, FemControl control);
int fem_solver_set_pressure(FemSolver *s, double p);      /* [Pa], load control */
int fem_solver_set_volume(FemSolver *s, double volume);   /* [m^3], volume control */
/* Prescribed displacement of fixed component comp (0..2) of nodes [in]; the dof must have been
 * fixed before setup. */
int fem_solver_set_prescribed(FemSolver *s, int n, const int *nodes, int comp, double value);
/* External nodal forces f [in] 3n [N] on nodes [in] (dead loads); other nodes keep theirs.
 * No allocation: meant for the DEM coupling, called every coupling step. */
int fem_solver_set_nodal_forces(FemSolver *s, int n, const int *nodes, const double *f);
void fem_solver_clear_nodal_forces(FemSolver *s);
/* Time [s] a static solve stands for (e.g. the coupling interval; 0, the default: none). With
 * dt > 0 a successful fem_solver_solve ends with velocities (u - u_start) / dt, u_start the
 * state the solve began from, zero accelerations, and time advanced by dt; with 0 the
 * velocities after a static solve are zero (a state at rest). Each static substep of the
 * solve's load ramp stands for its share of dt (load increment x dt), which the laws see as
 * their time step (FemLawCtx.dt: a rate-dependent law such as Mohr-Coulomb with a relaxation
 * time relaxes over it; with 0 they see dt = 0, a rate-independent step). */
int fem_solver_set_static_interval(FemSolver *s, double dt);

/* Domain hook: called on every Newton trial state x [in] 3 * nnodes; a non-zero return (> 0)
 * marks it outside the model's domain, and the line search backtracks as for an inverted
 * element (FEM_DIVERGED_DOMAIN if it cannot). */
typedef int (*FemDomainCheck)(const FemSolver *s, const double *x, void *ctx);
void fem_solver_set_domain_check(FemSolver *s, FemDomainCheck fn, void *ctx);

/* Linear spring of stiffness k [N/m] between the displacements of nodes a and b (force
 * k (u_a - u_b) on a, the opposite on b); b = -1 ties a to its reference position (a weak
 * support for a floating body). Before setup the pair enters the pattern; after setup the
 * first tangent assembly rebuilds the pattern (FemSolverStats.n_pattern_rebuilds). */
int fem_solver_add_spring(FemSolver *s, int a, int b, double k);

/* Per-element data for the laws (e.g. a magnetisation vector): data [borrowed, must outlive the
 * solves] ndata values per element, handed to the law as FemLawCtx.elem_data (fem_law.h). */
int fem_solver_set_element_data(FemSolver *s, int ndata, const double *data);
/* Committed history of element e [borrowed]: fem_element_nqp * nhist values (quadrature point
 * q at q * nhist; e.g. the equivalent plastic strain of a plastic law), nhist [out]; NULL
 * before setup. */
const double *fem_solver_history(const FemSolver *s, int e, int *nhist);
/* The solver's copy of region r's material [borrowed]; NULL when r is out of range. */
const FemMaterial *fem_solver_material(const FemSolver *s, int r);
/* An initial state of element e: its history (committed and trial) becomes hist [in], laid out
 * as fem_solver_history returns it (e.g. a K0 stress of the Mohr-Coulomb fill, fem_fill.h).
 * After setup and before a solve; SA_ERR_INPUT when e is out of range or has no history. */
int fem_solver_set_history(FemSolver *s, int e, const double *hist);

/* Bodies (connected parts of the model, contributors' pairs included) with no fixed dof and
 * no ground spring, found in setup (a WARN names them; a singular tangent then says so). */
int fem_solver_floating_bodies(const FemSolver *s);

/* Monitor called after every converged substep (static) / step (dynamic); a non-zero return
 * stops the solve with that code. */
typedef int (*FemMonitor)(FemSolver *s, void *ctx);
void fem_solver_set_monitor(FemSolver *s, FemMonitor fn, void *ctx);

/* Quasi-static ramp from the committed state to the targets. Returns 0 when the targets were
 * reached; SA_ERR_LIMIT_POINT under load control when the increment fell below dl_min at a
 * limit point (diagnosis in the error message and the report); SA_ERR_STEP_TOO_SMALL for any
 * other repeated failure. The state is then the last converged substep. */
int fem_solver_solve(FemSolver *s);
/* Implicit dynamic step (HHT-alpha / Newmark, lumped mass) of length dt [s] to the targets
 * (load control only); substeps itself when Newton fails. */
int fem_solver_step_dynamic(FemSolver *s, double dt);
void fem_solver_report(const FemSolver *s, FemSolveReport *rep);
/* Ramp parameter (0..1) of the loads the current solve applied last: inside a contributor's
 * eval / commit, that of the state being assembled / accepted; 1 after a completed solve, 0
 * before the first. A contributor with a moving target (a rigid piston) interpolates between
 * its committed and target positions with it, so the solver's cut-backs cut its motion too. */
double fem_solver_load_factor(const FemSolver *s);

/* Read-back [borrowed; valid until the next solve]: 3 * nnodes each. */
const double *fem_solver_positions(const FemSolver *s);
const double *fem_solver_displacements(const FemSolver *s);
const double *fem_solver_velocities(const FemSolver *s);
double fem_solver_pressure(const FemSolver *s);
/* Cavity volume enclosed by the pressure surfaces (and planes through the origin) [m^3]. */
double fem_solver_cavity_volume(const FemSolver *s);
double fem_solver_time(const FemSolver *s);
/* Nodal forces the supports exert on the body at the converged state r [out] 3 * nnodes
 * (zero on free dofs up to the residual tolerance). */
int fem_solver_reactions(FemSolver *s, double *r);
/* Total external force of the current pressure on the solid F [out] 3. */
int fem_solver_pressure_resultant(FemSolver *s, double F[3]);
/* Nodal forces of the current pressure on the solid f [out] 3 * nnodes (the load the DEM
 * coupling replaces by contact forces). */
int fem_solver_pressure_forces(FemSolver *s, double *f);
/* max|K - K^T| / max|K| of the free-dof tangent at the current state (assembles; NaN if an
 * element is inverted). */
double fem_solver_tangent_asymmetry(FemSolver *s);
/* Element-averaged Cauchy stress sigma [out] 9*nelem, von Mises vm [out] nelem, principal
 * stretches lam [out] 3*nelem (any may be NULL). */
int fem_solver_element_stress(FemSolver *s, double *sigma, double *vm, double *lam);
void fem_solver_stats(const FemSolver *s, FemSolverStats *st);
/* Finite-difference check of the assembled tangent at the current state and pressure:
 * rel_err [out] = |K v - (R(u + h v) - R(u - h v)) / 2h| / |K v| for a fixed pseudo-random v
 * over the free dofs. Debugging and tests; allocates. */
int fem_solver_check_tangent(FemSolver *s, double h, double *rel_err);
/* Finite-difference check of the energy merit (FEM_MERIT_ENERGY) at the current positions
 * and pressure p [in]: rel_err [out] = |R.v - (Pi(u + h v) - Pi(u - h v)) / 2h| / |R.v|,
 * Pi = W(u) - p V(u) - f_dead.u, R the residual at pressure p, v a fixed pseudo-random
 * free-dof vector. Small only where p V is the pressure's potential (rim fixed). */
int fem_solver_check_potential(FemSolver *s, double p, double h, double *rel_err);
const FemMesh *fem_solver_mesh(const FemSolver *s);
/* Checkpoint (fem_checkpoint.c): the solver's state - displacements, HHT velocities and
 * accelerations, committed and target loads, time, history - to the binary stream f [in]
 * (opened by the caller, e.g. an atomic sa_file), and back into a solver set up from the same
 * case. Writing drops the factorisation, so the run that goes on and one resumed from the
 * file take the same next Newton path. Reading checks the model's size (SA_ERR_INPUT naming
 * name [in] on a mismatch or a truncated stream). */
int fem_solver_write_state(FemSolver *s, FILE *f);
int fem_solver_read_state(FemSolver *s, FILE *f, const char *name);
/* The same state in memory, for a step that is solved again from where it began (the
 * iterated FEM-DEM coupling step): fem_solver_snapshot stores it in *snap (allocated on the
 * first call, [owned], reused after), fem_solver_rollback puts it back. Unlike the checkpoint
 * the factors are kept (a rolled-back solve reuses them as its iteration matrix). */
typedef struct FemSnapshot FemSnapshot;
int fem_solver_snapshot(FemSolver *s, FemSnapshot **snap);
int fem_solver_rollback(FemSolver *s, const FemSnapshot *snap);
void fem_snapshot_destroy(FemSnapshot **snap);
void fem_solver_destroy(FemSolver **s);

/* Bending angle [deg] of a deformed surface: rotation in the x-z plane of the area-weighted
 * mean outward normal of surface `tip`, measured from its reference direction, positive toward
 * -x (docs/fem.md). x [in] current coordinates 3 * nnodes. */
int fem_bending_angle(const FemMesh *m, const char *tip, const double *x, double *deg);
/* Deformed centre-line: nslices slices of equal reference height between zmin and zmax; slice
 * centroid = reference-volume-weighted mean of the deformed centroids of the elements whose
 * reference centroid lies in the slice. z_ref [out] nslices, c [out] 3*nslices. */
int fem_centerline(const FemMesh *m, const double *x, double zmin, double zmax, int nslices,
                   double *z_ref, double *c);

#endif
