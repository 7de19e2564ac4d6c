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
 * decides between committing the rows so far and aborting (sa_csv_row_gaps writes a NaN as an
 * empty field instead). Column names must not contain commas, quotes or control characters (no
 * quoting is ever needed); a missing unit is "-".
 *
 * sa_csv_read reads such a table back into columns (one array of doubles per column). */
#include "sa_csv.h"

#include <ctype.h>
#include <errno.h>
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

/* gaps: NaN is written as an empty field instead of being refused. */
static int sa_csv_write_row(SaCsv *t, const double *values, int gaps) {
  SA_REQUIRE(t, SA_ERR_INPUT, "sa_csv_row: NULL table");
  SA_REQUIRE(values, SA_ERR_INPUT, "%s: NULL row", sa_file_target(t->file));
  /* Check the whole row first so a refused row leaves no partial line behind. */
  for (int j = 0; j < t->ncols; j++)
    SA_REQUIRE(isfinite(values[j]) || (gaps && isnan(values[j])), SA_ERR_NAN,
               "%s: row %ld, column '%s' is %g", sa_file_target(t->file), t->nrows + 1,
               t->names[j], values[j]);
  FILE *f = sa_file_stream(t->file);
  int bad = 0;
  for (int j = 0; j < t->ncols; j++) {
    if (j) bad |= fputc(',', f) == EOF;
    if (!isnan(values[j])) bad |= fprintf(f, "%.17g", values[j]) < 0;
  }
  bad |= fputc('\n', f) == EOF;
  SA_REQUIRE(!bad, SA_ERR_IO, "write error on %s", sa_file_target(t->file));
  t->nrows++;
  return 0;
}

int sa_csv_row(SaCsv *t, const double *values) {
  SA_CHECK(sa_csv_write_row(t, values, 0));
  return 0;
}

