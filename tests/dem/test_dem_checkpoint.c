/* Checkpoint and resume of the DEM bridge (issue 12): a run stopped at a checkpoint and resumed
 * in a new process continues exactly as the run that wrote the checkpoint.
 *
 * Scene: 200 grains of 3 mm poured into a vertical tube (silicone, radius 9 mm, its nodes
 * breathing radially by 3 % with period 20 ms, velocities given), on a steel floor, under a
 * steel piston plate coming down at 0.5 m/s until it presses into the bed. Friction 0.5
 * everywhere: at the checkpoint grains touch each other, the tube, the floor and the piston
 * with tangential springs loaded, so a lost grain-grain or grain-wall contact history would
 * change the forces of the very next step. Every DEM step the moving meshes are set to their
 * positions and velocities at the end of that step (the coupling loop's per-step update).
 *
 * A: N steps, dem_bridge_write_checkpoint, M more steps (this process).
 * B: a child process (this executable again): refusals first (see below), then
 *    dem_bridge_setup_from_checkpoint, the meshes added again at the checkpoint's positions,
 *    the same M steps.
 * Check: B == A bitwise (ids, positions, velocities, forces of every grain, force of every wall
 * triangle). Bitwise, not a tolerance, because the bridge makes the two runs identical
 * operation by operation: both start the continuation with a set-up pass and the forces of the
 * checkpoint's last step (dem.h). Also bitwise: the grain-wall contacts LIGGGHTS tracks
 * (grain, triangle, tangential spring) in B after the resume and in A after the checkpoint,
 * of which there must be some on each wall with a loaded spring.
 * Measured for the record (DEM_TEST_VERBOSE=1; numbers in docs/dem.md), not a pass criterion
 * beyond sanity bounds:
 *   D: the same run without a checkpoint. It differs from A by round-off only (the set-up pass
 *      rebuilds neighbour lists and sorts grains: same forces summed in another order); the
 *      difference then grows as it does in any chaotic granular flow.
 *   E: D with the piston displaced by 1e-15 m for one step at step N: how fast a round-off
 *      sized perturbation grows in this bed. max |x_A - x_D| is required to stay within
 *      10 max |x_D - x_E| + 1e-13 m: checkpointing perturbs a run no more than round-off does
 *      (measured: 1.0e-11 m against 2.6e-11 m).
 * Refusals (child, before the valid resume, on the same bridge, which must stay usable): a
 * missing file (SA_ERR_IO), a truncated one (half, and all but its last byte), a damaged one
 * (one byte flipped), a file that is not a checkpoint, another grain diameter, another grain
 * count (SA_ERR_INPUT, message naming the file and the field); after the resume, a mesh added
 * under another name or at another position; the checkpoint file is unchanged by all of it.
 * In A, just before the real checkpoint, writing into a directory that does not exist fails
 * with SA_ERR_IO before LIGGGHTS is asked for anything (B == A shows that nothing changed). */
#include <stdint.h>
#include <sys/wait.h>
#include <unistd.h>

#include "dem_test_util.h"

enum { NGRAIN = 200, NCK = 4200, NMORE = 1500 };
static const double TUBE_R = 9e-3, TUBE_H = 90e-3, BREATH = 0.03, PERIOD = 20e-3;
static const double PISTON_Z0 = 80e-3, PISTON_V = 0.5, PISTON_STOP = 18e-3, PISTON_R = 8.6e-3;

static void params(DemParams *p) {
  t_params(p);
  p->diameter = 3e-3;
  p->dt = 0.15 * dem_rayleigh_dt(p->diameter, p->density, p->young, p->poisson);
  for (int k = 0; k < 2; k++) p->box_lo[k] = -0.015, p->box_hi[k] = 0.015;
  p->box_lo[2] = -0.005, p->box_hi[2] = 0.1;
}

typedef struct {
  double *xyz0[3], *xyz[3], *v[3];
  int *tri[3], nv[3], nt[3], id[3];
} Scene;

static const char *mesh_name[3] = {"tube", "floor", "piston"};

