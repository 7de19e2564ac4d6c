/* fem_solver.c - nonlinear total-Lagrangian solver: sparsity pattern with an element->slot
 * scatter map, coloured parallel assembly, Newton-Raphson with lazy backtracking line search,
 * adaptive load stepping, load or volume control (bordered system by two back-substitutions),
 * implicit HHT-alpha dynamics, and the limit-point diagnosis. Formulation: docs/fem.md.
 *
 * Residual (free dofs):  R(u, p) = f_int(u) - f_dead - p q(u)
 *   f_int  = dPi/du from the element kernels (mean-dilatation mixed element)
 *   q(u)   = -int N n da over the pressure faces (follower load per unit pressure)
 *   f_dead = nodal forces + lumped gravity
 * Tangent: K = K_int + p K_q, K_q = -dq/du (fem_face_pressure's load stiffness at p = 1).
 * Volume control adds c(u) = V(u) - V_target = 0 with p unknown:
 *   K a = -R,  K b = q,  dp = -(c + g.a) / (g.b),  du = a + dp b,   g = dV/du. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_element.h"
#include "fem_linsolve.h"
#include "sa_error.h"
#include "sa_log.h"

/* fem_mesh_check tolerance: det J / 6 <= this times the mean element volume is rejected. */
#define FEM_SOLVER_MESH_TOL 1e-10

/* Target of one assembly: f_int, q (load per unit pressure), gv = dV/du (all dofs), tangent
 * values val (free-dof pattern; NULL when not wanted) and trial history hist. */
typedef struct {
  double *fint, *q, *gv, *val, *hist;
  double V, energy, min_detF;
  int n_inv;
} AsmBuf;

struct FemSolver {
  const FemMesh *m;
  FemMaterial *mats;
  FemSolverParams prm;
  int N, ndof, nen, nqp;
  int *fixmask;       /* N: components fixed */
  int npf, nfn;       /* pressure faces */
  int *pf;            /* nfn * npf node indices */
  int setup_done;

  /* pattern */
  int nfree, *eq, *colptr, *rowind, *diag;
  long nnz;
  double *val;
  int *adj_ptr, *adj, *slot9, *epair, *fpair;
  int ngroups, *group_ptr, *group_elem; /* threaded assembly groups (see build_partition) */
  FemLinSolver *lin;

  /* history per quadrature point: committed and trial */
  int *hoff;
  double *hist_c, *hist_t;

  /* state */
  double *u, *x, *v, *acc;       /* current */
  double *u_last, *v_last, *a_last; /* last converged substep */
  double *u_start;                   /* committed state when the last solve began */
  double p, p_last, p_prev, V, V_ref;
  double time;

  /* loads: committed (ramp start) and target */
  FemControl control;
  double p_c, p_t, V_c, V_t, g_c[3], g_t[3];
  double *fn_c, *fn_t, *up_c, *up_t, *mlump;

  /* work */
  double *fint, *q, *gv, *fdead, *res_n; /* ndof */
  double *R, *da, *db, *du, *rhs, *qf, *gf; /* nfree */
  double *u_it;                          /* last accepted Newton iterate (ndof) */
  double p_it, V_goal, V_last, V_prev;
  double lam_total;                      /* ramp parameters completed since creation */
  int step_count;                        /* substeps attempted since creation (log numbering) */
  double dl_keep;                        /* increment carried over to the next ramp */
  double slope0;                         /* first measured dp/dV (stiffness reference) */
  int fail_not_pd;                       /* not positive definite seen since last convergence */
  char last_fail[200];
  double energy, min_detF;
  int n_inverted;

  AsmBuf rb;        /* read-back assembly (getters), val allocated on demand */
  double static_dt; /* time a static solve stands for (0: none, velocities 0) */

  FemMonitor mon;
  void *mon_ctx;
  FemSolveReport rep;
  FemSolverStats st;
  int last_sym;   /* symmetric path used at the last factorisation */
  int saw_not_pd; /* a factorisation in the current substep was not positive definite (the
                   * fallback is logged once per substep; CHOLMOD is still tried every time) */
  int lu_substep; /* LU factorisations in the current substep */
  /* the factors held by lin are a tangent of the last converged state (its last Newton
   * iteration), made for a substep of kind (fact_dynamic, fact_dt, fact_alpha): usable as
   * the next predictor (FEM_PREDICT_REUSE) */
  int fact_converged;
  int fact_dynamic;
  double fact_dt, fact_alpha;
};

FemSolverParams fem_solver_params_default(void) {
  FemSolverParams p = {
      .rtol = 1e-8, .atol = 1e-14, .utol = 1e-11, .vtol = 1e-10, .max_iter = 25, .line_search = 1,
      .dl_init = 1.0, .dl_min = 1e-4, .dl_max = 1.0, .easy_iter = 5, .grow = 1.5, .cut = 0.5,
      .threads = 2, .linsolver = FEM_LINSOLVER_AUTO, .sym_tol = 1e-9, .hht_alpha = -0.05,
      .mass_damping = 0.0, .ls_growth = 1e3, .max_stall = 6,
      .predictor = FEM_PREDICT_NEW_LOAD, .reuse_rate = 0.0};
  return p;
}

/* ------------------------------------------------------------------ create / BCs */

