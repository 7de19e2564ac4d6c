/* test_vtk_errors.c - input validation of the VTK writer and the exact bytes of a small
 * BINARY file (independent of any VTK reader).
 *
 * usage: test_vtk_errors WORKDIR
 * Bad names, component counts, cell types, node counts, connectivity and non-finite values
 * must be refused with the documented code and leave no file; a refused array must not spoil
 * the file. The byte check decodes the big-endian doubles/int32s by hand. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_output.h"
#include "sa_vtk.h"
#include "test_util.h"

static double be_f64(const unsigned char *b) {
  uint64_t u = 0;
  for (int i = 0; i < 8; i++) u = (u << 8) | b[i];
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}

static int32_t be_i32(const unsigned char *b) {
  uint32_t u = 0;
  for (int i = 0; i < 4; i++) u = (u << 8) | b[i];
  return (int32_t)u;
}

/* Finds keyword line `key` in buf and returns a pointer just after its newline. */
static const unsigned char *after_line(const unsigned char *buf, size_t n, const char *key) {
  size_t k = strlen(key);
  for (size_t i = 0; i + k <= n; i++)
    if ((i == 0 || buf[i - 1] == '\n') && !memcmp(buf + i, key, k)) {
      const unsigned char *nl = memchr(buf + i, '\n', n - i);
      return nl ? nl + 1 : NULL;
    }
  return NULL;
}

static void test_binary_bytes(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "bytes.vtk", path);
  const double xyz[6] = {1.0, -2.0, 0.5, 3.0e-300, -0.0, 6.02214076e23};
  const int types[2] = {SA_VTK_LINE, SA_VTK_VERTEX}, offs[3] = {0, 2, 3}, conn[3] = {1, 0, 1};
  const double temp[2] = {-1.5, 0.1};
  SaVtk *v = NULL;
  TU_OK(sa_vtk_grid_open(path, SA_VTK_BINARY, "bytes", 2, xyz, 2, types, offs, conn, &v));
  TU_OK(sa_vtk_point_data(v, "T", 1, temp));
  TU_OK(sa_vtk_commit(&v));
  TU_CHECK(v == NULL, "commit must null the handle");
  size_t n;
  unsigned char *buf = tu_slurp(path, &n);
  TU_CHECK(buf, "cannot read %s", path);
  if (!buf) return;
  const char *head = "# vtk DataFile Version 3.0\nbytes\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
                     "POINTS 2 double\n";
  TU_CHECK(n > strlen(head) && !memcmp(buf, head, strlen(head)), "header differs");
  const unsigned char *p = after_line(buf, n, "POINTS 2 double");
  TU_CHECK(p && p + 48 < buf + n, "POINTS block missing");
  if (p) {
    for (int i = 0; i < 6; i++) {
      double x = be_f64(p + 8 * i);
      TU_CHECK(!memcmp(&x, &xyz[i], 8), "coordinate %d: %g, expected %g", i, x, xyz[i]);
    }
    TU_CHECK(p[48] == '\n', "no newline after the POINTS block");
  }
  p = after_line(buf, n, "CELLS 2 5");
  const int32_t cells[5] = {2, 1, 0, 1, 1};
  TU_CHECK(p && p + 20 < buf + n, "CELLS 2 5 block missing");
  if (p) {
    for (int i = 0; i < 5; i++)
      TU_CHECK(be_i32(p + 4 * i) == cells[i], "CELLS entry %d: %d, expected %d", i,
               be_i32(p + 4 * i), cells[i]);
    TU_CHECK(p[20] == '\n', "no newline after the CELLS block");
  }
  p = after_line(buf, n, "CELL_TYPES 2");
  TU_CHECK(p && p + 8 < buf + n, "CELL_TYPES block missing");
  if (p) {
    TU_CHECK(be_i32(p) == 3 && be_i32(p + 4) == 1, "CELL_TYPES %d %d", be_i32(p), be_i32(p + 4));
    TU_CHECK(p[8] == '\n', "no newline after the CELL_TYPES block");
  }
  p = after_line(buf, n, "LOOKUP_TABLE default");
  TU_CHECK(p && after_line(buf, n, "POINT_DATA 2") && after_line(buf, n, "SCALARS T double 1"),
           "POINT_DATA / SCALARS / LOOKUP_TABLE lines missing");
  if (p) {
    TU_CHECK(p + 17 == buf + n, "file does not end right after the scalars");
    TU_CHECK(be_f64(p) == -1.5 && be_f64(p + 8) == 0.1, "scalars %g %g", be_f64(p), be_f64(p + 8));
    TU_CHECK(p[16] == '\n', "no newline after the scalars block");
  }
  free(buf);
}

