/* dem_bridge.c - the LIGGGHTS bridge: a LIGGGHTS instance driven through its C library
 * interface (library.h), serial or this rank's part of a domain-decomposed one (the section
 * "several MPI ranks" at the end, dem_parallel.h), wall meshes moved node by node through
 * dem_shim.cpp.
 *
 * Contact model (LIGGGHTS `model hertz tangential history [rolling_friction epsd2]`): Hertz
 * normal force F = 4/3 E* sqrt(R*) delta^1.5 with viscous damping set from the restitution,
 * Mindlin tangential spring capped by Coulomb friction, elastic-plastic rolling resistance
 * (Ai et al., Powder Technol. 206 (2011) 269) when rolling_friction > 0.
 * Time step bound (Rayleigh wave, Li et al. 2005 / Ning & Ghadiri):
 *   dt_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766),  G = E / (2 (1 + nu)).
 * Hertz contact time (Johnson, Contact Mechanics, 1985, sec. 11.4):
 *   t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5).
 *
 * LIGGGHTS aborts the process on a bad command, so every value is checked before a command is
 * sent. Wall meshes reach LIGGGHTS as temporary ASCII STL files (written and deleted during
 * set-up); LIGGGHTS keeps each triangle's position in that file as its id, which is the
 * caller's triangle index (degenerate triangles, which LIGGGHTS would drop, are refused). */
#include "dem.h"

#include <library.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <unistd.h>

#include "dem_parallel.h"
#include "dem_shim.h"
#include "sa_error.h"
#include "sa_log.h"

#define DEM_CMD_MAX 4096
#define DEM_NAME_MAX 31

typedef struct {
  char fix_id[DEM_NAME_MAX + 8];
  DemWallType type;
  int nverts, ntri;
  double *xyz; /* current vertex positions (caller order) [owned] */
  int *tri;    /* caller triangles [owned] */
  int *idx;    /* 3*ntri: caller vertex of corner c of LIGGGHTS element id [owned] */
  double *v;   /* node velocities last set (caller order), for checkpoints [owned] */
  double *acc; /* running sum of this rank's triangle forces (dem_bridge_mesh_forces_add),
                * 3*ntri [owned, allocated on first use] */
  double *path; /* dem_bridge_set_mesh_path's ends: start, then end, 2*3*nverts [owned,
                 * allocated on first use]; path_set: they are valid */
  int path_set;
  /* the node positions LIGGGHTS' rebuild test compares with: those of its last neighbour build
   * (caller order) [owned, first use], valid after built_epoch (see note_builds); used: 1 for
   * a vertex of some triangle [owned, first use] */
  double *built;
  long long built_epoch[3];
  int built_valid;
  unsigned char *used;
  void *shim;  /* the fix mesh/surface [borrowed from LIGGGHTS] */
} DemMesh;

/* What a checkpoint holds beside LIGGGHTS' restart: the meshes (checked when they are added
 * again, velocities restored) and, per grain, the state at the checkpoint with the force and
 * torque of its last step (put back after the set-up pass that follows, see ck_setup_pass). */
typedef struct {
  char name[DEM_NAME_MAX + 1];
  int type, nverts, ntri;
  int *tri;          /* [owned] */
  double *xyz, *v;   /* [owned] */
} CkMesh;

typedef struct {
  int64_t tag, type;
  double x[3], v[3], omega[3], f[3], torque[3], radius, rmass;
} CkGrain;

typedef struct {
  char path[1024];   /* the file read or written (for messages) */
  int64_t step, count;
  uint64_t rng;
  DemParams p;
  int nmesh;
  CkMesh *mesh;      /* [owned] */
  CkGrain *grain;    /* [owned] count records */
  const unsigned char *restart; /* LIGGGHTS restart bytes [borrowed from the file buffer] */
  uint64_t restart_bytes;
} Checkpoint;

struct DemBridge {
  void *lmp;
  char tmpdir[256];
  DemParams p;
  int is_setup, walls_done, need_setup, rolling, ran;
  DemMesh *mesh;
  int nmesh, mesh_cap;
  uint64_t rng;
  /* scratch of dem_bridge_max_overlap and dem_bridge_insert_cylinder, grown on demand */
  int *cell_head, *cell_next;
  size_t cell_cap, next_cap;
  double *pos;
  size_t pos_cap;
  /* the last checkpoint written or read; resumed: the meshes still to come are its */
  Checkpoint *ck; /* [owned] */
  int resumed;
  /* where dem_bridge_max_overlap found its largest overlap: the mesh (-1: two grains) and
   * the grain's centre (the first grain of a pair) */
  int ov_mesh;
  double ov_pos[3];
  double indent; /* largest indentation into a compliant silicone wall (fraction of d) */
  double indent_pos[3]; /* that grain's centre */
  /* MPI (dem_parallel.h): ranks LIGGGHTS runs on (1: serial, the library's own MPI_Init), this
   * rank, the processor grid asked for (0: LIGGGHTS' choice), and a follower's scratch for the
   * outputs that only the lead receives */
  int np, rank, procs[3];
  double *scratch;
  size_t scratch_cap;
  /* set-ups started (runs without "pre no"): with LIGGGHTS' build count, which a set-up
   * resets, and the step of its last build, they tell whether a build happened */
  long long setups;
};

static void ck_free(Checkpoint **ck);
static int ck_mesh_check(const DemBridge *b, const char *name, int nverts, const double *xyz,
                         int ntri, const int *tri, DemWallType type);
static int ck_setup_pass(DemBridge *b, int run0);
static int finalize_walls_here(DemBridge *b);
static int gather_grains(DemBridge *b, CkGrain **all, int *n);

/* ---------------------------------------------------------------- closed forms */

double dem_rayleigh_dt(double diameter, double density, double young, double poisson) {
  double G = young / (2.0 * (1.0 + poisson));
  return M_PI * 0.5 * diameter * sqrt(density / G) / (0.1631 * poisson + 0.8766);
}

static double hertz_time(double mstar, double rstar, double estar, double v) {
  return 2.87 * pow(mstar * mstar / (rstar * estar * estar * v), 0.2);
}

double dem_hertz_contact_time(double diameter, double density, double young, double poisson,
                              double v) {
  double R = 0.5 * diameter, m = density * 4.0 / 3.0 * M_PI * R * R * R;
  return hertz_time(0.5 * m, 0.5 * R, young / (2.0 * (1.0 - poisson * poisson)), v);
}

double dem_hertz_wall_contact_time(double diameter, double density, double young, double poisson,
                                   double wall_young, double wall_poisson, double v) {
  double R = 0.5 * diameter, m = density * 4.0 / 3.0 * M_PI * R * R * R;
  double estar =
      1.0 / ((1.0 - poisson * poisson) / young + (1.0 - wall_poisson * wall_poisson) / wall_young);
  return hertz_time(m, R, estar, v);
}

/* ---------------------------------------------------------------- helpers */

static int send(DemBridge *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int send(DemBridge *b, const char *fmt, ...) {
  char buf[DEM_CMD_MAX];
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  SA_REQUIRE(n >= 0 && n < (int)sizeof buf, SA_ERR_INTERNAL, "LIGGGHTS command too long: %.60s...",
             buf);
  if (!strncmp(buf, "run ", 4) && !strstr(buf, "pre no")) b->setups++;
  lammps_command(b->lmp, buf);
  return 0;
}

/* A path LIGGGHTS' input parser takes verbatim (no whitespace, comments, variables, quotes,
 * continuation, or the * and % that write_restart expands). */
static int path_is_plain(const char *s) {
  if (!s || !*s) return 0;
  for (; *s; s++)
    if ((unsigned char)*s <= ' ' || strchr("#$*%&'\"", *s)) return 0;
  return 1;
}

static int finite3(const double *x) {
  return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]);
}

static int inside_box(const DemParams *p, const double *x) {
  for (int k = 0; k < 3; k++)
    if (!(x[k] >= p->box_lo[k] && x[k] <= p->box_hi[k])) return 0;
  return 1;
}

/* splitmix64: a small, well-mixed generator seeded from DemParams.seed. */
static double rng_uniform(DemBridge *b) {
  uint64_t z = (b->rng += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static int grow_int(int **a, size_t *cap, size_t n) {
  if (n <= *cap) return 0;
  size_t c = n + n / 2 + 16;
  int *t = realloc(*a, c * sizeof *t);
  SA_REQUIRE(t, SA_ERR_MEMORY, "cannot allocate %zu ints", c);
  *a = t;
  *cap = c;
  return 0;
}

static int grow_double(double **a, size_t *cap, size_t n) {
  if (n <= *cap) return 0;
  size_t c = n + n / 2 + 16;
  double *t = realloc(*a, c * sizeof *t);
  SA_REQUIRE(t, SA_ERR_MEMORY, "cannot allocate %zu doubles", c);
  *a = t;
  *cap = c;
  return 0;
}

/* Squared distance from point p to triangle (a, b, c) (Ericson, Real-Time Collision Detection,
 * sec. 5.1.5: closest point by Voronoi region). */
static double point_tri_dist2(const double *p, const double *a, const double *b, const double *c) {
  double ab[3], ac[3], ap[3], q[3];
  for (int k = 0; k < 3; k++) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
  double d1 = DOT(ab, ap), d2 = DOT(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    for (int k = 0; k < 3; k++) q[k] = a[k];
    goto done;
  }
  double bp[3];
  for (int k = 0; k < 3; k++) bp[k] = p[k] - b[k];
  double d3 = DOT(ab, bp), d4 = DOT(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    for (int k = 0; k < 3; k++) q[k] = b[k];
    goto done;
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double t = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ab[k];
    goto done;
  }
  double cp[3];
  for (int k = 0; k < 3; k++) cp[k] = p[k] - c[k];
  double d5 = DOT(ab, cp), d6 = DOT(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    for (int k = 0; k < 3; k++) q[k] = c[k];
    goto done;
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double t = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ac[k];
    goto done;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) q[k] = b[k] + t * (c[k] - b[k]);
    goto done;
  }
  {
    double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
    for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
  }
done:;
  double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
  return DOT(d, d);
#undef DOT
}

/* ---------------------------------------------------------------- cell list */

typedef struct {
  double lo[3], h;
  int n[3];
} Grid;

/* Bins npts points pts (3 each) into cells of size >= hmin over their bounding box (at most
 * about 8 npts + 64 cells); b->cell_head / b->cell_next hold the lists (-1 ends). */
static int grid_build(DemBridge *b, const double *pts, int npts, double hmin, Grid *g) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < npts; i++)
    for (int k = 0; k < 3; k++) {
      if (pts[3 * i + k] < lo[k]) lo[k] = pts[3 * i + k];
      if (pts[3 * i + k] > hi[k]) hi[k] = pts[3 * i + k];
    }
  if (npts == 0)
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0;
  double h = hmin > 0 ? hmin : 1.0;
  double maxcells = 8.0 * npts + 64.0;
  for (;;) {
    double nc = 1;
    for (int k = 0; k < 3; k++) nc *= floor((hi[k] - lo[k]) / h) + 1;
    if (nc <= maxcells) break;
    h *= 1.26;
  }
  size_t ncell = 1;
  for (int k = 0; k < 3; k++) {
    g->lo[k] = lo[k];
    g->n[k] = (int)floor((hi[k] - lo[k]) / h) + 1;
    ncell *= (size_t)g->n[k];
  }
  g->h = h;
  SA_CHECK(grow_int(&b->cell_head, &b->cell_cap, ncell));
  SA_CHECK(grow_int(&b->cell_next, &b->next_cap, (size_t)npts + 1));
  for (size_t c = 0; c < ncell; c++) b->cell_head[c] = -1;
  for (int i = 0; i < npts; i++) {
    int ci[3];
    for (int k = 0; k < 3; k++) {
      ci[k] = (int)((pts[3 * i + k] - g->lo[k]) / h);
      if (ci[k] >= g->n[k]) ci[k] = g->n[k] - 1;
    }
    size_t c = ((size_t)ci[2] * g->n[1] + ci[1]) * g->n[0] + ci[0];
    b->cell_next[i] = b->cell_head[c];
    b->cell_head[c] = i;
  }
  return 0;
}

/* Cell index range [c0, c1] covering [xlo, xhi] along axis k. */
static void grid_range(const Grid *g, int k, double xlo, double xhi, int *c0, int *c1) {
  double a = floor((xlo - g->lo[k]) / g->h), z = floor((xhi - g->lo[k]) / g->h);
  *c0 = a < 0 ? 0 : a >= g->n[k] ? g->n[k] : (int)a;
  *c1 = z < 0 ? -1 : z >= g->n[k] ? g->n[k] - 1 : (int)z;
}

/* ---------------------------------------------------------------- lifecycle */

static int create_here(const char *log_path, DemBridge **out) {
  SA_REQUIRE(out, SA_ERR_INTERNAL, "dem_bridge_create: no output handle");
  *out = NULL;
  if (log_path) {
    /* LIGGGHTS aborts when it cannot open its log: try first. */
    FILE *f = fopen(log_path, "w");
    SA_REQUIRE(f, SA_ERR_IO, "cannot open the LIGGGHTS log file '%s'", log_path);
    fclose(f);
  }
  DemBridge *b;
  SA_CALLOC(b, 1);
  const char *tmp = getenv("TMPDIR");
  if (!tmp || !path_is_plain(tmp) || strlen(tmp) > 200) tmp = "/tmp";
  snprintf(b->tmpdir, sizeof b->tmpdir, "%s/softact-dem-XXXXXX", tmp);
  if (!mkdtemp(b->tmpdir)) {
    free(b);
    return SA_ERROR(SA_ERR_IO, "cannot create a temporary directory under %s", tmp);
  }
  /* -screen /dev/null, not none: parts of LIGGGHTS (the STL mesh reader) fprintf to the screen
   * without checking it is open, which crashes with "none" */
  char *argv[] = {"softact", "-log", log_path ? (char *)log_path : "none", "-screen", "/dev/null",
                  NULL};
  /* A second instance in one process re-registers LIGGGHTS' contact-model tables and says so
   * on std::cerr: stderr goes to /dev/null while the instance starts. */
  fflush(stderr);
  int saved = dup(2), devnull = open("/dev/null", O_WRONLY);
  if (saved >= 0 && devnull >= 0) dup2(devnull, 2);
  b->np = dem_par_leading() || dem_par_following() ? dem_par_size() : 1;
  b->rank = b->np > 1 ? dem_par_rank() : 0;
  if (b->np > 1)
    lammps_open(5, argv, MPI_COMM_WORLD, &b->lmp);
  else
    lammps_open_no_mpi(5, argv, &b->lmp);
  if (saved >= 0 && devnull >= 0) dup2(saved, 2);
  if (saved >= 0) close(saved);
  if (devnull >= 0) close(devnull);
  if (!b->lmp) {
    rmdir(b->tmpdir);
    free(b);
    return SA_ERROR(SA_ERR_LIBRARY, "LIGGGHTS failed to start");
  }
  *out = b;
  return 0;
}

static void destroy_here(DemBridge **pb) {
  if (!pb || !*pb) return;
  DemBridge *b = *pb;
  if (b->lmp) lammps_close(b->lmp);
  for (int i = 0; i < b->nmesh; i++) {
    free(b->mesh[i].xyz);
    free(b->mesh[i].tri);
    free(b->mesh[i].idx);
    free(b->mesh[i].v);
    free(b->mesh[i].acc);
    free(b->mesh[i].path);
    free(b->mesh[i].built);
    free(b->mesh[i].used);
  }
  free(b->mesh);
  ck_free(&b->ck);
  free(b->cell_head);
  free(b->cell_next);
  free(b->pos);
  free(b->scratch);
  rmdir(b->tmpdir);
  free(b);
  *pb = NULL;
}

