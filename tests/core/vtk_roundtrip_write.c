/* vtk_roundtrip_write.c - writes the VTK files that check_vtk_roundtrip.py reads back with
 * VTK's own legacy readers, plus manifest.json describing what was written.
 *
 * usage: vtk_roundtrip_write OUTDIR
 *
 * Every dataset (unstructured grid with vertex, line, triangle, tet4 and tet10 cells; POLYDATA
 * point cloud) is written in ASCII and BINARY with point and cell arrays of 1, 3 and 9
 * components (two scalars per location, so the reader must keep more than the active one).
 * Values come from sin/exp and are scaled to span signs and magnitudes from 1e-200 to 1e250,
 * so a lost digit, a byte-order or a component-order mistake cannot go unnoticed. The manifest
 * records the expected values as C99 hex floats ("%a"), which Python's float.fromhex reads
 * exactly: the expected values reach the checker without any decimal conversion. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sa_error.h"
#include "sa_output.h"
#include "sa_vtk.h"

#define NP 14 /* grid points */
#define NC 6  /* grid cells */
#define NQ 7  /* point-cloud points */
#define PATH_LEN 1024

/* Non-round value k of stream s, with magnitudes cycling over many decades and both signs. */
static double value(int s, int k) {
  static const double scale[] = {1.0, -3.0e-200, 7.0e250, -1.0e-7, 2.5e3, 1.0e-30};
  double x = sin(0.37 * k + 1.3 * s + 0.11) * exp(0.5 * sin(0.7 * k + s));
  return x * scale[(k + s) % 6];
}

static void fill(double *a, int n, int s) {
  for (int k = 0; k < n; k++) a[k] = value(s, k);
}

static void put_hex_list(FILE *m, const double *a, int n) {
  fputc('[', m);
  for (int k = 0; k < n; k++) fprintf(m, "%s\"%a\"", k ? "," : "", a[k]);
  fputc(']', m);
}

static void put_int_list(FILE *m, const int *a, int n) {
  fputc('[', m);
  for (int k = 0; k < n; k++) fprintf(m, "%s%d", k ? "," : "", a[k]);
  fputc(']', m);
}

typedef struct {
  const char *name;
  int ncomp, stream;
} ArraySpec;

static const ArraySpec point_arrays[] = {
    {"temperature", 1, 11}, {"pressure_p", 1, 12}, {"displacement", 3, 13}, {"stress", 9, 14}};
static const ArraySpec cell_arrays[] = {
    {"damage", 1, 21}, {"J", 1, 22}, {"fibre_dir", 3, 23}, {"F", 9, 24}};
#define NARR 4