static void test_validation(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "bad.vtk", path);
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int tet[1] = {SA_VTK_TETRA}, offs[2] = {0, 4}, conn[4] = {0, 1, 2, 3};
  SaVtk *v = NULL;

  /* Geometry errors: refused before any file exists. */
  const int bad_type[1] = {7}; /* VTK_POLYGON: not supported */
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, bad_type, offs, conn, &v),
          SA_ERR_INPUT);
  const int tri[1] = {SA_VTK_TRIANGLE}; /* 4 nodes given for a triangle */
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, tri, offs, conn, &v), SA_ERR_INPUT);
  const int conn_out[4] = {0, 1, 2, 4};
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, tet, offs, conn_out, &v),
          SA_ERR_INPUT);
  const int conn_neg[4] = {0, 1, -1, 3};
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, tet, offs, conn_neg, &v),
          SA_ERR_INPUT);
  const int offs_bad[2] = {1, 5};
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, tet, offs_bad, conn, &v),
          SA_ERR_INPUT);
  TU_CODE(sa_vtk_grid_open(path, (SaVtkEncoding)5, "t", 4, xyz, 1, tet, offs, conn, &v),
          SA_ERR_INPUT);
  double xyz_nan[12];
  memcpy(xyz_nan, xyz, sizeof xyz);
  xyz_nan[7] = NAN;
  TU_CODE(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz_nan, 1, tet, offs, conn, &v),
          SA_ERR_NAN);
  TU_CODE(sa_vtk_points_open(path, SA_VTK_BINARY, "t", 4, xyz_nan, &v), SA_ERR_NAN);
  TU_CHECK(v == NULL, "a failed open must leave the handle NULL");
  TU_CHECK(tu_count_entries(dir) == 0, "a refused open left a file in %s", dir);

  /* A folder that does not exist: I/O error. */
  char missing[TU_PATH];
  tu_join(dir, "no/such/folder/x.vtk", missing);
  TU_CODE(sa_vtk_points_open(missing, SA_VTK_ASCII, "t", 4, xyz, &v), SA_ERR_IO);

  /* Array errors: refused, the writer stays usable. */
  TU_OK(sa_vtk_grid_open(path, SA_VTK_ASCII, "t", 4, xyz, 1, tet, offs, conn, &v));
  const double s4[4] = {1, 2, 3, 4}, s12[12] = {0};
  const char *bad_names[] = {"", "two words", "tab\tname", "pct%20", "nl\n", "caf\xc3\xa9"};
  for (size_t i = 0; i < sizeof bad_names / sizeof *bad_names; i++)
    TU_CODE(sa_vtk_point_data(v, bad_names[i], 1, s4), SA_ERR_INPUT);
  TU_CODE(sa_vtk_point_data(v, NULL, 1, s4), SA_ERR_INPUT);
  char longname[300];
  memset(longname, 'a', sizeof longname - 1);
  longname[sizeof longname - 1] = 0;
  TU_CODE(sa_vtk_point_data(v, longname, 1, s4), SA_ERR_INPUT);
  TU_CODE(sa_vtk_point_data(v, "u", 2, s12), SA_ERR_INPUT);
  TU_CODE(sa_vtk_point_data(v, "u", 6, s12), SA_ERR_INPUT);
  TU_CODE(sa_vtk_cell_data(v, "u", 0, s12), SA_ERR_INPUT);
  TU_CODE(sa_vtk_point_data(v, "u", 3, NULL), SA_ERR_INPUT);
  double s4_inf[4] = {1, 2, INFINITY, 4};
  TU_CODE_MSG(sa_vtk_point_data(v, "hot", 1, s4_inf), SA_ERR_NAN, "'hot'");
  TU_OK(sa_vtk_point_data(v, "T", 1, s4));
  TU_CODE(sa_vtk_point_data(v, "T", 1, s4), SA_ERR_INPUT);   /* duplicate */
  TU_CODE(sa_vtk_cell_data(v, "T", 1, s4), SA_ERR_INPUT);    /* same name, other location */
  TU_OK(sa_vtk_cell_data(v, "vol", 1, s4));
  TU_OK(sa_vtk_commit(&v));
  size_t n;
  char *text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && strstr(text, "SCALARS T double") && strstr(text, "CELL_DATA 1") &&
               !strstr(text, "hot") && !strstr(text, "nan") && !strstr(text, "inf"),
           "committed file has wrong arrays:\n%s", text ? text : "(unreadable)");
  free(text);

  /* Series: name must end in .vtk.series; times must be finite. */
  SaVtkSeries *s = NULL;
  tu_join(dir, "run.series", path);
  TU_CODE(sa_vtk_series_open(path, &s), SA_ERR_INPUT);
  tu_join(dir, "run.vtk.series", path);
  TU_OK(sa_vtk_series_open(path, &s));
  TU_CODE(sa_vtk_series_add(s, "a.vtk", NAN), SA_ERR_NAN);
  TU_CODE(sa_vtk_series_add(s, "", 0.0), SA_ERR_INPUT);
  TU_OK(sa_vtk_series_add(s, "a.vtk", 0.5));
  sa_vtk_series_close(&s);
  TU_CHECK(s == NULL, "close must null the handle");
  text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && strstr(text, "\"a.vtk\"") && !strstr(text, "nan"), "series:\n%s",
           text ? text : "(unreadable)");
  free(text);
  sa_vtk_abort(&v); /* NULL: no-op */
  sa_vtk_series_close(&s);
}

int main(int argc, char **argv) {
  char dir[TU_PATH];
  if (tu_fresh_dir(argc, argv, "bytes", dir)) return 1;
  test_binary_bytes(dir);
  if (tu_fresh_dir(argc, argv, "validation", dir)) return 1;
  test_validation(dir);
  return tu_result();
}
