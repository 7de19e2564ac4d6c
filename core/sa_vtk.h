/* sa_vtk.h - legacy VTK writer (our own code, no VTK library).
 *
 * DATASET UNSTRUCTURED_GRID (vertex, line, triangle, tet4, tet10 cells) or POLYDATA points
 * with VERTICES (particles); POINT_DATA / CELL_DATA arrays of scalars (1 component),
 * vectors (3) or tensors (9, row-major); ASCII (%.17g) or BINARY (big-endian, float64
 * coordinates and data, int32 cells). Arrays are buffered and written on commit, so they may
 * be added in any order. Written atomically (sa_output.h).
 *
 * Time series: a ParaView ".vtk.series" JSON index; rewritten atomically after every added
 * file, so an interrupted run leaves a valid series of the steps completed. */
#ifndef SA_VTK_H
#define SA_VTK_H

typedef enum { SA_VTK_ASCII = 0, SA_VTK_BINARY = 1 } SaVtkEncoding;

/* VTK cell type ids. tet10 node order is VTK's: 4 corners, then edge mid-nodes
 * 01, 12, 02, 03, 13, 23. */
enum {
  SA_VTK_VERTEX = 1,
  SA_VTK_LINE = 3,
  SA_VTK_TRIANGLE = 5,
  SA_VTK_TETRA = 10,
  SA_VTK_QUADRATIC_TETRA = 24
};

typedef struct SaVtk SaVtk;

/* Unstructured grid. xyz [in] 3*npoints; cell_types [in] ncells; cell_offsets [in] ncells+1
 * (CSR into conn); conn [in] node indices (0-based). Inputs are copied. */
int sa_vtk_grid_open(const char *path, SaVtkEncoding enc, const char *title, int npoints,
                     const double *xyz, int ncells, const int *cell_types, const int *cell_offsets,
                     const int *conn, SaVtk **out);
/* Point cloud (POLYDATA with one vertex per point). */
int sa_vtk_points_open(const char *path, SaVtkEncoding enc, const char *title, int npoints,
                       const double *xyz, SaVtk **out);
/* ncomp 1 (SCALARS), 3 (VECTORS) or 9 (TENSORS). values [in] ncomp*n, copied. */
int sa_vtk_point_data(SaVtk *v, const char *name, int ncomp, const double *values);
int sa_vtk_cell_data(SaVtk *v, const char *name, int ncomp, const double *values);
int sa_vtk_commit(SaVtk **v);
void sa_vtk_abort(SaVtk **v);

typedef struct SaVtkSeries SaVtkSeries;
int sa_vtk_series_open(const char *path, SaVtkSeries **out); /* path ends in ".vtk.series" */
/* file: name relative to the series file's folder. */
int sa_vtk_series_add(SaVtkSeries *s, const char *file, double time);
void sa_vtk_series_close(SaVtkSeries **s);

#endif
