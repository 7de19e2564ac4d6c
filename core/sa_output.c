/* sa_output.c - atomic files, folders, results folders and clean interruption (see sa_output.h). */
#define _GNU_SOURCE /* renameat2 (swap a finished run's folder in), nftw */
#include "sa_output.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sa_error.h"
#include "sa_params.h"

struct SaFile {
  FILE *fp;
  char target[SA_STR_MAX];
  char temp[SA_STR_MAX + 48];
  int dead; /* closed and removed by sa_file_abort_all; the owner still frees it */
  struct SaFile *next;
};

/* Registry of open temporaries. The signal handler walks it with unlink(), which is
 * async-signal-safe; additions and removals are serialised by a mutex and the handler only
 * runs the second-signal path, after which the process exits. */
static struct SaFile *sa_open_files;
static pthread_mutex_t sa_files_lock = PTHREAD_MUTEX_INITIALIZER;
static volatile sig_atomic_t sa_signal_seen;

static void sa_file_unregister(SaFile *f) {
  pthread_mutex_lock(&sa_files_lock);
  for (SaFile **p = &sa_open_files; *p; p = &(*p)->next)
    if (*p == f) {
      *p = f->next;
      break;
    }
  pthread_mutex_unlock(&sa_files_lock);
}

int sa_file_open(const char *path, SaFile **out) {
  *out = NULL;
  SaFile *f;
  SA_CALLOC(f, 1);
  size_t n = strlen(path);
  if (n >= sizeof f->target) {
    free(f);
    return SA_ERROR(SA_ERR_INPUT, "path too long: %s", path);
  }
  memcpy(f->target, path, n + 1);
  const char *slash = strrchr(path, '/');
  int dirlen = slash ? (int)(slash - path + 1) : 0;
  /* pid + counter: unique across processes and across writers within this process */
  static long counter;
  pthread_mutex_lock(&sa_files_lock);
  long k = ++counter;
  pthread_mutex_unlock(&sa_files_lock);
  snprintf(f->temp, sizeof f->temp, "%.*s.%s.tmp.%ld.%ld", dirlen, path, path + dirlen, (long)getpid(), k);
  f->fp = fopen(f->temp, "wb");
  if (!f->fp) {
    int e = errno;
    free(f);
    return SA_ERROR(SA_ERR_IO, "cannot create %s: %s", path, strerror(e));
  }
  pthread_mutex_lock(&sa_files_lock);
  f->next = sa_open_files;
  sa_open_files = f;
  pthread_mutex_unlock(&sa_files_lock);
  *out = f;
  return 0;
}

FILE *sa_file_stream(SaFile *f) { return f->fp; }
const char *sa_file_target(const SaFile *f) { return f->target; }

int sa_file_commit(SaFile **fp) {
  SaFile *f = *fp;
  if (!f) return 0;
  *fp = NULL;
  if (f->dead) {
    int rc = SA_ERROR(SA_ERR_IO, "%s was abandoned before it was complete", f->target);
    free(f);
    return rc;
  }
  int bad = fflush(f->fp) != 0 || ferror(f->fp);
  int e = errno;
  bad |= fclose(f->fp) != 0;
  sa_file_unregister(f);
  if (bad) {
    unlink(f->temp);
    int rc = SA_ERROR(SA_ERR_IO, "writing %s failed: %s", f->target, strerror(e));
    free(f);
    return rc;
  }
  if (rename(f->temp, f->target) != 0) {
    e = errno;
    unlink(f->temp);
    int rc = SA_ERROR(SA_ERR_IO, "cannot rename onto %s: %s", f->target, strerror(e));
    free(f);
    return rc;
  }
  free(f);
  return 0;
}

void sa_file_abort(SaFile **fp) {
  SaFile *f = *fp;
  if (!f) return;
  *fp = NULL;
  if (f->dead) {
    free(f);
    return;
  }
  fclose(f->fp);
  unlink(f->temp);
  sa_file_unregister(f);
  free(f);
}

/* Close and remove every open temporary. The handles stay allocated (marked dead) because
 * writer objects still own them; their later abort/commit frees them. */
void sa_file_abort_all(void) {
  pthread_mutex_lock(&sa_files_lock);
  for (SaFile *f = sa_open_files; f; f = f->next) {
    fclose(f->fp);
    f->fp = NULL;
    unlink(f->temp);
    f->dead = 1;
  }
  sa_open_files = NULL;
  pthread_mutex_unlock(&sa_files_lock);
}

/* Child processes (gnuplot) that must not outlive a second signal: the handler kills and
 * reaps them and removes the temporary each was writing, else the child would write it after
 * softact has gone. Slots are claimed under sa_files_lock; the handler only reads them. */
