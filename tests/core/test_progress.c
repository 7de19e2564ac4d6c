/* test_progress.c - progress reports: nothing when quiet, a throttled redrawn bar on a
 * terminal, plain lines (about every 10 %, at most one per 5 s) otherwise; concurrent updates
 * from several threads.
 *
 * usage: test_progress WORKDIR       (takes about 6 s: it waits out the 5 s log period)
 * stderr is redirected (to a file, or to a pseudo-terminal for the TTY case) and read back. */
#define _XOPEN_SOURCE 700 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "sa_log.h"
#include "sa_output.h"
#include "test_util.h"

#define NTHREADS 4
#define PER_THREAD 20000

static int saved_stderr = -1;

static void redirect_stderr(int fd) {
  fflush(stderr);
  saved_stderr = dup(STDERR_FILENO);
  dup2(fd, STDERR_FILENO);
}

static void restore_stderr(void) {
  fflush(stderr);
  dup2(saved_stderr, STDERR_FILENO);
  close(saved_stderr);
}

static void sleep_s(double s) {
  struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
  while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
  }
}

static int count(const char *text, const char *sub) {
  int n = 0;
  for (const char *p = text; (p = strstr(p, sub)); p += strlen(sub)) n++;
  return n;
}

typedef struct {
  SaProgress *p;
  double pause; /* s between increments, 0 = none */
} Worker;

static void *work(void *arg) {
  Worker *w = arg;
  for (int i = 0; i < PER_THREAD; i++) {
    sa_progress_add(w->p, 1);
    if (w->pause > 0 && i % 1000 == 999) sleep_s(w->pause);
  }
  return NULL;
}

/* Runs NTHREADS workers on one progress; returns the elapsed time. */
static double run_threads(const char *label, double pause) {
  SaProgress *p = NULL;
  TU_OK(sa_progress_start(label, (long)NTHREADS * PER_THREAD, &p));
  double t0 = sa_time_now();
  pthread_t th[NTHREADS];
  Worker w = {p, pause};
  for (int i = 0; i < NTHREADS; i++) pthread_create(&th[i], NULL, work, &w);
  for (int i = 0; i < NTHREADS; i++) pthread_join(th[i], NULL);
  double dt = sa_time_now() - t0;
  sa_progress_finish(&p);
  TU_CHECK(p == NULL, "finish must null the handle");
  return dt;
}

/* Captures what fn writes to stderr into a file. [owned] */
static char *capture_file(const char *dir, const char *name, void (*fn)(void)) {
  char path[TU_PATH];
  tu_join(dir, name, path);
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return NULL;
  redirect_stderr(fd);
  fn();
  restore_stderr();
  close(fd);
  size_t n;
  return (char *)tu_slurp(path, &n);
}

static void quiet_run(void) {
  sa_log_set_level(SA_LOG_WARN);
  run_threads("quiet", 0.0);
  sa_log_set_level(SA_LOG_INFO);
}

static void fast_run(void) { run_threads("fast", 0.0); }

/* Slow: 80 pauses of 75 ms, 6 s in all; the 5 s period allows one intermediate line. */
static double slow_dt;
static void slow_run(void) {
  SaProgress *p = NULL;
  TU_OK(sa_progress_start("slow", 80, &p));
  slow_dt = sa_time_now();
  for (int i = 0; i < 80; i++) {
    sleep_s(0.075);
    sa_progress_update(p, i + 1);
  }
  slow_dt = sa_time_now() - slow_dt;
  sa_progress_finish(&p);
}

/* TTY: stderr on a pseudo-terminal; the bar is redrawn at most 10 times a second. */
static void test_tty(void) {
  int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) || unlockpt(master)) {
    printf("note: no pseudo-terminal, TTY case not tested\n");
    return;
  }
  int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
  TU_CHECK(slave >= 0, "cannot open the pty slave");
  if (slave < 0) return;
  redirect_stderr(slave);
  double dt = run_threads("tty", 0.02); /* 20 pauses of 20 ms per thread: ~0.4 s */
  restore_stderr();
  close(slave);
  char out[65536];
  size_t len = 0;
  fcntl(master, F_SETFL, O_NONBLOCK);
  ssize_t k;
  while (len < sizeof out - 1 && (k = read(master, out + len, sizeof out - 1 - len)) > 0)
    len += (size_t)k;
  out[len] = 0;
  close(master);
  int draws = count(out, "\033[K");
  /* One draw per 0.1 s at most, plus the final one (+1 for timer granularity). */
  int max_draws = (int)(dt / 0.1) + 2;
  TU_CHECK(draws >= 1 && draws <= max_draws, "%d redraws in %.2f s (allowed 1..%d):\n%s", draws,
           dt, max_draws, out);
  char total[64];
  snprintf(total, sizeof total, "%d/%d", NTHREADS * PER_THREAD, NTHREADS * PER_THREAD);
  TU_CHECK(strstr(out, "100%") && strstr(out, total), "final bar lacks 100%% and %s:\n%s", total,
           out);
  TU_CHECK(len > 0 && (out[len - 1] == '\n'), "the bar is not ended by a newline");
}

int main(int argc, char **argv) {
  char dir[TU_PATH];
  if (tu_fresh_dir(argc, argv, "progress", dir)) return 1;
  sa_log_set_level(SA_LOG_INFO);

  char *out = capture_file(dir, "quiet.txt", quiet_run);
  TU_CHECK(out && !out[0], "quiet run printed:\n%s", out ? out : "(unreadable)");
  free(out);

  /* A phase shorter than the 5 s period prints nothing, however many updates. */
  out = capture_file(dir, "fast.txt", fast_run);
  TU_CHECK(out && !out[0], "a fast phase printed:\n%s", out ? out : "(unreadable)");
  free(out);

  test_tty();

  out = capture_file(dir, "slow.txt", slow_run);
  TU_CHECK(out, "slow.txt unreadable");
  if (out) {
    int lines = count(out, "\n"), pct = count(out, "%");
    /* One line per 5 s at most: floor(6 s / 5 s) = 1 intermediate line, then "done". */
    int max_lines = (int)(slow_dt / 5.0) + 1;
    TU_CHECK(pct >= 1 && lines <= max_lines && strstr(out, "slow: done, 80/80"),
             "slow phase (%.2f s) printed %d lines (allowed %d), expected percentages and a final "
             "\"done, 80/80\":\n%s",
             slow_dt, lines, max_lines, out);
    TU_CHECK(!strchr(out, '\r') && !strchr(out, '\033'), "non-TTY output has control characters");
  }
  free(out);
  return tu_result();
}
