/* sa_run.c - the [run] section (core keys) and run-context helpers. */
#include "sa_run.h"

#include <stddef.h>

#include "sa_error.h"
#include "sa_output.h"

static const SaParam sa_run_params[] = {
    {"title", SA_PARAM_STRING, offsetof(SaRunParams, title), "-", "", 0, 0, 0, NULL,
     "free text describing the scene"},
    {"out_dir", SA_PARAM_STRING, offsetof(SaRunParams, out_dir), "-", "", 0, 0, 0, NULL,
     "results folder; empty = results/<case name> (overridden by --out)"},
    {"vtk_format", SA_PARAM_CHOICE, offsetof(SaRunParams, vtk_format), "-", "binary", 0, 0, 0,
     "binary|ascii", "encoding of the legacy VTK files"},
    {"plots", SA_PARAM_BOOL, offsetof(SaRunParams, plots), "-", "true", 0, 1, 0, NULL,
     "render PNG plots with gnuplot"},
    {"threads", SA_PARAM_INT, offsetof(SaRunParams, threads), "-", "0", 0, 1024, 0, NULL,
     "worker threads; 0 = all cores"},
};

const SaParamTable sa_run_table = {"run", "core", "output and execution settings common to every scene",
                                   sa_run_params, SA_NPARAMS(sa_run_params)};

int sa_run_path(const SaRun *run, const char *name, char *buf) {
  return sa_path_join(run->out_dir, name, buf);
}