#define SA_CHILD_MAX 8
static struct {
  volatile sig_atomic_t pid; /* 0: free */
  char temp[SA_STR_MAX + 64];
} sa_children[SA_CHILD_MAX];

int sa_signals_child_add(long pid, const char *temp) {
  pthread_mutex_lock(&sa_files_lock);
  int slot = -1;
  for (int i = 0; i < SA_CHILD_MAX && slot < 0; i++)
    if (!sa_children[i].pid) slot = i;
  if (slot >= 0) {
    snprintf(sa_children[slot].temp, sizeof sa_children[slot].temp, "%s", temp ? temp : "");
    atomic_thread_fence(memory_order_seq_cst); /* the handler sees the name before the pid */
    sa_children[slot].pid = (sig_atomic_t)pid;
  }
  pthread_mutex_unlock(&sa_files_lock);
  return slot;
}

void sa_signals_child_remove(int slot) {
  if (slot < 0 || slot >= SA_CHILD_MAX) return;
  pthread_mutex_lock(&sa_files_lock);
  sa_children[slot].pid = 0;
  pthread_mutex_unlock(&sa_files_lock);
}

static void sa_on_signal(int sig) {
  if (sa_signal_seen) {
    /* SIGPIPE after the first signal comes from our own writes to a closed stderr (the
     * reader went away), not from a user who insists: keep shutting down cleanly. */
    if (sig == SIGPIPE) return;
    /* Second signal: the user insists. End the children (a gnuplot left running would write
     * its temporary after we are gone), remove temporaries and leave at once. */
    for (int i = 0; i < SA_CHILD_MAX; i++) {
      pid_t pid = (pid_t)sa_children[i].pid;
      if (pid <= 0) continue;
      atomic_thread_fence(memory_order_seq_cst);
      kill(pid, SIGKILL);
      while (waitpid(pid, NULL, 0) < 0 && errno == EINTR) {
      }
      if (sa_children[i].temp[0]) unlink(sa_children[i].temp);
    }
    for (SaFile *f = sa_open_files; f; f = f->next) unlink(f->temp);
    static const char msg[] = "\nsoftact: second signal, stopped at once\n";
    ssize_t rc = write(2, msg, sizeof msg - 1);
    (void)rc;
    _exit(3);
  }
  sa_signal_seen = sig;
}

/* SIGHUP (terminal closed) and SIGPIPE (stderr piped into a reader that quit, e.g. `| head`)
 * end a run like SIGINT/SIGTERM: the results computed so far are committed. Without a handler
 * they would kill the process and leave the temporaries. With SIGPIPE handled, a write to a
 * closed pipe fails with EPIPE instead of killing us; stdio then just records the error. */
void sa_signals_install(void) {
  /* SIGUSR1: what a softact that started mpirun passes on for SIGINT/SIGTERM/SIGHUP (mpirun
   * forwards it to every rank; apps/softact.c relaunch_under_mpirun) */
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGUSR1};
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = sa_on_signal;
  sigemptyset(&sa.sa_mask);
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) sigaddset(&sa.sa_mask, sigs[i]);
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) sigaction(sigs[i], &sa, NULL);
}

int sa_interrupted(void) { return sa_signal_seen != 0; }
int sa_interrupt_signal(void) { return (int)sa_signal_seen; }

int sa_mkdir_p(const char *path) {
  char buf[SA_STR_MAX];
  size_t n = strlen(path);
  SA_REQUIRE(n > 0 && n < sizeof buf, SA_ERR_INPUT, "bad folder name '%s'", path);
  memcpy(buf, path, n + 1);
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = 0;
    if (mkdir(buf, 0777) != 0 && errno != EEXIST)
      return SA_ERROR(SA_ERR_IO, "cannot create folder %s: %s", buf, strerror(errno));
    *p = '/';
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST)
    return SA_ERROR(SA_ERR_IO, "cannot create folder %s: %s", buf, strerror(errno));
  struct stat st;
  SA_REQUIRE(stat(buf, &st) == 0 && S_ISDIR(st.st_mode), SA_ERR_IO, "%s is not a folder", buf);
  return 0;
}

int sa_path_join(const char *dir, const char *name, char *buf) {
  int n = (dir && dir[0]) ? snprintf(buf, SA_STR_MAX, "%s/%s", dir, name)
                          : snprintf(buf, SA_STR_MAX, "%s", name);
  SA_REQUIRE(n > 0 && n < SA_STR_MAX, SA_ERR_INPUT, "path too long: %s/%s", dir, name);
  return 0;
}

/* ------------------------------------------------------------------ results folder */

