/* sa_params.c - case files (INI via libinih) and parameter tables (see sa_params.h).
 *
 * libinih does not report line numbers to the handler, so the case is read through our own
 * line reader (ini_parse_stream): it counts lines, records section headers (inih calls the
 * handler only for key = value lines, so an empty section would otherwise be invisible),
 * rejects NUL bytes and control characters (binary garbage) and repeated sections with the line
 * they are on, and drops a UTF-8 byte-order mark. It reads whole lines of any length: inih's
 * buffer is fixed when libinih is built (200 bytes on Debian) and a longer line handed over in
 * pieces would be parsed as several lines, so the tail of a long comment could set a key. */
#include "sa_params.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sa_error.h"

#ifndef SOFTACT_SOURCE_DIR
#define SOFTACT_SOURCE_DIR "."
#endif

typedef struct {
  char *section, *key, *value;
  int line; /* 0 = from --set */
} SaEntry;

typedef struct {
  char *name;
  int line;
} SaSection;

struct SaCase {
  char path[SA_STR_MAX];
  char dir[SA_STR_MAX];
  char stem[SA_STR_MAX];
  SaEntry *e;
  int n, cap;
  SaSection *s;
  int ns, scap;
  /* reader state */
  FILE *fp;
  char *lbuf; /* the whole current line (getline) */
  size_t lcap;
  int line;
  int bad_line;
  char bad_what[128];
  int dup_line;
  char dup_msg[SA_STR_MAX];
};

static char *sa_strdup(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

/* Record a section (line 0: from --set). A section the file names twice is reported like a
 * repeated key: merging the two silently hides a pasted or half-edited block. */
static int sa_case_add_section(SaCase *c, const char *name, int line) {
  for (int i = 0; i < c->ns; i++)
    if (!strcmp(c->s[i].name, name)) {
      if (line > 0 && c->s[i].line > 0 && !c->dup_line) {
        c->dup_line = line;
        snprintf(c->dup_msg, sizeof c->dup_msg, "section [%s] given twice (first on line %d)", name,
                 c->s[i].line);
      }
      return 0;
    }
  if (c->ns == c->scap) {
    int cap = c->scap ? 2 * c->scap : 8;
    SaSection *s = realloc(c->s, (size_t)cap * sizeof *s);
    if (!s) return -1;
    c->s = s;
    c->scap = cap;
  }
  c->s[c->ns].name = sa_strdup(name);
  c->s[c->ns].line = line;
  if (!c->s[c->ns].name) return -1;
  c->ns++;
  return 0;
}

static SaEntry *sa_case_find(const SaCase *c, const char *section, const char *key) {
  for (int i = c->n - 1; i >= 0; i--) /* last wins: --set entries come after the file */
    if (!strcmp(c->e[i].section, section) && !strcmp(c->e[i].key, key)) return &c->e[i];
  return NULL;
}

static int sa_case_add(SaCase *c, const char *section, const char *key, const char *value, int line) {
  if (c->n == c->cap) {
    int cap = c->cap ? 2 * c->cap : 32;
    SaEntry *e = realloc(c->e, (size_t)cap * sizeof *e);
    if (!e) return -1;
    c->e = e;
    c->cap = cap;
  }
  SaEntry *e = &c->e[c->n];
  e->section = sa_strdup(section);
  e->key = sa_strdup(key);
  e->value = sa_strdup(value);
  e->line = line;
  if (!e->section || !e->key || !e->value) return -1;
  c->n++;
  return 0;
}

/* The part of a line inih would act on: a start-of-line comment (';' or '#') is nothing and an
 * inline comment starts at a ';' after a blank (inih's rules with its default build options).
 * Returns the length without the comment and trailing blanks. */
static size_t sa_code_length(const char *s, size_t n) {
  size_t i = 0;
  while (i < n && (s[i] == ' ' || s[i] == '\t')) i++;
  if (i < n && (s[i] == ';' || s[i] == '#')) return 0;
  for (; i < n; i++)
    if (s[i] == ';' && i > 0 && isspace((unsigned char)s[i - 1])) break;
  while (i > 0 && isspace((unsigned char)s[i - 1])) i--;
  return i;
}

/* Line reader for ini_parse_stream: reads one whole line, counts it, checks it and hands inih a
 * line that fits its buffer of size bytes. */
static char *sa_reader(char *buf, int size, void *stream) {
  SaCase *c = stream;
  ssize_t got = getline(&c->lbuf, &c->lcap, c->fp);
  if (got <= 0) return NULL;
  char *s = c->lbuf;
  size_t n = (size_t)got;
  c->line++;
  if (c->line == 1 && n >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3)) s += 3, n -= 3; /* UTF-8 BOM */
  while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r')) n--;
  for (size_t i = 0; i < n && !c->bad_line; i++) {
    unsigned char u = (unsigned char)s[i];
    if (u == 0 || (u < 32 && u != '\t') || u == 127) {
      c->bad_line = c->line;
      snprintf(c->bad_what, sizeof c->bad_what, "control byte 0x%02x at column %zu (binary file?)", u, i + 1);
    }
  }
  if (c->bad_line) return NULL; /* stop parsing */
  /* A line too long for inih's buffer goes in without its comment; if it still does not fit
   * (a value that long) it is refused, never split. Room is left for the '\n' so that inih
   * never takes the line for an unfinished one. */
  if (n > (size_t)size - 2) n = sa_code_length(s, n);
  if (n > (size_t)size - 2) {
    c->bad_line = c->line;
    snprintf(c->bad_what, sizeof c->bad_what,
             "line too long: at most %d characters before a comment (give a longer value with --set)",
             size - 2);
    return NULL;
  }
  memcpy(buf, s, n);
  buf[n] = '\n';
  buf[n + 1] = 0;
  /* section header: record it with its line */
  char *p = buf;
  while (*p == ' ' || *p == '\t') p++;
  if (*p == '[') {
    char *q = strchr(p, ']');
    if (q) {
      char name[SA_STR_MAX];
      char *a = p + 1;
      while (a < q && isspace((unsigned char)*a)) a++;
      char *b = q;
      while (b > a && isspace((unsigned char)b[-1])) b--;
      int len = (int)(b - a);
      if (len >= (int)sizeof name) len = (int)sizeof name - 1;
      memcpy(name, a, (size_t)len);
      name[len] = 0;
      if (sa_case_add_section(c, name, c->line)) return NULL;
    }
  }
  return buf;
}

