/* fem_assemble.c - assembly as a sum of contributions (fem_contrib.h):
 *   bodies      element kernels (fem_element_tl, the region's law), threaded over slabs that
 *               share no node, the interface elements serially: f_int, K_int
 *   pressure    follower pressure on the pressure faces (fem_face_pressure): q per unit
 *               pressure, its load stiffness p K_q, enclosed volume V and dV/du
 *   dead loads  nodal (coupling) forces and lumped-mass gravity at the ramp parameter
 *               (fem_continuation.c: fem_cont_apply_loads), f_dead
 *   contributors springs (fem_solver_add_spring) and any FemContributor: f_c, K_c
 * Residual R = f_int + f_c - f_dead - p q (fem_newton.c), tangent K = K_int + p K_q + K_c.
 * A contributor's block for a node pair outside the pattern triggers one pattern rebuild
 * (fem_dofmap_rebuild) and a second pass. Bodies, pressure and dead loads keep their dedicated
 * arrays so the built-in path computes exactly what it computed before contributors existed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem_element.h"
#include "fem_solver_priv.h"
#include "sa_error.h"
#include "sa_log.h"

struct FemAsmView {
  FemSolver *s;
  AsmBuf *bf;
  const double *x;
  int want_K;
};

struct FemPairSink {
  int *pairs, n, cap, err;
};

const FemMesh *fem_asm_mesh(const FemAsmView *v) { return v->s->m; }
const double *fem_asm_positions(const FemAsmView *v) { return v->x; }
double fem_asm_time(const FemAsmView *v) { return v->s->time; }
double fem_asm_load_factor(const FemAsmView *v) { return v->s->ct.lam_eval; }
int fem_asm_wants_tangent(const FemAsmView *v) { return v->want_K; }

void fem_asm_add_force(FemAsmView *v, int a, const double f[3]) {
  for (int i = 0; i < 3; i++) v->bf->fcon[3 * a + i] += f[i];
}

void fem_asm_add_block(FemAsmView *v, int a, int b, const double K[9]) {
  if (!v->want_K) return;
  FemSolver *s = v->s;
  int t = fem_dofmap_find_pair(s, a, b);
  if (t < 0) { /* outside the pattern: remember, the assembly rebuilds and repeats */
    FemAssembly *as = &s->as;
    if (as->nmissing == as->cap_missing) {
      int cap = as->cap_missing ? 2 * as->cap_missing : 64;
      int *p = realloc(as->missing, 2 * (size_t)cap * sizeof *p);
      if (!p) return; /* reported by the repeat pass (pair still missing) */
      as->missing = p;
      as->cap_missing = cap;
    }
    as->missing[2 * as->nmissing] = a;
    as->missing[2 * as->nmissing + 1] = b;
    as->nmissing++;
    return;
  }
  const int *sl = s->dm.slot9 + (size_t)t * 9;
  for (int k = 0; k < 9; k++)
    if (sl[k] >= 0) v->bf->val[sl[k]] += K[k];
}

void fem_pairs_add(FemPairSink *sink, int a, int b) {
  if (sink->err) return;
  if (sink->n == sink->cap) {
    int cap = sink->cap ? 2 * sink->cap : 64;
    int *p = realloc(sink->pairs, 2 * (size_t)cap * sizeof *p);
    if (!p) {
      sink->err = 1;
      return;
    }
    sink->pairs = p;
    sink->cap = cap;
  }
  sink->pairs[2 * sink->n] = a;
  sink->pairs[2 * sink->n + 1] = b;
  sink->n++;
}

int fem_solver_add_contributor(FemSolver *s, const FemContributor *c) {
  SA_REQUIRE(c && c->eval, SA_ERR_INPUT, "contributor without eval");
  FemAssembly *as = &s->as;
  if (as->ncontrib == as->cap_contrib) {
    int cap = as->cap_contrib ? 2 * as->cap_contrib : 4;
    FemContributor *p = realloc(as->contrib, (size_t)cap * sizeof *p);
    SA_REQUIRE(p, SA_ERR_MEMORY, "cannot grow the contributor list");
    as->contrib = p;
    as->cap_contrib = cap;
  }
  as->contrib[as->ncontrib++] = *c;
  if (s->setup_done && !as->fcon) SA_CALLOC(as->fcon, s->ndof);
  if (s->setup_done && !as->rb.fcon) SA_CALLOC(as->rb.fcon, s->ndof);
  return 0;
}

