/* sa_plot.c - PNG plots rendered by gnuplot.
 *
 * For a plot NAME.png we write NAME.gp (atomically) beside it and run
 *     gnuplot -e "sa_output='.NAME.png.tmp.PID.N'" NAME.gp
 * with the PNG's folder as working directory, then rename the temporary onto NAME.png. The
 * script starts with   if (!exists("sa_output")) sa_output = 'NAME.png'   so a user who edits
 * it re-renders the figure with a plain `gnuplot NAME.gp` in that folder.
 *
 * Paths and texts appear in the script only inside single-quoted gnuplot strings (a quote is
 * doubled; newlines are refused), where gnuplot expands neither backquotes nor @macros, and
 * gnuplot is started with fork/execv (no shell), so no name can inject a command.
 * A style (SaPlotSeries.style) is gnuplot syntax and goes in unquoted, so ';', '`', '#' and
 * line breaks are refused in it.
 *
 * Data paths (SaPlotSeries.csv) are taken as the calling process would open them: a file in
 * or below the PNG's folder is written relative to that folder (the script stays relocatable
 * with its data), another existing file by its absolute path; a name that does not exist
 * from here is left as given, i.e. relative to the PNG's folder. sa_plot_script bodies also
 * run in the PNG's folder, after "set datafile separator ','" and commentschars '#' (our CSV).
 *
 * The terminal is pngcairo when `gnuplot -e "set terminal"` lists it, else png; the probe runs
 * once per process. Any failure (no gnuplot, error in the script, timeout) is logged as a
 * warning and returns SA_ERR_IO; the .gp is kept for inspection. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "sa_plot.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_params.h" /* SA_STR_MAX */

#define SA_PLOT_TIMEOUT 60.0 /* seconds; a plot of a few curves takes well under one */
#define SA_PLOT_OUT_MAX 16384

typedef struct {
  int status; /* exit status, or -1 if killed by a signal */
  size_t len;
  char out[SA_PLOT_OUT_MAX]; /* stdout + stderr, truncated */
} SaPlotRun;

enum { SA_PLOT_TERM_UNKNOWN = 0, SA_PLOT_TERM_PNGCAIRO, SA_PLOT_TERM_PNG };
static int sa_plot_term = SA_PLOT_TERM_UNKNOWN;
static pthread_mutex_t sa_plot_lock = PTHREAD_MUTEX_INITIALIZER;
static unsigned sa_plot_counter;

/* Warns and returns SA_ERR_IO (plots are optional; the caller decides whether to clear it). */
__attribute__((format(printf, 2, 3))) static int sa_plot_fail(const char *png, const char *fmt,
                                                               ...) {
  char why[600];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  sa_log(SA_LOG_WARN, "plot", "%s not written: %s", png, why);
  return SA_ERROR(SA_ERR_IO, "plot %s not written: %s", png, why);
}

/* Looks gnuplot up on PATH (resolved in the parent: the child after fork may only call
 * async-signal-safe functions, so it uses execv, not execvp). */
static int sa_plot_find_gnuplot(char *buf, size_t size) {
  const char *path = getenv("PATH");
  if (!path) path = "/usr/bin:/bin";
  while (1) {
    const char *end = strchr(path, ':');
    size_t len = end ? (size_t)(end - path) : strlen(path);
    int n = len ? snprintf(buf, size, "%.*s/gnuplot", (int)len, path)
                : snprintf(buf, size, "./gnuplot");
    if (n > 0 && (size_t)n < size && access(buf, X_OK) == 0) return 0;
    if (!end) break;
    path = end + 1;
  }
  return -1;
}

/* Runs argv with cwd dir, stdin /dev/null, stdout+stderr captured; kills it after timeout s.
 * temp [may be NULL]: the file the child writes, removed along with the child by a second
 * signal (sa_signals_child_add).
 * Returns 0 when it ran to the end (r->status), -1 with errno-ish text in r->out otherwise. */
