/* softact_scene.c - the scene registry and the case validation of `softact check` (see
 * softact_scene.h). */
#include "softact_scene.h"

#include <string.h>

#include "sa_error.h"
#include "sa_output.h"

#ifdef SOFTACT_HAVE_HMSA
#include "hmsa.h"
#endif
#ifdef SOFTACT_HAVE_FEM
#include "fem.h"
#include "fem_fill.h"
#endif
#ifdef SOFTACT_HAVE_DEM
#include "dem_module.h"
#endif

#ifndef SOFTACT_VERSION
#define SOFTACT_VERSION "unknown"
#endif

const SaModule *const softact_modules[] = {
#ifdef SOFTACT_HAVE_HMSA
    &hmsa_module,
#endif
#ifdef SOFTACT_HAVE_FEM
    &fem_module,
    &fem_triaxial_module,
    &fem_footing_module,
    &fem_mc_bending_module,
#endif
#ifdef SOFTACT_HAVE_DEM
    &dem_module,
#endif
    &sa_compare_module,
    NULL};

/* Is table t among the first n of list (tables shared by two scenes are listed once)? */
static int table_seen(const SaParamTable *const *list, int n, const SaParamTable *t) {
  for (int i = 0; i < n; i++)
    if (list[i] == t) return 1;
  return 0;
}

/* Which module's scene the case describes: exactly one trigger section must be present, except
 * that a module extending another (FEM-DEM reads the actuator's [mesh]) wins over it. */
static int select_module(const SaCase *c, const SaModule **out) {
  const SaModule *const *modules = softact_modules;
  *out = NULL;
  char names[256] = "";
  for (int i = 0; modules[i]; i++) {
    size_t k = strlen(names);
    snprintf(names + k, sizeof names - k, "%s[%s]", i ? " or " : "", modules[i]->trigger);
    if (!sa_case_has_section(c, modules[i]->trigger)) continue;
    const SaModule *m = modules[i];
    if (*out && m->extends && !strcmp(m->extends, (*out)->trigger)) {
      *out = m; /* m extends the one found so far */
      continue;
    }
    if (*out && (*out)->extends && !strcmp((*out)->extends, m->trigger)) continue;
    SA_REQUIRE(!*out, SA_ERR_INPUT, "%s: the case has both [%s] and [%s]; a case file describes one scene",
               sa_case_path(c), (*out)->trigger, m->trigger);
    *out = m;
  }
  SA_REQUIRE(*out, SA_ERR_INPUT, "%s: no scene section found: a case needs %s", sa_case_path(c),
             names[0] ? names : "a module (none built)");
  return 0;
}

int softact_case_validate(const SaCase *c, SaRunParams *rp, const SaModule **mp, void **scene) {
  const SaModule *const *modules = softact_modules;
  const SaModule *m = NULL;
  *mp = NULL;
  *scene = NULL;
  /* unknown sections/keys first, against every module, so a typo in the scene section is
   * reported as a typo rather than as a missing scene */
  const SaParamTable *all[128];
  int na = 0;
  all[na++] = &sa_run_table;
  for (int i = 0; modules[i]; i++)
    for (int t = 0; t < modules[i]->ntables && na < 128; t++)
      if (!table_seen(all, na, modules[i]->tables[t])) all[na++] = modules[i]->tables[t];
  SA_CHECK(sa_case_check_known(c, all, na));
  SA_CHECK(select_module(c, &m));
  const SaParamTable *tables[64];
  int nt = 0;
  tables[nt++] = &sa_run_table;
  for (int i = 0; i < m->ntables && nt < 64; i++) tables[nt++] = m->tables[i];
  SA_CHECK(sa_case_check_known(c, tables, nt));
  SA_CHECK(sa_params_load(&sa_run_table, c, rp));
  SA_CHECK(m->check(c, scene));
  *mp = m;
  return 0;
}

void softact_write_resolved(FILE *f, const SaCase *c, const SaRunParams *rp, const SaModule *m,
                            const void *scene) {
  /* the mark is how a later run recognises this folder as a softact run (sa_output.h) */
  fprintf(f, SA_RESULTS_MARK " %s (softact %s): every key with its value, defaults filled in\n\n",
          sa_case_path(c), SOFTACT_VERSION);
  sa_params_write(&sa_run_table, rp, f);
  m->write_resolved(scene, f);
}

void softact_write_keys(FILE *f) {
  const SaParamTable *seen[128];
  int ns = 0;
  sa_params_write_markdown(&sa_run_table, f);
  for (int i = 0; softact_modules[i]; i++)
    for (int t = 0; t < softact_modules[i]->ntables && ns < 128; t++) {
      const SaParamTable *tb = softact_modules[i]->tables[t];
      if (table_seen(seen, ns, tb)) continue; /* shared by two scenes: listed once */
      seen[ns++] = tb;
      sa_params_write_markdown(tb, f);
    }
}
