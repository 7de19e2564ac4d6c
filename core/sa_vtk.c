/* sa_vtk.c - legacy VTK writer (file format "vtk DataFile Version 3.0") and ParaView
 * ".vtk.series" index.
 *
 * Reference: "VTK File Formats", VTK User's Guide (Kitware), section "Simple Legacy Formats".
 * Layout written here:
 *   # vtk DataFile Version 3.0
 *   <title, one line, < 256 chars>
 *   ASCII | BINARY
 *   DATASET UNSTRUCTURED_GRID | POLYDATA
 *   POINTS n double                       3n values
 *   CELLS nc size  + CELL_TYPES nc         (grid)    or   VERTICES n 2n   (points)
 *   POINT_DATA n / CELL_DATA nc, each followed by
 *     SCALARS name double 1 + LOOKUP_TABLE default | VECTORS name double | TENSORS name double
 * BINARY blocks are big-endian (float64 data, int32 cells) and each ends with a newline, which
 * the legacy reader expects before the next keyword. Geometry is written (to the atomic
 * temporary) when the writer is opened; arrays are buffered and written on commit, grouped by
 * location, so callers may add them in any order.
 *
 * Array names must be printable ASCII without whitespace (the reader splits on whitespace) and
 * without '%' (the reader decodes "%xx" escapes in names). Non-finite values are refused with
 * SA_ERR_NAN: a result file never carries NaN/Inf (the ASCII reader cannot even parse them). */
#include "sa_vtk.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_output.h"

#define SA_VTK_NAME_MAX 256 /* the legacy reader reads names into 256-char buffers */
#define SA_VTK_CHUNK 512    /* values per fwrite in binary blocks */

typedef struct {
  char name[SA_VTK_NAME_MAX];
  int ncomp;
  double *values; /* [owned] ncomp * n */
} SaVtkArray;

typedef struct {
  SaVtkArray *a; /* [owned] */
  int n, cap;
} SaVtkArrayList;

struct SaVtk {
  SaFile *file; /* [owned] atomic temporary holding header and geometry */
  SaVtkEncoding enc;
  int npoints, ncells;
  SaVtkArrayList pd, cd;
};

/* ---------------------------------------------------------------------------------------- */
/* Low-level writers                                                                         */

static int sa_vtk_io_error(const SaVtk *v) {
  return SA_ERROR(SA_ERR_IO, "write error on %s", sa_file_target(v->file));
}

/* Big-endian bytes are built with shifts, so the code is correct on any host byte order. */
static int sa_vtk_put_f64(const SaVtk *v, const double *x, size_t n) {
  unsigned char buf[8 * SA_VTK_CHUNK];
  FILE *f = sa_file_stream(v->file);
  size_t k = 0;
  for (size_t i = 0; i < n; i++) {
    uint64_t u;
    memcpy(&u, &x[i], sizeof u);
    for (int b = 0; b < 8; b++) buf[8 * k + (size_t)b] = (unsigned char)(u >> (56 - 8 * b));
    if (++k == SA_VTK_CHUNK) {
      if (fwrite(buf, 8, k, f) != k) return sa_vtk_io_error(v);
      k = 0;
    }
  }
  if (k && fwrite(buf, 8, k, f) != k) return sa_vtk_io_error(v);
  return 0;
}

static int sa_vtk_put_i32(const SaVtk *v, const int32_t *x, size_t n) {
  unsigned char buf[4 * SA_VTK_CHUNK];
  FILE *f = sa_file_stream(v->file);
  size_t k = 0;
  for (size_t i = 0; i < n; i++) {
    uint32_t u = (uint32_t)x[i];
    for (int b = 0; b < 4; b++) buf[4 * k + (size_t)b] = (unsigned char)(u >> (24 - 8 * b));
    if (++k == SA_VTK_CHUNK) {
      if (fwrite(buf, 4, k, f) != k) return sa_vtk_io_error(v);
      k = 0;
    }
  }
  if (k && fwrite(buf, 4, k, f) != k) return sa_vtk_io_error(v);
  return 0;
}