static void scene_init(Scene *s) {
  t_tube(0, 0, TUBE_R, 0, TUBE_H, 16, 10, &s->xyz0[0], &s->tri[0], &s->nv[0], &s->nt[0]);
  t_disk(0, 0, TUBE_R + 2e-3, 0, 16, 2, &s->xyz0[1], &s->tri[1], &s->nv[1], &s->nt[1]);
  t_disk(0, 0, PISTON_R, 0, 16, 2, &s->xyz0[2], &s->tri[2], &s->nv[2], &s->nt[2]);
  for (int m = 0; m < 3; m++) {
    s->xyz[m] = malloc(3 * (size_t)s->nv[m] * sizeof(double));
    s->v[m] = calloc(3 * (size_t)s->nv[m], sizeof(double));
  }
}

static void scene_free(Scene *s) {
  for (int m = 0; m < 3; m++) free(s->xyz0[m]), free(s->xyz[m]), free(s->v[m]), free(s->tri[m]);
}

/* Node positions and velocities of the tube and the piston at the end of step `step`
 * (time step*dt); dz: extra piston offset [m] (the perturbation of run E). */
static void scene_at(Scene *s, const DemParams *p, long step, double dz) {
  double t = step * p->dt, w = 2 * M_PI / PERIOD;
  double g = 1 + BREATH * sin(w * t), gd = BREATH * w * cos(w * t);
  for (int i = 0; i < s->nv[0]; i++) {
    const double *q = s->xyz0[0] + 3 * i;
    double *x = s->xyz[0] + 3 * i, *v = s->v[0] + 3 * i;
    x[0] = g * q[0], x[1] = g * q[1], x[2] = q[2];
    v[0] = gd * q[0], v[1] = gd * q[1], v[2] = 0;
  }
  double zp = PISTON_Z0 - PISTON_V * t, vz = -PISTON_V;
  if (zp < PISTON_STOP) zp = PISTON_STOP, vz = 0;
  for (int i = 0; i < s->nv[2]; i++) {
    const double *q = s->xyz0[2] + 3 * i;
    double *x = s->xyz[2] + 3 * i, *v = s->v[2] + 3 * i;
    x[0] = q[0], x[1] = q[1], x[2] = zp + dz;
    v[0] = v[1] = 0, v[2] = vz;
  }
  memcpy(s->xyz[1], s->xyz0[1], 3 * (size_t)s->nv[1] * sizeof(double));
}

static void scene_add(DemBridge *b, Scene *s) {
  static const DemWallType type[3] = {DEM_WALL_SILICONE, DEM_WALL_STEEL, DEM_WALL_STEEL};
  for (int m = 0; m < 3; m++)
    T_CHECK(dem_bridge_add_mesh(b, mesh_name[m], s->nv[m], s->xyz[m], s->nt[m], s->tri[m],
                                type[m], &s->id[m]));
}

/* Steps from..to-1, the moving meshes set at the end of each step; perturb_at: the step at
 * which the piston is displaced by 1e-15 m for one step (< 0: never). */
static void advance(DemBridge *b, Scene *s, const DemParams *p, long from, long to,
                    long perturb_at) {
  for (long k = from; k < to; k++) {
    scene_at(s, p, k + 1, k == perturb_at ? 1e-15 : 0);
    T_CHECK(dem_bridge_set_mesh_nodes(b, s->id[0], s->xyz[0], s->v[0]));
    T_CHECK(dem_bridge_set_mesh_nodes(b, s->id[2], s->xyz[2], s->v[2]));
    T_CHECK(dem_bridge_run(b, 1));
  }
}

/* The state compared: per grain (sorted by id) id, x, v, f; per wall triangle the force. */
typedef struct {
  int n, ntri;
  int *id;
  double *x, *v, *f, *wall;
} State;

