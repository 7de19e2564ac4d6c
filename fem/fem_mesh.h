/* fem_mesh.h - tetrahedral meshes with named regions, surfaces and node sets, generated and read
 * through the Gmsh C API (gmshc.h) from the .geo sources in meshes/.
 *
 * Conventions
 *  - Coordinates in metres. Element node order is VTK's: tet4 corners 0..3 (positive volume);
 *    tet10 corners 0..3 then edge mid-nodes on edges 01, 12, 02, 03, 13, 23.
 *  - Regions: 3-D physical groups (e.g. "silicone", "reinforcement", "strain_limit").
 *  - Surfaces: 2-D physical groups (e.g. "cavity_wall", "fixed_end", "tip"), stored as boundary
 *    faces of the volume mesh: tri3 (tet4) or tri6 (tet10; corners 0..2 then mid-nodes of edges
 *    01, 12, 20), oriented so that the right-hand normal points OUT of the solid, with the index
 *    of the element the face belongs to. Each surface also defines a node set (its nodes).
 *    A 2-D group on an interface between two elements is stored with the lower-numbered
 *    element's orientation.
 *  - Every array is owned by the FemMesh; fem_mesh_destroy frees all. */
#ifndef FEM_MESH_H
#define FEM_MESH_H

#include "sa_params.h"

typedef enum { FEM_TET4 = 4, FEM_TET10 = 10 } FemElemType;

typedef struct {
  char name[64];
  int nfaces;
  int nfn;        /* nodes per face: 3 or 6 */
  int *faces;     /* nfn * nfaces node indices, outward normal (out of the solid) */
  int *face_elem; /* element owning each face */
  int nnodes;     /* node set of the surface (sorted, unique) */
  int *nodes;
} FemSurface;

typedef struct {
  int nnodes;
  double *xyz;      /* 3 * nnodes reference coordinates [m] */
  FemElemType etype;
  int nen;          /* nodes per element: 4 or 10 */
  int nelem;
  int *conn;        /* nen * nelem */
  int *region;      /* nelem region indices into region_names */
  int nregions;
  char (*region_names)[64];
  int nsurfaces;
  FemSurface *surfaces;
  char source[256]; /* file the mesh came from, for messages ("" when built by hand) */
} FemMesh;

/* Numbers handed to the .geo file before it is parsed (e.g. {"R_in", 6e-3}). The .geo files
 * give every parameter a default (`If(!Exists(R_in)) R_in = 6e-3; EndIf`). */
typedef struct {
  const char *name;
  double value;
} FemGeoParam;

/* Generate a mesh from geo_path [in] with parameters, target element size h [m] (the .geo may
 * refine locally relative to it) and order 1 (tet4) or 2 (tet10). Errors: missing file, Gmsh
 * failure, missing physical groups -> SA_ERR_INPUT naming the file. */
int fem_mesh_generate(const char *geo_path, int nparams, const FemGeoParam *params, double h,
                      int order, FemMesh **out);
/* Read a Gmsh .msh file (any version Gmsh reads). */
int fem_mesh_read(const char *msh_path, FemMesh **out);
/* Check element quality: SA_ERR_INPUT naming the first inverted or degenerate element (volume
 * <= rel_tol * mean volume, or tet10 with det J <= 0 at a quadrature point). */
int fem_mesh_check(const FemMesh *m, double rel_tol);
/* Lookups: index or -1. */
int fem_mesh_find_region(const FemMesh *m, const char *name);
const FemSurface *fem_mesh_find_surface(const FemMesh *m, const char *name);
/* Require named groups: SA_ERR_INPUT naming the missing one and the groups present. */
int fem_mesh_require(const FemMesh *m, int nregions, const char *const *regions, int nsurfaces,
                     const char *const *surfaces);
/* Several bodies / an interface: add surface `name` [owned by m] made of the faces of
 * `surface` oriented out of the elements of `region` (a 2-D group on an interface is stored
 * with the lower-numbered element's orientation; this selects the side). SA_ERR_INPUT when a
 * face does not bound the region. */