static int log_append_here(DemBridge *b, const char *path) {
  SA_REQUIRE(b && b->lmp && path, SA_ERR_INTERNAL, "dem_bridge_log_append: no bridge");
  SA_REQUIRE(path_is_plain(path) && strlen(path) < 900, SA_ERR_INPUT,
             "LIGGGHTS cannot take the log path '%s' (whitespace or a special character)", path);
  FILE *f = fopen(path, "a"); /* LIGGGHTS aborts when it cannot open its log: try first */
  SA_REQUIRE(f, SA_ERR_IO, "cannot open the LIGGGHTS log file '%s'", path);
  fclose(f);
  return send(b, "log %s append", path);
}

static int command_here(DemBridge *b, const char *cmd) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(cmd, SA_ERR_INTERNAL, "no command");
  if (!strncmp(cmd, "run ", 4) && !strstr(cmd, "pre no")) b->setups++;
  lammps_command(b->lmp, (char *)cmd);
  b->need_setup = 1;
  return 0;
}

/* ---------------------------------------------------------------- set-up */

/* Reports value v of field `name` outside [lo, hi] (open at an end when lo_open / hi_open). */
static int check_range(const char *name, double v, double lo, int lo_open, double hi, int hi_open,
                       const char *what) {
  int ok = isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (ok) return 0;
  char lo_s[64] = "", hi_s[64] = "";
  if (isfinite(lo)) snprintf(lo_s, sizeof lo_s, "%s %g", lo_open ? ">" : ">=", lo);
  if (isfinite(hi)) snprintf(hi_s, sizeof hi_s, "%s%s %g", *lo_s ? " and " : "", hi_open ? "<" : "<=", hi);
  return SA_ERROR(SA_ERR_INPUT, "DEM parameter %s = %g is out of range: must be %s%s (%s)", name, v,
                  lo_s, hi_s, what);
}

static int params_check(const DemParams *p) {
  SA_REQUIRE(p, SA_ERR_INPUT, "no DEM parameters");
  SA_CHECK(check_range("diameter", p->diameter, 0, 1, 1.0, 0, "grain diameter [m]"));
  SA_CHECK(check_range("density", p->density, 0, 1, 1e5, 0, "grain density [kg/m^3]"));
  SA_CHECK(check_range("young", p->young, 0, 1, 1e13, 0, "grain Young's modulus [Pa]"));
  SA_CHECK(check_range("poisson", p->poisson, 0, 0, 0.5, 0, "grain Poisson ratio, LIGGGHTS' range"));
  SA_CHECK(check_range("restitution", p->restitution, 0.05, 1, 1.0, 0,
                       "coefficient of restitution, LIGGGHTS' range"));
  SA_CHECK(check_range("friction", p->friction, 0, 0, 10, 0, "grain-grain Coulomb coefficient"));
  SA_CHECK(check_range("friction_wall", p->friction_wall, 0, 0, 10, 0,
                       "grain-silicone Coulomb coefficient"));
  SA_CHECK(check_range("friction_piston", p->friction_piston, 0, 0, 10, 0,
                       "grain-steel Coulomb coefficient"));
  SA_CHECK(check_range("rolling_friction", p->rolling_friction, 0, 0, 10, 0,
                       "rolling-resistance coefficient"));
  SA_CHECK(check_range("wall_young", p->wall_young, 0, 1, 1e13, 0, "wall Young's modulus [Pa]"));
  SA_CHECK(check_range("wall_poisson", p->wall_poisson, 0, 0, 0.5, 0,
                       "wall Poisson ratio, LIGGGHTS' range"));
  SA_CHECK(check_range("silicone_young", p->silicone_young, 0, 0, 1e13, 0,
                       "silicone wall's Young's modulus [Pa] (0: wall_young)"));
  SA_CHECK(check_range("silicone_poisson", p->silicone_poisson, 0, 0, 0.5, 1,
                       "silicone wall's Poisson ratio, LIGGGHTS' range"));
  SA_CHECK(check_range("dt_safety", p->dt_safety, 0, 1, 1, 0, "fraction of the Rayleigh step"));
  SA_CHECK(check_range("dt", p->dt, 0, 1, INFINITY, 0, "DEM time step [s]"));
  double dtr = dem_rayleigh_dt(p->diameter, p->density, p->young, p->poisson);
  if (p->dt > p->dt_safety * dtr)
    return SA_ERROR(SA_ERR_INPUT,
                    "DEM parameter dt = %g s is unsafe: must be <= dt_safety * Rayleigh time step "
                    "= %g * %g s = %g s",
                    p->dt, p->dt_safety, dtr, p->dt_safety * dtr);
  static const char *gname[3] = {"gravity[0]", "gravity[1]", "gravity[2]"};
  static const char *loname[3] = {"box_lo[0]", "box_lo[1]", "box_lo[2]"};
  static const char *hiname[3] = {"box_hi[0]", "box_hi[1]", "box_hi[2]"};
  for (int k = 0; k < 3; k++) {
    SA_CHECK(check_range(gname[k], p->gravity[k], -1e4, 0, 1e4, 0, "gravity [m/s^2]"));
    SA_CHECK(check_range(loname[k], p->box_lo[k], -1e3, 0, 1e3, 0, "box corner [m]"));
    SA_CHECK(check_range(hiname[k], p->box_hi[k], p->box_lo[k] + p->diameter, 0, 1e3, 0,
                         "box corner [m], at least one diameter above box_lo"));
  }
  SA_CHECK(check_range("skin", p->skin, 0, 1, 10 * p->diameter, 0,
                       "neighbour skin [m], at most 10 diameters"));
  SA_REQUIRE(p->seed > 0, SA_ERR_INPUT, "DEM parameter seed = %d is out of range: must be > 0",
             p->seed);
  return 0;
}

/* Commands valid before the box exists (a fresh set-up and a resume both send them). */
static int setup_pre_box(DemBridge *b) {
  static const char *pre[] = {
      "atom_modify map array", "newton off", /* read_restart keeps the script's newton */
      /* the softened grains and the steel walls are outside LIGGGHTS' sanity range */
      "soft_particles yes", "hard_particles yes"};
  for (size_t i = 0; i < sizeof pre / sizeof *pre; i++) SA_CHECK(send(b, "%s", pre[i]));
  if (b->np > 1 && b->procs[0] > 0)
    SA_CHECK(send(b, "processors %d %d %d", b->procs[0], b->procs[1], b->procs[2]));
  return 0;
}

/* The friction fixes (m4 sliding, m5 rolling) for p's coefficients times scale; a fix
 * redefined under its ID replaces the old one. */
static int send_friction(DemBridge *b, const DemParams *p, double scale) {
  /* wall-wall entries never act; they repeat the grain-wall values */
  double mu = scale * p->friction, mw = scale * p->friction_wall, mp = scale * p->friction_piston;
  SA_CHECK(send(b,
                "fix m4 all property/global coefficientFriction peratomtypepair 3 "
                "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g",
                mu, mw, mp, mw, mw, mp, mp, mp, mp));
  double r = scale * p->rolling_friction;
  SA_CHECK(send(b,
                "fix m5 all property/global coefficientRollingFriction peratomtypepair 3 "
                "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g",
                r, r, r, r, r, r, r, r, r));
  return 0;
}

/* The silicone wall's (atom type 2) Young's modulus: its own when set, else the walls'. */
static double silicone_young(const DemParams *p) {
  return p->silicone_young > 0 ? p->silicone_young : p->wall_young;
}

/* Commands once the box exists: materials, contact model, integrator, gravity, time step. */
static int setup_post_box(DemBridge *b, const DemParams *p) {
  SA_CHECK(send(b, "communicate single vel yes"));
  /* spatial sorting with an explicit bin (LIGGGHTS derives it from the largest grain, and
   * aborts when there is none yet, e.g. at the set-up pass of dem_bridge_finalize_walls) */
  SA_CHECK(send(b, "atom_modify sort 1000 %.17g", p->diameter));
  SA_CHECK(send(b, "neighbor %.17g bin", p->skin));
  SA_CHECK(send(b, "neigh_modify delay 0"));
  SA_CHECK(send(b, "fix m1 all property/global youngsModulus peratomtype %.17g %.17g %.17g", p->young,
                silicone_young(p), p->wall_young));
  SA_CHECK(send(b, "fix m2 all property/global poissonsRatio peratomtype %.17g %.17g %.17g",
                p->poisson, p->silicone_young > 0 ? p->silicone_poisson : p->wall_poisson,
                p->wall_poisson));
  double e = p->restitution;
  SA_CHECK(send(b,
                "fix m3 all property/global coefficientRestitution peratomtypepair 3 "
                "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g",
                e, e, e, e, e, e, e, e, e));
  SA_CHECK(send_friction(b, p, 1));
  /* rolling resistance off when its coefficient is 0 (same result, less work) */
  SA_CHECK(send(b, "pair_style gran model hertz tangential history%s",
                b->rolling ? " rolling_friction epsd2" : ""));
  SA_CHECK(send(b, "pair_coeff * *"));
  SA_CHECK(send(b, "fix integr all nve/sphere"));
  double g = sqrt(p->gravity[0] * p->gravity[0] + p->gravity[1] * p->gravity[1] +
                  p->gravity[2] * p->gravity[2]);
  if (g > 0)
    SA_CHECK(send(b, "fix grav all gravity %.17g vector %.17g %.17g %.17g", g, p->gravity[0] / g,
                  p->gravity[1] / g, p->gravity[2] / g));
  SA_CHECK(send(b, "timestep %.17g", p->dt));
  SA_CHECK(send(b, "thermo_modify lost ignore norm no"));
  return 0;
}

static int setup_here(DemBridge *b, const DemParams *params) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(!b->is_setup, SA_ERR_INPUT, "dem_bridge_setup called twice");
  SA_CHECK(params_check(params));
  const DemParams *p = params;
  b->p = *p;
  b->rng = (uint64_t)p->seed * 0x2545F4914F6CDD1Dull;
  b->rolling = p->rolling_friction > 0;
  static const char *pre[] = {"units si", "atom_style granular", "boundary f f f"};
  for (size_t i = 0; i < sizeof pre / sizeof *pre; i++) SA_CHECK(send(b, "%s", pre[i]));
  SA_CHECK(setup_pre_box(b));
  SA_CHECK(send(b, "region simbox block %.17g %.17g %.17g %.17g %.17g %.17g units box", p->box_lo[0],
                p->box_hi[0], p->box_lo[1], p->box_hi[1], p->box_lo[2], p->box_hi[2]));
  SA_CHECK(send(b, "create_box 3 simbox"));
  SA_CHECK(setup_post_box(b, p));
  b->is_setup = 1;
  b->need_setup = 1;
  return 0;
}

/* ---------------------------------------------------------------- wall meshes */

static int name_ok(const char *s) {
  size_t n = s ? strlen(s) : 0;
  if (n == 0 || n > DEM_NAME_MAX) return 0;
  for (; *s; s++)
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
          *s == '_'))
      return 0;
  return 1;
}

