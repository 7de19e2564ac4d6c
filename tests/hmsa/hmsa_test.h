/* hmsa_test.h - tiny helpers shared by the hmsa tests: silent on success, one line per
 * failure, exit status = number of failures (capped). */
#ifndef HMSA_TEST_H
#define HMSA_TEST_H

#include <math.h>
#include <stdio.h>

#include "sa_error.h"

static int hmsa_test_failures = 0;

/* |a - b| <= atol + rtol |b| */
#define CLOSE(a, b, atol, rtol, what)                                                         \
  do {                                                                                        \
    double a_ = (a), b_ = (b);                                                                \
    if (!(fabs(a_ - b_) <= (atol) + (rtol) * fabs(b_))) {                                     \
      fprintf(stderr, "%s:%d: %s: got %.12g, expected %.12g (diff %.3g, atol %g, rtol %g)\n", \
              __FILE__, __LINE__, (what), a_, b_, fabs(a_ - b_), (double)(atol),             \
              (double)(rtol));                                                                \
      hmsa_test_failures++;                                                                   \
    }                                                                                         \
  } while (0)

#define EXPECT(cond, ...)                                                  \
  do {                                                                     \
    if (!(cond)) {                                                         \
      fprintf(stderr, "%s:%d: expected %s: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                                        \
      fprintf(stderr, "\n");                                               \
      hmsa_test_failures++;                                                \
    }                                                                      \
  } while (0)

#define OK(call)                                                                     \
  do {                                                                               \
    int rc_ = (call);                                                                \
    if (rc_) {                                                                       \
      fprintf(stderr, "%s:%d: %s returned %d\n", __FILE__, __LINE__, #call, rc_);    \
      sa_error_print();                                                              \
      hmsa_test_failures++;                                                          \
      return hmsa_test_failures;                                                     \
    }                                                                                \
  } while (0)

/* Deterministic uniform numbers in [a, b) (xorshift; no libc rand state). */
static inline double hmsa_test_uniform(unsigned long long *s, double a, double b) {
  *s ^= *s << 13;
  *s ^= *s >> 7;
  *s ^= *s << 17;
  return a + (b - a) * (double)(*s >> 11) / 9007199254740992.0;
}

#define TEST_RETURN() return hmsa_test_failures > 100 ? 100 : hmsa_test_failures

#endif
