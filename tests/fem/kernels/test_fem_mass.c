/* test_fem_mass.c - lumped mass.
 *  - tet4: rho V / 4 per node.
 *  - straight tet10, HRZ: with int L^k dV = 6 V k!/(k+3)!, the consistent-mass diagonal is
 *    corner int (L(2L-1))^2 = (4/35 - 4/20 + 1/10) V = V/70, mid-node int 16 Li^2 Lj^2 = 8V/105;
 *    their sum is 4/70 + 48/105 = 18/35, so HRZ gives rho V (1/70)/(18/35) = rho V/36 per corner
 *    and rho V (8/105)/(18/35) = 4 rho V/27 per mid-node.
 *  - curved tet10: all masses positive and the total equals rho times the element volume,
 *    computed independently as the volume enclosed by its four tri6 faces (normals inward) with
 *    fem_face_volume (exact for a quadratic tet).
 *  - composite tet10 (fem_element_lumped_mass_mat): each sub-tet's mass / 4 to its nodes; the
 *    straight values and, curved, the total against rho times the volume enclosed by the faces'
 *    flat sub-triangles. Tolerances: round-off, 1e-13 relative. */
#include <stdio.h>

#include "fem_element.h"
#include "kt_util.h"

/* tet10 faces as tri6 (corners + mid-nodes in VTK numbering), right-hand normal inward. */
static const int tet10_face[4][6] = {
    {0, 1, 2, 4, 5, 6}, {0, 3, 1, 7, 8, 4}, {1, 3, 2, 8, 9, 5}, {0, 2, 3, 6, 9, 7}};

static double tet10_volume(const double *X)
{
  double V = 0;
  for (int f = 0; f < 4; f++) {
    double xf[18];
    for (int a = 0; a < 6; a++)
      for (int k = 0; k < 3; k++) xf[3 * a + k] = X[3 * tet10_face[f][a] + k];
    V += fem_face_volume(6, xf, NULL, NULL);
  }
  return V;
}

/* Volume enclosed by a tet10's faces split into their 4 flat sub-triangles (the composite
 * element's boundary), as tri3 with fem_face_volume. */
static double composite_volume(const double *X)
{
  static const int sub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  double V = 0;
  for (int f = 0; f < 4; f++)
    for (int t = 0; t < 4; t++) {
      double xf[9];
      for (int a = 0; a < 3; a++)
        for (int k = 0; k < 3; k++) xf[3 * a + k] = X[3 * tet10_face[f][sub[t][a]] + k];
      V += fem_face_volume(3, xf, NULL, NULL);
    }
  return V;
}

/* Every one of the 10 nodal masses m [in] positive and their sum the element mass M. */
static void positive_with_total(const char *what, const double *m, double M) {
  double tot = 0;
  for (int a = 0; a < 10; a++) {
    tot += m[a];
    if (!(m[a] > 0)) {
      fprintf(stderr, "%s mass node %d = %g not positive\n", what, a, m[a]);
      kt_fail++;
    }
  }
  char msg[160];
  snprintf(msg, sizeof msg, "%s total mass vs rho x enclosed volume", what);
  kt_close(msg, tot, M, 0, 1e-13);
}

int main(void)
{
  const double rho = 1130;
  char what[120];
  for (int t = 0; t < 5; t++) {
    double X[30], m[10];
    kt_random_tet(10, 0.2, 0, X);
    double V = tet10_volume(X);
    fem_element_lumped_mass(FEM_TET4, X, rho, m);
    for (int a = 0; a < 4; a++) kt_close("tet4 lumped mass", m[a], rho * V / 4, 0, 1e-13);
    fem_element_lumped_mass(FEM_TET10, X, rho, m);
    for (int a = 0; a < 10; a++) {
      snprintf(what, sizeof what, "straight tet10 HRZ mass node %d", a);
      kt_close(what, m[a], a < 4 ? rho * V / 36 : 4 * rho * V / 27, 0, 1e-13);
    }
    kt_random_tet(10, 0.2, 0.06, X);
    V = tet10_volume(X);
    fem_element_lumped_mass(FEM_TET10, X, rho, m);
    positive_with_total("curved tet10 HRZ", m, rho * V);
    /* composite tet10: sum rho V (enclosed by the flat sub-triangles of its faces); straight:
     * rho V/32 per corner, rho V/8 per mid-node, 3 rho V/16 at mid-nodes 02 and 13 (the
     * octahedron's diagonal, each in 6 of the 8 sub-tets of volume V/8) */
    FemMaterial cm = fem_material_from_e_nu(1e6, 0.3, rho);
    cm.tet10_composite = 1;
    kt_random_tet(10, 0.2, 0, X);
    V = tet10_volume(X);
    fem_element_lumped_mass_mat(FEM_TET10, X, &cm, m);
    for (int a = 0; a < 10; a++) {
      snprintf(what, sizeof what, "straight composite tet10 mass node %d", a);
      kt_close(what, m[a], rho * V * (a < 4 ? 1.0 / 32 : (a == 6 || a == 8) ? 3.0 / 16 : 1.0 / 8), 0,
               1e-13);
    }
    kt_random_tet(10, 0.2, 0.06, X);
    V = composite_volume(X);
    fem_element_lumped_mass_mat(FEM_TET10, X, &cm, m);
    positive_with_total("curved composite tet10", m, rho * V);
  }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
