/* fem_law.c - the law registry and the built-in laws behind the law interface (fem_law.h).
 *
 * The built-in laws keep their direct path in the element kernel (FemMaterial.law == NULL with
 * the kind fields set): fem_material_from_law of a built-in name builds exactly the material
 * fem_actuator.c built by hand, so the numbers do not depend on how a material was made. Their
 * FemLaw objects (eval wrappers around fem_material_eval_iso) make them listable and callable
 * like any registered law. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "fem_law.h"
#include "fem_material.h"
#include "fem_mohr_coulomb.h"
#include "sa_error.h"

#define MAX_LAWS 64

/* parameters as the built-in kinds use them */
static FemMaterial builtin_material(const char *name, const double *par) {
  FemMaterial m = {0};
  if (!strcmp(name, "neohooke")) m.kind = FEM_MAT_NEOHOOKE, m.c10 = par[0], m.kappa = par[1];
  else if (!strcmp(name, "mooney_rivlin"))
    m.kind = FEM_MAT_MOONEY_RIVLIN, m.c10 = par[0], m.c01 = par[1], m.kappa = par[2];
  else if (!strcmp(name, "yeoh"))
    m.kind = FEM_MAT_YEOH, m.c10 = par[0], m.c20 = par[1], m.c30 = par[2], m.kappa = par[3];
  else m = fem_material_from_e_nu(par[0], par[1], 0.0);
  return m;
}

#define BUILTIN_EVAL(fn, lawname)                                                             \
  static int fn(const double *par, const FemLawCtx *ctx, const double F[9], const double *ho, \
                double *hn, double *W, double P[9], double A[81]) {                           \
    (void)ctx;                                                                                \
    FemMaterial m = builtin_material(lawname, par);                                           \
    return fem_material_eval_iso(&m, F, ho, hn, W, P, A);                                     \
  }                                                                                           \
  static double fn##_mu0(const double *par) {                                                 \
    FemMaterial m = builtin_material(lawname, par);                                           \
    return fem_material_mu0(&m);                                                              \
  }
BUILTIN_EVAL(eval_neohooke, "neohooke")
BUILTIN_EVAL(eval_mooney, "mooney_rivlin")
BUILTIN_EVAL(eval_yeoh, "yeoh")
BUILTIN_EVAL(eval_stiff, "stiff_neohooke")

static const char *const p_nh[] = {"c10", "kappa"};
static const char *const p_mr[] = {"c10", "c01", "kappa"};
static const char *const p_ye[] = {"c10", "c20", "c30", "kappa"};
static const char *const p_st[] = {"e", "nu"};
static const FemLaw builtin[] = {
    {"neohooke", 2, p_nh, 0, 1, FEM_LAW_ISOCHORIC, NULL, eval_neohooke, NULL, eval_neohooke_mu0, NULL, NULL},
    {"mooney_rivlin", 3, p_mr, 0, 1, FEM_LAW_ISOCHORIC, NULL, eval_mooney, NULL, eval_mooney_mu0, NULL, NULL},
    {"yeoh", 4, p_ye, 0, 1, FEM_LAW_ISOCHORIC, NULL, eval_yeoh, NULL, eval_yeoh_mu0, NULL, NULL},
    {"stiff_neohooke", 2, p_st, 0, 1, FEM_LAW_ISOCHORIC, NULL, eval_stiff, NULL, eval_stiff_mu0, NULL, NULL},
};
#define NBUILTIN ((int)(sizeof builtin / sizeof *builtin))

/* laws of fem/ that are objects only (no built-in kind): found and listed like registered ones */
static const FemLaw *const library[] = {&fem_law_mohr_coulomb};
#define NLIBRARY ((int)(sizeof library / sizeof *library))

static const FemLaw *laws[MAX_LAWS];
static int nlaws;
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

static const FemLaw *find_locked(const char *name) {
  for (int i = 0; i < NBUILTIN; i++)
    if (!strcmp(builtin[i].name, name)) return &builtin[i];
  for (int i = 0; i < NLIBRARY; i++)
    if (!strcmp(library[i]->name, name)) return library[i];
  for (int i = 0; i < nlaws; i++)
    if (!strcmp(laws[i]->name, name)) return laws[i];
  return NULL;
}

