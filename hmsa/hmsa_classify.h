/* hmsa_classify.h - classification of Poincare-section samples and peak finding on a
 * frequency-response curve (docs/hmsa_model.md sections 7-8).
 *
 * Pure C, no SUNDIALS: everything here works on arrays the caller has already computed.
 *
 * (a) Poincare section. x holds N states of dimension d (row n = state at tau = n T, T the
 *     forcing period, after the transient). The orbit is
 *       period-k       if x_{n+k} = x_n for every n (within atol + rtol * scale), smallest k;
 *       chaotic        if it is not periodic and the largest Lyapunov exponent of the Poincare
 *                      map is clearly positive;
 *       quasi-periodic if it is not periodic and that exponent is ~ 0 (points on a closed curve).
 *     The exponent is per forcing period (per iterate of the map; a flow exponent per unit tau
 *     times T). The caller passes it when it has integrated the variational equations; when it
 *     passes NAN the exponent is estimated from the samples themselves (nearest-neighbour
 *     divergence, Rosenstein et al. 1993), which is coarse: only exponents of order 0.1 per
 *     period and above are resolved.
 *
 * (b) Peaks. On a sampled curve (omega_i, a_i) with omega strictly increasing, the interior
 *     local maxima whose topographic prominence exceeds a threshold are peaks. Each peak is
 *     refined by golden-section search on [omega_{i-1}, omega_{i+1}] through a callback that
 *     returns the amplitude at any omega, and labelled relative to the primary frequency
 *     omega_p: omega ~ omega_p primary, omega ~ omega_p / n superharmonic of order n (the
 *     response contains n Omega), omega ~ n omega_p subharmonic of order n (response at
 *     Omega / n), n = 2 .. max_order. */
#ifndef HMSA_CLASSIFY_H
#define HMSA_CLASSIFY_H

/* ---------------------------------------------------------------- Poincare section */

typedef enum {
  HMSA_ORBIT_UNKNOWN = 0,   /* not periodic up to max_period and not decidable (e.g. still
                               contracting: transient not over, or period > max_period) */
  HMSA_ORBIT_PERIODIC,      /* period-k, k in result.period */
  HMSA_ORBIT_QUASIPERIODIC, /* not periodic, exponent ~ 0 */
  HMSA_ORBIT_CHAOTIC        /* not periodic, exponent clearly > 0 */
} HmsaOrbitKind;

typedef struct {
  int max_period;     /* largest k tested (16) */
  double rtol;        /* relative periodicity tolerance, on the scale max_n ||x_n||_inf (1e-4) */
  double atol;        /* absolute periodicity tolerance (1e-10) */
  double lyap_tol;    /* |exponent| <= lyap_tol counts as zero, for a caller's exponent (0.01) */
  double lyap_tol_data; /* same, for the exponent estimated from the samples (0.1) */
} HmsaClassifyParams;

typedef struct {
  HmsaOrbitKind kind;
  int period;         /* k for HMSA_ORBIT_PERIODIC, else 0 */
  double mismatch;    /* min over k of max_n ||x_{n+k} - x_n||_inf / scale (0 for exact repeat) */
  int mismatch_k;     /* the k attaining it */
  double lyap;        /* exponent used for the decision (caller's or estimated), NAN if unused */
  double lyap_data;   /* exponent estimated from the samples, NAN if not computed */
  double dim_corr;    /* correlation dimension of the sample cloud (~0 points, ~1 curve,
                         ~2 area), NAN if not computed; informative only */
} HmsaClassifyResult;

HmsaClassifyParams hmsa_classify_params_default(void);

/* Classify N samples x[n*d + j] (n < N, j < d).
 *   x       [in]  N x d, row-major
 *   lyap    [in]  largest Lyapunov exponent of the Poincare map per period, or NAN if unknown
 *   p       [in]  NULL for the defaults
 *   res     [out]
 * Needs N >= 4. Periods k with 2k > N are not tested. Non-finite samples give SA_ERR_NAN. */
int hmsa_poincare_classify(int N, int d, const double *x, double lyap,
                           const HmsaClassifyParams *p, HmsaClassifyResult *res);