int fem_solver_create(const FemMesh *mesh, const FemMaterial *mats, const FemSolverParams *prm,
                      FemSolver **out) {
  *out = NULL;
  SA_REQUIRE(mesh && mesh->nnodes > 0 && mesh->nelem > 0, SA_ERR_INPUT, "empty mesh");
  SA_REQUIRE(mats, SA_ERR_INPUT, "no materials");
  if (prm) {
    SA_REQUIRE(prm->predictor >= FEM_PREDICT_NEW_LOAD && prm->predictor <= FEM_PREDICT_REUSE,
               SA_ERR_INPUT, "predictor %d is not one of 0 (new_load), 1 (equilibrium), 2 (reuse)",
               (int)prm->predictor);
    SA_REQUIRE(prm->reuse_rate >= 0 && prm->reuse_rate < 1, SA_ERR_INPUT,
               "reuse_rate %g not in [0, 1)", prm->reuse_rate);
  }
  FemSolver *s;
  SA_CALLOC(s, 1);
  s->m = mesh;
  s->prm = prm ? *prm : fem_solver_params_default();
  if (s->prm.threads < 1) s->prm.threads = 1;
  s->N = mesh->nnodes;
  s->ndof = 3 * mesh->nnodes;
  s->nen = mesh->nen;
  s->nqp = fem_element_nqp(mesh->etype);
  int nreg = mesh->nregions > 0 ? mesh->nregions : 1;
  s->mats = malloc((size_t)nreg * sizeof *s->mats);
  s->fixmask = calloc((size_t)s->N, sizeof *s->fixmask);
  if (!s->mats || !s->fixmask) {
    fem_solver_destroy(&s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate solver");
  }
  memcpy(s->mats, mats, (size_t)nreg * sizeof *s->mats);
  s->nfn = mesh->etype == FEM_TET10 ? 6 : 3;
  /* nodal-force targets exist from creation: set_nodal_forces may come before setup */
  s->fn_c = calloc((size_t)s->ndof, sizeof *s->fn_c);
  s->fn_t = calloc((size_t)s->ndof, sizeof *s->fn_t);
  if (!s->fn_c || !s->fn_t) {
    fem_solver_destroy(&s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate solver");
  }
  /* validators run on every model, not only in tests */
  int rc = fem_mesh_check(mesh, FEM_SOLVER_MESH_TOL);
  for (int r = 0; r < nreg && rc == 0; r++)
    if (fem_material_check(&s->mats[r])) {
      char msg[256];
      snprintf(msg, sizeof msg, "%s", sa_error_message());
      rc = SA_ERROR(SA_ERR_INPUT, "region %d (%s): %s", r,
                    mesh->region_names && r < mesh->nregions ? mesh->region_names[r] : "-", msg);
    }
  if (rc) {
    fem_solver_destroy(&s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

int fem_solver_fix_nodes(FemSolver *s, int n, const int *nodes, int mask) {
  SA_REQUIRE(!s->setup_done, SA_ERR_INPUT, "boundary conditions must be set before setup");
  for (int k = 0; k < n; k++) {
    SA_REQUIRE(nodes[k] >= 0 && nodes[k] < s->N, SA_ERR_INPUT, "node %d out of range", nodes[k]);
    s->fixmask[nodes[k]] |= mask & FEM_XYZ;
  }
  return 0;
}

int fem_solver_fix_surface(FemSolver *s, const char *surface, int mask) {
  const FemSurface *f = fem_mesh_find_surface(s->m, surface);
  SA_REQUIRE(f, SA_ERR_INPUT, "mesh has no surface '%s'", surface);
  SA_CHECK(fem_solver_fix_nodes(s, f->nnodes, f->nodes, mask));
  return 0;
}

int fem_solver_add_pressure_surface(FemSolver *s, const char *surface) {
  SA_REQUIRE(!s->setup_done, SA_ERR_INPUT, "pressure surfaces must be set before setup");
  const FemSurface *f = fem_mesh_find_surface(s->m, surface);
  SA_REQUIRE(f, SA_ERR_INPUT, "mesh has no surface '%s'", surface);
  SA_REQUIRE(f->nfn == s->nfn, SA_ERR_INPUT, "surface '%s' has %d-node faces, expected %d",
             surface, f->nfn, s->nfn);
  int *pf = realloc(s->pf, (size_t)(s->npf + f->nfaces) * s->nfn * sizeof *pf);
  SA_REQUIRE(pf, SA_ERR_MEMORY, "cannot grow pressure face list");
  memcpy(pf + (size_t)s->npf * s->nfn, f->faces, (size_t)f->nfaces * s->nfn * sizeof *pf);
  s->pf = pf;
  s->npf += f->nfaces;
  return 0;
}

int fem_solver_set_gravity(FemSolver *s, const double g[3]) {
  for (int c = 0; c < 3; c++) s->g_t[c] = g[c];
  return 0;
}

/* ------------------------------------------------------------------ setup */

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

static int find_sorted(const int *a, int lo, int hi, int key) { /* [lo, hi) */
  hi--;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (a[mid] < key) lo = mid + 1;
    else if (a[mid] > key) hi = mid - 1;
    else return mid;
  }
  return -1;
}

/* Node graph (column-wise adjacency incl. self, sorted) from element connectivity. */
static int build_node_graph(FemSolver *s) {
  const FemMesh *m = s->m;
  int N = s->N, nen = s->nen, ne = m->nelem;
  int *n2e_ptr, *n2e, *mark, *cnt;
  SA_CALLOC(n2e_ptr, N + 1);
  SA_CALLOC(n2e, (size_t)ne * nen);
  SA_CALLOC(mark, N);
  SA_CALLOC(cnt, N);
  for (int e = 0; e < ne; e++)
    for (int a = 0; a < nen; a++) n2e_ptr[m->conn[(size_t)e * nen + a] + 1]++;
  for (int i = 0; i < N; i++) n2e_ptr[i + 1] += n2e_ptr[i];
  for (int e = 0; e < ne; e++)
    for (int a = 0; a < nen; a++) {
      int A = m->conn[(size_t)e * nen + a];
      n2e[n2e_ptr[A] + cnt[A]++] = e;
    }
  for (int i = 0; i < N; i++) mark[i] = -1;
  /* two passes: count, then fill */
  SA_CALLOC(s->adj_ptr, N + 1);
  for (int pass = 0; pass < 2; pass++) {
    for (int i = 0; i < N; i++) mark[i] = -1;
    for (int B = 0; B < N; B++) {
      int k = 0;
      for (int t = n2e_ptr[B]; t < n2e_ptr[B + 1]; t++) {
        const int *c = m->conn + (size_t)n2e[t] * nen;
        for (int a = 0; a < nen; a++)
          if (mark[c[a]] != B) {
            mark[c[a]] = B;
            if (pass) s->adj[s->adj_ptr[B] + k] = c[a];
            k++;
          }
      }
      if (!pass) s->adj_ptr[B + 1] = k;
      else qsort(s->adj + s->adj_ptr[B], (size_t)k, sizeof(int), cmp_int);
    }
    if (!pass) {
      for (int i = 0; i < N; i++) s->adj_ptr[i + 1] += s->adj_ptr[i];
      SA_CALLOC(s->adj, s->adj_ptr[N]);
    }
  }
  free(n2e_ptr);
  free(n2e);
  free(mark);
  free(cnt);
  return 0;
}

/* Free-dof CSC pattern (full, sorted) + slot map per node pair (9 entries, -1 = constrained). */
static int build_pattern(FemSolver *s) {
  int N = s->N;
  SA_CALLOC(s->eq, s->ndof);
  int nf = 0;
  for (int A = 0; A < N; A++)
    for (int c = 0; c < 3; c++) s->eq[3 * A + c] = (s->fixmask[A] >> c & 1) ? -1 : nf++;
  s->nfree = nf;
  SA_REQUIRE(nf > 0, SA_ERR_INPUT, "every degree of freedom is fixed");
  SA_CALLOC(s->colptr, nf + 1);
  SA_CALLOC(s->diag, nf);
  long npairs = s->adj_ptr[N];
  SA_CALLOC(s->slot9, (size_t)npairs * 9);
  for (long k = 0; k < npairs * 9; k++) s->slot9[k] = -1;
  long nnz = 0;
  for (int B = 0; B < N; B++)
    for (int j = 0; j < 3; j++) {
      if (s->eq[3 * B + j] < 0) continue;
      for (int t = s->adj_ptr[B]; t < s->adj_ptr[B + 1]; t++) {
        int A = s->adj[t];
        for (int i = 0; i < 3; i++)
          if (s->eq[3 * A + i] >= 0) nnz++;
      }
    }
  SA_REQUIRE(nnz < 2147483647L, SA_ERR_INPUT, "tangent too large for 32-bit indices");
  s->nnz = nnz;
  SA_CALLOC(s->rowind, nnz);
  SA_CALLOC(s->val, nnz);
  long k = 0;
  for (int B = 0; B < N; B++)
    for (int j = 0; j < 3; j++) {
      int col = s->eq[3 * B + j];
      if (col < 0) continue;
      s->colptr[col] = (int)k;
      for (int t = s->adj_ptr[B]; t < s->adj_ptr[B + 1]; t++) {
        int A = s->adj[t];
        for (int i = 0; i < 3; i++) {
          int row = s->eq[3 * A + i];
          if (row < 0) continue;
          if (row == col) s->diag[col] = (int)k;
          s->slot9[(size_t)t * 9 + 3 * i + j] = (int)k;
          s->rowind[k++] = row;
        }
      }
    }
  s->colptr[nf] = (int)k;
  return 0;
}

/* Pair index (row node A, column node B) of every element / face node pair. */
static int build_pair_maps(FemSolver *s) {
  const FemMesh *m = s->m;
  int nen = s->nen;
  SA_CALLOC(s->epair, (size_t)m->nelem * nen * nen);
  for (int e = 0; e < m->nelem; e++) {
    const int *c = m->conn + (size_t)e * nen;
    for (int a = 0; a < nen; a++)
      for (int b = 0; b < nen; b++) {
        int t = find_sorted(s->adj, s->adj_ptr[c[b]], s->adj_ptr[c[b] + 1], c[a]);
        SA_REQUIRE(t >= 0, SA_ERR_INTERNAL, "node pair missing from the graph");
        s->epair[((size_t)e * nen + a) * nen + b] = t;
      }
  }
  int nfn = s->nfn;
  SA_CALLOC(s->fpair, (size_t)s->npf * nfn * nfn);
  for (int f = 0; f < s->npf; f++) {
    const int *c = s->pf + (size_t)f * nfn;
    for (int a = 0; a < nfn; a++)
      for (int b = 0; b < nfn; b++) {
        int t = find_sorted(s->adj, s->adj_ptr[c[b]], s->adj_ptr[c[b] + 1], c[a]);
        SA_REQUIRE(t >= 0, SA_ERR_INPUT, "pressure face node pair not in one element");
        s->fpair[((size_t)f * nfn + a) * nfn + b] = t;
      }
  }
  return 0;
}

/* Element partition for the threaded assembly: elements sorted by the centroid coordinate along
 * the mesh's longest axis, cut into `threads` slabs of equal count; an element all of whose
 * nodes belong to its own slab only goes to that slab's group (groups 0..T-1 are scattered
 * concurrently without conflicts), the rest (a few layers at the cuts) to group T, scattered
 * serially afterwards. One fork/join per assembly: a per-colour barrier (graph colouring) costs
 * a scheduler time slice each on an oversubscribed machine, which we measured to dominate. */
typedef struct {
  double key;
  int e;
} ElemKey;

static int cmp_ekey(const void *a, const void *b) {
  double x = ((const ElemKey *)a)->key, y = ((const ElemKey *)b)->key;
  return (x > y) - (x < y);
}

static int build_partition(FemSolver *s) {
  const FemMesh *m = s->m;
  int nen = s->nen, ne = m->nelem, T = s->prm.threads;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < s->N; i++)
    for (int k = 0; k < 3; k++) {
      lo[k] = fmin(lo[k], m->xyz[3 * i + k]);
      hi[k] = fmax(hi[k], m->xyz[3 * i + k]);
    }
  int ax = 0;
  for (int k = 1; k < 3; k++)
    if (hi[k] - lo[k] > hi[ax] - lo[ax]) ax = k;
  ElemKey *ek;
  int *owner, *grp;
  SA_CALLOC(ek, ne);
  SA_CALLOC(owner, s->N);
  SA_CALLOC(grp, ne);
  for (int e = 0; e < ne; e++) {
    const int *c = m->conn + (size_t)e * nen;
    ek[e].e = e;
    for (int a = 0; a < 4; a++) ek[e].key += 0.25 * m->xyz[3 * c[a] + ax];
  }
  qsort(ek, (size_t)ne, sizeof *ek, cmp_ekey);
  for (int i = 0; i < s->N; i++) owner[i] = -1;
  for (int t = 0; t < ne; t++) {
    int e = ek[t].e, slab = (int)((long)t * T / ne);
    grp[e] = slab;
    const int *c = m->conn + (size_t)e * nen;
    for (int a = 0; a < nen; a++) {
      if (owner[c[a]] == -1) owner[c[a]] = slab;
      else if (owner[c[a]] != slab) owner[c[a]] = -2;
    }
  }
  for (int e = 0; e < ne; e++) {
    const int *c = m->conn + (size_t)e * nen;
    for (int a = 0; a < nen; a++)
      if (owner[c[a]] != grp[e]) grp[e] = T;
  }
  s->ngroups = T + 1;
  SA_CALLOC(s->group_ptr, T + 2);
  SA_CALLOC(s->group_elem, ne);
  for (int e = 0; e < ne; e++) s->group_ptr[grp[e] + 1]++;
  for (int k = 0; k <= T; k++) s->group_ptr[k + 1] += s->group_ptr[k];
  int *fill;
  SA_CALLOC(fill, T + 1);
  for (int e = 0; e < ne; e++) s->group_elem[s->group_ptr[grp[e]] + fill[grp[e]]++] = e;
  free(fill);
  free(ek);
  free(owner);
  free(grp);
  return 0;
}

int fem_solver_setup(FemSolver *s) {
  SA_REQUIRE(!s->setup_done, SA_ERR_INPUT, "fem_solver_setup called twice");
  const FemMesh *m = s->m;
  double t0 = sa_time_now();
  SA_CHECK(build_node_graph(s));
  SA_CHECK(build_pattern(s));
  SA_CHECK(build_pair_maps(s));
  SA_CHECK(build_partition(s));

  int ne = m->nelem, nd = s->ndof, nf = s->nfree;
  SA_CALLOC(s->hoff, ne + 1);
  for (int e = 0; e < ne; e++) {
    int r = m->region ? m->region[e] : 0;
    s->hoff[e + 1] = s->hoff[e] + s->nqp * s->mats[r].nhist;
  }
  SA_CALLOC(s->hist_c, s->hoff[ne]);
  SA_CALLOC(s->hist_t, s->hoff[ne]);
  SA_CALLOC(s->rb.hist, s->hoff[ne]);
  SA_CALLOC(s->rb.fint, nd);
  SA_CALLOC(s->rb.q, nd);
  SA_CALLOC(s->rb.gv, nd);

  double **vecs[] = {&s->u, &s->x, &s->v, &s->acc, &s->u_last, &s->v_last, &s->a_last,
                     &s->u_start, &s->up_c, &s->up_t, &s->fint, &s->q,
                     &s->gv, &s->fdead, &s->res_n, &s->u_it};
  for (size_t i = 0; i < sizeof vecs / sizeof *vecs; i++) SA_CALLOC(*vecs[i], nd);
  double **fvecs[] = {&s->R, &s->da, &s->db, &s->du, &s->rhs, &s->qf, &s->gf};
  for (size_t i = 0; i < sizeof fvecs / sizeof *fvecs; i++) SA_CALLOC(*fvecs[i], nf);
  SA_CALLOC(s->mlump, s->N);
  memcpy(s->x, m->xyz, (size_t)nd * sizeof *s->x);

  /* lumped mass (gravity, dynamics) */
  double X[30], mm[10];
  for (int e = 0; e < ne; e++) {
    const int *c = m->conn + (size_t)e * s->nen;
    for (int a = 0; a < s->nen; a++)
      for (int k = 0; k < 3; k++) X[3 * a + k] = m->xyz[3 * c[a] + k];
    int r = m->region ? m->region[e] : 0;
    fem_element_lumped_mass(m->etype, X, s->mats[r].rho, mm);
    for (int a = 0; a < s->nen; a++) s->mlump[c[a]] += mm[a];
  }

  SA_CHECK(fem_linsolve_create(nf, s->colptr, s->rowind, s->prm.threads, &s->lin));
  FemLinInfo li;
  fem_linsolve_info(s->lin, &li);
  s->st.nnodes = s->N;
  s->st.nelem = ne;
  s->st.ndof = nd;
  s->st.nfree = nf;
  s->st.nnz_k = s->nnz;
  s->st.nnz_l = li.nnz_l;
  s->st.t_symbolic = sa_time_now() - t0;
  s->st.n_interface = s->group_ptr[s->ngroups] - s->group_ptr[s->ngroups - 1];
  s->setup_done = 1;

  /* reference cavity volume */
  s->V_ref = 0.0;
  for (int f = 0; f < s->npf; f++) {
    double xf[18];
    const int *c = s->pf + (size_t)f * s->nfn;
    for (int a = 0; a < s->nfn; a++)
      for (int k = 0; k < 3; k++) xf[3 * a + k] = m->xyz[3 * c[a] + k];
    s->V_ref += fem_face_volume(s->nfn, xf, NULL, NULL);
  }
  s->V = s->V_c = s->V_t = s->V_last = s->V_prev = s->V_goal = s->V_ref;
  sa_log(SA_LOG_INFO, "fem",
         "setup: %d nodes, %d %s elements, %d free dofs, nnz(K) %ld, nnz(L) %.3g (fill %.1f), "
         "%d threads (%d interface elements), %d pressure faces, V0 = %.6g m^3, symbolic %.3f s",
         s->N, ne, m->etype == FEM_TET10 ? "tet10" : "tet4", nf, s->nnz, li.nnz_l,
         li.nnz_l / (0.5 * (s->nnz + nf)), s->prm.threads, s->st.n_interface, s->npf, s->V_ref, s->st.t_symbolic);
  return 0;
}

/* ------------------------------------------------------------------ assembly */

/* Kernel and scatter of one element (f_int and, if want_K, the tangent slots). */
static void elem_work(FemSolver *s, AsmBuf *bf, int e, const double *x, int want_K,
                      double *energy, double *min_detF, int *n_inv) {
  const FemMesh *m = s->m;
  int nen = s->nen, nd = 3 * nen;
  const int *c = m->conn + (size_t)e * nen;
  double X[30], xe[30];
  FemElemOut out;
  for (int a = 0; a < nen; a++)
    for (int k = 0; k < 3; k++) {
      X[3 * a + k] = m->xyz[3 * c[a] + k];
      xe[3 * a + k] = x[3 * c[a] + k];
    }
  int r = m->region ? m->region[e] : 0;
  int rc = fem_element_tl(m->etype, X, xe, &s->mats[r], s->hist_c + s->hoff[e],
                          bf->hist + s->hoff[e], want_K, &out);
  if (rc != 0 || !isfinite(out.energy)) {
    (*n_inv)++;
    return;
  }
  *energy += out.energy;
  if (out.min_detF < *min_detF) *min_detF = out.min_detF;
  for (int a = 0; a < nen; a++)
    for (int k = 0; k < 3; k++) bf->fint[3 * c[a] + k] += out.fe[3 * a + k];
  if (!want_K) return;
  const int *ep = s->epair + (size_t)e * nen * nen;
  for (int a = 0; a < nen; a++)
    for (int b = 0; b < nen; b++) {
      const int *sl = s->slot9 + (size_t)ep[a * nen + b] * 9;
      const double *Kab = out.Ke + (size_t)(3 * a) * nd + 3 * b;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          int k = sl[3 * i + j];
          if (k >= 0) bf->val[k] += Kab[i * nd + j];
        }
    }
}

/* f_int, q, V, g (all dofs) and, if want_K, the tangent values over the free dofs at x with
 * pressure p. Returns SA_ERR_INVERTED if an element inverted (state otherwise undefined). */
static int assemble_into(FemSolver *s, AsmBuf *bf, const double *x, double p, int want_K) {
  double t0 = sa_time_now();
  memset(bf->fint, 0, (size_t)s->ndof * sizeof *bf->fint);
  if (want_K) memset(bf->val, 0, (size_t)s->nnz * sizeof *bf->val);
  double energy = 0.0, min_detF = INFINITY;
  int n_inv = 0, T = s->prm.threads;
  /* slabs 0..T-1 share no node: one thread each; then the interface group serially */
#pragma omp parallel for num_threads(T) schedule(static, 1) reduction(+ : energy, n_inv) \
    reduction(min : min_detF)
  for (int g = 0; g < T; g++)
    for (int k = s->group_ptr[g]; k < s->group_ptr[g + 1]; k++)
      elem_work(s, bf, s->group_elem[k], x, want_K, &energy, &min_detF, &n_inv);
  for (int k = s->group_ptr[T]; k < s->group_ptr[T + 1]; k++)
    elem_work(s, bf, s->group_elem[k], x, want_K, &energy, &min_detF, &n_inv);
  if (n_inv) sa_error_clear();
  bf->energy = energy;
  bf->min_detF = min_detF;
  bf->n_inv = n_inv;

  /* pressure faces: load per unit pressure q, its stiffness, enclosed volume and gradient */
  memset(bf->q, 0, (size_t)s->ndof * sizeof *bf->q);
  memset(bf->gv, 0, (size_t)s->ndof * sizeof *bf->gv);
  double V = 0.0;
  int nfn = s->nfn, nfd = 3 * nfn;
  for (int f = 0; f < s->npf; f++) {
    const int *c = s->pf + (size_t)f * nfn;
    double xf[18], fe[18], Ke[324], dv[18];
    for (int a = 0; a < nfn; a++)
      for (int k = 0; k < 3; k++) xf[3 * a + k] = x[3 * c[a] + k];
    fem_face_pressure(nfn, xf, 1.0, fe, want_K ? Ke : NULL);
    V += fem_face_volume(nfn, xf, dv, NULL);
    for (int a = 0; a < nfn; a++)
      for (int k = 0; k < 3; k++) {
        bf->q[3 * c[a] + k] += fe[3 * a + k];
        bf->gv[3 * c[a] + k] += dv[3 * a + k];
      }
    if (!want_K || p == 0.0) continue;
    const int *fp = s->fpair + (size_t)f * nfn * nfn;
    for (int a = 0; a < nfn; a++)
      for (int b = 0; b < nfn; b++) {
        const int *sl = s->slot9 + (size_t)fp[a * nfn + b] * 9;
        const double *Kab = Ke + (size_t)(3 * a) * nfd + 3 * b;
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) {
            int k = sl[3 * i + j];
            if (k >= 0) bf->val[k] += p * Kab[i * nfd + j];
          }
      }
  }
  bf->V = V;
  double dt = sa_time_now() - t0;
  s->st.t_assemble += dt;
  s->st.n_assemble++;
  sa_timing_add("fem assemble", dt);
  return n_inv ? SA_ERR_INVERTED : 0;
}

/* Newton's assembly: its own work arrays and the trial history; sets V and the element
 * statistics of the solver. */
static int assemble(FemSolver *s, const double *x, double p, int want_K) {
  AsmBuf bf = {s->fint, s->q, s->gv, s->val, s->hist_t, 0, 0, 0, 0};
  int rc = assemble_into(s, &bf, x, p, want_K);
  if (want_K) s->st.n_assemble_tangent++;
  s->V = bf.V;
  s->energy = bf.energy;
  s->min_detF = bf.min_detF;
  s->n_inverted = bf.n_inv;
  return rc;
}

/* Read-back assembly at the converged state: separate arrays, so a getter called between
 * solves changes nothing a later Newton iteration (or a reused factorisation) depends on. */
static int assemble_readback(FemSolver *s, int want_K) {
  AsmBuf *bf = &s->rb;
  int rc = assemble_into(s, bf, s->x, s->p, want_K);
  if (rc) sa_error_clear();
  SA_REQUIRE(rc == 0, SA_ERR_NUMERICAL, "inverted elements in the converged state");
  return 0;
}

/* ------------------------------------------------------------------ loads */

static double nrm2(const double *a, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += a[i] * a[i];
  return sqrt(s);
}

static double dot(const double *a, const double *b, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* Dead loads and prescribed displacements at ramp parameter lam. */
static void apply_loads(FemSolver *s, double lam) {
  for (int A = 0; A < s->N; A++)
    for (int c = 0; c < 3; c++) {
      int d = 3 * A + c;
      double g = s->g_c[c] + lam * (s->g_t[c] - s->g_c[c]);
      s->fdead[d] = s->fn_c[d] + lam * (s->fn_t[d] - s->fn_c[d]) + s->mlump[A] * g;
      if (s->eq[d] < 0) {
        s->u[d] = s->up_c[d] + lam * (s->up_t[d] - s->up_c[d]);
        s->x[d] = s->m->xyz[d] + s->u[d];
      }
    }
  if (s->control == FEM_CONTROL_LOAD) s->p = s->p_c + lam * (s->p_t - s->p_c);
  else s->V_goal = s->V_c + lam * (s->V_t - s->V_c);
}

int fem_solver_set_control(FemSolver *s, FemControl control) {
  if (control == FEM_CONTROL_VOLUME)
    SA_REQUIRE(s->npf > 0, SA_ERR_INPUT, "volume control needs a pressure surface");
  s->control = control;
  s->V_c = s->V_t = s->V;
  s->p_c = s->p_t = s->p;
  return 0;
}

int fem_solver_set_pressure(FemSolver *s, double p) {
  SA_REQUIRE(isfinite(p), SA_ERR_INPUT, "pressure %g is not finite", p);
  s->p_t = p;
  return 0;
}

int fem_solver_set_volume(FemSolver *s, double volume) {
  SA_REQUIRE(isfinite(volume) && volume > 0, SA_ERR_INPUT, "cavity volume %g must be > 0", volume);
  s->V_t = volume;
  return 0;
}

int fem_solver_set_prescribed(FemSolver *s, int n, const int *nodes, int comp, double value) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "prescribed displacements are set after setup");
  SA_REQUIRE(comp >= 0 && comp < 3, SA_ERR_INPUT, "component %d not in 0..2", comp);
  for (int k = 0; k < n; k++) {
    int d = 3 * nodes[k] + comp;
    SA_REQUIRE(nodes[k] >= 0 && nodes[k] < s->N && s->eq[d] < 0, SA_ERR_INPUT,
               "node %d component %d is not fixed", nodes[k], comp);
    s->up_t[d] = value;
  }
  return 0;
}

