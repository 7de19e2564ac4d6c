/* softact - command-line front end: parse arguments, load the case, hand it to the module
 * whose section it contains, map the result to an exit status. The physics lives in the
 * modules; this file only wires them (see docs/architecture.md). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fem_blas.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_module.h"
#include "sa_output.h"
#include "sa_params.h"
#include "sa_run.h"

#include "softact_scene.h"

#ifndef SOFTACT_VERSION
#define SOFTACT_VERSION "unknown"
#endif

static void usage(FILE *f) {
  fprintf(f,
          "usage: softact run CASE.ini [--set section.key=value ...] [--out DIR] [--quiet|--verbose]\n"
          "       softact check CASE.ini [--set section.key=value ...]\n"
          "       softact keys            (reference of every case key, Markdown)\n"
          "       softact --help | --version\n"
          "\n"
          "  run     validate the case, then compute it; results go to DIR (default: [run] out_dir,\n"
          "          else results/<case name>): case.ini (resolved case), softact.log, CSV, PNG, VTK;\n"
          "          DIR is new, empty or an earlier softact run, which the run replaces when it ends\n"
          "  check   validate the case and print it fully resolved (defaults filled in); run nothing\n"
          "\n"
          "scenes (the section that selects each):\n");
  for (int i = 0; softact_modules[i]; i++)
    fprintf(f, "  [%s]  %s\n", softact_modules[i]->trigger, softact_modules[i]->help);
  fprintf(f,
          "\nexit status: 0 ok, 1 bad input (case file, arguments), 2 numerical failure\n"
          "(no convergence, inverted element, limit point, NaN), 3 interrupted (SIGINT, SIGTERM,\n"
          "SIGHUP, SIGPIPE; results computed so far are kept), 4 I/O, memory or library failure.\n");
}

typedef struct {
  const char *command, *case_path, *out;
  const char *sets[256];
  int nsets;
  int argc;
  char **argv; /* the command line as given (a relaunch under mpirun repeats it) */
} Args;

