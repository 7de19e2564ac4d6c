/* sa_compare.c - the comparison scene: FEM-DEM, Mohr-Coulomb fill and pressure baseline,
 * bending angle and piston force against piston displacement (what and why: sa_compare.h).
 *
 * Interpolation is linear, in x for the granular curves and in the cavity volume change for
 * the pressure run (x = volume_change / (pi r^2) is linear in it, so both are linear in x).
 * A curve is defined on [x_first, x_last] of its samples (ends matched to 1e-12 relative);
 * nothing is extrapolated.
 *
 * Validation happens in check: the keys, and every input folder that exists (bending.csv,
 * columns, units, monotone abscissa, bore radius). A folder that does not exist yet is only a
 * warning there (`softact check` of the committed case must pass before the runs are made);
 * run refuses it before writing anything. */
#include "sa_compare.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <ini.h>

#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"

enum { CMP_DEM, CMP_MC, CMP_PRESSURE, CMP_N };
static const char *const cmp_key[CMP_N] = {"dem", "mc", "pressure"};
static const char *const cmp_case[CMP_N] = {"cases/granular_bending_dem.ini",
                                            "cases/granular_bending_mc.ini",
                                            "cases/pressure_bending.ini"};
static const char *const cmp_label[CMP_N] = {"FEM-DEM (glass beads)", "FEM + Mohr-Coulomb fill",
                                             "pressure baseline (incompressible fill)"};

typedef struct {
  char dem[SA_STR_MAX], mc[SA_STR_MAX], pressure[SA_STR_MAX];
  double bore_radius;
} SaCompareParams;

#define P(f) offsetof(SaCompareParams, f)
static const SaParam compare_params[] = {
    {"dem", SA_PARAM_STRING, P(dem), "-", "", 0, 0, 0, NULL,
     "results folder of cases/granular_bending_dem.ini (its bending.csv); relative to the case "
     "file's folder; empty = not compared"},
    {"mc", SA_PARAM_STRING, P(mc), "-", "", 0, 0, 0, NULL,
     "results folder of cases/granular_bending_mc.ini (its bending.csv); relative to the case "
     "file's folder; empty = not compared"},
    {"pressure", SA_PARAM_STRING, P(pressure), "-", "", 0, 0, 0, NULL,
     "results folder of cases/pressure_bending.ini (its bending.csv), matched by volume: cavity "
     "volume change = pi bore_radius^2 x; relative to the case file's folder; empty = not compared"},
    {"bore_radius", SA_PARAM_REAL, P(bore_radius), "m", "6e-3", 0, 0.1, SA_MIN_OPEN, NULL,
     "barrel bore radius r: displaced volume pi r^2 x (checked against the granular runs' "
     "displaced_volume)"},
};
#undef P

static const SaParamTable compare_table = {
    "compare", "core",
    "comparison of earlier runs' bending curves (FEM-DEM, Mohr-Coulomb, pressure baseline); at "
    "least two inputs",
    compare_params, SA_NPARAMS(compare_params)};
static const SaParamTable *const compare_tables[] = {&compare_table};

/* One curve at its own samples, x increasing strictly. */
typedef struct {
  int given, loaded, n;
  char dir[SA_STR_MAX], csv[SA_STR_MAX];
  char origin[SA_STR_MAX]; /* file:line (or --set) of its key */
  double *x;      /* piston displacement [m] */
  double *angle;  /* [deg] */
  double *force;  /* piston force [N] */
  double *volrel; /* cavity volume change / initial [-], NaN if the run has none */
  double *p;      /* pressure run: cavity pressure [Pa]; NULL otherwise */
  double x_end;   /* pressure run: x of its largest volume change (before clipping) */
  int clipped;    /* pressure run: its last point is interpolated at the granular runs' end */
  char mesh[256]; /* its silicone mesh from [mesh] of its case.ini ("" when not found) */
} Curve;

typedef struct {
  SaCompareParams prm;
  Curve c[CMP_N];
} SaCompareScene;

static void curve_free(Curve *c) {
  free(c->x);
  free(c->angle);
  free(c->force);
  free(c->volrel);
  free(c->p);
  c->x = c->angle = c->force = c->volrel = c->p = NULL;
  c->n = c->loaded = 0;
}

static void compare_destroy(void **scene) {
  if (!scene || !*scene) return;
  SaCompareScene *s = *scene;
  for (int k = 0; k < CMP_N; k++) curve_free(&s->c[k]);
  free(s);
  *scene = NULL;
}

/* Linear interpolation of y(x) at xq; NaN outside [x0, x_{n-1}] (ends within 1e-12 of the
 * span count as inside). x increases strictly. */
