/* fem_solver.c - the FemSolver object: create (validators), boundary conditions, setup (which
 * runs every phase's symbolic work and allocation, fem_solver_priv.h), read-back and destroy.
 * The phases live in fem_dofmap.c, fem_assemble.c, fem_newton.c, fem_continuation.c and
 * fem_dynamics.c; the formulation is in docs/fem.md. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_blas.h"
#include "fem_element.h"
#include "fem_solver_priv.h"
#include "sa_error.h"
#include "sa_log.h"

/* fem_mesh_check tolerance: det J / 6 <= this times the mean element volume is rejected. */
#define FEM_SOLVER_MESH_TOL 1e-10


FemSolverParams fem_solver_params_default(void) {
  FemSolverParams p = {
      .rtol = 1e-8, .atol = 1e-14, .utol = 1e-11, .vtol = 1e-10, .max_iter = 25, .line_search = 1,
      .dl_init = 1.0, .dl_min = 1e-4, .dl_max = 1.0, .easy_iter = 5, .grow = 1.5, .cut = 0.5,
      .threads = 2, .linsolver = FEM_LINSOLVER_AUTO, .sym_tol = 1e-9, .hht_alpha = -0.05,
      .mass_damping = 0.0, .ls_growth = 1e3, .max_stall = 6,
      .predictor = FEM_PREDICT_NEW_LOAD, .reuse_rate = 0.0,
      .merit = FEM_MERIT_LAZY, .armijo = 1e-4, .ls_memory = 1, .indefinite = FEM_INDEFINITE_LU,
      .krylov_max = 0, .krylov_rtol = 1e-3};
  return p;
}

/* ------------------------------------------------------------------ create / BCs */

