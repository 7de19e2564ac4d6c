/* test_util.h - tiny helpers shared by the core tests (header-only, static functions).
 * A test is silent on success and prints "file:line: what differed" on failure. */
#ifndef SA_TEST_UTIL_H
#define SA_TEST_UTIL_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sa_error.h"
#include "sa_output.h"

#define TU_PATH 1024

static int tu_failures;

#define TU_CHECK(cond, ...)                                      \
  do {                                                           \
    if (!(cond)) {                                               \
      fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);            \
      fprintf(stderr, __VA_ARGS__);                              \
      fputc('\n', stderr);                                       \
      tu_failures++;                                             \
    }                                                            \
  } while (0)

/* The call must succeed; on failure print the error trace. */
#define TU_OK(call)                                              \
  do {                                                           \
    int tu_rc_ = (call);                                         \
    if (tu_rc_ != 0) {                                           \
      fprintf(stderr, "%s:%d: %s returned %d\n", __FILE__, __LINE__, #call, tu_rc_); \
      sa_error_print();                                          \
      tu_failures++;                                             \
    }                                                            \
  } while (0)

/* The call must fail with exactly this code; the expected error is then cleared. */
#define TU_CODE(call, code)                                      \
  do {                                                           \
    int tu_rc_ = (call);                                         \
    if (tu_rc_ != (code)) {                                      \
      fprintf(stderr, "%s:%d: %s returned %d, expected %d (%s)\n", __FILE__, __LINE__, #call, \
              tu_rc_, (code), #code);                            \
      sa_error_print();                                          \
      tu_failures++;                                             \
    }                                                            \
    sa_error_clear();                                            \
  } while (0)

/* Like TU_CODE, and the error message must contain the text sub. */
#define TU_CODE_MSG(call, code, sub)                             \
  do {                                                           \
    int tu_rc_ = (call);                                         \
    if (tu_rc_ != (code) || !strstr(sa_error_message(), (sub))) { \
      fprintf(stderr, "%s:%d: %s returned %d, expected %d (%s) with a message naming '%s'\n", \
              __FILE__, __LINE__, #call, tu_rc_, (code), #code, (sub)); \
      sa_error_print();                                          \
      tu_failures++;                                             \
    }                                                            \
    sa_error_clear();                                            \
  } while (0)

static inline void tu_join(const char *dir, const char *name, char *buf) {
  int n = snprintf(buf, TU_PATH, "%s/%s", dir, name);
  if (n < 0 || n >= TU_PATH) {
    fprintf(stderr, "test path too long: %s/%s\n", dir, name);
    exit(1);
  }
}

/* Whole file, NUL-terminated; *n = size in bytes. NULL if unreadable. [owned] */
static inline unsigned char *tu_slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 4096, len = 0;
  unsigned char *buf = malloc(cap + 1);
  size_t got;
  while (buf && (got = fread(buf + len, 1, cap - len, f)) > 0) {
    len += got;
    if (len == cap) {
      unsigned char *b = realloc(buf, 2 * cap + 1);
      if (!b) {
        free(buf);
        buf = NULL;
        break;
      }
      buf = b;
      cap *= 2;
    }
  }
  fclose(f);
  if (buf) buf[len] = 0;
  *n = len;
  return buf;
}

/* Number of entries of dir whose name contains sub ("" = all), "." and ".." excluded. */
static inline int tu_count_matching(const char *dir, const char *sub) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && strstr(e->d_name, sub)) n++;
  closedir(d);
  return n;
}

static inline int tu_count_entries(const char *dir) { return tu_count_matching(dir, ""); }

static inline int tu_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

static inline void tu_rm_rf(const char *path) {
  struct stat st;
  if (lstat(path, &st) != 0) return;
  if (S_ISDIR(st.st_mode)) {
    DIR *d = opendir(path);
    struct dirent *e;
    char sub[TU_PATH];
    while (d && (e = readdir(d)))
      if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
        tu_join(path, e->d_name, sub);
        tu_rm_rf(sub);
      }
    if (d) closedir(d);
    rmdir(path);
  } else {
    unlink(path);
  }
}

/* dir = ARGV1/sub (or ./core_test_out/sub), emptied and created. */
static inline int tu_fresh_dir(int argc, char **argv, const char *sub, char *dir) {
  tu_join(argc > 1 ? argv[1] : "core_test_out", sub, dir);
  tu_rm_rf(dir);
  if (sa_mkdir_p(dir) != 0) {
    sa_error_print();
    return 1;
  }
  return 0;
}

static inline int tu_result(void) { return tu_failures ? 1 : 0; }

#endif
