/* fem_dofmap.c - dof numbering (node-major, fixed dofs excluded), the node-pair graph (element
 * connectivity plus the contributors' pairs), the free-dof CSC pattern (full, sorted) with its
 * slot maps (9 slots per node pair, -1 for a fixed dof; per element and per pressure face the
 * node-pair indices, so assembly is a scatter without search), the element partition of the
 * threaded assembly, and the linear solver that borrows the pattern. All of it is symbolic work
 * done in setup; fem_dofmap_rebuild repeats it (new cholmod_analyze) only when a contributor
 * couples a pair outside the pattern. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_solver_priv.h"
#include "sa_error.h"
#include "sa_log.h"

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
  /* contributors' node pairs beyond the elements, both directions */
  int ne2 = s->dm.npairs_extra, *x2e_ptr, *x2e, *xcnt;
  SA_CALLOC(x2e_ptr, N + 1);
  SA_CALLOC(x2e, 2 * (size_t)ne2);
  SA_CALLOC(xcnt, N);
  for (int k = 0; k < ne2; k++) {
    x2e_ptr[s->dm.extra[2 * k] + 1]++;
    x2e_ptr[s->dm.extra[2 * k + 1] + 1]++;
  }
  for (int i = 0; i < N; i++) x2e_ptr[i + 1] += x2e_ptr[i];
  for (int k = 0; k < ne2; k++) {
    int A = s->dm.extra[2 * k], B = s->dm.extra[2 * k + 1];
    x2e[x2e_ptr[A] + xcnt[A]++] = B;
    x2e[x2e_ptr[B] + xcnt[B]++] = A;
  }
  for (int i = 0; i < N; i++) mark[i] = -1;
  /* two passes: count, then fill */
  SA_CALLOC(s->dm.adj_ptr, N + 1);
  for (int pass = 0; pass < 2; pass++) {
    for (int i = 0; i < N; i++) mark[i] = -1;
    for (int B = 0; B < N; B++) {
      int k = 0;
      for (int t = n2e_ptr[B]; t < n2e_ptr[B + 1]; t++) {
        const int *c = m->conn + (size_t)n2e[t] * nen;
        for (int a = 0; a < nen; a++)
          if (mark[c[a]] != B) {
            mark[c[a]] = B;
            if (pass) s->dm.adj[s->dm.adj_ptr[B] + k] = c[a];
            k++;
          }
      }
      if (mark[B] != B) { /* a node in no element (kept in the pattern: its own block) */
        mark[B] = B;
        if (pass) s->dm.adj[s->dm.adj_ptr[B] + k] = B;
        k++;
      }
      for (int t = x2e_ptr[B]; t < x2e_ptr[B + 1]; t++)
        if (mark[x2e[t]] != B) {
          mark[x2e[t]] = B;
          if (pass) s->dm.adj[s->dm.adj_ptr[B] + k] = x2e[t];
          k++;
        }
      if (!pass) s->dm.adj_ptr[B + 1] = k;
      else qsort(s->dm.adj + s->dm.adj_ptr[B], (size_t)k, sizeof(int), cmp_int);
    }
    if (!pass) {
      for (int i = 0; i < N; i++) s->dm.adj_ptr[i + 1] += s->dm.adj_ptr[i];
      SA_CALLOC(s->dm.adj, s->dm.adj_ptr[N]);
    }
  }
  free(n2e_ptr);
  free(n2e);
  free(mark);
  free(cnt);
  free(x2e_ptr);
  free(x2e);
  free(xcnt);
  return 0;
}

/* Free-dof CSC pattern (full, sorted) + slot map per node pair (9 entries, -1 = constrained). */
static int number_dofs(FemSolver *s) {
  SA_CALLOC(s->dm.eq, s->ndof);
  int nf = 0;
  for (int A = 0; A < s->N; A++)
    for (int c = 0; c < 3; c++) s->dm.eq[3 * A + c] = (s->dm.fixmask[A] >> c & 1) ? -1 : nf++;
  s->dm.nfree = nf;
  SA_REQUIRE(nf > 0, SA_ERR_INPUT, "every degree of freedom is fixed");
  return 0;
}

