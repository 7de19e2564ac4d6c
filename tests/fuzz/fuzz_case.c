/* fuzz_case.c - libFuzzer target for the case-file parser and every module's key table.
 *
 * The input is a case file, checked exactly as `softact check` does (softact_case_validate:
 * parse, unknown sections/keys, scene selection, every table of the scene, the module's
 * cross-key checks) and then written out resolved into /dev/null. Nothing runs: no mesh, no
 * LIGGGHTS/MPI, no output folder. An input may end with command-line overrides: after a line
 * holding only "%%", every further line is applied as `--set` would apply it.
 *
 * Relative [FILE] paths resolve as for a case in cases/ (SOFTACT_FUZZ_CASE_NAME), so the seeds
 * (the .ini files of cases/) pass. Built two ways (tests/fuzz/CMakeLists.txt): with libFuzzer
 * (-DSOFTACT_FUZZ=ON, clang), and with replay_main.c as the corpus replay test. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_log.h"
#include "sa_params.h"
#include "softact_scene.h"

#ifndef SOFTACT_FUZZ_CASE_NAME
#define SOFTACT_FUZZ_CASE_NAME "fuzz.ini"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Apply each line of sets[0, n) as a --set override; stops at the first rejected one. */
static int apply_sets(SaCase *c, const char *sets, size_t n) {
  char *buf = malloc(n + 1);
  if (!buf) return SA_ERR_MEMORY;
  memcpy(buf, sets, n);
  buf[n] = 0;
  int rc = 0;
  for (char *line = buf, *next; !rc && line; line = next) {
    next = strchr(line, '\n');
    if (next) *next++ = 0;
    if (line[0]) rc = sa_case_override(c, line);
  }
  free(buf);
  return rc;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static FILE *sink;
  static int verbose; /* SOFTACT_FUZZ_VERBOSE=1: print why each input was rejected */
  if (!sink) {
    sink = fopen("/dev/null", "w");
    if (!sink) abort();
    sa_log_set_level(SA_LOG_ERROR);
    verbose = getenv("SOFTACT_FUZZ_VERBOSE") != NULL;
  }
  const char *text = (const char *)data;
  size_t nfile = size, nsets = 0;
  const char *sets = NULL;
  for (size_t i = 0; i + 2 <= size; i++) /* the "%%" line that starts the overrides */
    if ((i == 0 || text[i - 1] == '\n') && !memcmp(text + i, "%%", 2) &&
        (i + 2 == size || text[i + 2] == '\n')) {
      nfile = i;
      sets = text + i + 2;
      nsets = size - i - 2;
      break;
    }
  SaCase *c = NULL;
  const SaModule *m = NULL;
  void *scene = NULL;
  SaRunParams rp;
  int rc = sa_case_load_mem(SOFTACT_FUZZ_CASE_NAME, text, nfile, &c);
  if (!rc && sets) rc = apply_sets(c, sets, nsets);
  if (!rc) rc = softact_case_validate(c, &rp, &m, &scene);
  if (!rc) {
    softact_write_resolved(sink, c, &rp, m, scene);
    fflush(sink);
  }
  if (verbose) fprintf(stderr, "fuzz_case: %s\n", rc ? sa_error_message() : "valid");
  if (m && scene) m->destroy(&scene);
  sa_case_destroy(&c);
  sa_error_clear();
  return 0;
}
