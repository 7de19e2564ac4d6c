/* sa_plot.h - PNG plots with gnuplot. The gnuplot script is kept beside the PNG (same stem,
 * ".gp") so a user can restyle the figure; the PNG is rendered to a temporary and renamed.
 * A missing or failing gnuplot is reported as a warning and returns SA_ERR_IO; callers
 * treat plots as optional so data is never lost because of a plot. */
#ifndef SA_PLOT_H
#define SA_PLOT_H

typedef struct {
  const char *csv;   /* data file (path as gnuplot should open it) */
  int xcol, ycol;    /* 1-based columns */
  const char *title; /* legend entry */
  const char *style; /* gnuplot style, e.g. "lines", "points pt 7 ps 0.3"; NULL = lines */
} SaPlotSeries;

typedef struct {
  const char *title, *xlabel, *ylabel;
  int logx, logy;
  int width, height; /* pixels; 0 = 900 x 600 */
} SaPlotAxes;

int sa_plot_lines(const char *png_path, const SaPlotAxes *axes, int nseries,
                  const SaPlotSeries *series);
/* Free-form: body is gnuplot commands after the terminal/output lines are set. */
int sa_plot_script(const char *png_path, const char *body);
/* As sa_plot_script, with the image size in pixels (0 = 900 x 600). */
int sa_plot_script_size(const char *png_path, int width, int height, const char *body);

#endif
