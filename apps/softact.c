/* softact - command-line front end: parse arguments, load the case, hand it to the module
 * whose section it contains, map the result to an exit status. The physics lives in the
 * modules; this file only wires them (see docs/architecture.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sa_error.h"
#include "sa_log.h"
#include "sa_module.h"
#include "sa_output.h"
#include "sa_params.h"
#include "sa_run.h"

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

static const SaModule *const modules[] = {
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
    NULL};

static void usage(FILE *f) {
  fprintf(f,
          "usage: softact run CASE.ini [--set section.key=value ...] [--out DIR] [--quiet|--verbose]\n"
          "       softact check CASE.ini [--set section.key=value ...]\n"
          "       softact keys            (reference of every case key, Markdown)\n"
          "       softact --help | --version\n"
          "\n"
          "  run     validate the case, then compute it; results go to DIR (default: [run] out_dir,\n"
          "          else results/<case name>): case.ini (resolved case), softact.log, CSV, PNG, VTK\n"
          "  check   validate the case and print it fully resolved (defaults filled in); run nothing\n"
          "\n"
          "scenes (the section that selects each):\n");
  for (int i = 0; modules[i]; i++) fprintf(f, "  [%s]  %s\n", modules[i]->trigger, modules[i]->help);
  fprintf(f,
          "\nexit status: 0 ok, 1 bad input (case file, arguments), 2 numerical failure\n"
          "(no convergence, inverted element, limit point, NaN), 3 interrupted (SIGINT/SIGTERM;\n"
          "results computed so far are kept), 4 I/O, memory or library failure.\n");
}

/* Is table t among the first n of list (tables shared by two scenes are listed once)? */
static int table_seen(const SaParamTable *const *list, int n, const SaParamTable *t) {
  for (int i = 0; i < n; i++)
    if (list[i] == t) return 1;
  return 0;
}

/* Which module's scene the case describes: exactly one trigger section must be present, except
 * that a module extending another (FEM-DEM reads the actuator's [mesh]) wins over it. */
static int select_module(const SaCase *c, const SaModule **out) {
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

typedef struct {
  const char *command, *case_path, *out;
  const char *sets[256];
  int nsets;
} Args;

static int parse_args(int argc, char **argv, Args *a) {
  memset(a, 0, sizeof *a);
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (!strcmp(s, "--set") || !strcmp(s, "--out")) {
      SA_REQUIRE(i + 1 < argc, SA_ERR_INPUT, "%s needs a value", s);
      if (s[2] == 's') {
        SA_REQUIRE(a->nsets < 256, SA_ERR_INPUT, "too many --set options");
        a->sets[a->nsets++] = argv[++i];
      } else
        a->out = argv[++i];
    } else if (!strncmp(s, "--set=", 6)) {
      SA_REQUIRE(a->nsets < 256, SA_ERR_INPUT, "too many --set options");
      a->sets[a->nsets++] = s + 6;
    } else if (!strncmp(s, "--out=", 6))
      a->out = s + 6;
    else if (!strcmp(s, "--quiet") || !strcmp(s, "-q"))
      sa_log_set_level(SA_LOG_WARN);
    else if (!strcmp(s, "--verbose") || !strcmp(s, "-v"))
      sa_log_set_level(SA_LOG_DEBUG);
    else if (s[0] == '-')
      return SA_ERROR(SA_ERR_INPUT, "unknown option '%s' (see softact --help)", s);
    else if (!a->command)
      a->command = s;
    else if (!a->case_path)
      a->case_path = s;
    else
      return SA_ERROR(SA_ERR_INPUT, "unexpected argument '%s' (see softact --help)", s);
  }
  SA_REQUIRE(a->command, SA_ERR_INPUT, "no command given (see softact --help)");
  SA_REQUIRE(!strcmp(a->command, "run") || !strcmp(a->command, "check"), SA_ERR_INPUT,
             "unknown command '%s' (expected run, check or keys)", a->command);
  SA_REQUIRE(a->case_path, SA_ERR_INPUT, "softact %s needs a case file", a->command);
  return 0;
}

/* Write the resolved case (run table + module tables) to f. */
static void write_resolved(FILE *f, const SaCase *c, const SaRunParams *rp, const SaModule *m, const void *scene) {
  fprintf(f, "; resolved case of %s (softact %s): every key with its value, defaults filled in\n\n",
          sa_case_path(c), SOFTACT_VERSION);
  sa_params_write(&sa_run_table, rp, f);
  m->write_resolved(scene, f);
}

/* Remove what this run created in a results folder when the input turned out to be bad. */
static void remove_created(const char *dir, int made_dir, const char *const *files, int nfiles) {
  char path[SA_STR_MAX];
  for (int i = 0; i < nfiles; i++)
    if (sa_path_join(dir, files[i], path) == 0) unlink(path);
  if (made_dir) rmdir(dir);
}