static int sa_handler(void *user, const char *section, const char *key, const char *value) {
  SaCase *c = user;
  SaEntry *old = sa_case_find(c, section, key);
  if (old && !c->dup_line) {
    c->dup_line = c->line;
    snprintf(c->dup_msg, sizeof c->dup_msg, "key '%s' in [%s] given twice (first on line %d)", key,
             section, old->line);
  }
  if (section[0] == 0 && !c->dup_line) {
    c->dup_line = c->line;
    snprintf(c->dup_msg, sizeof c->dup_msg, "key '%s' before any [section]", key);
  }
  return sa_case_add(c, section, key, value, c->line) == 0;
}

/* Parse the file at path, or, when text is not NULL, the len bytes at text (named path in
 * messages): both go through the same line reader. */
static int sa_case_read(const char *path, const char *text, size_t len, SaCase **out) {
  *out = NULL;
  SaCase *c;
  SA_CALLOC(c, 1);
  snprintf(c->path, sizeof c->path, "%s", path);
  const char *slash = strrchr(path, '/');
  if (slash)
    snprintf(c->dir, sizeof c->dir, "%.*s", (int)(slash - path), path);
  else
    snprintf(c->dir, sizeof c->dir, ".");
  const char *base = slash ? slash + 1 : path;
  snprintf(c->stem, sizeof c->stem, "%s", base);
  char *dot = strrchr(c->stem, '.');
  if (dot && dot != c->stem) *dot = 0;

  /* From memory (tests, the fuzzer): the same reader on fmemopen. From a file: O_NONBLOCK, so
   * that opening a FIFO does not wait for a writer; only a regular file is read (a folder would
   * read as empty, a FIFO or device could block for ever). */
  if (text) {
    c->fp = fmemopen((void *)text, len, "rb");
    if (!c->fp) {
      int e = errno;
      sa_case_destroy(&c);
      return SA_ERROR(SA_ERR_INPUT, "%s: cannot open case text: %s", path, strerror(e));
    }
  }
  int fd = text ? -1 : open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (!text && fd < 0) {
    int e = errno;
    sa_case_destroy(&c);
    return SA_ERROR(SA_ERR_INPUT, "%s: cannot open case file: %s", path, strerror(e));
  }
  if (!text) {
    struct stat st;
    const char *what = fstat(fd, &st) != 0 ? "cannot be examined"
                       : S_ISDIR(st.st_mode) ? "is a directory, not a case file"
                       : !S_ISREG(st.st_mode) ? "is not a regular file (a FIFO, device or socket); "
                                                "give a case file"
                                              : NULL;
    if (!what && fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0) what = "cannot be read";
    if (!what && !(c->fp = fdopen(fd, "rb"))) what = "cannot be read";
    if (what) {
      close(fd);
      sa_case_destroy(&c);
      return SA_ERROR(SA_ERR_INPUT, "%s: %s", path, what);
    }
  }
  int rc = ini_parse_stream(sa_reader, c, sa_handler, c);
  int read_error = ferror(c->fp) ? (errno ? errno : EIO) : 0;
  fclose(c->fp);
  c->fp = NULL;
  int err = 0;
  if (read_error)
    err = SA_ERROR(SA_ERR_IO, "%s:%d: cannot read the case file: %s", path, c->line + 1, strerror(read_error));
  else if (c->bad_line)
    err = SA_ERROR(SA_ERR_INPUT, "%s:%d: %s", path, c->bad_line, c->bad_what);
  else if (rc > 0)
    err = SA_ERROR(SA_ERR_INPUT, "%s:%d: syntax error: expected '[section]', 'key = value' or a comment", path, rc);
  else if (rc < 0)
    err = SA_ERROR(SA_ERR_MEMORY, "%s: out of memory while parsing", path);
  else if (c->dup_line)
    err = SA_ERROR(SA_ERR_INPUT, "%s:%d: %s", path, c->dup_line, c->dup_msg);
  else if (c->ns == 0)
    err = SA_ERROR(SA_ERR_INPUT, "%s:1: empty case file: no [section] found (a scene needs e.g. [hmsa] or [mesh])", path);
  if (err) {
    sa_case_destroy(&c);
    return err;
  }
  *out = c;
  return 0;
}

