/* fem_blas_select_kernels: on a CPU whose /proc/cpuinfo flags (the kernel's report, independent
 * of the compiler's CPUID test the code uses) list AVX-512 F/CD/BW/DQ/VL, OpenBLAS must run
 * its SkylakeX kernels after the call; with AVX2 + FMA at least Haswell's, never the Prescott
 * (SSE3) fallback. The re-executed process keeps its arguments. A user's OPENBLAS_CORETYPE is
 * kept: run again with OPENBLAS_CORETYPE=Prescott, the kernels stay Prescott. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fem_blas.h"

static int has_flag(const char *flags, const char *f) {
  size_t n = strlen(f);
  for (const char *p = flags; (p = strstr(p, f)); p += n)
    if ((p == flags || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\n' || p[n] == 0)) return 1;
  return 0;
}

int main(int argc, char **argv) {
  fem_blas_select_kernels(argv);
  const char *k = fem_blas_kernels(), *user = getenv("TEST_USER_CORETYPE");
  if (argc != 2 || strcmp(argv[1], "marker")) {
    printf("FAIL: arguments lost across the re-execution (argc %d)\n", argc);
    return 1;
  }
  if (user) { /* second run: the user's choice stands */
    printf("user OPENBLAS_CORETYPE=%s: kernels %s\n", user, k);
    return strcasecmp(k, user) ? 1 : 0;
  }
  static char line[8192];
  int avx512 = 0, avx2 = 0;
  FILE *f = fopen("/proc/cpuinfo", "r");
  while (f && fgets(line, sizeof line, f))
    if (!strncmp(line, "flags", 5)) {
      avx512 = has_flag(line, "avx512f") && has_flag(line, "avx512cd") &&
               has_flag(line, "avx512bw") && has_flag(line, "avx512dq") &&
               has_flag(line, "avx512vl");
      avx2 = has_flag(line, "avx2") && has_flag(line, "fma");
      break;
    }
  if (f) fclose(f);
  printf("CPU: AVX-512 %s, AVX2+FMA %s; OpenBLAS kernels %s\n", avx512 ? "yes" : "no",
         avx2 ? "yes" : "no", k);
  if ((avx512 || avx2) && !strcasecmp(k, "Prescott")) {
    printf("FAIL: the generic Prescott kernels on a CPU with %s\n", avx512 ? "AVX-512" : "AVX2");
    return 1;
  }
  return 0;
}
