/* sa_run.h - the context of one run, handed by the CLI to the module that runs the scene.
 * Core keys live in the [run] section (table sa_run_table). */
#ifndef SA_RUN_H
#define SA_RUN_H

#include "sa_params.h"
#include "sa_vtk.h"

typedef struct {
  char title[SA_STR_MAX];
  char out_dir[SA_STR_MAX];  /* "" = results/<case stem> */
  char vtk_format[SA_STR_MAX]; /* ascii | binary */
  int plots;                 /* render PNG plots */
  int threads;               /* worker threads, 0 = all cores */
} SaRunParams;

extern const SaParamTable sa_run_table;

typedef struct {
  const SaCase *scase;  /* [borrowed] the parsed case with overrides */
  SaRunParams params;
  char out_dir[SA_STR_MAX]; /* resolved results folder (exists once the run starts) */
  SaVtkEncoding vtk;
  int threads;          /* resolved (>= 1) */
} SaRun;

/* Results path for a file name: buf (SA_STR_MAX) = out_dir/name. */
int sa_run_path(const SaRun *run, const char *name, char *buf);

#endif
