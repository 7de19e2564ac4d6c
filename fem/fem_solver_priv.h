/* fem_solver_priv.h - private to fem/: the FemSolver object, split where the phases split, and
 * the functions each phase's file exports to the others.
 *
 *   phase            fields      file                what it owns
 *   dof map/pattern  s->dm       fem_dofmap.c        dof numbering, node-pair graph (elements +
 *                                                    contributors' pairs), CSC pattern, slot
 *                                                    maps, thread partition, linear solver;
 *                                                    rebuilt when a new pair appears
 *   assembly         s->as       fem_assemble.c      bodies (element kernels), follower pressure,
 *                                                    dead loads + gravity, contributors (springs,
 *                                                    user/coupling/contact) -> f_int, q, V, K
 *   Newton           s->nw       fem_newton.c        one substep: predictor, reuse plan, line
 *                                                    search + domain hook, bordered volume
 *                                                    solve, convergence/divergence reasons
 *   continuation     s->ct       fem_continuation.c  load targets, ramp with adaptive substeps,
 *                                                    commit/restore, limit-point diagnosis
 *   dynamics         s->dy       fem_dynamics.c      HHT-alpha kinematics, inertia residual,
 *                                                    effective tangent, fem_solver_step_dynamic
 *   object/read-back (top)       fem_solver.c        create, BCs, setup, getters, destroy
 *
 * The state (u, x, p, V, time, history) is shared by all phases and lives at the top level. */
#ifndef FEM_SOLVER_PRIV_H
#define FEM_SOLVER_PRIV_H

#include <math.h>

#include "fem.h"
#include "fem_contrib.h"
#include "fem_linsolve.h"
#include "fem_gmres.h"

/* Target of one assembly: f_int, q (load per unit pressure), gv = dV/du, fcon (contributors'
 * residual) over all dofs, tangent values val (free-dof pattern; NULL when not wanted) and the
 * trial history hist. */
typedef struct {
  double *fint, *q, *gv, *fcon, *val, *hist;
  double V, energy, min_detF;
  int n_inv;    /* elements inverted (det F <= 0) */
  int n_domain; /* evaluations outside the model's domain (e.g. a failed return mapping) */
} AsmBuf;

typedef struct { /* fem_dofmap.c */
  int *fixmask; /* N: components fixed */
  int nfree, *eq, *colptr, *rowind, *diag;
  long nnz;
  int *adj_ptr, *adj, *slot9, *epair, *fpair;
  int ngroups, *group_ptr, *group_elem; /* threaded assembly groups (fem_dofmap_partition) */
  int npairs_extra, cap_extra, *extra;  /* node pairs (A, B) beyond the elements' */
  int n_rebuilds;                       /* pattern rebuilds after setup */
  int nfloating;                        /* bodies held by nothing (fem_dofmap.c) */
  char floating_msg[400];
  FemLinSolver *lin;                    /* borrows the pattern: recreated with it */
} FemDofMap;

typedef struct { /* fem_assemble.c */
  int npf, nfn; /* pressure faces */
  int *pf;      /* nfn * npf node indices */
  int *hoff;    /* per element: offset of its history (nqp * nhist) */
  double *hist_c, *hist_t; /* committed and trial history per quadrature point */
  double *fint, *q, *gv, *fcon, *fdead, *val; /* Newton's assembly target and dead loads */
  double *mlump;
  double energy, min_detF;
  int n_inverted, n_domain;
  AsmBuf rb; /* read-back assembly (getters), val allocated on demand */
  int ncontrib, cap_contrib;
  FemContributor *contrib; /* [owned copies of the descriptors] */
  int need_rebuild;        /* a contributor asked for a pair outside the pattern */
  int *missing;            /* those pairs (2 per pair) */
  int nmissing, cap_missing;
  double t_eval, dt_eval;    /* time and time step of the state being assembled (laws) */
  const double *edata;       /* per-element law data [borrowed], nedata per element */
  int nedata;
  int nsprings, cap_springs; /* built-in spring contributor */
  int *spring_nodes;         /* 2 per spring */
  double *spring_k;
} FemAssembly;

typedef struct { /* fem_newton.c */
  double *R, *da, *db, *du, *rhs, *qf, *gf; /* nfree */
  double *kr, *kz, *kp, *kq;                /* PCG work (nfree) */
  FemGmres gm;    /* GMRES work (krylov_max > 0): directions of an unsymmetric tangent */
  double *u_it;                             /* last accepted Newton iterate (ndof) */
  double p_it;
  int last_sym;   /* symmetric path used at the last factorisation */
  int laws_unsym; /* a region's law declares an unsymmetric tangent (fem_material_symmetric):
                   * UMFPACK LU directly, no CHOLMOD attempt and no asymmetry measurement */
  int saw_not_pd; /* a factorisation in the current substep was not positive definite (the
                   * fallback is logged once per substep; CHOLMOD is still tried every time) */
  int lu_substep; /* LU factorisations in the current substep */
  int extrapolated; /* the substep starts from an extrapolated state (FEM_PREDICT_EXTRAPOLATE) */
  /* the factors held by lin are a tangent of the last converged state (its last Newton
   * iteration), made for a substep of kind (fact_dynamic, fact_dt, fact_alpha): usable as
   * the next predictor (FEM_PREDICT_REUSE) */
  int fact_converged;
  int have_factors; /* lin holds factors (cleared when a pattern rebuild recreates it) */
  int indef_step;   /* the last factorize() found the tangent at this iterate indefinite
                     * (indefinite = modify): the caller may step back */
  int fact_dynamic;
  double fact_dt, fact_alpha;
  FemNewtonReason reason; /* of the last substep */
  FemDomainCheck domain_check;
  void *domain_ctx;
} FemNewton;

