/* test_plot.c - gnuplot plots: PNG and .gp written, no temporaries, no command injection,
 * failures reported as SA_ERR_IO without leaving files.
 *
 * usage: test_plot WORKDIR        (exit 77 = skipped when gnuplot is not installed)
 * The folder and the titles contain quotes, spaces, backquotes and @: they must reach gnuplot
 * as text, never as commands (a backquote would run `touch` in a shell). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "test_util.h"

static int is_png(const char *path) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  size_t n;
  unsigned char *b = tu_slurp(path, &n);
  int ok = b && n > 100 && !memcmp(b, sig, 8);
  free(b);
  return ok;
}

static int have_gnuplot(void) {
  const char *path = getenv("PATH");
  char buf[TU_PATH];
  while (path && *path) {
    const char *end = strchr(path, ':');
    size_t len = end ? (size_t)(end - path) : strlen(path);
    snprintf(buf, sizeof buf, "%.*s/gnuplot", (int)len, path);
    if (access(buf, X_OK) == 0) return 1;
    path = end ? end + 1 : NULL;
  }
  return 0;
}

int main(int argc, char **argv) {
  if (!have_gnuplot()) {
    printf("SKIP: gnuplot not found\n");
    return 77;
  }
  sa_log_set_level(SA_LOG_ERROR); /* the expected failures below log warnings */
  char base[TU_PATH], dir[TU_PATH], csv[TU_PATH], png[TU_PATH], gp[TU_PATH], pwned[TU_PATH];
  if (tu_fresh_dir(argc, argv, "plots", base)) return 1;
  tu_join(base, "it's a `touch pwned` @dir", dir);
  TU_OK(sa_mkdir_p(dir));

  tu_join(dir, "history.csv", csv);
  const char *names[3] = {"t", "u_tip", "F"}, *units[3] = {"s", "m", "N"};
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(csv, 3, names, units, &t));
  for (int i = 1; i <= 20; i++) {
    double row[3] = {0.05 * i, 1e-3 * i * i, 2.0 * i};
    TU_OK(sa_csv_row(t, row));
  }
  TU_OK(sa_csv_commit(&t));

  /* Data path given as this process opens it (inside the PNG's folder). */
  tu_join(dir, "tip.png", png);
  tu_join(dir, "tip.gp", gp);
  SaPlotSeries s[2] = {
      {csv, 1, 2, "u_tip `touch pwned` it's", NULL},
      {csv, 1, 3, "F @x", "points pt 7 ps 0.5"},
  };
  SaPlotAxes ax = {"tip \"response\" 'quoted'", "t [s]", "u [m]", 0, 1, 640, 480};
  TU_OK(sa_plot_lines(png, &ax, 2, s));
  TU_CHECK(is_png(png), "%s is not a PNG", png);
  size_t n;
  char *script = (char *)tu_slurp(gp, &n);
  TU_CHECK(script, "script %s missing", gp);
  if (script) {
    TU_CHECK(strstr(script, "'history.csv' using 1:2 with lines"),
             "data file not referred to by its name in the PNG's folder:\n%s", script);
    TU_CHECK(strstr(script, "sa_output = 'tip.png'"), "default output missing:\n%s", script);
    TU_CHECK(strstr(script, "set logscale y") && !strstr(script, "set logscale x"),
             "log axes wrong:\n%s", script);
    TU_CHECK(strstr(script, "size 640,480"), "size wrong:\n%s", script);
  }
  free(script);
  tu_join(dir, "pwned", pwned);
  TU_CHECK(!tu_exists(pwned) && !tu_exists("pwned"), "a backquote in a title ran a command");
  TU_CHECK(tu_count_matching(dir, ".tmp.") == 0, "temporary left behind in %s", dir);

  /* Free-form script; a data file elsewhere is referred to by its absolute path. */
  char png2[TU_PATH];
  tu_join(base, "sine.png", png2);
  TU_OK(sa_plot_script(png2, "set xrange [0:6.3]\nplot sin(x) title 'sin'"));
  TU_CHECK(is_png(png2), "%s is not a PNG", png2);
  char png3[TU_PATH];
  tu_join(base, "other.png", png3);
  SaPlotSeries far = {csv, 1, 2, NULL, NULL};
  TU_OK(sa_plot_lines(png3, NULL, 1, &far));
  TU_CHECK(is_png(png3), "%s is not a PNG (data in another folder)", png3);
  tu_join(base, "other.gp", gp);
  script = (char *)tu_slurp(gp, &n);
  TU_CHECK(script && strstr(script, "plot 'it''s a `touch pwned` @dir/history.csv' using 1:2"),
           "data file below the PNG's folder not referred to relatively:\n%s",
           script ? script : "(unreadable)");
  free(script);

  /* Failures: bad gnuplot input, bad arguments, missing gnuplot. No PNG, no temporary. */
  char bad[TU_PATH];
  tu_join(base, "bad.png", bad);
  TU_CODE(sa_plot_script(bad, "plot sin(x) with nonsense_style"), SA_ERR_IO);
  TU_CHECK(!tu_exists(bad), "a failed plot left %s", bad);
  SaPlotSeries missing = {"no_such_file.csv", 1, 2, "x", NULL};
  TU_CODE(sa_plot_lines(bad, NULL, 1, &missing), SA_ERR_IO);
  TU_CHECK(!tu_exists(bad), "a plot of a missing file left %s", bad);
  SaPlotSeries inject = {csv, 1, 2, "x", "lines; system('touch pwned')"};
  TU_CODE(sa_plot_lines(bad, NULL, 1, &inject), SA_ERR_INPUT);
  SaPlotSeries nl = {csv, 1, 2, "two\nlines", NULL};
  TU_CODE(sa_plot_lines(bad, NULL, 1, &nl), SA_ERR_INPUT);
  SaPlotSeries col0 = {csv, 0, 2, "x", NULL};
  TU_CODE(sa_plot_lines(bad, NULL, 1, &col0), SA_ERR_INPUT);
  TU_CODE(sa_plot_lines(bad, NULL, 0, s), SA_ERR_INPUT);
  TU_CHECK(tu_count_matching(base, ".tmp.") == 0, "temporary left behind in %s", base);

  const char *saved = getenv("PATH");
  char *keep = saved ? strdup(saved) : NULL;
  setenv("PATH", "/nonexistent", 1);
  TU_CODE(sa_plot_script(bad, "plot x"), SA_ERR_IO);
  if (keep) setenv("PATH", keep, 1);
  free(keep);
  TU_CHECK(!tu_exists(bad), "plot without gnuplot left %s", bad);
  return tu_result();
}