/* Smallest angle of triangle (a, b, c) [rad]. */
static double min_angle(const double *a, const double *b, const double *c) {
  const double *v[3] = {a, b, c};
  double amin = M_PI;
  for (int i = 0; i < 3; i++) {
    const double *o = v[i], *p = v[(i + 1) % 3], *q = v[(i + 2) % 3];
    double u[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
    double w[3] = {q[0] - o[0], q[1] - o[1], q[2] - o[2]};
    double uw = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    double s = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    double ang = atan2(s, uw);
    if (ang < amin) amin = ang;
  }
  return amin;
}

static int cmp_int3(const void *x, const void *y) {
  const int *a = x, *b = y;
  for (int k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static int sort3(int *t) {
  int s;
  if (t[0] > t[1]) s = t[0], t[0] = t[1], t[1] = s;
  if (t[1] > t[2]) s = t[1], t[1] = t[2], t[2] = s;
  if (t[0] > t[1]) s = t[0], t[0] = t[1], t[1] = s;
  return 0;
}

static int mesh_check(const DemBridge *b, const char *name, int nverts, const double *xyz, int ntri,
                      const int *tri) {
  SA_REQUIRE(name_ok(name), SA_ERR_INPUT,
             "mesh name '%s' is not valid: 1 to %d letters, digits or '_'", name ? name : "(null)",
             DEM_NAME_MAX);
  for (int i = 0; i < b->nmesh; i++)
    SA_REQUIRE(strcmp(b->mesh[i].fix_id + 5, name), SA_ERR_INPUT, "mesh name '%s' used twice",
               name);
  SA_REQUIRE(nverts >= 3 && ntri >= 1 && xyz && tri, SA_ERR_INPUT,
             "mesh '%s': needs at least 3 vertices and 1 triangle (got %d, %d)", name, nverts, ntri);
  for (int v = 0; v < nverts; v++) {
    SA_REQUIRE(finite3(xyz + 3 * v), SA_ERR_INPUT, "mesh '%s': vertex %d is not finite", name, v);
    SA_REQUIRE(inside_box(&b->p, xyz + 3 * v), SA_ERR_INPUT,
               "mesh '%s': vertex %d (%g, %g, %g) is outside the DEM box", name, v, xyz[3 * v],
               xyz[3 * v + 1], xyz[3 * v + 2]);
  }
  for (int t = 0; t < ntri; t++) {
    const int *k = tri + 3 * t;
    for (int c = 0; c < 3; c++)
      SA_REQUIRE(k[c] >= 0 && k[c] < nverts, SA_ERR_INPUT,
                 "mesh '%s': triangle %d names vertex %d (there are %d)", name, t, k[c], nverts);
    SA_REQUIRE(k[0] != k[1] && k[1] != k[2] && k[0] != k[2], SA_ERR_INPUT,
               "mesh '%s': triangle %d repeats a vertex", name, t);
    double a = min_angle(xyz + 3 * k[0], xyz + 3 * k[1], xyz + 3 * k[2]);
    /* LIGGGHTS refuses an angle below ~0.06 degree and merges nodes closer than 1e-8 m */
    SA_REQUIRE(a > 0.1 * M_PI / 180, SA_ERR_INPUT,
               "mesh '%s': triangle %d is degenerate (smallest angle %g degree, must be > 0.1)",
               name, t, a * 180 / M_PI);
    for (int c = 0; c < 3; c++) {
      const double *p = xyz + 3 * k[c], *q = xyz + 3 * k[(c + 1) % 3];
      double d = fmax(fmax(fabs(p[0] - q[0]), fabs(p[1] - q[1])), fabs(p[2] - q[2]));
      SA_REQUIRE(d > 1e-7, SA_ERR_INPUT,
                 "mesh '%s': triangle %d has an edge of %g m (LIGGGHTS merges nodes closer than "
                 "1e-8 m; must be > 1e-7 m)",
                 name, t, d);
    }
  }
  /* duplicate triangles (same three vertices): LIGGGHTS aborts on them */
  int *s = malloc(3 * (size_t)ntri * sizeof *s);
  SA_REQUIRE(s, SA_ERR_MEMORY, "cannot allocate %d ints", 3 * ntri);
  memcpy(s, tri, 3 * (size_t)ntri * sizeof *s);
  for (int t = 0; t < ntri; t++) sort3(s + 3 * t);
  qsort(s, ntri, 3 * sizeof *s, cmp_int3);
  int dup = -1;
  for (int t = 1; t < ntri && dup < 0; t++)
    if (!cmp_int3(s + 3 * t, s + 3 * (t - 1))) dup = t;
  int dv[3] = {0, 0, 0};
  if (dup >= 0) memcpy(dv, s + 3 * dup, sizeof dv);
  free(s);
  SA_REQUIRE(dup < 0, SA_ERR_INPUT, "mesh '%s': two triangles share vertices %d %d %d", name, dv[0],
             dv[1], dv[2]);
  return 0;
}

static int add_mesh_here(DemBridge *b, const char *name, int nverts, const double *xyz, int ntri,
                        const int *tri, DemWallType type, int *id) {
  SA_REQUIRE(b && b->lmp && id, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_add_mesh before dem_bridge_setup");
  SA_REQUIRE(!b->walls_done, SA_ERR_INPUT,
             "dem_bridge_add_mesh after the walls were finalized (first run)");
  SA_REQUIRE(type == DEM_WALL_SILICONE || type == DEM_WALL_STEEL, SA_ERR_INPUT,
             "mesh '%s': wall type %d is neither DEM_WALL_SILICONE nor DEM_WALL_STEEL",
             name ? name : "", (int)type);
  SA_CHECK(mesh_check(b, name, nverts, xyz, ntri, tri));
  if (b->resumed) SA_CHECK(ck_mesh_check(b, name, nverts, xyz, ntri, tri, type));
  if (b->nmesh == b->mesh_cap) {
    int cap = b->mesh_cap ? 2 * b->mesh_cap : 4;
    DemMesh *t = realloc(b->mesh, (size_t)cap * sizeof *t);
    SA_REQUIRE(t, SA_ERR_MEMORY, "cannot allocate %d meshes", cap);
    b->mesh = t;
    b->mesh_cap = cap;
  }
  DemMesh *m = &b->mesh[b->nmesh];
  memset(m, 0, sizeof *m);
  snprintf(m->fix_id, sizeof m->fix_id, "mesh_%s", name);
  m->type = type;
  m->nverts = nverts;
  m->ntri = ntri;
  m->xyz = malloc(3 * (size_t)nverts * sizeof *m->xyz);
  m->tri = malloc(3 * (size_t)ntri * sizeof *m->tri);
  m->idx = malloc(3 * (size_t)ntri * sizeof *m->idx);
  m->v = calloc(3 * (size_t)nverts, sizeof *m->v);
  if (!m->xyz || !m->tri || !m->idx || !m->v) {
    free(m->xyz), free(m->tri), free(m->idx), free(m->v);
    return SA_ERROR(SA_ERR_MEMORY, "mesh '%s': cannot allocate %d vertices", name, nverts);
  }
  memcpy(m->xyz, xyz, 3 * (size_t)nverts * sizeof *xyz);
  memcpy(m->tri, tri, 3 * (size_t)ntri * sizeof *tri);
  memcpy(m->idx, tri, 3 * (size_t)ntri * sizeof *tri);
  if (b->resumed) /* the node velocities of the checkpoint, until the caller sets others */
    memcpy(m->v, b->ck->mesh[b->nmesh].v, 3 * (size_t)nverts * sizeof *m->v);

  char path[320];
  snprintf(path, sizeof path, "%s/%s.stl", b->tmpdir, name);
  FILE *f = fopen(path, "w");
  int ok = f != NULL;
  if (ok) {
    fprintf(f, "solid %s\n", name);
    for (int t = 0; t < ntri; t++) {
      fprintf(f, " facet normal 0 0 0\n  outer loop\n");
      for (int c = 0; c < 3; c++) {
        const double *p = xyz + 3 * tri[3 * t + c];
        fprintf(f, "   vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
      }
      fprintf(f, "  endloop\n endfacet\n");
    }
    fprintf(f, "endsolid %s\n", name);
    ok = !ferror(f);
    ok = (fclose(f) == 0) && ok;
  }
  if (!ok) {
    remove(path);
    free(m->xyz), free(m->tri), free(m->idx), free(m->v);
    return SA_ERROR(SA_ERR_IO, "cannot write the temporary mesh file %s", path);
  }
  /* LIGGGHTS reads the file while creating the fix */
  int rc = send(b, "fix %s all mesh/surface/stress file %s type %d stress on", m->fix_id, path,
                (int)type);
  remove(path);
  if (rc) {
    free(m->xyz), free(m->tri), free(m->idx), free(m->v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  b->nmesh++;
  m->shim = dem_shim_mesh(b->lmp, m->fix_id);
  SA_REQUIRE(m->shim, SA_ERR_LIBRARY, "LIGGGHTS did not create mesh '%s'", name);
  int n = dem_shim_mesh_size(m->shim);
  /* (several ranks: LIGGGHTS distributes the triangles at the set-up pass; mesh_map checks) */
  SA_REQUIRE(n == ntri || b->np > 1, SA_ERR_LIBRARY,
             "LIGGGHTS read %d of the %d triangles of mesh '%s'", n, ntri, name);
  SA_REQUIRE(dem_shim_mesh_make_moving(m->shim) == 0, SA_ERR_LIBRARY,
             "cannot make mesh '%s' movable", name);
  b->need_setup = 1;
  *id = b->nmesh - 1;
  if (b->resumed) {
    /* the checkpoint's node velocities for the set-up pass, which follows the last mesh at
     * once: with the walls where they were at the checkpoint (the caller moves them next) */
    dem_shim_mesh_set_nodes(b->lmp, m->shim, m->idx, m->xyz, m->v, 0);
    if (b->nmesh == b->ck->nmesh) SA_CHECK(finalize_walls_here(b));
  }
  return 0;
}

/* Checks LIGGGHTS' triangles against the caller's, element id by id, and records for each
 * (id, corner) the caller vertex there (LIGGGHTS keeps the file's corner order; checked). */
static int mesh_map(DemBridge *b, DemMesh *m) {
  /* the triangles this rank owns (all of them on one rank); an error is recorded, not returned
   * at once, so that every rank reaches the count below */
  int n = dem_shim_mesh_size(m->shim), rc = 0;
  double ext = 0;
  for (int k = 0; k < 3; k++) ext = fmax(ext, b->p.box_hi[k] - b->p.box_lo[k]);
  double tol = 1e-12 * ext;
  for (int i = 0; i < n && !rc; i++) {
    int id = dem_shim_mesh_id(m->shim, i);
    if (id < 0 || id >= m->ntri) {
      rc = SA_ERROR(SA_ERR_LIBRARY, "mesh '%s': element id %d out of range", m->fix_id + 5, id);
      break;
    }
    for (int c = 0; c < 3 && !rc; c++) {
      double x[3];
      dem_shim_mesh_node(m->shim, i, c, x);
      int found = -1;
      for (int cc = 0; cc < 3 && found < 0; cc++) {
        const double *p = m->xyz + 3 * m->tri[3 * id + cc];
        if (fabs(p[0] - x[0]) <= tol && fabs(p[1] - x[1]) <= tol && fabs(p[2] - x[2]) <= tol)
          found = m->tri[3 * id + cc];
      }
      if (found < 0)
        rc = SA_ERROR(SA_ERR_LIBRARY,
                      "mesh '%s': LIGGGHTS' triangle %d corner %d (%g, %g, %g) is not a corner of "
                      "the caller's triangle %d",
                      m->fix_id + 5, id, c, x[0], x[1], x[2], id);
      else
        m->idx[3 * id + c] = found;
    }
  }
  long long all = dem_par_sum_ll(n);
  if (!rc && all != m->ntri)
    rc = SA_ERROR(SA_ERR_LIBRARY, "mesh '%s': LIGGGHTS holds %lld of %d triangles", m->fix_id + 5,
                  all, m->ntri);
  return rc;
}

static int finalize_walls_here(DemBridge *b) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_finalize_walls before dem_bridge_setup");
  if (b->walls_done) return 0;
  if (b->resumed)
    SA_REQUIRE(b->nmesh == b->ck->nmesh, SA_ERR_INPUT,
               "checkpoint '%s' has %d wall meshes, %d were added before the first run",
               b->ck->path, b->ck->nmesh, b->nmesh);
  b->walls_done = 1;
  if (b->nmesh == 0) return 0;
  char list[DEM_CMD_MAX / 2] = "";
  size_t len = 0;
  for (int i = 0; i < b->nmesh; i++) {
    int n = snprintf(list + len, sizeof list - len, " %s", b->mesh[i].fix_id);
    SA_REQUIRE(n > 0 && len + n < sizeof list, SA_ERR_INPUT, "too many wall meshes (%d)", b->nmesh);
    len += n;
  }
  SA_CHECK(send(b, "fix walls all wall/gran model hertz tangential history%s mesh n_meshes %d meshes%s",
                b->rolling ? " rolling_friction epsd2" : "", b->nmesh, list));
  /* a set-up pass (LIGGGHTS distributes and may reorder the mesh elements there) */
  SA_CHECK(send(b, "run 0 post no"));
  b->ran = 1;
  b->need_setup = 0;
  int rc = 0; /* every mesh on every rank, then agreed: mesh_map ends in a collective */
  for (int i = 0; i < b->nmesh; i++) {
    int r = mesh_map(b, &b->mesh[i]);
    if (!rc) rc = r;
  }
  if (b->np > 1) rc = dem_par_agree(rc);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  /* node velocities are not in LIGGGHTS' restart ("v" is restart_no): those of the checkpoint
   * or the caller's since (the set-up pass keeps them; set again once the map is checked) */
  if (b->resumed) {
    for (int i = 0; i < b->nmesh; i++) {
      DemMesh *m = &b->mesh[i];
      dem_shim_mesh_set_nodes(b->lmp, m->shim, m->idx, m->xyz, m->v, 0);
    }
    SA_CHECK(ck_setup_pass(b, 0)); /* the run 0 above was the set-up pass */
  }
  return 0;
}

static int mesh_get(DemBridge *b, int id, DemMesh **m) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(id >= 0 && id < b->nmesh, SA_ERR_INPUT, "no wall mesh %d (there are %d)", id,
             b->nmesh);
  *m = &b->mesh[id];
  return 0;
}

int dem_bridge_mesh_ntri(DemBridge *b, int id) {
  return b && id >= 0 && id < b->nmesh ? b->mesh[id].ntri : 0;
}

static int check_nodes(const DemBridge *b, const DemMesh *m, const double *xyz,
                       const double *v);
static int note_builds(DemBridge *b, DemMesh *m);

static int set_mesh_nodes_here(DemBridge *b, int id, const double *xyz, const double *v) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(xyz, SA_ERR_INPUT, "mesh '%s': no node positions", m->fix_id + 5);
  SA_CHECK(check_nodes(b, m, xyz, v));
  SA_CHECK(note_builds(b, m));
  m->path_set = 0;
  memcpy(m->xyz, xyz, 3 * (size_t)m->nverts * sizeof *xyz);
  if (v)
    memcpy(m->v, v, 3 * (size_t)m->nverts * sizeof *v);
  else
    memset(m->v, 0, 3 * (size_t)m->nverts * sizeof *m->v);
  dem_shim_mesh_set_nodes(b->lmp, m->shim, m->idx, m->xyz, v, b->ran);
  return 0;
}

static int check_nodes(const DemBridge *b, const DemMesh *m, const double *xyz,
                       const double *v) {
  for (int i = 0; i < m->nverts; i++) {
    SA_REQUIRE(finite3(xyz + 3 * i) && (!v || finite3(v + 3 * i)), SA_ERR_NAN,
               "mesh '%s': node %d position or velocity is not finite", m->fix_id + 5, i);
    SA_REQUIRE(inside_box(&b->p, xyz + 3 * i), SA_ERR_DOMAIN,
               "mesh '%s': node %d (%g, %g, %g) left the DEM box", m->fix_id + 5, i, xyz[3 * i],
               xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  return 0;
}

static int set_mesh_path_here(DemBridge *b, int id, const double *x0, const double *x1,
                              const double *v) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(x0 && x1, SA_ERR_INPUT, "mesh '%s': no path ends", m->fix_id + 5);
  m->path_set = 0;
  /* the box is convex: both ends inside, every point between is */
  SA_CHECK(check_nodes(b, m, x0, v));
  SA_CHECK(check_nodes(b, m, x1, NULL));
  size_t n = 3 * (size_t)m->nverts;
  if (!m->path) SA_CALLOC(m->path, 2 * n);
  memcpy(m->path, x0, n * sizeof *x0);
  memcpy(m->path + n, x1, n * sizeof *x1);
  if (v)
    memcpy(m->v, v, n * sizeof *v);
  else
    memset(m->v, 0, n * sizeof *m->v);
  m->path_set = 1;
  return 0;
}

/* Before mesh m's nodes change. LIGGGHTS stores the node positions of every neighbour build as
 * the reference of its rebuild test (storeNodePosRebuild); a build since the last change used
 * the nodes m holds now, so they become the reference here too. Builds are seen on every rank
 * alike: the build count, the step of the last build and the set-ups started. */
static int note_builds(DemBridge *b, DemMesh *m) {
  if (!b->ran) {
    m->built_valid = 0;
    return 0;
  }
  long long e[3];
  dem_shim_builds(b->lmp, &e[0], &e[1]);
  e[2] = b->setups;
  if (m->built_valid && !memcmp(e, m->built_epoch, sizeof e)) return 0;
  size_t n = 3 * (size_t)m->nverts;
  if (!m->built) SA_CALLOC(m->built, n);
  memcpy(m->built, m->xyz, n * sizeof *m->xyz);
  memcpy(m->built_epoch, e, sizeof e);
  m->built_valid = 1;
  return 0;
}

/* LIGGGHTS' rebuild test (MultiNodeMesh::decideRebuild: a node of some triangle moved more than
 * half the skin since the last build, the same arithmetic), on every rank from the whole mesh
 * instead of each rank's triangles and a reduction: requests the rebuild at the next step. */
static int request_rebuild_if_moved(DemBridge *b, DemMesh *m) {
  if (!b->ran || !m->built_valid) return 0;
  if (!m->used) {
    SA_CALLOC(m->used, (size_t)m->nverts);
    for (int k = 0; k < 3 * m->ntri; k++) m->used[m->tri[k]] = 1;
  }
  double skin = dem_shim_skin(b->lmp), triggersq = 0.25 * skin * skin;
  for (int i = 0; i < m->nverts; i++) {
    if (!m->used[i]) continue;
    const double *x = m->xyz + 3 * i, *o = m->built + 3 * i;
    double d[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
    if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > triggersq) {
      dem_shim_mesh_request_rebuild(b->lmp, m->shim);
      return 0;
    }
  }
  return 0;
}

static int place_on_path_here(DemBridge *b, int id, double a) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(m->path_set, SA_ERR_INPUT, "mesh '%s': placed on a path before one was set",
             m->fix_id + 5);
  SA_REQUIRE(a >= 0 && a <= 1, SA_ERR_INPUT, "mesh '%s': path fraction %g outside [0, 1]",
             m->fix_id + 5, a);
  SA_CHECK(note_builds(b, m));
  size_t n = 3 * (size_t)m->nverts;
  const double *x0 = m->path, *x1 = m->path + n;
  for (size_t k = 0; k < n; k++) m->xyz[k] = x0[k] + a * (x1[k] - x0[k]);
  dem_shim_mesh_place(m->shim, m->idx, m->xyz, m->v);
  return request_rebuild_if_moved(b, m);
}

static int place_flat_mesh_here(DemBridge *b, int id, double z, double vz) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(isfinite(z) && isfinite(vz), SA_ERR_NAN, "mesh '%s': height %g or speed %g is "
             "not finite", m->fix_id + 5, z, vz);
  for (int i = 0; i < m->nverts; i++) {
    double *x = m->xyz + 3 * i;
    SA_REQUIRE(x[2] == m->xyz[2], SA_ERR_INPUT, "mesh '%s' is not flat (node %d at z = %g, "
               "node 0 at %g): it cannot be moved as a flat mesh", m->fix_id + 5, i, x[2],
               m->xyz[2]);
    double p[3] = {x[0], x[1], z};
    SA_REQUIRE(inside_box(&b->p, p), SA_ERR_DOMAIN, "mesh '%s': node %d (%g, %g, %g) left "
               "the DEM box", m->fix_id + 5, i, p[0], p[1], p[2]);
  }
  SA_CHECK(note_builds(b, m));
  for (int i = 0; i < m->nverts; i++) {
    m->xyz[3 * i + 2] = z;
    m->v[3 * i] = m->v[3 * i + 1] = 0, m->v[3 * i + 2] = vz;
  }
  m->path_set = 0;
  dem_shim_mesh_place_flat(m->shim, z, vz);
  return request_rebuild_if_moved(b, m);
}

static int mesh_forces_here(DemBridge *b, int id, double *f) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(f, SA_ERR_INPUT, "mesh '%s': no output array", m->fix_id + 5);
  if (!b->ran) {
    memset(f, 0, 3 * (size_t)m->ntri * sizeof *f);
    return 0;
  }
  SA_REQUIRE(dem_shim_mesh_forces(m->shim, f) == 0, SA_ERR_LIBRARY,
             "mesh '%s' has no force (stress) data", m->fix_id + 5);
  return 0;
}

static int mesh_nodes_here(DemBridge *b, int id, double *xyz) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  int n = dem_shim_mesh_size(m->shim);
  for (int i = 0; i < 3 * m->nverts; i++) xyz[i] = NAN;
  for (int i = 0; i < n; i++) {
    int t = dem_shim_mesh_id(m->shim, i);
    for (int c = 0; c < 3; c++) {
      double x[3];
      dem_shim_mesh_node(m->shim, i, c, x);
      double *o = xyz + 3 * m->idx[3 * t + c];
      if (isnan(o[0])) {
        memcpy(o, x, sizeof x);
        continue;
      }
      SA_REQUIRE(o[0] == x[0] && o[1] == x[1] && o[2] == x[2], SA_ERR_INTERNAL,
                 "mesh '%s': the copies of vertex %d disagree in LIGGGHTS", m->fix_id + 5,
                 m->idx[3 * t + c]);
    }
  }
  return 0;
}

/* ---------------------------------------------------------------- grains */

static int nlocal(DemBridge *b) {
  int *n = lammps_extract_global(b->lmp, "nlocal");
  return n ? *n : 0;
}

static int count_here(DemBridge *b) { return b && b->lmp ? nlocal(b) : 0; }

/* Smallest distance from x to any wall triangle, less than `than` (else `than`). */
static double wall_dist(const DemBridge *b, const double *x, double than) {
  double best2 = than * than;
  for (int i = 0; i < b->nmesh; i++) {
    const DemMesh *m = &b->mesh[i];
    for (int t = 0; t < m->ntri; t++) {
      const double *p0 = m->xyz + 3 * m->tri[3 * t], *p1 = m->xyz + 3 * m->tri[3 * t + 1],
                   *p2 = m->xyz + 3 * m->tri[3 * t + 2];
      int skip = 0;
      for (int k = 0; k < 3 && !skip; k++) {
        double lo = fmin(fmin(p0[k], p1[k]), p2[k]), hi = fmax(fmax(p0[k], p1[k]), p2[k]);
        skip = x[k] < lo - than || x[k] > hi + than;
      }
      if (skip) continue;
      double d2 = point_tri_dist2(x, p0, p1, p2);
      if (d2 < best2) best2 = d2;
    }
  }
  return sqrt(best2);
}

static int insert_cylinder_here(DemBridge *b, double cx, double cy, double r, double z_lo,
                               double z_hi, int n, int *inserted) {
  SA_REQUIRE(b && b->lmp && inserted, SA_ERR_INTERNAL, "DEM bridge not started");
  *inserted = 0;
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_insert_cylinder before dem_bridge_setup");
  const DemParams *p = &b->p;
  double R = 0.5 * p->diameter;
  SA_REQUIRE(n >= 0, SA_ERR_INPUT, "insert: n = %d grains, must be >= 0", n);
  SA_REQUIRE(isfinite(cx) && isfinite(cy) && isfinite(z_lo) && isfinite(z_hi) && isfinite(r),
             SA_ERR_INPUT, "insert: the cylinder is not finite");
  SA_REQUIRE(r >= R && z_hi - z_lo >= p->diameter, SA_ERR_INPUT,
             "insert: cylinder radius %g m and height %g m must hold one grain (diameter %g m)", r,
             z_hi - z_lo, p->diameter);
  SA_REQUIRE(cx - r >= p->box_lo[0] && cx + r <= p->box_hi[0] && cy - r >= p->box_lo[1] &&
                 cy + r <= p->box_hi[1] && z_lo >= p->box_lo[2] && z_hi <= p->box_hi[2],
             SA_ERR_INPUT, "insert: the cylinder (%g, %g) r %g, z %g..%g is not inside the DEM box",
             cx, cy, r, z_lo, z_hi);
  if (n == 0) return 0;

  /* existing grains + candidates in one array; a uniform grid of cell 2R rebuilt per pass is
   * avoided: the grid covers the cylinder and is filled incrementally. */
  int n0 = nlocal(b);
  double *rad = lammps_extract_atom(b->lmp, "radius");
  CkGrain *all = NULL;
  if (b->np > 1) { /* every rank places the same grains among those of every rank */
    SA_CHECK(gather_grains(b, &all, &n0));
    if (grow_double(&b->scratch, &b->scratch_cap, (size_t)n0 + 1)) {
      free(all);
      return sa_error_push(SA_ERR_MEMORY, __func__, __FILE__, __LINE__);
    }
    rad = b->scratch;
    for (int i = 0; i < n0; i++) rad[i] = all[i].radius;
  }
  if (grow_double(&b->pos, &b->pos_cap, 3 * ((size_t)n0 + n))) {
    free(all);
    return sa_error_push(SA_ERR_MEMORY, __func__, __FILE__, __LINE__);
  }
  double **x = lammps_extract_atom(b->lmp, "x");
  double rmax = R;
  for (int i = 0; i < n0; i++) {
    memcpy(b->pos + 3 * i, all ? all[i].x : x[i], 3 * sizeof(double));
    if (rad && rad[i] > rmax) rmax = rad[i];
  }
  free(all);
  Grid g;
  double h = 2 * rmax;
  g.h = h;
  g.lo[0] = cx - r - h, g.lo[1] = cy - r - h, g.lo[2] = z_lo - h;
  g.n[0] = g.n[1] = (int)ceil((2 * r + 2 * h) / h) + 1;
  g.n[2] = (int)ceil((z_hi - z_lo + 2 * h) / h) + 1;
  size_t ncell = (size_t)g.n[0] * g.n[1] * g.n[2];
  SA_REQUIRE(ncell < (size_t)1 << 28, SA_ERR_INPUT, "insert: the cylinder is too large (%zu cells)",
             ncell);
  SA_CHECK(grow_int(&b->cell_head, &b->cell_cap, ncell));
  SA_CHECK(grow_int(&b->cell_next, &b->next_cap, (size_t)n0 + n + 1));
  for (size_t c = 0; c < ncell; c++) b->cell_head[c] = -1;
  int np = 0;
#define CELL_OF(q, ci)                                                 \
  do {                                                                 \
    for (int k_ = 0; k_ < 3; k_++) {                                   \
      int c_ = (int)floor(((q)[k_] - g.lo[k_]) / h);                   \
      (ci)[k_] = c_ < 0 ? 0 : c_ >= g.n[k_] ? g.n[k_] - 1 : c_;         \
    }                                                                  \
  } while (0)
  for (int i = 0; i < n0; i++) {
    const double *q = b->pos + 3 * i;
    if (q[0] < g.lo[0] || q[1] < g.lo[1] || q[2] < g.lo[2] || q[0] > g.lo[0] + g.n[0] * h ||
        q[1] > g.lo[1] + g.n[1] * h || q[2] > g.lo[2] + g.n[2] * h)
      continue;
    int ci[3];
    CELL_OF(q, ci);
    size_t c = ((size_t)ci[2] * g.n[1] + ci[1]) * g.n[0] + ci[0];
    b->cell_next[i] = b->cell_head[c];
    b->cell_head[c] = i;
  }
  np = n0;
  long attempts = 0, max_attempts = 1000L * n + 10000;
  double rr = r - R;
  while (np - n0 < n && attempts < max_attempts) {
    attempts++;
    double q[3], ux, uy;
    do {
      ux = 2 * rng_uniform(b) - 1, uy = 2 * rng_uniform(b) - 1;
    } while (ux * ux + uy * uy > 1);
    q[0] = cx + rr * ux, q[1] = cy + rr * uy;
    q[2] = z_lo + R + (z_hi - z_lo - 2 * R) * rng_uniform(b);
    int ci[3], ok = 1;
    CELL_OF(q, ci);
    for (int dz = -1; dz <= 1 && ok; dz++)
      for (int dy = -1; dy <= 1 && ok; dy++)
        for (int dx = -1; dx <= 1 && ok; dx++) {
          int a = ci[0] + dx, bb = ci[1] + dy, c = ci[2] + dz;
          if (a < 0 || bb < 0 || c < 0 || a >= g.n[0] || bb >= g.n[1] || c >= g.n[2]) continue;
          for (int j = b->cell_head[((size_t)c * g.n[1] + bb) * g.n[0] + a]; j >= 0 && ok;
               j = b->cell_next[j]) {
            const double *o = b->pos + 3 * j;
            double rj = j < n0 && rad ? rad[j] : R;
            double d2 = (q[0] - o[0]) * (q[0] - o[0]) + (q[1] - o[1]) * (q[1] - o[1]) +
                        (q[2] - o[2]) * (q[2] - o[2]);
            if (d2 < (R + rj) * (R + rj)) ok = 0;
          }
        }
    if (!ok || wall_dist(b, q, R) < R) continue;
    memcpy(b->pos + 3 * np, q, sizeof q);
    size_t c = ((size_t)ci[2] * g.n[1] + ci[1]) * g.n[0] + ci[0];
    b->cell_next[np] = b->cell_head[c];
    b->cell_head[c] = np;
    np++;
  }
#undef CELL_OF
  for (int i = n0; i < np; i++)
    SA_CHECK(send(b, "create_atoms 1 single %.17g %.17g %.17g units box", b->pos[3 * i],
                  b->pos[3 * i + 1], b->pos[3 * i + 2]));
  /* every grain has the same size and density: set them on type 1 as a whole */
  SA_CHECK(send(b, "set type 1 diameter %.17g", p->diameter));
  SA_CHECK(send(b, "set type 1 density %.17g", p->density));
  *inserted = (int)dem_par_sum_ll(nlocal(b)) - n0;
  SA_REQUIRE(*inserted == np - n0, SA_ERR_LIBRARY, "LIGGGHTS created %d of %d grains", *inserted,
             np - n0);
  b->need_setup = 1;
  return 0;
}

static int run_here(DemBridge *b, int nsteps) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_run before dem_bridge_setup");
  SA_REQUIRE(nsteps >= 0, SA_ERR_INPUT, "dem_bridge_run: nsteps = %d, must be >= 0", nsteps);
  SA_CHECK(finalize_walls_here(b));
  if (nsteps == 0) return 0;
  /* the full set-up (neighbour lists from scratch, fix set-up) only when something changed */
  /* long runs (pouring, settling) print LIGGGHTS's time breakdown to the log; per-step runs
   * of the coupling would flood it */
  SA_CHECK(send(b, "run %d pre %s post %s", nsteps, b->need_setup || !b->ran ? "yes" : "no",
                nsteps >= 1000 ? "yes" : "no"));
  b->ran = 1;
  b->need_setup = 0;
  return 0;
}

