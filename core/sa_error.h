/* sa_error.h - error codes, propagation and the error trace shared by every module.
 *
 * Convention (see docs/architecture.md): every fallible function returns int.
 *   0      success
 *   < 0    fatal: bad input, I/O, memory, library failure (the run stops)
 *   > 0    recoverable numerical failure (not positive definite, inverted element,
 *          no convergence, ...) that a caller may handle, e.g. by cutting the step.
 * SA_CHECK propagates a non-zero code and appends a frame (function, file, line) to a
 * thread-local trace; main() prints the trace once and maps the code to an exit status.
 * Library code never calls exit(). */
#ifndef SA_ERROR_H
#define SA_ERROR_H

#include <stdarg.h>

/* X(name, value, exit status, message) -- the single error table. */
#define SA_ERROR_LIST(X)                                                        \
  X(SA_OK, 0, 0, "success")                                                     \
  X(SA_ERR_INPUT, -1, 1, "bad input")                                           \
  X(SA_ERR_IO, -2, 4, "input/output failure")                                   \
  X(SA_ERR_MEMORY, -3, 4, "out of memory")                                      \
  X(SA_ERR_LIBRARY, -4, 4, "library failure")                                   \
  X(SA_ERR_INTERNAL, -5, 4, "internal error")                                   \
  X(SA_ERR_INTERRUPTED, -6, 3, "interrupted by signal")                         \
  X(SA_ERR_NUMERICAL, -7, 2, "numerical failure")                               \
  X(SA_ERR_NOT_CONVERGED, 1, 2, "no convergence")                               \
  X(SA_ERR_NOT_SPD, 2, 2, "matrix not positive definite")                       \
  X(SA_ERR_INVERTED, 3, 2, "inverted element (det F <= 0)")                     \
  X(SA_ERR_NAN, 4, 2, "not-a-number in the solution")                           \
  X(SA_ERR_LIMIT_POINT, 5, 2, "limit point reached under load control")         \
  X(SA_ERR_STEP_TOO_SMALL, 6, 2, "step size fell below its minimum")            \
  X(SA_ERR_DOMAIN, 7, 2, "state left the domain of the model")

enum {
#define SA_X_ENUM(name, value, status, msg) name = value,
  SA_ERROR_LIST(SA_X_ENUM)
#undef SA_X_ENUM
};

/* Message for a code ("unknown error" for an unlisted one). */
const char *sa_error_string(int code);
/* Process exit status for a code: 0 ok, 1 bad input, 2 numerical failure,
 * 3 interrupted, 4 I/O, memory, library or internal error. */
int sa_error_exit_status(int code);

/* Record an error with a formatted message; starts a fresh trace. Returns code. */
int sa_error_set(int code, const char *func, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* Append a propagation frame to the trace. Returns code. */
int sa_error_push(int code, const char *func, const char *file, int line);
/* Print the trace (message first, then frames) to stderr and clear it. */
void sa_error_print(void);
/* Same, but the frames only if with_trace (a typo in a case file needs no call trace). */
void sa_error_print_opt(int with_trace);
/* Clear the trace (after a recoverable failure was handled). */
void sa_error_clear(void);
/* The message of the last sa_error_set (empty string if none). */
const char *sa_error_message(void);

#define SA_ERROR(code, ...) sa_error_set((code), __func__, __FILE__, __LINE__, __VA_ARGS__)

#define SA_CHECK(call)                                                          \
  do {                                                                          \
    int sa_check_rc_ = (call);                                                  \
    if (sa_check_rc_ != 0) return sa_error_push(sa_check_rc_, __func__, __FILE__, __LINE__); \
  } while (0)

#define SA_REQUIRE(cond, code, ...)                                             \
  do {                                                                          \
    if (!(cond)) return SA_ERROR((code), __VA_ARGS__);                          \
  } while (0)

/* Allocation helpers that set SA_ERR_MEMORY on failure. */
#define SA_CALLOC(ptr, n)                                                       \
  do {                                                                          \
    size_t sa_n_ = (size_t)(n);                                                 \
    (ptr) = calloc(sa_n_ ? sa_n_ : 1, sizeof *(ptr));                           \
    if (!(ptr)) return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %zu x %zu bytes", sa_n_, sizeof *(ptr)); \
  } while (0)

#endif
