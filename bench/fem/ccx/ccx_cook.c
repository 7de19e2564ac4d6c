/* ccx_cook.c - Cook's membrane (nearly incompressible neo-Hookean, plane strain, dead shear load)
 * as a CalculiX deck on a structured n x n x 1 mesh of 20-node hexahedra (C3D20R or C3D20).
 *
 * The same problem as tests/fem/solver/test_cook.c and bench/fem/ccx/cook_ours.c:
 *  - geometry (mm): the bilinear map of the unit square (a, b) onto the quadrilateral
 *    (0,0), (48,44), (48,60), (0,44); thickness t = 1 (z in [0, 1]), one element thick;
 *  - u_z = 0 at every node (plane strain), left edge x = 0 clamped (u_x = u_y = 0);
 *  - dead load F = 32 N in +y, a uniform traction F / (16 t) on the right edge x = 48, given as
 *    *CLOAD (fixed direction and size: a dead load, unlike *DLOAD pressures, which follow the face
 *    under NLGEOM) with the consistent nodal forces of each 8-node face: for a serendipity quad
 *    whose map is affine (here: a rectangle 16/n x 1) under a uniform traction, corner nodes get
 *    -1/12 and mid-edge nodes +1/3 of the face force (int N_i dA: corners -1/12, mid +1/3 of A);
 *    the program sums the nodal forces and checks that the total is F;
 *  - material: W = C10 (I1b - 3) + (1/D1) (J - 1)^2 with C10 = mu/2, D1 = 2/kappa
 *    (*HYPERELASTIC, NEO HOOKE), i.e. mu/2 (I1b - 3) + kappa/2 (J - 1)^2, the law of
 *    FEM_MAT_NEOHOOKE; mu = 80.194 MPa, kappa = 400889.8 MPa by default (K/mu ~ 5000);
 *  - *STATIC with NLGEOM, the load ramped linearly over the step in a few increments.
 * Output (BASE.dat): U of N_A (the corner (48, 60) at z = 0 and z = 1) at every increment and
 * the total reaction force of the clamp (RF, TOTALS=ONLY: must be (0, -F, 0) at the end).
 *
 * CalculiX 2.20 conventions (see ccx_inp.h): C3D20 corners 1-4 on zeta = -1 counter-clockwise
 * seen from zeta = +1, corners 5-8 above them, mid-nodes 9:(1,2) 10:(2,3) 11:(3,4) 12:(4,1)
 * 13:(5,6) 14:(6,7) 15:(7,8) 16:(8,5) 17:(1,5) 18:(2,6) 19:(3,7) 20:(4,8); numbers are printed
 * with %.12e (ccx reads a number from at most 20 characters); at most 16 entries per data line.
 *
 * Nodes live on the (2n+1) x (2n+1) x 3 lattice of half-element steps (i, j, k): the levels
 * k = 0, 2 hold the corner and mid-edge nodes (not the face centres, i and j both odd), the level
 * k = 1 the mid-nodes of the vertical edges (i and j both even).
 *
 * usage: ccx_cook --n N --out BASE [--etype C3D20R|C3D20] [--mu MU] [--kappa K | --kappa-ratio R]
 *                 [--force F] [--inc0 F] [--incmin F] [--incmax F] [--tol R]
 * prints one line: ccx_cook: BASE.inp nodes N dof N elems N etype E kappa K load_sum F */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

#define COOK_L 16.0 /* length of the loaded right edge [mm] */

/* Lattice offsets (0, 1, 2 in half-element steps) of the 20 C3D20 nodes. */
static const int kOff[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2},
                                {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0},
                                {1, 0, 2}, {2, 1, 2}, {1, 2, 2}, {0, 1, 2}, {0, 0, 1}, {2, 0, 1},
                                {2, 2, 1}, {0, 2, 1}};