int sa_case_load(const char *path, SaCase **out) { return sa_case_read(path, NULL, 0, out); }

int sa_case_load_mem(const char *name, const char *text, size_t len, SaCase **out) {
  return sa_case_read(name, text ? text : "", len, out);
}

/* s[0..n) without leading and trailing blanks, into buf of size bytes; -1 if it does not fit. */
static int sa_trim_copy(const char *s, size_t n, char *buf, size_t size) {
  while (n > 0 && isspace((unsigned char)*s)) s++, n--;
  while (n > 0 && isspace((unsigned char)s[n - 1])) n--;
  if (n >= size) return -1;
  memcpy(buf, s, n);
  buf[n] = 0;
  return 0;
}

int sa_case_override(SaCase *c, const char *assignment) {
  /* A case value is one line of text: a line break would be written as-is into the resolved
   * case.ini and start a new line (a section, a key) there; other control characters have no
   * business in a value either (the case-file reader refuses them too). */
  for (const char *p = assignment; *p; p++) {
    unsigned char u = (unsigned char)*p;
    SA_REQUIRE(u >= 32 && u != 127, SA_ERR_INPUT,
               "--set: control character 0x%02x at position %d of '%.*s...': a value is one line of "
               "printable text", u, (int)(p - assignment) + 1, (int)(p - assignment), assignment);
  }
  const char *dot = strchr(assignment, '.');
  const char *eq = strchr(assignment, '=');
  SA_REQUIRE(dot && eq && dot < eq, SA_ERR_INPUT, "--set %s: expected section.key=value", assignment);
  /* blanks around the names and the value are dropped, as in a case file */
  char section[SA_STR_MAX], key[SA_STR_MAX];
  SA_REQUIRE(sa_trim_copy(assignment, (size_t)(dot - assignment), section, sizeof section) == 0 &&
                 sa_trim_copy(dot + 1, (size_t)(eq - dot - 1), key, sizeof key) == 0,
             SA_ERR_INPUT, "--set %.60s...: name longer than %d characters", assignment, SA_STR_MAX - 1);
  SA_REQUIRE(section[0] && key[0], SA_ERR_INPUT, "--set %s: expected section.key=value", assignment);
  const char *v = eq + 1; /* the value may be longer than a name (a list) */
  size_t n = strlen(v);
  while (n > 0 && isspace((unsigned char)*v)) v++, n--;
  while (n > 0 && isspace((unsigned char)v[n - 1])) n--;
  char *value = strndup(v, n);
  int ok = value && sa_case_add_section(c, section, 0) == 0 && sa_case_add(c, section, key, value, 0) == 0;
  free(value);
  SA_REQUIRE(ok, SA_ERR_MEMORY, "out of memory");
  return 0;
}

