/* test_atomic.c - atomic writing through the writers: while a file is being written only a
 * hidden temporary exists; abort removes it and leaves an older target untouched; commit
 * replaces the target and leaves no temporary.
 *
 * usage: test_atomic WORKDIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_csv.h"
#include "sa_error.h"
#include "sa_output.h"
#include "sa_vtk.h"
#include "test_util.h"

static const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double s4[4] = {0.25, -1.5, 3.0, 1e-3};

/* While open: temporary present, target absent (or still the old one). */
static void expect_open(const char *dir, const char *what) {
  TU_CHECK(tu_count_matching(dir, ".tmp.") == 1, "%s: %d temporaries while open, expected 1",
           what, tu_count_matching(dir, ".tmp."));
}

static void expect_empty(const char *dir, const char *what) {
  TU_CHECK(tu_count_entries(dir) == 0, "%s: %d entries left in %s after abort", what,
           tu_count_entries(dir), dir);
}

static void test_abort_leaves_nothing(const char *dir) {
  char path[TU_PATH];
  const int tet[1] = {SA_VTK_TETRA}, offs[2] = {0, 4}, conn[4] = {0, 1, 2, 3};

  tu_join(dir, "grid.vtk", path);
  for (int enc = 0; enc < 2; enc++) {
    SaVtk *v = NULL;
    TU_OK(sa_vtk_grid_open(path, (SaVtkEncoding)enc, "t", 4, xyz, 1, tet, offs, conn, &v));
    TU_OK(sa_vtk_point_data(v, "T", 1, s4));
    expect_open(dir, "vtk grid");
    TU_CHECK(!tu_exists(path), "vtk grid: target visible before commit");
    sa_vtk_abort(&v);
    TU_CHECK(v == NULL, "sa_vtk_abort must null the handle");
    expect_empty(dir, "vtk grid");
  }

  tu_join(dir, "cloud.vtk", path);
  SaVtk *v = NULL;
  TU_OK(sa_vtk_points_open(path, SA_VTK_BINARY, "t", 4, xyz, &v));
  expect_open(dir, "vtk points");
  sa_vtk_abort(&v);
  expect_empty(dir, "vtk points");

  tu_join(dir, "table.csv", path);
  const char *names[1] = {"x"};
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(path, 1, names, NULL, &t));
  TU_OK(sa_csv_row(t, s4));
  expect_open(dir, "csv");
  sa_csv_abort(&t);
  TU_CHECK(t == NULL, "sa_csv_abort must null the handle");
  expect_empty(dir, "csv");

  tu_join(dir, "raw.bin", path);
  SaFile *f = NULL;
  TU_OK(sa_file_open(path, &f));
  fputs("partial", sa_file_stream(f));
  expect_open(dir, "sa_file");
  sa_file_abort(&f);
  TU_CHECK(f == NULL, "sa_file_abort must null the handle");
  expect_empty(dir, "sa_file");

  /* Aborting NULL handles is a no-op. */
  sa_vtk_abort(&v);
  sa_csv_abort(&t);
  sa_vtk_abort(NULL);
  sa_csv_abort(NULL);
}

/* An existing result survives an aborted rewrite and is replaced by a committed one. */
static void test_replace(const char *dir) {
  char path[TU_PATH];
  tu_join(dir, "table.csv", path);
  FILE *old = fopen(path, "w");
  TU_CHECK(old, "cannot create %s", path);
  if (!old) return;
  fputs("old content\n", old);
  fclose(old);

  const char *names[1] = {"x"};
  SaCsv *t = NULL;
  TU_OK(sa_csv_open(path, 1, names, NULL, &t));
  TU_OK(sa_csv_row(t, s4));
  size_t n;
  char *text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && !strcmp(text, "old content\n"), "target changed while the new one is open");
  free(text);
  sa_csv_abort(&t);
  text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && !strcmp(text, "old content\n"), "abort changed the existing target");
  free(text);
  TU_CHECK(tu_count_entries(dir) == 1, "abort left %d entries (expected only the old target)",
           tu_count_entries(dir));

  TU_OK(sa_csv_open(path, 1, names, NULL, &t));
  TU_OK(sa_csv_row(t, s4));
  TU_OK(sa_csv_commit(&t));
  text = (char *)tu_slurp(path, &n);
  TU_CHECK(text && !strcmp(text, "# units: x=-\nx\n0.25\n"), "committed table:\n%s",
           text ? text : "(unreadable)");
  free(text);
  TU_CHECK(tu_count_entries(dir) == 1, "commit left %d entries", tu_count_entries(dir));
}

int main(int argc, char **argv) {
  char dir[TU_PATH];
  if (tu_fresh_dir(argc, argv, "abort", dir)) return 1;
  test_abort_leaves_nothing(dir);
  if (tu_fresh_dir(argc, argv, "replace", dir)) return 1;
  test_replace(dir);
  return tu_result();
}
