/* test_mesh_errors.c - bad input is reported, not crashed on:
 *  - a missing .geo / .msh gives SA_ERR_INPUT naming the file;
 *  - a .geo with a syntax error, or without any physical volume, gives SA_ERR_INPUT naming it;
 *  - a .geo lacking a required group passes generation but fem_mesh_require names the group;
 *  - a bad parameter name is rejected;
 *  - fem_mesh_check rejects a hand-built inverted tet4 (swapped nodes), a flat tet4 and a tet10
 *    whose mid-node is dragged across the element, naming the element, and a curved tet10
 *    inverted only at a point of the 8-point rule curved elements are integrated with;
 *  - fem_mesh_quality gives the radius ratio of known tets (corner tet sqrt 3 - 1, regular 1);
 * and fem_mesh_read reads back a .msh written by Gmsh from cook.geo (same counts and volume as
 * fem_mesh_generate). */
#include <gmshc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh_test_util.h"
#include "sa_error.h"
#include "sa_log.h"

static int expect(int rc, int code, const char *needle, const char *what)
{
  const char *msg = sa_error_message();
  int ok = (rc == code) && strstr(msg, needle) != NULL;
  if (!ok) fprintf(stderr, "%s: rc %d (want %d), message '%s' (want it to name '%s')\n", what, rc,
                   code, msg, needle);
  sa_error_clear();
  return !ok;
}

static int write_file(const char *path, const char *text)
{
  FILE *f = fopen(path, "w");
  if (!f) return 1;
  fputs(text, f);
  return fclose(f) != 0;
}