static int sa_plot_exec(const char *exe, const char *dir, char *const argv[], double timeout,
                        const char *temp, SaPlotRun *r) {
  r->status = -1;
  r->len = 0;
  r->out[0] = 0;
  int fd[2];
  if (pipe(fd) != 0) {
    snprintf(r->out, sizeof r->out, "pipe: %s", strerror(errno));
    return -1;
  }
  fcntl(fd[0], F_SETFD, FD_CLOEXEC);
  fcntl(fd[1], F_SETFD, FD_CLOEXEC);
  /* the termination signals stay blocked until the child is registered, so a second signal
   * cannot fall between fork and registration and leave an unwatched child */
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigaddset(&block, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &block, &old);
  pid_t pid = fork();
  if (pid < 0) {
    int e = errno;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    snprintf(r->out, sizeof r->out, "fork: %s", strerror(e));
    close(fd[0]);
    close(fd[1]);
    return -1;
  }
  if (pid == 0) {
    sigprocmask(SIG_SETMASK, &old, NULL); /* exec keeps the mask: gnuplot gets the caller's */
    int nul = open("/dev/null", O_RDONLY);
    if (nul >= 0) dup2(nul, STDIN_FILENO);
    dup2(fd[1], STDOUT_FILENO);
    dup2(fd[1], STDERR_FILENO);
    if (dir && chdir(dir) != 0) _exit(126);
    execv(exe, argv);
    _exit(127);
  }
  int slot = sa_signals_child_add((long)pid, temp);
  pthread_sigmask(SIG_SETMASK, &old, NULL);
  close(fd[1]);
  double t_end = sa_time_now() + timeout;
  int timed_out = 0;
  while (1) {
    int ms = (int)((t_end - sa_time_now()) * 1000.0);
    if (ms <= 0) {
      timed_out = 1;
      kill(pid, SIGKILL);
      break;
    }
    struct pollfd p = {.fd = fd[0], .events = POLLIN};
    int k = poll(&p, 1, ms);
    if (k < 0 && errno == EINTR) continue;
    if (k < 0) break;
    if (k == 0) continue;
    char buf[1024];
    ssize_t m = read(fd[0], buf, sizeof buf);
    if (m < 0 && errno == EINTR) continue;
    if (m <= 0) break; /* EOF: gnuplot closed its output, i.e. it is exiting */
    size_t take = (size_t)m;
    if (take > sizeof r->out - 1 - r->len) take = sizeof r->out - 1 - r->len;
    memcpy(r->out + r->len, buf, take);
    r->len += take;
    r->out[r->len] = 0;
  }
  close(fd[0]);
  int st = 0;
  while (waitpid(pid, &st, 0) < 0)
    if (errno != EINTR) break;
  sa_signals_child_remove(slot);
  if (timed_out) {
    snprintf(r->out, sizeof r->out, "gnuplot killed after %.0f s", timeout);
    return -1;
  }
  r->status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return 0;
}

/* First lines of gnuplot's output, on one line, for a warning. */
static const char *sa_plot_excerpt(SaPlotRun *r) {
  size_t n = r->len < 400 ? r->len : 400;
  r->out[n] = 0;
  for (size_t i = 0; i < n; i++)
    if (r->out[i] == '\n') r->out[i] = ' ';
  return r->len ? r->out : "(no output)";
}

/* Terminal probe, once per process (a failed probe is retried next time). */
static int sa_plot_terminal(const char *exe, int *term) {
  pthread_mutex_lock(&sa_plot_lock);
  int t = sa_plot_term;
  pthread_mutex_unlock(&sa_plot_lock);
  if (t == SA_PLOT_TERM_UNKNOWN) {
    SaPlotRun *r = malloc(sizeof *r);
    if (!r) return -1;
    char *argv[] = {"gnuplot", "-e", "set terminal", NULL};
    if (sa_plot_exec(exe, NULL, argv, SA_PLOT_TIMEOUT, NULL, r) == 0 && r->status == 0)
      t = strstr(r->out, "pngcairo") ? SA_PLOT_TERM_PNGCAIRO : SA_PLOT_TERM_PNG;
    free(r);
    if (t == SA_PLOT_TERM_UNKNOWN) return -1;
    pthread_mutex_lock(&sa_plot_lock);
    sa_plot_term = t;
    pthread_mutex_unlock(&sa_plot_lock);
  }
  *term = t;
  return 0;
}