/* n tuples of ncomp doubles: ASCII one tuple per line, BINARY one block ended by '\n'. */
static int sa_vtk_put_tuples(const SaVtk *v, const double *x, size_t n, int ncomp) {
  FILE *f = sa_file_stream(v->file);
  if (v->enc == SA_VTK_BINARY) {
    SA_CHECK(sa_vtk_put_f64(v, x, n * (size_t)ncomp));
    if (fputc('\n', f) == EOF) return sa_vtk_io_error(v);
    return 0;
  }
  for (size_t i = 0; i < n; i++) {
    for (int c = 0; c < ncomp; c++)
      if (fprintf(f, c ? " %.17g" : "%.17g", x[i * (size_t)ncomp + (size_t)c]) < 0)
        return sa_vtk_io_error(v);
    if (fputc('\n', f) == EOF) return sa_vtk_io_error(v);
  }
  return 0;
}

/* ---------------------------------------------------------------------------------------- */
/* Validation                                                                                */

static int sa_vtk_nodes_per_cell(int type) {
  switch (type) {
    case SA_VTK_VERTEX: return 1;
    case SA_VTK_LINE: return 2;
    case SA_VTK_TRIANGLE: return 3;
    case SA_VTK_TETRA: return 4;
    case SA_VTK_QUADRATIC_TETRA: return 10;
  }
  return -1;
}

static int sa_vtk_check_finite(const double *x, size_t n, int ncomp, const char *what,
                               const char *path) {
  for (size_t i = 0; i < n * (size_t)ncomp; i++)
    if (!isfinite(x[i]))
      return SA_ERROR(SA_ERR_NAN, "%s: %s has a non-finite value (%g) at entry %zu component %zu",
                      path, what, x[i], i / (size_t)ncomp, i % (size_t)ncomp);
  return 0;
}

static int sa_vtk_check_name(const char *name) {
  SA_REQUIRE(name && name[0], SA_ERR_INPUT, "VTK array name is empty");
  size_t len = strlen(name);
  SA_REQUIRE(len < SA_VTK_NAME_MAX, SA_ERR_INPUT, "VTK array name '%.40s...' is longer than %d",
             name, SA_VTK_NAME_MAX - 1);
  for (size_t i = 0; i < len; i++) {
    unsigned char c = (unsigned char)name[i];
    SA_REQUIRE(c > 32 && c < 127 && c != '%', SA_ERR_INPUT,
               "VTK array name '%s' must be printable ASCII without spaces or '%%'", name);
  }
  return 0;
}

/* ---------------------------------------------------------------------------------------- */
/* Header and geometry                                                                       */

static void sa_vtk_free(SaVtk *v) {
  if (!v) return;
  SaVtkArrayList *lists[2] = {&v->pd, &v->cd};
  for (int l = 0; l < 2; l++) {
    for (int i = 0; i < lists[l]->n; i++) free(lists[l]->a[i].values);
    free(lists[l]->a);
  }
  sa_file_abort(&v->file); /* no-op after a commit (file is NULL then) */
  free(v);
}

static int sa_vtk_header(SaVtk *v, const char *title, const char *dataset) {
  /* The title is one line of at most 255 characters; newlines would corrupt the file. */
  char line[256];
  snprintf(line, sizeof line, "%s", title && title[0] ? title : "softact");
  for (char *c = line; *c; c++)
    if (*c == '\n' || *c == '\r') *c = ' ';
  FILE *f = sa_file_stream(v->file);
  if (fprintf(f, "# vtk DataFile Version 3.0\n%s\n%s\nDATASET %s\n", line,
              v->enc == SA_VTK_BINARY ? "BINARY" : "ASCII", dataset) < 0)
    return sa_vtk_io_error(v);
  if (fprintf(f, "POINTS %d double\n", v->npoints) < 0) return sa_vtk_io_error(v);
  return 0;
}