int fem_law_register(const FemLaw *law) {
  SA_REQUIRE(law && law->name && law->name[0] && law->eval, SA_ERR_INPUT,
             "fem_law_register: a law needs a name and eval");
  SA_REQUIRE(law->nparams >= 0 && law->nparams <= FEM_LAW_MAX_PARAMS &&
                 (law->nparams == 0 || law->param_names),
             SA_ERR_INPUT, "law '%s': %d parameters (at most %d, each named)", law->name,
             law->nparams, FEM_LAW_MAX_PARAMS);
  SA_REQUIRE(law->nhist >= 0 && law->nhist <= FEM_MAT_MAX_HIST, SA_ERR_INPUT,
             "law '%s': %d history variables (at most %d)", law->name, law->nhist,
             FEM_MAT_MAX_HIST);
  SA_REQUIRE(law->kind == FEM_LAW_ISOCHORIC || law->kind == FEM_LAW_FULL, SA_ERR_INPUT,
             "law '%s': unknown kind %d", law->name, (int)law->kind);
  pthread_mutex_lock(&lock);
  const FemLaw *old = find_locked(law->name);
  int rc = 0;
  if (old && old != law) rc = 1;
  else if (!old && nlaws == MAX_LAWS) rc = 2;
  else if (!old) laws[nlaws++] = law;
  pthread_mutex_unlock(&lock);
  SA_REQUIRE(rc != 1, SA_ERR_INPUT, "a different law is registered as '%s'", law->name);
  SA_REQUIRE(rc != 2, SA_ERR_INPUT, "law registry full (%d laws)", MAX_LAWS);
  return 0;
}

const FemLaw *fem_law_find(const char *name) {
  if (!name) return NULL;
  pthread_mutex_lock(&lock);
  const FemLaw *l = find_locked(name);
  pthread_mutex_unlock(&lock);
  return l;
}

int fem_law_param(const FemLaw *law, const char *name) {
  for (int i = 0; i < law->nparams; i++)
    if (!strcmp(law->param_names[i], name)) return i;
  return -1;
}

void fem_law_list(char *buf, int n) {
  int len = 0;
  buf[0] = '\0';
  pthread_mutex_lock(&lock);
  for (int i = 0; i < NBUILTIN + NLIBRARY + nlaws && len < n; i++)
    len += snprintf(buf + len, (size_t)(n - len), "%s%s", i ? ", " : "",
                    i < NBUILTIN              ? builtin[i].name
                    : i < NBUILTIN + NLIBRARY ? library[i - NBUILTIN]->name
                                              : laws[i - NBUILTIN - NLIBRARY]->name);
  pthread_mutex_unlock(&lock);
}

int fem_material_from_law(const char *name, int nvals, const char *const *names,
                          const double *values, double rho, FemMaterial *out) {
  const FemLaw *L = fem_law_find(name);
  if (!L) {
    char list[512];
    fem_law_list(list, sizeof list);
    return SA_ERROR(SA_ERR_INPUT, "unknown material law '%s' (registered: %s)", name, list);
  }
  double par[FEM_LAW_MAX_PARAMS];
  int seen[FEM_LAW_MAX_PARAMS] = {0};
  for (int k = 0; k < nvals; k++) {
    int i = fem_law_param(L, names[k]);
    SA_REQUIRE(i >= 0, SA_ERR_INPUT, "law '%s' has no parameter '%s'", name, names[k]);
    SA_REQUIRE(!seen[i], SA_ERR_INPUT, "law '%s': parameter '%s' given twice", name, names[k]);
    seen[i] = 1;
    par[i] = values[k];
  }
  for (int i = 0; i < L->nparams; i++) {
    if (!seen[i] && L->param_defaults && !isnan(L->param_defaults[i]))
      par[i] = L->param_defaults[i], seen[i] = 1;
    SA_REQUIRE(seen[i], SA_ERR_INPUT, "law '%s': parameter '%s' missing", name,
               L->param_names[i]);
  }
  FemMaterial m = {0};
  if (L >= builtin && L < builtin + NBUILTIN) {
    m = builtin_material(name, par);
  } else {
    m.law = L;
    for (int i = 0; i < L->nparams; i++) m.par[i] = par[i];
    m.nhist = L->nhist;
    int ik = fem_law_param(L, "kappa");
    if (ik >= 0) m.kappa = par[ik];
  }
  m.rho = rho;
  *out = m;
  return 0;
}