static double interp(int n, const double *x, const double *y, double xq) {
  if (n < 1) return NAN;
  double tol = 1e-12 * fmax(fabs(x[0]), fabs(x[n - 1]));
  if (xq < x[0] - tol || xq > x[n - 1] + tol) return NAN;
  if (xq <= x[0]) return y[0];
  if (xq >= x[n - 1]) return y[n - 1];
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (x[mid] <= xq) lo = mid;
    else hi = mid;
  }
  double t = (xq - x[lo]) / (x[hi] - x[lo]);
  return y[lo] + t * (y[hi] - y[lo]);
}

static int curve_covers(const Curve *c, double xq) {
  return c->loaded && c->n > 0 && !isnan(interp(c->n, c->x, c->x, xq));
}

/* Column name of file for key, with its unit when the file states units. */
static int need_column(const SaCsvData *d, const char *who, const char *csv, const char *name,
                       const char *unit, const double **col) {
  *col = sa_csv_data_column(d, name);
  SA_REQUIRE(*col, SA_ERR_INPUT, "%s: %s has no column '%s' (it has: %s); is it a "
             "results folder of the right scene?", who, csv, name, sa_csv_data_names(d));
  const char *u = sa_csv_data_unit(d, name);
  SA_REQUIRE(!u || !strcmp(u, unit), SA_ERR_INPUT,
             "%s: %s: column '%s' is in '%s', expected '%s'", who, csv, name, u, unit);
  for (int i = 0; i < sa_csv_data_nrows(d); i++)
    SA_REQUIRE(isfinite((*col)[i]), SA_ERR_INPUT, "%s: %s: column '%s' has no finite "
               "value in data row %d", who, csv, name, i + 1);
  return 0;
}

static int curve_alloc(Curve *c, int n, int with_p) {
  c->n = n;
  SA_CALLOC(c->x, n);
  SA_CALLOC(c->angle, n);
  SA_CALLOC(c->force, n);
  SA_CALLOC(c->volrel, n);
  if (with_p) SA_CALLOC(c->p, n);
  return 0;
}

/* Granular run (dem, mc): x, angle, force as given; displaced_volume checked against pi r^2 x. */
static int load_granular(const SaCsvData *d, const char *who, const char *csv, double r, Curve *c) {
  const double *x, *ang, *f, *vd;
  SA_CHECK(need_column(d, who, csv, "piston_displacement", "m", &x));
  SA_CHECK(need_column(d, who, csv, "bending_angle", "deg", &ang));
  SA_CHECK(need_column(d, who, csv, "piston_force", "N", &f));
  SA_CHECK(need_column(d, who, csv, "displaced_volume", "m^3", &vd));
  const double *vr = sa_csv_data_column(d, "volume_change_rel");
  int n = sa_csv_data_nrows(d);
  SA_REQUIRE(n >= 2, SA_ERR_INPUT, "%s: %s has %d data rows; a curve needs two", who,
             csv, n);
  const double A = M_PI * r * r;
  for (int i = 0; i < n; i++) {
    SA_REQUIRE(x[i] >= 0 && (i == 0 || x[i] > x[i - 1]), SA_ERR_INPUT,
               "%s: %s: piston_displacement must start at >= 0 and increase strictly "
               "(data row %d: %.17g after %.17g)", who, csv, i + 1, x[i], i ? x[i - 1] : 0.0);
    /* the run's own bore: its displaced volume is pi r^2 x to round-off */
    SA_REQUIRE(fabs(vd[i] - A * x[i]) <= 1e-6 * A * x[i] + 1e-18, SA_ERR_INPUT,
               "%s: %s: displaced_volume %.6g m^3 at piston_displacement %.6g m is "
               "pi (%.6g m)^2 x, but [compare] bore_radius = %g m", who, csv, vd[i], x[i],
               sqrt(vd[i] / (M_PI * x[i])), r);
  }
  SA_CHECK(curve_alloc(c, n, 0));
  for (int i = 0; i < n; i++) {
    c->x[i] = x[i];
    c->angle[i] = ang[i];
    c->force[i] = f[i];
    c->volrel[i] = vr && isfinite(vr[i]) ? vr[i] : NAN;
  }
  return 0;
}