typedef struct { /* fem_continuation.c */
  FemControl control;
  double p_c, p_t, V_c, V_t, g_c[3], g_t[3]; /* committed (ramp start) and target loads */
  double *fn_c, *fn_t, *up_c, *up_t;
  double V_goal, V_last, V_prev, p_last, p_prev;
  double lam_total;  /* ramp parameters completed since creation */
  double lam_eval;   /* ramp parameter of the loads last applied (the state being assembled;
                      * 1 after a completed solve): contributors' moving targets follow it */
  int step_count;    /* substeps attempted since creation (log numbering) */
  double dl_keep;    /* increment carried over to the next ramp */
  double slope0;     /* first measured dp/dV (stiffness reference) */
  int fail_not_pd;   /* not positive definite seen since last convergence */
  int n_static_commits; /* static pressure-only substeps committed in a row (extrapolation) */
  char last_fail[200];
  double static_dt;  /* time a static solve stands for (0: none, velocities 0) */
  FemSolveReport rep;
  FemMonitor mon;
  void *mon_ctx;
} FemContinuation;

typedef struct { /* fem_dynamics.c */
  double *v, *acc, *v_last, *a_last; /* current and last converged */
  double *res_n;                     /* r(u_n, t_n) = f_int - f_ext at the last step */
} FemDynamics;

/* One substep's kind: static, or HHT/Newmark with these constants. */
typedef struct {
  int dynamic;
  double dt, beta, gamma, alpha;
  double law_dt; /* static substep: the time it stands for (its load increment times the solve's
                    static interval), which rate-dependent laws see as their time step */
} StepKind;

struct FemSolver {
  const FemMesh *m;
  FemMaterial *mats;
  FemSolverParams prm;
  int N, ndof, nen, nqp;
  int setup_done;
  /* state shared by the phases */
  double *u, *x;       /* current displacement and position */
  double *u_last;      /* last converged substep */
  double *u_prev;      /* the converged substep before it (extrapolating predictor) */
  double *u_start;     /* committed state when the last solve began */
  double p, V, V_ref, time;
  FemSolverStats st;

  FemDofMap dm;
  FemAssembly as;
  FemNewton nw;
  FemContinuation ct;
  FemDynamics dy;
};

static inline double fem_nrm2(const double *a, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += a[i] * a[i];
  return sqrt(s);
}

static inline double fem_dot(const double *a, const double *b, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

static inline void fem_set_x(FemSolver *s) {
  for (int d = 0; d < s->ndof; d++) s->x[d] = s->m->xyz[d] + s->u[d];
}

/* fem_dofmap.c */
int fem_dofmap_build(FemSolver *s);   /* numbering, graph, pattern, pair maps (setup) */
int fem_dofmap_partition(FemSolver *s);
int fem_dofmap_rebuild(FemSolver *s, int npairs, const int *pairs); /* add pairs, new analysis */
int fem_dofmap_find_pair(const FemSolver *s, int A, int B);         /* graph index or -1 */
void fem_dofmap_free(FemDofMap *dm);

/* fem_assemble.c */
int fem_asm_setup(FemSolver *s);
int fem_asm_into(FemSolver *s, AsmBuf *bf, const double *x, double p, int want_K);
int fem_asm_newton(FemSolver *s, const double *x, double p, int want_K);
int fem_asm_readback(FemSolver *s, int want_K);
void fem_asm_add_load_stiffness(FemSolver *s, const double *x, double scale);
int fem_asm_candidate_pairs(FemSolver *s, int **pairs, int *npairs); /* [owned] */
void fem_asm_free(FemAssembly *as);

/* fem_newton.c */
int fem_newton_substep(FemSolver *s, const StepKind *sk, int step, int *iters);
int fem_newton_alloc(FemSolver *s);
void fem_newton_free(FemNewton *nw);

/* fem_continuation.c */
int fem_cont_ramp(FemSolver *s, int dynamic, double dt_total);
void fem_cont_apply_loads(FemSolver *s, double lam);
void fem_cont_free(FemContinuation *ct);

/* fem_dynamics.c */
StepKind fem_dyn_step_kind(const FemSolver *s, double dt);
void fem_dyn_kinematics(FemSolver *s, const StepKind *sk);
double fem_dyn_residual(FemSolver *s, const StepKind *sk, double *fref);
void fem_dyn_effective_tangent(FemSolver *s, const StepKind *sk);
void fem_dyn_rest(FemSolver *s);
void fem_dyn_commit(FemSolver *s);
void fem_dyn_restore(FemSolver *s);
void fem_dyn_free(FemDynamics *dy);

#endif
