/* dem_iqn.c - IQN-ILS for the iterated coupling step (dem_iqn.h). */
#include "dem_iqn.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

/* a column is dropped when orthogonalising it against the newer ones leaves less than this
 * fraction of its length (QR2 filter of Haelterman et al. 2016): it adds noise, not a direction */
#define FILTER 1e-2

struct DemIqn {
  int n, max_cols, reuse, ncols, step, have_prev;
  double w0; /* relaxation of the update without columns */
  double *V, *W;    /* columns, newest first: V[c * n], W[c * n] */
  int *col_step;    /* the step each column was made in */
  double *r_prev, *xt_prev;
  double *Q, *R, *rhs, *c; /* least-squares work: Q n x max_cols, R max_cols^2 */
  int *keep;
};

int dem_iqn_create(int n, int max_cols, int reuse_steps, DemIqn **out) {
  SA_REQUIRE(out && n > 0 && max_cols > 0 && reuse_steps >= 0, SA_ERR_INTERNAL,
             "dem_iqn_create: bad arguments");
  *out = NULL;
  DemIqn *q;
  SA_CALLOC(q, 1);
  q->n = n, q->max_cols = max_cols, q->reuse = reuse_steps, q->w0 = 1;
  size_t nc = (size_t)n * (size_t)max_cols;
  q->V = malloc(sizeof(double) * nc), q->W = malloc(sizeof(double) * nc);
  q->Q = malloc(sizeof(double) * nc);
  q->R = malloc(sizeof(double) * (size_t)max_cols * (size_t)max_cols);
  q->rhs = malloc(sizeof(double) * (size_t)max_cols), q->c = malloc(sizeof(double) * (size_t)max_cols);
  q->col_step = malloc(sizeof(int) * (size_t)max_cols), q->keep = malloc(sizeof(int) * (size_t)max_cols);
  q->r_prev = malloc(sizeof(double) * (size_t)n), q->xt_prev = malloc(sizeof(double) * (size_t)n);
  if (!q->V || !q->W || !q->Q || !q->R || !q->rhs || !q->c || !q->col_step || !q->keep ||
      !q->r_prev || !q->xt_prev) {
    dem_iqn_destroy(&q);
    return SA_ERROR(SA_ERR_MEMORY, "quasi-Newton columns (%d x %d)", n, max_cols);
  }
  *out = q;
  return 0;
}

void dem_iqn_destroy(DemIqn **pq) {
  if (!pq || !*pq) return;
  DemIqn *q = *pq;
  free(q->V), free(q->W), free(q->Q), free(q->R), free(q->rhs), free(q->c);
  free(q->col_step), free(q->keep), free(q->r_prev), free(q->xt_prev);
  free(q);
  *pq = NULL;
}

int dem_iqn_columns(const DemIqn *q) { return q ? q->ncols : 0; }

void dem_iqn_set_initial_relaxation(DemIqn *q, double w) { q->w0 = w; }

/* Keep the columns with keep[c] set, in their order. */
static void compact(DemIqn *q) {
  int k = 0;
  size_t n = (size_t)q->n;
  for (int c = 0; c < q->ncols; c++) {
    if (!q->keep[c]) continue;
    if (k != c) {
      memmove(q->V + k * n, q->V + c * n, sizeof(double) * n);
      memmove(q->W + k * n, q->W + c * n, sizeof(double) * n);
      q->col_step[k] = q->col_step[c];
    }
    k++;
  }
  q->ncols = k;
}

void dem_iqn_new_step(DemIqn *q) {
  q->step++;
  q->have_prev = 0;
  for (int c = 0; c < q->ncols; c++) q->keep[c] = q->step - q->col_step[c] <= q->reuse;
  compact(q);
}

void dem_iqn_clear(DemIqn *q) {
  q->ncols = 0;
  q->have_prev = 0;
}