/* Pressure run: its states mapped to x = volume_change / (pi r^2), force = p pi r^2. */
static int load_pressure(const SaCsvData *d, const char *who, const char *csv, double r, Curve *c) {
  const double *p, *ang, *dv;
  SA_CHECK(need_column(d, who, csv, "pressure", "Pa", &p));
  SA_CHECK(need_column(d, who, csv, "bending_angle", "deg", &ang));
  SA_CHECK(need_column(d, who, csv, "volume_change", "m^3", &dv));
  const double *vr = sa_csv_data_column(d, "volume_change_rel");
  int n = sa_csv_data_nrows(d);
  SA_REQUIRE(n >= 2, SA_ERR_INPUT, "%s: %s has %d data rows; a curve needs two", who,
             csv, n);
  for (int i = 1; i < n; i++)
    SA_REQUIRE(dv[i] > dv[i - 1], SA_ERR_INPUT,
               "%s: %s: volume_change must increase strictly along the run to match "
               "states by volume (data row %d: %.6g m^3 after %.6g m^3)", who, csv, i + 1, dv[i],
               dv[i - 1]);
  const double A = M_PI * r * r;
  SA_CHECK(curve_alloc(c, n, 1));
  for (int i = 0; i < n; i++) {
    c->x[i] = dv[i] / A;
    c->angle[i] = ang[i];
    c->p[i] = p[i];
    c->force[i] = p[i] * A;
    c->volrel[i] = vr && isfinite(vr[i]) ? vr[i] : NAN;
  }
  c->x_end = c->x[n - 1];
  return 0;
}