static void map_cook(double a, double b, double xy[2])
{
  static const double P[4][2] = {{0, 0}, {48, 44}, {48, 60}, {0, 44}};
  const double w[4] = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
  xy[0] = xy[1] = 0;
  for (int k = 0; k < 4; ++k) {
    xy[0] += w[k] * P[k][0];
    xy[1] += w[k] * P[k][1];
  }
}

typedef struct {
  int n, m;       /* elements per side, lattice points per side (2n + 1) */
  int nnodes, nelem;
  int *id;        /* [owned] m * m * 3 lattice -> node index, -1 where there is no node */
  double *xyz;    /* [owned] 3 * nnodes */
  int *conn;      /* [owned] 20 * nelem, 0-based */
  double *fy;     /* [owned] nnodes: y-force of the load */
} Cook;

static int lat(const Cook *c, int i, int j, int k) { return (k * c->m + j) * c->m + i; }

static void cook_free(Cook *c)
{
  free(c->id);
  free(c->xyz);
  free(c->conn);
  free(c->fy);
}

static int cook_build(Cook *c, int n, double force)
{
  c->n = n;
  c->m = 2 * n + 1;
  SA_CALLOC(c->id, (size_t)c->m * c->m * 3);
  SA_CALLOC(c->xyz, 3 * (size_t)c->m * c->m * 3);
  c->nnodes = 0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < c->m; ++j)
      for (int i = 0; i < c->m; ++i) {
        int face_centre = (i % 2) && (j % 2), mid_level_off = k == 1 && ((i % 2) || (j % 2));
        if (face_centre || mid_level_off) {
          c->id[lat(c, i, j, k)] = -1;
          continue;
        }
        int v = c->nnodes++;
        c->id[lat(c, i, j, k)] = v;
        map_cook((double)i / (c->m - 1), (double)j / (c->m - 1), c->xyz + 3 * (size_t)v);
        c->xyz[3 * (size_t)v + 2] = 0.5 * k;
      }
  c->nelem = n * n;
  SA_CALLOC(c->conn, 20 * (size_t)c->nelem);
  for (int ej = 0; ej < n; ++ej)
    for (int ei = 0; ei < n; ++ei) {
      int *e = c->conn + 20 * (size_t)(ej * n + ei);
      for (int q = 0; q < 20; ++q) {
        e[q] = c->id[lat(c, 2 * ei + kOff[q][0], 2 * ej + kOff[q][1], kOff[q][2])];
        SA_REQUIRE(e[q] >= 0, SA_ERR_INTERNAL, "element (%d,%d) node %d missing", ei, ej, q + 1);
      }
    }
  /* Consistent forces of the uniform traction on each right-edge face (the element's face
   * xi = +1, F4 = nodes 2,3,7,6 with mid-nodes 10,14,18,19): the face is the rectangle
   * [y_j, y_j + 16/n] x [0, 1] (the map is affine along a = 1), face force f = F / n. */
  SA_CALLOC(c->fy, c->nnodes);
  static const int corner[4] = {1, 2, 6, 5}, mid[4] = {9, 13, 17, 18};
  for (int ej = 0; ej < n; ++ej) {
    const int *e = c->conn + 20 * (size_t)(ej * n + n - 1);
    double area = fabs(c->xyz[3 * (size_t)e[2] + 1] - c->xyz[3 * (size_t)e[1] + 1]) *
                  fabs(c->xyz[3 * (size_t)e[5] + 2] - c->xyz[3 * (size_t)e[1] + 2]);
    double f = force / COOK_L * area;
    for (int q = 0; q < 4; ++q) {
      c->fy[e[corner[q]]] += -f / 12.0;
      c->fy[e[mid[q]]] += f / 3.0;
    }
  }
  return 0;
}

/* A node list, 1-based, 16 per line. */
static void write_list(FILE *f, int n, const int *v)
{
  for (int i = 0; i < n; ++i) fprintf(f, "%d%s", v[i] + 1, (i % 16 == 15 || i == n - 1) ? "\n" : ",");
}