int fem_asm_candidate_pairs(FemSolver *s, int **pairs, int *npairs) {
  FemPairSink sink = {0};
  for (int c = 0; c < s->as.ncontrib; c++) {
    const FemContributor *k = &s->as.contrib[c];
    if (!k->candidates) continue;
    int rc = k->candidates(k->ctx, s->m, &sink);
    if (rc) {
      free(sink.pairs);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
  }
  if (sink.err) {
    free(sink.pairs);
    return SA_ERROR(SA_ERR_MEMORY, "contributor pairs");
  }
  for (int k = 0; k < sink.n; k++)
    SA_REQUIRE(sink.pairs[2 * k] >= 0 && sink.pairs[2 * k] < s->N && sink.pairs[2 * k + 1] >= 0 &&
               sink.pairs[2 * k + 1] < s->N, SA_ERR_INPUT, "contributor pair (%d, %d) out of range",
               sink.pairs[2 * k], sink.pairs[2 * k + 1]);
  *pairs = sink.pairs;
  *npairs = sink.n;
  return 0;
}

/* Contributors on top of bodies and pressure: f_c into bf->fcon, K_c into bf->val. Returns the
 * first non-zero code (> 0: a domain error). */
static int eval_contributors(FemSolver *s, AsmBuf *bf, const double *x, int want_K) {
  memset(bf->fcon, 0, (size_t)s->ndof * sizeof *bf->fcon);
  FemAsmView v = {s, bf, x, want_K};
  int first = 0;
  for (int c = 0; c < s->as.ncontrib; c++) {
    int rc = s->as.contrib[c].eval(s->as.contrib[c].ctx, &v);
    if (rc < 0) return SA_ERROR(rc, "contributor '%s' failed: %s", s->as.contrib[c].name ?
                                s->as.contrib[c].name : "?", sa_error_message());
    if (rc > 0) sa_error_clear();
    if (rc && !first) first = rc;
  }
  return first;
}

/* ------------------------------------------------------------------ springs */

/* k (u_a - u_b) on a, the opposite on b; b < 0: tied to the reference position. */
static int springs_eval(void *ctx, FemAsmView *v) {
  FemSolver *s = ctx;
  const double *X = s->m->xyz, *x = v->x;
  for (int k = 0; k < s->as.nsprings; k++) {
    int a = s->as.spring_nodes[2 * k], b = s->as.spring_nodes[2 * k + 1];
    double kk = s->as.spring_k[k], f[3], K[9] = {kk, 0, 0, 0, kk, 0, 0, 0, kk};
    for (int i = 0; i < 3; i++) {
      double ua = x[3 * a + i] - X[3 * a + i], ub = b >= 0 ? x[3 * b + i] - X[3 * b + i] : 0.0;
      f[i] = kk * (ua - ub);
    }
    fem_asm_add_force(v, a, f);
    fem_asm_add_block(v, a, a, K);
    if (b < 0) continue;
    double mf[3] = {-f[0], -f[1], -f[2]}, mK[9] = {-kk, 0, 0, 0, -kk, 0, 0, 0, -kk};
    fem_asm_add_force(v, b, mf);
    fem_asm_add_block(v, b, b, K);
    fem_asm_add_block(v, a, b, mK);
    fem_asm_add_block(v, b, a, mK);
  }
  return 0;
}

static int springs_candidates(void *ctx, const FemMesh *m, FemPairSink *sink) {
  (void)m;
  FemSolver *s = ctx;
  for (int k = 0; k < s->as.nsprings; k++)
    if (s->as.spring_nodes[2 * k + 1] >= 0)
      fem_pairs_add(sink, s->as.spring_nodes[2 * k], s->as.spring_nodes[2 * k + 1]);
  return 0;
}

int fem_solver_add_spring(FemSolver *s, int a, int b, double k) {
  SA_REQUIRE(a >= 0 && a < s->N && b >= -1 && b < s->N && a != b, SA_ERR_INPUT,
             "spring between nodes %d and %d: out of range or the same node", a, b);
  SA_REQUIRE(k > 0 && isfinite(k), SA_ERR_INPUT, "spring stiffness %g must be > 0", k);
  FemAssembly *as = &s->as;
  if (as->nsprings == 0) {
    FemContributor c = {"springs", springs_candidates, springs_eval, s, NULL};
    SA_CHECK(fem_solver_add_contributor(s, &c));
  }
  if (as->nsprings == as->cap_springs) {
    int cap = as->cap_springs ? 2 * as->cap_springs : 16;
    int *n = realloc(as->spring_nodes, 2 * (size_t)cap * sizeof *n);
    SA_REQUIRE(n, SA_ERR_MEMORY, "springs");
    as->spring_nodes = n;
    double *kk = realloc(as->spring_k, (size_t)cap * sizeof *kk);
    SA_REQUIRE(kk, SA_ERR_MEMORY, "springs");
    as->spring_k = kk;
    as->cap_springs = cap;
  }
  as->spring_nodes[2 * as->nsprings] = a;
  as->spring_nodes[2 * as->nsprings + 1] = b;
  as->spring_k[as->nsprings++] = k;
  return 0;
}

/* ------------------------------------------------------------------ bodies and pressure */

/* Kernel and scatter of one element (f_int and, if want_K, the tangent slots). */
static void elem_work(FemSolver *s, AsmBuf *bf, int e, const double *x, int want_K,
                      double *energy, double *min_detF, int *n_inv, int *n_dom) {
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
  FemLawCtx lc = {s->as.t_eval, s->as.dt_eval, e, -1,
                  s->as.edata ? s->as.edata + (size_t)e * s->as.nedata : NULL};
  int rc = fem_element_tl_ctx(m->etype, X, xe, &s->mats[r], &lc, s->as.hist_c + s->as.hoff[e],
                              bf->hist + s->as.hoff[e], want_K, &out);
  if (rc != 0 || !isfinite(out.energy)) {
    if (rc == SA_ERR_DOMAIN) (*n_dom)++;
    else (*n_inv)++;
    return;
  }
  *energy += out.energy;
  if (out.min_detF < *min_detF) *min_detF = out.min_detF;
  for (int a = 0; a < nen; a++)
    for (int k = 0; k < 3; k++) bf->fint[3 * c[a] + k] += out.fe[3 * a + k];
  if (!want_K) return;
  const int *ep = s->dm.epair + (size_t)e * nen * nen;
  for (int a = 0; a < nen; a++)
    for (int b = 0; b < nen; b++) {
      const int *sl = s->dm.slot9 + (size_t)ep[a * nen + b] * 9;
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
/* val += w * Ke, Ke the 3nfn x 3nfn block of pressure face f, through the face's node-pair slots
 * (the pattern's positions of its 3x3 blocks; -1 for constrained dofs). */
static void scatter_face_block(const FemSolver *s, int f, const double *Ke, double w, double *val) {
  int nfn = s->as.nfn, nfd = 3 * nfn;
  const int *fp = s->dm.fpair + (size_t)f * nfn * nfn;
  for (int a = 0; a < nfn; a++)
    for (int b = 0; b < nfn; b++) {
      const int *sl = s->dm.slot9 + (size_t)fp[a * nfn + b] * 9;
      const double *Kab = Ke + (size_t)(3 * a) * nfd + 3 * b;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          int k = sl[3 * i + j];
          if (k >= 0) val[k] += w * Kab[i * nfd + j];
        }
    }
}

static int assemble_once(FemSolver *s, AsmBuf *bf, const double *x, double p, int want_K) {
  double t0 = sa_time_now();
  memset(bf->fint, 0, (size_t)s->ndof * sizeof *bf->fint);
  if (want_K) memset(bf->val, 0, (size_t)s->dm.nnz * sizeof *bf->val);
  double energy = 0.0, min_detF = INFINITY;
  int n_inv = 0, n_dom = 0, T = s->prm.threads;
  /* slabs 0..T-1 share no node: one thread each; then the interface group serially */
#pragma omp parallel for num_threads(T) schedule(static, 1) reduction(+ : energy, n_inv, n_dom) \
    reduction(min : min_detF)
  for (int g = 0; g < T; g++)
    for (int k = s->dm.group_ptr[g]; k < s->dm.group_ptr[g + 1]; k++)
      elem_work(s, bf, s->dm.group_elem[k], x, want_K, &energy, &min_detF, &n_inv, &n_dom);
  for (int k = s->dm.group_ptr[T]; k < s->dm.group_ptr[T + 1]; k++)
    elem_work(s, bf, s->dm.group_elem[k], x, want_K, &energy, &min_detF, &n_inv, &n_dom);
  if (n_inv || n_dom) sa_error_clear();
  bf->energy = energy;
  bf->min_detF = min_detF;
  bf->n_inv = n_inv;
  bf->n_domain = n_dom;

  /* pressure faces: load per unit pressure q, its stiffness, enclosed volume and gradient */
  memset(bf->q, 0, (size_t)s->ndof * sizeof *bf->q);
  memset(bf->gv, 0, (size_t)s->ndof * sizeof *bf->gv);
  double V = 0.0;
  int nfn = s->as.nfn;
  for (int f = 0; f < s->as.npf; f++) {
    const int *c = s->as.pf + (size_t)f * nfn;
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
    scatter_face_block(s, f, Ke, p, bf->val);
  }
  bf->V = V;
  int crc = s->as.ncontrib ? eval_contributors(s, bf, x, want_K) : 0;
  double dt = sa_time_now() - t0;
  s->st.t_assemble += dt;
  s->st.n_assemble++;
  sa_timing_add("fem assemble", dt);
  if (crc < 0) return crc;
  if (n_inv) return SA_ERR_INVERTED;
  if (n_dom || crc > 0) {
    bf->n_domain += crc > 0;
    return SA_ERR_DOMAIN;
  }
  return 0;
}

/* Assembly into bf; when a contributor coupled a pair outside the pattern, rebuild the pattern
 * once and assemble again (the values of the first pass are laid out for the old pattern). */
int fem_asm_into(FemSolver *s, AsmBuf *bf, const double *x, double p, int want_K) {
  int rc = assemble_once(s, bf, x, p, want_K);
  if (s->as.nmissing == 0) return rc;
  int n = s->as.nmissing;
  s->as.nmissing = 0;
  SA_CHECK(fem_dofmap_rebuild(s, n, s->as.missing));
  if (bf == &s->as.rb) SA_CALLOC(s->as.rb.val, s->dm.nnz);
  else bf->val = s->as.val;
  rc = assemble_once(s, bf, x, p, want_K);
  SA_REQUIRE(s->as.nmissing == 0, SA_ERR_INTERNAL, "node pair missing after a pattern rebuild");
  return rc;
}

/* Newton's assembly: its own work arrays and the trial history; sets V and the element
 * statistics of the solver. */
int fem_asm_newton(FemSolver *s, const double *x, double p, int want_K) {
  AsmBuf bf = {s->as.fint, s->as.q, s->as.gv, s->as.fcon, s->as.val, s->as.hist_t, 0, 0, 0, 0, 0};
  int rc = fem_asm_into(s, &bf, x, p, want_K);
  if (want_K) s->st.n_assemble_tangent++;
  s->V = bf.V;
  s->as.energy = bf.energy;
  s->as.min_detF = bf.min_detF;
  s->as.n_inverted = bf.n_inv;
  s->as.n_domain = bf.n_domain;
  return rc;
}

/* Adds scale * K_q(x) (the follower pressure's load stiffness per unit pressure) to Newton's
 * tangent values: with scale = -(1 - beta) p it turns K_int + p K_q into K_int + beta p K_q
 * (FEM_INDEFINITE_MODIFY). Same face loop as the assembly; no allocation. */
void fem_asm_add_load_stiffness(FemSolver *s, const double *x, double scale) {
  int nfn = s->as.nfn;
  double t0 = sa_time_now();
  for (int f = 0; f < s->as.npf; f++) {
    const int *c = s->as.pf + (size_t)f * nfn;
    double xf[18], fe[18], Ke[324];
    for (int a = 0; a < nfn; a++)
      for (int k = 0; k < 3; k++) xf[3 * a + k] = x[3 * c[a] + k];
    fem_face_pressure(nfn, xf, 1.0, fe, Ke);
    scatter_face_block(s, f, Ke, scale, s->as.val);
  }
  s->st.t_assemble += sa_time_now() - t0;
}

/* Read-back assembly at the converged state: separate arrays, so a getter called between
 * solves changes nothing a later Newton iteration (or a reused factorisation) depends on. */
int fem_asm_readback(FemSolver *s, int want_K) {
  AsmBuf *bf = &s->as.rb;
  if (want_K && !bf->val) SA_CALLOC(bf->val, s->dm.nnz);
  int rc = fem_asm_into(s, bf, s->x, s->p, want_K);
  if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  if (rc) sa_error_clear();
  SA_REQUIRE(rc == 0, SA_ERR_NUMERICAL, "%s in the converged state",
             rc == SA_ERR_DOMAIN ? "law or contributor outside its domain" : "inverted elements");
  return 0;
}


/* History, lumped mass and the assembly targets (setup). */
int fem_asm_setup(FemSolver *s) {
  const FemMesh *m = s->m;
  int ne = m->nelem, nd = s->ndof;
  FemAssembly *as = &s->as;
  SA_CALLOC(as->hoff, ne + 1);
  for (int e = 0; e < ne; e++) {
    int r = m->region ? m->region[e] : 0;
    as->hoff[e + 1] = as->hoff[e] + s->nqp * s->mats[r].nhist;
  }
  SA_CALLOC(as->hist_c, as->hoff[ne]);
  SA_CALLOC(as->hist_t, as->hoff[ne]);
  SA_CALLOC(as->rb.hist, as->hoff[ne]);
  /* history starts where each law says (zeros without an init hook) */
  for (int e = 0; e < ne; e++) {
    const FemMaterial *mt = &s->mats[m->region ? m->region[e] : 0];
    if (!mt->law || !mt->law->init_hist || !mt->nhist) continue;
    for (int q = 0; q < s->nqp; q++) {
      size_t o = (size_t)as->hoff[e] + (size_t)q * mt->nhist;
      mt->law->init_hist(mt->par, as->hist_c + o);
      memcpy(as->hist_t + o, as->hist_c + o, (size_t)mt->nhist * sizeof *as->hist_c);
      memcpy(as->rb.hist + o, as->hist_c + o, (size_t)mt->nhist * sizeof *as->hist_c);
    }
  }
  double **v[] = {&as->fint, &as->q, &as->gv, &as->fdead, &as->rb.fint, &as->rb.q, &as->rb.gv};
  for (size_t i = 0; i < sizeof v / sizeof *v; i++) SA_CALLOC(*v[i], nd);
  if (as->ncontrib) {
    SA_CALLOC(as->fcon, nd);
    SA_CALLOC(as->rb.fcon, nd);
  }
  SA_CALLOC(as->val, s->dm.nnz);
  SA_CALLOC(as->mlump, s->N);
  /* lumped mass (gravity, dynamics) */
  double X[30], mm[10];
  for (int e = 0; e < ne; e++) {
    const int *c = m->conn + (size_t)e * s->nen;
    for (int a = 0; a < s->nen; a++)
      for (int k = 0; k < 3; k++) X[3 * a + k] = m->xyz[3 * c[a] + k];
    int r = m->region ? m->region[e] : 0;
    fem_element_lumped_mass_mat(m->etype, X, &s->mats[r], mm);
    for (int a = 0; a < s->nen; a++) as->mlump[c[a]] += mm[a];
  }
  return 0;
}

void fem_asm_free(FemAssembly *as) {
  void *p[] = {as->pf, as->hoff, as->hist_c, as->hist_t, as->fint, as->q, as->gv, as->fcon,
               as->fdead, as->val, as->mlump, as->rb.fint, as->rb.q, as->rb.gv, as->rb.fcon,
               as->rb.val, as->rb.hist, as->contrib, as->missing, as->spring_nodes, as->spring_k};
  for (size_t i = 0; i < sizeof p / sizeof *p; i++) free(p[i]);
}

int fem_solver_set_element_data(FemSolver *s, int ndata, const double *data) {
  SA_REQUIRE(ndata >= 0 && (ndata == 0 || data), SA_ERR_INPUT, "element data: %d values per "
             "element without data", ndata);
  s->as.nedata = ndata;
  s->as.edata = ndata ? data : NULL;
  return 0;
}

const double *fem_solver_history(const FemSolver *s, int e, int *nhist) {
  if (!s->setup_done || e < 0 || e >= s->m->nelem) return NULL;
  const FemMaterial *mt = &s->mats[s->m->region ? s->m->region[e] : 0];
  if (nhist) *nhist = mt->nhist;
  return s->as.hist_c + s->as.hoff[e];
}

const FemMaterial *fem_solver_material(const FemSolver *s, int r) {
  if (!s) return NULL;
  int nr = s->m->nregions > 0 ? s->m->nregions : 1;
  return r >= 0 && r < nr ? &s->mats[r] : NULL;
}

int fem_solver_set_history(FemSolver *s, int e, const double *hist) {
  SA_REQUIRE(s && s->setup_done, SA_ERR_INPUT, "fem_solver_set_history before fem_solver_setup");
  SA_REQUIRE(e >= 0 && e < s->m->nelem && hist, SA_ERR_INPUT, "fem_solver_set_history: element "
             "%d of %d", e, s->m->nelem);
  size_t o = (size_t)s->as.hoff[e], n = (size_t)(s->as.hoff[e + 1] - s->as.hoff[e]);
  SA_REQUIRE(n > 0, SA_ERR_INPUT, "fem_solver_set_history: element %d's material has no history",
             e);
  for (size_t k = 0; k < n; k++)
    SA_REQUIRE(isfinite(hist[k]), SA_ERR_INPUT, "fem_solver_set_history: element %d, value %zu "
               "is not finite", e, k);
  memcpy(s->as.hist_c + o, hist, n * sizeof *hist);
  memcpy(s->as.hist_t + o, hist, n * sizeof *hist);
  memcpy(s->as.rb.hist + o, hist, n * sizeof *hist);
  return 0;
}
