/* ccx_post.c - results of the CalculiX peer runs (and of our solver) on one footing.
 *
 * tip BASE [--log FILE] [--at T1,T2,...]
 *   Reads BASE.tip (ccx_inp.h) and the displacement blocks of BASE.dat (one per increment,
 *   *NODE PRINT ... FREQUENCYF=1) and prints, per increment: step time, the tip displacement
 *   (area-weighted mean over the reference tip surface) and the bending angle: the rotation of
 *   the tip surface's mean outward normal N = int n da (deformed) in the x-z plane, positive
 *   toward -x (the strain-limiting side): angle = atan2(-N_x, -N_z) (the definition of
 *   fem_bending_angle). u_xz = |(u_x, u_z)| is the tip displacement in the bending plane (u_y of
 *   a half model's half tip surface is not the whole tip's, 0, so it is left out). With --log (ccx's stdout)
 *   the last line also gives the increments, attempts and Newton iterations ccx used.
 *   With --at (step times, e.g. 0.25,0.5,0.75,1 for a deck written with --time-points) it ends
 *   with one line per requested time, "# at T angle A u_xz U" from the block printed at that
 *   time (within 1e-6), or "# at T not reached"; then "# last printed T angle A u_xz U" and
 *   "# reached T", the last converged step time (from the log when given: ccx's "sum of previous
 *   increments" of its last attempt, or that attempt's step time if the job finished; else the
 *   last printed time), so a run that stopped short still reports how far it got.
 *   N depends only on the deformed rim of the tip surface (int n da = (1/2) oint x x dl), so
 *   the angle is insensitive to how the surface is triangulated.
 * field BASE DISPFILE
 *   The same quantities from a displacement field of the same mesh (text: one "ux uy uz" line
 *   per node, node order of BASE.inp), e.g. written by our solver's driver.
 * uniaxial BASE --c10 C --c20 C --c30 C --kappa K --pressure P
 *   Verification: a block with rollers on x = 0, y = 0, z = 0 and a follower pressure P on
 *   z = Lz is in homogeneous uniaxial stress. For W = W_iso(I1b) + (K/2)(J - 1)^2 the Cauchy
 *   stress is sigma = (2/J) W1 dev(b_bar) + K (J - 1) I, W1 = dW_iso/dI1b, b_bar = J^-2/3 b;
 *   with b = diag(a^2, a^2, c^2): sigma_xx = 0, sigma_zz = -P fixes (a, c), solved by Newton.
 *   The exact field u = ((a-1) x, (a-1) y, (c-1) z) is compared with every node of the last
 *   increment of BASE.dat (printed with --print-all); prints the largest error relative to
 *   max |u| and exits 1 if it exceeds 1e-4 (quadratic elements represent a linear field exactly;
 *   the residue, ~1e-6, is ccx's convergence tolerance and 7-digit output; a wrong node or face
 *   order or material constant gives errors of 1e-2 and more). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

typedef struct {
  int n;
  int *id;      /* node numbers (1-based) */
  double *X;    /* reference coordinates */
  int ntri;
  int *tri;     /* node numbers */
  int maxid;
  int *slot;    /* node number -> index into id (-1) */
} Tip;