int sa_csv_row_gaps(SaCsv *t, const double *values) {
  SA_CHECK(sa_csv_write_row(t, values, 1));
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

/* ---- reading ---- */

struct SaCsvData {
  int ncols, nrows, cap;
  char **names, **units; /* [owned] ncols each; units[j] NULL when not given */
  double **cols;         /* [owned] ncols arrays of nrows */
  char *namelist;        /* [owned] "a, b, c" */
};

void sa_csv_data_destroy(SaCsvData **dp) {
  if (!dp || !*dp) return;
  SaCsvData *d = *dp;
  for (int j = 0; j < d->ncols; j++) {
    if (d->names) free(d->names[j]);
    if (d->units) free(d->units[j]);
    if (d->cols) free(d->cols[j]);
  }
  free(d->names);
  free(d->units);
  free(d->cols);
  free(d->namelist);
  free(d);
  *dp = NULL;
}

static char *sa_csv_strip(char *s) {
  while (*s && isspace((unsigned char)*s)) s++;
  size_t n = strlen(s);
  while (n && isspace((unsigned char)s[n - 1])) s[--n] = 0;
  return s;
}

/* Split line in place at commas into at most max fields; returns the count (max + 1 if more). */
static int sa_csv_split(char *line, char **fields, int max) {
  int n = 0;
  for (char *p = line;;) {
    char *comma = strchr(p, ',');
    if (comma) *comma = 0;
    if (n < max) fields[n] = sa_csv_strip(p);
    n++;
    if (!comma || n > max) break;
    p = comma + 1;
  }
  return n;
}

static int sa_csv_header(SaCsvData *d, const char *path, long lineno, char *line) {
  int n = 1;
  for (const char *p = line; *p; p++) n += *p == ',';
  d->ncols = n;
  d->names = calloc((size_t)n, sizeof *d->names);
  d->units = calloc((size_t)n, sizeof *d->units);
  d->cols = calloc((size_t)n, sizeof *d->cols);
  SA_REQUIRE(d->names && d->units && d->cols, SA_ERR_MEMORY, "%s: %d columns", path, n);
  d->cap = 64;
  for (int j = 0; j < n; j++) {
    d->cols[j] = malloc(sizeof(double) * (size_t)d->cap);
    SA_REQUIRE(d->cols[j], SA_ERR_MEMORY, "%s: %d columns", path, n);
  }
  char **f = calloc((size_t)n, sizeof *f);
  SA_REQUIRE(f, SA_ERR_MEMORY, "%s: %d columns", path, n);
  sa_csv_split(line, f, n);
  size_t len = 1;
  int rc = 0;
  for (int j = 0; j < n && !rc; j++) {
    if (!f[j][0]) rc = SA_ERROR(SA_ERR_INPUT, "%s:%ld: column %d has no name", path, lineno, j + 1);
    else if (!(d->names[j] = strdup(f[j]))) rc = SA_ERROR(SA_ERR_MEMORY, "column name");
    else len += strlen(f[j]) + 2;
  }
  free(f);
  SA_CHECK(rc);
  d->namelist = malloc(len);
  SA_REQUIRE(d->namelist, SA_ERR_MEMORY, "column names");
  d->namelist[0] = 0;
  for (int j = 0; j < n; j++) {
    if (j) strcat(d->namelist, ", ");
    strcat(d->namelist, d->names[j]);
  }
  return 0;
}

/* "# units: a=m, b=deg" -> units of the named columns (applied once the names are known). */
static int sa_csv_units(SaCsvData *d, const char *path, char *units_line) {
  if (!units_line) return 0;
  char *p = units_line;
  for (char *tok = strtok_r(p, ",", &p); tok; tok = strtok_r(NULL, ",", &p)) {
    char *eq = strchr(tok, '=');
    if (!eq) continue;
    *eq = 0;
    char *name = sa_csv_strip(tok), *unit = sa_csv_strip(eq + 1);
    for (int j = 0; j < d->ncols; j++)
      if (!strcmp(d->names[j], name) && !d->units[j]) {
        d->units[j] = strdup(unit);
        SA_REQUIRE(d->units[j], SA_ERR_MEMORY, "%s: unit", path);
      }
  }
  return 0;
}

static int sa_csv_add_row(SaCsvData *d, const char *path, long lineno, char *line) {
  if (d->nrows == d->cap) {
    int cap = 2 * d->cap;
    for (int j = 0; j < d->ncols; j++) {
      double *c = realloc(d->cols[j], sizeof(double) * (size_t)cap);
      SA_REQUIRE(c, SA_ERR_MEMORY, "%s: %d rows", path, cap);
      d->cols[j] = c;
    }
    d->cap = cap;
  }
  char *stack[32], **f = d->ncols <= 31 ? stack : malloc(sizeof(char *) * (size_t)(d->ncols + 1));
  SA_REQUIRE(f, SA_ERR_MEMORY, "%s: fields", path);
  int n = sa_csv_split(line, f, d->ncols), rc = 0;
  if (n != d->ncols)
    rc = SA_ERROR(SA_ERR_INPUT, "%s:%ld: %s%d fields, the header has %d columns (%s)", path, lineno,
                  n > d->ncols ? "more than " : "", n > d->ncols ? d->ncols : n, d->ncols,
                  d->namelist);
  for (int j = 0; j < d->ncols && !rc; j++) {
    double v = NAN;
    if (f[j][0]) {
      char *end;
      errno = 0;
      v = strtod(f[j], &end);
      if (end == f[j] || *end || errno == ERANGE)
        rc = SA_ERROR(SA_ERR_INPUT, "%s:%ld: column '%s' is '%s', not a number", path, lineno,
                      d->names[j], f[j]);
    }
    d->cols[j][d->nrows] = v;
  }
  if (f != stack) free(f);
  SA_CHECK(rc);
  d->nrows++;
  return 0;
}

int sa_csv_read(const char *path, SaCsvData **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_csv_read: NULL output handle");
  *out = NULL;
  SA_REQUIRE(path && path[0], SA_ERR_INPUT, "sa_csv_read: empty path");
  FILE *fp = fopen(path, "r");
  SA_REQUIRE(fp, SA_ERR_INPUT, "%s: cannot open: %s", path, strerror(errno));
  SaCsvData *d = calloc(1, sizeof *d);
  char *line = NULL, *units = NULL;
  size_t cap = 0;
  long lineno = 0;
  int rc = d ? 0 : SA_ERROR(SA_ERR_MEMORY, "%s: table", path);
  ssize_t len;
  while (!rc && (len = getline(&line, &cap, fp)) >= 0) {
    lineno++;
    if (memchr(line, 0, (size_t)len)) {
      rc = SA_ERROR(SA_ERR_INPUT, "%s:%ld: NUL byte (not a text table)", path, lineno);
      break;
    }
    char *s = sa_csv_strip(line);
    if (s[0] == '#') {
      s = sa_csv_strip(s + 1);
      if (!d->names && !units && !strncmp(s, "units:", 6) && !(units = strdup(s + 6)))
        rc = SA_ERROR(SA_ERR_MEMORY, "%s: units line", path);
      continue;
    }
    if (!s[0]) continue;
    if (!d->names) {
      rc = sa_csv_header(d, path, lineno, s);
      if (!rc) rc = sa_csv_units(d, path, units);
    } else {
      rc = sa_csv_add_row(d, path, lineno, s);
    }
  }
  if (!rc && ferror(fp)) rc = SA_ERROR(SA_ERR_IO, "%s: read error", path);
  if (!rc && !d->names) rc = SA_ERROR(SA_ERR_INPUT, "%s: no header line with column names", path);
  fclose(fp);
  free(line);
  free(units);
  if (rc) {
    sa_csv_data_destroy(&d);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = d;
  return 0;
}

int sa_csv_data_nrows(const SaCsvData *d) { return d ? d->nrows : 0; }

static int sa_csv_data_find(const SaCsvData *d, const char *name) {
  for (int j = 0; d && name && j < d->ncols; j++)
    if (!strcmp(d->names[j], name)) return j;
  return -1;
}

const double *sa_csv_data_column(const SaCsvData *d, const char *name) {
  int j = sa_csv_data_find(d, name);
  return j < 0 ? NULL : d->cols[j];
}

const char *sa_csv_data_unit(const SaCsvData *d, const char *name) {
  int j = sa_csv_data_find(d, name);
  return j < 0 ? NULL : d->units[j];
}

const char *sa_csv_data_names(const SaCsvData *d) { return d && d->namelist ? d->namelist : ""; }