typedef enum { SA_RESULTS_FRESH, SA_RESULTS_STAGED, SA_RESULTS_IN_PLACE } SaResultsMode;

struct SaResults {
  SaResultsMode mode;
  char dir[SA_STR_MAX];     /* the results folder */
  char work[SA_STR_MAX];    /* where the run writes: dir, or its sibling while staged */
  char created[SA_STR_MAX]; /* FRESH: the topmost folder of dir's path this run made ("" none) */
};

/* Does folder dir hold a run written by softact (a case.ini starting with the mark)? */
static int sa_results_is_run(const char *dir) {
  char path[SA_STR_MAX + 16], head[sizeof SA_RESULTS_MARK] = "";
  snprintf(path, sizeof path, "%s/case.ini", dir);
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return 0;
  struct stat st;
  int ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
           read(fd, head, sizeof head - 1) == (ssize_t)(sizeof head - 1) &&
           !memcmp(head, SA_RESULTS_MARK, sizeof head - 1);
  close(fd);
  return ok;
}

/* 1 if folder dir has no entries, 0 if it has, -1 if it cannot be read. */
static int sa_dir_empty(const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int empty = 1;
  for (struct dirent *e; empty && (e = readdir(d));)
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) empty = 0;
  closedir(d);
  return empty;
}

/* Recursive removal for nftw, which passes no user data: hence the statics (single caller at a
 * time: the end of a run). Never follows a symbolic link or crosses into another file system. */
static int sa_rm_keep_root, sa_rm_errno;
static int sa_rm_one(const char *path, const struct stat *st, int flag, struct FTW *ftw) {
  (void)st, (void)flag;
  if (ftw->level == 0 && sa_rm_keep_root) return 0;
  if (remove(path) != 0 && !sa_rm_errno) sa_rm_errno = errno;
  return 0;
}
static int sa_rm_tree(const char *path, int keep_root) {
  sa_rm_keep_root = keep_root;
  sa_rm_errno = 0;
  if (nftw(path, sa_rm_one, 16, FTW_DEPTH | FTW_PHYS | FTW_MOUNT) != 0 && !sa_rm_errno) sa_rm_errno = errno;
  return sa_rm_errno ? SA_ERROR(SA_ERR_IO, "cannot remove %s: %s", path, strerror(sa_rm_errno)) : 0;
}