int fem_solver_set_nodal_forces(FemSolver *s, int n, const int *nodes, const double *f) {
  for (int k = 0; k < n; k++) {
    int A = nodes[k];
    if (A < 0 || A >= s->N) return SA_ERROR(SA_ERR_INPUT, "node %d out of range", A);
    s->fn_t[3 * A] = f[3 * k];
    s->fn_t[3 * A + 1] = f[3 * k + 1];
    s->fn_t[3 * A + 2] = f[3 * k + 2];
  }
  return 0;
}

int fem_solver_set_static_interval(FemSolver *s, double dt) {
  SA_REQUIRE(dt >= 0 && isfinite(dt), SA_ERR_INPUT, "static interval %g must be >= 0", dt);
  s->static_dt = dt;
  return 0;
}

void fem_solver_clear_nodal_forces(FemSolver *s) {
  memset(s->fn_t, 0, (size_t)s->ndof * sizeof *s->fn_t);
}

void fem_solver_set_monitor(FemSolver *s, FemMonitor fn, void *ctx) {
  s->mon = fn;
  s->mon_ctx = ctx;
}

/* ------------------------------------------------------------------ Newton */

typedef struct {
  int dynamic;
  double dt, beta, gamma, alpha; /* Newmark/HHT for this substep */
} StepKind;