typedef struct {
  const char *etype;
  double mu, kappa, force, inc0, incmin, incmax;
  double tol; /* > 0: *CONTROLS with R_n = C_n = tol (ccx defaults 0.005, 0.01 otherwise) */
} CookDeck;

static int cook_write(const Cook *c, const CookDeck *d, const char *path, double *load_sum)
{
  FILE *f = fopen(path, "w");
  SA_REQUIRE(f, SA_ERR_IO, "cannot write %s", path);
  int *list = malloc(sizeof(int) * (size_t)c->nnodes);
  if (!list) {
    fclose(f);
    return SA_ERROR(SA_ERR_MEMORY, "out of memory");
  }
  fprintf(f, "** softact Cook's membrane (bench/fem/ccx/ccx_cook.c): units mm, N, MPa\n");
  fprintf(f, "** %d x %d x 1 %s, mu %.12g, kappa %.12g, dead shear load %.12g N\n", c->n, c->n,
          d->etype, d->mu, d->kappa, d->force);
  fprintf(f, "*NODE, NSET=NALL\n");
  for (int v = 0; v < c->nnodes; ++v)
    fprintf(f, "%d, %.12e, %.12e, %.12e\n", v + 1, c->xyz[3 * v], c->xyz[3 * v + 1],
            c->xyz[3 * v + 2]);
  fprintf(f, "*ELEMENT, TYPE=%s, ELSET=EALL\n", d->etype);
  for (int e = 0; e < c->nelem; ++e) {
    fprintf(f, "%d", e + 1);
    for (int q = 0; q < 20; ++q) fprintf(f, ",%s%d", q == 15 ? "\n" : "", c->conn[20 * e + q] + 1);
    fprintf(f, "\n");
  }
  int nl = 0;
  for (int v = 0; v < c->nnodes; ++v)
    if (fabs(c->xyz[3 * v]) < 1e-9) list[nl++] = v;
  fprintf(f, "*NSET, NSET=N_CLAMP\n");
  write_list(f, nl, list);
  nl = 0;
  for (int v = 0; v < c->nnodes; ++v)
    if (fabs(c->xyz[3 * v] - 48) < 1e-9 && fabs(c->xyz[3 * v + 1] - 60) < 1e-9 &&
        (fabs(c->xyz[3 * v + 2]) < 1e-9 || fabs(c->xyz[3 * v + 2] - 1) < 1e-9))
      list[nl++] = v;
  int rc = nl == 2 ? 0 : SA_ERROR(SA_ERR_INTERNAL, "corner (48, 60) has %d nodes, expected 2", nl);
  fprintf(f, "*NSET, NSET=N_A\n");
  write_list(f, nl, list);
  fprintf(f, "*MATERIAL, NAME=RUBBER\n*HYPERELASTIC, NEO HOOKE\n%.12e, %.12e\n", 0.5 * d->mu,
          2.0 / d->kappa);
  fprintf(f, "*SOLID SECTION, ELSET=EALL, MATERIAL=RUBBER\n");
  fprintf(f, "*AMPLITUDE, NAME=RAMP\n0., 0., 1., 1.\n");
  fprintf(f, "*STEP, NLGEOM, INC=1000\n");
  /* R_n (largest residual / mean force) and C_n (largest correction / largest increment), the
   * first two FIELD controls; the iteration limits are raised so that the tighter test does not
   * trigger ccx's divergence heuristics (empty fields keep ccx's defaults). */
  if (d->tol > 0)
    fprintf(f, "*CONTROLS, PARAMETERS=FIELD\n%.3e, %.3e,,,,,,\n"
               "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n100, 100, 100, 100, 100,,,,,\n",
            d->tol, d->tol);
  fprintf(f, "*STATIC\n%.9g, 1., %.9g, %.9g\n", d->inc0, d->incmin, d->incmax);
  fprintf(f, "*BOUNDARY\nN_CLAMP, 1, 2\nNALL, 3, 3\n");
  fprintf(f, "*CLOAD, AMPLITUDE=RAMP\n");
  double sum = 0;
  for (int v = 0; v < c->nnodes; ++v)
    if (c->fy[v] != 0) {
      fprintf(f, "%d, 2, %.12e\n", v + 1, c->fy[v]);
      sum += c->fy[v];
    }
  fprintf(f, "*NODE PRINT, NSET=N_A, FREQUENCYF=1\nU\n");
  fprintf(f, "*NODE PRINT, NSET=N_CLAMP, TOTALS=ONLY, FREQUENCYF=1\nRF\n");
  fprintf(f, "*END STEP\n");
  *load_sum = sum;
  free(list);
  if (ferror(f) && !rc) rc = SA_ERROR(SA_ERR_IO, "write error on %s", path);
  if (fclose(f) && !rc) rc = SA_ERROR(SA_ERR_IO, "cannot close %s", path);
  return rc;
}

