/* hmsa.h - the HMSA module as seen by the CLI: a scene is selected by the [hmsa] section.
 * Keys: tables hmsa_table ([hmsa]), hmsa_sweep_table ([hmsa_sweep]),
 * hmsa_poincare_table ([hmsa_poincare]); see docs/hmsa.md. The building blocks are public in
 * hmsa_model.h, hmsa_integrate.h, hmsa_analysis.h and hmsa_classify.h. */
#ifndef HMSA_H
#define HMSA_H

#include "sa_module.h"

extern const SaModule hmsa_module;
extern const SaParamTable hmsa_table, hmsa_sweep_table, hmsa_poincare_table;

#endif