static double dot(const double *a, const double *b, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* New column (newest first); the oldest falls off when full. */
static void push_column(DemIqn *q, const double *r, const double *xt) {
  size_t n = (size_t)q->n;
  int m = q->ncols < q->max_cols ? q->ncols : q->max_cols - 1;
  memmove(q->V + n, q->V, sizeof(double) * n * (size_t)m);
  memmove(q->W + n, q->W, sizeof(double) * n * (size_t)m);
  memmove(q->col_step + 1, q->col_step, sizeof(int) * (size_t)m);
  for (size_t i = 0; i < n; i++) q->V[i] = r[i] - q->r_prev[i], q->W[i] = xt[i] - q->xt_prev[i];
  q->col_step[0] = q->step;
  q->ncols = m + 1;
}

/* Modified Gram-Schmidt QR of V (newest first), dropping filtered columns for good. */
static void factor(DemIqn *q) {
  int n = q->n, k = 0;
  for (int c = 0; c < q->ncols; c++) {
    double *v = q->V + (size_t)c * n, *qk = q->Q + (size_t)k * n;
    memcpy(qk, v, sizeof(double) * (size_t)n);
    double len0 = sqrt(dot(v, v, n));
    for (int j = 0; j < k; j++) {
      double *qj = q->Q + (size_t)j * n, h = dot(qj, qk, n);
      q->R[j * q->max_cols + k] = h;
      for (int i = 0; i < n; i++) qk[i] -= h * qj[i];
    }
    double len = sqrt(dot(qk, qk, n));
    q->keep[c] = len0 > 0 && len > FILTER * len0;
    if (!q->keep[c]) continue;
    q->R[k * q->max_cols + k] = len;
    for (int i = 0; i < n; i++) qk[i] /= len;
    k++;
  }
  compact(q);
}

int dem_iqn_update(DemIqn *q, const double *x, const double *xt, double *x_next) {
  int n = q->n;
  double *r = x_next; /* r = xt - x, kept in x_next until the update */
  for (int i = 0; i < n; i++) r[i] = xt[i] - x[i];
  if (q->have_prev) push_column(q, r, xt);
  memcpy(q->r_prev, r, sizeof(double) * (size_t)n);
  memcpy(q->xt_prev, xt, sizeof(double) * (size_t)n);
  q->have_prev = 1;
  if (q->ncols) factor(q);
  int m = q->ncols, ld = q->max_cols;
  /* R c = -Q^T r, back substitution */
  for (int j = 0; j < m; j++) q->rhs[j] = -dot(q->Q + (size_t)j * n, r, n);
  for (int j = m - 1; j >= 0; j--) {
    double s = q->rhs[j];
    for (int l = j + 1; l < m; l++) s -= q->R[j * ld + l] * q->c[l];
    q->c[j] = s / q->R[j * ld + j];
  }
  if (m == 0 && q->w0 != 1) { /* no model: relaxed substitution (w = 1: xt itself, exactly) */
    for (int i = 0; i < n; i++) x_next[i] = x[i] + q->w0 * (xt[i] - x[i]);
    return 0;
  }
  memcpy(x_next, xt, sizeof(double) * (size_t)n);
  for (int j = 0; j < m; j++) {
    const double *w = q->W + (size_t)j * n;
    for (int i = 0; i < n; i++) x_next[i] += q->c[j] * w[i];
  }
  return 0;
}

double dem_iqn_limit_step(const double *x, double *x_next, int n, double max_change) {
  if (!(max_change > 0)) return 1;
  double m2 = 0;
  for (int v = 0; v + 2 < n; v += 3) {
    double e2 = 0;
    for (int d = 0; d < 3; d++) e2 += (x_next[v + d] - x[v + d]) * (x_next[v + d] - x[v + d]);
    if (e2 > m2) m2 = e2;
  }
  double m = sqrt(m2);
  if (!(m > max_change)) return 1;
  double f = max_change / m;
  for (int i = 0; i < n; i++) x_next[i] = x[i] + f * (x_next[i] - x[i]);
  return f;
}
