/* fem_blas.h - the OpenBLAS kernels under CHOLMOD's supernodal factorisation.
 *
 * OpenBLAS picks its kernels once, when the library loads, from the CPU it recognises or from
 * the environment variable OPENBLAS_CORETYPE. Debian 12's OpenBLAS 0.3.21 does not recognise
 * Intel CPUs newer than its release (family 6 model 207, Emerald Rapids, on the machines this
 * project is built and tested on) and falls back to its Prescott (SSE3) kernels, although the
 * CPU has AVX-512: CHOLMOD's dense updates (dgemm, dtrsm, dsyrk) then run several times slower
 * than they could (docs/fem_time_to_accuracy.md, "OpenBLAS kernels"). */
#ifndef FEM_BLAS_H
#define FEM_BLAS_H

/* Call first thing in main(). When OpenBLAS runs its Prescott fallback on a CPU that has
 * AVX-512 (F, CD, BW, DQ, VL) or AVX2 with FMA, and OPENBLAS_CORETYPE is not set, sets it to
 * SkylakeX or Haswell and re-executes the program (/proc/self/exe, same argv and PID), once.
 * Otherwise, or if the re-execution fails, returns and nothing changes. A user's own
 * OPENBLAS_CORETYPE is always kept. */
void fem_blas_select_kernels(char **argv);

/* The kernel set OpenBLAS runs ("SkylakeX", "Haswell", "Prescott", ...) [static string]. */
const char *fem_blas_kernels(void);

#endif