/* Residual on free dofs at the last assembled state; returns ||R||, and the force scale fref
 * (max of the internal-force norm incl. reactions and the external-force norm). */
static double residual(FemSolver *s, const StepKind *sk, double *fref) {
  double fe2 = 0, fi2 = 0, r2 = 0;
  for (int d = 0; d < s->ndof; d++) {
    double fext = s->fdead[d] + s->p * s->q[d];
    double r = s->fint[d] - fext;
    fi2 += s->fint[d] * s->fint[d];
    int k = s->eq[d];
    if (k < 0) continue;
    fe2 += fext * fext;
    if (sk->dynamic) {
      double M = s->mlump[d / 3];
      /* HHT: M a + C v + (1 + alpha) r_{n+1} - alpha r_n, alpha in [-1/3, 0] */
      r = M * (s->acc[d] + s->prm.mass_damping * s->v[d]) + (1 + sk->alpha) * r -
          sk->alpha * s->res_n[d];
    }
    s->R[k] = r;
    r2 += r * r;
  }
  *fref = fmax(sqrt(fi2), sqrt(fe2));
  return sqrt(r2);
}

/* Newmark kinematics of the current u from the substep start state. */
static void newmark_update(FemSolver *s, const StepKind *sk) {
  double dt = sk->dt, b = sk->beta, g = sk->gamma;
  for (int d = 0; d < s->ndof; d++) {
    double a = (s->u[d] - s->u_last[d] - dt * s->v_last[d]) / (b * dt * dt) -
               (0.5 / b - 1.0) * s->a_last[d];
    s->acc[d] = a;
    s->v[d] = s->v_last[d] + dt * ((1 - g) * s->a_last[d] + g * a);
  }
}