static int set_young_here(DemBridge *b, double young, double dt) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_set_young before dem_bridge_setup");
  DemParams p = b->p;
  p.young = p.wall_young = young;
  p.dt = dt;
  SA_CHECK(params_check(&p));
  /* a fix redefined under its ID replaces the old one; the pair and wall styles read the
   * material properties again at the next full set-up (test dem_stiffness_switch checks the
   * static Hertz overlap before and after) */
  SA_CHECK(send(b, "fix m1 all property/global youngsModulus peratomtype %.17g %.17g %.17g",
                p.young, silicone_young(&p), p.wall_young));
  SA_CHECK(send(b, "timestep %.17g", p.dt));
  b->p = p;
  b->need_setup = 1;
  return 0;
}

static int scale_friction_here(DemBridge *b, double scale) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_scale_friction before dem_bridge_setup");
  SA_REQUIRE(scale >= 0 && scale <= 1, SA_ERR_INPUT, "friction scale %g outside [0, 1]", scale);
  /* the pair and wall styles read the coefficients again at the next full set-up (test
   * dem_friction_switch: a block on a slope slides frictionless and sticks after the switch) */
  SA_CHECK(send_friction(b, &b->p, scale));
  b->need_setup = 1;
  return 0;
}

static int set_skin_here(DemBridge *b, double skin) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_set_skin before dem_bridge_setup");
  DemParams p = b->p;
  p.skin = skin;
  SA_CHECK(params_check(&p));
  SA_CHECK(send(b, "neighbor %.17g bin", p.skin));
  b->p = p;
  b->need_setup = 1;
  return 0;
}

static int particles_here(DemBridge *b, double *x, double *v, double *f, double *radius) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  int n = nlocal(b);
  double **src[3] = {x ? lammps_extract_atom(b->lmp, "x") : NULL,
                     v ? lammps_extract_atom(b->lmp, "v") : NULL,
                     f ? lammps_extract_atom(b->lmp, "f") : NULL};
  double *dst[3] = {x, v, f};
  for (int a = 0; a < 3; a++) {
    if (!dst[a]) continue;
    SA_REQUIRE(src[a] || n == 0, SA_ERR_LIBRARY, "LIGGGHTS has no per-atom array %d", a);
    for (int i = 0; i < n; i++) memcpy(dst[a] + 3 * i, src[a][i], 3 * sizeof(double));
  }
  if (radius) {
    double *r = lammps_extract_atom(b->lmp, "radius");
    SA_REQUIRE(r || n == 0, SA_ERR_LIBRARY, "LIGGGHTS has no radius array");
    if (n) memcpy(radius, r, (size_t)n * sizeof *r);
  }
  return 0;
}

static int wall_contacts_here(DemBridge *b, int id, int max, int *grain, int *tri, double *shear,
                             int *n) {
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  SA_REQUIRE(n && max >= 0 && (max == 0 || (grain && tri && shear)), SA_ERR_INPUT,
             "dem_bridge_wall_contacts: no output arrays");
  *n = 0;
  SA_REQUIRE(b->ran, SA_ERR_INPUT, "dem_bridge_wall_contacts before the first run");
  int k = dem_shim_mesh_contacts(b->lmp, m->shim, max, grain, tri, shear);
  SA_REQUIRE(k >= 0, SA_ERR_LIBRARY, "mesh '%s' has no contact history", m->fix_id + 5);
  *n = k;
  return 0;
}

static int particle_ids_here(DemBridge *b, int *id) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  int n = nlocal(b);
  int *tag = lammps_extract_atom(b->lmp, "id");
  SA_REQUIRE(tag || n == 0, SA_ERR_LIBRARY, "LIGGGHTS has no atom id array");
  SA_REQUIRE(id || n == 0, SA_ERR_INPUT, "dem_bridge_particle_ids: no output array");
  if (n) memcpy(id, tag, (size_t)n * sizeof *id);
  return 0;
}

static double kinetic_energy_here(DemBridge *b) {
  if (!b || !b->lmp) return 0;
  int n = nlocal(b);
  double **v = lammps_extract_atom(b->lmp, "v"), **w = lammps_extract_atom(b->lmp, "omega");
  double *m = lammps_extract_atom(b->lmp, "rmass"), *r = lammps_extract_atom(b->lmp, "radius");
  if (!v || !m) return 0;
  double e = 0;
  for (int i = 0; i < n; i++) {
    e += 0.5 * m[i] * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    if (w && r) /* solid sphere: I = 2/5 m r^2 */
      e += 0.2 * m[i] * r[i] * r[i] * (w[i][0] * w[i][0] + w[i][1] * w[i][1] + w[i][2] * w[i][2]);
  }
  return e;
}

const char *dem_bridge_overlap_site(const DemBridge *b, double pos[3]) {
  if (!b) return "";
  memcpy(pos, b->ov_pos, sizeof b->ov_pos);
  return b->ov_mesh < 0 || b->ov_mesh >= b->nmesh ? "two grains" : b->mesh[b->ov_mesh].fix_id;
}