int fem_solver_create(const FemMesh *mesh, const FemMaterial *mats, const FemSolverParams *prm,
                      FemSolver **out) {
  *out = NULL;
  SA_REQUIRE(mesh && mesh->nnodes > 0 && mesh->nelem > 0, SA_ERR_INPUT, "empty mesh");
  SA_REQUIRE(mats, SA_ERR_INPUT, "no materials");
  if (prm) {
    SA_REQUIRE(prm->predictor >= FEM_PREDICT_NEW_LOAD && prm->predictor <= FEM_PREDICT_EXTRAPOLATE,
               SA_ERR_INPUT, "predictor %d is not one of 0 (new_load), 1 (equilibrium), 2 (reuse), 3 (extrapolate)",
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
  s->dm.fixmask = calloc((size_t)s->N, sizeof *s->dm.fixmask);
  if (!s->mats || !s->dm.fixmask) {
    fem_solver_destroy(&s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate solver");
  }
  memcpy(s->mats, mats, (size_t)nreg * sizeof *s->mats);
  s->as.nfn = mesh->etype == FEM_TET10 ? 6 : 3;
  /* nodal-force targets exist from creation: set_nodal_forces may come before setup */
  s->ct.fn_c = calloc((size_t)s->ndof, sizeof *s->ct.fn_c);
  s->ct.fn_t = calloc((size_t)s->ndof, sizeof *s->ct.fn_t);
  if (!s->ct.fn_c || !s->ct.fn_t) {
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
    s->dm.fixmask[nodes[k]] |= mask & FEM_XYZ;
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
  SA_REQUIRE(f->nfn == s->as.nfn, SA_ERR_INPUT, "surface '%s' has %d-node faces, expected %d",
             surface, f->nfn, s->as.nfn);
  int *pf = realloc(s->as.pf, (size_t)(s->as.npf + f->nfaces) * s->as.nfn * sizeof *pf);
  SA_REQUIRE(pf, SA_ERR_MEMORY, "cannot grow pressure face list");
  memcpy(pf + (size_t)s->as.npf * s->as.nfn, f->faces, (size_t)f->nfaces * s->as.nfn * sizeof *pf);
  s->as.pf = pf;
  s->as.npf += f->nfaces;
  return 0;
}

int fem_solver_set_gravity(FemSolver *s, const double g[3]) {
  for (int c = 0; c < 3; c++) s->ct.g_t[c] = g[c];
  return 0;
}

int fem_solver_setup(FemSolver *s) {
  SA_REQUIRE(!s->setup_done, SA_ERR_INPUT, "fem_solver_setup called twice");
  const FemMesh *m = s->m;
  double t0 = sa_time_now();
  SA_CHECK(fem_dofmap_build(s));
  SA_CHECK(fem_dofmap_partition(s));
  SA_CHECK(fem_asm_setup(s));
  SA_CHECK(fem_newton_alloc(s));
  int ne = m->nelem, nd = s->ndof, nf = s->dm.nfree;
  double **vecs[] = {&s->u, &s->x, &s->u_last, &s->u_prev, &s->u_start, &s->ct.up_c, &s->ct.up_t,
                     &s->dy.v, &s->dy.acc, &s->dy.v_last, &s->dy.a_last, &s->dy.res_n};
  for (size_t i = 0; i < sizeof vecs / sizeof *vecs; i++) SA_CALLOC(*vecs[i], nd);
  memcpy(s->x, m->xyz, (size_t)nd * sizeof *s->x);

  FemLinInfo li;
  fem_linsolve_info(s->dm.lin, &li);
  s->st.nnodes = s->N;
  s->st.nelem = ne;
  s->st.ndof = nd;
  s->st.nfree = nf;
  s->st.nnz_k = s->dm.nnz;
  s->st.nnz_l = li.nnz_l;
  s->st.t_symbolic = sa_time_now() - t0;
  s->st.n_interface = s->dm.group_ptr[s->dm.ngroups] - s->dm.group_ptr[s->dm.ngroups - 1];
  s->setup_done = 1;

  /* reference cavity volume */
  s->V_ref = 0.0;
  for (int f = 0; f < s->as.npf; f++) {
    double xf[18];
    const int *c = s->as.pf + (size_t)f * s->as.nfn;
    for (int a = 0; a < s->as.nfn; a++)
      for (int k = 0; k < 3; k++) xf[3 * a + k] = m->xyz[3 * c[a] + k];
    s->V_ref += fem_face_volume(s->as.nfn, xf, NULL, NULL);
  }
  s->V = s->ct.V_c = s->ct.V_t = s->ct.V_last = s->ct.V_prev = s->ct.V_goal = s->V_ref;
  sa_log(SA_LOG_INFO, "fem",
         "setup: %d nodes, %d %s elements, %d free dofs, nnz(K) %ld, nnz(L) %.3g (fill %.1f), "
         "%d threads (%d interface elements; OpenBLAS %s kernels), %d pressure faces, V0 = "
         "%.6g m^3, symbolic %.3f s",
         s->N, ne, m->etype == FEM_TET10 ? "tet10" : "tet4", nf, s->dm.nnz, li.nnz_l,
         li.nnz_l / (0.5 * (s->dm.nnz + nf)), s->prm.threads, s->st.n_interface, fem_blas_kernels(),
         s->as.npf,
         s->V_ref, s->st.t_symbolic);
  return 0;
}


/* ------------------------------------------------------------------ read-back */

const double *fem_solver_positions(const FemSolver *s) { return s->x; }
const double *fem_solver_displacements(const FemSolver *s) { return s->u; }
double fem_solver_pressure(const FemSolver *s) { return s->p; }
double fem_solver_cavity_volume(const FemSolver *s) { return s->V; }
double fem_solver_time(const FemSolver *s) { return s->time; }
const FemMesh *fem_solver_mesh(const FemSolver *s) { return s->m; }

int fem_solver_reactions(FemSolver *s, double *r) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_reactions before setup");
  SA_CHECK(fem_asm_readback(s, 0));
  for (int d = 0; d < s->ndof; d++) {
    r[d] = s->as.rb.fint[d] - s->as.fdead[d] - s->p * s->as.rb.q[d];
    if (s->as.ncontrib) r[d] += s->as.rb.fcon[d];
  }
  return 0;
}

int fem_solver_pressure_resultant(FemSolver *s, double F[3]) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_pressure_resultant before setup");
  SA_CHECK(fem_asm_readback(s, 0));
  F[0] = F[1] = F[2] = 0;
  for (int d = 0; d < s->ndof; d++) F[d % 3] += s->p * s->as.rb.q[d];
  return 0;
}

int fem_solver_pressure_forces(FemSolver *s, double *f) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "fem_solver_pressure_forces before setup");
  SA_CHECK(fem_asm_readback(s, 0));
  for (int d = 0; d < s->ndof; d++) f[d] = s->p * s->as.rb.q[d];
  return 0;
}