void sa_case_destroy(SaCase **cp) {
  SaCase *c = *cp;
  if (!c) return;
  for (int i = 0; i < c->n; i++) {
    free(c->e[i].section);
    free(c->e[i].key);
    free(c->e[i].value);
  }
  for (int i = 0; i < c->ns; i++) free(c->s[i].name);
  free(c->lbuf);
  free(c->e);
  free(c->s);
  free(c);
  *cp = NULL;
}

const char *sa_case_path(const SaCase *c) { return c->path; }
const char *sa_case_stem(const SaCase *c) { return c->stem; }

int sa_case_has_section(const SaCase *c, const char *section) {
  for (int i = 0; i < c->ns; i++)
    if (!strcmp(c->s[i].name, section)) return 1;
  return 0;
}

/* "file:line" or "--set" for messages. */
#define SA_WHERE_MAX (SA_STR_MAX + 64)
static const char *sa_where(const SaCase *c, int line, char *buf) {
  if (line > 0)
    snprintf(buf, SA_WHERE_MAX, "%s:%d", c->path, line);
  else
    snprintf(buf, SA_WHERE_MAX, "--set");
  return buf;
}

const char *sa_case_origin(const SaCase *c, const char *section, const char *key, char *buf) {
  SaEntry *e = sa_case_find(c, section, key);
  if (!e) return snprintf(buf, SA_STR_MAX, "default"), buf;
  char where[SA_WHERE_MAX];
  snprintf(buf, SA_STR_MAX, "%.*s", SA_STR_MAX - 1, sa_where(c, e->line, where));
  return buf;
}

int sa_case_is_set(const SaCase *c, const char *section, const char *key) {
  return sa_case_find(c, section, key) != NULL;
}

const char *sa_case_where(const SaCase *c, const char *section, const char *key, char *buf) {
  SaEntry *e = sa_case_find(c, section, key);
  char where[SA_WHERE_MAX];
  snprintf(buf, SA_STR_MAX, "%.*s", SA_STR_MAX - 1, e ? sa_where(c, e->line, where) : c->path);
  return buf;
}

/* Edit distance, for "did you mean" suggestions. */
static int sa_distance(const char *a, const char *b) {
  int la = (int)strlen(a), lb = (int)strlen(b);
  if (la > 63 || lb > 63) return 99;
  int d[64][64];
  for (int i = 0; i <= la; i++) d[i][0] = i;
  for (int j = 0; j <= lb; j++) d[0][j] = j;
  for (int i = 1; i <= la; i++)
    for (int j = 1; j <= lb; j++) {
      int cost = a[i - 1] != b[j - 1];
      int m = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < m) m = d[i][j - 1] + 1;
      if (d[i - 1][j - 1] + cost < m) m = d[i - 1][j - 1] + cost;
      d[i][j] = m;
    }
  return d[la][lb];
}

