/* test_csv_read.c - reading CSV tables back (sa_csv_read) and writing rows with gaps
 * (sa_csv_row_gaps): exact round trip, empty field <-> NaN, units, and refusal of malformed
 * tables with path:line in the message.
 *
 * usage: test_csv_read WORKDIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_csv.h"
#include "sa_error.h"
#include "sa_output.h"
#include "test_util.h"

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f) {
    TU_CHECK(0, "cannot write %s", path);
    return;
  }
  fputs(text, f);
  fclose(f);
}

static void test_round_trip(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "gaps.csv", path);
  const char *names[3] = {"x", "angle", "force"};
  const char *units[3] = {"m", "deg", NULL};
  const double rows[4][3] = {{0.0, 0.17198187889002481, 0.0},
                             {2.5e-4, NAN, 0.067786416695410301},
                             {1.0 / 3.0, -1e-300, NAN},
                             {1e22, 5.0, -0.0}};
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(path, 3, names, units, &t));
  for (int r = 0; r < 4; r++) TU_OK(sa_csv_row_gaps(t, rows[r]));
  double inf_row[3] = {1, INFINITY, 2};
  TU_CHECK(sa_csv_row_gaps(t, inf_row) == SA_ERR_NAN, "an infinity was not refused");
  sa_error_clear();
  double nan_row[3] = {1, NAN, 2};
  TU_CHECK(sa_csv_row(t, nan_row) == SA_ERR_NAN, "sa_csv_row took a NaN");
  sa_error_clear();
  TU_OK(sa_csv_commit(&t));

  SaCsvData *d = NULL;
  TU_OK(sa_csv_read(path, &d));
  if (!d) return;
  TU_CHECK(sa_csv_data_nrows(d) == 4, "%d rows read back, expected 4", sa_csv_data_nrows(d));
  TU_CHECK(!strcmp(sa_csv_data_names(d), "x, angle, force"), "names '%s'", sa_csv_data_names(d));
  const char *u = sa_csv_data_unit(d, "angle");
  TU_CHECK(u && !strcmp(u, "deg"), "unit of angle '%s'", u ? u : "(none)");
  u = sa_csv_data_unit(d, "force");
  TU_CHECK(u && !strcmp(u, "-"), "unit of force '%s' (a missing unit is written as -)", u ? u : "(none)");
  TU_CHECK(!sa_csv_data_column(d, "missing"), "a column that does not exist was found");
  for (int c = 0; c < 3; c++) {
    const double *col = sa_csv_data_column(d, names[c]);
    TU_CHECK(col, "column %s not found", names[c]);
    for (int r = 0; col && r < 4 && r < sa_csv_data_nrows(d); r++) {
      if (isnan(rows[r][c]))
        TU_CHECK(isnan(col[r]), "row %d column %s: %g, expected a gap (NaN)", r, names[c], col[r]);
      else
        TU_CHECK(!memcmp(&col[r], &rows[r][c], sizeof(double)), "row %d column %s: %.17g != %.17g",
                 r, names[c], col[r], rows[r][c]);
    }
  }
  sa_csv_data_destroy(&d);
  TU_CHECK(d == NULL, "destroy did not null the handle");
  sa_csv_data_destroy(&d); /* accepts NULL */
}

/* A table of someone else's making: no units line, blanks, comment lines, many rows. */
static void test_foreign(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "foreign.csv", path);
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f, "# written by hand\n a , b \n\n");
  for (int i = 0; i < 1000; i++) fprintf(f, "%d, %g\n", i, 0.5 * i);
  fclose(f);
  SaCsvData *d = NULL;
  TU_OK(sa_csv_read(path, &d));
  if (!d) return;
  const double *a = sa_csv_data_column(d, "a"), *b = sa_csv_data_column(d, "b");
  TU_CHECK(sa_csv_data_nrows(d) == 1000 && a && b, "%d rows", sa_csv_data_nrows(d));
  TU_CHECK(!sa_csv_data_unit(d, "a"), "a unit without a units line");
  if (a && b && sa_csv_data_nrows(d) == 1000)
    TU_CHECK(a[999] == 999 && b[999] == 499.5, "last row %g, %g", a[999], b[999]);
  sa_csv_data_destroy(&d);
}

static void expect_error(const char *dir, const char *name, const char *text, const char *needle) {
  char path[TU_PATH];
  tu_join(dir, name, path);
  if (text) write_text(path, text);
  SaCsvData *d = NULL;
  int rc = sa_csv_read(path, &d);
  TU_CHECK(rc == SA_ERR_INPUT, "%s: rc %d, expected SA_ERR_INPUT", name, rc);
  TU_CHECK(d == NULL, "%s: a table was returned", name);
  const char *msg = sa_error_message();
  TU_CHECK(strstr(msg, path) && strstr(msg, needle), "%s: message '%s' lacks the path or '%s'",
           name, msg, needle);
  sa_error_clear();
  sa_csv_data_destroy(&d);
}

int main(int argc, char **argv) {
  char dir[TU_PATH];
  if (tu_fresh_dir(argc, argv, "read", dir)) return 1;
  test_round_trip(dir);
  test_foreign(dir);
  expect_error(dir, "short_row.csv", "# units: a=m, b=m\na,b\n1,2\n3\n", ":4:");
  expect_error(dir, "long_row.csv", "a,b\n1,2,3\n", ":2:");
  expect_error(dir, "not_a_number.csv", "a,b\n1,abc\n", "'b' is 'abc'");
  expect_error(dir, "no_header.csv", "# only a comment\n\n", "no header");
  expect_error(dir, "empty_name.csv", "a,,c\n1,2,3\n", "column 2 has no name");
  expect_error(dir, "missing.csv", NULL, "cannot open");
  return tu_result();
}