static void state_get(DemBridge *b, const Scene *s, State *st) {
  int n = dem_bridge_count(b);
  int *id = malloc(n * sizeof *id);
  double *x = malloc(3 * n * sizeof *x), *v = malloc(3 * n * sizeof *v),
         *f = malloc(3 * n * sizeof *f);
  T_CHECK(dem_bridge_particle_ids(b, id));
  T_CHECK(dem_bridge_particles(b, x, v, f, NULL));
  st->n = n;
  st->id = malloc(n * sizeof *id);
  st->x = malloc(3 * n * sizeof *x), st->v = malloc(3 * n * sizeof *v);
  st->f = malloc(3 * n * sizeof *f);
  /* ids are 1..n (no grain lost: checked) */
  for (int i = 0; i < n; i++) {
    int j = id[i] - 1;
    if (j < 0 || j >= n) {
      printf("grain id %d outside 1..%d (a grain was lost?)\n", id[i], n);
      exit(1);
    }
    st->id[j] = id[i];
    memcpy(st->x + 3 * j, x + 3 * i, 3 * sizeof *x);
    memcpy(st->v + 3 * j, v + 3 * i, 3 * sizeof *v);
    memcpy(st->f + 3 * j, f + 3 * i, 3 * sizeof *f);
  }
  st->ntri = 0;
  for (int m = 0; m < 3; m++) st->ntri += s->nt[m];
  st->wall = malloc(3 * (size_t)st->ntri * sizeof(double));
  for (int m = 0, o = 0; m < 3; o += s->nt[m], m++)
    T_CHECK(dem_bridge_mesh_forces(b, s->id[m], st->wall + 3 * o));
  free(id), free(x), free(v), free(f);
}

static void state_free(State *st) {
  free(st->id), free(st->x), free(st->v), free(st->f), free(st->wall);
}

static int state_write(const char *path, const State *st) {
  FILE *fp = fopen(path, "wb");
  if (!fp) return -1;
  fwrite(&st->n, sizeof st->n, 1, fp);
  fwrite(&st->ntri, sizeof st->ntri, 1, fp);
  fwrite(st->id, sizeof *st->id, st->n, fp);
  fwrite(st->x, sizeof *st->x, 3 * st->n, fp);
  fwrite(st->v, sizeof *st->v, 3 * st->n, fp);
  fwrite(st->f, sizeof *st->f, 3 * st->n, fp);
  fwrite(st->wall, sizeof *st->wall, 3 * st->ntri, fp);
  return fclose(fp);
}

static int state_read(const char *path, State *st) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return -1;
  int ok = fread(&st->n, sizeof st->n, 1, fp) == 1 && fread(&st->ntri, sizeof st->ntri, 1, fp) == 1 &&
           st->n > 0 && st->n < 1000000 && st->ntri > 0 && st->ntri < 1000000;
  if (ok) {
    st->id = malloc(st->n * sizeof *st->id);
    st->x = malloc(3 * st->n * sizeof *st->x), st->v = malloc(3 * st->n * sizeof *st->v);
    st->f = malloc(3 * st->n * sizeof *st->f);
    st->wall = malloc(3 * st->ntri * sizeof *st->wall);
    ok = fread(st->id, sizeof *st->id, st->n, fp) == (size_t)st->n &&
         fread(st->x, sizeof *st->x, 3 * st->n, fp) == 3 * (size_t)st->n &&
         fread(st->v, sizeof *st->v, 3 * st->n, fp) == 3 * (size_t)st->n &&
         fread(st->f, sizeof *st->f, 3 * st->n, fp) == 3 * (size_t)st->n &&
         fread(st->wall, sizeof *st->wall, 3 * st->ntri, fp) == 3 * (size_t)st->ntri;
  }
  fclose(fp);
  return ok ? 0 : -1;
}

static double maxdiff(const double *a, const double *b, int n) {
  double d = 0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

static double maxabs(const double *a, int n) {
  double d = 0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i]));
  return d;
}

/* Largest differences of positions [m], velocities [m/s], grain forces [N], wall forces [N]. */
static void state_diff(const State *a, const State *b, double d[4]) {
  d[0] = maxdiff(a->x, b->x, 3 * a->n);
  d[1] = maxdiff(a->v, b->v, 3 * a->n);
  d[2] = maxdiff(a->f, b->f, 3 * a->n);
  d[3] = maxdiff(a->wall, b->wall, 3 * a->ntri);
}

static int state_identical(const State *a, const State *b) {
  return a->n == b->n && a->ntri == b->ntri && !memcmp(a->id, b->id, a->n * sizeof *a->id) &&
         !memcmp(a->x, b->x, 3 * a->n * sizeof *a->x) && !memcmp(a->v, b->v, 3 * a->n * sizeof *a->v) &&
         !memcmp(a->f, b->f, 3 * a->n * sizeof *a->f) &&
         !memcmp(a->wall, b->wall, 3 * a->ntri * sizeof *a->wall);
}