static int tip_read(const char *base, Tip *t)
{
  char path[1024], line[512];
  snprintf(path, sizeof path, "%s.tip", base);
  FILE *f = fopen(path, "r");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", path);
  memset(t, 0, sizeof *t);
  int rc = 0;
  while (fgets(line, sizeof line, f) && line[0] == '#') {
  }
  if (sscanf(line, "nodes %d", &t->n) != 1) rc = SA_ERROR(SA_ERR_IO, "%s: no node count", path);
  if (!rc) {
    t->id = calloc((size_t)t->n, sizeof *t->id);
    t->X = calloc(3 * (size_t)t->n, sizeof *t->X);
    if (!t->id || !t->X) rc = SA_ERROR(SA_ERR_MEMORY, "tip nodes");
  }
  for (int i = 0; !rc && i < t->n; ++i) {
    if (!fgets(line, sizeof line, f) ||
        sscanf(line, "%d %lf %lf %lf", &t->id[i], &t->X[3 * i], &t->X[3 * i + 1], &t->X[3 * i + 2]) != 4)
      rc = SA_ERROR(SA_ERR_IO, "%s: bad node line %d", path, i);
    if (!rc && t->id[i] > t->maxid) t->maxid = t->id[i];
  }
  if (!rc && (!fgets(line, sizeof line, f) || sscanf(line, "triangles %d", &t->ntri) != 1))
    rc = SA_ERROR(SA_ERR_IO, "%s: no triangle count", path);
  if (!rc && !(t->tri = calloc(3 * (size_t)t->ntri + 1, sizeof *t->tri))) rc = SA_ERROR(SA_ERR_MEMORY, "tri");
  for (int i = 0; !rc && i < t->ntri; ++i)
    if (!fgets(line, sizeof line, f) ||
        sscanf(line, "%d %d %d", &t->tri[3 * i], &t->tri[3 * i + 1], &t->tri[3 * i + 2]) != 3)
      rc = SA_ERROR(SA_ERR_IO, "%s: bad triangle line %d", path, i);
  fclose(f);
  SA_CHECK(rc);
  SA_CALLOC(t->slot, t->maxid + 1);
  for (int i = 0; i <= t->maxid; ++i) t->slot[i] = -1;
  for (int i = 0; i < t->n; ++i) t->slot[t->id[i]] = i;
  for (int i = 0; i < 3 * t->ntri; ++i)
    SA_REQUIRE(t->tri[i] <= t->maxid && t->slot[t->tri[i]] >= 0, SA_ERR_INPUT,
               "%s: triangle node %d is not a tip node", path, t->tri[i]);
  return 0;
}

static void tip_free(Tip *t)
{
  free(t->id);
  free(t->X);
  free(t->tri);
  free(t->slot);
}