int sa_case_check_known(const SaCase *c, const SaParamTable *const *tables, int ntables) {
  char where[SA_WHERE_MAX];
  for (int i = 0; i < c->ns; i++) {
    int found = 0;
    for (int t = 0; t < ntables && !found; t++) found = !strcmp(tables[t]->section, c->s[i].name);
    if (found) continue;
    char list[SA_STR_MAX] = "", *p = list;
    const char *best = NULL;
    int bestd = 3;
    for (int t = 0; t < ntables; t++) {
      p += snprintf(p, (size_t)(list + sizeof list - p), "%s[%s]", t ? " " : "", tables[t]->section);
      if (p >= list + sizeof list) break;
      int d = sa_distance(c->s[i].name, tables[t]->section);
      if (d < bestd) bestd = d, best = tables[t]->section;
    }
    char hint[SA_STR_MAX] = "";
    if (best) snprintf(hint, sizeof hint, "; did you mean [%s]?", best);
    return SA_ERROR(SA_ERR_INPUT, "%s: unknown section [%s]%s (valid sections: %s)",
                    sa_where(c, c->s[i].line, where), c->s[i].name, hint, list);
  }
  for (int i = 0; i < c->n; i++) {
    const SaParamTable *t = NULL;
    for (int k = 0; k < ntables; k++)
      if (!strcmp(tables[k]->section, c->e[i].section)) t = tables[k];
    if (!t) continue; /* reported above */
    int found = 0;
    for (int k = 0; k < t->nparams && !found; k++) found = !strcmp(t->params[k].key, c->e[i].key);
    if (found) continue;
    const char *best = NULL;
    int bestd = 3;
    char list[2048] = "", *p = list;
    for (int k = 0; k < t->nparams; k++) {
      int d = sa_distance(c->e[i].key, t->params[k].key);
      if (d < bestd) bestd = d, best = t->params[k].key;
      if (p < list + sizeof list - 1)
        p += snprintf(p, (size_t)(list + sizeof list - p), "%s%s", k ? ", " : "", t->params[k].key);
    }
    char hint[SA_STR_MAX] = "";
    if (best) snprintf(hint, sizeof hint, "; did you mean '%s'?", best);
    return SA_ERROR(SA_ERR_INPUT, "%s: unknown key '%s' in [%s]%s (valid keys: %s)",
                    sa_where(c, c->e[i].line, where), c->e[i].key, c->e[i].section, hint, list);
  }
  return 0;
}

static int sa_unbounded(const SaParam *p) { return p->min == 0 && p->max == 0 && p->open == 0; }

/* "in [a, b]" / "in (0, inf)" text for messages and tables. */
static void sa_range_text(const SaParam *p, char *buf, size_t n) {
  if (sa_unbounded(p)) {
    snprintf(buf, n, "any");
    return;
  }
  char a[32], b[32];
  if (isinf(p->min)) snprintf(a, sizeof a, "-inf"); else snprintf(a, sizeof a, "%g", p->min);
  if (isinf(p->max)) snprintf(b, sizeof b, "inf"); else snprintf(b, sizeof b, "%g", p->max);
  snprintf(buf, n, "%c%s, %s%c", (p->open & SA_MIN_OPEN) || isinf(p->min) ? '(' : '[', a, b,
           (p->open & SA_MAX_OPEN) || isinf(p->max) ? ')' : ']');
}

static const char *sa_type_name(SaParamType t) {
  switch (t) {
    case SA_PARAM_REAL: return "real";
    case SA_PARAM_INT: return "integer";
    case SA_PARAM_BOOL: return "bool";
    case SA_PARAM_STRING: return "string";
    case SA_PARAM_CHOICE: return "choice";
    case SA_PARAM_FILE: return "file";
    case SA_PARAM_REAL_LIST: return "real list";
  }
  return "?";
}

static int sa_in_range(const SaParam *p, double v) {
  if (!isfinite(v)) return 0;
  if (sa_unbounded(p)) return 1;
  if ((p->open & SA_MIN_OPEN) ? !(v > p->min) : !(v >= p->min)) return 0;
  if ((p->open & SA_MAX_OPEN) ? !(v < p->max) : !(v <= p->max)) return 0;
  return 1;
}

static int sa_parse_real(const char *s, double *v) {
  char *end;
  errno = 0;
  *v = strtod(s, &end);
  if (end == s || errno == ERANGE) return -1;
  while (isspace((unsigned char)*end)) end++;
  return *end ? -1 : 0;
}

static int sa_file_ok(const char *path) { return access(path, R_OK) == 0; }