/* Writes a cell list: n records "k i0 .. i(k-1)". ASCII one record per line, BINARY int32. */
static int sa_vtk_put_cells(SaVtk *v, const char *keyword, int n, long long size,
                            const int *offsets, const int *conn) {
  FILE *f = sa_file_stream(v->file);
  if (fprintf(f, "%s %d %lld\n", keyword, n, size) < 0) return sa_vtk_io_error(v);
  if (v->enc == SA_VTK_BINARY) {
    int32_t rec[1 + 10];
    for (int c = 0; c < n; c++) {
      int k = offsets ? offsets[c + 1] - offsets[c] : 1;
      rec[0] = k;
      for (int j = 0; j < k; j++) rec[1 + j] = offsets ? conn[offsets[c] + j] : c;
      SA_CHECK(sa_vtk_put_i32(v, rec, (size_t)k + 1));
    }
    if (fputc('\n', f) == EOF) return sa_vtk_io_error(v);
    return 0;
  }
  for (int c = 0; c < n; c++) {
    int k = offsets ? offsets[c + 1] - offsets[c] : 1;
    if (fprintf(f, "%d", k) < 0) return sa_vtk_io_error(v);
    for (int j = 0; j < k; j++)
      if (fprintf(f, " %d", offsets ? conn[offsets[c] + j] : c) < 0) return sa_vtk_io_error(v);
    if (fputc('\n', f) == EOF) return sa_vtk_io_error(v);
  }
  return 0;
}

