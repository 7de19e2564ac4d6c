/* sa_log.h - levelled logging to stderr (for people) and to the run's log file, plus a
 * wall-clock timer and named timing accumulators for the end-of-run timing table. */
#ifndef SA_LOG_H
#define SA_LOG_H

#include <stdio.h>

typedef enum { SA_LOG_ERROR = 0, SA_LOG_WARN, SA_LOG_INFO, SA_LOG_DEBUG } SaLogLevel;

/* Level shown on stderr (default INFO; --quiet sets WARN, --verbose DEBUG). */
void sa_log_set_level(SaLogLevel level);
SaLogLevel sa_log_get_level(void);
/* Also copy every message (all levels up to DEBUG) to this file [borrowed]; NULL stops. */
void sa_log_set_file(FILE *f);
/* Log with a module tag, e.g. sa_log(SA_LOG_INFO, "fem", "step %d", k). */
void sa_log(SaLogLevel level, const char *tag, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* A progress bar is drawn on the terminal's current line: log lines first clear it. */
void sa_log_bar_active(int active);

/* Monotonic wall time in seconds. */
double sa_time_now(void);

/* CPU time of this process (user + system, all threads) in seconds: the cost of a run on a
 * machine shared with other jobs, where wall time depends on their load. */
double sa_cpu_time(void);

/* Named accumulators: sa_timing_add("assemble", dt). Printed by sa_timing_report as a table
 * "phase  seconds  calls  share". Thread-safe. */
void sa_timing_add(const char *phase, double seconds);
void sa_timing_report(FILE *f, double total_seconds);
void sa_timing_reset(void);

#endif