/* Parse one value into the field. where: "file:line" or "default". Returns 0 or SA_ERR_INPUT. */
static int sa_param_set(const SaParamTable *t, const SaParam *p, const char *value, const char *where,
                        const char *case_dir, void *params) {
  char *field = (char *)params + p->offset;
  char range[96];
  sa_range_text(p, range, sizeof range);
  switch (p->type) {
    case SA_PARAM_REAL: {
      double v;
      if (sa_parse_real(value, &v) || !sa_in_range(p, v))
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': expected a real number in %s [%s]", where,
                        t->section, p->key, value, range, p->unit);
      *(double *)field = v;
      return 0;
    }
    case SA_PARAM_INT: {
      char *end;
      errno = 0;
      long v = strtol(value, &end, 10);
      while (isspace((unsigned char)*end)) end++;
      if (end == value || *end || errno || !sa_in_range(p, (double)v))
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': expected an integer in %s", where, t->section,
                        p->key, value, range);
      *(int *)field = (int)v;
      return 0;
    }
    case SA_PARAM_BOOL: {
      static const char *yes[] = {"true", "yes", "on", "1"}, *no[] = {"false", "no", "off", "0"};
      for (int i = 0; i < 4; i++) {
        if (!strcasecmp(value, yes[i])) return *(int *)field = 1, 0;
        if (!strcasecmp(value, no[i])) return *(int *)field = 0, 0;
      }
      return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': expected true or false", where, t->section, p->key, value);
    }
    case SA_PARAM_STRING:
      if (strlen(value) >= SA_STR_MAX)
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s: value longer than %d characters", where, t->section,
                        p->key, SA_STR_MAX - 1);
      strcpy(field, value);
      return 0;
    case SA_PARAM_CHOICE: {
      const char *s = p->choices;
      size_t n = strlen(value);
      while (s && *s) {
        const char *bar = strchr(s, '|');
        size_t len = bar ? (size_t)(bar - s) : strlen(s);
        if (len == n && !strncmp(s, value, n)) {
          strcpy(field, value);
          return 0;
        }
        s = bar ? bar + 1 : NULL;
      }
      return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': expected one of %s", where, t->section, p->key, value,
                      p->choices);
    }
    case SA_PARAM_FILE: {
      if (!value[0]) { /* empty = not given; the module decides whether it needs it */
        field[0] = 0;
        return 0;
      }
      char buf[2 * SA_STR_MAX];
      if (value[0] == '/')
        snprintf(buf, sizeof buf, "%s", value);
      else {
        snprintf(buf, sizeof buf, "%s/%s", case_dir, value);
        if (!sa_file_ok(buf)) {
          char alt[2 * SA_STR_MAX];
          snprintf(alt, sizeof alt, "%s/%s", SOFTACT_SOURCE_DIR, value);
          if (sa_file_ok(alt)) memcpy(buf, alt, sizeof buf);
        }
      }
      if (strlen(buf) >= SA_STR_MAX)
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s: path too long", where, t->section, p->key);
      if (!sa_file_ok(buf))
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': file not found or not readable (looked for %s)",
                        where, t->section, p->key, value, buf);
      strcpy(field, buf);
      return 0;
    }
    case SA_PARAM_REAL_LIST: {
      SaRealList *l = (SaRealList *)field;
      l->n = 0;
      const char *s = value;
      while (isspace((unsigned char)*s)) s++;
      if (!*s)
        return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s: expected a comma-separated list of real numbers", where,
                        t->section, p->key);
      /* item by item, in place (no copy to truncate); an empty item ("5,,10", "5,") is an error,
       * not skipped: it is a typo or a value left out */
      for (int item = 1;; item++) {
        const char *comma = strchr(s, ',');
        size_t len = comma ? (size_t)(comma - s) : strlen(s);
        char tok[64];
        if (sa_trim_copy(s, len, tok, sizeof tok)) /* too long for a number: shown cut, refused below */
          snprintf(tok, sizeof tok, "%.48s...", s);
        if (!tok[0])
          return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': item %d of the list is empty (expected real "
                          "numbers separated by single commas)", where, t->section, p->key, value, item);
        double v;
        if (l->n == SA_LIST_MAX)
          return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s: more than %d values", where, t->section, p->key, SA_LIST_MAX);
        if (sa_parse_real(tok, &v) || !sa_in_range(p, v))
          return SA_ERROR(SA_ERR_INPUT, "%s: [%s] %s = '%s': expected a real number in %s [%s] (or a comma-separated list of them)",
                          where, t->section, p->key, tok, range, p->unit);
        l->v[l->n++] = v;
        if (!comma) break;
        s = comma + 1;
      }
      return 0;
    }
  }
  return SA_ERROR(SA_ERR_INTERNAL, "bad parameter type");
}

