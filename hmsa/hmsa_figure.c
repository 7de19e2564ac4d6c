/* hmsa_figure.c - decimation of long histories for plotting and multi-panel gnuplot figures
 * with a shared legend (see hmsa_figure.h). */
#include "hmsa_figure.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_plot.h"

/* ------------------------------------------------------------------ decimation */

#define DEC_MAX_COLS 16

struct HmsaDecimator {
  long n_rows, bin_size, row; /* rows expected, rows per bin, next row index */
  int ncols;
  unsigned track;
  SaCsv *out;
  long kept;
  /* the current bin: candidate rows (first, last, argmin/argmax per tracked column) */
  long cand_idx[2 + 2 * DEC_MAX_COLS];
  double cand[2 + 2 * DEC_MAX_COLS][DEC_MAX_COLS];
  int in_bin;                     /* rows of the current bin seen so far */
};

int hmsa_decimator_create(long n_rows, int ncols, int n_bins, unsigned track, SaCsv *out,
                          HmsaDecimator **d) {
  *d = NULL;
  SA_REQUIRE(n_rows >= 1 && n_bins >= 1, SA_ERR_INPUT, "decimator: %ld rows, %d bins", n_rows,
             n_bins);
  SA_REQUIRE(ncols >= 1 && ncols <= DEC_MAX_COLS, SA_ERR_INPUT, "decimator: %d columns", ncols);
  HmsaDecimator *x;
  SA_CALLOC(x, 1);
  x->n_rows = n_rows;
  x->bin_size = (n_rows + n_bins - 1) / n_bins;
  x->ncols = ncols;
  x->track = track & ((1u << ncols) - 1u);
  x->out = out;
  *d = x;
  return 0;
}

/* Candidate slots: 0 first, 1 last, 2 + 2j min of column j, 3 + 2j max of column j. */
static int dec_flush(HmsaDecimator *d) {
  if (!d->in_bin) return 0;
  int ns = 2 + 2 * d->ncols, order[2 + 2 * DEC_MAX_COLS], n = 0;
  for (int s = 0; s < ns; s++) {
    if (s >= 2 && !(d->track & (1u << ((s - 2) / 2)))) continue;
    int dup = 0;
    for (int k = 0; k < n; k++)
      if (d->cand_idx[order[k]] == d->cand_idx[s]) dup = 1;
    if (!dup) order[n++] = s;
  }
  for (int i = 1; i < n; i++) /* insertion sort by row index (n <= 34) */
    for (int k = i; k > 0 && d->cand_idx[order[k - 1]] > d->cand_idx[order[k]]; k--) {
      int t = order[k];
      order[k] = order[k - 1];
      order[k - 1] = t;
    }
  for (int k = 0; k < n; k++) SA_CHECK(sa_csv_row(d->out, d->cand[order[k]]));
  d->kept += n;
  d->in_bin = 0;
  return 0;
}

static void dec_take(HmsaDecimator *d, int slot, const double *row) {
  d->cand_idx[slot] = d->row;
  memcpy(d->cand[slot], row, sizeof(double) * (size_t)d->ncols);
}

int hmsa_decimator_push(HmsaDecimator *d, const double *row) {
  if (d->in_bin == 0) {
    for (int s = 0; s < 2 + 2 * d->ncols; s++) dec_take(d, s, row);
  } else {
    dec_take(d, 1, row);
    for (int j = 0; j < d->ncols; j++) {
      if (!(d->track & (1u << j))) continue;
      if (row[j] < d->cand[2 + 2 * j][j]) dec_take(d, 2 + 2 * j, row);
      if (row[j] > d->cand[3 + 2 * j][j]) dec_take(d, 3 + 2 * j, row);
    }
  }
  d->row++;
  if (++d->in_bin >= d->bin_size) SA_CHECK(dec_flush(d));
  return 0;
}

int hmsa_decimator_finish(HmsaDecimator *d) { return dec_flush(d); }

long hmsa_decimator_kept(const HmsaDecimator *d) { return d->kept; }

void hmsa_decimator_destroy(HmsaDecimator **d) {
  if (!d) return;
  free(*d);
  *d = NULL;
}

/* ------------------------------------------------------------------ figures */

/* Okabe-Ito colours (distinguishable with the common colour-vision deficiencies), then black */
static const char *const palette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                      "#E69F00", "#56B4E9", "#000000", "#7F7F7F"};

void hmsa_figure_init(HmsaFigure *f) {
  memset(f, 0, sizeof *f);
  f->rows = f->cols = 1;
  f->npanels = 1;
  f->xr[0] = f->xr[1] = f->yr[0] = f->yr[1] = NAN;
}