static double max_overlap_here(DemBridge *b) {
  if (!b || !b->lmp) return 0;
  b->ov_mesh = -1;
  b->ov_pos[0] = b->ov_pos[1] = b->ov_pos[2] = NAN;
  int n = nlocal(b);
  double **x = lammps_extract_atom(b->lmp, "x");
  double *rad = lammps_extract_atom(b->lmp, "radius");
  CkGrain *all = NULL;
  if (b->np > 1) { /* the grains of every rank, on every rank (each finds the same) */
    if (gather_grains(b, &all, &n)) return NAN;
    if (grow_double(&b->scratch, &b->scratch_cap, (size_t)n + 1)) {
      free(all);
      return NAN;
    }
    rad = b->scratch;
    for (int i = 0; i < n; i++) rad[i] = all[i].radius;
  }
  if (n == 0) {
    free(all);
    return 0;
  }
  if ((!all && !x) || !rad || grow_double(&b->pos, &b->pos_cap, 3 * (size_t)n)) {
    free(all);
    return NAN;
  }
  double rmax = 0;
  for (int i = 0; i < n; i++) {
    memcpy(b->pos + 3 * i, all ? all[i].x : x[i], 3 * sizeof(double));
    if (rad[i] > rmax) rmax = rad[i];
  }
  free(all);
  Grid g;
  if (grid_build(b, b->pos, n, 2 * rmax, &g)) return NAN;
  double worst = 0; /* largest overlap / diameter */
  /* grain-grain: each pair once (j < i) in the 27 neighbouring cells */
  for (int i = 0; i < n; i++) {
    const double *p = b->pos + 3 * i;
    int c0[3], c1[3];
    for (int k = 0; k < 3; k++) grid_range(&g, k, p[k] - 2 * rmax, p[k] + 2 * rmax, c0 + k, c1 + k);
    for (int cz = c0[2]; cz <= c1[2]; cz++)
      for (int cy = c0[1]; cy <= c1[1]; cy++)
        for (int cx = c0[0]; cx <= c1[0]; cx++)
          for (int j = b->cell_head[((size_t)cz * g.n[1] + cy) * g.n[0] + cx]; j >= 0;
               j = b->cell_next[j]) {
            if (j >= i) continue;
            const double *q = b->pos + 3 * j;
            double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]);
            double s = rad[i] + rad[j];
            if (d2 >= s * s) continue;
            double ov = (s - sqrt(d2)) / fmin(2 * rad[i], 2 * rad[j]);
            if (ov > worst) {
              worst = ov, b->ov_mesh = -1;
              memcpy(b->ov_pos, p, sizeof b->ov_pos);
            }
          }
  }
  /* grain-wall: the grains in the cells that a triangle's box (grown by rmax) touches; a
   * compliant silicone wall's overlaps are its indentation, kept apart */
  b->indent = 0;
  b->indent_pos[0] = b->indent_pos[1] = b->indent_pos[2] = NAN;
  for (int im = 0; im < b->nmesh; im++) {
    const DemMesh *m = &b->mesh[im];
    int compliant = m->type == DEM_WALL_SILICONE && b->p.silicone_young > 0;
    for (int t = 0; t < m->ntri; t++) {
      const double *p0 = m->xyz + 3 * m->tri[3 * t], *p1 = m->xyz + 3 * m->tri[3 * t + 1],
                   *p2 = m->xyz + 3 * m->tri[3 * t + 2];
      int c0[3], c1[3];
      for (int k = 0; k < 3; k++)
        grid_range(&g, k, fmin(fmin(p0[k], p1[k]), p2[k]) - rmax,
                   fmax(fmax(p0[k], p1[k]), p2[k]) + rmax, c0 + k, c1 + k);
      for (int cz = c0[2]; cz <= c1[2]; cz++)
        for (int cy = c0[1]; cy <= c1[1]; cy++)
          for (int cx = c0[0]; cx <= c1[0]; cx++)
            for (int j = b->cell_head[((size_t)cz * g.n[1] + cy) * g.n[0] + cx]; j >= 0;
                 j = b->cell_next[j]) {
              double d2 = point_tri_dist2(b->pos + 3 * j, p0, p1, p2);
              if (d2 >= rad[j] * rad[j]) continue;
              double ov = (rad[j] - sqrt(d2)) / (2 * rad[j]);
              if (compliant) {
                if (ov > b->indent) {
                  b->indent = ov;
                  memcpy(b->indent_pos, b->pos + 3 * j, sizeof b->indent_pos);
                }
              } else if (ov > worst) {
                worst = ov, b->ov_mesh = im;
                memcpy(b->ov_pos, b->pos + 3 * j, sizeof b->ov_pos);
              }
            }
    }
  }
  return worst;
}

static int write_restart_here(DemBridge *b, const char *path) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_write_restart before dem_bridge_setup");
  SA_REQUIRE(path_is_plain(path) && strlen(path) < DEM_CMD_MAX - 64, SA_ERR_INPUT,
             "restart path '%s' must be non-empty, without whitespace or any of # $ * %% & ' \"",
             path ? path : "(null)");
  /* LIGGGHTS aborts if it cannot open the file: try first (the lead: LIGGGHTS' rank 0 writes) */
  int rc = 0;
  if (b->rank == 0) {
    FILE *f = fopen(path, "wb");
    if (f) fclose(f);
    else rc = SA_ERROR(SA_ERR_IO, "cannot open the restart file '%s'", path);
  }
  if (b->np > 1) rc = dem_par_agree(rc);
  if (rc) return rc;
  SA_CHECK(send(b, "write_restart %s", path));
  return 0;
}

/* ---------------------------------------------------------------- checkpoint and resume
 *
 * One file, written atomically (temporary file in the same directory, fsync, rename), native
 * byte order (checked), little framing:
 *   offset 0  char[8]  "SADEMCKP"
 *          8  uint32   version (2; 1 is read too)
 *         12  uint32   0x01020304 (byte-order mark)
 *         16  int64    LIGGGHTS time step counter
 *         24  int64    grain count
 *         32  uint64   state of the bridge's insertion generator
 *         40  DemParams, field by field (25 doubles, 23 in version 1, then int64 seed)
 *             int32 nmesh; per mesh: char[32] name, int32 type, nverts, ntri,
 *               int32 tri[3 ntri], double xyz[3 nverts], double v[3 nverts]
 *             per grain (sorted by tag): int64 tag, int64 type, double x[3], v[3], omega[3],
 *               f[3], torque[3], radius, rmass
 *             int64 n; n bytes: LIGGGHTS' own restart file (write_restart)
 *   last 8    uint64   FNV-1a hash of every byte before it
 * LIGGGHTS' restart carries the grains, the time step counter, the grain-grain contact history
 * (fix contacthistory, per atom), the grain-wall contact history (fix contacthistory/mesh
 * `tracker_mesh_<name>`, per atom: triangle id and tangential spring) and the wall meshes'
 * nodes (fix mesh/surface, global). It does not carry the meshes' node velocities (element
 * property "v" is restart_no), the forces of the last step (a run's set-up recomputes them
 * from the full-step velocities, where the step itself used the half-step ones) or this
 * bridge's state: those are the framing's. Everything is validated before LIGGGHTS reads a
 * byte (it aborts the process on a bad restart file). */

#define CK_MAGIC "SADEMCKP"
#define CK_VERSION 2u /* 2: silicone_young, silicone_poisson after skin; 1 is read (as 0, 0) */
#define CK_BOM 0x01020304u
#define CK_PATH_MAX 1000

static const struct {
  const char *name;
  size_t off;
} ck_fields[] = {
#define F(x) {#x, offsetof(DemParams, x)}
    F(diameter),        F(density),       F(young),       F(poisson),        F(restitution),
    F(friction),        F(friction_wall), F(friction_piston), F(rolling_friction),
    F(wall_young),      F(wall_poisson),  F(dt),          F(dt_safety),      F(gravity[0]),
    F(gravity[1]),      F(gravity[2]),    F(box_lo[0]),   F(box_lo[1]),      F(box_lo[2]),
    F(box_hi[0]),       F(box_hi[1]),     F(box_hi[2]),   F(skin),
    F(silicone_young),  F(silicone_poisson), /* version 2 */
#undef F
};

static uint64_t fnv1a(const unsigned char *d, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) h = (h ^ d[i]) * 0x100000001b3ull;
  return h;
}

static void ck_free(Checkpoint **pck) {
  if (!pck || !*pck) return;
  Checkpoint *ck = *pck;
  for (int i = 0; i < ck->nmesh; i++) {
    free(ck->mesh[i].tri);
    free(ck->mesh[i].xyz);
    free(ck->mesh[i].v);
  }
  free(ck->mesh);
  free(ck->grain);
  free(ck);
  *pck = NULL;
}

static int cmp_grain(const void *x, const void *y) {
  int64_t a = ((const CkGrain *)x)->tag, c = ((const CkGrain *)y)->tag;
  return a < c ? -1 : a > c;
}

static const CkGrain *ck_find(const Checkpoint *ck, int64_t tag) {
  CkGrain key;
  key.tag = tag;
  return bsearch(&key, ck->grain, (size_t)ck->count, sizeof key, cmp_grain);
}

/* growable byte buffer; err set on allocation failure */
typedef struct {
  unsigned char *d;
  size_t n, cap;
  int err;
} Buf;

static void put(Buf *w, const void *p, size_t len) {
  if (w->err) return;
  if (w->n + len > w->cap) {
    size_t c = 2 * (w->n + len) + 4096;
    unsigned char *t = realloc(w->d, c);
    if (!t) {
      w->err = 1;
      return;
    }
    w->d = t, w->cap = c;
  }
  memcpy(w->d + w->n, p, len);
  w->n += len;
}

static void put_i32(Buf *w, int32_t v) { put(w, &v, sizeof v); }
static void put_i64(Buf *w, int64_t v) { put(w, &v, sizeof v); }

/* bounds-checked reader over a whole file in memory */
typedef struct {
  const unsigned char *d;
  size_t n, off;
  const char *path;
} Rd;

static int get(Rd *r, void *p, size_t len, const char *what) {
  SA_REQUIRE(len <= r->n && r->off <= r->n - len, SA_ERR_INPUT,
             "checkpoint '%s' is truncated: %s needs bytes %zu..%zu, the file has %zu bytes",
             r->path, what, r->off, r->off + len, r->n);
  if (p) memcpy(p, r->d + r->off, len);
  r->off += len;
  return 0;
}

/* Builds the in-memory checkpoint of the bridge's current state (restart bytes not included). */
static int ck_capture(DemBridge *b, Checkpoint **out) {
  Checkpoint *ck;
  SA_CALLOC(ck, 1);
  *out = ck;
  int64_t *step = lammps_extract_global(b->lmp, "ntimestep");
  SA_REQUIRE(step, SA_ERR_LIBRARY, "LIGGGHTS has no time step counter");
  ck->step = *step;
  if (b->np > 1) { /* every rank holds the whole checkpoint (ck_setup_pass reads its grains) */
    int n_all = 0;
    SA_CHECK(gather_grains(b, &ck->grain, &n_all));
    ck->count = n_all;
  } else
    ck->count = nlocal(b);
  ck->rng = b->rng;
  ck->p = b->p;
  ck->nmesh = b->nmesh;
  SA_CALLOC(ck->mesh, b->nmesh);
  for (int i = 0; i < b->nmesh; i++) {
    const DemMesh *m = &b->mesh[i];
    CkMesh *c = &ck->mesh[i];
    snprintf(c->name, sizeof c->name, "%s", m->fix_id + 5);
    c->type = (int)m->type, c->nverts = m->nverts, c->ntri = m->ntri;
    SA_CALLOC(c->tri, 3 * (size_t)m->ntri);
    SA_CALLOC(c->xyz, 3 * (size_t)m->nverts);
    SA_CALLOC(c->v, 3 * (size_t)m->nverts);
    memcpy(c->tri, m->tri, 3 * (size_t)m->ntri * sizeof *c->tri);
    memcpy(c->xyz, m->xyz, 3 * (size_t)m->nverts * sizeof *c->xyz);
    memcpy(c->v, m->v, 3 * (size_t)m->nverts * sizeof *c->v);
  }
  if (b->np > 1) return 0; /* gathered above, in tag order */
  SA_CALLOC(ck->grain, ck->count);
  int n = (int)ck->count;
  if (n == 0) return 0;
  int *tag = lammps_extract_atom(b->lmp, "id"), *type = lammps_extract_atom(b->lmp, "type");
  double **x = lammps_extract_atom(b->lmp, "x"), **v = lammps_extract_atom(b->lmp, "v"),
         **w = lammps_extract_atom(b->lmp, "omega"), **f = lammps_extract_atom(b->lmp, "f"),
         **t = lammps_extract_atom(b->lmp, "torque");
  double *rad = lammps_extract_atom(b->lmp, "radius"), *rm = lammps_extract_atom(b->lmp, "rmass");
  SA_REQUIRE(tag && type && x && v && w && f && t && rad && rm, SA_ERR_LIBRARY,
             "LIGGGHTS lacks a per-grain array of atom style granular");
  for (int i = 0; i < n; i++) {
    CkGrain *g = &ck->grain[i];
    g->tag = tag[i], g->type = type[i];
    memcpy(g->x, x[i], sizeof g->x), memcpy(g->v, v[i], sizeof g->v);
    memcpy(g->omega, w[i], sizeof g->omega), memcpy(g->f, f[i], sizeof g->f);
    memcpy(g->torque, t[i], sizeof g->torque);
    g->radius = rad[i], g->rmass = rm[i];
  }
  qsort(ck->grain, (size_t)n, sizeof *ck->grain, cmp_grain);
  for (int i = 1; i < n; i++)
    SA_REQUIRE(ck->grain[i].tag != ck->grain[i - 1].tag, SA_ERR_LIBRARY,
               "two grains share the tag %lld", (long long)ck->grain[i].tag);
  return 0;
}

static void ck_serialise(const Checkpoint *ck, const unsigned char *restart, uint64_t nrestart,
                         Buf *w) {
  put(w, CK_MAGIC, 8);
  uint32_t u = CK_VERSION;
  put(w, &u, 4);
  u = CK_BOM;
  put(w, &u, 4);
  put_i64(w, ck->step);
  put_i64(w, ck->count);
  put(w, &ck->rng, 8);
  for (size_t k = 0; k < sizeof ck_fields / sizeof *ck_fields; k++)
    put(w, (const char *)&ck->p + ck_fields[k].off, sizeof(double));
  put_i64(w, ck->p.seed);
  put_i32(w, ck->nmesh);
  for (int i = 0; i < ck->nmesh; i++) {
    const CkMesh *m = &ck->mesh[i];
    char name[32] = {0};
    memcpy(name, m->name, strlen(m->name));
    put(w, name, 32);
    put_i32(w, m->type), put_i32(w, m->nverts), put_i32(w, m->ntri);
    for (int k = 0; k < 3 * m->ntri; k++) put_i32(w, m->tri[k]);
    put(w, m->xyz, 3 * (size_t)m->nverts * sizeof(double));
    put(w, m->v, 3 * (size_t)m->nverts * sizeof(double));
  }
  for (int64_t i = 0; i < ck->count; i++) {
    const CkGrain *g = &ck->grain[i];
    put_i64(w, g->tag), put_i64(w, g->type);
    put(w, g->x, sizeof g->x), put(w, g->v, sizeof g->v), put(w, g->omega, sizeof g->omega);
    put(w, g->f, sizeof g->f), put(w, g->torque, sizeof g->torque);
    put(w, &g->radius, 8), put(w, &g->rmass, 8);
  }
  put_i64(w, (int64_t)nrestart);
  put(w, restart, nrestart);
  if (w->err) return;
  uint64_t h = fnv1a(w->d, w->n);
  put(w, &h, 8);
}

/* Parses and checks a whole checkpoint file d[0..n) read from path; *out [owned] borrows the
 * restart bytes from d. */
