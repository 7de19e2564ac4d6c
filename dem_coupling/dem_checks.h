/* dem_checks.h - the run checks of the FEM-DEM scene (private to dem_coupling/): is every grain
 * still inside the bore (cavity + barrel), the force balance of the bed, and the packing implied
 * by the volume balance. Each returns numbers; dem_granular.c decides when a run stops. */
#ifndef DEM_CHECKS_H
#define DEM_CHECKS_H

typedef struct DemBore DemBore;

/* The bore seen by the grains: the cavity wall triangles tri [in] 3*ntri over nverts vertices
 * (normals out of the solid, i.e. into the cavity), its open top edge (which may zig-zag, as
 * the lower edge of [dem] rigid_band does) drawn straight up to a flat cap at the edge's highest
 * vertex or z = 0, whichever is higher, and above that cap the barrel of radius r_barrel.
 * *out [owned]. */
int dem_bore_create(int nverts, const int *tri, int ntri, double r_barrel, DemBore **out);
/* Count the grains whose centre is outside the bore: x [in] 3*n grain centres, xw [in]
 * 3*nverts current wall vertices; tol [m] slack on the barrel radius. For z < 0 the test is the
 * generalised winding number of the closed cavity surface (inside: |w| > 1/2, robust to the
 * wall's bending); first [out] index of the first offender or -1. */
int dem_bore_count_outside(const DemBore *b, const double *xw, int n, const double *x, double tol,
                           int *first);
void dem_bore_destroy(DemBore **b);

/* Momentum balance of the bed over a time T [s]: the mean force the grains put on all walls
 * F_walls [in] 3 [N], their weight W [N] (along -z) and the change of their total momentum dp
 * [in] 3 [kg m/s] over T. Newton's second law for the grains, dp / T = -F_walls - W e_z, so the
 * residual |F_walls + W e_z + dp / T| [N] returned is zero up to the sampling of the mean force
 * (lost or invented force shows in it; inertia does not, unlike a static balance). */
double dem_momentum_residual(const double F_walls[3], double W, const double dp[3], double T);

/* Generalised winding number of the closed triangle surface (tri over xyz) about point p:
 * sum of signed solid angles / 4 pi (van Oosterom & Strackee 1983). +-1 inside, 0 outside. */
double dem_winding_number(const double *xyz, const int *tri, int ntri, const double p[3]);

#endif
