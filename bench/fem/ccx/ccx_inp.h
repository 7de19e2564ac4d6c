/* ccx_inp.h - a CalculiX/Abaqus input-deck (.inp) writer for the CalculiX peer comparison of the
 * FEM module (bench only: never part of the library or the test suite).
 *
 * A CcxModel holds one mesh in CalculiX's conventions plus what the deck needs: node sets with
 * constrained dofs, element faces under a follower pressure, materials per region and a
 * load-ramped NLGEOM static step. ccx_model_write writes
 *   NAME.inp  the deck (all node/element numbers 1-based = index + 1);
 *   NAME.tip  a side file for ccx_post: the tip nodes (number, x, y, z) and the tip surface as
 *             flat sub-triangles (node numbers, right-hand normal out of the solid), so the tip
 *             displacement and bending angle are computed with one definition for every mesh.
 *
 * CalculiX conventions (checked against ccx's own face tables, e.g. removeface.f: ifacet/ifaceq,
 * and verified on analytic cases by bench/fem/ccx/run.sh verify):
 *  - C3D10: corners 1-4 (positive volume: (x2-x1) x (x3-x1) . (x4-x1) > 0), then the mid-nodes
 *    5:(1,2) 6:(2,3) 7:(3,1) 8:(1,4) 9:(2,4) 10:(3,4) -- the same order as VTK's tet10.
 *    Faces: F1 = {1,2,3}, F2 = {1,2,4}, F3 = {2,3,4}, F4 = {1,3,4}.
 *  - C3D20(R): corners 1-4 on the face zeta = -1 counter-clockwise seen from zeta = +1, corners
 *    5-8 above them; mid-nodes 9:(1,2) 10:(2,3) 11:(3,4) 12:(4,1) 13:(5,6) 14:(6,7) 15:(7,8)
 *    16:(8,5) 17:(1,5) 18:(2,6) 19:(3,7) 20:(4,8). Faces: F1 = {1,2,3,4} (zeta = -1),
 *    F2 = {5,6,7,8}, F3 = {1,2,6,5}, F4 = {2,3,7,6}, F5 = {3,4,8,7}, F6 = {4,1,5,8}.
 *  - *DLOAD Pk: a positive pressure pushes into the element through face k; under NLGEOM it
 *    follows the face (follower load).
 *
 * Materials: the silicone region is *HYPERELASTIC, YEOH (C10, C20, C30, D1 = 2/kappa); every
 * other region is *HYPERELASTIC, NEO HOOKE with C10 = mu/2, D1 = 2/kappa from (E, nu). Both are
 * W = W_iso(I1b) + (kappa/2)(J - 1)^2, exactly the laws of fem_material.h (YEOH and
 * STIFF_NEOHOOKE), so the two codes solve the same continuum problem. */
#ifndef CCX_INP_H
#define CCX_INP_H

#include <stdio.h>

#define CCX_MAX_REGIONS 8
#define CCX_MAX_BCS 8
#define CCX_MAX_TIME_POINTS 64

typedef struct {
  char name[64];
  int stiff;         /* 0: Yeoh silicone, 1: neo-Hookean from E, nu */
  double E, nu;      /* stiff regions [Pa, -] */
} CcxRegion;

typedef struct {
  char name[32];
  int first, last;   /* constrained dofs (1..3) */
  int n;
  int *nodes;        /* [owned] 0-based */
} CcxBc;

typedef struct {
  /* mesh */
  const char *etype;   /* "C3D10", "C3D20R", "C3D20" */
  int nen;             /* 10 or 20 */
  int nnodes;
  double *xyz;         /* [owned] 3 * nnodes */
  int nelem;
  int *conn;           /* [owned] nen * nelem, 0-based, CalculiX order */
  int *region;         /* [owned] nelem */
  int nregions;
  CcxRegion regions[CCX_MAX_REGIONS];
  /* boundary conditions and load */
  int nbcs;
  CcxBc bcs[CCX_MAX_BCS];
  int nload;
  int *load_elem;      /* [owned] 0-based element */
  int *load_face;      /* [owned] CalculiX face number 1..6 */
  /* tip surface for the post-processor */
  int ntip_nodes;
  int *tip_nodes;      /* [owned] */
  int ntip_tri;
  int *tip_tri;        /* [owned] 3 * ntip_tri */
  /* silicone */
  double c10, c20, c30, kappa; /* [Pa] */
  /* step */
  double pressure;     /* [Pa] at step time 1 */
  double inc0, incmin, incmax; /* increment sizes as fractions of the step (time 1) */
  int print_all;       /* 1: print U of every node at every increment (verification runs) */
  /* > 0: print U only at these step times (*TIME POINTS, TIME POINTS= on *NODE PRINT; ccx cuts
   * an increment that would pass one, so each is hit exactly) instead of every increment */
  int ntime_points;
  double time_points[CCX_MAX_TIME_POINTS];
} CcxModel;

/* Write NAME.inp and NAME.tip (base [in] is NAME). */
int ccx_model_write(const CcxModel *m, const char *base);
/* Signed volume of a corner tetrahedron (a, b, c, d coordinates, 3 each). */
double ccx_tet_volume(const double *a, const double *b, const double *c, const double *d);
/* Output times from a comma-separated list list [in] (ascending, in (0, 1], e.g.
 * "0.25,0.5,0.75,1"): sets m->ntime_points and m->time_points. */
int ccx_model_set_time_points(CcxModel *m, const char *list);
/* Add a BC set (nodes copied). */
int ccx_model_add_bc(CcxModel *m, const char *name, int first, int last, int n, const int *nodes);
void ccx_model_free(CcxModel *m);

#endif
