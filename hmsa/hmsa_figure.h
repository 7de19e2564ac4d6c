/* hmsa_figure.h - figures of the HMSA scene (private to the hmsa module): decimation of long
 * histories for plotting, and multi-panel gnuplot figures with one shared legend.
 *
 * Decimation keeps what a line plot shows: the rows are split into n_bins consecutive bins (one
 * bin per pixel column or finer), and of each bin the first and last rows and the rows holding
 * the minimum and the maximum of every tracked column are kept, in their original order, each
 * once. The global extrema and the first and last rows therefore always survive; the CSV the
 * user reads stays complete, only the figure reads the decimated copy. */
#ifndef HMSA_FIGURE_H
#define HMSA_FIGURE_H

#include "sa_csv.h"

/* ---- decimation ---- */
typedef struct HmsaDecimator HmsaDecimator;

/* n_rows rows of ncols (<= 16) values will be pushed; track: bit j set = keep the extremes of
 * column j. out [borrowed] receives the kept rows as bins complete. *d [owned]. */
int hmsa_decimator_create(long n_rows, int ncols, int n_bins, unsigned track, SaCsv *out,
                          HmsaDecimator **d);
int hmsa_decimator_push(HmsaDecimator *d, const double *row);
/* Writes the rows kept from the last (possibly partial) bin. */
int hmsa_decimator_finish(HmsaDecimator *d);
long hmsa_decimator_kept(const HmsaDecimator *d);
void hmsa_decimator_destroy(HmsaDecimator **d);

/* Above this many rows a history is plotted from a decimated copy. */
#define HMSA_PLOT_MAX_ROWS 20000
/* Bins of the decimated copy: ~10 per pixel column (a phase-plane loop stays round). */
#define HMSA_PLOT_BINS 10000

/* ---- figures ---- */
typedef enum {
  HMSA_CURVE_LINE = 0,  /* solid line */
  HMSA_CURVE_DASH,      /* dashed line */
  HMSA_CURVE_THIN,      /* thin solid line */
  HMSA_CURVE_POINTS,    /* filled circles */
  HMSA_CURVE_OPEN,      /* open circles */
  HMSA_CURVE_LINEPOINTS, /* line with small filled circles */
  HMSA_CURVE_MARK,      /* crosses */
  HMSA_CURVE_REF,       /* thin dotted grey line (a reference value) */
  HMSA_CURVE_DOTS       /* small filled circles (many points) */
} HmsaCurveKind;

#define HMSA_FIG_TEXT 160

typedef struct {
  char data[256];           /* CSV, relative to the run folder */
  char using[128];          /* gnuplot `using` expression, e.g. "1:4" */
  int color;                /* palette index (0..7), -1 = grey */
  HmsaCurveKind kind;
} HmsaCurve;

typedef struct {
  char text[HMSA_FIG_TEXT]; /* UTF-8, gnuplot enhanced text, e.g. "λ_3" */
  int color;
  HmsaCurveKind kind;
} HmsaLegend;

#define HMSA_FIG_MAX_PANELS 16
#define HMSA_FIG_MAX_CURVES 64
#define HMSA_FIG_MAX_LEGEND 16

typedef struct {
  char title[HMSA_FIG_TEXT];
  int n;
  HmsaCurve c[HMSA_FIG_MAX_CURVES];
} HmsaPanel;

typedef struct {
  char title[2 * HMSA_FIG_TEXT];  /* figure title (top) */
  char xlabel[HMSA_FIG_TEXT], ylabel[HMSA_FIG_TEXT];
  int rows, cols;               /* panel grid */
  double xr[2], yr[2];          /* axis ranges; NaN = automatic */
  int npanels;
  HmsaPanel panel[HMSA_FIG_MAX_PANELS];
  int nlegend;
  HmsaLegend legend[HMSA_FIG_MAX_LEGEND];
} HmsaFigure;

/* Empty figure (automatic ranges, 1 x 1). */
void hmsa_figure_init(HmsaFigure *f);
/* Appends a curve to panel p (ignored beyond the capacity). */
void hmsa_figure_curve(HmsaFigure *f, int p, const char *data, const char *using, int color,
                       HmsaCurveKind kind);
/* Appends a legend entry unless one with the same text exists. */
void hmsa_figure_legend(HmsaFigure *f, const char *text, int color, HmsaCurveKind kind);
/* Writes png_path (and its .gp) with gnuplot: the title and the shared legend in a strip above
 * the panels, so that no legend covers a curve. Returns the sa_plot code (SA_ERR_IO when
 * gnuplot fails: plots are optional, the caller may clear it). */
int hmsa_figure_render(const char *png_path, const HmsaFigure *f);

#endif