/* The grain-wall contacts LIGGGHTS tracks (fix contacthistory/mesh) on the three meshes: per
 * contact the mesh, grain id, triangle and tangential spring. */
typedef struct {
  int n, nshear, per_mesh[3];
  int mesh[4000], grain[4000], tri[4000];
  double shear[12000];
} Contacts;

static void contacts_get(DemBridge *b, const Scene *s, Contacts *c) {
  memset(c, 0, sizeof *c);
  for (int m = 0; m < 3; m++) {
    int k = 0, room = 4000 - c->n;
    T_CHECK(dem_bridge_wall_contacts(b, s->id[m], room, c->grain + c->n, c->tri + c->n,
                                     c->shear + 3 * c->n, &k));
    if (k > room) printf("more than 4000 wall contacts\n"), exit(1);
    for (int i = c->n; i < c->n + k; i++) {
      c->mesh[i] = m;
      c->nshear += c->shear[3 * i] != 0 || c->shear[3 * i + 1] != 0 || c->shear[3 * i + 2] != 0;
    }
    c->per_mesh[m] = k;
    c->n += k;
  }
}

static int contacts_identical(const Contacts *a, const Contacts *b) {
  return a->n == b->n && !memcmp(a->mesh, b->mesh, a->n * sizeof *a->mesh) &&
         !memcmp(a->grain, b->grain, a->n * sizeof *a->grain) &&
         !memcmp(a->tri, b->tri, a->n * sizeof *a->tri) &&
         !memcmp(a->shear, b->shear, 3 * a->n * sizeof *a->shear);
}

static Contacts contacts_a, contacts_b;

/* A run from the start to step NCK (+ checkpoint at NCK if ck_path) and on to NCK + NMORE. */
static void run_full(const char *ck_path, long perturb_at, State *st, double *wall_at_ck) {
  DemParams p;
  params(&p);
  Scene s;
  scene_init(&s);
  scene_at(&s, &p, 0, 0);
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  scene_add(b, &s);
  int ins = 0;
  T_CHECK(dem_bridge_insert_cylinder(b, 0, 0, TUBE_R * (1 - BREATH) - 0.2e-3, 1e-3, 75e-3, NGRAIN,
                                     &ins));
  if (ins != NGRAIN) {
    printf("inserted %d of %d grains\n", ins, NGRAIN);
    exit(1);
  }
  advance(b, &s, &p, 0, NCK, perturb_at);
  if (wall_at_ck) {
    /* the load on each wall at the checkpoint (z force summed) */
    for (int m = 0; m < 3; m++) {
      double *f = malloc(3 * (size_t)s.nt[m] * sizeof *f);
      T_CHECK(dem_bridge_mesh_forces(b, s.id[m], f));
      wall_at_ck[m] = 0;
      for (int t = 0; t < s.nt[m]; t++)
        wall_at_ck[m] += sqrt(f[3 * t] * f[3 * t] + f[3 * t + 1] * f[3 * t + 1] +
                              f[3 * t + 2] * f[3 * t + 2]);
      free(f);
    }
  }
  if (ck_path) {
    /* a checkpoint where no file can be is refused before LIGGGHTS is asked for anything (the
     * bitwise comparison with B below shows that nothing changed) */
    int rc = dem_bridge_write_checkpoint(b, "/nonexistent-softact-dir/x.dem");
    if (rc != SA_ERR_IO || !strstr(sa_error_message(), "/nonexistent-softact-dir/x.dem"))
      printf("checkpoint into a missing directory: returned %d (%s)\n", rc, sa_error_message()),
          t_failures++;
    sa_error_clear();
    T_CHECK(dem_bridge_write_checkpoint(b, ck_path));
    contacts_get(b, &s, &contacts_a);
  }
  advance(b, &s, &p, NCK, NCK + NMORE, perturb_at);
  state_get(b, &s, st);
  t_true("no grain lost", dem_bridge_count(b) == NGRAIN);
  dem_bridge_destroy(&b);
  scene_free(&s);
}

/* ------------------------------------------------------------------ child: resume */

