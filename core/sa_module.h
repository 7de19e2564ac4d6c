/* sa_module.h - what a physics module hands the CLI.
 *
 * A scene is selected by the presence of its module's trigger section in the case file;
 * a module whose sections are absent is never initialised (no LIGGGHTS, no MPI, no mesh
 * I/O in a scene that does not need them). Lifecycle driven by apps/softact.c:
 *   check(case, &scene)     parse + validate every key of the module (cross-key checks too),
 *                           touching no output; SA_ERR_INPUT names file:line and key
 *   write_resolved(scene,f) every key with its resolved value (defaults filled in)
 *   run(scene, run)         compute, writing into run->out_dir
 *   destroy(&scene)         free; accepts NULL
 *   resumes(scene)          optional: non-zero when the run continues the results already in
 *                           its folder (a checkpoint resume); it then writes into that folder
 *                           itself instead of a fresh one (sa_results_open)
 *   follow(scene)           optional: the scene runs on several MPI ranks (`mpirun -np N`);
 *                           a rank other than 0 calls this instead of run, touching no output
 *                           (rank 0 runs the scene and writes everything). A scene without it
 *                           refuses to start under mpirun with several ranks.
 *   ranks(scene)            optional: MPI ranks the case asks for; > 1 outside mpirun makes
 *                           softact start itself again under `mpirun -np N` (apps/softact.c) */
#ifndef SA_MODULE_H
#define SA_MODULE_H

#include <stdio.h>

#include "sa_params.h"
#include "sa_run.h"

typedef struct {
  const char *name;                  /* "hmsa", "fem" */
  const char *trigger;               /* section that selects this module's scene */
  const char *extends;               /* trigger of a module whose sections this scene also
                                      * reads (the FEM-DEM scene reads the actuator's [mesh]):
                                      * when both triggers are present, this module is chosen */
  const char *help;                  /* one line for --help */
  const SaParamTable *const *tables; /* every section the module owns */
  int ntables;
  int (*check)(const SaCase *c, void **scene);
  void (*write_resolved)(const void *scene, FILE *f);
  int (*run)(void *scene, SaRun *run);
  void (*destroy)(void **scene);
  int (*resumes)(const void *scene); /* may be NULL: never resumes */
  int (*follow)(void *scene);        /* may be NULL: one process only */
  int (*ranks)(const void *scene);   /* may be NULL: one rank */
} SaModule;

/* Scenes core provides itself (registered in apps/softact.c like every module's):
 * [compare], the comparison of earlier runs' bending curves (sa_compare.h). */
extern const SaModule sa_compare_module;

#endif