static int factorize(FemSolver *s, const StepKind *sk) {
  if (sk->dynamic) {
    double cm = 1.0 / (sk->beta * sk->dt * sk->dt) +
                s->prm.mass_damping * sk->gamma / (sk->beta * sk->dt);
    for (long k = 0; k < s->nnz; k++) s->val[k] *= 1 + sk->alpha;
    for (int d = 0; d < s->ndof; d++)
      if (s->eq[d] >= 0) s->val[s->diag[s->eq[d]]] += cm * s->mlump[d / 3];
  }
  /* CHOLMOD at every iteration: a tangent that is indefinite at the first iteration of a
   * substep (the load increment applied to the converged state) is usually positive definite
   * again near the new equilibrium, and a failed CHOLMOD attempt costs at most one Cholesky
   * (quick return at the first non-positive pivot), ~6x less than the LU it would replace. */
  int sym = s->prm.linsolver == FEM_LINSOLVER_AUTO;
  if (sym) {
    double asym = fem_linsolve_asymmetry(s->lin, s->val);
    s->st.asymmetry = asym;
    if (asym > s->prm.sym_tol) {
      sym = 0;
      sa_log(s->last_sym ? SA_LOG_INFO : SA_LOG_DEBUG, "fem",
             "tangent not symmetric (max|K-K^T|/max|K| = %.2e > %.0e): UMFPACK LU", asym,
             s->prm.sym_tol);
    }
  }
  double t0 = sa_time_now();
  int rc = fem_linsolve_factorize(s->lin, s->val, sym);
  s->st.t_factor += sa_time_now() - t0;
  s->st.n_factor++;
  FemLinInfo li;
  fem_linsolve_info(s->lin, &li);
  if (li.not_pd) {
    sa_log(s->saw_not_pd ? SA_LOG_DEBUG : SA_LOG_INFO, "fem",
           "tangent not positive definite (CHOLMOD): UMFPACK LU for this iteration");
    s->saw_not_pd = s->fail_not_pd = 1;
  }
  if (rc == 0 && li.kind == FEM_LIN_UMFPACK) {
    s->lu_substep++;
    s->rep.lu_fallbacks++;
    s->st.n_lu++;
  } else if (rc == 0) {
    s->st.n_chol++;
  }
  s->last_sym = (rc == 0 && li.kind == FEM_LIN_CHOLMOD);
  return rc;
}

static int linsolve(FemSolver *s, const double *b, double *x) {
  double t0 = sa_time_now();
  int rc = fem_linsolve_solve(s->lin, b, x);
  s->st.t_solve += sa_time_now() - t0;
  s->st.n_solve++;
  return rc;
}

static void set_x(FemSolver *s) {
  for (int d = 0; d < s->ndof; d++) s->x[d] = s->m->xyz[d] + s->u[d];
}

/* One substep: Newton from the current u (the predictor is applied by the caller) to
 * equilibrium with the loads already applied. Lazy backtracking: a full step is taken; if the
 * next assembly finds an inverted element, a NaN or a larger merit (residual norm, plus the
 * volume-constraint violation in force units), the step is halved (up to 6 times).
 * Returns 0, > 0 (recoverable: caller cuts the increment) or < 0 (fatal). */