static int parse_args(int argc, char **argv, Args *a) {
  memset(a, 0, sizeof *a);
  a->argc = argc, a->argv = argv;
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

/* Flush standard output and report a failed write (a full disk, a closed pipe): a listing that
 * was cut must not exit 0. */
static int stdout_flush(void) {
  SA_REQUIRE(fflush(stdout) == 0 && !ferror(stdout), SA_ERR_IO, "cannot write to standard output: %s",
             strerror(errno));
  return 0;
}

/* The rank and size mpirun gives this process in the environment (Open MPI, then MPICH's PMI):
 * read, never initialised here, so that a scene without particles never starts MPI. */
static void launcher_rank(int *rank, int *size) {
  const char *r = getenv("OMPI_COMM_WORLD_RANK"), *n = getenv("OMPI_COMM_WORLD_SIZE");
  if (!r || !n) r = getenv("PMI_RANK"), n = getenv("PMI_SIZE");
  *rank = r ? atoi(r) : 0;
  *size = n ? atoi(n) : 1;
  if (*size < 1) *size = 1;
}

/* This program again, under `mpirun -np n --bind-to none` with the same arguments: the scene
 * asked for n MPI ranks (sa_module.h `ranks`). No binding: rank 0's FEM threads use every core
 * while the other ranks wait. Open MPI refuses root unless told: a container's root is the
 * usual case here, so the two variables that say so are set (never overriding a user's).
 * Signals: mpirun answers SIGINT/SIGTERM by killing its ranks (SIGTERM, then SIGKILL a moment
 * later, its own output relay already closing), which would lose the interrupted run's
 * checkpoint and summary. So mpirun runs as a child in its own process group (a terminal's ^C
 * reaches only this process), without stdin, and this process passes SIGINT, SIGTERM and
 * SIGHUP on as SIGUSR1, which mpirun forwards to every rank, where it stops the run like
 * SIGINT (sa_signals_install). Exits with mpirun's status (rank 0's: 3 when interrupted).
 * Returns only if mpirun could not be started. */
static volatile sig_atomic_t mpirun_pid;

static void pass_signal_to_mpirun(int sig) {
  (void)sig;
  if (mpirun_pid > 0) kill((pid_t)mpirun_pid, SIGUSR1);
}

static int relaunch_under_mpirun(const Args *a, int n) {
  /* more ranks than cores: mpirun would refuse (no slots), and ranks that share a core spin
   * against each other in every collective */
  long cores = sysconf(_SC_NPROCESSORS_ONLN);
  SA_REQUIRE(cores < 1 || n <= cores, SA_ERR_INPUT, "%s: [dem] mpi_ranks = %d is more than the %ld "
             "cores of this machine (allowed: 1..%ld)", a->case_path, n, cores, cores);
  char exe[4096];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  SA_REQUIRE(len > 0, SA_ERR_IO, "cannot find this program's path to start it under mpirun");
  exe[len] = 0;
  char np[16];
  snprintf(np, sizeof np, "%d", n);
  char **v = calloc((size_t)a->argc + 10, sizeof *v);
  SA_REQUIRE(v, SA_ERR_MEMORY, "cannot allocate the mpirun command line");
  int k = 0;
  v[k++] = "mpirun", v[k++] = "-np", v[k++] = np, v[k++] = "--bind-to", v[k++] = "none";
  v[k++] = "--stdin", v[k++] = "none", v[k++] = exe;
  for (int i = 1; i < a->argc; i++) v[k++] = a->argv[i];
  v[k] = NULL;
  if (geteuid() == 0) {
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  }
  sa_log(SA_LOG_INFO, "core", "%s asks for %d MPI ranks: starting mpirun -np %d --bind-to none %s",
         a->case_path, n, n, exe);
  fflush(stdout);
  fflush(stderr);
  int pipefd[2]; /* the child reports a failed exec through it (close-on-exec) */
  SA_REQUIRE(pipe(pipefd) == 0, SA_ERR_IO, "cannot start mpirun: %s", strerror(errno));
  fcntl(pipefd[1], F_SETFD, FD_CLOEXEC);
  pid_t pid = fork();
  if (pid < 0) {
    free(v);
    return SA_ERROR(SA_ERR_IO, "cannot start mpirun: %s", strerror(errno));
  }
  if (pid == 0) {
    close(pipefd[0]);
    setpgid(0, 0);
    signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL), signal(SIGHUP, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);
    execvp("mpirun", v);
    int e = errno;
    ssize_t w = write(pipefd[1], &e, sizeof e);
    (void)w;
    _exit(127);
  }
  close(pipefd[1]);
  free(v);
  int e = 0;
  ssize_t got;
  while ((got = read(pipefd[0], &e, sizeof e)) < 0 && errno == EINTR) {
  }
  close(pipefd[0]);
  if (got == (ssize_t)sizeof e) {
    while (waitpid(pid, NULL, 0) < 0 && errno == EINTR) {
    }
    return SA_ERROR(SA_ERR_LIBRARY, "%s: [dem] mpi_ranks = %d, but mpirun cannot be started "
                    "(%s): install Debian's openmpi-bin, or set mpi_ranks = 1", a->case_path, n,
                    strerror(e));
  }
  mpirun_pid = pid;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = pass_signal_to_mpirun;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL), sigaction(SIGTERM, &sa, NULL), sigaction(SIGHUP, &sa, NULL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  fflush(stdout);
  exit(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
}

static int run_case(const Args *a) {
  SaCase *c = NULL;
  void *scene = NULL;
  const SaModule *m = NULL;
  SaRun run;
  memset(&run, 0, sizeof run);
  int rc = sa_case_load(a->case_path, &c);
  for (int i = 0; !rc && i < a->nsets; i++) rc = sa_case_override(c, a->sets[i]);
  if (!rc) rc = softact_case_validate(c, &run.params, &m, &scene);
  if (rc) goto done;

  if (!strcmp(a->command, "check")) {
    softact_write_resolved(stdout, c, &run.params, m, scene);
    rc = stdout_flush();
    goto done;
  }

  /* several MPI ranks: rank 0 runs the scene; the others only follow it (sa_module.h) */
  int rank, size;
  launcher_rank(&rank, &size);
  if (size > 1 && !m->follow) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: the %s scene runs on one process; start it without mpirun "
                  "(only the FEM-DEM scene uses several MPI ranks)", a->case_path, m->name);
    goto done;
  }
  int wanted = m->ranks ? m->ranks(scene) : 1;
  if (size == 1 && wanted > 1) {
    rc = relaunch_under_mpirun(a, wanted); /* only on failure */
    goto done;
  }
  if (size > 1 && rank > 0) {
    sa_log_set_level(SA_LOG_WARN); /* rank 0 reports the run */
    rc = m->follow(scene);
    goto done;
  }

  /* run: the results folder is created only now, after the whole case validated; see
   * sa_results_open for what happens to an existing folder */
  run.scase = c;
  run.vtk = strcmp(run.params.vtk_format, "ascii") ? SA_VTK_BINARY : SA_VTK_ASCII;
  run.threads = run.params.threads > 0 ? run.params.threads : (int)sysconf(_SC_NPROCESSORS_ONLN);
  if (run.threads < 1) run.threads = 1;
  char stem_dir[SA_STR_MAX];
  snprintf(stem_dir, sizeof stem_dir, "results/%s", sa_case_stem(c));
  const char *out = a->out ? a->out : run.params.out_dir[0] ? run.params.out_dir : stem_dir;
  SaResults *res = NULL;
  rc = sa_results_open(out, m->resumes && m->resumes(scene), &res);
  if (rc) goto done;
  snprintf(run.out_dir, sizeof run.out_dir, "%s", sa_results_work(res));
  const char *final_dir = sa_results_dir(res);

  /* A resumed run keeps the folder's case.ini until it ends: if the resume is refused (bad
   * input), the folder must still describe the run it holds. */
  int in_place = sa_results_in_place(res);
  char path[SA_STR_MAX];
  SaFile *cf = NULL, *lf = NULL;
  rc = sa_run_path(&run, "case.ini", path);
  if (!rc) rc = sa_file_open(path, &cf);
  if (!rc) {
    softact_write_resolved(sa_file_stream(cf), c, &run.params, m, scene);
    if (!in_place) rc = sa_file_commit(&cf);
  }
  if (!rc) rc = sa_run_path(&run, "softact.log", path);
  if (!rc) rc = sa_file_open(path, &lf);
  int ran = !rc;
  if (ran) {
    sa_log_set_file(sa_file_stream(lf));
    if (strcmp(final_dir, run.out_dir))
      sa_log(SA_LOG_INFO, "core", "softact %s: %s (%s scene) -> %s (written in %s until the run ends; "
             "then it replaces the earlier run there)", SOFTACT_VERSION, a->case_path, m->name, final_dir,
             run.out_dir);
    else
      sa_log(SA_LOG_INFO, "core", "softact %s: %s (%s scene) -> %s", SOFTACT_VERSION, a->case_path, m->name,
             final_dir);
    double t0 = sa_time_now();
    rc = m->run(scene, &run);
    double elapsed = sa_time_now() - t0;
    if (rc == SA_ERR_INTERRUPTED || (sa_interrupted() && rc == 0)) {
      rc = SA_ERR_INTERRUPTED;
      sa_log(SA_LOG_WARN, "core", "interrupted by signal %d: results computed so far are kept in %s",
             sa_interrupt_signal(), final_dir);
    }
    if (sa_log_get_level() >= SA_LOG_INFO) sa_timing_report(stderr, elapsed);
    sa_timing_report(sa_file_stream(lf), elapsed);
    if (rc && rc != SA_ERR_INTERRUPTED)
      fprintf(sa_file_stream(lf), "run failed: %s: %s\n", sa_error_string(rc), sa_error_message());
    sa_log_set_file(NULL);
  }
  /* A run that computed something keeps it (done, numerical failure, interrupted). Bad input
   * found only while running (a .geo syntax error, a missing surface), or a run that never
   * started, leaves nothing behind, and an earlier run in the folder stays as it was. */
  int keep = ran && !(rc < 0 && rc != SA_ERR_INTERRUPTED && sa_error_exit_status(rc) == 1);
  if (keep) {
    int rc2 = sa_file_commit(&cf);
    int rc3 = sa_file_commit(&lf);
    if (!rc) rc = rc2 ? rc2 : rc3;
  } else {
    sa_file_abort(&cf);
    sa_file_abort(&lf);
  }
  sa_file_abort_all(); /* nothing may be half-written when the folder is swapped or removed */
  int rc4 = sa_results_close(&res, keep);
  if (!rc) rc = rc4;
done:
  sa_file_abort_all();
  if (m && scene) m->destroy(&scene);
  sa_case_destroy(&c);
  return rc;
}

int main(int argc, char **argv) {
  /* OpenBLAS' generic kernels on a CPU it does not recognise: re-run with the right ones
   * (fem_blas.h; before anything else, since the process image is replaced) */
  fem_blas_select_kernels(argv);
  /* Handlers first: a signal that arrives while the case loads (start-up takes ~0.25 s) must
   * stop the run cleanly, not kill the process with the default action. */
  sa_signals_install();
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
    softact_write_keys(stdout);
    int rc = stdout_flush();
    if (rc) sa_error_print_opt(0);
    return sa_error_exit_status(rc);
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
