/* fem_actuator.h - the reference actuator (/work/shared/ACTUATOR.md) as a FEM model, shared by
 * every scene of it (pressure baseline, FEM-DEM coupling, Mohr-Coulomb fill): the [mesh],
 * [material] and [solver] case tables, mesh generation from meshes/actuator.geo, the material
 * of each mesh region and the solver parameters. A scene adds its own loads and outputs. */
#ifndef FEM_ACTUATOR_H
#define FEM_ACTUATOR_H

#include <stdio.h>

#include "fem.h"
#include "sa_params.h"

typedef struct {
  char geo[SA_STR_MAX];
  double h, h_band, h_ring;
  int order, rings;
  char kind[SA_STR_MAX]; /* gmsh (the .geo, isotropic tets) | swept (fem_mesh_actuator_swept) */
  double h_radial, grade; /* swept only */
} FemMeshParams;

typedef struct {
  char model[SA_STR_MAX];
  double c10, c01, c20, c30, kappa_ratio, rho;
  double limit_e, limit_nu, limit_rho, ring_e, ring_nu, ring_rho;
  char regions[SA_STR_MAX]; /* "region:set, ..." with set silicone | limit | ring */
} FemMatParams;

typedef struct {
  double rtol, dl_min, reuse_rate, krylov_rtol;
  int max_iter, threads, krylov_max, ls_memory;
  char linear_solver[SA_STR_MAX], predictor[SA_STR_MAX], merit[SA_STR_MAX], indefinite[SA_STR_MAX];
} FemSolverCaseParams;

/* The three sections every actuator scene reads. */
typedef struct {
  FemMeshParams mesh;
  FemMatParams mat;
  FemSolverCaseParams solver;
} FemActuatorCase;

extern const SaParamTable fem_actuator_mesh_table;     /* [mesh] */
extern const SaParamTable fem_actuator_material_table; /* [material] */
extern const SaParamTable fem_actuator_solver_table;   /* [solver] */

/* Load and cross-check [mesh], [material], [solver] of case c [in] into a [out]. */
int fem_actuator_load(const SaCase *c, FemActuatorCase *a);
/* Write the three resolved sections to f. */
void fem_actuator_write_resolved(const FemActuatorCase *a, FILE *f);
/* Generate the mesh of a [in] (Gmsh from [mesh] geo, or the swept grid): *m [owned]. */
int fem_actuator_mesh(const FemActuatorCase *a, FemMesh **m);
/* Material of every region of m [in] from a [in]: mats [out] m->nregions entries. Which
 * material set (silicone: the law `model` with c10..c30, kappa_ratio, rho; limit and ring:
 * stiff neo-Hookean from E, nu, rho) a region gets is the case's [material] regions map
 * (default "silicone:silicone, strain_limit:limit, reinforcement:ring"); a region it does not
 * name is an input error. The laws come from the law registry (fem_law.h). */
int fem_actuator_materials(const FemActuatorCase *a, const FemMesh *m, FemMaterial *mats);
/* Solver parameters of a [in]; run_threads is used when [solver] threads = 0. */
FemSolverParams fem_actuator_solver_params(const FemActuatorCase *a, int run_threads);

#endif
