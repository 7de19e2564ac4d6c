/* sa_params.h - case files (INI via libinih) and the parameter tables that drive them.
 *
 * Each module declares its keys once, in an SaParamTable: type, SI unit, default, valid range
 * and help text, plus the offset of the field it sets in the module's params struct. That one
 * table drives parsing, validation, `softact check` output, the resolved case written beside
 * the results, and the key reference in the README (`softact keys`).
 *
 * Field storage by type:
 *   SA_PARAM_REAL   double          SA_PARAM_INT   int        SA_PARAM_BOOL  int (0/1)
 *   SA_PARAM_STRING char[SA_STR_MAX]   SA_PARAM_CHOICE char[SA_STR_MAX] (one of `choices`)
 *   SA_PARAM_FILE   char[SA_STR_MAX]   path resolved against the case file's folder (then, for
 *                   defaults and relative paths not found there, the source tree); must exist
 *   SA_PARAM_REAL_LIST SaRealList   comma-separated reals, each within [min, max]; no empty item
 */
#ifndef SA_PARAMS_H
#define SA_PARAMS_H

#include <stddef.h>
#include <stdio.h>

#define SA_STR_MAX 512
#define SA_LIST_MAX 64

typedef enum {
  SA_PARAM_REAL,
  SA_PARAM_INT,
  SA_PARAM_BOOL,
  SA_PARAM_STRING,
  SA_PARAM_CHOICE,
  SA_PARAM_FILE,
  SA_PARAM_REAL_LIST
} SaParamType;

/* Range flags: by default [min, max] is closed; these make an end open. */
enum { SA_MIN_OPEN = 1, SA_MAX_OPEN = 2 };

typedef struct {
  int n;
  double v[SA_LIST_MAX];
} SaRealList;

typedef struct {
  const char *key;      /* lower_snake, equal to the field it sets */
  SaParamType type;
  size_t offset;        /* offsetof(struct, field) */
  const char *unit;     /* SI unit, "-" if dimensionless */
  const char *def;      /* default, as it would be written in the file ("" = empty) */
  double min, max;      /* valid range for REAL/INT/REAL_LIST; min = max = 0: any finite value;
                           use -HUGE_VAL / HUGE_VAL for a one-sided range */
  int open;             /* SA_MIN_OPEN | SA_MAX_OPEN */
  const char *choices;  /* "a|b|c" for SA_PARAM_CHOICE */
  const char *help;     /* one line */
} SaParam;

typedef struct {
  const char *section;  /* INI section this table owns */
  const char *module;   /* owning module ("core", "fem", "hmsa", "dem") */
  const char *help;     /* one line about the section */
  const SaParam *params;
  int nparams;
} SaParamTable;

#define SA_NPARAMS(arr) ((int)(sizeof(arr) / sizeof((arr)[0])))

/* A parsed case file: (section, key, value) entries with their file:line. */
typedef struct SaCase SaCase;

/* Parse path [in], a regular file (a folder, FIFO or device is refused). Syntax errors,
 * control bytes, repeated keys or sections, lines too long to parse and files with no
 * section are SA_ERR_INPUT naming file:line; a UTF-8 byte-order mark is skipped. *out [owned]
 * is NULL on failure. */
int sa_case_load(const char *path, SaCase **out);
/* The same from memory: the len bytes at text [in] (may hold NUL bytes, which are rejected
 * like in a file), named name [in] in messages (its folder is where relative [FILE] paths are
 * looked up). For tests and the fuzzer (tests/fuzz/). */
int sa_case_load_mem(const char *name, const char *text, size_t len, SaCase **out);
/* Apply a command-line override "section.key=value" (recorded as coming from --set); blanks
 * around the names and the value are dropped; control characters are SA_ERR_INPUT. */
int sa_case_override(SaCase *c, const char *assignment);
void sa_case_destroy(SaCase **c);
const char *sa_case_path(const SaCase *c);
/* Case file stem, e.g. "pressure_bending" for cases/pressure_bending.ini. */
const char *sa_case_stem(const SaCase *c);
int sa_case_has_section(const SaCase *c, const char *section);

/* Every section must belong to one of the tables and every key to its table; otherwise
 * SA_ERR_INPUT naming file:line, the unknown name and what is valid. */
int sa_case_check_known(const SaCase *c, const SaParamTable *const *tables, int ntables);

/* Fill params [out] from defaults, then from the case's section t->section (may be absent).
 * Every bad value is SA_ERR_INPUT naming file:line, [section] key, the value and the
 * expected type/range/choices. */
int sa_params_load(const SaParamTable *t, const SaCase *c, void *params);
/* Fill params [out] with the defaults only. */
int sa_params_defaults(const SaParamTable *t, void *params);
/* Write "[section]" and "key = value   ; unit, help" lines for the resolved values. */
void sa_params_write(const SaParamTable *t, const void *params, FILE *f);
/* Markdown reference table of t (key | type | unit | default | range | meaning). */
void sa_params_write_markdown(const SaParamTable *t, FILE *f);
/* Where a key's value came from ("file.ini:12", "--set", or "default"); buf of SA_STR_MAX. */
const char *sa_case_origin(const SaCase *c, const char *section, const char *key, char *buf);
/* Does the case (file or --set) give the key? */
int sa_case_is_set(const SaCase *c, const char *section, const char *key);
/* Where a message about the key points: "file.ini:12" or "--set" when the case gives it, else
 * the case file's path (a check that fails on defaults still names the file); buf of SA_STR_MAX.
 * A check between two keys points at the one the case gives (sa_case_is_set). */
const char *sa_case_where(const SaCase *c, const char *section, const char *key, char *buf);

#endif