/* Two tets sharing face (1,2,3), positively oriented. */
static void two_tets(FemMesh *m, double *xyz, int *conn, int *region, char (*names)[64])
{
  static const double X[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  static const int C[] = {0, 1, 2, 3, 1, 4, 2, 3};
  memcpy(xyz, X, sizeof X);
  memcpy(conn, C, sizeof C);
  region[0] = region[1] = 0;
  strcpy(names[0], "solid");
  memset(m, 0, sizeof *m);
  m->nnodes = 5;
  m->xyz = xyz;
  m->etype = FEM_TET4;
  m->nen = 4;
  m->nelem = 2;
  m->conn = conn;
  m->region = region;
  m->nregions = 1;
  m->region_names = names;
  strcpy(m->source, "hand-built");
}

static int test_check(void)
{
  int fail = 0;
  double xyz[15 + 30];
  int conn[20], region[2];
  char names[1][64];
  FemMesh m;
  two_tets(&m, xyz, conn, region, names);
  /* orientation of the second tet: (x1-x0, x2-x0, x3-x0) = ((1,1,1)-(1,0,0), ...) */
  if (fem_mesh_check(&m, 1e-6)) {
    sa_error_print();
    fail = 1;
  }
  /* radius ratio of the unit corner tet: r_in = 1 / (3 + sqrt 3), r_circ = sqrt 3 / 2, so
   * 3 r_in / r_circ = sqrt 3 - 1; a regular tet gives 1 */
  double qmin, qmean;
  int worst = fem_mesh_quality(&m, 0, &qmin, &qmean);
  fail |= !mt_close("corner tet radius ratio", qmin, sqrt(3.0) - 1.0, 0, 1e-12);
  if (worst != 0) fprintf(stderr, "worst element %d, expected 0\n", worst), fail = 1;
  static const double reg[] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
  double xr[12];
  int cr[4] = {0, 1, 2, 3}, rr = 0;
  memcpy(xr, reg, sizeof reg);
  FemMesh R = m;
  R.nnodes = 4, R.xyz = xr, R.nelem = 1, R.conn = cr, R.region = &rr;
  fem_mesh_quality(&R, -1, &qmin, &qmean);
  if (fem_mesh_check(&R, 1e-6)) { /* orient positively if the listed order is negative */
    sa_error_clear();
    cr[1] = 2, cr[2] = 1;
  }
  fem_mesh_quality(&R, -1, &qmin, &qmean);
  fail |= !mt_close("regular tet radius ratio", qmin, 1.0, 0, 1e-12);

  int t = conn[5];
  conn[5] = conn[6], conn[6] = t; /* swap nodes 1 and 2 of element 1 */
  fail |= expect(fem_mesh_check(&m, 1e-6), SA_ERR_INPUT, "element 1", "inverted tet4");
  conn[6] = conn[5], conn[5] = t;
  double z = xyz[3 * 3 + 2];
  xyz[3 * 3 + 2] = 1e-9; /* flatten: node 3 almost in the plane of 0, 1, 2 */
  fail |= expect(fem_mesh_check(&m, 1e-6), SA_ERR_INPUT, "element 0", "flat tet4");
  xyz[3 * 3 + 2] = z;

  /* One straight tet10 (unit corner tet), then mid-node of edge 01 dragged past corner 1. */
  static const double C10[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const int E[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  double x10[30];
  int c10[10], r10 = 0;
  memcpy(x10, C10, sizeof C10);
  for (int k = 0; k < 6; ++k)
    for (int i = 0; i < 3; ++i) x10[3 * (4 + k) + i] = 0.5 * (C10[3 * E[k][0] + i] + C10[3 * E[k][1] + i]);
  for (int a = 0; a < 10; ++a) c10[a] = a;
  FemMesh q = m;
  q.nnodes = 10;
  q.xyz = x10;
  q.etype = FEM_TET10;
  q.nen = 10;
  q.nelem = 1;
  q.conn = c10;
  q.region = &r10;
  if (fem_mesh_check(&q, 1e-6)) {
    sa_error_print();
    fail = 1;
  }
  x10[3 * 4] = 1.2; /* mid-node of edge 01 beyond node 1: det J < 0 near corner 1 */
  fail |= expect(fem_mesh_check(&q, 1e-6), SA_ERR_INPUT, "element 0", "inverted tet10");
  /* Curved tet10 whose det J is positive at the corners and at the 4- and 14-point rules'
   * points (min 0.65, 0.015, 0.0032) but negative at a point of the 8-point rule the kernels
   * use for curved elements (min -0.0084; found by a random search over mid-node positions). */
  static const double mid8[18] = {
      0.30335951605968153, -0.25301169448206745, 0.26354838230812389, 0.163594731345584,
      0.27006169714502137, 0.31387513350410168, 0.053458643543281871, 0.30040513547156245,
      0.25457864992999407, -0.35119399277083296, -0.051683654846476218, 0.71568102306485226,
      0.66049330558650809, -0.38202236256656352, 0.8161371893790258, -0.049657362163838627,
      0.66010041262959152, 0.16078424493818738};
  memcpy(x10 + 12, mid8, sizeof mid8);
  fail |= expect(fem_mesh_check(&q, 1e-12), SA_ERR_INPUT, "element 0",
                 "tet10 inverted at an 8-point-rule point");
  return fail;
}

static int test_files(const char *dir)
{
  int fail = 0;
  FemMesh *m = NULL;
  char path[1024];
  snprintf(path, sizeof path, "%s/no_such.geo", dir);
  fail |= expect(fem_mesh_generate(path, 0, NULL, 0.0, 2, &m), SA_ERR_INPUT, "no_such.geo",
                 "missing .geo");
  snprintf(path, sizeof path, "%s/no_such.msh", dir);
  fail |= expect(fem_mesh_read(path, &m), SA_ERR_INPUT, "no_such.msh", "missing .msh");

  snprintf(path, sizeof path, "%s/syntax.geo", dir);
  write_file(path, "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1;\n");
  fail |= expect(fem_mesh_generate(path, 0, NULL, 0.5, 1, &m), SA_ERR_INPUT, "syntax.geo",
                 "syntax error");

  snprintf(path, sizeof path, "%s/novolume.geo", dir);
  write_file(path, "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                   "Physical Surface(\"loaded\") = {1};\n");
  fail |= expect(fem_mesh_generate(path, 0, NULL, 0.5, 1, &m), SA_ERR_INPUT, "novolume.geo",
                 "no physical volume");

  snprintf(path, sizeof path, "%s/nogroup.geo", dir);
  write_file(path, "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                   "Physical Volume(\"solid\") = {1};\nPhysical Surface(\"clamped\") = {1};\n"
                   "Mesh.MeshSizeMax = h;\n");
  const FemGeoParam bad[] = {{"1x", 1.0}};
  fail |= expect(fem_mesh_generate(path, 1, bad, 0.5, 1, &m), SA_ERR_INPUT, "1x", "bad parameter");
  if (fem_mesh_generate(path, 0, NULL, 0.5, 2, &m)) {
    sa_error_print();
    return 1;
  }
  const char *regs[] = {"solid"}, *surfs[] = {"clamped", "loaded"}, *regs2[] = {"silicone"};
  fail |= expect(fem_mesh_require(m, 1, regs, 2, surfs), SA_ERR_INPUT, "'loaded'", "missing surface");
  fail |= expect(fem_mesh_require(m, 1, regs2, 0, NULL), SA_ERR_INPUT, "'silicone'", "missing region");
  if (fem_mesh_require(m, 1, regs, 1, surfs)) {
    sa_error_print();
    fail = 1;
  }
  fem_mesh_destroy(&m);
  return fail;
}

/* Gmsh writes cook.geo's tet10 mesh; fem_mesh_read must give what fem_mesh_generate gives. */
static int test_read(const char *dir)
{
  char geo[512], msh[1024];
  mt_geo("cook.geo", geo, sizeof geo);
  snprintf(msh, sizeof msh, "%s/cook.msh", dir);
  int ierr = 0, fail = 0;
  gmshInitialize(0, NULL, 0, &ierr);
  gmshOptionSetNumber("General.Terminal", 0, &ierr);
  gmshOpen(geo, &ierr);
  gmshModelMeshGenerate(3, &ierr);
  gmshModelMeshSetOrder(2, &ierr);
  gmshWrite(msh, &ierr);
  gmshFinalize(&ierr);
  if (ierr) {
    fprintf(stderr, "gmsh could not write %s\n", msh);
    return 1;
  }
  FemMesh *a = NULL, *b = NULL;
  if (fem_mesh_read(msh, &a) || fem_mesh_generate(geo, 0, NULL, 0.0, 2, &b)) {
    sa_error_print();
    fem_mesh_destroy(&a);
    return 1;
  }
  if (a->nelem != b->nelem || a->nnodes != b->nnodes || a->nsurfaces != b->nsurfaces ||
      a->etype != FEM_TET10) {
    fprintf(stderr, "read %d elements %d nodes %d surfaces, generated %d %d %d\n", a->nelem,
            a->nnodes, a->nsurfaces, b->nelem, b->nnodes, b->nsurfaces);
    fail = 1;
  }
  /* same geometry: volumes agree to round-off (the .msh stores 16 significant digits) */
  fail |= !mt_close("read vs generated volume", fem_mesh_volume(a, -1), fem_mesh_volume(b, -1), 0,
                    1e-12);
  if (fem_mesh_check(a, 1e-6)) {
    sa_error_print();
    fail = 1;
  }
  fem_mesh_destroy(&a);
  fem_mesh_destroy(&b);
  remove(msh);
  return fail;
}

int main(void)
{
  sa_log_set_level(SA_LOG_WARN);
  const char *tmp = getenv("TMPDIR");
  char dir[512];
  snprintf(dir, sizeof dir, "%s/softact-mesh-test-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  int fail = 0;
  fail |= test_check();
  fail |= test_files(dir);
  fail |= test_read(dir);
  const char *files[] = {"syntax.geo", "novolume.geo", "nogroup.geo"};
  for (int i = 0; i < 3; ++i) {
    char p[1024];
    snprintf(p, sizeof p, "%s/%s", dir, files[i]);
    remove(p);
  }
  rmdir(dir);
  return fail;
}