static int run(int argc, char **argv)
{
  int n = 0;
  const char *out = NULL;
  double kratio = 0;
  CookDeck d = {.etype = "C3D20R", .mu = 80.194, .kappa = 400889.8, .force = 32.0,
                .inc0 = 0.1, .incmin = 1e-5, .incmax = 0.25};
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define OPT(name) (!strcmp(a, name) && v && ++i)
    if (OPT("--n")) n = atoi(v);
    else if (OPT("--out")) out = v;
    else if (OPT("--etype")) d.etype = v;
    else if (OPT("--mu")) d.mu = atof(v);
    else if (OPT("--kappa")) d.kappa = atof(v);
    else if (OPT("--kappa-ratio")) kratio = atof(v);
    else if (OPT("--force")) d.force = atof(v);
    else if (OPT("--inc0")) d.inc0 = atof(v);
    else if (OPT("--incmin")) d.incmin = atof(v);
    else if (OPT("--incmax")) d.incmax = atof(v);
    else if (OPT("--tol")) d.tol = atof(v);
    else return SA_ERROR(SA_ERR_INPUT, "unknown or incomplete option %s", a);
#undef OPT
  }
  SA_REQUIRE(n >= 1 && n <= 512 && out, SA_ERR_INPUT, "usage: ccx_cook --n N --out BASE [...]");
  SA_REQUIRE(!strcmp(d.etype, "C3D20R") || !strcmp(d.etype, "C3D20"), SA_ERR_INPUT,
             "--etype must be C3D20R or C3D20");
  if (kratio > 0) d.kappa = kratio * d.mu;
  SA_REQUIRE(d.mu > 0 && d.kappa > 0, SA_ERR_INPUT, "mu and kappa must be positive");
  Cook c;
  memset(&c, 0, sizeof c);
  int rc = cook_build(&c, n, d.force);
  char path[1024];
  snprintf(path, sizeof path, "%s.inp", out);
  double sum = 0;
  if (!rc) rc = cook_write(&c, &d, path, &sum);
  /* the nodal forces must add up to F up to round-off (a few ulps per node) */
  if (!rc && fabs(sum - d.force) > 1e-12 * d.force * c.nnodes)
    rc = SA_ERROR(SA_ERR_INTERNAL, "nodal forces sum to %.17g N, expected %.17g", sum, d.force);
  if (!rc) {
    int nclamp = 0;
    for (int v = 0; v < c.nnodes; ++v) nclamp += fabs(c.xyz[3 * v]) < 1e-9;
    printf("ccx_cook: %s nodes %d dof %d elems %d etype %s kappa %.12g load_sum %.17g\n", path,
           c.nnodes, 2 * (c.nnodes - nclamp), c.nelem, d.etype, d.kappa, sum);
  }
  cook_free(&c);
  return rc;
}

int main(int argc, char **argv)
{
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
