/* hmsa_analysis.h - derived quantities of MODEL.md section 7 on top of hmsa_integrate.h:
 * steady amplitude under periodic load, settling time, Poincare samples, largest Lyapunov
 * exponent (Benettin), and frequency sweeps from rest (parallel) and by continuation. */
#ifndef HMSA_ANALYSIS_H
#define HMSA_ANALYSIS_H

#include "hmsa_integrate.h"
#include "sa_output.h"

typedef struct {
  int transient_periods;  /* at least this many forcing periods of transient (60) */
  double transient_tau;   /* and at least this much tau (400) */
  int measure_periods;    /* then measure over this many periods (40) */
  int samples_per_period; /* sampled at this many points per period (128) */
} HmsaSteadyOptions;

typedef struct {
  double a3, a;           /* (max - min)/2 of lambda3 and of lambda */
  double l3_min, l3_max, l_min, l_max;
  double y_end[HMSA_NEQ_MAX]; /* state at the end (an integer number of periods) */
  double tau_end;
} HmsaSteady;

void hmsa_steady_options_default(HmsaSteadyOptions *o);
/* Steady amplitude of the periodic response started at tau = 0 from y0 [in] (rest or the final
 * state of a previous frequency: the sq/lin loads have phase 0 at every period end). Extremes
 * are refined by a parabola through the three samples around them. it [in] must be created on
 * m (its omega may have been changed since). Polls sa_interrupted(). */
int hmsa_steady_amplitude(HmsaIntegrator *it, const HmsaModel *m, const HmsaSteadyOptions *o,
                          const double *y0, HmsaSteady *out);

/* Settling time (section 7) of a step load from rest to the relaxed equilibrium lambda3_eq:
 * grid dtau = 0.002 up to t_end, last exit from the 1 % band refined by bisection on
 * re-integrations from the grid point. *tau_s [out] (-1 if it never settles before t_end). */
int hmsa_settling_time(const HmsaModel *m, const HmsaIntegratorOptions *io, double lambda3_eq,
                       double t_end, double *tau_s);

/* Poincare samples x [out] n_points x n at tau = (n_transient + j) 2 pi/omega, j = 1..n_points,
 * from y0. lyap [out, may be NULL]: largest Lyapunov exponent per forcing period (Benettin: a
 * second trajectory at distance d0, renormalised every period, over the sampled periods).
 * progress [borrowed, may be NULL] advanced by one per period. */
int hmsa_poincare(const HmsaModel *m, const HmsaIntegratorOptions *io, const double *y0,
                  int n_transient, int n_points, double d0, double *x, double *lyap,
                  SaProgress *progress);

/* Sweep from rest: a3[i], a[i] [out] for omega[i], i < n, with `threads` workers (one
 * integrator and SUNContext each). status[i] [out]: 0 ok, else the error code of that point
 * (a3 = NaN). On interruption returns SA_ERR_INTERRUPTED with done points kept (status
 * SA_ERR_INTERRUPTED for the others). progress [borrowed, may be NULL]. */
int hmsa_sweep_rest(const HmsaModel *m, const HmsaIntegratorOptions *io,
                    const HmsaSteadyOptions *so, int n, const double *omega, int threads,
                    SaProgress *progress, double *a3, double *a, int *status);
/* Continuation sweeps: up (omega ascending, from rest at omega[0]) and down (descending, from
 * rest at omega[n-1]), each frequency started from the previous final state; run on two threads
 * when threads >= 2. up_a3, down_a3 [out] n each, indexed like omega. */
int hmsa_sweep_continuation(const HmsaModel *m, const HmsaIntegratorOptions *io,
                            const HmsaSteadyOptions *so, int n, const double *omega, int threads,
                            SaProgress *progress, double *up_a3, double *up_a, double *down_a3,
                            double *down_a);

#endif