int sa_results_open(const char *dir, int continue_run, SaResults **out) {
  *out = NULL;
  size_t n = strlen(dir);
  /* checked before anything is created: a longer name used to be cut and the cut tree made */
  SA_REQUIRE(n > 0, SA_ERR_INPUT, "empty results folder name");
  SA_REQUIRE(n <= SA_RESULTS_DIR_MAX, SA_ERR_INPUT,
             "results folder name too long: %zu characters, at most %d (room is needed for the file "
             "names in it): %.80s...", n, SA_RESULTS_DIR_MAX, dir);
  SaResults *r;
  SA_CALLOC(r, 1);
  memcpy(r->dir, dir, n + 1);
  while (n > 1 && r->dir[n - 1] == '/') r->dir[--n] = 0;
  int rc = 0;
  struct stat st;
  if (lstat(r->dir, &st) == 0 && S_ISLNK(st.st_mode)) { /* act on the folder the link names */
    char real[PATH_MAX];
    if (realpath(r->dir, real) && strlen(real) <= SA_RESULTS_DIR_MAX) snprintf(r->dir, sizeof r->dir, "%s", real);
  }
  if (stat(r->dir, &st) != 0) {
    if (errno != ENOENT) { /* ENOTDIR: a file where a parent folder should be */
      rc = SA_ERROR(errno == ENOTDIR ? SA_ERR_INPUT : SA_ERR_IO, "results folder %s: %s", r->dir, strerror(errno));
    } else if (continue_run) {
      rc = SA_ERROR(SA_ERR_INPUT, "results folder %s does not exist: there is no earlier run to "
                    "continue (run the case without resume first)", r->dir);
    } else { /* FRESH: note the topmost folder made, so a failed run can remove it again */
      r->mode = SA_RESULTS_FRESH;
      char part[SA_STR_MAX];
      for (size_t i = 1; i <= n && !r->created[0]; i++)
        if (i == n || r->dir[i] == '/') {
          snprintf(part, sizeof part, "%.*s", (int)i, r->dir);
          if (stat(part, &st) != 0) memcpy(r->created, part, i + 1);
        }
      rc = sa_mkdir_p(r->dir);
    }
  } else if (!S_ISDIR(st.st_mode)) {
    rc = SA_ERROR(SA_ERR_INPUT, "results folder %s exists and is not a folder", r->dir);
  } else {
    int empty = sa_dir_empty(r->dir);
    if (empty < 0)
      rc = SA_ERROR(SA_ERR_IO, "cannot read results folder %s: %s", r->dir, strerror(errno));
    else if (!empty && !sa_results_is_run(r->dir))
      rc = SA_ERROR(SA_ERR_INPUT, "results folder %s holds files that are not a softact run (no case.ini "
                    "written by softact); softact does not write into it: choose another folder (--out, "
                    "[run] out_dir) or empty it", r->dir);
    else if (continue_run && empty)
      rc = SA_ERROR(SA_ERR_INPUT, "results folder %s is empty: there is no earlier run to continue (run "
                    "the case without resume first)", r->dir);
    else if (continue_run)
      r->mode = SA_RESULTS_IN_PLACE;
    else if (empty)
      r->mode = SA_RESULTS_FRESH;
    else {
      const char *base = strrchr(r->dir, '/');
      base = base ? base + 1 : r->dir;
      if (!strcmp(base, ".") || !strcmp(base, "..") || !base[0])
        rc = SA_ERROR(SA_ERR_INPUT, "results folder %s holds an earlier run and is replaced by the new "
                      "one, so it must be named by its own name (not '.' or '..')", r->dir);
      else {
        r->mode = SA_RESULTS_STAGED;
        snprintf(r->work, sizeof r->work, "%s.incomplete-%ld", r->dir, (long)getpid());
        if (mkdir(r->work, 0777) != 0)
          rc = SA_ERROR(SA_ERR_IO, "cannot create folder %s: %s", r->work, strerror(errno));
      }
    }
  }
  if (rc) {
    free(r);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  if (r->mode != SA_RESULTS_STAGED) memcpy(r->work, r->dir, sizeof r->work);
  *out = r;
  return 0;
}

const char *sa_results_work(const SaResults *r) { return r->work; }
const char *sa_results_dir(const SaResults *r) { return r->dir; }
int sa_results_in_place(const SaResults *r) { return r->mode == SA_RESULTS_IN_PLACE; }

int sa_results_close(SaResults **rp, int keep) {
  SaResults *r = *rp;
  if (!r) return 0;
  *rp = NULL;
  int rc = 0;
  if (r->mode == SA_RESULTS_FRESH && !keep) {
    /* the folder was empty or missing: all it holds is this run's */
    rc = sa_rm_tree(r->dir, 1);
    if (!rc && r->created[0]) { /* and the folders made for it, deepest first */
      char path[SA_STR_MAX];
      memcpy(path, r->dir, sizeof path);
      size_t top = strlen(r->created);
      while (strlen(path) >= top && rmdir(path) == 0) {
        char *slash = strrchr(path, '/');
        if (!slash || (size_t)(slash - path) < top) break;
        *slash = 0;
      }
    }
  } else if (r->mode == SA_RESULTS_STAGED && !keep) {
    rc = sa_rm_tree(r->work, 0);
  } else if (r->mode == SA_RESULTS_STAGED) {
    /* swap the finished folder in, then remove the earlier run (now at the sibling's name);
     * the earlier run is checked again: the folder may have changed while this one ran */
    struct stat st;
    int gone = stat(r->dir, &st) != 0 && errno == ENOENT;
    if (gone) {
      if (rename(r->work, r->dir) != 0) rc = SA_ERROR(SA_ERR_IO, "cannot rename %s to %s: %s", r->work, r->dir, strerror(errno));
    } else if (!sa_results_is_run(r->dir)) {
      rc = SA_ERROR(SA_ERR_IO, "%s no longer holds a softact run; the results of this run stay in %s",
                    r->dir, r->work);
    } else if (renameat2(AT_FDCWD, r->work, AT_FDCWD, r->dir, RENAME_EXCHANGE) == 0) {
      rc = sa_rm_tree(r->work, 0);
    } else { /* a file system without an atomic swap: two renames */
      char old[SA_STR_MAX + 8];
      snprintf(old, sizeof old, "%s.old", r->work);
      if (rename(r->dir, old) != 0)
        rc = SA_ERROR(SA_ERR_IO, "cannot replace %s by %s: %s", r->dir, r->work, strerror(errno));
      else if (rename(r->work, r->dir) != 0) {
        rc = SA_ERROR(SA_ERR_IO, "cannot replace %s by %s: %s", r->dir, r->work, strerror(errno));
        if (rename(old, r->dir) != 0) /* put the earlier run back; else say where it is */
          rc = SA_ERROR(SA_ERR_IO, "the earlier run in %s is now in %s", r->dir, old);
      } else
        rc = sa_rm_tree(old, 0);
    }
  }
  free(r);
  return rc;
}
