/* dem_test_util.h - shared pieces of the DEM bridge tests: parameters, meshes, comparisons.
 * Header-only (static functions): each test is its own executable. */
#ifndef DEM_TEST_UTIL_H
#define DEM_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dem.h"
#include "dem_parallel.h"
#include "sa_error.h"

/* Exit with the error trace if a bridge call fails. */
#define T_CHECK(call)                                                           \
  do {                                                                          \
    if ((call) != 0) {                                                          \
      printf("%s:%d: %s failed\n", __FILE__, __LINE__, #call);                  \
      sa_error_print();                                                         \
      exit(1);                                                                  \
    }                                                                           \
  } while (0)

static int t_failures;

/* Under `mpirun -np N` (the tests named *_mpi): MPI started, and a follower rank makes rank 0's
 * bridge calls (dem_bridge_follow) and exits here; rank 0 runs the test. One rank: nothing. */
static inline void t_mpi_begin(void) {
  if (dem_par_size() <= 1) return;
  if (dem_par_start()) {
    sa_error_print();
    exit(1);
  }
  if (!dem_par_following()) return;
  int rc = dem_bridge_follow();
  dem_par_finish();
  exit(rc ? 1 : 0);
}

/* Rank 0, after its last bridge is destroyed: release the followers, stop MPI. */
static inline void t_mpi_end(void) {
  dem_par_release();
  dem_par_finish();
}

/* |a - b| <= atol + rtol |b|, else report. */
static inline void t_close(const char *what, double a, double b, double atol, double rtol) {
  if (fabs(a - b) <= atol + rtol * fabs(b)) return;
  printf("%s: got %.6g, expected %.6g (|diff| %.3g > %.3g + %.3g * |expected|)\n", what, a, b,
         fabs(a - b), atol, rtol);
  t_failures++;
}

static inline void t_true(const char *what, int ok) {
  if (ok) return;
  printf("%s\n", what);
  t_failures++;
}

static inline int t_verbose(void) {
  const char *s = getenv("DEM_TEST_VERBOSE");
  return s && *s && strcmp(s, "0");
}

/* LIGGGHTS log of the test (DEM_TEST_LOG=path in the environment), else none. */
static inline const char *t_log(void) { return getenv("DEM_TEST_LOG"); }

static inline double t_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Moderate defaults: 2 mm grains, softened silicone-like modulus. */
static inline void t_params(DemParams *p) {
  memset(p, 0, sizeof *p);
  p->diameter = 2e-3;
  p->density = 2500;
  p->young = 5e6;
  p->poisson = 0.3;
  p->restitution = 0.5;
  p->friction = 0.5;
  p->friction_wall = 0.5;
  p->friction_piston = 0.5;
  p->rolling_friction = 0;
  p->wall_young = 5e6;
  p->wall_poisson = 0.3;
  p->dt_safety = 0.2;
  p->dt = 0.1 * dem_rayleigh_dt(p->diameter, p->density, p->young, p->poisson);
  p->gravity[2] = -9.81;
  for (int k = 0; k < 3; k++) p->box_lo[k] = -0.05, p->box_hi[k] = 0.05;
  p->skin = 0.2 * p->diameter;
  p->seed = 32452843;
}

/* Square in the plane z = z0, side 2 h centred at (cx, cy): 4 vertices, 2 triangles. */
static inline void t_square(double cx, double cy, double z0, double h, double xyz[12], int tri[6]) {
  double v[12] = {cx - h, cy - h, z0, cx + h, cy - h, z0, cx + h, cy + h, z0, cx - h, cy + h, z0};
  int t[6] = {0, 1, 2, 0, 2, 3};
  memcpy(xyz, v, sizeof v);
  memcpy(tri, t, sizeof t);
}

/* A bridge set up with p, a steel plate of side 20 mm at z = 0 (mesh *id) and one sphere of
 * p's diameter inserted with its bottom `gap` above the plate at (cx, cy). */
static inline void t_sphere_on_plate(const DemParams *p, double cx, double cy, double gap,
                                     DemBridge **b, int *id) {
  double xyz[12];
  int tri[6], ins = 0;
  T_CHECK(dem_bridge_create(t_log(), b));
  T_CHECK(dem_bridge_setup(*b, p));
  t_square(0, 0, 0, 0.01, xyz, tri);
  T_CHECK(dem_bridge_add_mesh(*b, "plate", 4, xyz, 2, tri, DEM_WALL_STEEL, id));
  T_CHECK(dem_bridge_insert_cylinder(*b, cx, cy, 0.5 * p->diameter, gap, gap + p->diameter, 1,
                                     &ins));
  t_true("one sphere inserted", ins == 1);
}

/* Open vertical cylinder (axis (cx, cy), radius r, z0..z1), nseg around, nz rings of cells:
 * (nz+1) nseg vertices, 2 nseg nz triangles; caller frees *xyz, *tri. */
static inline void t_tube(double cx, double cy, double r, double z0, double z1, int nseg, int nz,
                   double **xyz, int **tri, int *nv, int *nt) {
  *nv = (nz + 1) * nseg;
  *nt = 2 * nseg * nz;
  *xyz = malloc(3 * (size_t)*nv * sizeof **xyz);
  *tri = malloc(3 * (size_t)*nt * sizeof **tri);
  for (int j = 0; j <= nz; j++)
    for (int i = 0; i < nseg; i++) {
      double a = 2 * M_PI * i / nseg;
      double *p = *xyz + 3 * (j * nseg + i);
      p[0] = cx + r * cos(a), p[1] = cy + r * sin(a), p[2] = z0 + (z1 - z0) * j / nz;
    }
  int t = 0;
  for (int j = 0; j < nz; j++)
    for (int i = 0; i < nseg; i++) {
      int a = j * nseg + i, b = j * nseg + (i + 1) % nseg, c = a + nseg, d = b + nseg;
      int *q = *tri + 3 * t;
      q[0] = a, q[1] = b, q[2] = d, q[3] = a, q[4] = d, q[5] = c;
      t += 2;
    }
}

/* Disk in the plane z = z0 (centre (cx, cy), radius r): a centre vertex, nring rings of nseg
 * vertices, triangulated fan + quads; caller frees. */
static inline void t_disk(double cx, double cy, double r, double z0, int nseg, int nring, double **xyz,
                   int **tri, int *nv, int *nt) {
  *nv = 1 + nring * nseg;
  *nt = nseg + 2 * nseg * (nring - 1);
  *xyz = malloc(3 * (size_t)*nv * sizeof **xyz);
  *tri = malloc(3 * (size_t)*nt * sizeof **tri);
  double *p = *xyz;
  p[0] = cx, p[1] = cy, p[2] = z0;
  for (int j = 1; j <= nring; j++)
    for (int i = 0; i < nseg; i++) {
      double a = 2 * M_PI * i / nseg, rr = r * j / nring;
      p = *xyz + 3 * (1 + (j - 1) * nseg + i);
      p[0] = cx + rr * cos(a), p[1] = cy + rr * sin(a), p[2] = z0;
    }
  int t = 0;
  for (int i = 0; i < nseg; i++) {
    int *q = *tri + 3 * t++;
    q[0] = 0, q[1] = 1 + i, q[2] = 1 + (i + 1) % nseg;
  }
  for (int j = 1; j < nring; j++)
    for (int i = 0; i < nseg; i++) {
      int a = 1 + (j - 1) * nseg + i, b = 1 + (j - 1) * nseg + (i + 1) % nseg, c = a + nseg,
          d = b + nseg;
      int *q = *tri + 3 * t;
      q[0] = a, q[1] = c, q[2] = d, q[3] = a, q[4] = d, q[5] = b;
      t += 2;
    }
}

#endif