static int ck_parse(const unsigned char *d, size_t n, const char *path, Checkpoint **out) {
  *out = NULL;
  Rd r = {d, n, 0, path};
  char magic[8] = {0};
  uint32_t version = 0, bom = 0;
  SA_CHECK(get(&r, magic, 8, "the file type"));
  SA_REQUIRE(!memcmp(magic, CK_MAGIC, 8), SA_ERR_INPUT,
             "'%s' is not a softact DEM checkpoint (it does not start with " CK_MAGIC ")", path);
  SA_CHECK(get(&r, &version, 4, "the version"));
  SA_REQUIRE(version == CK_VERSION || version == 1, SA_ERR_INPUT,
             "checkpoint '%s' has format version %u, this build reads versions 1 and %u", path,
             version, CK_VERSION);
  SA_CHECK(get(&r, &bom, 4, "the byte-order mark"));
  SA_REQUIRE(bom == CK_BOM, SA_ERR_INPUT,
             "checkpoint '%s' was written on a machine of another byte order", path);
  /* the hash first: a truncated or damaged file is named as such before any field is used */
  SA_REQUIRE(n >= 16 + 8, SA_ERR_INPUT, "checkpoint '%s' is truncated: %zu bytes", path, n);
  uint64_t h;
  memcpy(&h, d + n - 8, 8);
  Checkpoint *ck = calloc(1, sizeof *ck);
  SA_REQUIRE(ck, SA_ERR_MEMORY, "cannot allocate a checkpoint");
  snprintf(ck->path, sizeof ck->path, "%s", path);
  int rc = 0;
#define CK_TRY(call)          \
  do {                        \
    if ((rc = (call)) != 0) { \
      ck_free(&ck);           \
      SA_CHECK(rc);           \
    }                         \
  } while (0)
#define CK_REQ(cond, ...)                                    \
  do {                                                       \
    if (!(cond)) {                                           \
      int e_ = SA_ERROR(SA_ERR_INPUT, __VA_ARGS__);          \
      ck_free(&ck);                                          \
      return e_;                                             \
    }                                                        \
  } while (0)
  r.n = n - 8; /* the fields end where the hash begins */
  CK_TRY(get(&r, &ck->step, 8, "the time step counter"));
  CK_TRY(get(&r, &ck->count, 8, "the grain count"));
  CK_TRY(get(&r, &ck->rng, 8, "the generator state"));
  /* version 1 ends before the silicone wall's two fields (a rigid-contact run: 0, 0) */
  size_t nfields = sizeof ck_fields / sizeof *ck_fields - (version == 1 ? 2 : 0);
  for (size_t k = 0; k < nfields; k++)
    CK_TRY(get(&r, (char *)&ck->p + ck_fields[k].off, 8, "the parameters"));
  int64_t seed = 0;
  CK_TRY(get(&r, &seed, 8, "the parameters"));
  ck->p.seed = (int)seed;
  int32_t nmesh = 0;
  CK_TRY(get(&r, &nmesh, 4, "the mesh count"));
  CK_REQ(nmesh >= 0 && (size_t)nmesh <= (r.n - r.off) / 44,
         "checkpoint '%s' is damaged: %d wall meshes", path, nmesh);
  ck->mesh = calloc(nmesh ? (size_t)nmesh : 1, sizeof *ck->mesh);
  CK_REQ(ck->mesh, "cannot allocate %d meshes", nmesh);
  for (int i = 0; i < nmesh; i++) {
    CkMesh *m = &ck->mesh[i];
    ck->nmesh = i + 1;
    int32_t t[3];
    CK_TRY(get(&r, m->name, 32, "a mesh name"));
    m->name[DEM_NAME_MAX] = 0;
    CK_TRY(get(&r, t, 12, "a mesh size"));
    m->type = t[0], m->nverts = t[1], m->ntri = t[2];
    size_t left = r.n - r.off;
    CK_REQ(m->nverts >= 3 && m->ntri >= 1 && (size_t)m->ntri <= left / 12 &&
               (size_t)m->nverts <= left / 48,
           "checkpoint '%s' is damaged or truncated: mesh %d has %d vertices and %d triangles",
           path, i, m->nverts, m->ntri);
    m->tri = malloc(3 * (size_t)m->ntri * sizeof *m->tri);
    m->xyz = malloc(3 * (size_t)m->nverts * sizeof *m->xyz);
    m->v = malloc(3 * (size_t)m->nverts * sizeof *m->v);
    CK_REQ(m->tri && m->xyz && m->v, "cannot allocate mesh %d of checkpoint '%s'", i, path);
    for (int k = 0; k < 3 * m->ntri; k++) {
      int32_t q = 0;
      CK_TRY(get(&r, &q, 4, "a mesh triangle"));
      m->tri[k] = q;
    }
    CK_TRY(get(&r, m->xyz, 3 * (size_t)m->nverts * 8, "mesh nodes"));
    CK_TRY(get(&r, m->v, 3 * (size_t)m->nverts * 8, "mesh node velocities"));
  }
  const size_t grain_bytes = 16 + 17 * 8;
  CK_REQ(ck->count >= 0 && ck->count <= INT32_MAX &&
             (uint64_t)ck->count <= (r.n - r.off) / grain_bytes,
         "checkpoint '%s' is damaged or truncated: %lld grains do not fit in its %zu bytes", path,
         (long long)ck->count, n);
  ck->grain = calloc(ck->count ? (size_t)ck->count : 1, sizeof *ck->grain);
  CK_REQ(ck->grain, "cannot allocate %lld grains", (long long)ck->count);
  for (int64_t i = 0; i < ck->count; i++) {
    CkGrain *g = &ck->grain[i];
    CK_TRY(get(&r, &g->tag, 8, "a grain"));
    CK_TRY(get(&r, &g->type, 8, "a grain"));
    CK_TRY(get(&r, g->x, 3 * 8, "a grain"));
    CK_TRY(get(&r, g->v, 3 * 8, "a grain"));
    CK_TRY(get(&r, g->omega, 3 * 8, "a grain"));
    CK_TRY(get(&r, g->f, 3 * 8, "a grain"));
    CK_TRY(get(&r, g->torque, 3 * 8, "a grain"));
    CK_TRY(get(&r, &g->radius, 8, "a grain"));
    CK_TRY(get(&r, &g->rmass, 8, "a grain"));
    CK_REQ(i == 0 || g->tag > ck->grain[i - 1].tag,
           "checkpoint '%s' is damaged: grain tags are not increasing", path);
  }
  CK_TRY(get(&r, &ck->restart_bytes, 8, "the LIGGGHTS restart size"));
  CK_REQ(ck->restart_bytes == r.n - r.off,
         "checkpoint '%s' is damaged or truncated: the LIGGGHTS restart should have %llu bytes, "
         "%zu are left",
         path, (unsigned long long)ck->restart_bytes, r.n - r.off);
  ck->restart = d + r.off;
  CK_REQ(fnv1a(d, n - 8) == h,
         "checkpoint '%s' is damaged: its hash does not match its contents", path);
#undef CK_TRY
#undef CK_REQ
  *out = ck;
  return 0;
}

/* Reads path whole into *buf [owned] of *n bytes. */
static int read_whole(const char *path, unsigned char **buf, size_t *n) {
  *buf = NULL, *n = 0;
  FILE *f = fopen(path, "rb");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open the checkpoint '%s': %s", path, strerror(errno));
  long size = -1;
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  if (size < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    return SA_ERROR(SA_ERR_IO, "cannot read the checkpoint '%s'", path);
  }
  unsigned char *d = malloc(size ? (size_t)size : 1);
  if (!d) {
    fclose(f);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %ld bytes for the checkpoint '%s'", size, path);
  }
  size_t got = fread(d, 1, (size_t)size, f);
  fclose(f);
  if (got != (size_t)size) {
    free(d);
    return SA_ERROR(SA_ERR_IO, "cannot read the checkpoint '%s' (%zu of %ld bytes)", path, got,
                    size);
  }
  *buf = d, *n = (size_t)size;
  return 0;
}

/* The temporary file beside path that becomes path (opened before LIGGGHTS is asked for
 * anything, so that an unwritable place changes nothing). */
static int tmp_open(const char *path, char *tmp, size_t len, FILE **f) {
  snprintf(tmp, len, "%s.tmp.%ld", path, (long)getpid());
  *f = fopen(tmp, "wb");
  SA_REQUIRE(*f, SA_ERR_IO, "cannot write the checkpoint '%s' (temporary file '%s': %s)", path, tmp,
             strerror(errno));
  return 0;
}

/* Writes n bytes d to the open temporary file f, flushes it to disk, renames it to path. */
static int tmp_commit(FILE *f, const char *tmp, const char *path, const unsigned char *d,
                      size_t n) {
  int ok = fwrite(d, 1, n, f) == n;
  ok = fflush(f) == 0 && ok;
  ok = fsync(fileno(f)) == 0 && ok;
  ok = fclose(f) == 0 && ok;
  if (!ok || rename(tmp, path) != 0) {
    int e = errno;
    remove(tmp);
    return SA_ERROR(SA_ERR_IO, "cannot write the checkpoint '%s': %s", path, strerror(e));
  }
  /* the rename itself reaches the disk with the directory */
  char dir[CK_PATH_MAX + 1];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash == dir) slash[1] = 0;
  else if (slash) *slash = 0;
  else snprintf(dir, sizeof dir, ".");
  int fd = open(dir, O_RDONLY);
  if (fd >= 0) fsync(fd), close(fd);
  return 0;
}