/* Text safe to put in a single-quoted gnuplot string: one line. */
static int sa_plot_check_text(const char *what, const char *s) {
  if (!s) return 0;
  SA_REQUIRE(!strpbrk(s, "\n\r"), SA_ERR_INPUT, "plot %s '%s' contains a line break", what, s);
  return 0;
}

static void sa_plot_quote(FILE *f, const char *s) {
  fputc('\'', f);
  for (; *s; s++) {
    if (*s == '\'') fputc('\'', f); /* '' is a quote inside a single-quoted gnuplot string */
    fputc(*s, f);
  }
  fputc('\'', f);
}

/* dir (of the PNG) and base name; buffers of SA_STR_MAX. */
static int sa_plot_split(const char *png, char *dir, char *base) {
  SA_REQUIRE(png && png[0], SA_ERR_INPUT, "plot: empty PNG path");
  SA_REQUIRE(strlen(png) < SA_STR_MAX - 32, SA_ERR_INPUT, "plot: path too long: %s", png);
  SA_REQUIRE(!strpbrk(png, "\n\r"), SA_ERR_INPUT, "plot: path with a line break");
  const char *slash = strrchr(png, '/');
  if (!slash) {
    snprintf(dir, SA_STR_MAX, ".");
    snprintf(base, SA_STR_MAX, "%s", png);
  } else {
    snprintf(dir, SA_STR_MAX, "%.*s", slash == png ? 1 : (int)(slash - png), png);
    snprintf(base, SA_STR_MAX, "%s", slash + 1);
  }
  SA_REQUIRE(base[0], SA_ERR_INPUT, "plot: PNG path %s names a folder", png);
  return 0;
}

/* How the script (run in png_dir) should name data file csv; see the file comment. */
static void sa_plot_data_path(const char *csv, const char *png_dir, char *out, size_t size) {
  snprintf(out, size, "%s", csv);
  if (access(csv, F_OK) != 0) return;
  char *abs = realpath(csv, NULL), *dir = realpath(png_dir, NULL);
  if (abs) {
    size_t dlen = dir ? strlen(dir) : 0;
    if (dir && dlen > 1 && !strncmp(abs, dir, dlen) && abs[dlen] == '/')
      snprintf(out, size, "%s", abs + dlen + 1);
    else if (dir && dlen == 1) /* PNG in the root folder */
      snprintf(out, size, "%s", abs + 1);
    else
      snprintf(out, size, "%s", abs);
  }
  free(abs);
  free(dir);
}