int sa_params_defaults(const SaParamTable *t, void *params) {
  for (int i = 0; i < t->nparams; i++) {
    const SaParam *p = &t->params[i];
    /* A default file that does not exist is not an error until the module needs it. */
    if (p->type == SA_PARAM_FILE) {
      char *field = (char *)params + p->offset;
      snprintf(field, SA_STR_MAX, "%s", p->def);
      continue;
    }
    char where[SA_WHERE_MAX];
    snprintf(where, sizeof where, "default of");
    int rc = sa_param_set(t, p, p->def, where, SOFTACT_SOURCE_DIR, params);
    if (rc) return sa_error_push(SA_ERR_INTERNAL, __func__, __FILE__, __LINE__);
  }
  return 0;
}

int sa_params_load(const SaParamTable *t, const SaCase *c, void *params) {
  SA_CHECK(sa_params_defaults(t, params));
  for (int i = 0; i < t->nparams; i++) {
    const SaParam *p = &t->params[i];
    SaEntry *e = c ? sa_case_find(c, t->section, p->key) : NULL;
    char where[SA_WHERE_MAX];
    if (e) {
      sa_where(c, e->line, where);
      SA_CHECK(sa_param_set(t, p, e->value, where, c->dir, params));
    } else if (p->type == SA_PARAM_FILE && p->def[0]) {
      snprintf(where, sizeof where, "%s (default)", c ? c->path : "");
      SA_CHECK(sa_param_set(t, p, p->def, where, c ? c->dir : ".", params));
    }
  }
  return 0;
}

static void sa_value_text(const SaParam *p, const void *params, char *buf, size_t n) {
  const char *field = (const char *)params + p->offset;
  switch (p->type) {
    case SA_PARAM_REAL: {
      double v = *(const double *)field;
      snprintf(buf, n, "%.15g", v);
      if (strtod(buf, NULL) != v) snprintf(buf, n, "%.17g", v);
      break;
    }
    case SA_PARAM_INT: snprintf(buf, n, "%d", *(const int *)field); break;
    case SA_PARAM_BOOL: snprintf(buf, n, "%s", *(const int *)field ? "true" : "false"); break;
    case SA_PARAM_REAL_LIST: {
      const SaRealList *l = (const SaRealList *)field;
      size_t k = 0;
      buf[0] = 0;
      for (int i = 0; i < l->n && k < n; i++) k += (size_t)snprintf(buf + k, n - k, "%s%.15g", i ? ", " : "", l->v[i]);
      break;
    }
    default: snprintf(buf, n, "%s", field); break;
  }
}

void sa_params_write(const SaParamTable *t, const void *params, FILE *f) {
  fprintf(f, "[%s]\n", t->section);
  for (int i = 0; i < t->nparams; i++) {
    char v[4 * SA_STR_MAX]; /* SA_LIST_MAX values of up to 24 characters + ", " */
    sa_value_text(&t->params[i], params, v, sizeof v);
    fprintf(f, "%s = %s", t->params[i].key, v);
    int pad = 28 - (int)(strlen(t->params[i].key) + strlen(v) + 3);
    fprintf(f, "%*s ; [%s] %s\n", pad > 0 ? pad : 0, "", t->params[i].unit, t->params[i].help);
  }
  fputc('\n', f);
}

void sa_params_write_markdown(const SaParamTable *t, FILE *f) {
  fprintf(f, "#### `[%s]` - %s\n\n", t->section, t->help);
  fprintf(f, "| key | type | unit | default | range | meaning |\n|---|---|---|---|---|---|\n");
  for (int i = 0; i < t->nparams; i++) {
    const SaParam *p = &t->params[i];
    char range[128];
    if (p->type == SA_PARAM_CHOICE)
      snprintf(range, sizeof range, "%s", p->choices);
    else if (p->type == SA_PARAM_REAL || p->type == SA_PARAM_INT || p->type == SA_PARAM_REAL_LIST)
      sa_range_text(p, range, sizeof range);
    else
      snprintf(range, sizeof range, "-");
    /* '|' inside a table cell must be escaped */
    char esc[256];
    size_t k = 0;
    for (const char *s = range; *s && k < sizeof esc - 2; s++) {
      if (*s == '|') esc[k++] = '\\';
      esc[k++] = *s;
    }
    esc[k] = 0;
    fprintf(f, "| `%s` | %s | %s | `%s` | %s | %s |\n", p->key, sa_type_name(p->type), p->unit, p->def, esc, p->help);
  }
  fputc('\n', f);
}