static int newton(FemSolver *s, const StepKind *sk, int step, int *iters) {
  const int vol = s->control == FEM_CONTROL_VOLUME;
  const int nf = s->nfree;
  int ls = 0, it = 0, stall = 0;
  double r_prev = -1, r_first = -1, merit_prev = INFINITY, step_len = 1.0, dp = 0.0, gb = 0.0;
  double du_norm = 0.0, qnorm = 0.0;
  *iters = 0;
  /* Predictor (it 0), FemPredictor: NEW_LOAD (default) factorises the converged state with the
   * new pressure's load stiffness, K(u_n, p_n+1); EQUILIBRIUM uses K(u_n, p_n), the
   * equilibrium path's tangent (on the actuator K(u_n, p_n+1) is indefinite above ~4 kPa of
   * increment: no stress yet carries the extra pressure); REUSE takes the factors of the last
   * iteration of the previous substep (no factorisation: meant for many small coupled
   * solves). Measured on the default scene (docs/fem.md): NEW_LOAD needs the fewest
   * factorisations and LU fallbacks, although its first tangent is often indefinite. */
  int reuse = s->prm.predictor == FEM_PREDICT_REUSE && s->fact_converged &&
              s->fact_dynamic == sk->dynamic && (!sk->dynamic || (s->fact_dt == sk->dt &&
              s->fact_alpha == sk->alpha));
  double p_pred = s->prm.predictor == FEM_PREDICT_NEW_LOAD ? s->p : s->p_last;
  /* reuse_rate > 0 (modified Newton): a direction from fresh factors is followed by one that
   * reuses them (assembly + triangular solves): for a nearly incompressible solid a full
   * Newton step leaves a volumetric residual ~ kappa |grad du|^2 (|R| jumps x10-100) that one
   * more solve with the same factors mostly removes. Reuse goes on while |R| falls by
   * reuse_rate per iteration, else fresh factors. Off by default: on the default scene it
   * saved a third of the factorisations but not time (docs/fem.md). */
  int have_fact = reuse, fresh_last = 0, nfresh = 0;
  for (;;) {
    if (sk->dynamic) newmark_update(s, sk);
    /* Reuse is planned before the assembly, so a direction from reused factors builds no
     * tangent and the values the factors were computed from (incl. the dynamic mass term) stay
     * in val for UMFPACK's iterative refinement. Certain: the REUSE predictor at it 0, and the
     * iteration after fresh factors; tentative: continued reuse, confirmed by the rate below
     * (if rejected, the tangent is assembled then). */
    int plan_reuse = it == 0 ? reuse
                             : (s->prm.reuse_rate > 0 && have_fact && ls == 0);
    int rc = assemble(s, s->x, it == 0 ? p_pred : s->p, !plan_reuse);
    double fref = 0, rnorm = INFINITY, c = 0, merit = INFINITY;
    if (rc == 0) {
      rnorm = residual(s, sk, &fref);
      if (vol) c = s->V - s->V_goal;
      /* merit: |R| plus, under volume control, the constraint violation in force units
       * (|q| |c| / (g.b): the pressure error that c implies, times the load per pressure) */
      merit = rnorm;
      if (vol && gb != 0.0) merit += qnorm * fabs(c) / fabs(gb);
    }
    int bad = rc != 0 || !isfinite(rnorm);
    /* Backtrack on inverted elements / non-finite residuals, and on a residual blow-up by
     * more than ls_growth. Not on any increase: for a nearly incompressible solid the full
     * Newton step changes the volume to second order and kappa times that makes the residual
     * norm jump although the next iterations converge quadratically (docs/fem.md). */
    if (it > 0 && s->prm.line_search && ls < 6 &&
        (bad || merit > s->prm.ls_growth * merit_prev)) {
      step_len *= 0.5;
      ls++;
      for (int d = 0; d < s->ndof; d++)
        if (s->eq[d] >= 0) s->u[d] = s->u_it[d] + step_len * s->du[s->eq[d]];
      s->p = s->p_it + step_len * dp;
      set_x(s);
      continue;
    }
    if (bad) {
      *iters = it;
      if (rc == SA_ERR_INVERTED)
        return SA_ERROR(SA_ERR_INVERTED, "%d element(s) inverted at iteration %d",
                        s->n_inverted, it);
      return SA_ERROR(SA_ERR_NAN, "residual is not finite at iteration %d", it);
    }
    double rate = r_prev > 0 ? rnorm / r_prev : 0.0;
    if (vol)
      sa_log(SA_LOG_DEBUG, "fem",
             "step %d it %2d |R| %.3e |du| %.3e rate %.3f  p %.6g dV %.2e%s%s", step, it, rnorm,
             du_norm, rate, s->p, c, ls ? "  (line search)" : "",
             it > 0 && !fresh_last ? "  (reused factors)" : "");
    else
      sa_log(SA_LOG_DEBUG, "fem", "step %d it %2d |R| %.3e |du| %.3e rate %.3f%s%s", step, it,
             rnorm, du_norm, rate, ls ? "  (line search)" : "",
             it > 0 && !fresh_last ? "  (reused factors)" : "");
    if (it <= 1) r_first = fmax(r_first, rnorm); /* it 0 may be ~0 under volume control */
    /* converged: residual below tolerance, or (round-off floor of a stiff, nearly
     * incompressible problem) the last update negligible against the displacement */
    int conv = (rnorm <= s->prm.rtol * fref + s->prm.atol ||
                (it > 0 && ls == 0 && du_norm <= s->prm.utol * nrm2(s->u, s->ndof))) &&
               (!vol || fabs(c) <= s->prm.vtol * s->V_ref);
    if (conv) {
      *iters = it;
      return 0;
    }
    if (nfresh >= s->prm.max_iter || it >= 4 * s->prm.max_iter) {
      *iters = it;
      return SA_ERROR(SA_ERR_NOT_CONVERGED, "no convergence in %d iterations (|R| %.3e, %.3e x "
                      "tolerance)", it, rnorm, rnorm / (s->prm.rtol * fref + s->prm.atol));
    }
    stall = (it > 1 && rnorm > 0.5 * r_prev) ? stall + 1 : 0;
    if (stall >= s->prm.max_stall) {
      *iters = it;
      return SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton stalled (|R| %.3e not halved in %d "
                      "iterations)", rnorm, stall);
    }
    if (it >= 3 && rnorm > 1e6 * r_first) {
      *iters = it;
      return SA_ERROR(SA_ERR_NOT_CONVERGED, "Newton diverging (|R| grew from %.3e to %.3e)",
                      r_first, rnorm);
    }
    /* new direction: fresh factors, or reuse (see above) */
    int use_old = it == 0 ? reuse
                          : (s->prm.reuse_rate > 0 && have_fact && ls == 0 &&
                             (fresh_last || rate <= s->prm.reuse_rate));
    if (!use_old && plan_reuse) { /* tentative reuse rejected: the tangent at this iterate */
      rc = assemble(s, s->x, s->p, 1);
      if (rc) {
        *iters = it;
        return SA_ERROR(SA_ERR_INVERTED, "%d element(s) inverted at iteration %d",
                        s->n_inverted, it);
      }
    }
    rc = use_old ? 0 : factorize(s, sk);
    if (!use_old) nfresh++;
    else s->st.n_reuse++;
    fresh_last = !use_old;
    have_fact = rc == 0;
    if (rc) {
      *iters = it;
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    for (int k = 0; k < nf; k++) s->rhs[k] = -s->R[k];
    SA_CHECK(linsolve(s, s->rhs, s->da));
    if (vol) {
      for (int d = 0; d < s->ndof; d++)
        if (s->eq[d] >= 0) {
          s->qf[s->eq[d]] = s->q[d];
          s->gf[s->eq[d]] = s->gv[d];
        }
      SA_CHECK(linsolve(s, s->qf, s->db));
      gb = dot(s->gf, s->db, nf);
      if (gb == 0.0 || !isfinite(gb)) {
        *iters = it;
        return SA_ERROR(SA_ERR_NOT_CONVERGED, "volume control: dV/dp = 0 (bordered system "
                        "singular)");
      }
      dp = -(c + dot(s->gf, s->da, nf)) / gb;
      qnorm = nrm2(s->qf, nf);
      merit = rnorm + qnorm * fabs(c) / fabs(gb);
      for (int k = 0; k < nf; k++) s->du[k] = s->da[k] + dp * s->db[k];
    } else {
      dp = 0.0;
      memcpy(s->du, s->da, (size_t)nf * sizeof *s->du);
    }
    du_norm = nrm2(s->du, nf);
    memcpy(s->u_it, s->u, (size_t)s->ndof * sizeof *s->u);
    s->p_it = s->p;
    merit_prev = merit;
    r_prev = rnorm;
    ls = 0;
    step_len = 1.0;
    for (int d = 0; d < s->ndof; d++)
      if (s->eq[d] >= 0) s->u[d] += s->du[s->eq[d]];
    s->p += dp;
    set_x(s);
    it++;
  }
}

/* ------------------------------------------------------------------ load stepping */

static void restore_last(FemSolver *s) {
  memcpy(s->u, s->u_last, (size_t)s->ndof * sizeof *s->u);
  memcpy(s->v, s->v_last, (size_t)s->ndof * sizeof *s->v);
  memcpy(s->acc, s->a_last, (size_t)s->ndof * sizeof *s->acc);
  s->p = s->p_last;
  set_x(s);
}

static void commit_substep(FemSolver *s, double dt) {
  memcpy(s->u_last, s->u, (size_t)s->ndof * sizeof *s->u);
  memcpy(s->v_last, s->v, (size_t)s->ndof * sizeof *s->v);
  memcpy(s->a_last, s->acc, (size_t)s->ndof * sizeof *s->acc);
  double dV = s->V - s->V_last, dP = s->p - s->p_last;
  if (s->npf > 0 && fabs(dV) > 1e-12 * s->V_ref && s->slope0 == 0.0 && dP != 0.0)
    s->slope0 = dP / dV;
  s->p_prev = s->p_last;
  s->p_last = s->p;
  s->V_prev = s->V_last;
  s->V_last = s->V;
  double *h = s->hist_c;
  s->hist_c = s->hist_t;
  s->hist_t = h;
  for (int d = 0; d < s->ndof; d++) s->res_n[d] = s->fint[d] - s->fdead[d] - s->p * s->q[d];
  s->time += dt;
  s->fail_not_pd = 0;
}

/* Loads reached at ramp parameter lam become the committed loads. */
static void commit_loads(FemSolver *s, double lam) {
  for (int d = 0; d < s->ndof; d++) {
    s->fn_c[d] += lam * (s->fn_t[d] - s->fn_c[d]);
    s->up_c[d] += lam * (s->up_t[d] - s->up_c[d]);
  }
  for (int c = 0; c < 3; c++) s->g_c[c] += lam * (s->g_t[c] - s->g_c[c]);
  if (s->control == FEM_CONTROL_LOAD) s->p_c += lam * (s->p_t - s->p_c);
  else {
    s->V_c += lam * (s->V_t - s->V_c);
    s->p_c = s->p_t = s->p;
  }
  s->lam_total += lam;
}

static int diagnose_failure(FemSolver *s, double lam) {
  double slope = (s->V_last != s->V_prev) ? (s->p_last - s->p_prev) / (s->V_last - s->V_prev) : NAN;
  int flat = s->npf > 0 && s->slope0 > 0 && isfinite(slope) && slope < 0.05 * s->slope0;
  commit_loads(s, lam);
  if (s->control == FEM_CONTROL_LOAD && (s->fail_not_pd || flat)) {
    snprintf(s->rep.reason, sizeof s->rep.reason,
             "limit point under load control at p = %.6g Pa, V = %.6g m^3: increment cut below "
             "%.1e; %s%s dp/dV = %.3g Pa/m^3 (initially %.3g); continue with volume control",
             s->p_last, s->V_last, s->prm.dl_min,
             s->fail_not_pd ? "tangent lost positive definiteness (CHOLMOD); " : "",
             flat ? "pressure-volume curve flat:" : "", slope, s->slope0);
    return SA_ERROR(SA_ERR_LIMIT_POINT, "%s", s->rep.reason);
  }
  snprintf(s->rep.reason, sizeof s->rep.reason,
           "increment cut below %.1e at ramp parameter %.6g (p = %.6g Pa); last failure: %s",
           s->prm.dl_min, lam, s->p_last, s->last_fail);
  return SA_ERROR(SA_ERR_STEP_TOO_SMALL, "%s", s->rep.reason);
}

/* After a static solve standing for the interval static_dt: the mean velocity over the solve,
 * v = (u - u_start) / dt, becomes the state's velocity (the read-back and the start of a later
 * dynamic step), a = 0, and time advances by dt. */
static void static_velocities(FemSolver *s) {
  for (int d = 0; d < s->ndof; d++) {
    s->v[d] = s->v_last[d] = (s->u[d] - s->u_start[d]) / s->static_dt;
    s->acc[d] = s->a_last[d] = 0.0;
  }
  s->time += s->static_dt;
}

static int ramp(FemSolver *s, int dynamic, double dt_total) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_setup must be called before solving");
  SA_REQUIRE(!dynamic || s->control == FEM_CONTROL_LOAD, SA_ERR_INPUT,
             "implicit dynamics supports load control only");
  memset(&s->rep, 0, sizeof s->rep);
  double lam = 0.0, dl = s->dl_keep > 0 ? s->dl_keep : s->prm.dl_init;
  s->fail_not_pd = 0;
  memcpy(s->u_start, s->u_last, (size_t)s->ndof * sizeof *s->u);
  if (!dynamic) { /* the substeps of a static ramp have no inertia: v = a = 0 inside it */
    size_t nb = (size_t)s->ndof * sizeof *s->v;
    memset(s->v, 0, nb);
    memset(s->acc, 0, nb);
    memset(s->v_last, 0, nb);
    memset(s->a_last, 0, nb);
  }
  while (lam < 1.0 - 1e-12) {
    double dl_try = dl;
    if (dl > 1.0 - lam || 1.0 - lam - dl < 1e-9) dl = 1.0 - lam;
    double lam_b = lam + dl;
    apply_loads(s, lam_b);
    /* No extrapolation predictor: for a nearly incompressible solid a linearly extrapolated
     * displacement changes element volumes to second order and kappa times that gives a far
     * worse start than the last converged state (measured: residual x 600). The first Newton
     * iteration from the converged state is the tangent predictor. */
    StepKind sk = {0};
    if (dynamic) {
      sk.dynamic = 1;
      sk.dt = dl * dt_total;
      sk.alpha = fmin(0.0, fmax(-1.0 / 3.0, s->prm.hht_alpha));
      sk.beta = 0.25 * (1 - sk.alpha) * (1 - sk.alpha);
      sk.gamma = 0.5 - sk.alpha;
    }
    int iters = 0;
    s->step_count++;
    s->saw_not_pd = 0;
    s->lu_substep = 0;
    int rc = newton(s, &sk, s->step_count, &iters);
    if (s->saw_not_pd)
      sa_log(SA_LOG_DEBUG, "fem", "step %d: %d of %d factorisations by UMFPACK LU",
             s->step_count, s->lu_substep, iters);
    s->rep.newton_iters += iters;
    s->rep.last_dl = dl;
    if (rc == 0) {
      commit_substep(s, sk.dt);
      if (iters > 0) { /* else the factors are still those of the state before */
        s->fact_converged = 1;
        s->fact_dynamic = sk.dynamic;
        s->fact_dt = sk.dt;
        s->fact_alpha = sk.alpha;
      }
      lam = lam_b;
      s->rep.substeps++;
      s->rep.lambda = lam;
      sa_log(SA_LOG_DEBUG, "fem", "step %d converged: lambda %.4f (dl %.3g), %d iterations, "
             "p %.6g Pa, V %.6g m^3", s->step_count, lam, dl, iters, s->p, s->V);
      dl = dl_try; /* a cropped last increment does not shrink the next ramp's */
      if (iters <= s->prm.easy_iter) dl = fmin(dl * s->prm.grow, s->prm.dl_max);
      s->dl_keep = dl;
      if (s->mon) {
        int mrc = s->mon(s, s->mon_ctx);
        if (mrc) {
          commit_loads(s, lam);
          return sa_error_push(mrc, __func__, __FILE__, __LINE__);
        }
      }
      continue;
    }
    if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    snprintf(s->last_fail, sizeof s->last_fail, "%s", sa_error_message());
    sa_error_clear();
    restore_last(s);
    s->fact_converged = 0; /* the factors belong to a failed iterate */
    s->rep.cuts++;
    dl *= s->prm.cut;
    s->dl_keep = dl;
    sa_log(SA_LOG_INFO, "fem", "step %d failed (%s): increment cut to %.3g", s->step_count,
           s->last_fail, dl);
    if (dl < s->prm.dl_min) {
      apply_loads(s, lam);
      return diagnose_failure(s, lam);
    }
  }
  commit_loads(s, 1.0);
  if (!dynamic && s->static_dt > 0) static_velocities(s);
  s->rep.lambda = 1.0;
  snprintf(s->rep.reason, sizeof s->rep.reason,
           "converged: targets reached in %d substep(s), %d cut(s), %d Newton iterations",
           s->rep.substeps, s->rep.cuts, s->rep.newton_iters);
  return 0;
}

