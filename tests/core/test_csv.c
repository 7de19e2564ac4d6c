/* test_csv.c - CSV writer: header lines, exact round trip of the values, refusal of NaN/Inf.
 *
 * usage: test_csv WORKDIR
 * Values are read back with strtod (correctly rounded in glibc), so a %.17g-printed double
 * must come back bit-identical (memcmp, which also tells -0.0 from 0.0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_csv.h"
#include "sa_error.h"
#include "sa_output.h"
#include "test_util.h"

#define NCOL 4
#define NROW 40

static double value(int r, int c) {
  static const double scale[] = {1.0, -1.0e-300, 3.0e300, 1.0e-9, -7.5, 0.0};
  double x = sin(1.7 * r + 0.3 * c + 0.2) * exp(0.3 * cos(0.9 * r - c));
  return x * scale[(r + 2 * c) % 6];
}

static void test_round_trip(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "history.csv", path);
  const char *names[NCOL] = {"t", "u_tip", "F", "det F min"};
  const char *units[NCOL] = {"s", "m", "N", NULL};
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(path, NCOL, names, units, &t));
  double rows[NROW + 2][NCOL];
  for (int r = 0; r < NROW; r++)
    for (int c = 0; c < NCOL; c++) rows[r][c] = value(r, c);
  /* Edge values: signed zero, extremes, smallest normal, an integer. */
  const double edge[2][NCOL] = {{-0.0, 1.7976931348623157e308, -2.2250738585072014e-308, 42.0},
                                {0.1, 1.0 / 3.0, -2.0 / 3.0, 1e22}};
  memcpy(rows[NROW], edge, sizeof edge);
  for (int r = 0; r < NROW + 2; r++) TU_OK(sa_csv_row(t, rows[r]));
  TU_CHECK(!tu_exists(path), "target exists before commit");
  TU_OK(sa_csv_commit(&t));
  TU_CHECK(t == NULL, "commit must null the handle");

  FILE *f = fopen(path, "r");
  TU_CHECK(f, "cannot open %s", path);
  if (!f) return;
  char line[4096];
  TU_CHECK(fgets(line, sizeof line, f) && !strcmp(line, "# units: t=s, u_tip=m, F=N, det F min=-\n"),
           "line 1: %s", line);
  TU_CHECK(fgets(line, sizeof line, f) && !strcmp(line, "t,u_tip,F,det F min\n"), "line 2: %s",
           line);
  int r = 0;
  while (fgets(line, sizeof line, f)) {
    TU_CHECK(r < NROW + 2, "extra line %d: %s", r + 3, line);
    if (r >= NROW + 2) break;
    char *p = line;
    for (int c = 0; c < NCOL; c++) {
      char *end;
      double x = strtod(p, &end);
      TU_CHECK(end != p, "row %d column %d: no number in '%s'", r, c, line);
      TU_CHECK(!memcmp(&x, &rows[r][c], sizeof x), "row %d column %d: read %.17g, wrote %.17g", r,
               c, x, rows[r][c]);
      TU_CHECK(*end == (c + 1 < NCOL ? ',' : '\n'), "row %d column %d: separator '%c'", r, c,
               *end);
      p = end + 1;
    }
    r++;
  }
  fclose(f);
  TU_CHECK(r == NROW + 2, "read %d rows, wrote %d", r, NROW + 2);
  TU_CHECK(tu_count_matching(dir, ".tmp.") == 0, "temporary left behind");
}

/* NaN/Inf are refused naming the column; the row is not written; abort leaves nothing. */
static void test_nan(const char *dir) {
  char path[TU_PATH];
  const char *names[3] = {"t", "energy", "x"};
  const char *units[3] = {"s", "J", "m"};
  const double good[3] = {0.5, 1.25, -3.0}, bad_nan[3] = {1.0, NAN, 2.0},
               bad_inf[3] = {1.0, 2.0, -INFINITY};

  tu_join(dir, "refused.csv", path);
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(path, 3, names, units, &t));
  TU_OK(sa_csv_row(t, good));
  TU_CODE_MSG(sa_csv_row(t, bad_nan), SA_ERR_NAN, "'energy'");
  TU_CODE_MSG(sa_csv_row(t, bad_inf), SA_ERR_NAN, "'x'");
  sa_csv_abort(&t);
  TU_CHECK(t == NULL, "abort must null the handle");
  TU_CHECK(tu_count_entries(dir) == 0, "abort after NaN left %d entries in %s",
           tu_count_entries(dir), dir);

  /* Committing after a refused row keeps only the good rows. */
  tu_join(dir, "partial.csv", path);
  TU_OK(sa_csv_open(path, 3, names, units, &t));
  TU_OK(sa_csv_row(t, good));
  TU_CODE(sa_csv_row(t, bad_nan), SA_ERR_NAN);
  TU_OK(sa_csv_row(t, good));
  TU_OK(sa_csv_commit(&t));
  size_t n;
  char *text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && !strcmp(text, "# units: t=s, energy=J, x=m\nt,energy,x\n0.5,1.25,-3\n0.5,1.25,-3\n"),
           "partial.csv:\n%s", text ? text : "(unreadable)");
  free(text);
}

static void test_bad_header(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "bad.csv", path);
  SaCsv *t = NULL;
  const char *comma[2] = {"a,b", "c"}, *quote[2] = {"a", "\"c\""}, *empty[2] = {"a", ""},
             *dup[2] = {"a", "a"}, *nl[2] = {"a", "b\n"}, *blank[2] = {" a", "b"},
             *ok[2] = {"a", "b"}, *bad_unit[2] = {"m", "kg,s"};
  TU_CODE(sa_csv_open(path, 2, comma, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, quote, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, empty, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, dup, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, nl, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, blank, NULL, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 2, ok, bad_unit, &t), SA_ERR_INPUT);
  TU_CODE(sa_csv_open(path, 0, ok, NULL, &t), SA_ERR_INPUT);
  TU_CHECK(t == NULL && tu_count_entries(dir) == 0, "a refused open left a handle or a file");
  char missing[TU_PATH];
  tu_join(dir, "no/such/dir.csv", missing);
  TU_CODE(sa_csv_open(missing, 2, ok, NULL, &t), SA_ERR_IO);
}

int main(int argc, char **argv) {
  char dir[TU_PATH];
  if (tu_fresh_dir(argc, argv, "round_trip", dir)) return 1;
  test_round_trip(dir);
  if (tu_fresh_dir(argc, argv, "nan", dir)) return 1;
  test_nan(dir);
  if (tu_fresh_dir(argc, argv, "header", dir)) return 1;
  test_bad_header(dir);
  return tu_result();
}
