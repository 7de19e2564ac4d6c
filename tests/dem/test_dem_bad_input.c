/* Bad input reaches the caller as SA_ERR_INPUT (SA_ERR_DOMAIN for a wall leaving the box) with
 * a message naming the field, never as a LIGGGHTS abort: every case below would abort the
 * process if it reached LIGGGHTS. After the refusals the same bridge still sets up and runs
 * (with rolling friction on, the one contact-model variant the other tests do not use). */
#include <stddef.h>
#include <unistd.h>

#include "dem_test_util.h"

static void expect(const char *what, int rc, int code, const char *needle) {
  const char *msg = sa_error_message();
  if (rc != code) {
    printf("%s: returned %d, expected %d (message: %s)\n", what, rc, code, msg);
    t_failures++;
  } else if (needle && !strstr(msg, needle)) {
    printf("%s: message \"%s\" does not name \"%s\"\n", what, msg, needle);
    t_failures++;
  }
  sa_error_clear();
}

int main(void) {
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  DemParams p;

  t_params(&p);
  double dtr = dem_rayleigh_dt(p.diameter, p.density, p.young, p.poisson);
  p.dt = 0.5 * dtr;
  int rc = dem_bridge_setup(b, &p);
  expect("unsafe time step", rc, SA_ERR_INPUT, "dt = ");
  {
    /* the message states both numbers: the step and the allowed bound */
    char want[64];
    t_params(&p);
    p.dt = 0.5 * dtr;
    rc = dem_bridge_setup(b, &p);
    snprintf(want, sizeof want, "%g s", p.dt_safety * dtr);
    expect("unsafe time step states the bound", rc, SA_ERR_INPUT, want);
  }
  struct {
    const char *field;
    size_t off;
    double bad;
  } cases[] = {
      {"friction", offsetof(DemParams, friction), -0.1},
      {"friction_wall", offsetof(DemParams, friction_wall), -1},
      {"friction_piston", offsetof(DemParams, friction_piston), NAN},
      {"rolling_friction", offsetof(DemParams, rolling_friction), -0.01},
      {"restitution", offsetof(DemParams, restitution), 0},
      {"restitution", offsetof(DemParams, restitution), 1.2},
      {"poisson", offsetof(DemParams, poisson), 0.6},
      {"wall_poisson", offsetof(DemParams, wall_poisson), -0.1},
      {"young", offsetof(DemParams, young), 0},
      {"wall_young", offsetof(DemParams, wall_young), -5},
      {"silicone_young", offsetof(DemParams, silicone_young), -1},
      {"silicone_poisson", offsetof(DemParams, silicone_poisson), 0.5},
      {"density", offsetof(DemParams, density), NAN},
      {"diameter", offsetof(DemParams, diameter), -1e-3},
      {"dt_safety", offsetof(DemParams, dt_safety), 1.5},
      {"skin", offsetof(DemParams, skin), 0},
      {"box_hi[2]", offsetof(DemParams, box_hi) + 2 * sizeof(double), -0.06},
      {"gravity[1]", offsetof(DemParams, gravity) + sizeof(double), INFINITY},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    t_params(&p);
    *(double *)((char *)&p + cases[i].off) = cases[i].bad;
    char what[80];
    snprintf(what, sizeof what, "%s = %g", cases[i].field, cases[i].bad);
    expect(what, dem_bridge_setup(b, &p), SA_ERR_INPUT, cases[i].field);
  }
  t_params(&p);
  p.seed = 0;
  expect("seed = 0", dem_bridge_setup(b, &p), SA_ERR_INPUT, "seed");
  t_params(&p);
  p.dt = -1e-6;
  expect("dt < 0", dem_bridge_setup(b, &p), SA_ERR_INPUT, "dt");

  /* a valid set-up, then refused meshes, insertions and paths */
  t_params(&p);
  p.rolling_friction = 0.05;
  T_CHECK(dem_bridge_setup(b, &p));
  double sq[12];
  int tri[6], id;
  t_square(0, 0, -0.02, 0.01, sq, tri);
  double out[12];
  memcpy(out, sq, sizeof sq);
  out[2] = -0.2;
  expect("mesh vertex outside the box", dem_bridge_add_mesh(b, "floor", 4, out, 2, tri,
                                                          DEM_WALL_STEEL, &id),
         SA_ERR_INPUT, "outside");
  int degen[6] = {0, 1, 2, 0, 1, 1};
  expect("degenerate triangle", dem_bridge_add_mesh(b, "floor", 4, sq, 2, degen, DEM_WALL_STEEL,
                                                    &id),
         SA_ERR_INPUT, "repeats");
  double line[12];
  memcpy(line, sq, sizeof sq);
  line[9] = 0.5 * (sq[0] + sq[6]), line[10] = 0.5 * (sq[1] + sq[7]); /* vertex 3 on edge 0-2 */
  expect("collinear triangle", dem_bridge_add_mesh(b, "floor", 4, line, 2, tri, DEM_WALL_STEEL,
                                                   &id),
         SA_ERR_INPUT, "degenerate");
  int dup[6] = {0, 1, 2, 2, 0, 1};
  expect("duplicate triangle", dem_bridge_add_mesh(b, "floor", 4, sq, 2, dup, DEM_WALL_STEEL, &id),
         SA_ERR_INPUT, "share vertices");
  int range[6] = {0, 1, 2, 0, 2, 7};
  expect("vertex index out of range", dem_bridge_add_mesh(b, "floor", 4, sq, 2, range,
                                                          DEM_WALL_STEEL, &id),
         SA_ERR_INPUT, "names vertex 7");
  expect("mesh name with a space", dem_bridge_add_mesh(b, "the floor", 4, sq, 2, tri,
                                                       DEM_WALL_STEEL, &id),
         SA_ERR_INPUT, "name");
  expect("wall type", dem_bridge_add_mesh(b, "floor", 4, sq, 2, tri, (DemWallType)1, &id),
         SA_ERR_INPUT, "wall type");
  T_CHECK(dem_bridge_add_mesh(b, "floor", 4, sq, 2, tri, DEM_WALL_STEEL, &id));
  expect("mesh name used twice", dem_bridge_add_mesh(b, "floor", 4, sq, 2, tri, DEM_WALL_STEEL,
                                                     &id),
         SA_ERR_INPUT, "twice");
  int ins;
  expect("insertion cylinder outside the box",
         dem_bridge_insert_cylinder(b, 0, 0, 0.08, -0.01, 0.01, 10, &ins), SA_ERR_INPUT, "box");
  expect("insertion cylinder thinner than a grain",
         dem_bridge_insert_cylinder(b, 0, 0, 0.5e-3, -0.01, 0.01, 10, &ins), SA_ERR_INPUT,
         "radius");
  expect("restart path with a space", dem_bridge_write_restart(b, "/tmp/a b.restart"), SA_ERR_INPUT,
         "restart path");
  expect("restart path with a *", dem_bridge_write_restart(b, "/tmp/a*.restart"), SA_ERR_INPUT,
         "restart path");

  T_CHECK(dem_bridge_insert_cylinder(b, 0, 0, 0.008, -0.015, 0.0, 50, &ins));
  t_true("50 grains inserted", ins == 50);
  T_CHECK(dem_bridge_run(b, 200));
  double moved[12];
  memcpy(moved, sq, sizeof sq);
  moved[2] = 0.06;
  expect("wall node leaving the box", dem_bridge_set_mesh_nodes(b, id, moved, NULL), SA_ERR_DOMAIN,
         "left the DEM box");
  expect("mesh added after the first run", dem_bridge_add_mesh(b, "late", 4, sq, 2, tri,
                                                               DEM_WALL_STEEL, &id),
         SA_ERR_INPUT, "finalized");
  T_CHECK(dem_bridge_run(b, 200));
  t_true("the bridge still runs after the refusals: 50 grains", dem_bridge_count(b) == 50);
  char rpath[64];
  snprintf(rpath, sizeof rpath, "/tmp/softact_test_dem_%ld.restart", (long)getpid());
  T_CHECK(dem_bridge_write_restart(b, rpath));
  FILE *f = fopen(rpath, "rb");
  long size = 0;
  if (f) fseek(f, 0, SEEK_END), size = ftell(f), fclose(f);
  t_true("a valid restart path gives a non-empty restart file", size > 0);
  remove(rpath);
  dem_bridge_destroy(&b);
  dem_bridge_destroy(&b); /* NULL is accepted */
  return t_failures ? 1 : 0;
}