int fem_solver_solve(FemSolver *s) {
  SA_CHECK(ramp(s, 0, 0.0));
  return 0;
}

int fem_solver_step_dynamic(FemSolver *s, double dt) {
  SA_REQUIRE(dt > 0 && isfinite(dt), SA_ERR_INPUT, "time step %g must be > 0", dt);
  SA_CHECK(ramp(s, 1, dt));
  return 0;
}

void fem_solver_report(const FemSolver *s, FemSolveReport *rep) { *rep = s->rep; }

/* ------------------------------------------------------------------ read-back */

const double *fem_solver_positions(const FemSolver *s) { return s->x; }
const double *fem_solver_displacements(const FemSolver *s) { return s->u; }
const double *fem_solver_velocities(const FemSolver *s) { return s->v; }
double fem_solver_pressure(const FemSolver *s) { return s->p; }
double fem_solver_cavity_volume(const FemSolver *s) { return s->V; }
double fem_solver_time(const FemSolver *s) { return s->time; }
const FemMesh *fem_solver_mesh(const FemSolver *s) { return s->m; }

int fem_solver_reactions(FemSolver *s, double *r) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_reactions before setup");
  SA_CHECK(assemble_readback(s, 0));
  for (int d = 0; d < s->ndof; d++) r[d] = s->rb.fint[d] - s->fdead[d] - s->p * s->rb.q[d];
  return 0;
}

