/* test_material_regions - [material] regions picks any registered law with its parameters
 * (fem_actuator_materials, fem_actuator_load).
 * 1. "solid:stiff_neohooke(e = .. nu = .. rho = ..)" builds exactly (bytewise) the material of
 *    the built-in set "solid:limit" with the same values (one path for the numbers).
 * 2. "solid:mohr_coulomb(...)" gives the law object with its parameters in the law's order.
 * 3. Bad entries are input errors naming the case key, the region and what is wrong: unknown
 *    law (listing the registered ones), missing parameter, out-of-range value, missing rho.
 * 4. fem_actuator_load (what `softact check` runs) finds them already, also after a tab. */
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>

#include "fem_actuator.h"
#include "fem_law.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static void map_cube(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  for (int k = 0; k < 3; k++) X[k] = xi[k];
}

/* materials of mesh m from a case whose [material] regions is `regions` */
static int mats_of(const char *path, const char *regions, const FemMesh *m, FemMaterial *mat) {
  FILE *f = fopen(path, "w");
  fprintf(f, "[mesh]\n[material]\nregions = %s\n", regions);
  fclose(f);
  SaCase *c;
  TU_CHECK(sa_case_load(path, &c));
  FemActuatorCase a;
  int rc = fem_actuator_load(c, &a);
  if (!rc) rc = fem_actuator_materials(&a, m, mat);
  sa_case_destroy(&c);
  return rc;
}

static int bad(const char *path, const char *regions, const FemMesh *m, const char *needle) {
  FemMaterial mat;
  int rc = mats_of(path, regions, m, &mat);
  const char *msg = sa_error_message();
  int ok = rc == SA_ERR_INPUT && msg && strstr(msg, needle) && strstr(msg, "regions");
  if (!ok) fprintf(stderr, "'%s': rc %d, message '%s' lacks '%s'\n", regions, rc, msg ? msg : "", needle);
  sa_error_clear();
  return !ok;
}

/* fem_actuator_load alone (no mesh: `softact check`) rejects regions with needle */
static int check_rejects(const char *path, const char *regions, const char *needle) {
  FILE *f = fopen(path, "w");
  fprintf(f, "[mesh]\n[material]\nregions = %s\n", regions);
  fclose(f);
  SaCase *c;
  TU_CHECK(sa_case_load(path, &c));
  FemActuatorCase a;
  int rc = fem_actuator_load(c, &a);
  sa_case_destroy(&c);
  const char *msg = sa_error_message();
  int ok = rc == SA_ERR_INPUT && msg && strstr(msg, needle);
  if (!ok) fprintf(stderr, "check of '%s': rc %d, message '%s' lacks '%s'\n", regions, rc, msg, needle);
  sa_error_clear();
  return !ok;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  SmeshBlock blk = {{1, 1, 1}, map_cube, NULL, {"x0", "x1", "y0", "y1", "z0", "z1"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 1, 1e-9, &m));
  char path[] = "/tmp/softact_test_regions_XXXXXX";
  int fd = mkstemp(path);
  if (fd < 0) return 1;
  close(fd);
  int fails = 0;
  FemMaterial a, b;
  memset(&a, 0, sizeof a);
  memset(&b, 0, sizeof b);
  TU_CHECK(mats_of(path, "solid:limit", m, &a));
  TU_CHECK(mats_of(path, "solid:stiff_neohooke(e = 1000e6, nu = 0.3, rho = 1000)", m, &b));
  if (memcmp(&a, &b, sizeof a)) fprintf(stderr, "law entry differs from the built-in set\n"), fails++;
  TU_CHECK(mats_of(path, "solid:mohr_coulomb(young=20e6 poisson=0.3 friction_angle=28 cohesion=100 "
                         "dilation_angle=3 rho=1550)", m, &b));
  const double want[] = {20e6, 0.3, 28, 100, 3};
  if (b.law != fem_law_find("mohr_coulomb") || b.rho != 1550 || memcmp(b.par, want, sizeof want))
    fprintf(stderr, "mohr_coulomb entry: wrong law or parameters\n"), fails++;
  fails += bad(path, "solid:foo(a = 1 rho = 1)", m, "unknown law 'foo' (registered: neohooke");
  fails += bad(path, "solid:stiff_neohooke(e = 1e9 rho = 1)", m, "parameter 'nu' missing");
  fails += bad(path, "solid:mohr_coulomb(young=2e7 poisson=0.3 friction_angle=95 cohesion=1 "
                     "dilation_angle=3 rho=1)", m, "friction_angle = 95 deg must be in [0, 90)");
  fails += bad(path, "solid:stiff_neohooke(e = 1e9 nu = 0.3)", m, "rho");
  fails += check_rejects(path, "a:silicone, solid:stiff_neohooke(e = 1e9 rho = 1)", "'nu' missing");
  fails += check_rejects(path, "a:silicone,\tsolid:stiff_neohooke(e = 1e9 rho = 1)", "'nu' missing");
  remove(path);
  smesh_free(&m);
  return fails ? 1 : 0;
}
