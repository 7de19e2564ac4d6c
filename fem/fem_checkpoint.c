/* fem_checkpoint.c - the solver's state to and from a stream (fem.h "Checkpoint"), for runs
 * that are stopped and resumed (the FEM-DEM coupling).
 *
 * Stored: displacements (current and last converged), the HHT velocities, accelerations and
 * r(u_n, t_n), the committed and target loads of the continuation (nodal forces, prescribed
 * displacements, gravity, pressure or volume) with its bookkeeping, the time, and the history
 * of every quadrature point. Not stored: the factorisation. Writing a checkpoint therefore
 * also drops the factors of the running solver, so that the run that goes on and the run that
 * resumes from the file take the same next Newton path (fresh factors) and stay identical. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_solver_priv.h"
#include "sa_error.h"

#define CK_MAGIC "SAFEMCK1"

typedef struct {
  char magic[8];
  int32_t ndof, nhist, control, step_count;
} CkHeader;

static int write_all(FILE *f, const void *p, size_t n) {
  return n == 0 || fwrite(p, 1, n, f) == n ? 0 : SA_ERROR(SA_ERR_IO, "checkpoint write failed");
}

static int read_all(FILE *f, void *p, size_t n, const char *what) {
  return n == 0 || fread(p, 1, n, f) == n
             ? 0
             : SA_ERROR(SA_ERR_INPUT, "checkpoint truncated while reading %s", what);
}

/* The state's vectors and scalars in one fixed order (both directions use it). */
static void state_vectors(FemSolver *s, double **v) {
  double *vv[] = {s->u,          s->u_last,    s->dy.v,    s->dy.acc,  s->dy.v_last,
                  s->dy.a_last,  s->dy.res_n,  s->ct.fn_c, s->ct.fn_t, s->ct.up_c,
                  s->ct.up_t};
  memcpy(v, vv, sizeof vv);
}
#define N_VEC 11

static void state_scalars(FemSolver *s, double **d) {
  double *dd[] = {&s->p,        &s->V,        &s->time,       &s->ct.p_c,    &s->ct.p_t,
                  &s->ct.V_c,   &s->ct.V_t,   &s->ct.g_c[0],  &s->ct.g_c[1], &s->ct.g_c[2],
                  &s->ct.g_t[0], &s->ct.g_t[1], &s->ct.g_t[2], &s->ct.V_goal, &s->ct.V_last,
                  &s->ct.V_prev, &s->ct.p_last, &s->ct.p_prev, &s->ct.lam_total,
                  &s->ct.dl_keep, &s->ct.slope0, &s->ct.static_dt};
  memcpy(d, dd, sizeof dd);
}
#define N_SCAL 22

int fem_solver_write_state(FemSolver *s, FILE *f) {
  SA_REQUIRE(s && s->setup_done && f, SA_ERR_INPUT, "fem_solver_write_state: no solver set up");
  CkHeader h;
  memcpy(h.magic, CK_MAGIC, 8);
  h.ndof = s->ndof, h.nhist = s->as.hoff[s->m->nelem], h.control = (int32_t)s->ct.control;
  h.step_count = s->ct.step_count;
  SA_CHECK(write_all(f, &h, sizeof h));
  double *v[N_VEC], *d[N_SCAL];
  state_vectors(s, v);
  state_scalars(s, d);
  for (int k = 0; k < N_VEC; k++) SA_CHECK(write_all(f, v[k], sizeof(double) * (size_t)s->ndof));
  for (int k = 0; k < N_SCAL; k++) SA_CHECK(write_all(f, d[k], sizeof(double)));
  SA_CHECK(write_all(f, s->as.hist_c, sizeof(double) * (size_t)h.nhist));
  s->nw.fact_converged = 0; /* both runs refactorise next (see the top of the file) */
  return 0;
}