void hmsa_figure_curve(HmsaFigure *f, int p, const char *data, const char *using, int color,
                       HmsaCurveKind kind) {
  if (p < 0 || p >= HMSA_FIG_MAX_PANELS) return;
  HmsaPanel *P = &f->panel[p];
  if (P->n >= HMSA_FIG_MAX_CURVES) return;
  HmsaCurve *c = &P->c[P->n++];
  snprintf(c->data, sizeof c->data, "%s", data);
  snprintf(c->using, sizeof c->using, "%s", using);
  c->color = color;
  c->kind = kind;
  if (p >= f->npanels) f->npanels = p + 1;
}

void hmsa_figure_legend(HmsaFigure *f, const char *text, int color, HmsaCurveKind kind) {
  for (int i = 0; i < f->nlegend; i++)
    if (!strcmp(f->legend[i].text, text)) return;
  if (f->nlegend >= HMSA_FIG_MAX_LEGEND) return;
  HmsaLegend *l = &f->legend[f->nlegend++];
  snprintf(l->text, sizeof l->text, "%s", text);
  l->color = color;
  l->kind = kind;
}

static void put_quoted(FILE *f, const char *s) {
  fputc('\'', f);
  for (; *s; s++) {
    if (*s == '\n' || *s == '\r') continue;
    if (*s == '\'') fputc('\'', f);
    fputc(*s, f);
  }
  fputc('\'', f);
}

static void put_style(FILE *f, int color, HmsaCurveKind kind) {
  const char *c = color < 0 ? palette[7] : palette[color % 8];
  switch (kind) {
  case HMSA_CURVE_DASH: fprintf(f, "with lines lw 2 dt (8,5) lc rgb '%s'", c); break;
  case HMSA_CURVE_THIN: fprintf(f, "with lines lw 1 lc rgb '%s'", c); break;
  case HMSA_CURVE_POINTS: fprintf(f, "with points pt 7 ps 1.6 lc rgb '%s'", c); break;
  case HMSA_CURVE_OPEN: fprintf(f, "with points pt 6 ps 1.7 lw 2 lc rgb '%s'", c); break;
  case HMSA_CURVE_DOTS: fprintf(f, "with points pt 7 ps 0.55 lc rgb '%s'", c); break;
  case HMSA_CURVE_LINEPOINTS: fprintf(f, "with linespoints lw 1.5 pt 7 ps 0.45 lc rgb '%s'", c); break;
  case HMSA_CURVE_MARK: fprintf(f, "with points pt 2 ps 1.8 lw 2 lc rgb '%s'", c); break;
  case HMSA_CURVE_REF: fprintf(f, "with lines lw 1.5 dt (2,4) lc rgb '%s'", palette[6]); break;
  default: fprintf(f, "with lines lw 2 lc rgb '%s'", c); break;
  }
}

static void put_range(FILE *f, const char *axis, const double *r) {
  if (isnan(r[0]) && isnan(r[1])) {
    fprintf(f, "set %srange [*:*]\n", axis);
    return;
  }
  fprintf(f, "set %srange [", axis);
  if (isnan(r[0])) fputc('*', f); else fprintf(f, "%.10g", r[0]);
  fputc(':', f);
  if (isnan(r[1])) fputc('*', f); else fprintf(f, "%.10g", r[1]);
  fprintf(f, "]\n");
}