double fem_solver_tangent_asymmetry(FemSolver *s) {
  if (!s->setup_done || fem_asm_readback(s, 1)) {
    sa_error_clear();
    return NAN;
  }
  return fem_linsolve_asymmetry(s->dm.lin, s->as.rb.val);
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
    int rc = fem_element_stress(m->etype, X, xe, &s->mats[r], s->as.hist_c + s->as.hoff[e], sg, lm);
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

int fem_solver_floating_bodies(const FemSolver *s) { return s->dm.nfloating; }

void fem_solver_destroy(FemSolver **ps) {
  if (!ps || !*ps) return;
  FemSolver *s = *ps;
  fem_dofmap_free(&s->dm);
  fem_asm_free(&s->as);
  fem_newton_free(&s->nw);
  fem_cont_free(&s->ct);
  fem_dyn_free(&s->dy);
  free(s->mats);
  free(s->u);
  free(s->x);
  free(s->u_last);
  free(s->u_prev);
  free(s->u_start);
  free(s);
  *ps = NULL;
}

/* ------------------------------------------------------------------ diagnostics */

int fem_solver_check_tangent(FemSolver *s, double h, double *rel_err) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "check_tangent before setup");
  if (!s->as.rb.val) SA_CALLOC(s->as.rb.val, s->dm.nnz);
  int nf = s->dm.nfree, nd = s->ndof;
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
  AsmBuf *bf = &s->as.rb;
  int rc = fem_asm_into(s, bf, s->x, s->p, 1);
  for (int j = 0; j < nf; j++)
    for (int k = s->dm.colptr[j]; k < s->dm.colptr[j + 1]; k++) Kv[s->dm.rowind[k]] += bf->val[k] * v[j];
  double *xp = NULL;
  if (rc == 0) SA_CALLOC(xp, nd);
  for (int sgn = 1; sgn >= -1 && rc == 0; sgn -= 2) {
    for (int d = 0; d < nd; d++) xp[d] = x0[d] + (s->dm.eq[d] >= 0 ? sgn * h * v[s->dm.eq[d]] : 0.0);
    rc = fem_asm_into(s, bf, xp, s->p, 0);
    for (int d = 0; d < nd; d++)
      if (s->dm.eq[d] >= 0)
        Rp[s->dm.eq[d]] += sgn * (bf->fint[d] + (s->as.ncontrib ? bf->fcon[d] : 0.0) -
                                  s->as.fdead[d] - s->p * bf->q[d]) / (2 * h);
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

int fem_solver_check_potential(FemSolver *s, double p, double h, double *rel_err) {
  SA_REQUIRE(s->setup_done, SA_ERR_INPUT, "check_potential before setup");
  int nf = s->dm.nfree, nd = s->ndof;
  double *v, *xp;
  SA_CALLOC(v, nf);
  SA_CALLOC(xp, nd);
  unsigned long seed = 4242;
  for (int k = 0; k < nf; k++) {
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    v[k] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
  }
  AsmBuf *bf = &s->as.rb;
  double Rv = 0.0, pi[2] = {0, 0};
  int rc = fem_asm_into(s, bf, s->x, p, 0);
  for (int d = 0; d < nd && rc == 0; d++)
    if (s->dm.eq[d] >= 0)
      Rv += (bf->fint[d] - s->as.fdead[d] - p * bf->q[d]) * v[s->dm.eq[d]];
  for (int i = 0; i < 2 && rc == 0; i++) {
    double sgn = i == 0 ? 1.0 : -1.0, wd = 0.0;
    for (int d = 0; d < nd; d++) {
      xp[d] = s->x[d] + (s->dm.eq[d] >= 0 ? sgn * h * v[s->dm.eq[d]] : 0.0);
      wd += s->as.fdead[d] * (xp[d] - s->m->xyz[d]);
    }
    rc = fem_asm_into(s, bf, xp, p, 0);
    pi[i] = bf->energy - p * bf->V - wd;
  }
  if (rc) sa_error_clear();
  *rel_err = fabs(Rv - (pi[0] - pi[1]) / (2 * h)) / fmax(fabs(Rv), 1e-300);
  free(v);
  free(xp);
  SA_REQUIRE(rc == 0, SA_ERR_INVERTED, "inverted element during the potential check");
  SA_REQUIRE(s->as.ncontrib == 0, SA_ERR_INPUT, "contributors have no potential here");
  return 0;
}
