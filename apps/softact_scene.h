/* softact_scene.h - the scenes this softact was built with and the validation that
 * `softact check` (and `softact run`, before it computes) applies to a parsed case.
 *
 * Split out of softact.c so that the case-file fuzzer (tests/fuzz/) drives exactly the path
 * the command line uses: no output folder, no LIGGGHTS/MPI, nothing written. */
#ifndef SOFTACT_SCENE_H
#define SOFTACT_SCENE_H

#include <stdio.h>

#include "sa_module.h"
#include "sa_params.h"
#include "sa_run.h"

/* Every built scene module, NULL-terminated. */
extern const SaModule *const softact_modules[];

/* Validate c [in] (file plus --set overrides): unknown sections/keys against every module,
 * then which scene it describes (*m [out]), the scene's own tables, [run] into rp [out] and
 * the module's check, which creates *scene [owned; free with (*m)->destroy]. On failure
 * *scene is NULL and the error names file:line and the key. */
int softact_case_validate(const SaCase *c, SaRunParams *rp, const SaModule **m, void **scene);

/* Write the resolved case (the [run] table + the module's tables) to f [in]. */
void softact_write_resolved(FILE *f, const SaCase *c, const SaRunParams *rp, const SaModule *m,
                            const void *scene);

/* The key reference of every table (`softact keys`, Markdown), each shared table once. */
void softact_write_keys(FILE *f);

#endif
