/* sa_output.c - atomic files, folders and clean interruption (see sa_output.h). */
#include "sa_output.h"

#include <errno.h>
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
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
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