static int write_checkpoint_here(DemBridge *b, const char *path) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(b->is_setup, SA_ERR_INPUT, "dem_bridge_write_checkpoint before dem_bridge_setup");
  SA_REQUIRE(path && *path && strlen(path) < CK_PATH_MAX, SA_ERR_INPUT,
             "checkpoint path must be non-empty and shorter than %d characters", CK_PATH_MAX);
  /* LIGGGHTS aborts in write_restart when it has no grain */
  SA_REQUIRE(dem_par_sum_ll(nlocal(b)) > 0, SA_ERR_INPUT,
             "checkpoint '%s': there are no grains to checkpoint", path);
  /* files are the lead's (rank 0 writes LIGGGHTS' restart); the other ranks take part in the
   * collectives only, and learn whether the lead could open them */
  int lead = b->rank == 0, rc = 0;
  char tmp[CK_PATH_MAX + 64];
  FILE *out = NULL;
  char rpath[320];
  snprintf(rpath, sizeof rpath, "%s/checkpoint.restart", b->tmpdir);
  if (lead) {
    rc = tmp_open(path, tmp, sizeof tmp, &out);
    FILE *f = rc ? NULL : fopen(rpath, "wb"); /* LIGGGHTS aborts if it cannot open it: try first */
    if (!rc && !f) rc = SA_ERROR(SA_ERR_IO, "cannot open the temporary restart file '%s'", rpath);
    if (f) fclose(f);
  }
  if (b->np > 1) rc = dem_par_agree(rc);
  if (rc) {
    if (out) fclose(out), remove(tmp);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  rc = finalize_walls_here(b);
  if (!rc) rc = send(b, "write_restart %s", rpath);
  unsigned char *restart = NULL;
  size_t nrestart = 0;
  if (!rc && lead) rc = read_whole(rpath, &restart, &nrestart);
  if (lead) remove(rpath);
  Checkpoint *ck = NULL;
  Buf w = {0};
  if (!rc) rc = ck_capture(b, &ck);
  if (!rc && lead) {
    ck_serialise(ck, restart, nrestart, &w);
    if (w.err) rc = SA_ERROR(SA_ERR_MEMORY, "cannot allocate the checkpoint '%s'", path);
  }
  free(restart);
  if (lead) {
    if (!rc) rc = tmp_commit(out, tmp, path, w.d, w.n);
    else fclose(out), remove(tmp);
  }
  free(w.d);
  if (b->np > 1) rc = dem_par_agree(rc);
  if (rc) {
    ck_free(&ck);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  /* continue the way a resumed bridge does */
  snprintf(ck->path, sizeof ck->path, "%s", path);
  ck_free(&b->ck);
  b->ck = ck;
  SA_CHECK(ck_setup_pass(b, 1));
  return 0;
}

static int ck_load(const char *path, unsigned char **buf, Checkpoint **ck) {
  *buf = NULL, *ck = NULL;
  SA_REQUIRE(path && *path && strlen(path) < CK_PATH_MAX, SA_ERR_INPUT,
             "checkpoint path must be non-empty and shorter than %d characters", CK_PATH_MAX);
  size_t n;
  SA_CHECK(read_whole(path, buf, &n));
  int rc = ck_parse(*buf, n, path, ck);
  if (rc) {
    free(*buf);
    *buf = NULL;
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  return 0;
}

int dem_bridge_checkpoint_info(const char *path, DemCheckpointInfo *info) {
  SA_REQUIRE(info, SA_ERR_INTERNAL, "dem_bridge_checkpoint_info: no output");
  memset(info, 0, sizeof *info);
  unsigned char *buf;
  Checkpoint *ck;
  SA_CHECK(ck_load(path, &buf, &ck));
  info->step = ck->step;
  info->count = (int)ck->count;
  info->nmesh = ck->nmesh;
  info->diameter = ck->p.diameter;
  info->dt = ck->p.dt;
  ck_free(&ck);
  free(buf);
  return 0;
}

/* The checkpoint's params against the caller's, field by field (bitwise: a resumed run must
 * be the same run). */
static int ck_params_match(const Checkpoint *ck, const DemParams *p) {
  for (size_t k = 0; k < sizeof ck_fields / sizeof *ck_fields; k++) {
    /* the time step does not enter the bed's state (positions, velocities, contact
     * histories), so a variant may change it; every other field shapes the state */
    if (p->resume_new_dt && (ck_fields[k].off == offsetof(DemParams, dt) ||
                             ck_fields[k].off == offsetof(DemParams, dt_safety)))
      continue;
    double a = *(const double *)((const char *)&ck->p + ck_fields[k].off);
    double c = *(const double *)((const char *)p + ck_fields[k].off);
    SA_REQUIRE(memcmp(&a, &c, sizeof a) == 0, SA_ERR_INPUT,
               "checkpoint '%s' was written with %s = %.17g, the run has %s = %.17g", ck->path,
               ck_fields[k].name, a, ck_fields[k].name, c);
  }
  SA_REQUIRE(ck->p.seed == p->seed, SA_ERR_INPUT,
             "checkpoint '%s' was written with seed = %d, the run has seed = %d", ck->path,
             ck->p.seed, p->seed);
  return 0;
}

/* After read_restart: LIGGGHTS holds exactly the grains of the framing, bit for bit. */
static int ck_verify_grains(DemBridge *b, const Checkpoint *ck) {
  int64_t *step = lammps_extract_global(b->lmp, "ntimestep");
  SA_REQUIRE(step && *step == ck->step, SA_ERR_LIBRARY,
             "LIGGGHTS restored time step %lld from checkpoint '%s', which was written at %lld",
             step ? (long long)*step : -1LL, ck->path, (long long)ck->step);
  int n = nlocal(b);
  long long n_all = dem_par_sum_ll(n);
  SA_REQUIRE(n_all == ck->count, SA_ERR_LIBRARY,
             "LIGGGHTS restored %lld grains from checkpoint '%s', which holds %lld", n_all,
             ck->path, (long long)ck->count);
  if (n == 0) return 0;
  int *tag = lammps_extract_atom(b->lmp, "id"), *type = lammps_extract_atom(b->lmp, "type");
  double **x = lammps_extract_atom(b->lmp, "x"), **v = lammps_extract_atom(b->lmp, "v"),
         **w = lammps_extract_atom(b->lmp, "omega");
  double *rad = lammps_extract_atom(b->lmp, "radius"), *rm = lammps_extract_atom(b->lmp, "rmass");
  SA_REQUIRE(tag && type && x && v && w && rad && rm, SA_ERR_LIBRARY,
             "LIGGGHTS lacks a per-grain array of atom style granular");
  for (int i = 0; i < n; i++) {
    const CkGrain *g = ck_find(ck, tag[i]);
    SA_REQUIRE(g, SA_ERR_LIBRARY, "LIGGGHTS restored grain %d, which checkpoint '%s' does not hold",
               tag[i], ck->path);
    int same = g->type == type[i] && !memcmp(g->x, x[i], sizeof g->x) &&
               !memcmp(g->v, v[i], sizeof g->v) && !memcmp(g->omega, w[i], sizeof g->omega) &&
               !memcmp(&g->radius, &rad[i], 8) && !memcmp(&g->rmass, &rm[i], 8);
    SA_REQUIRE(same, SA_ERR_LIBRARY,
               "LIGGGHTS restored grain %d of checkpoint '%s' with another type, position, "
               "velocity, spin, radius or mass than was saved",
               tag[i], ck->path);
  }
  return 0;
}

static int setup_from_checkpoint_here(DemBridge *b, const DemParams *params, const char *path,
                                     int expected_count) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(!b->is_setup, SA_ERR_INPUT,
             "dem_bridge_setup_from_checkpoint on a bridge already set up");
  SA_CHECK(params_check(params));
  unsigned char *buf;
  Checkpoint *ck;
  SA_CHECK(ck_load(path, &buf, &ck));
  int rc = ck_params_match(ck, params);
  if (!rc && expected_count >= 0 && ck->count != expected_count)
    rc = SA_ERROR(SA_ERR_INPUT, "checkpoint '%s' holds %lld grains, the run expects %d", path,
                  (long long)ck->count, expected_count);
  /* LIGGGHTS reads its part from a file of its own */
  char rpath[320];
  snprintf(rpath, sizeof rpath, "%s/resume.restart", b->tmpdir);
  if (!rc && b->rank == 0) {
    FILE *f = fopen(rpath, "wb");
    int ok = f && fwrite(ck->restart, 1, ck->restart_bytes, f) == ck->restart_bytes;
    if (f) ok = (fclose(f) == 0) && ok;
    if (!ok) {
      remove(rpath);
      rc = SA_ERROR(SA_ERR_IO, "cannot write the temporary restart file '%s'", rpath);
    }
  }
  if (b->np > 1) rc = dem_par_agree(rc);
  if (rc) {
    ck_free(&ck);
    free(buf);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  /* from here on LIGGGHTS holds state: a failure leaves a bridge only fit for destroy */
  ck->restart = NULL;
  free(buf);
  b->rolling = params->rolling_friction > 0;
  rc = setup_pre_box(b);
  if (!rc) {
    /* read_restart prints LIGGGHTS' version on stdout: to /dev/null while it reads */
    fflush(stdout);
    int saved = dup(1), devnull = open("/dev/null", O_WRONLY);
    if (saved >= 0 && devnull >= 0) dup2(devnull, 1);
    rc = send(b, "read_restart %s", rpath);
    fflush(stdout);
    if (saved >= 0 && devnull >= 0) dup2(saved, 1);
    if (saved >= 0) close(saved);
    if (devnull >= 0) close(devnull);
  }
  remove(rpath);
  if (!rc) rc = ck_verify_grains(b, ck);
  if (b->np > 1) rc = dem_par_agree(rc);
  if (!rc) rc = setup_post_box(b, params);
  if (rc) {
    ck_free(&ck);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  b->p = *params;
  b->rng = ck->rng;
  b->ck = ck;
  b->is_setup = 1;
  b->need_setup = 1;
  b->resumed = 1;
  /* no mesh to wait for: the set-up pass now */
  if (ck->nmesh == 0) {
    SA_CHECK(finalize_walls_here(b));
    SA_CHECK(ck_setup_pass(b, 1));
  }
  return 0;
}

static int ck_mesh_check(const DemBridge *b, const char *name, int nverts, const double *xyz,
                         int ntri, const int *tri, DemWallType type) {
  const Checkpoint *ck = b->ck;
  int i = b->nmesh;
  SA_REQUIRE(i < ck->nmesh, SA_ERR_INPUT,
             "checkpoint '%s' has %d wall meshes: mesh '%s' would be one more", ck->path,
             ck->nmesh, name);
  const CkMesh *m = &ck->mesh[i];
  SA_REQUIRE(!strcmp(m->name, name), SA_ERR_INPUT,
             "wall mesh %d of checkpoint '%s' is '%s', not '%s' (add the meshes in the same order)",
             i, ck->path, m->name, name);
  SA_REQUIRE(m->type == (int)type && m->nverts == nverts && m->ntri == ntri, SA_ERR_INPUT,
             "mesh '%s' of checkpoint '%s' has type %d, %d vertices, %d triangles; added: type %d, "
             "%d vertices, %d triangles",
             name, ck->path, m->type, m->nverts, m->ntri, (int)type, nverts, ntri);
  SA_REQUIRE(!memcmp(m->tri, tri, 3 * (size_t)ntri * sizeof *tri), SA_ERR_INPUT,
             "mesh '%s' of checkpoint '%s' has other triangles than the one added", name,
             ck->path);
  for (int v = 0; v < nverts; v++)
    SA_REQUIRE(!memcmp(m->xyz + 3 * v, xyz + 3 * v, 3 * sizeof *xyz), SA_ERR_INPUT,
               "mesh '%s': vertex %d is added at (%.17g, %.17g, %.17g), checkpoint '%s' has it at "
               "(%.17g, %.17g, %.17g) (add a mesh where it was, move it afterwards)",
               name, v, xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], ck->path, m->xyz[3 * v],
               m->xyz[3 * v + 1], m->xyz[3 * v + 2]);
  return 0;
}

/* The state at a checkpoint, written or read, made the same: a set-up pass (run 0: neighbour
 * lists built, grains sorted, contact histories laid out, forces recomputed from the full-step
 * velocities; a resumed LIGGGHTS cannot do without it) with the walls where they were at the
 * checkpoint, then the forces and torques of the checkpoint's last step put back, so that the
 * next step integrates with what an uninterrupted run uses. run0 = 0: the caller has just done
 * the set-up pass (dem_bridge_finalize_walls). */
static int ck_setup_pass(DemBridge *b, int run0) {
  const Checkpoint *ck = b->ck;
  SA_REQUIRE(ck, SA_ERR_INTERNAL, "no checkpoint to restore forces from");
  if (run0) SA_CHECK(send(b, "run 0 post no"));
  b->ran = 1;
  b->need_setup = 0;
  int n = nlocal(b); /* at most ck->count: a grain may have left the box in the set-up pass */
  if (n == 0) return 0;
  int *tag = lammps_extract_atom(b->lmp, "id");
  double **f = lammps_extract_atom(b->lmp, "f"), **t = lammps_extract_atom(b->lmp, "torque");
  SA_REQUIRE(tag && f && t, SA_ERR_LIBRARY, "LIGGGHTS has no force or torque array");
  for (int i = 0; i < n; i++) {
    const CkGrain *g = ck_find(ck, tag[i]);
    SA_REQUIRE(g, SA_ERR_INTERNAL, "grain %d is not in the checkpoint", tag[i]);
    memcpy(f[i], g->f, sizeof g->f);
    memcpy(t[i], g->torque, sizeof g->torque);
  }
  return 0;
}

/* ---------------------------------------------------------------- several MPI ranks
 *
 * dem_parallel.h describes the scheme. The functions above are each rank's part of a call
 * (their names end in _here); the public functions below are what the scene calls: on the lead
 * of a several-rank bridge they first broadcast the call, and a follower, in dem_bridge_follow,
 * makes the same public call. A call ends with dem_par_agree where a rank could fail alone
 * before the others went on into a LIGGGHTS collective (set-up, meshes, checkpoints); the
 * calls made every DEM step (run, wall nodes, forces) fail only on their arguments, which
 * every rank checks alike. Grains come back in tag order on several ranks (LIGGGHTS' own order
 * on one). */

enum {
  OP_CREATE = 1, OP_DESTROY, OP_LOG_APPEND, OP_COMMAND, OP_SETUP, OP_SETUP_CK, OP_PROCESSORS,
  OP_ADD_MESH, OP_FINALIZE, OP_SET_NODES, OP_FORCES, OP_NODES, OP_COUNT, OP_INSERT, OP_RUN,
  OP_SET_YOUNG, OP_SCALE_FRICTION, OP_SET_SKIN, OP_PARTICLES, OP_CONTACTS, OP_IDS, OP_KE,
  OP_OVERLAP, OP_WRITE_RESTART, OP_WRITE_CK, OP_FORCES_ADD, OP_FORCES_TAKE, OP_SET_PATH,
  OP_PLACE_PATH, OP_PLACE_FLAT
};

/* A bridge whose calls the lead broadcasts (rank 0 of several). */
static int leads(const DemBridge *b) { return b && b->np > 1 && b->rank == 0; }
static int parallel(const DemBridge *b) { return b && b->np > 1; }

/* Bytes of string s with its terminator (0 for NULL: the follower then receives NULL too, and
 * fails on it as the lead does; a call is always broadcast, so that both agree). */
static size_t slen(const char *s) { return s ? strlen(s) + 1 : 0; }

/* Broadcast call op with integers i[0..ni), reals d[0..nd) and buffers p[k] of n[k] bytes. */
static void lead_call(int op, int ni, const int *i, int nd, const double *d, const void *p0,
                      size_t n0, const void *p1, size_t n1, const void *p2, size_t n2) {
  DemParCall c;
  memset(&c, 0, sizeof c);
  c.op = op;
  for (int k = 0; k < ni && k < 6; k++) c.i[k] = i[k];
  for (int k = 0; k < nd && k < 8; k++) c.d[k] = d[k];
  const void *buf[DEM_PAR_NBUF] = {p0, p1, p2, NULL};
  size_t n[DEM_PAR_NBUF] = {p0 ? n0 : 0, p1 ? n1 : 0, p2 ? n2 : 0, 0};
  for (int k = 0; k < DEM_PAR_NBUF; k++) c.bytes[k] = (int64_t)n[k];
  dem_par_call(&c, buf);
}

/* Every rank's grains, on every rank, in tag order: *all [owned by the caller], *n. */
static int gather_grains(DemBridge *b, CkGrain **all, int *n) {
  *all = NULL, *n = 0;
  int nl = nlocal(b);
  CkGrain *loc = calloc((size_t)(nl > 0 ? nl : 1), sizeof *loc);
  SA_REQUIRE(loc, SA_ERR_MEMORY, "cannot allocate %d grains", nl);
  int *tag = lammps_extract_atom(b->lmp, "id"), *type = lammps_extract_atom(b->lmp, "type");
  double **x = lammps_extract_atom(b->lmp, "x"), **v = lammps_extract_atom(b->lmp, "v"),
         **w = lammps_extract_atom(b->lmp, "omega"), **f = lammps_extract_atom(b->lmp, "f"),
         **t = lammps_extract_atom(b->lmp, "torque");
  double *rad = lammps_extract_atom(b->lmp, "radius"), *rm = lammps_extract_atom(b->lmp, "rmass");
  int ok = nl == 0 || (tag && type && x && v && w && f && t && rad && rm);
  for (int i = 0; ok && i < nl; i++) {
    CkGrain *g = &loc[i];
    g->tag = tag[i], g->type = type[i];
    memcpy(g->x, x[i], sizeof g->x), memcpy(g->v, v[i], sizeof g->v);
    memcpy(g->omega, w[i], sizeof g->omega), memcpy(g->f, f[i], sizeof g->f);
    memcpy(g->torque, t[i], sizeof g->torque);
    g->radius = rad[i], g->rmass = rm[i];
  }
  void *out = NULL;
  int rc = dem_par_allgather(loc, ok ? nl : 0, sizeof *loc, &out, n);
  free(loc);
  if (rc) return rc;
  SA_REQUIRE(ok, SA_ERR_LIBRARY, "LIGGGHTS lacks a per-grain array of atom style granular");
  *all = out;
  qsort(*all, (size_t)*n, sizeof **all, cmp_grain);
  return 0;
}

int dem_bridge_create(const char *log_path, DemBridge **out) {
  if (dem_par_leading()) {
    if (log_path) { /* the lead's own check first: the followers must not start alone */
      FILE *f = fopen(log_path, "w");
      SA_REQUIRE(f, SA_ERR_IO, "cannot open the LIGGGHTS log file '%s'", log_path);
      fclose(f);
    }
    lead_call(OP_CREATE, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  }
  int rc = create_here(log_path, out);
  return dem_par_leading() || dem_par_following() ? dem_par_agree(rc) : rc;
}

void dem_bridge_destroy(DemBridge **pb) {
  if (pb && leads(*pb)) lead_call(OP_DESTROY, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  destroy_here(pb);
}

int dem_bridge_log_append(DemBridge *b, const char *path) {
  if (leads(b)) lead_call(OP_LOG_APPEND, 0, NULL, 0, NULL, path, slen(path), NULL, 0, NULL, 0);
  int rc = log_append_here(b, path);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_command(DemBridge *b, const char *cmd) {
  if (leads(b)) lead_call(OP_COMMAND, 0, NULL, 0, NULL, cmd, slen(cmd), NULL, 0, NULL, 0);
  return command_here(b, cmd);
}

int dem_bridge_set_processors(DemBridge *b, int px, int py, int pz) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  SA_REQUIRE(!b->is_setup, SA_ERR_INPUT, "dem_bridge_set_processors after the set-up");
  SA_REQUIRE(px > 0 && py > 0 && pz > 0, SA_ERR_INPUT,
             "processor grid %d x %d x %d: every count must be >= 1", px, py, pz);
  SA_REQUIRE(b->np == 1 || (long)px * py * pz == b->np, SA_ERR_INPUT,
             "processor grid %d x %d x %d does not hold the %d MPI ranks", px, py, pz, b->np);
  if (leads(b)) {
    int i[3] = {px, py, pz};
    lead_call(OP_PROCESSORS, 3, i, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  }
  b->procs[0] = px, b->procs[1] = py, b->procs[2] = pz;
  return 0;
}

int dem_bridge_setup(DemBridge *b, const DemParams *params) {
  if (leads(b)) lead_call(OP_SETUP, 0, NULL, 0, NULL, params, sizeof *params, NULL, 0, NULL, 0);
  int rc = setup_here(b, params);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_setup_from_checkpoint(DemBridge *b, const DemParams *params, const char *path,
                                     int expected_count) {
  if (leads(b))
    lead_call(OP_SETUP_CK, 1, &expected_count, 0, NULL, params, sizeof *params, path, slen(path),
              NULL, 0);
  int rc = setup_from_checkpoint_here(b, params, path, expected_count);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_add_mesh(DemBridge *b, const char *name, int nverts, const double *xyz, int ntri,
                        const int *tri, DemWallType type, int *id) {
  if (leads(b) && name && xyz && tri && nverts > 0 && ntri > 0) {
    int i[3] = {nverts, ntri, (int)type};
    lead_call(OP_ADD_MESH, 3, i, 0, NULL, name, strlen(name) + 1, xyz,
              3 * (size_t)nverts * sizeof *xyz, tri, 3 * (size_t)ntri * sizeof *tri);
  } else if (leads(b)) /* the followers fail alike on what is missing */
    lead_call(OP_ADD_MESH, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  int rc = add_mesh_here(b, name, nverts, xyz, ntri, tri, type, id);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_finalize_walls(DemBridge *b) {
  if (leads(b)) lead_call(OP_FINALIZE, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  int rc = finalize_walls_here(b);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_set_mesh_nodes(DemBridge *b, int id, const double *xyz, const double *v) {
  if (leads(b)) {
    size_t n = id >= 0 && id < b->nmesh ? 3 * (size_t)b->mesh[id].nverts * sizeof(double) : 0;
    lead_call(OP_SET_NODES, 1, &id, 0, NULL, xyz, n, v, n, NULL, 0);
  }
  return set_mesh_nodes_here(b, id, xyz, v);
}

int dem_bridge_set_mesh_path(DemBridge *b, int id, const double *x0, const double *x1,
                             const double *v) {
  if (leads(b)) {
    size_t n = id >= 0 && id < b->nmesh ? 3 * (size_t)b->mesh[id].nverts * sizeof(double) : 0;
    lead_call(OP_SET_PATH, 1, &id, 0, NULL, x0, n, x1, n, v, n);
  }
  return set_mesh_path_here(b, id, x0, x1, v);
}

int dem_bridge_place_on_path(DemBridge *b, int id, double a) {
  if (leads(b)) lead_call(OP_PLACE_PATH, 1, &id, 1, &a, NULL, 0, NULL, 0, NULL, 0);
  return place_on_path_here(b, id, a);
}

int dem_bridge_place_flat_mesh(DemBridge *b, int id, double z, double vz) {
  if (leads(b)) {
    double d[2] = {z, vz};
    lead_call(OP_PLACE_FLAT, 1, &id, 2, d, NULL, 0, NULL, 0, NULL, 0);
  }
  return place_flat_mesh_here(b, id, z, vz);
}

int dem_bridge_mesh_forces(DemBridge *b, int id, double *f) {
  if (!parallel(b)) return mesh_forces_here(b, id, f);
  if (leads(b)) lead_call(OP_FORCES, 1, &id, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  if (b->rank > 0) { /* a follower's share goes into its scratch */
    SA_CHECK(grow_double(&b->scratch, &b->scratch_cap, 3 * (size_t)m->ntri));
    f = b->scratch;
  }
  SA_REQUIRE(f, SA_ERR_INPUT, "mesh '%s': no output array", m->fix_id + 5);
  /* each triangle's force is on the rank that owns it (LIGGGHTS adds what its ghost copies
   * took to the owner): zero elsewhere, summed over the ranks */
  memset(f, 0, 3 * (size_t)m->ntri * sizeof *f);
  int bad = b->ran && dem_shim_mesh_forces(m->shim, f) != 0;
  dem_par_sum_to_lead(f, 3 * (size_t)m->ntri);
  SA_REQUIRE(!bad, SA_ERR_LIBRARY, "mesh '%s' has no force (stress) data", m->fix_id + 5);
  return 0;
}

int dem_bridge_mesh_forces_add(DemBridge *b) {
  if (leads(b)) lead_call(OP_FORCES_ADD, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  for (int i = 0; i < b->nmesh; i++) {
    DemMesh *m = &b->mesh[i];
    size_t n = 3 * (size_t)m->ntri;
    if (!m->acc) SA_CALLOC(m->acc, n);
    if (!b->ran) continue;
    /* this rank's triangles (all on one rank), term by term as dem_bridge_mesh_forces + sum */
    SA_REQUIRE(dem_shim_mesh_forces_add(m->shim, m->acc) == 0, SA_ERR_LIBRARY,
               "mesh '%s' has no force (stress) data", m->fix_id + 5);
  }
  return 0;
}

int dem_bridge_mesh_forces_take(DemBridge *b, int id, double *sum) {
  if (leads(b)) lead_call(OP_FORCES_TAKE, 1, &id, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  size_t n = 3 * (size_t)m->ntri;
  if (!m->acc) SA_CALLOC(m->acc, n);
  dem_par_sum_to_lead(m->acc, n); /* one rank: nothing to sum */
  if (b->rank == 0) {
    SA_REQUIRE(sum, SA_ERR_INPUT, "mesh '%s': no output array", m->fix_id + 5);
    memcpy(sum, m->acc, n * sizeof *sum);
  }
  memset(m->acc, 0, n * sizeof *m->acc);
  return 0;
}

int dem_bridge_mesh_nodes(DemBridge *b, int id, double *xyz) {
  if (!parallel(b)) return mesh_nodes_here(b, id, xyz);
  if (leads(b)) lead_call(OP_NODES, 1, &id, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  if (b->rank > 0) {
    SA_CHECK(grow_double(&b->scratch, &b->scratch_cap, 3 * (size_t)m->nverts));
    xyz = b->scratch;
  }
  SA_REQUIRE(xyz, SA_ERR_INPUT, "mesh '%s': no output array", m->fix_id + 5);
  /* the copies this rank owns, -inf elsewhere; the maximum over the ranks */
  for (int i = 0; i < 3 * m->nverts; i++) xyz[i] = -INFINITY;
  int n = dem_shim_mesh_size(m->shim), differ = -1;
  for (int i = 0; i < n; i++) {
    int t = dem_shim_mesh_id(m->shim, i);
    for (int c = 0; c < 3; c++) {
      double x[3];
      dem_shim_mesh_node(m->shim, i, c, x);
      double *o = xyz + 3 * m->idx[3 * t + c];
      if (o[0] != -INFINITY && (o[0] != x[0] || o[1] != x[1] || o[2] != x[2]))
        differ = m->idx[3 * t + c];
      memcpy(o, x, sizeof x);
    }
  }
  dem_par_max(xyz, 3 * (size_t)m->nverts);
  for (int i = 0; i < 3 * m->nverts; i++)
    if (xyz[i] == -INFINITY) xyz[i] = NAN;
  SA_REQUIRE(differ < 0, SA_ERR_INTERNAL, "mesh '%s': the copies of vertex %d disagree in LIGGGHTS",
             m->fix_id + 5, differ);
  return 0;
}

int dem_bridge_count(DemBridge *b) {
  if (!parallel(b)) return count_here(b);
  if (leads(b)) lead_call(OP_COUNT, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  return (int)dem_par_sum_ll(nlocal(b));
}

int dem_bridge_insert_cylinder(DemBridge *b, double cx, double cy, double r, double z_lo,
                               double z_hi, int n, int *inserted) {
  if (leads(b)) {
    double d[5] = {cx, cy, r, z_lo, z_hi};
    lead_call(OP_INSERT, 1, &n, 5, d, NULL, 0, NULL, 0, NULL, 0);
  }
  int rc = insert_cylinder_here(b, cx, cy, r, z_lo, z_hi, n, inserted);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_run(DemBridge *b, int nsteps) {
  int first = b && !b->walls_done; /* the walls are finalised: an agreed call */
  if (leads(b)) lead_call(OP_RUN, 1, &nsteps, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  int rc = run_here(b, nsteps);
  return parallel(b) && first ? dem_par_agree(rc) : rc;
}

int dem_bridge_set_young(DemBridge *b, double young, double dt) {
  if (leads(b)) {
    double d[2] = {young, dt};
    lead_call(OP_SET_YOUNG, 0, NULL, 2, d, NULL, 0, NULL, 0, NULL, 0);
  }
  return set_young_here(b, young, dt);
}

int dem_bridge_scale_friction(DemBridge *b, double scale) {
  if (leads(b)) lead_call(OP_SCALE_FRICTION, 0, NULL, 1, &scale, NULL, 0, NULL, 0, NULL, 0);
  return scale_friction_here(b, scale);
}

int dem_bridge_set_skin(DemBridge *b, double skin) {
  if (leads(b)) lead_call(OP_SET_SKIN, 0, NULL, 1, &skin, NULL, 0, NULL, 0, NULL, 0);
  return set_skin_here(b, skin);
}

int dem_bridge_particles(DemBridge *b, double *x, double *v, double *f, double *radius) {
  if (!parallel(b)) return particles_here(b, x, v, f, radius);
  if (leads(b)) lead_call(OP_PARTICLES, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  CkGrain *all;
  int n;
  SA_CHECK(gather_grains(b, &all, &n));
  if (b->rank == 0)
    for (int i = 0; i < n; i++) {
      if (x) memcpy(x + 3 * i, all[i].x, sizeof all[i].x);
      if (v) memcpy(v + 3 * i, all[i].v, sizeof all[i].v);
      if (f) memcpy(f + 3 * i, all[i].f, sizeof all[i].f);
      if (radius) radius[i] = all[i].radius;
    }
  free(all);
  return 0;
}

typedef struct {
  int grain, tri;
  double shear[3];
} Contact;

static int cmp_contact(const void *x, const void *y) {
  const Contact *a = x, *c = y;
  if (a->grain != c->grain) return a->grain < c->grain ? -1 : 1;
  return (a->tri > c->tri) - (a->tri < c->tri);
}

int dem_bridge_wall_contacts(DemBridge *b, int id, int max, int *grain, int *tri, double *shear,
                             int *n) {
  if (!parallel(b)) return wall_contacts_here(b, id, max, grain, tri, shear, n);
  if (leads(b)) lead_call(OP_CONTACTS, 1, &id, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  DemMesh *m = NULL;
  SA_CHECK(mesh_get(b, id, &m));
  /* this rank's contacts (counted, then read), gathered, in (grain, triangle) order */
  int k = b->ran ? dem_shim_mesh_contacts(b->lmp, m->shim, 0, NULL, NULL, NULL) : 0;
  int nk = k > 0 ? k : 0;
  int *g = malloc(sizeof(int) * (size_t)(nk + 1)), *t = malloc(sizeof(int) * (size_t)(nk + 1));
  double *h = malloc(sizeof(double) * 3 * (size_t)(nk + 1));
  Contact *loc = calloc((size_t)nk + 1, sizeof *loc);
  int ok = g && t && h && loc;
  if (ok && nk > 0) dem_shim_mesh_contacts(b->lmp, m->shim, nk, g, t, h);
  for (int i = 0; ok && i < nk; i++) {
    loc[i].grain = g[i], loc[i].tri = t[i];
    memcpy(loc[i].shear, h + 3 * i, sizeof loc[i].shear);
  }
  free(g), free(t), free(h);
  void *all = NULL;
  int na = 0, rc = dem_par_allgather(loc, ok ? nk : 0, sizeof *loc, &all, &na);
  free(loc);
  SA_CHECK(rc);
  Contact *c = all;
  qsort(c, (size_t)na, sizeof *c, cmp_contact);
  if (n) *n = na;
  for (int i = 0; b->rank == 0 && i < na && i < max; i++) {
    grain[i] = c[i].grain, tri[i] = c[i].tri;
    memcpy(shear + 3 * i, c[i].shear, sizeof c[i].shear);
  }
  free(all);
  SA_REQUIRE(ok && k >= 0, SA_ERR_LIBRARY, "mesh '%s' has no contact history", m->fix_id + 5);
  return 0;
}

int dem_bridge_particle_ids(DemBridge *b, int *id) {
  if (!parallel(b)) return particle_ids_here(b, id);
  if (leads(b)) lead_call(OP_IDS, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  CkGrain *all;
  int n;
  SA_CHECK(gather_grains(b, &all, &n));
  for (int i = 0; b->rank == 0 && id && i < n; i++) id[i] = (int)all[i].tag;
  free(all);
  return 0;
}

double dem_bridge_kinetic_energy(DemBridge *b) {
  if (!parallel(b)) return kinetic_energy_here(b);
  if (leads(b)) lead_call(OP_KE, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  double e = kinetic_energy_here(b);
  dem_par_sum_to_lead(&e, 1);
  return e;
}

double dem_bridge_max_overlap(DemBridge *b) {
  if (leads(b)) lead_call(OP_OVERLAP, 0, NULL, 0, NULL, NULL, 0, NULL, 0, NULL, 0);
  return max_overlap_here(b);
}

double dem_bridge_max_indentation(const DemBridge *b) { return b ? b->indent : 0; }

void dem_bridge_indentation_site(const DemBridge *b, double pos[3]) {
  for (int k = 0; k < 3; k++) pos[k] = b ? b->indent_pos[k] : NAN;
}

int dem_bridge_write_restart(DemBridge *b, const char *path) {
  if (leads(b)) lead_call(OP_WRITE_RESTART, 0, NULL, 0, NULL, path, slen(path), NULL, 0, NULL, 0);
  int rc = write_restart_here(b, path);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_write_checkpoint(DemBridge *b, const char *path) {
  if (leads(b)) lead_call(OP_WRITE_CK, 0, NULL, 0, NULL, path, slen(path), NULL, 0, NULL, 0);
  int rc = write_checkpoint_here(b, path);
  return parallel(b) ? dem_par_agree(rc) : rc;
}

int dem_bridge_follow(void) {
  SA_REQUIRE(dem_par_following(), SA_ERR_INTERNAL, "dem_bridge_follow on the lead or on one rank");
  DemBridge *b = NULL;
  for (;;) {
    DemParCall c;
    void *p[DEM_PAR_NBUF];
    SA_CHECK(dem_par_next(&c, p));
    if (c.op < 0) break;
    int rc = 0, k = 0;
    switch (c.op) {
    case OP_CREATE: rc = dem_bridge_create(NULL, &b); break;
    case OP_DESTROY: dem_bridge_destroy(&b); break;
    case OP_LOG_APPEND: rc = dem_bridge_log_append(b, p[0]); break;
    case OP_COMMAND: rc = dem_bridge_command(b, p[0]); break;
    case OP_SETUP: rc = dem_bridge_setup(b, p[0]); break;
    case OP_SETUP_CK: rc = dem_bridge_setup_from_checkpoint(b, p[0], p[1], c.i[0]); break;
    case OP_PROCESSORS: rc = dem_bridge_set_processors(b, c.i[0], c.i[1], c.i[2]); break;
    case OP_ADD_MESH:
      rc = dem_bridge_add_mesh(b, p[0], c.i[0], p[1], c.i[1], p[2], (DemWallType)c.i[2], &k);
      break;
    case OP_FINALIZE: rc = dem_bridge_finalize_walls(b); break;
    case OP_SET_NODES: rc = dem_bridge_set_mesh_nodes(b, c.i[0], p[0], p[1]); break;
    case OP_FORCES: rc = dem_bridge_mesh_forces(b, c.i[0], NULL); break;
    case OP_NODES: rc = dem_bridge_mesh_nodes(b, c.i[0], NULL); break;
    case OP_COUNT: dem_bridge_count(b); break;
    case OP_INSERT:
      rc = dem_bridge_insert_cylinder(b, c.d[0], c.d[1], c.d[2], c.d[3], c.d[4], c.i[0], &k);
      break;
    case OP_RUN: rc = dem_bridge_run(b, c.i[0]); break;
    case OP_SET_YOUNG: rc = dem_bridge_set_young(b, c.d[0], c.d[1]); break;
    case OP_SCALE_FRICTION: rc = dem_bridge_scale_friction(b, c.d[0]); break;
    case OP_SET_SKIN: rc = dem_bridge_set_skin(b, c.d[0]); break;
    case OP_PARTICLES: rc = dem_bridge_particles(b, NULL, NULL, NULL, NULL); break;
    case OP_CONTACTS: rc = dem_bridge_wall_contacts(b, c.i[0], 0, NULL, NULL, NULL, &k); break;
    case OP_IDS: rc = dem_bridge_particle_ids(b, NULL); break;
    case OP_KE: dem_bridge_kinetic_energy(b); break;
    case OP_OVERLAP: dem_bridge_max_overlap(b); break;
    case OP_WRITE_RESTART: rc = dem_bridge_write_restart(b, p[0]); break;
    case OP_WRITE_CK: rc = dem_bridge_write_checkpoint(b, p[0]); break;
    case OP_FORCES_ADD: rc = dem_bridge_mesh_forces_add(b); break;
    case OP_FORCES_TAKE: rc = dem_bridge_mesh_forces_take(b, c.i[0], NULL); break;
    case OP_SET_PATH: rc = dem_bridge_set_mesh_path(b, c.i[0], p[0], p[1], p[2]); break;
    case OP_PLACE_PATH: rc = dem_bridge_place_on_path(b, c.i[0], c.d[0]); break;
    case OP_PLACE_FLAT: rc = dem_bridge_place_flat_mesh(b, c.i[0], c.d[0], c.d[1]); break;
    default: rc = SA_ERROR(SA_ERR_INTERNAL, "unknown DEM call %d from the lead", c.op);
    }
    for (int j = 0; j < DEM_PAR_NBUF; j++) free(p[j]);
    if (rc) { /* the lead hears of it through dem_par_agree; the message is said here */
      sa_log(SA_LOG_ERROR, "dem", "MPI rank %d: %s", dem_par_rank(), sa_error_message());
      sa_error_clear();
    }
  }
  /* the lead destroys its bridge before it releases the followers; a bridge left here would
   * need the lead for LIGGGHTS' collective shutdown, so it is left to the process exit */
  if (b) sa_log(SA_LOG_WARN, "dem", "MPI rank %d: released with a DEM bridge open", dem_par_rank());
  return 0;
}