/* Checks what grid and points share, then opens the atomic temporary. */
static int sa_vtk_create(const char *path, SaVtkEncoding enc, int npoints, const double *xyz,
                         int ncells, SaVtk **out) {
  *out = NULL;
  SA_REQUIRE(path[0], SA_ERR_INPUT, "sa_vtk: empty path");
  SA_REQUIRE(enc == SA_VTK_ASCII || enc == SA_VTK_BINARY, SA_ERR_INPUT,
             "%s: unknown VTK encoding %d", path, (int)enc);
  SA_REQUIRE(npoints >= 0 && ncells >= 0, SA_ERR_INPUT, "%s: negative point (%d) or cell (%d) count",
             path, npoints, ncells);
  SA_REQUIRE(xyz || npoints == 0, SA_ERR_INPUT, "%s: NULL coordinates", path);
  SA_CHECK(sa_vtk_check_finite(xyz, (size_t)npoints, 3, "point coordinates", path));
  SaVtk *v;
  SA_CALLOC(v, 1);
  v->enc = enc;
  v->npoints = npoints;
  v->ncells = ncells;
  int rc = sa_file_open(path, &v->file);
  if (rc) {
    free(v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = v;
  return 0;
}

int sa_vtk_grid_open(const char *path, SaVtkEncoding enc, const char *title, int npoints,
                     const double *xyz, int ncells, const int *cell_types, const int *cell_offsets,
                     const int *conn, SaVtk **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_vtk_grid_open: NULL output handle");
  *out = NULL;
  SA_REQUIRE(path, SA_ERR_INPUT, "sa_vtk_grid_open: NULL path");
  SA_REQUIRE(ncells >= 0, SA_ERR_INPUT, "%s: negative cell count %d", path, ncells);
  SA_REQUIRE(ncells == 0 || (cell_types && cell_offsets), SA_ERR_INPUT,
             "%s: NULL cell types or offsets", path);
  /* Validate every cell before touching the file system. */
  long long nconn = 0;
  if (ncells > 0) {
    SA_REQUIRE(cell_offsets[0] == 0, SA_ERR_INPUT, "%s: cell_offsets[0] = %d, expected 0", path,
               cell_offsets[0]);
    for (int c = 0; c < ncells; c++) {
      int want = sa_vtk_nodes_per_cell(cell_types[c]);
      SA_REQUIRE(want > 0, SA_ERR_INPUT, "%s: cell %d has unsupported VTK type %d", path, c,
                 cell_types[c]);
      int have = cell_offsets[c + 1] - cell_offsets[c];
      SA_REQUIRE(have == want, SA_ERR_INPUT, "%s: cell %d (VTK type %d) has %d nodes, expected %d",
                 path, c, cell_types[c], have, want);
    }
    nconn = cell_offsets[ncells];
    SA_REQUIRE(conn || nconn == 0, SA_ERR_INPUT, "%s: NULL connectivity", path);
    for (long long k = 0; k < nconn; k++)
      SA_REQUIRE(conn[k] >= 0 && conn[k] < npoints, SA_ERR_INPUT,
                 "%s: connectivity entry %lld = %d is outside [0, %d)", path, k, conn[k], npoints);
  }
  SA_REQUIRE(ncells + nconn <= INT32_MAX, SA_ERR_INPUT,
             "%s: %d cells with %lld nodes exceed the int32 range of the legacy format", path,
             ncells, nconn);

  SaVtk *v;
  SA_CHECK(sa_vtk_create(path, enc, npoints, xyz, ncells, &v));
  int rc = sa_vtk_header(v, title, "UNSTRUCTURED_GRID");
  if (!rc) rc = sa_vtk_put_tuples(v, xyz, (size_t)npoints, 3);
  if (!rc) rc = sa_vtk_put_cells(v, "CELLS", ncells, ncells + nconn, cell_offsets, conn);
  if (!rc && fprintf(sa_file_stream(v->file), "CELL_TYPES %d\n", ncells) < 0)
    rc = sa_vtk_io_error(v);
  if (!rc && v->enc == SA_VTK_BINARY) {
    for (int c = 0; c < ncells && !rc; c++) {
      int32_t t = cell_types[c];
      rc = sa_vtk_put_i32(v, &t, 1);
    }
    if (!rc && fputc('\n', sa_file_stream(v->file)) == EOF) rc = sa_vtk_io_error(v);
  } else {
    for (int c = 0; c < ncells && !rc; c++)
      if (fprintf(sa_file_stream(v->file), "%d\n", cell_types[c]) < 0) rc = sa_vtk_io_error(v);
  }
  if (rc) {
    sa_vtk_free(v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = v;
  return 0;
}

int sa_vtk_points_open(const char *path, SaVtkEncoding enc, const char *title, int npoints,
                       const double *xyz, SaVtk **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_vtk_points_open: NULL output handle");
  *out = NULL;
  SA_REQUIRE(path, SA_ERR_INPUT, "sa_vtk_points_open: NULL path");
  SA_REQUIRE(npoints >= 0 && npoints <= INT32_MAX / 2, SA_ERR_INPUT,
             "%s: point count %d outside the range of the legacy format", path, npoints);
  SaVtk *v;
  SA_CHECK(sa_vtk_create(path, enc, npoints, xyz, npoints, &v));
  int rc = sa_vtk_header(v, title, "POLYDATA");
  if (!rc) rc = sa_vtk_put_tuples(v, xyz, (size_t)npoints, 3);
  if (!rc) rc = sa_vtk_put_cells(v, "VERTICES", npoints, 2LL * npoints, NULL, NULL);
  if (rc) {
    sa_vtk_free(v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = v;
  return 0;
}

/* ---------------------------------------------------------------------------------------- */
/* Arrays                                                                                    */

static int sa_vtk_add(SaVtk *v, SaVtkArrayList *list, int n, const char *where, const char *name,
                      int ncomp, const double *values) {
  SA_REQUIRE(v, SA_ERR_INPUT, "sa_vtk: NULL writer");
  const char *path = sa_file_target(v->file);
  SA_CHECK(sa_vtk_check_name(name));
  SA_REQUIRE(ncomp == 1 || ncomp == 3 || ncomp == 9, SA_ERR_INPUT,
             "%s: %s array '%s' has %d components; expected 1 (scalar), 3 (vector) or 9 (tensor)",
             path, where, name, ncomp);
  SA_REQUIRE(values || n == 0, SA_ERR_INPUT, "%s: %s array '%s' has NULL values", path, where,
             name);
  for (int i = 0; i < v->pd.n; i++)
    SA_REQUIRE(strcmp(v->pd.a[i].name, name), SA_ERR_INPUT, "%s: duplicate array name '%s'", path,
               name);
  for (int i = 0; i < v->cd.n; i++)
    SA_REQUIRE(strcmp(v->cd.a[i].name, name), SA_ERR_INPUT, "%s: duplicate array name '%s'", path,
               name);
  char what[SA_VTK_NAME_MAX + 32];
  snprintf(what, sizeof what, "%s array '%s'", where, name);
  SA_CHECK(sa_vtk_check_finite(values, (size_t)n, ncomp, what, path));

  if (list->n == list->cap) {
    int cap = list->cap ? 2 * list->cap : 8;
    SaVtkArray *a = realloc(list->a, (size_t)cap * sizeof *a);
    SA_REQUIRE(a, SA_ERR_MEMORY, "cannot grow the VTK array list to %d", cap);
    list->a = a;
    list->cap = cap;
  }
  SaVtkArray *a = &list->a[list->n];
  SA_CALLOC(a->values, (size_t)n * (size_t)ncomp);
  if (n) memcpy(a->values, values, (size_t)n * (size_t)ncomp * sizeof *values);
  snprintf(a->name, sizeof a->name, "%s", name);
  a->ncomp = ncomp;
  list->n++;
  return 0;
}

int sa_vtk_point_data(SaVtk *v, const char *name, int ncomp, const double *values) {
  SA_REQUIRE(v, SA_ERR_INPUT, "sa_vtk_point_data: NULL writer");
  SA_CHECK(sa_vtk_add(v, &v->pd, v->npoints, "point", name, ncomp, values));
  return 0;
}

int sa_vtk_cell_data(SaVtk *v, const char *name, int ncomp, const double *values) {
  SA_REQUIRE(v, SA_ERR_INPUT, "sa_vtk_cell_data: NULL writer");
  SA_CHECK(sa_vtk_add(v, &v->cd, v->ncells, "cell", name, ncomp, values));
  return 0;
}

static int sa_vtk_put_section(SaVtk *v, const char *keyword, int n, const SaVtkArrayList *list) {
  if (!list->n) return 0;
  FILE *f = sa_file_stream(v->file);
  if (fprintf(f, "%s %d\n", keyword, n) < 0) return sa_vtk_io_error(v);
  for (int i = 0; i < list->n; i++) {
    const SaVtkArray *a = &list->a[i];
    int rc;
    if (a->ncomp == 1)
      rc = fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", a->name);
    else if (a->ncomp == 3)
      rc = fprintf(f, "VECTORS %s double\n", a->name);
    else
      rc = fprintf(f, "TENSORS %s double\n", a->name);
    if (rc < 0) return sa_vtk_io_error(v);
    SA_CHECK(sa_vtk_put_tuples(v, a->values, (size_t)n, a->ncomp));
  }
  return 0;
}

int sa_vtk_commit(SaVtk **vp) {
  SA_REQUIRE(vp && *vp, SA_ERR_INPUT, "sa_vtk_commit: NULL writer");
  SaVtk *v = *vp;
  *vp = NULL;
  int rc = sa_vtk_put_section(v, "POINT_DATA", v->npoints, &v->pd);
  if (!rc) rc = sa_vtk_put_section(v, "CELL_DATA", v->ncells, &v->cd);
  if (!rc) rc = sa_file_commit(&v->file);
  sa_vtk_free(v);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

void sa_vtk_abort(SaVtk **vp) {
  if (!vp || !*vp) return;
  sa_vtk_free(*vp);
  *vp = NULL;
}

/* ---------------------------------------------------------------------------------------- */
/* ParaView .vtk.series                                                                      */

struct SaVtkSeries {
  char *path; /* [owned] */
  char **names; /* [owned] n strings */
  double *times;
  int n, cap;
};

static int sa_vtk_json_string(FILE *f, const char *s) {
  if (fputc('"', f) == EOF) return -1;
  for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
    int rc;
    if (*c == '"' || *c == '\\')
      rc = fprintf(f, "\\%c", *c);
    else if (*c < 0x20)
      rc = fprintf(f, "\\u%04x", *c);
    else
      rc = fputc(*c, f) == EOF ? -1 : 0;
    if (rc < 0) return -1;
  }
  return fputc('"', f) == EOF ? -1 : 0;
}

static int sa_vtk_series_write(const SaVtkSeries *s) {
  SaFile *file;
  SA_CHECK(sa_file_open(s->path, &file));
  FILE *f = sa_file_stream(file);
  int bad = fprintf(f, "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n") < 0;
  for (int i = 0; i < s->n && !bad; i++) {
    bad |= fprintf(f, "    { \"name\" : ") < 0;
    bad |= sa_vtk_json_string(f, s->names[i]) < 0;
    bad |= fprintf(f, ", \"time\" : %.17g }%s\n", s->times[i], i + 1 < s->n ? "," : "") < 0;
  }
  bad |= fprintf(f, "  ]\n}\n") < 0;
  if (bad) {
    sa_file_abort(&file);
    return SA_ERROR(SA_ERR_IO, "write error on %s", s->path);
  }
  SA_CHECK(sa_file_commit(&file));
  return 0;
}

int sa_vtk_series_open(const char *path, SaVtkSeries **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_vtk_series_open: NULL output handle");
  *out = NULL;
  SA_REQUIRE(path && path[0], SA_ERR_INPUT, "sa_vtk_series_open: empty path");
  static const char ext[] = ".vtk.series";
  size_t len = strlen(path), le = sizeof ext - 1;
  SA_REQUIRE(len > le && !strcmp(path + len - le, ext), SA_ERR_INPUT,
             "%s: a VTK series index must end in \"%s\" (ParaView recognises it by that)", path,
             ext);
  SaVtkSeries *s;
  SA_CALLOC(s, 1);
  s->path = strdup(path);
  if (!s->path) {
    free(s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot copy path %s", path);
  }
  /* Write the empty index now: a stale index from an earlier run must not survive. */
  int rc = sa_vtk_series_write(s);
  if (rc) {
    sa_vtk_series_close(&s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

int sa_vtk_series_add(SaVtkSeries *s, const char *file, double time) {
  SA_REQUIRE(s, SA_ERR_INPUT, "sa_vtk_series_add: NULL series");
  SA_REQUIRE(file && file[0], SA_ERR_INPUT, "%s: empty file name", s->path);
  SA_REQUIRE(isfinite(time), SA_ERR_NAN, "%s: non-finite time %g for %s", s->path, time, file);
  if (s->n == s->cap) {
    int cap = s->cap ? 2 * s->cap : 16;
    char **names = realloc(s->names, (size_t)cap * sizeof *names);
    SA_REQUIRE(names, SA_ERR_MEMORY, "cannot grow the series to %d entries", cap);
    s->names = names;
    double *times = realloc(s->times, (size_t)cap * sizeof *times);
    SA_REQUIRE(times, SA_ERR_MEMORY, "cannot grow the series to %d entries", cap);
    s->times = times;
    s->cap = cap;
  }
  s->names[s->n] = strdup(file);
  SA_REQUIRE(s->names[s->n], SA_ERR_MEMORY, "cannot copy file name %s", file);
  s->times[s->n] = time;
  s->n++;
  SA_CHECK(sa_vtk_series_write(s));
  return 0;
}

void sa_vtk_series_close(SaVtkSeries **sp) {
  if (!sp || !*sp) return;
  SaVtkSeries *s = *sp;
  for (int i = 0; i < s->n; i++) free(s->names[i]);
  free(s->names);
  free(s->times);
  free(s->path);
  free(s);
  *sp = NULL;
}
