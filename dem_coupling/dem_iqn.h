/* dem_iqn.h - interface quasi-Newton with inverse Jacobian from a least-squares model
 * (IQN-ILS; Degroote, Bathe & Vierendeels 2009, as in preCICE), for the iterated FEM-DEM
 * coupling step (private to dem_coupling/; docs/dem.md "Iterated coupling").
 *
 * The coupling step is a fixed point x = H(x): x the wall positions handed to the DEM, H the
 * DEM forces on that wall fed to the FEM, x~ = H(x) the wall the FEM returns. With the
 * residual r = x~ - x, each pair of iterates adds the columns dr = r^k - r^(k-1) to V and
 * dx~ = x~^k - x~^(k-1) to W; the next iterate is
 *     x^(k+1) = x~^k + W c,   c = argmin || V c + r^k ||_2,
 * i.e. a secant model of the inverse Jacobian on span(V) and plain substitution (x~) across
 * the rest. On a linear map it is equivalent to GMRES (tests/dem/test_dem_iqn.c checks the
 * exact solve of an n-dimensional linear fixed point: the (n+1)-th update is the solution). Columns of
 * earlier coupling steps are kept for `reuse_steps` steps (the bed's response changes slowly),
 * and columns that are nearly dependent on newer ones are dropped (QR filter), which keeps the
 * least-squares problem well posed when the DEM forces are noisy. */
#ifndef DEM_IQN_H
#define DEM_IQN_H

typedef struct DemIqn DemIqn;

/* n unknowns, at most max_cols columns, columns kept for reuse_steps earlier steps (0: only
 * the current step's). *out [owned]. */
int dem_iqn_create(int n, int max_cols, int reuse_steps, DemIqn **out);
/* The iterate when the model has no columns (a step's first update without reused columns,
 * after dem_iqn_clear): x + w (xt - x) instead of plain substitution xt (w = 1, the default).
 * w < 1 is preCICE's initial relaxation: with a map whose gain is far above 1 (a jammed bed
 * against a soft wall) xt lies far beyond the fixed point. 0 < w <= 1. */
void dem_iqn_set_initial_relaxation(DemIqn *q, double w);
/* A new coupling step: the last iterate of the previous step no longer pairs with the next;
 * columns older than reuse_steps steps are dropped. */
void dem_iqn_new_step(DemIqn *q);
/* Forget every column (e.g. at a checkpoint, so that a resumed run takes the same path). */
void dem_iqn_clear(DemIqn *q);
/* Given the iterate x [in] n and the map's value xt = H(x) [in] n, write the next iterate
 * x_next [out] n (may alias neither). Returns 0. */
int dem_iqn_update(DemIqn *q, const double *x, const double *xt, double *x_next);
/* Number of columns in the model now. */
int dem_iqn_columns(const DemIqn *q);
/* A trust region on the iterate: where some node of x_next [in/out] (n = 3 x nodes, xyz per
 * node) lies farther than max_change from the same node of x [in], shorten the whole update
 * x_next - x by one factor so that the farthest node moves exactly max_change (the direction
 * kept). Returns the factor (1: unchanged; also when max_change <= 0, no limit). */
double dem_iqn_limit_step(const double *x, double *x_next, int n, double max_change);
void dem_iqn_destroy(DemIqn **q);

#endif