int hmsa_figure_render(const char *png_path, const HmsaFigure *fig) {
  int rows = fig->rows > 0 ? fig->rows : 1, cols = fig->cols > 0 ? fig->cols : 1;
  /* layout in pixels: panel 560 x 380 (one panel alone 900 x 560), fixed margins */
  const int pw = rows * cols == 1 ? 820 : 560, ph = rows * cols == 1 ? 470 : 360;
  const int left = 80, right = 25, gap_x = 95, gap_y = 110, bottom = 60, ptitle = 28;
  int nleg = fig->nlegend, per_row = 0, wide = 0;
  int W = left + cols * pw + (cols - 1) * gap_x + right;
  for (int i = 0; i < nleg; i++) wide = wide > (int)strlen(fig->legend[i].text) ? wide : (int)strlen(fig->legend[i].text);
  int entry_px = 60 + 8 * wide; /* sample line + text */
  per_row = (W - 40) / entry_px;
  if (per_row < 1) per_row = 1;
  int leg_rows = nleg ? (nleg + per_row - 1) / per_row : 0;
  /* the title is broken at ", " into lines of at most ~W/9 characters */
  char lines[4][2 * HMSA_FIG_TEXT];
  int nlines = 0;
  if (fig->title[0]) {
    int maxc = (W - 40) / 9;
    const char *t = fig->title;
    while (*t && nlines < 4) {
      size_t len = strlen(t), cut = len;
      if ((int)len > maxc && nlines < 3) {
        const char *best = NULL;
        for (const char *q = strstr(t, ", "); q && (int)(q - t) <= maxc; q = strstr(q + 1, ", "))
          best = q;
        if (best) cut = (size_t)(best - t) + 1;
      }
      snprintf(lines[nlines++], sizeof lines[0], "%.*s", (int)cut, t);
      t += cut;
      while (*t == ' ') t++;
    }
  }
  int head = nlines ? 14 + 24 * nlines : 10;
  int top = head + 24 * leg_rows + 18;
  int H = top + rows * (ph + ptitle) + (rows - 1) * (gap_y - ptitle) + bottom;
  char *body = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&body, &size);
  SA_REQUIRE(f, SA_ERR_MEMORY, "figure %s: cannot build the script", png_path);
  fprintf(f, "set encoding utf8\nset termoption enhanced\nset multiplot\n");
  /* title and shared legend: an empty plot spanning the canvas, its key at the top */
  for (int i = 0; i < nlines; i++) {
    fprintf(f, "set label %d ", i + 1);
    put_quoted(f, lines[i]);
    fprintf(f, " at screen 0.5, screen %.5f center font ',13'\n", 1.0 - (22.0 + 24.0 * i) / H);
  }
  fprintf(f, "set lmargin at screen 0\nset rmargin at screen 1\nset tmargin at screen 1\n"
             "set bmargin at screen 0\nunset border\nunset tics\nunset grid\n"
             "set xrange [0:1]\nset yrange [0:1]\n");
  if (nleg) {
    fprintf(f, "set key at screen 0.5, screen %.5f center top horizontal maxcols %d samplen 3 "
               "spacing 1.2 width 2 reverse Left font ',11'\nplot ",
            1.0 - (double)head / H, per_row);
    for (int i = 0; i < nleg; i++) {
      fprintf(f, "%s1/0 ", i ? ", " : "");
      put_style(f, fig->legend[i].color, fig->legend[i].kind);
      fprintf(f, " title ");
      put_quoted(f, fig->legend[i].text);
    }
    fprintf(f, "\n");
  } else {
    fprintf(f, "unset key\nplot 1/0 notitle\n");
  }
  fprintf(f, "unset label\nunset key\nset border\nset tics\nset grid lc rgb '#d8d8d8'\n"
             "set tics font ',10'\n");
  fprintf(f, "set xlabel ");
  put_quoted(f, fig->xlabel);
  fprintf(f, " font ',12'\nset ylabel ");
  put_quoted(f, fig->ylabel);
  fprintf(f, " font ',12'\n");
  put_range(f, "x", fig->xr);
  put_range(f, "y", fig->yr);
  for (int p = 0; p < fig->npanels && p < rows * cols; p++) {
    const HmsaPanel *P = &fig->panel[p];
    int r = p / cols, c = p % cols;
    double x0 = left + c * (pw + gap_x), x1 = x0 + pw;
    double y1 = H - top - r * (ph + gap_y) - ptitle, y0 = y1 - ph;
    fprintf(f, "set lmargin at screen %.5f\nset rmargin at screen %.5f\n", x0 / W, x1 / W);
    fprintf(f, "set bmargin at screen %.5f\nset tmargin at screen %.5f\n", y0 / H, y1 / H);
    fprintf(f, "set title ");
    put_quoted(f, P->title);
    fprintf(f, " font ',12'\n");
    if (!P->n) {
      fprintf(f, "plot 1/0 notitle\n");
      continue;
    }
    fprintf(f, "plot ");
    for (int i = 0; i < P->n; i++) {
      const HmsaCurve *C = &P->c[i];
      if (i) fprintf(f, ", \\\n     ");
      put_quoted(f, C->data);
      fprintf(f, " using %s ", C->using);
      put_style(f, C->color, C->kind);
      fprintf(f, " notitle");
    }
    fprintf(f, "\n");
  }
  fprintf(f, "unset multiplot\n");
  if (fclose(f) != 0 || !body) {
    free(body);
    return SA_ERROR(SA_ERR_MEMORY, "figure %s: cannot build the script", png_path);
  }
  int rc = sa_plot_script_size(png_path, W, H, body);
  free(body);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}
