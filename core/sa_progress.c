/* sa_progress.c - progress reports on stderr (sa_output.h).
 *
 * TTY: one line redrawn in place ("\r" ... erase to end of line), at most 10 times a second:
 *     label [##########..........]  50%  500/1000  ETA 12s
 * Otherwise (log files, CI): a plain line through sa_log each time another 10 % is done, but
 * at most one line per 5 s, so short phases print nothing and long ones about ten lines.
 * A phase that printed anything ends with a final "done" line. Nothing is printed when the
 * log level is below INFO (--quiet). The ETA extrapolates the mean rate since the start.
 * Updates from several threads are serialised by a mutex. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"

#define SA_PROGRESS_TTY_PERIOD 0.1 /* s between redraws of the bar */
#define SA_PROGRESS_LOG_PERIOD 5.0 /* s between plain lines */
#define SA_PROGRESS_BAR 24         /* bar width in characters */

struct SaProgress {
  pthread_mutex_t lock;
  char label[64];
  long total, done; /* total <= 0: unknown */
  double t0, t_last; /* start, last output */
  int enabled, tty, printed;
  long last_tenth; /* non-TTY: last 10 % step reported */
};

static void sa_progress_duration(double s, char *buf, size_t size) {
  if (s < 0) s = 0;
  long t = (long)(s + 0.5);
  if (s < 9.95)
    snprintf(buf, size, "%.1fs", s);
  else if (t < 60)
    snprintf(buf, size, "%lds", t);
  else if (t < 3600)
    snprintf(buf, size, "%ldm%02lds", t / 60, t % 60);
  else
    snprintf(buf, size, "%ldh%02ldm", t / 3600, (t % 3600) / 60);
}

/* Draws (TTY) or logs the current state; final = the phase is over. p->lock is held. */
static void sa_progress_emit(SaProgress *p, double now, int final) {
  long done = p->done, total = p->total;
  if (total > 0 && done > total) done = total;
  double elapsed = now - p->t0;
  char tel[32], teta[32];
  sa_progress_duration(elapsed, tel, sizeof tel);
  teta[0] = 0;
  if (total > 0 && done > 0 && !final)
    sa_progress_duration(elapsed * (double)(total - done) / (double)done, teta, sizeof teta);
  int pct = total > 0 ? (int)(100.0 * (double)done / (double)total) : 0;

  if (p->tty) {
    char line[256], bar[SA_PROGRESS_BAR + 1];
    if (total > 0) {
      int fill = (int)((double)SA_PROGRESS_BAR * (double)done / (double)total);
      for (int i = 0; i < SA_PROGRESS_BAR; i++) bar[i] = i < fill ? '#' : '.';
      bar[SA_PROGRESS_BAR] = 0;
      snprintf(line, sizeof line, "\r%s [%s] %3d%%  %ld/%ld  %s %s\033[K%s", p->label, bar, pct,
               done, total, final ? "in" : "ETA", final ? tel : (teta[0] ? teta : "?"),
               final ? "\n" : "");
    } else {
      snprintf(line, sizeof line, "\r%s  %ld  %s\033[K%s", p->label, done, tel, final ? "\n" : "");
    }
    fputs(line, stderr);
    fflush(stderr);
    sa_log_bar_active(!final);
  } else if (final) {
    if (total > 0)
      sa_log(SA_LOG_INFO, "progress", "%s: done, %ld/%ld in %s", p->label, done, total, tel);
    else
      sa_log(SA_LOG_INFO, "progress", "%s: done, %ld in %s", p->label, done, tel);
  } else if (total > 0) {
    sa_log(SA_LOG_INFO, "progress", "%s: %d%% (%ld/%ld), elapsed %s, ETA %s", p->label, pct, done,
           total, tel, teta[0] ? teta : "?");
  } else {
    sa_log(SA_LOG_INFO, "progress", "%s: %ld, elapsed %s", p->label, done, tel);
  }
  p->t_last = now;
  p->printed = 1;
}

/* Decides whether the new state is worth a line. p->lock is held. */
static void sa_progress_maybe(SaProgress *p) {
  double now = sa_time_now();
  if (p->tty) {
    if (now - p->t_last >= SA_PROGRESS_TTY_PERIOD) sa_progress_emit(p, now, 0);
    return;
  }
  if (now - p->t_last < SA_PROGRESS_LOG_PERIOD) return;
  if (p->total > 0) {
    long tenth = (long)(10.0 * (double)p->done / (double)p->total);
    if (tenth <= p->last_tenth) return;
    p->last_tenth = tenth;
  }
  sa_progress_emit(p, now, 0);
}

int sa_progress_start(const char *label, long total, SaProgress **out) {
  SA_REQUIRE(out, SA_ERR_INPUT, "sa_progress_start: NULL output handle");
  *out = NULL;
  SaProgress *p;
  SA_CALLOC(p, 1);
  if (pthread_mutex_init(&p->lock, NULL) != 0) {
    free(p);
    return SA_ERROR(SA_ERR_LIBRARY, "pthread_mutex_init failed");
  }
  snprintf(p->label, sizeof p->label, "%s", label && label[0] ? label : "progress");
  for (char *c = p->label; *c; c++)
    if (*c == '\n' || *c == '\r') *c = ' ';
  p->total = total > 0 ? total : 0;
  p->enabled = sa_log_get_level() >= SA_LOG_INFO;
  p->tty = isatty(STDERR_FILENO);
  p->t0 = p->t_last = sa_time_now();
  *out = p;
  return 0;
}

void sa_progress_update(SaProgress *p, long done) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  p->done = done;
  if (p->enabled) sa_progress_maybe(p);
  pthread_mutex_unlock(&p->lock);
}

void sa_progress_add(SaProgress *p, long increment) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  p->done += increment;
  if (p->enabled) sa_progress_maybe(p);
  pthread_mutex_unlock(&p->lock);
}

void sa_progress_finish(SaProgress **pp) {
  if (!pp || !*pp) return;
  SaProgress *p = *pp;
  pthread_mutex_lock(&p->lock);
  if (p->enabled && p->printed) sa_progress_emit(p, sa_time_now(), 1);
  pthread_mutex_unlock(&p->lock);
  pthread_mutex_destroy(&p->lock);
  free(p);
  *pp = NULL;
}
