/* mesh_test_util.h - helpers shared by the mesh tests: tolerance comparison, surface integrals
 * computed independently of the library (own tri6 quadrature), geometry paths. */
#ifndef MESH_TEST_UTIL_H
#define MESH_TEST_UTIL_H

#include "fem_mesh.h"

/* |a - b| <= atol + rtol |b|; prints what differed (with label) and returns 0 if not. */
int mt_close(const char *label, double a, double b, double atol, double rtol);
/* Path of meshes/<name> into buf. */
const char *mt_geo(const char *name, char *buf, int n);
/* Over the faces of s: area vector sum int n da [out] a[3] and flux -(1/3) int x.n da (the
 * volume enclosed, when s is closed), exact for tri3 and tri6 (degree-4 rule). */
void mt_surface_integrals(const FemMesh *m, const FemSurface *s, double a[3], double *vol);
/* Sum of face areas (positive). */
double mt_surface_area(const FemMesh *m, const FemSurface *s);

#endif