/* u [in] 3 per tip node (index order of t->id). umean [out] 3, angle [out] degrees. */
static void tip_eval(const Tip *t, const double *u, double umean[3], double *angle)
{
  double area = 0, N[3] = {0, 0, 0};
  umean[0] = umean[1] = umean[2] = 0;
  for (int i = 0; i < t->ntri; ++i) {
    int s[3];
    double X[3][3], x[3][3];
    for (int k = 0; k < 3; ++k) {
      s[k] = t->slot[t->tri[3 * i + k]];
      for (int q = 0; q < 3; ++q) {
        X[k][q] = t->X[3 * s[k] + q];
        x[k][q] = X[k][q] + u[3 * s[k] + q];
      }
    }
    double a[3], b[3], c[3];
    for (int q = 0; q < 3; ++q) a[q] = X[1][q] - X[0][q], b[q] = X[2][q] - X[0][q];
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
    double A0 = 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    area += A0;
    for (int q = 0; q < 3; ++q)
      umean[q] += A0 * (u[3 * s[0] + q] + u[3 * s[1] + q] + u[3 * s[2] + q]) / 3.0;
    for (int q = 0; q < 3; ++q) a[q] = x[1][q] - x[0][q], b[q] = x[2][q] - x[0][q];
    N[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
    N[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
    N[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  for (int q = 0; q < 3; ++q) umean[q] /= area;
  *angle = atan2(-N[0], -N[2]) * 180.0 / M_PI;
}

/* Next displacement block of a .dat file: time [out]; fills u [out] for the nodes in slot
 * (node number -> index, -1 to skip). Returns 1 when a block was read, 0 at end of file. */
static int dat_next(FILE *f, int maxid, const int *slot, double *u, double *time)
{
  char line[512];
  while (fgets(line, sizeof line, f)) {
    const char *p = strstr(line, " and time");
    if (!strstr(line, "displacements (vx,vy,vz)") || !p) continue;
    *time = atof(p + 9);
    int seen = 0;
    while (fgets(line, sizeof line, f)) {
      int id;
      double v[3];
      if (sscanf(line, "%d %lf %lf %lf", &id, &v[0], &v[1], &v[2]) != 4) {
        if (seen) break;
        continue; /* blank line after the header */
      }
      seen = 1;
      if (id <= maxid && slot[id] >= 0) memcpy(u + 3 * slot[id], v, sizeof v);
    }
    return 1;
  }
  return 0;
}

/* conv [out]: the last converged step time, -1 if unknown (single-step decks). */
static void log_counts(const char *path, int *inc, int *att, int *iters, double *conv)
{
  *inc = *att = *iters = 0;
  *conv = -1;
  FILE *f = fopen(path, "r");
  if (!f) return;
  char line[512];
  int last = 0;
  double t_attempt = -1, t_before = -1;
  while (fgets(line, sizeof line, f)) {
    int i, a;
    const char *p;
    if ((p = strstr(line, "sum of previous increments=")))
      t_before = atof(p + 27);
    else if ((p = strstr(line, "actual step time=")))
      t_attempt = atof(p + 17);
    else if (strstr(line, "Job finished"))
      t_before = t_attempt;
    if (sscanf(line, " increment %d attempt %d", &i, &a) == 2) {
      (*att)++;
      if (i > last) last = i;
    } else if (!strncmp(line, " iteration ", 11))
      (*iters)++;
  }
  *inc = last;
  *conv = t_before;
  fclose(f);
}

#define MAX_AT 64

static int cmd_tip(int argc, char **argv)
{
  SA_REQUIRE(argc >= 3, SA_ERR_INPUT, "usage: ccx_post tip BASE [--log FILE] [--at T1,T2,...]");
  const char *base = argv[2], *logf = NULL;
  int nat = 0, got[MAX_AT] = {0};
  double at[MAX_AT], at_ang[MAX_AT], at_uxz[MAX_AT], last = -1, last_ang = 0, last_uxz = 0;
  for (int i = 3; i < argc; i += 2) {
    SA_REQUIRE(i + 1 < argc, SA_ERR_INPUT, "option %s wants a value", argv[i]);
    if (!strcmp(argv[i], "--log")) {
      logf = argv[i + 1];
    } else if (!strcmp(argv[i], "--at")) {
      for (const char *p = argv[i + 1]; *p;) {
        char *end;
        SA_REQUIRE(nat < MAX_AT, SA_ERR_INPUT, "more than %d times in --at", MAX_AT);
        at[nat++] = strtod(p, &end);
        SA_REQUIRE(end != p && (*end == ',' || !*end), SA_ERR_INPUT, "bad --at list %s", argv[i + 1]);
        p = *end ? end + 1 : end;
      }
    } else {
      return SA_ERROR(SA_ERR_INPUT, "unknown option %s", argv[i]);
    }
  }
  Tip t;
  SA_CHECK(tip_read(base, &t));
  char path[1024];
  snprintf(path, sizeof path, "%s.dat", base);
  FILE *f = fopen(path, "r");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", path);
  double *u = calloc(3 * (size_t)t.n, sizeof *u), time;
  SA_REQUIRE(u, SA_ERR_MEMORY, "u");
  printf("# time  tip_ux[m]  tip_uy[m]  tip_uz[m]  u_xz[m]  angle[deg]\n");
  while (dat_next(f, t.maxid, t.slot, u, &time)) {
    double um[3], ang;
    tip_eval(&t, u, um, &ang);
    printf("%.6f %.9e %.9e %.9e %.9e %.6f\n", time, um[0], um[1], um[2],
           sqrt(um[0] * um[0] + um[2] * um[2]), ang);
    last = time;
    last_ang = ang;
    last_uxz = sqrt(um[0] * um[0] + um[2] * um[2]);
    for (int k = 0; k < nat; ++k)
      if (fabs(time - at[k]) <= 1e-6) {
        got[k] = 1;
        at_ang[k] = ang;
        at_uxz[k] = sqrt(um[0] * um[0] + um[2] * um[2]);
      }
  }
  fclose(f);
  for (int k = 0; k < nat; ++k) {
    if (got[k]) printf("# at %.6f angle %.6f u_xz %.9e\n", at[k], at_ang[k], at_uxz[k]);
    else printf("# at %.6f not reached\n", at[k]);
  }
  int inc, att, it;
  double conv = -1;
  if (logf) log_counts(logf, &inc, &att, &it, &conv);
  if (nat) {
    printf("# last printed %.6f angle %.6f u_xz %.9e\n", last, last_ang, last_uxz);
    printf("# reached %.6f\n", conv >= 0 ? conv : last);
  }
  if (logf) {
    printf("# increments %d attempts %d iterations %d\n", inc, att, it);
  }
  free(u);
  tip_free(&t);
  return 0;
}

static int cmd_field(int argc, char **argv)
{
  SA_REQUIRE(argc >= 4, SA_ERR_INPUT, "usage: ccx_post field BASE DISPFILE");
  Tip t;
  SA_CHECK(tip_read(argv[2], &t));
  FILE *f = fopen(argv[3], "r");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", argv[3]);
  double *u = calloc(3 * (size_t)t.n, sizeof *u);
  SA_REQUIRE(u, SA_ERR_MEMORY, "u");
  char line[512];
  int node = 0, got = 0;
  while (fgets(line, sizeof line, f)) {
    double v[3];
    if (line[0] == '#' || sscanf(line, "%lf %lf %lf", &v[0], &v[1], &v[2]) != 3) continue;
    node++;
    if (node <= t.maxid && t.slot[node] >= 0) memcpy(u + 3 * t.slot[node], v, sizeof v), got++;
  }
  fclose(f);
  SA_REQUIRE(got == t.n, SA_ERR_INPUT, "%s covers %d of %d tip nodes", argv[3], got, t.n);
  double um[3], ang;
  tip_eval(&t, u, um, &ang);
  printf("# time  tip_ux[m]  tip_uy[m]  tip_uz[m]  u_xz[m]  angle[deg]\n");
  printf("%.6f %.9e %.9e %.9e %.9e %.6f\n", 1.0, um[0], um[1], um[2],
         sqrt(um[0] * um[0] + um[2] * um[2]), ang);
  free(u);
  tip_free(&t);
  return 0;
}

/* Uniaxial-stress residuals (sigma_xx, sigma_zz + P) at lateral stretch a, axial stretch c. */
static void uniax_res(const double *mp, double a, double c, double r[2])
{
  double c10 = mp[0], c20 = mp[1], c30 = mp[2], K = mp[3], P = mp[4];
  double J = a * a * c, I = 2 * a * a + c * c, j23 = pow(J, -2.0 / 3.0), I1b = j23 * I;
  double W1 = c10 + 2 * c20 * (I1b - 3) + 3 * c30 * (I1b - 3) * (I1b - 3);
  r[0] = 2 * W1 / J * j23 * (a * a - I / 3) + K * (J - 1);
  r[1] = 2 * W1 / J * j23 * (c * c - I / 3) + K * (J - 1) + P;
}

static int cmd_uniaxial(int argc, char **argv)
{
  SA_REQUIRE(argc >= 3, SA_ERR_INPUT, "usage: ccx_post uniaxial BASE --c10 ..");
  const char *base = argv[2];
  double mp[5] = {0, 0, 0, 0, 0}; /* c10 c20 c30 kappa pressure */
  for (int i = 3; i + 1 < argc; i += 2) {
    const char *k[5] = {"--c10", "--c20", "--c30", "--kappa", "--pressure"};
    int hit = 0;
    for (int q = 0; q < 5; ++q)
      if (!strcmp(argv[i], k[q])) mp[q] = atof(argv[i + 1]), hit = 1;
    SA_REQUIRE(hit, SA_ERR_INPUT, "unknown option %s", argv[i]);
  }
  SA_REQUIRE(mp[0] > 0 && mp[3] > 0, SA_ERR_INPUT, "need --c10 and --kappa");
  double a = 1, c = 1;
  for (int it = 0; it < 50; ++it) {
    double r[2], ra[2], rc[2], h = 1e-7;
    uniax_res(mp, a, c, r);
    uniax_res(mp, a + h, c, ra);
    uniax_res(mp, a, c + h, rc);
    double J11 = (ra[0] - r[0]) / h, J12 = (rc[0] - r[0]) / h, J21 = (ra[1] - r[1]) / h,
           J22 = (rc[1] - r[1]) / h, det = J11 * J22 - J12 * J21;
    double da = (r[0] * J22 - r[1] * J12) / det, dc = (J11 * r[1] - J21 * r[0]) / det;
    a -= da, c -= dc;
    if (fabs(da) + fabs(dc) < 1e-15) break;
  }
  /* nodes of BASE.inp */
  char path[1024], line[512];
  snprintf(path, sizeof path, "%s.inp", base);
  FILE *f = fopen(path, "r");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", path);
  int n = 0, cap = 1 << 20, in = 0;
  double *X = calloc(3 * (size_t)cap, sizeof *X);
  SA_REQUIRE(X, SA_ERR_MEMORY, "X");
  while (fgets(line, sizeof line, f)) {
    if (line[0] == '*') {
      in = !strncmp(line, "*NODE,", 6) || !strncmp(line, "*NODE\n", 6);
      continue;
    }
    int id;
    double p[3];
    if (in && sscanf(line, "%d, %lf, %lf, %lf", &id, &p[0], &p[1], &p[2]) == 4 && id <= cap) {
      memcpy(X + 3 * (size_t)(id - 1), p, sizeof p);
      if (id > n) n = id;
    }
  }
  fclose(f);
  int *slot = calloc((size_t)n + 1, sizeof *slot);
  double *u = calloc(3 * (size_t)n, sizeof *u), *ul = calloc(3 * (size_t)n, sizeof *ul), time = 0;
  SA_REQUIRE(slot && u && ul, SA_ERR_MEMORY, "u");
  for (int i = 1; i <= n; ++i) slot[i] = i - 1;
  snprintf(path, sizeof path, "%s.dat", base);
  f = fopen(path, "r");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", path);
  int blocks = 0;
  while (dat_next(f, n, slot, u, &time)) {
    memcpy(ul, u, 3 * (size_t)n * sizeof *u);
    blocks++;
  }
  fclose(f);
  SA_REQUIRE(blocks > 0 && fabs(time - 1) < 1e-9, SA_ERR_INPUT, "%s: no displacements at time 1", path);
  double err = 0, umax = 0;
  for (int i = 0; i < n; ++i) {
    double ue[3] = {(a - 1) * X[3 * i], (a - 1) * X[3 * i + 1], (c - 1) * X[3 * i + 2]};
    for (int q = 0; q < 3; ++q) {
      err = fmax(err, fabs(ul[3 * i + q] - ue[q]));
      umax = fmax(umax, fabs(ue[q]));
    }
  }
  printf("uniaxial %s: stretches a = %.8f (lateral), c = %.8f (axial); %d nodes; "
         "max |u - u_exact| / max |u| = %.3e\n", base, a, c, n, err / umax);
  free(X), free(slot), free(u), free(ul);
  return err / umax <= 1e-4 ? 0 : SA_ERROR(SA_ERR_NUMERICAL, "uniaxial check failed");
}

static int run(int argc, char **argv)
{
  SA_REQUIRE(argc >= 2, SA_ERR_INPUT, "usage: ccx_post tip|field|uniaxial ... (see ccx_post.c)");
  if (!strcmp(argv[1], "tip")) return cmd_tip(argc, argv);
  if (!strcmp(argv[1], "field")) return cmd_field(argc, argv);
  if (!strcmp(argv[1], "uniaxial")) return cmd_uniaxial(argc, argv);
  return SA_ERROR(SA_ERR_INPUT, "unknown mode %s", argv[1]);
}

int main(int argc, char **argv)
{
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
