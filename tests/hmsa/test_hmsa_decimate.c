/* test_hmsa_decimate - decimation of long histories for plotting (issue 15, item 4).
 *
 * 1e6 rows (tau, y1, y2) of a decaying oscillation with isolated spikes (the global maximum and
 * minimum of y1 and y2 each sit on one row) go through the decimator with 4000 bins, tracking
 * y1 and y2. Reference: the generator itself, i.e. the exact per-bin extremes computed here
 * while generating. The decimated CSV, read back, must
 *   - hold the first and the last row and the rows of the four global extremes;
 *   - reproduce every bin's minimum and maximum of y1 and y2 exactly (what a line plot with one
 *     bin per pixel column or finer shows) and contain only input rows, in order;
 *   - have at most 6 rows a bin (first, last, min and max of two columns).
 * Then gnuplot (when installed) draws it through the scene's figure writer: that must take
 * seconds (limit 10 s; the 1e6-row original exceeded sa_plot's 60 s limit). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hmsa_figure.h"
#include "hmsa_test.h"
#include "sa_log.h"
#include "sa_output.h"

#define NROWS 1000000L
#define NBINS 4000

static void gen(long k, double *r) {
  double t = 1e-4 * (double)k;
  r[0] = t;
  r[1] = 1.0 + 0.1 * sin(37.0 * t) * exp(-t / 50.0);
  r[2] = 3.7 * cos(37.0 * t) * exp(-t / 50.0);
  if (k == 123457) r[1] = 1.5;   /* global max of y1 */
  if (k == 876543) r[1] = 0.5;   /* global min of y1 */
  if (k == 400001) r[2] = 9.0;   /* global max of y2 */
  if (k == 999998) r[2] = -9.0;  /* global min of y2, next to the last row */
}

int main(void) {
  char dir[] = "/tmp/test_hmsa_decimate_XXXXXX";
  EXPECT(mkdtemp(dir) != NULL, "mkdtemp failed");
  char csv[256], png[256];
  snprintf(csv, sizeof csv, "%s/history_decimated.csv", dir);
  snprintf(png, sizeof png, "%s/history.png", dir);
  const char *names[] = {"tau", "y1", "y2"}, *units[] = {"-", "-", "-"};
  SaCsv *t;
  OK(sa_csv_open(csv, 3, names, units, &t));
  HmsaDecimator *d;
  OK(hmsa_decimator_create(NROWS, 3, NBINS, (1u << 1) | (1u << 2), t, &d));
  long bin = (NROWS + NBINS - 1) / NBINS;
  static double bmin[NBINS][3], bmax[NBINS][3];
  for (long k = 0; k < NROWS; k++) {
    double r[3];
    gen(k, r);
    long b = k / bin;
    for (int j = 1; j < 3; j++) {
      if (k % bin == 0 || r[j] < bmin[b][j]) bmin[b][j] = r[j];
      if (k % bin == 0 || r[j] > bmax[b][j]) bmax[b][j] = r[j];
    }
    OK(hmsa_decimator_push(d, r));
  }
  OK(hmsa_decimator_finish(d));
  long kept = hmsa_decimator_kept(d);
  hmsa_decimator_destroy(&d);
  OK(sa_csv_commit(&t));
  EXPECT(kept <= 6L * NBINS, "%ld rows kept, at most %d expected", kept, 6 * NBINS);

  /* read back: rows are "tau,y1,y2" after a units comment and the names line */
  FILE *f = fopen(csv, "r");
  EXPECT(f != NULL, "cannot read %s", csv);
  if (!f) TEST_RETURN();
  static double gmin[NBINS][3], gmax[NBINS][3];
  static char seen[NBINS];
  char line[512];
  long rows = 0, prev = -1;
  int first = 0, last = 0, spikes = 0, exact = 1, ordered = 1;
  while (fgets(line, sizeof line, f)) {
    double r[3], g[3];
    if (sscanf(line, "%lf,%lf,%lf", &r[0], &r[1], &r[2]) != 3) continue;
    long k = lround(r[0] * 1e4);
    gen(k, g);
    if (memcmp(r, g, sizeof r)) exact = 0;
    if (k <= prev) ordered = 0;
    prev = k;
    first |= k == 0;
    last |= k == NROWS - 1;
    spikes += (k == 123457) + (k == 876543) + (k == 400001) + (k == 999998);
    long b = k / bin;
    for (int j = 1; j < 3; j++) {
      if (!seen[b] || r[j] < gmin[b][j]) gmin[b][j] = r[j];
      if (!seen[b] || r[j] > gmax[b][j]) gmax[b][j] = r[j];
    }
    seen[b] = 1;
    rows++;
  }
  fclose(f);
  EXPECT(rows == kept, "%ld rows read back, %ld written", rows, kept);
  EXPECT(first && last, "first row kept %d, last row kept %d", first, last);
  EXPECT(spikes == 4, "%d of the 4 global extremes kept", spikes);
  EXPECT(exact, "a kept row differs from the input row (values must be copied, not computed)");
  EXPECT(ordered, "kept rows are not in their original order");
  int bins_ok = 1;
  for (long b = 0; b < NBINS; b++)
    for (int j = 1; j < 3; j++)
      if (!seen[b] || gmin[b][j] != bmin[b][j] || gmax[b][j] != bmax[b][j]) bins_ok = 0;
  EXPECT(bins_ok, "a bin's minimum or maximum was lost");

  /* the figure of the decimated data is drawn in seconds */
  if (access("/usr/bin/gnuplot", X_OK) == 0 || access("/usr/local/bin/gnuplot", X_OK) == 0) {
    HmsaFigure fig;
    hmsa_figure_init(&fig);
    snprintf(fig.title, sizeof fig.title, "1e6 rows decimated to %ld", kept);
    snprintf(fig.xlabel, sizeof fig.xlabel, "τ");
    snprintf(fig.ylabel, sizeof fig.ylabel, "y");
    hmsa_figure_curve(&fig, 0, "history_decimated.csv", "1:2", 0, HMSA_CURVE_LINE);
    double t0 = sa_time_now();
    OK(hmsa_figure_render(png, &fig));
    double secs = sa_time_now() - t0;
    EXPECT(secs < 10.0, "figure of the decimated history took %.1f s", secs);
    EXPECT(access(png, F_OK) == 0, "no figure %s", png);
  }
  char cmd[320];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "note: could not remove %s\n", dir);
  TEST_RETURN();
}
