/* dem_parallel.h - LIGGGHTS domain-decomposed over MPI ranks while the rest of softact stays on
 * one (private to dem_coupling).
 *
 * Started as `mpirun -np N softact run CASE` (docs/dem.md, "MPI scale-out"), every rank runs
 * softact, but only rank 0 (the lead) runs the scene: the pour, the coupling loop, the FEM,
 * the checks and every output. The other ranks (followers) wait in dem_par_follow() and make
 * each DemBridge call the lead makes, with the same arguments, so that LIGGGHTS' collective
 * commands run on all ranks together:
 *   - every public dem_bridge_* function that touches LIGGGHTS begins, on the lead, by
 *     broadcasting its name and arguments (dem_par_call); a follower receives them and calls the
 *     same function;
 *   - inside, data LIGGGHTS holds per rank are combined: grains gathered in tag order, wall
 *     forces summed over the ranks that own the triangles (LIGGGHTS already moves the force
 *     on a ghost triangle to its owner), grain counts summed;
 *   - calls that can fail on one rank only agree on the result (dem_par_agree), so that no
 *     rank goes on into a collective the others left.
 * With one rank (no mpirun) nothing here initialises MPI and the bridge is the serial one, bit
 * for bit.
 *
 * A follower polls for the next call and sleeps once none came for a while, so that it leaves
 * its core to the lead's FEM threads during a solve (mpirun must not bind ranks to one core:
 * `--bind-to none`). */
#ifndef DEM_PARALLEL_H
#define DEM_PARALLEL_H

#include <stddef.h>
#include <stdint.h>

/* Ranks of the job: MPI's once started, else what mpirun put in the environment (1 when the
 * process was not started by mpirun). */
int dem_par_size(void);
/* This process's rank (0 without mpirun). */
int dem_par_rank(void);
/* MPI_Init when the job has several ranks (idempotent; 0 or an SA_ERR code). */
int dem_par_start(void);
/* The lead tells the followers to return from dem_par_follow (no-op on one rank or a follower). */
void dem_par_release(void);
/* MPI_Finalize if dem_par_start initialised MPI. */
void dem_par_finish(void);
/* 1 on rank 0 of a several-rank job that has started MPI: calls must be broadcast. */
int dem_par_leading(void);
/* 1 on a follower. */
int dem_par_following(void);

/* One broadcast call: an opcode, small integer and real arguments, and up to four buffers. */
#define DEM_PAR_NBUF 4
typedef struct {
  int32_t op;
  int32_t i[6];
  double d[8];
  int64_t bytes[DEM_PAR_NBUF]; /* length of each buffer (0: none) */
} DemParCall;

/* Lead: broadcast c and its buffers buf[k] (bytes[k] each). */
void dem_par_call(DemParCall *c, const void *const buf[DEM_PAR_NBUF]);
/* Follower: the next call into *c, its buffers into buf[k] (malloc'ed; the caller frees);
 * 0 or an SA_ERR code. */
int dem_par_next(DemParCall *c, void *buf[DEM_PAR_NBUF]);
/* The worst (lowest, SA_ERR codes being negative) of every rank's rc; a rank whose own rc was
 * 0 gets an error naming the rank that failed (that rank printed its own message). */
int dem_par_agree(int rc);
/* Broadcast n bytes from the lead. */
void dem_par_bcast(void *p, size_t n);
/* Sum of v over the ranks, on every rank. */
long long dem_par_sum_ll(long long v);
/* Element-wise sum of a[0..n) over the ranks into a on rank 0 (other ranks: unchanged). */
void dem_par_sum_to_lead(double *a, size_t n);
/* Element-wise maximum of a[0..n) over the ranks, on every rank. */
void dem_par_max(double *a, size_t n);
/* Concatenation of every rank's n_local records of `size` bytes, in rank order, on every rank:
 * *out (malloc'ed, the caller frees) holds *n_all records. 0 or an SA_ERR code. */
int dem_par_allgather(const void *local, int n_local, size_t size, void **out, int *n_all);

#endif
