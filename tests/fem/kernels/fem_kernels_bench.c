/* fem_kernels_bench.c - cost of the element kernels: microseconds per call of fem_element_tl
 * (residual + tangent, and residual only) for tet4, straight tet10 (4-point rule) and curved
 * tet10 (8-point rule), Yeoh silicone at K/mu = 500. Thread CPU time, so the numbers hold on a
 * shared machine (wall time there includes waiting for a core). Not a test; run by hand:
 *   fem_kernels_bench [calls] */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fem_element.h"
#include "kt_util.h"

#define NEL 64 /* distinct elements cycled through, so the data is not all in registers */

static double bench(FemElemType t, double curve, int want_K, int calls, const FemMaterial *m)
{
  static double X[NEL][30], x[NEL][30];
  static FemElemOut out;
  int nen = (int)t;
  for (int e = 0; e < NEL; e++) {
    double F0[9];
    kt_random_tet(nen, 0.2, curve, X[e]);
    kt_random_F(0.2, kt_rand(0.9, 1.1), F0);
    for (int a = 0; a < nen; a++)
      for (int i = 0; i < 3; i++)
        x[e][3 * a + i] = F0[3 * i] * X[e][3 * a] + F0[3 * i + 1] * X[e][3 * a + 1] +
                          F0[3 * i + 2] * X[e][3 * a + 2] + kt_rand(-0.02, 0.02);
  }
  struct timespec t0, t1;
  double sink = 0;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
  for (int c = 0; c < calls; c++) {
    int e = c % NEL;
    if (fem_element_tl(t, X[e], x[e], m, NULL, NULL, want_K, &out)) return -1;
    sink += out.fe[0] + out.Ke[31];
  }
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
  double dt = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  if (sink == 12345.678) printf(" ");
  return 1e6 * dt / calls;
}

int main(int argc, char **argv)
{
  int calls = argc > 1 ? atoi(argv[1]) : 200000;
  FemMaterial m = {.kind = FEM_MAT_YEOH, .c10 = 0.11e6, .c20 = 0.02e6, .kappa = 500 * 0.22e6};
  printf("element           residual+tangent [us]   residual only [us]\n");
  printf("tet4              %10.3f              %10.3f\n", bench(FEM_TET4, 0, 1, calls, &m),
         bench(FEM_TET4, 0, 0, calls, &m));
  printf("tet10 (4 qp)      %10.3f              %10.3f\n", bench(FEM_TET10, 0, 1, calls, &m),
         bench(FEM_TET10, 0, 0, calls, &m));
  printf("tet10 curved (8)  %10.3f              %10.3f\n",
         bench(FEM_TET10, 0.03, 1, calls / 3, &m), bench(FEM_TET10, 0.03, 0, calls / 3, &m));
  return 0;
}