static void expect(const char *what, int rc, int code, const char *n1, const char *n2) {
  const char *msg = sa_error_message();
  if (rc != code)
    printf("%s: returned %d, expected %d (message: %s)\n", what, rc, code, msg), t_failures++;
  else if ((n1 && !strstr(msg, n1)) || (n2 && !strstr(msg, n2)))
    printf("%s: message \"%s\" does not name \"%s\"%s%s\n", what, msg, n1, n2 ? " and " : "",
           n2 ? n2 : ""), t_failures++;
  else if (t_verbose())
    printf("  refused as expected: %s: %s\n", what, msg);
  sa_error_clear();
}

static unsigned char *slurp(const char *path, size_t *n) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  *n = (size_t)ftell(fp);
  fseek(fp, 0, SEEK_SET);
  unsigned char *d = malloc(*n + 1);
  if (fread(d, 1, *n, fp) != *n) *n = 0;
  fclose(fp);
  return d;
}

static void spill(const char *path, const unsigned char *d, size_t n) {
  FILE *fp = fopen(path, "wb");
  if (!fp || fwrite(d, 1, n, fp) != n) printf("cannot write %s\n", path), exit(1);
  fclose(fp);
}

static int child(const char *ck, const char *out) {
  DemParams p;
  params(&p);
  size_t n0 = 0;
  unsigned char *orig = slurp(ck, &n0);
  if (!orig || n0 < 64) return printf("child: cannot read %s\n", ck), 1;
  char bad[1100];
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));

  snprintf(bad, sizeof bad, "%s.missing", ck);
  expect("missing file", dem_bridge_setup_from_checkpoint(b, &p, bad, NGRAIN), SA_ERR_IO, bad,
         NULL);
  snprintf(bad, sizeof bad, "%s.half", ck);
  spill(bad, orig, n0 / 2);
  expect("file cut in half", dem_bridge_setup_from_checkpoint(b, &p, bad, NGRAIN), SA_ERR_INPUT,
         bad, "truncated");
  spill(bad, orig, n0 - 1);
  expect("file without its last byte", dem_bridge_setup_from_checkpoint(b, &p, bad, NGRAIN),
         SA_ERR_INPUT, bad, "truncated");
  unsigned char *flip = malloc(n0);
  memcpy(flip, orig, n0);
  flip[n0 / 2] ^= 0x10;
  spill(bad, flip, n0);
  expect("one byte flipped", dem_bridge_setup_from_checkpoint(b, &p, bad, NGRAIN), SA_ERR_INPUT,
         bad, "damaged");
  spill(bad, (const unsigned char *)"solid tube\nendsolid tube\n", 25);
  expect("not a checkpoint", dem_bridge_setup_from_checkpoint(b, &p, bad, NGRAIN), SA_ERR_INPUT,
         bad, "not a softact DEM checkpoint");
  remove(bad);
  free(flip);
  DemParams q = p;
  q.diameter = 2.9e-3;
  expect("another grain diameter", dem_bridge_setup_from_checkpoint(b, &q, ck, NGRAIN),
         SA_ERR_INPUT, ck, "diameter");
  q = p; /* another time step: refused unless the run asks for a variant of the bed */
  q.dt *= 0.5;
  expect("another time step", dem_bridge_setup_from_checkpoint(b, &q, ck, NGRAIN), SA_ERR_INPUT,
         ck, "dt =");
  q = p; /* resume_new_dt frees the time step only */
  q.resume_new_dt = 1;
  q.diameter = 2.9e-3;
  expect("another grain diameter with resume_new_dt",
         dem_bridge_setup_from_checkpoint(b, &q, ck, NGRAIN), SA_ERR_INPUT, ck, "diameter");
  q = p; /* the silicone wall's moduli (format version 2) are part of the parameters too */
  q.silicone_young = 1e6;
  expect("a compliant silicone wall", dem_bridge_setup_from_checkpoint(b, &q, ck, NGRAIN),
         SA_ERR_INPUT, ck, "silicone_young");
  /* a version-1 file (before the silicone wall's two moduli): the same bytes without the 16 at
   * offset 224 (after 23 doubles of parameters from offset 40), version 1, its FNV-1a hash of
   * every byte before it redone here (Fowler-Noll-Vo, 64 bit). It reads as a near-rigid
   * silicone wall (0, 0): the info passes, a compliant wall's parameters are refused */
  unsigned char *v1 = malloc(n0);
  size_t nv1 = n0 - 16;
  memcpy(v1, orig, 224);
  memcpy(v1 + 224, orig + 240, n0 - 240);
  uint32_t one = 1;
  memcpy(v1 + 8, &one, 4);
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < nv1 - 8; i++) h = (h ^ v1[i]) * 0x100000001b3ull;
  memcpy(v1 + nv1 - 8, &h, 8);
  snprintf(bad, sizeof bad, "%s.v1", ck);
  spill(bad, v1, nv1);
  DemCheckpointInfo i1;
  int rc1 = dem_bridge_checkpoint_info(bad, &i1);
  if (rc1) printf("version 1: %s\n", sa_error_message());
  t_true("a version-1 checkpoint is read (step, count, meshes)",
         rc1 == 0 && i1.step == NCK && i1.count == NGRAIN && i1.nmesh == 3);
  expect("a compliant silicone wall against a version-1 file",
         dem_bridge_setup_from_checkpoint(b, &q, bad, NGRAIN), SA_ERR_INPUT, bad, "silicone_young");
  remove(bad);
  free(v1);
  expect("another grain count", dem_bridge_setup_from_checkpoint(b, &p, ck, NGRAIN - 1),
         SA_ERR_INPUT, ck, "grains");
  DemCheckpointInfo info;
  T_CHECK(dem_bridge_checkpoint_info(ck, &info));
  t_true("checkpoint info: step, count, meshes, diameter",
         info.step == NCK && info.count == NGRAIN && info.nmesh == 3 && info.diameter == p.diameter);

  /* the same bridge, untouched by the refusals, resumes */
  T_CHECK(dem_bridge_setup_from_checkpoint(b, &p, ck, NGRAIN));
  Scene s;
  scene_init(&s);
  scene_at(&s, &p, NCK, 0);
  int id;
  expect("mesh added under another name",
         dem_bridge_add_mesh(b, "barrel", s.nv[0], s.xyz[0], s.nt[0], s.tri[0], DEM_WALL_SILICONE,
                             &id),
         SA_ERR_INPUT, ck, "tube");
  s.xyz[0][5] += 1e-12;
  expect("mesh added at another position",
         dem_bridge_add_mesh(b, "tube", s.nv[0], s.xyz[0], s.nt[0], s.tri[0], DEM_WALL_SILICONE,
                             &id),
         SA_ERR_INPUT, ck, "vertex 1");
  s.xyz[0][5] -= 1e-12;
  scene_at(&s, &p, NCK, 0);
  scene_add(b, &s);
  contacts_get(b, &s, &contacts_b);
  {
    char cpath[1100];
    snprintf(cpath, sizeof cpath, "%s.contacts", out);
    spill(cpath, (const unsigned char *)&contacts_b, sizeof contacts_b);
  }
  advance(b, &s, &p, NCK, NCK + NMORE, -1);
  State st;
  state_get(b, &s, &st);
  if (state_write(out, &st)) return printf("child: cannot write %s\n", out), 1;
  state_free(&st);
  dem_bridge_destroy(&b);
  scene_free(&s);

  size_t n1 = 0;
  unsigned char *now = slurp(ck, &n1);
  t_true("the checkpoint file is unchanged by the refusals and the resume",
         now && n1 == n0 && !memcmp(now, orig, n0));
  free(now), free(orig);
  return t_failures ? 1 : 0;
}