/* Largest Lyapunov exponent of the map n -> n+1 estimated from the samples alone
 * (components scaled to unit range; mean log nearest-neighbour separation fitted over the
 * first few iterates). Needs N >= 20. *lyap [out]. */
int hmsa_poincare_lyapunov_estimate(int N, int d, const double *x, double *lyap);

/* Correlation dimension from the pair-distance counts at the 1 % and 10 % quantiles.
 * Needs N >= 20. *dim [out]. */
int hmsa_poincare_dimension(int N, int d, const double *x, double *dim);

const char *hmsa_orbit_kind_name(HmsaOrbitKind kind);

/* ---------------------------------------------------------------- peaks */

/* Amplitude at omega. Returns 0 on success, > 0 for a recoverable failure (the peak is then
 * left unrefined), < 0 for a fatal one (propagated). ctx [borrowed]. */
typedef int (*HmsaAmplitudeFn)(double omega, double *amplitude, void *ctx);

typedef enum {
  HMSA_PEAK_OTHER = 0,     /* no simple ratio to omega_p */
  HMSA_PEAK_PRIMARY,       /* omega ~ omega_p */
  HMSA_PEAK_SUPERHARMONIC, /* omega ~ omega_p / order */
  HMSA_PEAK_SUBHARMONIC    /* omega ~ omega_p * order */
} HmsaPeakKind;

typedef struct {
  double prominence_rel; /* keep peaks with prominence >= prominence_abs +        (0.05)  */
  double prominence_abs; /*   prominence_rel * (max a - min a)                     (0)     */
  double xtol;           /* golden-section stops when the bracket is < xtol times the
                            bracket width at the start, i.e. relative to 2 grid steps (1e-3) */
  int max_evals;         /* callback evaluations per peak at most (40) */
  double label_rtol;     /* |omega/omega_p - r| <= label_rtol * r labels ratio r (0.1) */
  int max_order;         /* ratios 1/n and n for n = 2 .. max_order (4) */
} HmsaPeakParams;

typedef struct {
  int index;             /* grid index of the local maximum */
  double omega_grid, amp_grid;
  double omega, amp;     /* refined (equal to the grid values if not refined) */
  double prominence;     /* on the grid */
  int refined;           /* 1 refined, 0 not (no callback, or it failed recoverably) */
  int refine_status;     /* 0, or the callback's recoverable code */
  int n_evals;           /* callback evaluations spent */
  double ratio;          /* omega / omega_p */
  HmsaPeakKind kind;
  int order;             /* n for super/subharmonic, 1 primary, 0 other */
} HmsaPeak;

HmsaPeakParams hmsa_peak_params_default(void);

/* Find, refine and label peaks of (omega[i], amp[i]), i < n, omega strictly increasing.
 *   fn, ctx        [in, borrowed] amplitude callback; fn == NULL: no refinement
 *   omega_p        [in]  primary frequency estimate; <= 0: the highest refined peak is primary
 *   cap            [in]  capacity of peaks; if more peaks qualify, the most prominent are kept
 *   peaks          [out] cap entries, sorted by omega
 *   n_peaks        [out] number stored (<= cap)
 * Grid end points are never peaks (no bracket). Recoverable callback failures leave that peak
 * unrefined (refine_status set, error trace cleared); fatal ones are returned. */
int hmsa_peaks_find(int n, const double *omega, const double *amp, const HmsaPeakParams *p,
                    HmsaAmplitudeFn fn, void *ctx, double omega_p, int cap, HmsaPeak *peaks,
                    int *n_peaks);

/* Label one frequency against omega_p: kind and order [out], ratio [out, may be NULL]. */
void hmsa_peak_label(double omega, double omega_p, const HmsaPeakParams *p, HmsaPeakKind *kind,
                     int *order, double *ratio);

/* Golden-section maximisation of fn on [a, b]: stops when the bracket is < xtol (absolute) or
 * after max_evals evaluations. The best point evaluated is returned in *x_best, *f_best [out];
 * *n_evals [out, may be NULL]. Callback codes are returned unchanged (with a trace frame). */
int hmsa_golden_max(HmsaAmplitudeFn fn, void *ctx, double a, double b, double xtol,
                    int max_evals, double *x_best, double *f_best, int *n_evals);

const char *hmsa_peak_kind_name(HmsaPeakKind kind);

#endif