int fem_mesh_add_surface_side(FemMesh *m, const char *surface, const char *region,
                              const char *name);
/* Several bodies without shared nodes: append a copy of b [in] to a [in/out]: b's nodes,
 * elements (same element type), regions and surfaces follow a's, with indices offset. A region
 * or surface name of b that a already has is an SA_ERR_INPUT (the bodies stay apart); on any
 * error a is unchanged. */
int fem_mesh_append(FemMesh *a, const FemMesh *b);
/* Total reference volume of a region (-1 = all). */
double fem_mesh_volume(const FemMesh *m, int region);
/* Shape quality of the corner tets of a region (-1 = all): radius ratio 3 r_in / r_circ
 * (1 for a regular tet, 0 for a flat one); qmin [out] smallest, qmean [out] mean (either may be
 * NULL). Returns the index of the worst element (-1 if the region is empty). */
int fem_mesh_quality(const FemMesh *m, int region, double *qmin, double *qmean);
void fem_mesh_destroy(FemMesh **m);

/* Structured meshes (fem_mesh_block.c): mapped hexahedral blocks, each cell split into 6 tets
 * (Kuhn split, conforming between cells and between blocks whose shared index directions
 * agree), order 1 (tet4) or 2 (tet10, mid-nodes placed by the map). */
typedef void (*FemMeshMap)(const double xi[3], const void *ctx, double X[3]);
typedef struct {
  int n[3];            /* cells per direction */
  FemMeshMap map;      /* [0,1]^3 -> reference coordinates [m] */
  const void *ctx;     /* [borrowed] for map */
  const char *side[6]; /* surface names of sides xi0=0, xi0=1, xi1=0, xi1=1, xi2=0, xi2=1 (NULL:
                          none; several sides may share a name) */
} FemMeshBlock;
/* blocks [in]; merge_tol [m]: nodes closer than this are one node. One region, "solid".
 * A map may collapse a side to a line (the axis r = 0 of a polar block): the flat tets of its
 * cells are dropped and the others form wedges. *out [owned, fem_mesh_destroy]. */
int fem_mesh_blocks(int nblocks, const FemMeshBlock *blocks, int order, double merge_tol,
                    FemMesh **out);

/* The reference actuator (meshes/actuator.geo's geometry, groups and names) as a swept mesh
 * (fem_mesh_swept.c): a tensor grid in (r, theta, z) whose grid lines include every material
 * interface (band radii and angles, ring faces, the clamp line), each hexahedral cell split
 * into 6 tets (Kuhn), so elements are long along the rings and the band instead of isotropic;
 * the cap's core r < R_cav a polar grid whose axis cells are wedges. Regions silicone,
 * strain_limit, reinforcement (rings only); surfaces cavity_wall, fixed_end, tip, outer, as
 * the .geo file. Sizes: h along z and around (arc at the wall's mid radius), h_radial across
 * the silicone layers, h_band across the band, h_ring at the rings' faces (their corners), from
 * which the cells grow by the factor grade: along z up to h between the rings and up to half
 * the ring's height inside it, along r up to h_radial inside the wall and half the ring's
 * depth inside it. */
typedef struct {
  double R_cav, R_out, L_cav, t_cap, L_fix;
  double band_r_in, band_r_out, band_w;
  int rings, ring_n;
  double ring_d, ring_h, ring_pitch, ring_z0;
  double h, h_radial, h_band, h_ring, grade;
} FemSweptActuator;
/* ACTUATOR.md's dimensions with the given sizes. */
FemSweptActuator fem_swept_actuator_default(double h, double h_radial, double h_band,
                                            double h_ring, int rings);
/* p [in], order 1 or 2; SA_ERR_INPUT naming the bad dimension. *out [owned]. */
int fem_mesh_actuator_swept(const FemSweptActuator *p, int order, FemMesh **out);

#endif