/* ------------------------------------------------------------------ parent */

int main(int argc, char **argv) {
  if (argc == 4 && !strcmp(argv[1], "--resume")) return child(argv[2], argv[3]);
  char ck[256], out[256];
  snprintf(ck, sizeof ck, "/tmp/softact_test_ckpt_%ld.dem", (long)getpid());
  snprintf(out, sizeof out, "/tmp/softact_test_ckpt_%ld.state", (long)getpid());
  double t0 = t_now();

  /* A: checkpoint at NCK, then NMORE steps */
  State A;
  double wall[3];
  run_full(ck, -1, &A, wall);
  t_true("the wall meshes carry load at the checkpoint (tube, floor, piston)",
         wall[0] > 0 && wall[1] > 0 && wall[2] > 0);
  double ta = t_now();

  /* B: a new process resumes from the checkpoint */
  fflush(stdout);
  pid_t pid = fork();
  if (pid == 0) {
    char *args[] = {argv[0], "--resume", ck, out, NULL};
    execv("/proc/self/exe", args);
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  t_true("the resuming process succeeded", WIFEXITED(status) && WEXITSTATUS(status) == 0);
  {
    char cpath[300];
    snprintf(cpath, sizeof cpath, "%s.contacts", out);
    size_t nc = 0;
    unsigned char *d = slurp(cpath, &nc);
    if (d && nc == sizeof contacts_b) memcpy(&contacts_b, d, nc);
    free(d);
    remove(cpath);
    t_true("the resumed bridge holds the grain-wall contact histories of the checkpoint, bitwise",
           contacts_identical(&contacts_a, &contacts_b));
    t_true("grain-wall contacts with a loaded tangential spring at the checkpoint",
           contacts_a.nshear > 10 && contacts_a.per_mesh[0] > 0 && contacts_a.per_mesh[1] > 0 &&
               contacts_a.per_mesh[2] > 0);
    if (t_verbose())
      printf("grain-wall contacts at the checkpoint: tube %d, floor %d, piston %d; %d with a "
             "non-zero tangential spring\n",
             contacts_a.per_mesh[0], contacts_a.per_mesh[1], contacts_a.per_mesh[2],
             contacts_a.nshear);
  }
  State B;
  if (state_read(out, &B) == 0) {
    double d[4];
    state_diff(&A, &B, d);
    if (!state_identical(&A, &B)) {
      printf("resumed run differs from the run that wrote the checkpoint: |dx| %.3g m, |dv| %.3g "
             "m/s, |df| %.3g N, |df_wall| %.3g N (expected bitwise equality)\n",
             d[0], d[1], d[2], d[3]);
      t_failures++;
    } else if (t_verbose())
      printf("resumed run == run that wrote the checkpoint, bitwise (%d grains, %d wall "
             "triangles, %d steps after the checkpoint)\n",
             A.n, A.ntri, NMORE);
    state_free(&B);
  } else {
    printf("no state from the resuming process\n");
    t_failures++;
  }
  double tb = t_now();

  /* D: no checkpoint; E: no checkpoint, piston displaced by 1e-15 m for one step at NCK */
  State D, E;
  run_full(NULL, -1, &D, NULL);
  run_full(NULL, NCK, &E, NULL);
  double dad[4], dde[4];
  state_diff(&A, &D, dad);
  state_diff(&D, &E, dde);
  if (t_verbose()) {
    printf("wall load at the checkpoint (sum |f| per triangle) [N]: tube %.4g, floor %.4g, "
           "piston %.4g\n",
           wall[0], wall[1], wall[2]);
    printf("scale: max |x| %.3g m, |v| %.3g m/s, |f| %.3g N, |f_wall| %.3g N\n",
           maxabs(A.x, 3 * A.n), maxabs(A.v, 3 * A.n), maxabs(A.f, 3 * A.n),
           maxabs(A.wall, 3 * A.ntri));
    printf("A - D (checkpoint vs none), %d steps on: |dx| %.3g m, |dv| %.3g m/s, |df| %.3g N, "
           "|df_wall| %.3g N\n",
           NMORE, dad[0], dad[1], dad[2], dad[3]);
    printf("D - E (1e-15 m piston kick), %d steps on: |dx| %.3g m, |dv| %.3g m/s, |df| %.3g N, "
           "|df_wall| %.3g N\n",
           NMORE, dde[0], dde[1], dde[2], dde[3]);
    printf("time: A %.1f s, B (child, with refusals) %.1f s, D+E %.1f s\n", ta - t0, tb - ta,
           t_now() - tb);
  }
  t_true("checkpointing perturbs the run no more than round-off does: |x_A - x_D| <= 10 "
         "|x_D - x_E| + 1e-13 m",
         dad[0] <= 10 * dde[0] + 1e-13);
  state_free(&A), state_free(&D), state_free(&E);
  remove(ck), remove(out);
  return t_failures ? 1 : 0;
}
