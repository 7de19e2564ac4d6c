/* dem_parallel.c - the MPI transport of dem_parallel.h: start and stop, the broadcast of a
 * bridge call to the followers, and the reductions the bridge needs. */
#include "dem_parallel.h"

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sa_error.h"

static int started_here; /* dem_par_start called MPI_Init */
static int released;     /* the lead sent the release */

/* SOFTACT_DEM_TRACE set: every call and agreement on stderr (debugging a hang) */
static int tracing(void) {
  static int t = -1;
  if (t < 0) t = getenv("SOFTACT_DEM_TRACE") != NULL;
  return t;
}

/* The job size mpirun announces in the environment (Open MPI, then MPICH/PMI). */
static int env_int(const char *a, const char *b, int fallback) {
  const char *s = getenv(a);
  if (!s || !*s) s = getenv(b);
  if (!s || !*s) return fallback;
  char *end;
  long v = strtol(s, &end, 10);
  return *end || v < 0 || v > 1 << 20 ? fallback : (int)v;
}

static int mpi_up(void) {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  return init && !fin;
}

int dem_par_size(void) {
  if (mpi_up()) {
    int n;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
  }
  return env_int("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", 1);
}

int dem_par_rank(void) {
  if (mpi_up()) {
    int r;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
  }
  return env_int("OMPI_COMM_WORLD_RANK", "PMI_RANK", 0);
}

int dem_par_start(void) {
  if (dem_par_size() <= 1 || mpi_up()) return 0;
  int provided;
  SA_REQUIRE(MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) == MPI_SUCCESS,
             SA_ERR_LIBRARY, "MPI_Init failed");
  started_here = 1;
  return 0;
}

void dem_par_release(void) {
  if (!dem_par_leading() || released) return;
  DemParCall c;
  memset(&c, 0, sizeof c);
  c.op = -1; /* the release: never an opcode of the bridge */
  const void *none[DEM_PAR_NBUF] = {0};
  dem_par_call(&c, none);
  released = 1;
}

void dem_par_finish(void) {
  if (started_here && mpi_up()) MPI_Finalize();
  started_here = 0;
}

int dem_par_leading(void) { return mpi_up() && dem_par_size() > 1 && dem_par_rank() == 0; }

int dem_par_following(void) { return mpi_up() && dem_par_size() > 1 && dem_par_rank() > 0; }

void dem_par_call(DemParCall *c, const void *const buf[DEM_PAR_NBUF]) {
  if (tracing()) fprintf(stderr, "[lead] call %d\n", c->op);
  /* a non-blocking broadcast, as the followers wait for it (the two kinds never match) */
  MPI_Request rq;
  MPI_Ibcast(c, (int)sizeof *c, MPI_BYTE, 0, MPI_COMM_WORLD, &rq);
  MPI_Wait(&rq, MPI_STATUS_IGNORE);
  for (int k = 0; k < DEM_PAR_NBUF; k++)
    if (c->bytes[k] > 0) dem_par_bcast((void *)buf[k], (size_t)c->bytes[k]);
}

/* Wait for the lead's next broadcast without holding a core: poll at full speed while calls
 * come in quick succession (the coupling loop makes several per DEM step), then sleep between
 * polls (the lead is solving the FEM with every core, or writing output). */
static void wait_bcast(void *p, int n) {
  MPI_Request rq;
  MPI_Ibcast(p, n, MPI_BYTE, 0, MPI_COMM_WORLD, &rq);
  /* naps growing from 50 us to 2 ms: a follower waking thousands of times a second slowed
   * the lead's two FEM threads by a third (they wait for each other at every barrier) */
  struct timespec t0, t, nap = {0, 50000};
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (;;) {
    int done = 0;
    MPI_Test(&rq, &done, MPI_STATUS_IGNORE);
    if (done) return;
    clock_gettime(CLOCK_MONOTONIC, &t);
    if ((t.tv_sec - t0.tv_sec) + 1e-9 * (t.tv_nsec - t0.tv_nsec) < 5e-3) continue;
    nanosleep(&nap, NULL);
    if (nap.tv_nsec < 2000000) nap.tv_nsec *= 2;
  }
}