static int is_dir(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The silicone mesh of a run: [mesh] order, h, h_band, h_ring, rings of the resolved case.ini
 * softact wrote into its results folder. The curves of runs on different meshes belong to
 * different actuators (a tet4 silicone locks: docs/compare.md, "The MC scene's silicone"). */
enum { MK_ORDER, MK_H, MK_HBAND, MK_HRING, MK_RINGS, MK_N };
static const char *const mesh_key[MK_N] = {"order", "h", "h_band", "h_ring", "rings"};
typedef struct {
  char v[MK_N][32];
} MeshKeys;

static int mesh_handler(void *user, const char *section, const char *key, const char *value) {
  MeshKeys *m = user;
  if (strcmp(section, "mesh")) return 1;
  for (int i = 0; i < MK_N; i++)
    if (!strcmp(key, mesh_key[i])) { /* value up to an inline comment, trimmed */
      size_t n = strcspn(value, ";");
      while (n > 0 && (value[n - 1] == ' ' || value[n - 1] == '\t')) n--;
      snprintf(m->v[i], sizeof m->v[i], "%.*s", (int)n, value);
    }
  return 1;
}

static void read_mesh(Curve *c) {
  char path[SA_STR_MAX];
  c->mesh[0] = 0;
  if (sa_path_join(c->dir, "case.ini", path)) {
    sa_error_clear();
    return;
  }
  MeshKeys m;
  memset(&m, 0, sizeof m);
  /* a line inih cannot read elsewhere in the file does not matter here; a missing file does */
  if (ini_parse(path, mesh_handler, &m) < 0 || !m.v[MK_ORDER][0]) return;
  snprintf(c->mesh, sizeof c->mesh, "%s, h %s m, h_band %s m, h_ring %s m, rings %s",
           strcmp(m.v[MK_ORDER], "1") ? "tet10" : "tet4", m.v[MK_H], m.v[MK_HBAND],
           m.v[MK_HRING], m.v[MK_RINGS]);
}

/* 1 when two loaded runs name different silicone meshes (description in *what). */
static int meshes_differ(const SaCompareScene *s, char *what, size_t n) {
  int differ = 0;
  size_t len = 0;
  what[0] = 0;
  for (int k = 0; k < CMP_N; k++) {
    const Curve *c = &s->c[k];
    if (!c->loaded || !c->mesh[0]) continue;
    for (int j = 0; j < k; j++)
      if (s->c[j].loaded && s->c[j].mesh[0] && strcmp(s->c[j].mesh, c->mesh)) differ = 1;
    if (len < n)
      len += (size_t)snprintf(what + len, n - len, "%s%s: %s", len ? "; " : "", cmp_key[k],
                              c->mesh);
  }
  return differ;
}

/* Resolve a folder key against the case file's folder; read its bending.csv if it exists. */
static int load_input(const SaCase *cs, SaCompareScene *s, int k, char *value) {
  Curve *c = &s->c[k];
  c->given = value[0] != 0;
  if (!c->given) return 0;
  char *origin = c->origin;
  sa_case_origin(cs, "compare", cmp_key[k], origin);
  if (value[0] == '/') {
    snprintf(c->dir, sizeof c->dir, "%s", value);
  } else {
    const char *path = sa_case_path(cs), *slash = strrchr(path, '/');
    int dl = slash ? (int)(slash - path) : 1;
    int len = snprintf(c->dir, sizeof c->dir, "%.*s/%s", dl, slash ? path : ".", value);
    SA_REQUIRE(len < (int)sizeof c->dir, SA_ERR_INPUT, "%s: [compare] %s: path too long", origin,
               cmp_key[k]);
  }
  char *real = realpath(c->dir, NULL);
  if (real && strlen(real) < sizeof c->dir) snprintf(c->dir, sizeof c->dir, "%s", real);
  free(real);
  snprintf(value, SA_STR_MAX, "%s", c->dir); /* the resolved case shows where it looked */
  if (!is_dir(c->dir)) {
    sa_log(SA_LOG_WARN, "compare", "%s: [compare] %s: results folder %s does not exist (yet); "
           "`softact run` needs it (run %s first)", origin, cmp_key[k], c->dir, cmp_case[k]);
    return 0;
  }
  SA_CHECK(sa_path_join(c->dir, "bending.csv", c->csv));
  SaCsvData *d = NULL;
  FILE *probe = fopen(c->csv, "r");
  SA_REQUIRE(probe, SA_ERR_INPUT, "%s: [compare] %s: %s has no bending.csv (is it a results "
             "folder of %s?)", origin, cmp_key[k], c->dir, cmp_case[k]);
  fclose(probe);
  char who[SA_STR_MAX + 32];
  snprintf(who, sizeof who, "%s: [compare] %s", origin, cmp_key[k]);
  int rc = sa_csv_read(c->csv, &d);
  if (!rc)
    rc = k == CMP_PRESSURE ? load_pressure(d, who, c->csv, s->prm.bore_radius, c)
                           : load_granular(d, who, c->csv, s->prm.bore_radius, c);
  sa_csv_data_destroy(&d);
  SA_CHECK(rc);
  c->loaded = 1;
  read_mesh(c);
  return 0;
}

static int compare_check(const SaCase *cs, void **out) {
  *out = NULL;
  SaCompareScene *s;
  SA_CALLOC(s, 1);
  int rc = sa_params_load(&compare_table, cs, &s->prm);
  char *val[CMP_N] = {s->prm.dem, s->prm.mc, s->prm.pressure};
  int ngiven = 0;
  for (int k = 0; k < CMP_N; k++) ngiven += val[k][0] != 0;
  if (!rc && ngiven < 2)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [compare] needs at least two of dem, mc, pressure (results "
                  "folders of the runs to compare); %d given", sa_case_path(cs), ngiven);
  for (int k = 0; k < CMP_N && !rc; k++) rc = load_input(cs, s, k, val[k]);
  if (rc) {
    void *v = s;
    compare_destroy(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

static void compare_write_resolved(const void *scene, FILE *f) {
  const SaCompareScene *s = scene;
  sa_params_write(&compare_table, &s->prm, f);
  fprintf(f, "\n");
}

/* ---- run ---- */

/* The pressure curve up to the largest displacement of the granular runs (its own states, plus
 * the interpolated one at that end): beyond, nothing is compared and the plot stays readable. */
static void clip_pressure(Curve *p, double x_max) {
  int m = 0;
  while (m < p->n && p->x[m] <= x_max) m++;
  if (m < p->n && (m == 0 || p->x[m - 1] < x_max)) { /* interpolated end at x_max */
    double xs = x_max;
    if (m > 0) {
      double t = (xs - p->x[m - 1]) / (p->x[m] - p->x[m - 1]);
      p->angle[m] = p->angle[m - 1] + t * (p->angle[m] - p->angle[m - 1]);
      p->force[m] = p->force[m - 1] + t * (p->force[m] - p->force[m - 1]);
      p->p[m] = p->p[m - 1] + t * (p->p[m] - p->p[m - 1]);
      p->volrel[m] = p->volrel[m - 1] + t * (p->volrel[m] - p->volrel[m - 1]);
      p->x[m] = xs;
      p->clipped = 1;
      m++;
    }
  }
  p->n = m;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Table abscissae: every sample of every curve where at least two curves exist. */
static int table_grid(const SaCompareScene *s, double **xs, int *nx) {
  int total = 0;
  for (int k = 0; k < CMP_N; k++) total += s->c[k].loaded ? s->c[k].n : 0;
  double *all;
  SA_CALLOC(all, total);
  int m = 0;
  for (int k = 0; k < CMP_N; k++)
    for (int i = 0; s->c[k].loaded && i < s->c[k].n; i++) all[m++] = s->c[k].x[i];
  qsort(all, (size_t)m, sizeof *all, cmp_double);
  int n = 0;
  double scale = m ? fmax(fabs(all[0]), fabs(all[m - 1])) : 0;
  for (int i = 0; i < m; i++) {
    if (n && all[i] - all[n - 1] <= 1e-12 * scale) continue; /* same displacement */
    int cover = 0;
    for (int k = 0; k < CMP_N; k++) cover += curve_covers(&s->c[k], all[i]);
    if (cover >= 2) all[n++] = all[i];
  }
  *xs = all;
  *nx = n;
  return 0;
}

/* comparison.csv columns */
enum {
  T_X, T_XMM, T_VD, T_A_DEM, T_A_MC, T_A_P, T_MC_DEM, T_MC_DEM_REL, T_P_DEM, T_P_DEM_REL,
  T_P_MC, T_P_MC_REL, T_F_DEM, T_F_MC, T_F_P, T_P, T_V_DEM, T_V_MC, T_V_P, T_NCOL
};
static const char *const t_names[T_NCOL] = {
    "piston_displacement", "piston_displacement_mm", "displaced_volume", "angle_dem", "angle_mc",
    "angle_pressure", "mc_minus_dem", "mc_minus_dem_rel", "pressure_minus_dem",
    "pressure_minus_dem_rel", "pressure_minus_mc", "pressure_minus_mc_rel", "force_dem",
    "force_mc", "force_pressure", "pressure", "volume_change_rel_dem", "volume_change_rel_mc",
    "volume_change_rel_pressure"};
static const char *const t_units[T_NCOL] = {"m", "mm", "m^3", "deg", "deg", "deg", "deg", "-",
                                            "deg", "-", "deg", "-", "N", "N", "N", "Pa", "-",
                                            "-", "-"};

static double rel(double a, double b) { return fabs(b) > 1e-12 ? (a - b) / fabs(b) : NAN; }

static void table_row(const SaCompareScene *s, double x, double r, double *row) {
  double a[CMP_N], f[CMP_N], v[CMP_N];
  for (int k = 0; k < CMP_N; k++) {
    const Curve *c = &s->c[k];
    int ok = curve_covers(c, x);
    a[k] = ok ? interp(c->n, c->x, c->angle, x) : NAN;
    f[k] = ok ? interp(c->n, c->x, c->force, x) : NAN;
    v[k] = ok ? interp(c->n, c->x, c->volrel, x) : NAN;
  }
  const Curve *pc = &s->c[CMP_PRESSURE];
  row[T_X] = x;
  row[T_XMM] = 1e3 * x;
  row[T_VD] = M_PI * r * r * x;
  row[T_A_DEM] = a[CMP_DEM];
  row[T_A_MC] = a[CMP_MC];
  row[T_A_P] = a[CMP_PRESSURE];
  row[T_MC_DEM] = a[CMP_MC] - a[CMP_DEM];
  row[T_MC_DEM_REL] = rel(a[CMP_MC], a[CMP_DEM]);
  row[T_P_DEM] = a[CMP_PRESSURE] - a[CMP_DEM];
  row[T_P_DEM_REL] = rel(a[CMP_PRESSURE], a[CMP_DEM]);
  row[T_P_MC] = a[CMP_PRESSURE] - a[CMP_MC];
  row[T_P_MC_REL] = rel(a[CMP_PRESSURE], a[CMP_MC]);
  row[T_F_DEM] = f[CMP_DEM];
  row[T_F_MC] = f[CMP_MC];
  row[T_F_P] = f[CMP_PRESSURE];
  row[T_P] = curve_covers(pc, x) ? interp(pc->n, pc->x, pc->p, x) : NAN;
  row[T_V_DEM] = v[CMP_DEM];
  row[T_V_MC] = v[CMP_MC];
  row[T_V_P] = v[CMP_PRESSURE];
}

static int write_curve(const SaRun *run, int k, const Curve *c) {
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "curve_%s.csv", cmp_key[k]);
  SA_CHECK(sa_run_path(run, name, path));
  /* run_state (pressure run): 1 = a state of the run, 0 = interpolated at the granular end */
  const char *names[] = {"piston_displacement_mm", "bending_angle", "piston_force",
                         "volume_change_rel", "pressure", "run_state"};
  const char *units[] = {"mm", "deg", "N", "-", "Pa", "-"};
  int nc = c->p ? 6 : 4;
  SaCsv *t = NULL;
  SA_CHECK(sa_csv_open(path, nc, names, units, &t));
  int rc = 0;
  for (int i = 0; i < c->n && !rc; i++) {
    double row[6] = {1e3 * c->x[i], c->angle[i],  c->force[i], c->volrel[i], c->p ? c->p[i] : 0,
                     !(c->clipped && i == c->n - 1)};
    rc = sa_csv_row_gaps(t, row);
  }
  if (rc) {
    sa_csv_abort(&t);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_csv_commit(&t));
  return 0;
}

/* Both plots from the curve_*.csv files beside them (the scripts stay relocatable). */
static int make_plots(const SaCompareScene *s, const SaRun *run) {
  static const char *const line[CMP_N] = {"lw 2 lc rgb 'dark-red'", "lw 2 lc rgb 'dark-green'",
                                          "lw 2 dt 2 lc rgb 'blue'"};
  static const char *const point[CMP_N] = {"pt 7 ps 1.0", "pt 5 ps 0.9", "pt 6 ps 1.1"};
  const char *ycol[2] = {"2", "3"};
  const char *png[2] = {"bending_comparison.png", "piston_force_comparison.png"};
  const char *title[2] = {"Bending angle against piston displacement",
                          "Piston force against piston displacement"};
  const char *ylabel[2] = {"bending angle [deg]", "piston force [N]"};
  int rc_any = 0;
  for (int fig = 0; fig < 2; fig++) {
    char *body = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&body, &size);
    SA_REQUIRE(f, SA_ERR_MEMORY, "plot script");
    fprintf(f, "set title '%s (bore radius %.3g mm)'\nset xlabel 'piston displacement [mm]'\n"
            "set ylabel '%s'\nset grid\nset key below left Left reverse\nset xrange [0:*]\n"
            "set offsets 0, 0, graph 0.05, 0\nplot ", title[fig], 1e3 * s->prm.bore_radius, ylabel[fig]);
    int first = 1;
    for (int k = 0; k < CMP_N; k++) {
      if (!s->c[k].loaded) continue;
      const char *lab = cmp_label[k];
      char buf[160];
      if (k == CMP_PRESSURE) {
        snprintf(buf, sizeof buf, fig ? "%s: piston force p pi r^2" : "%s: cavity volume change = pi r^2 x", lab);
        lab = buf;
      }
      const char *sep = first ? "" : ", \\\n     ";
      if (k == CMP_PRESSURE) /* markers only on the run's own states, not the interpolated end */
        fprintf(f, "%s'curve_%s.csv' using 1:%s with lines %s notitle, \\\n     "
                "'' using 1:($6 > 0 ? $%s : 1/0) with points %s %s notitle, \\\n     "
                "NaN with linespoints %s %s title '%s'", sep, cmp_key[k], ycol[fig], line[k],
                ycol[fig], point[k], line[k], line[k], point[k], lab);
      else
        fprintf(f, "%s'curve_%s.csv' using 1:%s with linespoints %s %s title '%s'", sep,
                cmp_key[k], ycol[fig], line[k], point[k], lab);
      first = 0;
    }
    fputc('\n', f);
    if (fclose(f) != 0 || !body) {
      free(body);
      return SA_ERROR(SA_ERR_MEMORY, "plot script");
    }
    char path[SA_STR_MAX];
    int rc = sa_run_path(run, png[fig], path);
    if (!rc) rc = sa_plot_script_size(path, 1000, 650, body);
    free(body);
    if (rc) rc_any = rc;
  }
  if (rc_any) sa_error_clear(); /* plots are optional; the data is in the CSVs */
  return 0;
}

static void fmt_cell(char *buf, size_t n, double v, const char *fmt) {
  if (isnan(v)) snprintf(buf, n, "%s", "-");
  else snprintf(buf, n, fmt, v);
}

/* The table for people: in the log, at most ~24 rows (every k-th and the last). */
static void log_table(const double *rows, int nrows) {
  sa_log(SA_LOG_INFO, "compare", "%9s %11s %11s %11s %11s %11s %11s", "x [mm]", "DEM [deg]",
         "MC [deg]", "press [deg]", "MC-DEM", "press-DEM", "press-MC");
  int every = nrows > 24 ? (nrows + 23) / 24 : 1;
  for (int i = 0; i < nrows; i++) {
    if (i % every && i != nrows - 1) continue;
    const double *r = rows + (size_t)i * T_NCOL;
    char c[7][32];
    int cols[7] = {T_XMM, T_A_DEM, T_A_MC, T_A_P, T_MC_DEM, T_P_DEM, T_P_MC};
    for (int j = 0; j < 7; j++) fmt_cell(c[j], sizeof c[j], r[cols[j]], "%.4f");
    sa_log(SA_LOG_INFO, "compare", "%9s %11s %11s %11s %11s %11s %11s", c[0], c[1], c[2], c[3],
           c[4], c[5], c[6]);
  }
}

/* summary.ini: inputs, ranges, and per pair (a - b) the values at the end of the common range
 * and the largest difference. */
static void write_pair(FILE *fp, const char *name, const char *la, const char *lb, int ca, int cb,
                       int cd, int cr, const double *rows, int nrows) {
  int first = -1, last = -1, imax = -1;
  for (int i = 0; i < nrows; i++) {
    const double *r = rows + (size_t)i * T_NCOL;
    if (isnan(r[cd])) continue;
    if (first < 0) first = i;
    last = i;
    if (imax < 0 || fabs(r[cd]) > fabs(rows[(size_t)imax * T_NCOL + cd])) imax = i;
  }
  if (first < 0) return;
  const double *a = rows + (size_t)first * T_NCOL, *b = rows + (size_t)last * T_NCOL,
               *m = rows + (size_t)imax * T_NCOL;
  fprintf(fp, "\n[%s]\n", name);
  fprintf(fp, "common_from = %.9g ; m\ncommon_to = %.9g ; m\n", a[T_X], b[T_X]);
  fprintf(fp, "%s_at_end = %.6g ; deg\n%s_at_end = %.6g ; deg\n", la, b[ca], lb, b[cb]);
  fprintf(fp, "difference_at_end = %.6g ; deg, %s - %s\n", b[cd], la, lb);
  if (isnan(b[cr])) fprintf(fp, "relative_at_end = ; %s is 0\n", lb);
  else fprintf(fp, "relative_at_end = %.6g ; (%s - %s) / |%s|\n", b[cr], la, lb, lb);
  fprintf(fp, "max_abs_difference = %.6g ; deg\nmax_abs_difference_at = %.9g ; m\n", fabs(m[cd]),
          m[T_X]);
}

static int write_summary(const SaCompareScene *s, const SaRun *run, const double *rows, int nrows,
                         double x_gran) {
  char path[SA_STR_MAX];
  SA_CHECK(sa_run_path(run, "summary.ini", path));
  SaFile *f = NULL;
  SA_CHECK(sa_file_open(path, &f));
  FILE *fp = sa_file_stream(f);
  fprintf(fp, "; softact comparison of bending curves against piston displacement (comparison.csv)"
          "\n[inputs]\n");
  for (int k = 0; k < CMP_N; k++) {
    const Curve *c = &s->c[k];
    if (!c->loaded) {
      fprintf(fp, "%s = ; not given\n", cmp_key[k]);
      continue;
    }
    fprintf(fp, "%s = %s\n", cmp_key[k], c->csv);
  }
  fprintf(fp, "bore_radius = %.9g ; m\n\n[range]\n", s->prm.bore_radius);
  for (int k = 0; k < CMP_N; k++) {
    const Curve *c = &s->c[k];
    if (!c->loaded) continue;
    double xe = k == CMP_PRESSURE ? c->x_end : c->x[c->n - 1];
    fprintf(fp, "%s_to = %.9g ; m%s\n", cmp_key[k], xe,
            k == CMP_PRESSURE ? " (the run's largest cavity volume change / pi r^2)" : "");
  }
  char meshes[4 * 256];
  int differ = meshes_differ(s, meshes, sizeof meshes);
  fprintf(fp, "meshes = %s ; %s\n", differ ? "differ" : "same",
          meshes[0] ? meshes : "no case.ini in the inputs");
  fprintf(fp, "table_rows = %d\n", nrows);
  if (nrows)
    fprintf(fp, "table_from = %.9g ; m\ntable_to = %.9g ; m\n", rows[T_X],
            rows[(size_t)(nrows - 1) * T_NCOL + T_X]);
  const Curve *pc = &s->c[CMP_PRESSURE];
  if (pc->loaded)
    fprintf(fp, "pressure_baseline = %s\n", pc->x_end < x_gran * (1 - 1e-12)
            ? "ends before the granular runs (its run's volume change is too small)"
            : "covers the granular runs");
  write_pair(fp, "mc_minus_dem", "mc", "dem", T_A_MC, T_A_DEM, T_MC_DEM, T_MC_DEM_REL, rows, nrows);
  write_pair(fp, "pressure_minus_dem", "pressure", "dem", T_A_P, T_A_DEM, T_P_DEM, T_P_DEM_REL,
             rows, nrows);
  write_pair(fp, "pressure_minus_mc", "pressure", "mc", T_A_P, T_A_MC, T_P_MC, T_P_MC_REL, rows,
             nrows);
  SA_CHECK(sa_file_commit(&f));
  return 0;
}

static int compare_run(void *scene, SaRun *run) {
  SaCompareScene *s = scene;
  double t0 = sa_time_now();
  /* inputs first: nothing is written unless every given folder is there */
  for (int k = 0; k < CMP_N; k++) {
    const Curve *c = &s->c[k];
    SA_REQUIRE(!c->given || c->loaded, SA_ERR_INPUT,
               "%s: [compare] %s: results folder %s does not exist (run %s first, or correct the "
               "key)", c->origin, cmp_key[k], c->dir, cmp_case[k]);
  }
  const double r = s->prm.bore_radius;
  double x_gran = 0;
  for (int k = 0; k < CMP_N; k++)
    if (k != CMP_PRESSURE && s->c[k].loaded) x_gran = fmax(x_gran, s->c[k].x[s->c[k].n - 1]);
  for (int k = 0; k < CMP_N; k++)
    if (s->c[k].loaded)
      sa_log(SA_LOG_INFO, "compare", "%-8s %s: %d states, piston displacement %.4g to %.4g mm, "
             "bending angle %.4g to %.4g deg", cmp_key[k], s->c[k].csv, s->c[k].n,
             1e3 * s->c[k].x[0], 1e3 * s->c[k].x[s->c[k].n - 1], s->c[k].angle[0],
             s->c[k].angle[s->c[k].n - 1]);
  char meshes[4 * 256];
  if (meshes_differ(s, meshes, sizeof meshes))
    sa_log(SA_LOG_WARN, "compare", "the runs' silicone meshes differ (%s): their curves are those "
           "of different actuators; a tet4 silicone locks (docs/compare.md). Compare runs on one "
           "mesh", meshes);
  Curve *pc = &s->c[CMP_PRESSURE];
  if (pc->loaded) {
    if (pc->x_end < x_gran * (1 - 1e-12))
      sa_log(SA_LOG_WARN, "compare", "the pressure baseline ends at %.4g mm (its run's largest "
             "cavity volume change %.4g mm^3 = pi r^2 x); the granular runs go to %.4g mm: a "
             "pressure run to a higher [loading] p_max covers them", 1e3 * pc->x_end,
             1e9 * M_PI * r * r * pc->x_end, 1e3 * x_gran);
    clip_pressure(pc, x_gran);
    if (pc->n < 2)
      sa_log(SA_LOG_WARN, "compare", "the pressure run has %d state(s) within the granular runs' "
             "displacements (0 to %.4g mm): its curve is a straight line between its states; a "
             "run with finer steps resolves it", pc->n, 1e3 * x_gran);
  }

  double *xs = NULL, *rows = NULL;
  int nx = 0;
  SA_CHECK(table_grid(s, &xs, &nx));
  int rc = 0;
  rows = calloc((size_t)(nx ? nx : 1) * T_NCOL, sizeof *rows);
  if (!rows) rc = SA_ERROR(SA_ERR_MEMORY, "comparison table");
  for (int i = 0; i < nx && !rc; i++) table_row(s, xs[i], r, rows + (size_t)i * T_NCOL);
  if (!rc && nx == 0)
    rc = SA_ERROR(SA_ERR_INPUT, "[compare]: the curves share no piston displacement (no two "
                  "overlap); nothing to compare");

  char path[SA_STR_MAX];
  SaCsv *t = NULL;
  if (!rc) rc = sa_run_path(run, "comparison.csv", path);
  if (!rc) rc = sa_csv_open(path, T_NCOL, t_names, t_units, &t);
  for (int i = 0; i < nx && !rc; i++) rc = sa_csv_row_gaps(t, rows + (size_t)i * T_NCOL);
  if (!rc) rc = sa_csv_commit(&t);
  sa_csv_abort(&t);
  for (int k = 0; k < CMP_N && !rc; k++)
    if (s->c[k].loaded) rc = write_curve(run, k, &s->c[k]);
  if (!rc) rc = write_summary(s, run, rows, nx, x_gran);
  if (!rc) log_table(rows, nx);
  if (!rc && run->params.plots) rc = make_plots(s, run);
  free(xs);
  free(rows);
  sa_timing_add("I/O", sa_time_now() - t0);
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

const SaModule sa_compare_module = {
    .name = "compare",
    .trigger = "compare",
    .help = "comparison of earlier runs: FEM-DEM, Mohr-Coulomb and pressure baseline bending "
            "curves on one plot and in one table",
    .tables = compare_tables,
    .ntables = 1,
    .check = compare_check,
    .write_resolved = compare_write_resolved,
    .run = compare_run,
    .destroy = compare_destroy,
};