static int run_case(const Args *a) {
  SaCase *c = NULL;
  void *scene = NULL;
  const SaModule *m = NULL;
  SaRun run;
  memset(&run, 0, sizeof run);
  int rc = sa_case_load(a->case_path, &c);
  for (int i = 0; !rc && i < a->nsets; i++) rc = sa_case_override(c, a->sets[i]);
  if (!rc) { /* unknown sections/keys first, against every module, so a typo in the scene
                section is reported as a typo rather than as a missing scene */
    const SaParamTable *all[128];
    int na = 0;
    all[na++] = &sa_run_table;
    for (int i = 0; modules[i]; i++)
      for (int t = 0; t < modules[i]->ntables && na < 128; t++)
        if (!table_seen(all, na, modules[i]->tables[t])) all[na++] = modules[i]->tables[t];
    rc = sa_case_check_known(c, all, na);
  }
  if (!rc) rc = select_module(c, &m);
  if (!rc) {
    const SaParamTable *tables[64];
    int nt = 0;
    tables[nt++] = &sa_run_table;
    for (int i = 0; i < m->ntables && nt < 64; i++) tables[nt++] = m->tables[i];
    rc = sa_case_check_known(c, tables, nt);
  }
  if (!rc) rc = sa_params_load(&sa_run_table, c, &run.params);
  if (!rc) rc = m->check(c, &scene);
  if (rc) goto done;

  if (!strcmp(a->command, "check")) {
    write_resolved(stdout, c, &run.params, m, scene);
    goto done;
  }

  /* run: the results folder is created only now, after the whole case validated */
  run.scase = c;
  run.vtk = strcmp(run.params.vtk_format, "ascii") ? SA_VTK_BINARY : SA_VTK_ASCII;
  run.threads = run.params.threads > 0 ? run.params.threads : (int)sysconf(_SC_NPROCESSORS_ONLN);
  if (run.threads < 1) run.threads = 1;
  if (a->out)
    snprintf(run.out_dir, sizeof run.out_dir, "%s", a->out);
  else if (run.params.out_dir[0])
    snprintf(run.out_dir, sizeof run.out_dir, "%s", run.params.out_dir);
  else
    snprintf(run.out_dir, sizeof run.out_dir, "results/%s", sa_case_stem(c));
  struct stat st;
  int made_dir = stat(run.out_dir, &st) != 0;
  rc = sa_mkdir_p(run.out_dir);
  if (rc) goto done;

  char path[SA_STR_MAX];
  SaFile *cf = NULL, *lf = NULL;
  rc = sa_run_path(&run, "case.ini", path);
  if (!rc) rc = sa_file_open(path, &cf);
  if (!rc) {
    write_resolved(sa_file_stream(cf), c, &run.params, m, scene);
    rc = sa_file_commit(&cf);
  }
  if (!rc) rc = sa_run_path(&run, "softact.log", path);
  if (!rc) rc = sa_file_open(path, &lf);
  if (rc) goto done;
  sa_log_set_file(sa_file_stream(lf));
  sa_signals_install();
  sa_log(SA_LOG_INFO, "core", "softact %s: %s (%s scene) -> %s", SOFTACT_VERSION, a->case_path, m->name,
         run.out_dir);
  double t0 = sa_time_now();
  rc = m->run(scene, &run);
  double elapsed = sa_time_now() - t0;
  if (rc == SA_ERR_INTERRUPTED || (sa_interrupted() && rc == 0)) {
    rc = SA_ERR_INTERRUPTED;
    sa_log(SA_LOG_WARN, "core", "interrupted by signal %d: results computed so far are kept in %s",
           sa_interrupt_signal(), run.out_dir);
  }
  if (sa_log_get_level() >= SA_LOG_INFO) sa_timing_report(stderr, elapsed);
  sa_timing_report(sa_file_stream(lf), elapsed);
  if (rc && rc != SA_ERR_INTERRUPTED) {
    fprintf(sa_file_stream(lf), "run failed: %s: %s\n", sa_error_string(rc), sa_error_message());
  }
  sa_log_set_file(NULL);
  if (rc < 0 && rc != SA_ERR_INTERRUPTED && sa_error_exit_status(rc) == 1) {
    /* bad input found only while running: leave nothing behind */
    sa_file_abort(&lf);
    sa_file_abort_all();
    static const char *created[] = {"case.ini"};
    remove_created(run.out_dir, made_dir, created, 1);
  } else {
    int rc2 = sa_file_commit(&lf);
    if (!rc) rc = rc2;
  }
done:
  sa_file_abort_all();
  if (m && scene) m->destroy(&scene);
  sa_case_destroy(&c);
  return rc;
}

int main(int argc, char **argv) {
  setvbuf(stderr, NULL, _IOLBF, 0);
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      usage(stdout);
      return 0;
    }
    if (!strcmp(argv[i], "--version")) {
      printf("softact %s\n", SOFTACT_VERSION);
      return 0;
    }
  }
  if (argc >= 2 && !strcmp(argv[1], "keys")) {
    const SaParamTable *seen[128];
    int ns = 0;
    sa_params_write_markdown(&sa_run_table, stdout);
    for (int i = 0; modules[i]; i++)
      for (int t = 0; t < modules[i]->ntables && ns < 128; t++) {
        const SaParamTable *tb = modules[i]->tables[t];
        if (table_seen(seen, ns, tb)) continue; /* shared by two scenes: listed once */
        seen[ns++] = tb;
        sa_params_write_markdown(tb, stdout);
      }
    return 0;
  }
  if (argc < 2) {
    usage(stderr);
    return 1;
  }
  Args a;
  int rc = parse_args(argc, argv, &a);
  if (!rc) rc = run_case(&a);
  if (rc) {
    if (rc == SA_ERR_INTERRUPTED)
      fprintf(stderr, "softact: interrupted; results computed so far are kept\n");
    else /* the call trace helps with a failure, not with a typo in a case file */
      sa_error_print_opt(sa_error_exit_status(rc) != 1 || sa_log_get_level() >= SA_LOG_DEBUG);
  }
  return sa_error_exit_status(rc);
}
