/* fem_blas.c - see fem_blas.h. */
#include "fem_blas.h"

#include <stdlib.h>
#include <strings.h>
#include <unistd.h>

char *openblas_get_corename(void);

const char *fem_blas_kernels(void) { return openblas_get_corename(); }

/* The best kernel set OpenBLAS 0.3.21 has for this CPU's instruction set, or NULL. */
static const char *kernels_for_cpu(void) {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  return NULL;
}

void fem_blas_select_kernels(char **argv) {
  if (getenv("OPENBLAS_CORETYPE")) return; /* the user's choice, or already re-executed */
  const char *now = openblas_get_corename();
  if (!now || strcasecmp(now, "Prescott")) return; /* recognised: OpenBLAS chose itself */
  const char *best = kernels_for_cpu();
  if (!best || setenv("OPENBLAS_CORETYPE", best, 1)) return;
  execv("/proc/self/exe", argv);
  unsetenv("OPENBLAS_CORETYPE"); /* exec failed: run on as loaded */
}