/* Adds the arrays (in an order mixing locations, to exercise buffering) and describes them. */
static int add_arrays(SaVtk *v, int np, int nc, FILE *m) {
  double *buf = malloc(sizeof(double) * 9 * (size_t)(np > nc ? np : nc));
  if (!buf) return SA_ERR_MEMORY;
  fprintf(m, ",\"point_data\":[");
  for (int i = 0; i < NARR; i++) {
    const ArraySpec *a = &point_arrays[i];
    fill(buf, a->ncomp * np, a->stream);
    int rc = sa_vtk_point_data(v, a->name, a->ncomp, buf);
    if (rc) {
      free(buf);
      return rc;
    }
    fprintf(m, "%s{\"name\":\"%s\",\"ncomp\":%d,\"values\":", i ? "," : "", a->name, a->ncomp);
    put_hex_list(m, buf, a->ncomp * np);
    fputc('}', m);
    const ArraySpec *c = &cell_arrays[i];
    fill(buf, c->ncomp * nc, c->stream);
    rc = sa_vtk_cell_data(v, c->name, c->ncomp, buf);
    if (rc) {
      free(buf);
      return rc;
    }
  }
  fprintf(m, "],\"cell_data\":[");
  for (int i = 0; i < NARR; i++) {
    const ArraySpec *c = &cell_arrays[i];
    fill(buf, c->ncomp * nc, c->stream);
    fprintf(m, "%s{\"name\":\"%s\",\"ncomp\":%d,\"values\":", i ? "," : "", c->name, c->ncomp);
    put_hex_list(m, buf, c->ncomp * nc);
    fputc('}', m);
  }
  fputc(']', m);
  free(buf);
  return 0;
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  const char *dir = argv[1];
  char path[PATH_LEN], mpath[PATH_LEN];
  snprintf(mpath, sizeof mpath, "%s/manifest.json", dir);
  FILE *m = fopen(mpath, "w");
  if (!m) {
    perror(mpath);
    return 1;
  }

  /* Grid: points 0..3 carry the vertex/line/triangle/tet4 cells, 4..13 one tet10. */
  double xyz[3 * NP];
  fill(xyz, 3 * NP, 1);
  const int types[NC] = {SA_VTK_VERTEX, SA_VTK_LINE, SA_VTK_TRIANGLE,
                         SA_VTK_TETRA,  SA_VTK_QUADRATIC_TETRA, SA_VTK_LINE};
  const int offsets[NC + 1] = {0, 1, 3, 6, 10, 20, 22};
  const int conn[22] = {3, 0, 1, 2, 0, 3, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 13, 0};
  double cloud[3 * NQ];
  fill(cloud, 3 * NQ, 2);

  const char *enc_name[2] = {"ascii", "binary"};
  SaVtkSeries *series = NULL;
  snprintf(path, sizeof path, "%s/grid.vtk.series", dir);
  int rc = sa_vtk_series_open(path, &series);
  double times[2] = {0.0, exp(-1.0) * 1e-3};
  fprintf(m, "{\"datasets\":[");
  for (int e = 0; e < 2 && !rc; e++) {
    SaVtk *v = NULL;
    char name[64];
    snprintf(name, sizeof name, "grid_%s.vtk", enc_name[e]);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    rc = sa_vtk_grid_open(path, (SaVtkEncoding)e, "softact grid round trip", NP, xyz, NC, types,
                          offsets, conn, &v);
    if (rc) break;
    fprintf(m, "%s{\"file\":\"%s\",\"kind\":\"grid\",\"encoding\":\"%s\",\"points\":", e ? "," : "",
            name, enc_name[e]);
    put_hex_list(m, xyz, 3 * NP);
    fprintf(m, ",\"cell_types\":");
    put_int_list(m, types, NC);
    fprintf(m, ",\"cell_offsets\":");
    put_int_list(m, offsets, NC + 1);
    fprintf(m, ",\"conn\":");
    put_int_list(m, conn, offsets[NC]);
    rc = add_arrays(v, NP, NC, m);
    if (!rc) rc = sa_vtk_commit(&v);
    sa_vtk_abort(&v);
    fputc('}', m);
    if (!rc) rc = sa_vtk_series_add(series, name, times[e]);
  }
  for (int e = 0; e < 2 && !rc; e++) {
    SaVtk *v = NULL;
    char name[64];
    snprintf(name, sizeof name, "cloud_%s.vtk", enc_name[e]);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    rc = sa_vtk_points_open(path, (SaVtkEncoding)e, "softact cloud round trip", NQ, cloud, &v);
    if (rc) break;
    fprintf(m, ",{\"file\":\"%s\",\"kind\":\"points\",\"encoding\":\"%s\",\"points\":", name,
            enc_name[e]);
    put_hex_list(m, cloud, 3 * NQ);
    rc = add_arrays(v, NQ, NQ, m);
    if (!rc) rc = sa_vtk_commit(&v);
    sa_vtk_abort(&v);
    fputc('}', m);
  }
  /* A name that needs JSON escaping (quote, backslash) must still give a valid index. */
  const char *odd = "odd \"name\"\\x.vtk";
  if (!rc) rc = sa_vtk_series_add(series, odd, 2.5);
  sa_vtk_series_close(&series);
  fprintf(m, "],\"series\":{\"file\":\"grid.vtk.series\",\"entries\":[");
  fprintf(m, "{\"name\":\"grid_ascii.vtk\",\"time\":\"%a\"},", times[0]);
  fprintf(m, "{\"name\":\"grid_binary.vtk\",\"time\":\"%a\"},", times[1]);
  fprintf(m, "{\"name\":\"odd \\\"name\\\"\\\\x.vtk\",\"time\":\"%a\"}]}}\n", 2.5);
  if (fclose(m) != 0) rc = rc ? rc : SA_ERR_IO;
  if (rc) {
    sa_error_print();
    return 1;
  }
  return 0;
}