/* Writes NAME.gp = header + body and renders it. */
static int sa_plot_render(const char *png, int width, int height, const char *body) {
  char dir[SA_STR_MAX], base[SA_STR_MAX], script[SA_STR_MAX + 8], gp_base[SA_STR_MAX + 8];
  SA_CHECK(sa_plot_split(png, dir, base));
  size_t blen = strlen(base);
  size_t cut = blen > 4 && !strcmp(base + blen - 4, ".png") ? 4 : 0;
  snprintf(gp_base, sizeof gp_base, "%s%.*s.gp", base[0] == '-' ? "./" : "", (int)(blen - cut),
           base);
  snprintf(script, sizeof script, "%.*s.gp", (int)(strlen(png) - cut), png);
  SA_REQUIRE(width >= 0 && height >= 0, SA_ERR_INPUT, "plot %s: negative size %d x %d", png,
             width, height);
  if (!width) width = 900;
  if (!height) height = 600;

  char exe[SA_STR_MAX];
  if (sa_plot_find_gnuplot(exe, sizeof exe) != 0)
    return sa_plot_fail(png, "%s", "gnuplot is not on PATH");
  int term;
  if (sa_plot_terminal(exe, &term) != 0)
    return sa_plot_fail(png, "%s", "gnuplot does not start (`gnuplot -e \"set terminal\"` failed)");

  SaFile *file;
  int rc = sa_file_open(script, &file);
  if (rc) {
    sa_log(SA_LOG_WARN, "plot", "%s not written: cannot write its script %s", png, script);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  FILE *f = sa_file_stream(file);
  fprintf(f, "# %.*s.gp - written by softact; run `gnuplot %s` in this folder to redraw %s\n",
          (int)(blen - cut), base, gp_base, base);
  fprintf(f, "if (!exists(\"sa_output\")) sa_output = ");
  sa_plot_quote(f, base);
  fprintf(f, "\nset terminal %s size %d,%d noenhanced%s\n",
          term == SA_PLOT_TERM_PNGCAIRO ? "pngcairo" : "png", width, height,
          term == SA_PLOT_TERM_PNGCAIRO ? " font ',11'" : "");
  fprintf(f, "set output sa_output\nset datafile separator ','\nset datafile commentschars '#'\n");
  fputs(body, f);
  if (body[0] && body[strlen(body) - 1] != '\n') fputc('\n', f);
  fputs("unset output\n", f);
  rc = sa_file_commit(&file);
  if (rc) {
    sa_log(SA_LOG_WARN, "plot", "%s not written: cannot write its script %s", png, script);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }

  pthread_mutex_lock(&sa_plot_lock);
  unsigned id = sa_plot_counter++;
  pthread_mutex_unlock(&sa_plot_lock);
  char tmp[SA_STR_MAX + 64], tmp_path[2 * SA_STR_MAX + 64], set_out[2 * SA_STR_MAX + 80];
  snprintf(tmp, sizeof tmp, ".%s.tmp.%ld.%u", base, (long)getpid(), id);
  snprintf(tmp_path, sizeof tmp_path, "%s/%s", dir, tmp);
  /* -e text is parsed by gnuplot: quote the name the same way as in the script. */
  char *p = set_out;
  p += sprintf(p, "sa_output='");
  for (const char *c = tmp; *c; c++) {
    if (*c == '\'') *p++ = '\'';
    *p++ = *c;
  }
  sprintf(p, "'");

  SaPlotRun *r = malloc(sizeof *r);
  if (!r) return SA_ERROR(SA_ERR_MEMORY, "cannot allocate the gnuplot output buffer");
  char *argv[] = {"gnuplot", "-e", set_out, gp_base, NULL};
  int ran = sa_plot_exec(exe, dir, argv, SA_PLOT_TIMEOUT, tmp_path, r);
  struct stat st;
  int made = stat(tmp_path, &st) == 0 && st.st_size > 0;
  if (ran != 0 || r->status != 0 || !made) {
    remove(tmp_path);
    rc = ran != 0 ? sa_plot_fail(png, "%s", r->out)
         : r->status != 0
             ? sa_plot_fail(png, "gnuplot %s exited with status %d: %s", script, r->status,
                            sa_plot_excerpt(r))
             : sa_plot_fail(png, "gnuplot %s made no image: %s", script, sa_plot_excerpt(r));
    free(r);
    return rc;
  }
  if (r->len) sa_log(SA_LOG_DEBUG, "plot", "gnuplot %s: %s", script, sa_plot_excerpt(r));
  free(r);
  if (rename(tmp_path, png) != 0) {
    int e = errno;
    remove(tmp_path);
    return sa_plot_fail(png, "rename: %s", strerror(e));
  }
  return 0;
}

int sa_plot_lines(const char *png_path, const SaPlotAxes *axes, int nseries,
                  const SaPlotSeries *series) {
  SA_REQUIRE(png_path && png_path[0], SA_ERR_INPUT, "sa_plot_lines: empty PNG path");
  SA_REQUIRE(nseries >= 1 && series, SA_ERR_INPUT, "plot %s: no series", png_path);
  SaPlotAxes ax = axes ? *axes : (SaPlotAxes){0};
  SA_CHECK(sa_plot_check_text("title", ax.title));
  SA_CHECK(sa_plot_check_text("x label", ax.xlabel));
  SA_CHECK(sa_plot_check_text("y label", ax.ylabel));
  for (int i = 0; i < nseries; i++) {
    const SaPlotSeries *s = &series[i];
    SA_REQUIRE(s->csv && s->csv[0], SA_ERR_INPUT, "plot %s: series %d has no data file", png_path,
               i);
    SA_REQUIRE(s->xcol >= 1 && s->ycol >= 1, SA_ERR_INPUT,
               "plot %s: series %d columns %d:%d (they are 1-based)", png_path, i, s->xcol, s->ycol);
    SA_CHECK(sa_plot_check_text("data path", s->csv));
    SA_CHECK(sa_plot_check_text("series title", s->title));
    /* The style is gnuplot syntax put in unquoted: no command separators or substitutions. */
    SA_REQUIRE(!s->style || !strpbrk(s->style, "\n\r;`#"), SA_ERR_INPUT,
               "plot %s: style '%s' may not contain line breaks, ';', '`' or '#'", png_path,
               s->style);
  }
  char dir[SA_STR_MAX], base[SA_STR_MAX];
  SA_CHECK(sa_plot_split(png_path, dir, base));

  char *body = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&body, &size);
  SA_REQUIRE(f, SA_ERR_MEMORY, "plot %s: cannot build the script", png_path);
  const char *labels[3][2] = {{"title", ax.title}, {"xlabel", ax.xlabel}, {"ylabel", ax.ylabel}};
  for (int k = 0; k < 3; k++)
    if (labels[k][1] && labels[k][1][0]) {
      fprintf(f, "set %s ", labels[k][0]);
      sa_plot_quote(f, labels[k][1]);
      fputc('\n', f);
    }
  if (ax.logx) fputs("set logscale x\n", f);
  if (ax.logy) fputs("set logscale y\n", f);
  fputs("set grid\nset key noautotitle\nplot ", f);
  for (int i = 0; i < nseries; i++) {
    const SaPlotSeries *s = &series[i];
    char data[2 * SA_STR_MAX];
    sa_plot_data_path(s->csv, dir, data, sizeof data);
    sa_plot_quote(f, data);
    fprintf(f, " using %d:%d with %s", s->xcol, s->ycol, s->style ? s->style : "lines");
    if (s->title && s->title[0]) {
      fputs(" title ", f);
      sa_plot_quote(f, s->title);
    }
    fputs(i + 1 < nseries ? ", \\\n     " : "\n", f);
  }
  if (fclose(f) != 0 || !body) {
    free(body);
    return SA_ERROR(SA_ERR_MEMORY, "plot %s: cannot build the script", png_path);
  }
  int rc = sa_plot_render(png_path, ax.width, ax.height, body);
  free(body);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

int sa_plot_script(const char *png_path, const char *body) {
  SA_REQUIRE(png_path && png_path[0], SA_ERR_INPUT, "sa_plot_script: empty PNG path");
  SA_REQUIRE(body, SA_ERR_INPUT, "plot %s: NULL script body", png_path);
  SA_CHECK(sa_plot_render(png_path, 0, 0, body));
  return 0;
}

int sa_plot_script_size(const char *png_path, int width, int height, const char *body) {
  SA_REQUIRE(png_path && png_path[0], SA_ERR_INPUT, "sa_plot_script_size: empty PNG path");
  SA_REQUIRE(body, SA_ERR_INPUT, "plot %s: NULL script body", png_path);
  SA_CHECK(sa_plot_render(png_path, width, height, body));
  return 0;
}
