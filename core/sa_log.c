/* sa_log.c - logging and timing accumulators. */
#include "sa_log.h"

#include <pthread.h>
#include <stdarg.h>
#include <string.h>
#include <time.h>

static SaLogLevel sa_level = SA_LOG_INFO;
static FILE *sa_logfile;
static pthread_mutex_t sa_log_lock = PTHREAD_MUTEX_INITIALIZER;
static const char *sa_level_names[] = {"ERROR", "WARN", "INFO", "DEBUG"};

void sa_log_set_level(SaLogLevel level) { sa_level = level; }
SaLogLevel sa_log_get_level(void) { return sa_level; }
void sa_log_set_file(FILE *f) { sa_logfile = f; }
static int sa_bar_active;
void sa_log_bar_active(int active) { sa_bar_active = active; }

void sa_log(SaLogLevel level, const char *tag, const char *fmt, ...) {
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  pthread_mutex_lock(&sa_log_lock);
  if (level <= sa_level) {
    if (sa_bar_active) fputs("\r\033[K", stderr); /* the bar is redrawn on its next update */
    if (level <= SA_LOG_WARN)
      fprintf(stderr, "%s [%s] %s\n", sa_level_names[level], tag, buf);
    else
      fprintf(stderr, "[%s] %s\n", tag, buf);
  }
  if (sa_logfile) {
    fprintf(sa_logfile, "%-5s [%s] %s\n", sa_level_names[level], tag, buf);
    fflush(sa_logfile);
  }
  pthread_mutex_unlock(&sa_log_lock);
}

double sa_time_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double sa_cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define SA_TIMING_MAX 32
static struct {
  char name[32];
  double seconds;
  long calls;
} sa_timings[SA_TIMING_MAX];
static int sa_ntimings;

void sa_timing_add(const char *phase, double seconds) {
  pthread_mutex_lock(&sa_log_lock);
  int i;
  for (i = 0; i < sa_ntimings; i++)
    if (!strcmp(sa_timings[i].name, phase)) break;
  if (i == sa_ntimings && sa_ntimings < SA_TIMING_MAX) {
    snprintf(sa_timings[i].name, sizeof sa_timings[i].name, "%s", phase);
    sa_ntimings++;
  }
  if (i < SA_TIMING_MAX) {
    sa_timings[i].seconds += seconds;
    sa_timings[i].calls++;
  }
  pthread_mutex_unlock(&sa_log_lock);
}

void sa_timing_report(FILE *f, double total) {
  fprintf(f, "%-16s %12s %10s %7s\n", "phase", "seconds", "calls", "share");
  for (int i = 0; i < sa_ntimings; i++)
    fprintf(f, "%-16s %12.4f %10ld %6.1f%%\n", sa_timings[i].name, sa_timings[i].seconds,
            sa_timings[i].calls, total > 0 ? 100.0 * sa_timings[i].seconds / total : 0.0);
  fprintf(f, "%-16s %12.4f\n", "total", total);
}

void sa_timing_reset(void) { sa_ntimings = 0; }