static int build_pattern(FemSolver *s) {
  int N = s->N, nf = s->dm.nfree;
  SA_CALLOC(s->dm.colptr, nf + 1);
  SA_CALLOC(s->dm.diag, nf);
  long npairs = s->dm.adj_ptr[N];
  SA_CALLOC(s->dm.slot9, (size_t)npairs * 9);
  for (long k = 0; k < npairs * 9; k++) s->dm.slot9[k] = -1;
  long nnz = 0;
  for (int B = 0; B < N; B++)
    for (int j = 0; j < 3; j++) {
      if (s->dm.eq[3 * B + j] < 0) continue;
      for (int t = s->dm.adj_ptr[B]; t < s->dm.adj_ptr[B + 1]; t++) {
        int A = s->dm.adj[t];
        for (int i = 0; i < 3; i++)
          if (s->dm.eq[3 * A + i] >= 0) nnz++;
      }
    }
  SA_REQUIRE(nnz < 2147483647L, SA_ERR_INPUT, "tangent too large for 32-bit indices");
  s->dm.nnz = nnz;
  SA_CALLOC(s->dm.rowind, nnz);
  long k = 0;
  for (int B = 0; B < N; B++)
    for (int j = 0; j < 3; j++) {
      int col = s->dm.eq[3 * B + j];
      if (col < 0) continue;
      s->dm.colptr[col] = (int)k;
      for (int t = s->dm.adj_ptr[B]; t < s->dm.adj_ptr[B + 1]; t++) {
        int A = s->dm.adj[t];
        for (int i = 0; i < 3; i++) {
          int row = s->dm.eq[3 * A + i];
          if (row < 0) continue;
          if (row == col) s->dm.diag[col] = (int)k;
          s->dm.slot9[(size_t)t * 9 + 3 * i + j] = (int)k;
          s->dm.rowind[k++] = row;
        }
      }
    }
  s->dm.colptr[nf] = (int)k;
  return 0;
}

