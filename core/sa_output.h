/* sa_output.h - results folder, atomic files and clean interruption.
 *
 * Atomic files: sa_file_open writes to a hidden temporary name beside the target
 * (".NAME.tmp.PID"); sa_file_commit flushes, checks for write errors and renames it onto the
 * target, so a reader never sees a truncated result. Open temporaries are registered: a
 * failed run (sa_file_abort_all, called by main) or a second signal removes them.
 *
 * Signals: sa_signals_install() makes SIGINT/SIGTERM/SIGHUP/SIGPIPE set a flag; long loops
 * poll sa_interrupted() (often enough to answer within about a second), commit what they
 * computed, and return SA_ERR_INTERRUPTED. A second signal (not SIGPIPE, which our own writes
 * to a closed stderr raise) kills and reaps registered children, removes their and our open
 * temporaries and exits at once with status 3. */
#ifndef SA_OUTPUT_H
#define SA_OUTPUT_H

#include <stdio.h>

typedef struct SaFile SaFile;

int sa_file_open(const char *path, SaFile **out); /* binary-safe "wb" stream */
FILE *sa_file_stream(SaFile *f);                  /* [borrowed] */
const char *sa_file_target(const SaFile *f);
int sa_file_commit(SaFile **f);                   /* flush, close, rename; *f = NULL */
void sa_file_abort(SaFile **f);                   /* close, remove temporary; *f = NULL */
void sa_file_abort_all(void);                     /* remove every open temporary */

void sa_signals_install(void);
int sa_interrupted(void);                         /* non-zero once a signal arrived */
int sa_interrupt_signal(void);                    /* which signal (0 if none) */
/* A child process pid [in] writing temporary file temp [in, copied; may be NULL] is killed,
 * reaped and its temporary removed by a second signal. Returns a slot (-1: table full, the
 * child is then not watched) for sa_signals_child_remove, to call once the child is reaped. */
int sa_signals_child_add(long pid, const char *temp);
void sa_signals_child_remove(int slot);

/* mkdir -p. */
int sa_mkdir_p(const char *path);

/* The results folder of one run. A folder never holds files of two runs, and softact never
 * writes into or removes a folder it did not make a run folder:
 *   - dir missing or empty: the run writes into it (creating it and its parents); if the run
 *     fails on bad input everything it made is removed again.
 *   - dir holds an earlier softact run (its case.ini starts with SA_RESULTS_MARK): the run
 *     writes into a fresh sibling "DIR.incomplete-PID" that replaces DIR as a whole when the
 *     run ends with results (done, numerical failure, interrupted); a run that fails on bad
 *     input leaves DIR as it was. A run killed outright leaves the sibling behind.
 *   - continue_run (a checkpoint resume) and dir holds an earlier run: the run writes into DIR
 *     itself, since it continues those files; the caller keeps DIR's case.ini until the end.
 *   - anything else (a file, a folder with other content, a name too long): SA_ERR_INPUT,
 *     before anything is created or changed. */
#define SA_RESULTS_MARK "; resolved case of"
#define SA_RESULTS_DIR_MAX 384 /* leaves room in SA_STR_MAX for the sibling suffix and file names */
typedef struct SaResults SaResults;
int sa_results_open(const char *dir, int continue_run, SaResults **out);
const char *sa_results_work(const SaResults *r); /* where the run writes now */
const char *sa_results_dir(const SaResults *r);  /* the folder the results end up in */
int sa_results_in_place(const SaResults *r);     /* the run writes into an earlier run's folder */
/* keep: 1 the run's files become DIR; 0 (bad input found while running) they are removed and
 * DIR is as before. Commit or abort every SaFile first. Frees *r and sets it NULL. */
int sa_results_close(SaResults **r, int keep);
/* Join dir and name into buf (size SA_STR_MAX); error if it does not fit. */
int sa_path_join(const char *dir, const char *name, char *buf);

/* Progress on stderr: one updating bar with ETA on a TTY, a plain line every ~10 % (and at
 * most every 5 s) otherwise, nothing when the log level is below INFO (--quiet).
 * sa_progress_update is thread-safe. */
typedef struct SaProgress SaProgress;
int sa_progress_start(const char *label, long total, SaProgress **out);
void sa_progress_update(SaProgress *p, long done);
void sa_progress_add(SaProgress *p, long increment);
void sa_progress_finish(SaProgress **p);

#endif
