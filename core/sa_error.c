/* sa_error.c - the error table and a small thread-local error trace. */
#include "sa_error.h"

#include <stdio.h>
#include <string.h>

#define SA_TRACE_MAX 32

typedef struct {
  const char *func, *file;
  int line;
} SaFrame;

static _Thread_local char sa_msg[1024];
static _Thread_local int sa_code;
static _Thread_local SaFrame sa_frames[SA_TRACE_MAX];
static _Thread_local int sa_nframes;

const char *sa_error_string(int code) {
  switch (code) {
#define SA_X_STR(name, value, status, msg) case value: return msg;
    SA_ERROR_LIST(SA_X_STR)
#undef SA_X_STR
  }
  return "unknown error";
}

int sa_error_exit_status(int code) {
  switch (code) {
#define SA_X_ST(name, value, status, msg) case value: return status;
    SA_ERROR_LIST(SA_X_ST)
#undef SA_X_ST
  }
  return 4;
}

int sa_error_set(int code, const char *func, const char *file, int line, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(sa_msg, sizeof sa_msg, fmt, ap);
  va_end(ap);
  sa_code = code;
  sa_nframes = 0;
  return sa_error_push(code, func, file, line);
}

int sa_error_push(int code, const char *func, const char *file, int line) {
  if (sa_nframes < SA_TRACE_MAX) sa_frames[sa_nframes++] = (SaFrame){func, file, line};
  if (!sa_code) sa_code = code;
  return code;
}

void sa_error_print(void) { sa_error_print_opt(1); }

void sa_error_print_opt(int with_trace) {
  if (!sa_code && !sa_nframes) return;
  fprintf(stderr, "error: %s%s%s\n", sa_msg[0] ? sa_msg : "", sa_msg[0] ? " -- " : "",
          sa_error_string(sa_code));
  for (int i = 0; with_trace && i < sa_nframes; i++)
    fprintf(stderr, "  at %s (%s:%d)\n", sa_frames[i].func, sa_frames[i].file, sa_frames[i].line);
  sa_error_clear();
}

void sa_error_clear(void) {
  sa_msg[0] = 0;
  sa_code = 0;
  sa_nframes = 0;
}

const char *sa_error_message(void) { return sa_msg; }