int fem_solver_pressure_resultant(FemSolver *s, double F[3]) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_pressure_resultant before setup");
  SA_CHECK(assemble_readback(s, 0));
  F[0] = F[1] = F[2] = 0;
  for (int d = 0; d < s->ndof; d++) F[d % 3] += s->p * s->rb.q[d];
  return 0;
}

int fem_solver_pressure_forces(FemSolver *s, double *f) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_pressure_forces before setup");
  SA_CHECK(assemble_readback(s, 0));
  for (int d = 0; d < s->ndof; d++) f[d] = s->p * s->rb.q[d];
  return 0;
}

/* The read-back tangent values (allocated on first use: a diagnostic, not the coupling path). */
static int readback_val(FemSolver *s) {
  if (!s->rb.val) SA_CALLOC(s->rb.val, s->nnz);
  return 0;
}

double fem_solver_tangent_asymmetry(FemSolver *s) {
  if (!s->setup_done || readback_val(s) || assemble_readback(s, 1)) {
    sa_error_clear();
    return NAN;
  }
  return fem_linsolve_asymmetry(s->lin, s->rb.val);
}

int fem_solver_element_stress(FemSolver *s, double *sigma, double *vm, double *lam) {
  const FemMesh *m = s->m;
  int nen = s->nen;
  for (int e = 0; e < m->nelem; e++) {
    const int *c = m->conn + (size_t)e * nen;
    double X[30], xe[30], sg[9], lm[3];
    for (int a = 0; a < nen; a++)
      for (int k = 0; k < 3; k++) {
        X[3 * a + k] = m->xyz[3 * c[a] + k];
        xe[3 * a + k] = s->x[3 * c[a] + k];
      }
    int r = m->region ? m->region[e] : 0;
    int rc = fem_element_stress(m->etype, X, xe, &s->mats[r], s->hist_c + s->hoff[e], sg, lm);
    if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    if (sigma) memcpy(sigma + 9 * (size_t)e, sg, sizeof sg);
    if (lam) memcpy(lam + 3 * (size_t)e, lm, sizeof lm);
    if (vm) {
      double d0 = sg[0] - sg[4], d1 = sg[4] - sg[8], d2 = sg[8] - sg[0];
      vm[e] = sqrt(0.5 * (d0 * d0 + d1 * d1 + d2 * d2) +
                   3.0 * (sg[1] * sg[1] + sg[2] * sg[2] + sg[5] * sg[5]));
    }
  }
  return 0;
}

void fem_solver_stats(const FemSolver *s, FemSolverStats *st) { *st = s->st; }

void fem_solver_destroy(FemSolver **ps) {
  if (!ps || !*ps) return;
  FemSolver *s = *ps;
  fem_linsolve_destroy(&s->lin);
  void *ptrs[] = {s->mats, s->fixmask, s->pf, s->eq, s->colptr, s->rowind, s->diag, s->val,
                  s->adj_ptr, s->adj, s->slot9, s->epair, s->fpair, s->group_ptr,
                  s->group_elem, s->hoff, s->hist_c, s->hist_t, s->u, s->x, s->v, s->acc,
                  s->u_last, s->v_last, s->a_last, s->u_start, s->fn_c, s->fn_t, s->up_c,
                  s->up_t, s->mlump, s->fint, s->q, s->gv, s->fdead, s->res_n, s->R, s->da,
                  s->db, s->du, s->rhs, s->qf, s->gf, s->u_it, s->rb.fint, s->rb.q, s->rb.gv,
                  s->rb.val, s->rb.hist};
  for (size_t i = 0; i < sizeof ptrs / sizeof *ptrs; i++) free(ptrs[i]);
  free(s);
  *ps = NULL;
}

/* ------------------------------------------------------------------ diagnostics */

int fem_solver_check_tangent(FemSolver *s, double h, double *rel_err) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "check_tangent before setup");
  SA_CHECK(readback_val(s));
  int nf = s->nfree, nd = s->ndof;
  double *v, *Kv, *Rp, *x0;
  SA_CALLOC(v, nf);
  SA_CALLOC(Kv, nf);
  SA_CALLOC(Rp, nf);
  SA_CALLOC(x0, nd);
  unsigned long seed = 12345;
  for (int k = 0; k < nf; k++) {
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    v[k] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
  }
  /* read-back buffers and a perturbed copy of x: the solver's state and work arrays stay */
  memcpy(x0, s->x, (size_t)nd * sizeof *x0);
  AsmBuf *bf = &s->rb;
  int rc = assemble_into(s, bf, s->x, s->p, 1);
  for (int j = 0; j < nf; j++)
    for (int k = s->colptr[j]; k < s->colptr[j + 1]; k++) Kv[s->rowind[k]] += bf->val[k] * v[j];
  double *xp = NULL;
  if (rc == 0) SA_CALLOC(xp, nd);
  for (int sgn = 1; sgn >= -1 && rc == 0; sgn -= 2) {
    for (int d = 0; d < nd; d++) xp[d] = x0[d] + (s->eq[d] >= 0 ? sgn * h * v[s->eq[d]] : 0.0);
    rc = assemble_into(s, bf, xp, s->p, 0);
    for (int d = 0; d < nd; d++)
      if (s->eq[d] >= 0)
        Rp[s->eq[d]] += sgn * (bf->fint[d] - s->fdead[d] - s->p * bf->q[d]) / (2 * h);
  }
  if (rc) sa_error_clear();
  double num = 0, den = 0;
  for (int k = 0; k < nf; k++) {
    num += (Rp[k] - Kv[k]) * (Rp[k] - Kv[k]);
    den += Kv[k] * Kv[k];
  }
  *rel_err = sqrt(num / fmax(den, 1e-300));
  free(v);
  free(Kv);
  free(Rp);
  free(x0);
  free(xp);
  SA_REQUIRE(rc == 0, SA_ERR_INVERTED, "inverted element during the tangent check");
  return 0;
}