/* Pair index (row node A, column node B) of every element / face node pair. */
static int build_pair_maps(FemSolver *s) {
  const FemMesh *m = s->m;
  int nen = s->nen;
  SA_CALLOC(s->dm.epair, (size_t)m->nelem * nen * nen);
  for (int e = 0; e < m->nelem; e++) {
    const int *c = m->conn + (size_t)e * nen;
    for (int a = 0; a < nen; a++)
      for (int b = 0; b < nen; b++) {
        int t = find_sorted(s->dm.adj, s->dm.adj_ptr[c[b]], s->dm.adj_ptr[c[b] + 1], c[a]);
        SA_REQUIRE(t >= 0, SA_ERR_INTERNAL, "node pair missing from the graph");
        s->dm.epair[((size_t)e * nen + a) * nen + b] = t;
      }
  }
  int nfn = s->as.nfn;
  SA_CALLOC(s->dm.fpair, (size_t)s->as.npf * nfn * nfn);
  for (int f = 0; f < s->as.npf; f++) {
    const int *c = s->as.pf + (size_t)f * nfn;
    for (int a = 0; a < nfn; a++)
      for (int b = 0; b < nfn; b++) {
        int t = find_sorted(s->dm.adj, s->dm.adj_ptr[c[b]], s->dm.adj_ptr[c[b] + 1], c[a]);
        SA_REQUIRE(t >= 0, SA_ERR_INPUT, "pressure face node pair not in one element");
        s->dm.fpair[((size_t)f * nfn + a) * nfn + b] = t;
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

int fem_dofmap_partition(FemSolver *s) {
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
  s->dm.ngroups = T + 1;
  SA_CALLOC(s->dm.group_ptr, T + 2);
  SA_CALLOC(s->dm.group_elem, ne);
  for (int e = 0; e < ne; e++) s->dm.group_ptr[grp[e] + 1]++;
  for (int k = 0; k <= T; k++) s->dm.group_ptr[k + 1] += s->dm.group_ptr[k];
  int *fill;
  SA_CALLOC(fill, T + 1);
  for (int e = 0; e < ne; e++) s->dm.group_elem[s->dm.group_ptr[grp[e]] + fill[grp[e]]++] = e;
  free(fill);
  free(ek);
  free(owner);
  free(grp);
  return 0;
}


int fem_dofmap_find_pair(const FemSolver *s, int A, int B) {
  return find_sorted(s->dm.adj, s->dm.adj_ptr[B], s->dm.adj_ptr[B + 1], A);
}

static void free_pattern(FemDofMap *dm) {
  fem_linsolve_destroy(&dm->lin);
  void *p[] = {dm->colptr, dm->rowind, dm->diag, dm->adj_ptr, dm->adj, dm->slot9, dm->epair,
               dm->fpair};
  for (size_t i = 0; i < sizeof p / sizeof *p; i++) free(p[i]);
  dm->colptr = dm->rowind = dm->diag = dm->adj_ptr = dm->adj = dm->slot9 = dm->epair =
      dm->fpair = NULL;
}

static int add_extra(FemDofMap *dm, int A, int B) {
  if (dm->npairs_extra == dm->cap_extra) {
    int cap = dm->cap_extra ? 2 * dm->cap_extra : 64;
    int *e = realloc(dm->extra, 2 * (size_t)cap * sizeof *e);
    SA_REQUIRE(e, SA_ERR_MEMORY, "cannot grow the contributor pair list");
    dm->extra = e;
    dm->cap_extra = cap;
  }
  dm->extra[2 * dm->npairs_extra] = A;
  dm->extra[2 * dm->npairs_extra + 1] = B;
  dm->npairs_extra++;
  return 0;
}

static int build_all(FemSolver *s) {
  SA_CHECK(build_node_graph(s));
  SA_CHECK(build_pattern(s));
  SA_CHECK(build_pair_maps(s));
  SA_CHECK(fem_linsolve_create(s->dm.nfree, s->dm.colptr, s->dm.rowind, s->prm.threads,
                               &s->dm.lin));
  return 0;
}

/* Bodies (connected components of the node graph, contributors' pairs included) that nothing
 * holds: no fixed dof and no ground spring in the component. Their tangent is singular until a
 * contact or a coupling holds them; say so now, in words, instead of failing later in CHOLMOD
 * or UMFPACK. Fills s->dm.floating_msg (empty if every body is held). */
static int diagnose_floating(FemSolver *s) {
  int N = s->N, *comp, *held, *stack, ncomp = 0;
  SA_CALLOC(comp, N);
  SA_CALLOC(stack, N);
  for (int i = 0; i < N; i++) comp[i] = -1;
  for (int i = 0; i < N; i++) {
    if (comp[i] >= 0) continue;
    int top = 0;
    stack[top++] = i;
    comp[i] = ncomp;
    while (top) {
      int B = stack[--top];
      for (int t = s->dm.adj_ptr[B]; t < s->dm.adj_ptr[B + 1]; t++)
        if (comp[s->dm.adj[t]] < 0) comp[s->dm.adj[t]] = ncomp, stack[top++] = s->dm.adj[t];
    }
    ncomp++;
  }
  held = calloc((size_t)ncomp, sizeof *held);
  int *size = calloc((size_t)ncomp, sizeof *size), *first = malloc((size_t)ncomp * sizeof *first);
  if (!held || !size || !first) {
    free(comp), free(stack), free(held), free(size), free(first);
    return SA_ERROR(SA_ERR_MEMORY, "floating-body diagnosis");
  }
  for (int i = 0; i < N; i++) {
    if (s->dm.fixmask[i]) held[comp[i]] = 1;
    if (size[comp[i]]++ == 0) first[comp[i]] = i;
  }
  for (int k = 0; k < s->as.nsprings; k++)
    if (s->as.spring_nodes[2 * k + 1] < 0) held[comp[s->as.spring_nodes[2 * k]]] = 1;
  s->dm.nfloating = 0;
  s->dm.floating_msg[0] = '\0';
  size_t len = 0;
  for (int c = 0; c < ncomp; c++) {
    if (held[c]) continue;
    s->dm.nfloating++;
    const double *X = s->m->xyz + 3 * (size_t)first[c];
    if (len < sizeof s->dm.floating_msg - 1)
      len += (size_t)snprintf(s->dm.floating_msg + len, sizeof s->dm.floating_msg - len,
                              "%sbody of %d node(s) containing node %d at (%g, %g, %g)",
                              len ? "; " : "", size[c], first[c], X[0], X[1], X[2]);
  }
  if (s->dm.nfloating)
    sa_log(SA_LOG_WARN, "fem", "%d floating body/bodies: %s: no fixed dof and no contributor "
           "ties it to a supported body, so the tangent is singular until contact holds it "
           "(fix dofs, or hold it with weak springs: fem_solver_add_spring(s, node, -1, k))",
           s->dm.nfloating, s->dm.floating_msg);
  free(comp), free(stack), free(held), free(size), free(first);
  return 0;
}

int fem_dofmap_build(FemSolver *s) {
  int *pairs = NULL, np = 0;
  SA_CHECK(number_dofs(s));
  SA_CHECK(fem_asm_candidate_pairs(s, &pairs, &np));
  for (int k = 0; k < np; k++) {
    int rc = add_extra(&s->dm, pairs[2 * k], pairs[2 * k + 1]);
    if (rc) {
      free(pairs);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
  }
  free(pairs);
  SA_CHECK(build_all(s));
  SA_CHECK(diagnose_floating(s));
  return 0;
}

int fem_dofmap_rebuild(FemSolver *s, int npairs, const int *pairs) {
  double t0 = sa_time_now();
  for (int k = 0; k < npairs; k++) SA_CHECK(add_extra(&s->dm, pairs[2 * k], pairs[2 * k + 1]));
  free_pattern(&s->dm);
  SA_CHECK(build_all(s));
  SA_CHECK(diagnose_floating(s));
  /* everything sized or indexed by the old pattern */
  free(s->as.val);
  SA_CALLOC(s->as.val, s->dm.nnz);
  free(s->as.rb.val);
  s->as.rb.val = NULL;
  s->nw.fact_converged = s->nw.have_factors = 0; /* the factors went with the old solver */
  s->dm.n_rebuilds++;
  FemLinInfo li;
  fem_linsolve_info(s->dm.lin, &li);
  s->st.nnz_k = s->dm.nnz;
  s->st.nnz_l = li.nnz_l;
  s->st.n_pattern_rebuilds = s->dm.n_rebuilds;
  double dt = sa_time_now() - t0;
  s->st.t_symbolic += dt;
  sa_log(SA_LOG_INFO, "fem", "pattern rebuilt for %d new node pair(s): nnz(K) %ld, nnz(L) %.3g, "
         "%.3f s (rebuild %d)", npairs, s->dm.nnz, li.nnz_l, dt, s->dm.n_rebuilds);
  return 0;
}

void fem_dofmap_free(FemDofMap *dm) {
  free_pattern(dm);
  free(dm->fixmask);
  free(dm->eq);
  free(dm->group_ptr);
  free(dm->group_elem);
  free(dm->extra);
}
