/* sa_csv.c - CSV tables written atomically (sa_output.h).
 *
 *   # units: t=s, u_tip=m
 *   t,u_tip
 *   0,0
 *   0.10000000000000001,1.2345678901234567e-05
 *
 * 17 significant digits ("%.17g") make every double round-trip exactly through a correctly
 * rounded reader (strtod, Python float, numpy). Non-finite values are refused with SA_ERR_NAN
 * naming the column; the refused row is not written, the table stays open, and the caller
 * decides between committing the rows so far and aborting. Column names must not contain
 * commas, quotes or control characters (no quoting is ever needed); a missing unit is "-". */
#include "sa_csv.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_output.h"

struct SaCsv {
  SaFile *file; /* [owned] */
  int ncols;
  long nrows;
  char **names; /* [owned] ncols, for error messages */
};

static void sa_csv_free(SaCsv *t) {
  if (!t) return;
  sa_file_abort(&t->file);
  if (t->names)
    for (int j = 0; j < t->ncols; j++) free(t->names[j]);
  free(t->names);
  free(t);
}

/* what: "name" or "unit". Leading/trailing blanks are refused too: readers strip them
 * inconsistently, so a name would not match itself. */
static int sa_csv_check_text(const char *path, const char *what, int col, const char *s,
                             int allow_empty) {
  SA_REQUIRE(s && (s[0] || allow_empty), SA_ERR_INPUT, "%s: column %d has an empty %s", path,
             col + 1, what);
  size_t len = strlen(s);
  for (size_t i = 0; i < len; i++) {
    unsigned char c = (unsigned char)s[i];
    SA_REQUIRE(c >= 32 && c != 127 && c != ',' && c != '"', SA_ERR_INPUT,
               "%s: %s '%s' of column %d contains a comma, quote or control character", path,
               what, s, col + 1);
  }
  SA_REQUIRE(!len || (s[0] != ' ' && s[len - 1] != ' '), SA_ERR_INPUT,
             "%s: %s '%s' of column %d has leading or trailing blanks", path, what, s, col + 1);
  return 0;
}

int sa_csv_open(const char *path, int ncols, const char *const *names, const char *const *units,
                SaCsv **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_csv_open: NULL output handle");
  *out = NULL;
  SA_REQUIRE(path && path[0], SA_ERR_INPUT, "sa_csv_open: empty path");
  SA_REQUIRE(ncols >= 1, SA_ERR_INPUT, "%s: %d columns", path, ncols);
  SA_REQUIRE(names, SA_ERR_INPUT, "%s: NULL column names", path);
  for (int j = 0; j < ncols; j++) {
    SA_CHECK(sa_csv_check_text(path, "name", j, names[j], 0));
    if (units && units[j]) SA_CHECK(sa_csv_check_text(path, "unit", j, units[j], 1));
    for (int k = 0; k < j; k++)
      SA_REQUIRE(strcmp(names[j], names[k]), SA_ERR_INPUT, "%s: duplicate column name '%s'", path,
                 names[j]);
  }

  SaCsv *t;
  SA_CALLOC(t, 1);
  t->ncols = ncols;
  t->names = calloc((size_t)ncols, sizeof *t->names);
  int rc = t->names ? 0 : SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d column names", ncols);
  for (int j = 0; j < ncols && !rc; j++)
    if (!(t->names[j] = strdup(names[j]))) rc = SA_ERROR(SA_ERR_MEMORY, "cannot copy a name");
  if (!rc) rc = sa_file_open(path, &t->file);
  if (!rc) {
    FILE *f = sa_file_stream(t->file);
    int bad = fputs("# units:", f) == EOF;
    for (int j = 0; j < ncols; j++) {
      const char *u = units && units[j] && units[j][0] ? units[j] : "-";
      bad |= fprintf(f, "%s%s=%s", j ? ", " : " ", names[j], u) < 0;
    }
    bad |= fputc('\n', f) == EOF;
    for (int j = 0; j < ncols; j++) bad |= fprintf(f, j ? ",%s" : "%s", names[j]) < 0;
    bad |= fputc('\n', f) == EOF;
    if (bad) rc = SA_ERROR(SA_ERR_IO, "write error on %s", path);
  }
  if (rc) {
    sa_csv_free(t);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = t;
  return 0;
}

int sa_csv_row(SaCsv *t, const double *values) {
  SA_REQUIRE(t, SA_ERR_INPUT, "sa_csv_row: NULL table");
  SA_REQUIRE(values, SA_ERR_INPUT, "%s: NULL row", sa_file_target(t->file));
  /* Check the whole row first so a refused row leaves no partial line behind. */
  for (int j = 0; j < t->ncols; j++)
    SA_REQUIRE(isfinite(values[j]), SA_ERR_NAN, "%s: row %ld, column '%s' is %g",
               sa_file_target(t->file), t->nrows + 1, t->names[j], values[j]);
  FILE *f = sa_file_stream(t->file);
  int bad = 0;
  for (int j = 0; j < t->ncols; j++) bad |= fprintf(f, j ? ",%.17g" : "%.17g", values[j]) < 0;
  bad |= fputc('\n', f) == EOF;
  SA_REQUIRE(!bad, SA_ERR_IO, "write error on %s", sa_file_target(t->file));
  t->nrows++;
  return 0;
}

int sa_csv_commit(SaCsv **tp) {
  SA_REQUIRE(tp && *tp, SA_ERR_INPUT, "sa_csv_commit: NULL table");
  SaCsv *t = *tp;
  *tp = NULL;
  int rc = sa_file_commit(&t->file);
  sa_csv_free(t);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

void sa_csv_abort(SaCsv **tp) {
  if (!tp || !*tp) return;
  sa_csv_free(*tp);
  *tp = NULL;
}
