/* tutil.h - small helpers shared by the solver tests. */
#ifndef TUTIL_H
#define TUTIL_H

#include <math.h>
#include <stdio.h>

#include "sa_error.h"

/* |a - b| <= atol + rtol |b|; prints what differed. Returns 1 on failure. */
static inline int tu_close(const char *what, double a, double b, double atol, double rtol) {
  if (fabs(a - b) <= atol + rtol * fabs(b)) return 0;
  fprintf(stderr, "%s: got %.10g, expected %.10g (|diff| %.3g > %.3g)\n", what, a, b,
          fabs(a - b), atol + rtol * fabs(b));
  return 1;
}

#define TU_CHECK(call)                                                                     \
  do {                                                                                     \
    int tu_rc_ = (call);                                                                   \
    if (tu_rc_) {                                                                          \
      fprintf(stderr, "%s:%d: %s failed (%d)\n", __FILE__, __LINE__, #call, tu_rc_);       \
      sa_error_print();                                                                    \
      return 1;                                                                            \
    }                                                                                      \
  } while (0)

#endif
