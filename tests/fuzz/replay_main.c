/* replay_main.c - runs LLVMFuzzerTestOneInput (fuzz_case.c) once on every file given, or on
 * every file in a folder given, without libFuzzer: the committed corpus (tests/fuzz/corpus/)
 * as a regression test with the normal compiler. Silent on success; a crash or sanitizer
 * report fails the test (the file being replayed is printed first with -v).
 *
 * `fuzz_case_replay --dict` prints a libFuzzer dictionary made from the key tables of every
 * built scene (sections, keys, choices) plus the syntax of values (tests/fuzz/case.dict). */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "softact_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* One dictionary entry: the n bytes at s quoted, '"' and backslash escaped, other bytes
 * outside printable ASCII as \xAB. */
static void dict_entry(const char *s, size_t n) {
  putchar('"');
  for (size_t i = 0; i < n; i++) {
    unsigned char u = (unsigned char)s[i];
    if (u == '"' || u == '\\') printf("\\%c", u);
    else if (u < 32 || u >= 127) printf("\\x%02X", u);
    else putchar(u);
  }
  puts("\"");
}

static void dict_table(const SaParamTable *t) {
  char buf[256];
  snprintf(buf, sizeof buf, "[%s]", t->section);
  dict_entry(buf, strlen(buf));
  for (int k = 0; k < t->nparams; k++) {
    const SaParam *p = &t->params[k];
    snprintf(buf, sizeof buf, "%s = ", p->key);
    dict_entry(buf, strlen(buf));
    if (p->def[0] && strlen(p->def) < 64 && !p->choices) dict_entry(p->def, strlen(p->def));
    for (const char *c = p->choices; c && *c;) { /* each choice of "a|b|c" */
      const char *bar = strchr(c, '|');
      size_t len = bar ? (size_t)(bar - c) : strlen(c);
      dict_entry(c, len);
      c = bar ? bar + 1 : NULL;
    }
  }
}

/* Value syntax the tables do not spell: booleans, numbers at the edges, lists, the region map
 * and the law syntax of [material] regions (fem_actuator.c), the --set part (fuzz_case.c). */
static const char *const dict_extra[] = {
    "\n", " = ", "=", ";", "#", ",", ":", "(", ")", "[", "]", "%%\n", ".",
    "true", "false", "yes", "no", "on", "off", "0", "1", "-1", "1e308", "-1e308", "1e-320",
    "inf", "-inf", "nan", "0x1p-1074", "2147483647", "2147483648", "-2147483649",
    "silicone", "limit", "ring", "neohooke(", "mooney_rivlin(", "yeoh(", "stiff_neohooke(",
    "mohr_coulomb(", "c10 = ", "c01 = ", "c20 = ", "c30 = ", "kappa = ", "e = ", "nu = ",
    "young = ", "poisson = ", "friction_angle = ", "cohesion = ", "dilation_angle = ", "rho = ",
    "../meshes/actuator.geo", "/dev/null", "\xef\xbb\xbf", "\r\n"};

static void print_dict(void) {
  const SaParamTable *seen[128];
  int ns = 0;
  dict_table(&sa_run_table);
  for (int i = 0; softact_modules[i]; i++)
    for (int t = 0; t < softact_modules[i]->ntables && ns < 128; t++) {
      const SaParamTable *tb = softact_modules[i]->tables[t];
      int dup = 0;
      for (int j = 0; j < ns; j++) dup |= seen[j] == tb;
      if (dup) continue;
      seen[ns++] = tb;
      dict_table(tb);
    }
  for (size_t i = 0; i < sizeof dict_extra / sizeof *dict_extra; i++)
    dict_entry(dict_extra[i], strlen(dict_extra[i]));
}

static int verbose;

static int replay_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "replay: cannot open %s\n", path);
    return -1;
  }
  size_t cap = 4096, n = 0, k;
  uint8_t *buf = malloc(cap);
  while (buf && (k = fread(buf + n, 1, cap - n, f)) > 0) {
    n += k;
    if (n == cap) {
      uint8_t *b = realloc(buf, cap *= 2);
      if (!b) free(buf);
      buf = b;
    }
  }
  fclose(f);
  if (!buf) {
    fprintf(stderr, "replay: out of memory reading %s\n", path);
    return -1;
  }
  if (verbose) fprintf(stderr, "replay: %s (%zu bytes)\n", path, n);
  /* an exact-size copy, so that ASan catches a read past the input's end */
  uint8_t *exact = malloc(n ? n : 1);
  if (!exact) return free(buf), -1;
  memcpy(exact, buf, n);
  free(buf);
  LLVMFuzzerTestOneInput(exact, n);
  free(exact);
  return 0;
}

int main(int argc, char **argv) {
  int nfiles = 0, bad = 0;
  if (argc == 2 && !strcmp(argv[1], "--dict")) {
    print_dict();
    return 0;
  }
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-v")) {
      verbose = 1;
      continue;
    }
    struct stat st;
    if (stat(argv[i], &st)) {
      fprintf(stderr, "replay: no such file or folder %s\n", argv[i]);
      bad++;
      continue;
    }
    if (!S_ISDIR(st.st_mode)) {
      bad += replay_file(argv[i]) != 0;
      nfiles++;
      continue;
    }
    DIR *d = opendir(argv[i]);
    if (!d) {
      fprintf(stderr, "replay: cannot read folder %s\n", argv[i]);
      bad++;
      continue;
    }
    for (struct dirent *e; (e = readdir(d));) {
      if (e->d_name[0] == '.') continue;
      char path[4096];
      snprintf(path, sizeof path, "%s/%s", argv[i], e->d_name);
      bad += replay_file(path) != 0;
      nfiles++;
    }
    closedir(d);
  }
  if (nfiles == 0) {
    fprintf(stderr, "replay: no inputs (usage: fuzz_case_replay [-v] FILE|DIR ...)\n");
    return 1;
  }
  if (verbose) fprintf(stderr, "replay: %d inputs\n", nfiles);
  return bad ? 1 : 0;
}