int fem_solver_read_state(FemSolver *s, FILE *f, const char *name) {
  SA_REQUIRE(s && s->setup_done && f, SA_ERR_INPUT, "fem_solver_read_state: no solver set up");
  CkHeader h;
  SA_CHECK(read_all(f, &h, sizeof h, "the header"));
  SA_REQUIRE(!memcmp(h.magic, CK_MAGIC, 8), SA_ERR_INPUT, "%s is not a softact FEM checkpoint",
             name);
  SA_REQUIRE(h.ndof == s->ndof && h.nhist == s->as.hoff[s->m->nelem], SA_ERR_INPUT,
             "%s was written for another model (%d dofs, %d history values; this one has %d and "
             "%d): same mesh and materials needed", name, (int)h.ndof, (int)h.nhist, s->ndof,
             s->as.hoff[s->m->nelem]);
  SA_REQUIRE(h.control == (int32_t)s->ct.control, SA_ERR_INPUT,
             "%s was written under another control mode", name);
  double *v[N_VEC], *d[N_SCAL];
  state_vectors(s, v);
  state_scalars(s, d);
  for (int k = 0; k < N_VEC; k++)
    SA_CHECK(read_all(f, v[k], sizeof(double) * (size_t)s->ndof, "the state vectors"));
  for (int k = 0; k < N_SCAL; k++) SA_CHECK(read_all(f, d[k], sizeof(double), "the scalars"));
  SA_CHECK(read_all(f, s->as.hist_c, sizeof(double) * (size_t)h.nhist, "the history"));
  memcpy(s->as.hist_t, s->as.hist_c, sizeof(double) * (size_t)h.nhist);
  s->ct.step_count = h.step_count;
  fem_set_x(s);
  s->nw.fact_converged = 0;
  return 0;
}

/* In-memory snapshot: the same state as the checkpoint, for a coupling step that is iterated
 * (rolled back and solved again). The factors are kept: a rolled-back solve reuses them as
 * its modified-Newton iteration matrix, which changes the path, not the converged answer. */
struct FemSnapshot {
  size_t ndof, nhist;
  double *data;
  int step_count;
};

int fem_solver_snapshot(FemSolver *s, FemSnapshot **snap) {
  SA_REQUIRE(s && s->setup_done && snap, SA_ERR_INPUT, "fem_solver_snapshot: no solver set up");
  size_t ndof = (size_t)s->ndof, nhist = (size_t)s->as.hoff[s->m->nelem];
  if (!*snap) {
    FemSnapshot *p;
    SA_CALLOC(p, 1);
    p->ndof = ndof, p->nhist = nhist;
    p->data = malloc(sizeof(double) * (N_VEC * ndof + N_SCAL + nhist));
    if (!p->data) {
      free(p);
      return SA_ERROR(SA_ERR_MEMORY, "FEM snapshot (%zu dofs)", ndof);
    }
    *snap = p;
  }
  FemSnapshot *p = *snap;
  SA_REQUIRE(p->ndof == ndof && p->nhist == nhist, SA_ERR_INTERNAL, "snapshot of another model");
  double *v[N_VEC], *d[N_SCAL], *w = p->data;
  state_vectors(s, v);
  state_scalars(s, d);
  for (int k = 0; k < N_VEC; k++, w += ndof) memcpy(w, v[k], sizeof(double) * ndof);
  for (int k = 0; k < N_SCAL; k++) *w++ = *d[k];
  memcpy(w, s->as.hist_c, sizeof(double) * nhist);
  p->step_count = s->ct.step_count;
  return 0;
}

int fem_solver_rollback(FemSolver *s, const FemSnapshot *p) {
  SA_REQUIRE(s && s->setup_done && p && p->ndof == (size_t)s->ndof &&
             p->nhist == (size_t)s->as.hoff[s->m->nelem], SA_ERR_INTERNAL,
             "fem_solver_rollback: no snapshot of this solver");
  double *v[N_VEC], *d[N_SCAL];
  const double *w = p->data;
  state_vectors(s, v);
  state_scalars(s, d);
  for (int k = 0; k < N_VEC; k++, w += p->ndof) memcpy(v[k], w, sizeof(double) * p->ndof);
  for (int k = 0; k < N_SCAL; k++) *d[k] = *w++;
  memcpy(s->as.hist_c, w, sizeof(double) * p->nhist);
  memcpy(s->as.hist_t, s->as.hist_c, sizeof(double) * p->nhist);
  s->ct.step_count = p->step_count;
  fem_set_x(s);
  return 0;
}

void fem_snapshot_destroy(FemSnapshot **p) {
  if (!p || !*p) return;
  free((*p)->data);
  free(*p);
  *p = NULL;
}