int dem_par_next(DemParCall *c, void *buf[DEM_PAR_NBUF]) {
  for (int k = 0; k < DEM_PAR_NBUF; k++) buf[k] = NULL;
  wait_bcast(c, (int)sizeof *c);
  if (tracing()) fprintf(stderr, "[follower] call %d\n", c->op);
  for (int k = 0; k < DEM_PAR_NBUF; k++) {
    if (c->bytes[k] <= 0) continue;
    buf[k] = malloc((size_t)c->bytes[k]);
    SA_REQUIRE(buf[k], SA_ERR_MEMORY, "DEM follower: cannot allocate %lld bytes",
               (long long)c->bytes[k]);
    dem_par_bcast(buf[k], (size_t)c->bytes[k]);
  }
  return 0;
}

int dem_par_agree(int rc) {
  if (!mpi_up() || dem_par_size() <= 1) return rc;
  if (tracing()) fprintf(stderr, "[%d] agree %d\n", dem_par_rank(), rc);
  int n = dem_par_size();
  int *all = malloc(sizeof(int) * (size_t)n);
  if (!all) return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d results", n);
  MPI_Allgather(&rc, 1, MPI_INT, all, 1, MPI_INT, MPI_COMM_WORLD);
  int worst = 0, who = -1;
  for (int r = 0; r < n && !worst; r++)
    if (all[r]) worst = all[r], who = r;
  free(all);
  if (rc || !worst) return rc;
  return SA_ERROR(worst, "the DEM failed on MPI rank %d of %d (its message is on its stderr)",
                  who, n);
}

void dem_par_bcast(void *p, size_t n) {
  /* in pieces below INT_MAX bytes */
  const size_t piece = (size_t)1 << 30;
  for (size_t off = 0; off < n; off += piece) {
    size_t len = n - off < piece ? n - off : piece;
    MPI_Bcast((char *)p + off, (int)len, MPI_BYTE, 0, MPI_COMM_WORLD);
  }
}

long long dem_par_sum_ll(long long v) {
  if (!mpi_up() || dem_par_size() <= 1) return v;
  long long s = 0;
  MPI_Allreduce(&v, &s, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

void dem_par_sum_to_lead(double *a, size_t n) {
  if (!mpi_up() || dem_par_size() <= 1 || n == 0) return;
  if (dem_par_rank() == 0)
    MPI_Reduce(MPI_IN_PLACE, a, (int)n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  else
    MPI_Reduce(a, NULL, (int)n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
}

void dem_par_max(double *a, size_t n) {
  if (!mpi_up() || dem_par_size() <= 1 || n == 0) return;
  MPI_Allreduce(MPI_IN_PLACE, a, (int)n, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
}

int dem_par_allgather(const void *local, int n_local, size_t size, void **out, int *n_all) {
  *out = NULL, *n_all = 0;
  int np = dem_par_size();
  if (!mpi_up() || np <= 1) {
    void *o = malloc(size * (size_t)(n_local > 0 ? n_local : 1));
    SA_REQUIRE(o, SA_ERR_MEMORY, "cannot allocate %d records", n_local);
    if (n_local > 0) memcpy(o, local, size * (size_t)n_local);
    *out = o, *n_all = n_local;
    return 0;
  }
  int bytes = (int)(size * (size_t)n_local);
  int *cnt = malloc(sizeof(int) * 2 * (size_t)np);
  SA_REQUIRE(cnt, SA_ERR_MEMORY, "cannot allocate %d counts", np);
  int *disp = cnt + np;
  MPI_Allgather(&bytes, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  long long total = 0;
  for (int r = 0; r < np; r++) disp[r] = (int)total, total += cnt[r];
  char *o = malloc((size_t)total + 1);
  if (!o) {
    free(cnt);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %lld bytes of grains", total);
  }
  MPI_Allgatherv(local, bytes, MPI_BYTE, o, cnt, disp, MPI_BYTE, MPI_COMM_WORLD);
  free(cnt);
  *out = o, *n_all = (int)(total / (long long)size);
  return 0;
}
