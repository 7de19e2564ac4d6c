/* fem_actuator.c - the reference actuator as a FEM model: case tables, mesh, materials and
 * solver parameters shared by the pressure, FEM-DEM and Mohr-Coulomb scenes (fem_actuator.h). */
#include "fem_actuator.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_law.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"

#define P(f) offsetof(FemMeshParams, f)
static const SaParam mesh_params[] = {
    {"geo", SA_PARAM_FILE, P(geo), "-", "meshes/actuator.geo", 0, 0, 0, NULL,
     "Gmsh .geo source of the actuator (relative to the case file, then to the softact source tree)"},
    {"h", SA_PARAM_REAL, P(h), "m", "4e-3", 1e-4, 0.05, 0, NULL,
     "target element size (mesh refinement is this one key)"},
    {"h_band", SA_PARAM_REAL, P(h_band), "m", "2e-3", 1e-4, 0.05, 0, NULL,
     "element size in the strain-limiting band"},
    {"h_ring", SA_PARAM_REAL, P(h_ring), "m", "2e-3", 1e-5, 0.05, 0, NULL,
     "element size in the reinforcement rings (kind = swept: at their faces, where the cells "
     "grow from by [mesh] grade)"},
    {"order", SA_PARAM_INT, P(order), "-", "2", 1, 2, 0, NULL,
     "element order: 2 = tet10 mixed (use this), 1 = tet4 (locks when nearly incompressible)"},
    {"rings", SA_PARAM_INT, P(rings), "-", "1", 0, 1, 0, NULL,
     "radial reinforcement rings present (0 = the design without rings)"},
    {"kind", SA_PARAM_CHOICE, P(kind), "-", "gmsh", 0, 0, 0, "gmsh|swept",
     "gmsh = isotropic tets from [mesh] geo; swept = a tensor grid in r, theta, z through every "
     "interface of ACTUATOR.md's design, each cell 6 tets: elements thin across the rings and "
     "band and long along them (geo is then not used; docs/fem_time_to_accuracy.md)"},
    {"h_radial", SA_PARAM_REAL, P(h_radial), "m", "0", 0, 0.05, 0, NULL,
     "kind = swept: radial size in the silicone's layers (0 = h_band)"},
    {"grade", SA_PARAM_REAL, P(grade), "-", "1.5", 1, 4, 0, NULL,
     "kind = swept: growth factor of the cell size away from a ring face (h_ring) or a corner, "
     "up to h along z and h_radial across the wall"},
};
#undef P
#define P(f) offsetof(FemMatParams, f)
static const SaParam mat_params[] = {
    {"model", SA_PARAM_CHOICE, P(model), "-", "yeoh", 0, 0, 0, "yeoh|mooney_rivlin|neohooke",
     "hyperelastic law of the silicone"},
    {"c10", SA_PARAM_REAL, P(c10), "Pa", "0.11e6", 0, INFINITY, SA_MIN_OPEN, NULL,
     "silicone C10 (neo-Hookean: mu = 2 C10)"},
    {"c01", SA_PARAM_REAL, P(c01), "Pa", "0", 0, INFINITY, 0, NULL, "silicone C01 (Mooney-Rivlin)"},
    {"c20", SA_PARAM_REAL, P(c20), "Pa", "0.02e6", -INFINITY, INFINITY, 0, NULL,
     "silicone C20 (Yeoh)"},
    {"c30", SA_PARAM_REAL, P(c30), "Pa", "0", -INFINITY, INFINITY, 0, NULL, "silicone C30 (Yeoh)"},
    {"kappa_ratio", SA_PARAM_REAL, P(kappa_ratio), "-", "500", 1, 1e5, 0, NULL,
     "silicone bulk modulus / initial shear modulus"},
    {"rho", SA_PARAM_REAL, P(rho), "kg/m^3", "1130", 0, INFINITY, SA_MIN_OPEN, NULL,
     "silicone density"},
    {"limit_e", SA_PARAM_REAL, P(limit_e), "Pa", "1000e6", 0, INFINITY, SA_MIN_OPEN, NULL,
     "strain-limiting layer Young's modulus"},
    {"limit_nu", SA_PARAM_REAL, P(limit_nu), "-", "0.3", 0, 0.5, SA_MAX_OPEN, NULL,
     "strain-limiting layer Poisson's ratio"},
    {"limit_rho", SA_PARAM_REAL, P(limit_rho), "kg/m^3", "1000", 0, INFINITY, SA_MIN_OPEN, NULL,
     "strain-limiting layer density"},
    {"ring_e", SA_PARAM_REAL, P(ring_e), "Pa", "2000e6", 0, INFINITY, SA_MIN_OPEN, NULL,
     "reinforcement ring Young's modulus"},
    {"ring_nu", SA_PARAM_REAL, P(ring_nu), "-", "0.3", 0, 0.5, SA_MAX_OPEN, NULL,
     "reinforcement ring Poisson's ratio"},
    {"ring_rho", SA_PARAM_REAL, P(ring_rho), "kg/m^3", "1300", 0, INFINITY, SA_MIN_OPEN, NULL,
     "reinforcement ring density"},
    {"regions", SA_PARAM_STRING, P(regions), "-",
     "silicone:silicone, strain_limit:limit, reinforcement:ring", 0, 0, 0, NULL,
     "material of each mesh region as region:set, set = silicone, limit, ring, or any "
     "registered law with its parameters, e.g. fill:mohr_coulomb(young = 20e6 poisson = 0.3 "
     "friction_angle = 28 cohesion = 100 dilation_angle = 3 rho = 1550)"},
};
#undef P
#define P(f) offsetof(FemSolverCaseParams, f)
static const SaParam solver_params[] = {
    {"rtol", SA_PARAM_REAL, P(rtol), "-", "1e-8", 1e-14, 1e-2, 0, NULL,
     "Newton residual tolerance relative to the force scale"},
    {"max_iter", SA_PARAM_INT, P(max_iter), "-", "25", 1, 1000, 0, NULL,
     "Newton iterations per substep"},
    {"dl_min", SA_PARAM_REAL, P(dl_min), "-", "1e-4", 1e-12, 1, SA_MIN_OPEN, NULL,
     "smallest substep as a fraction of an output step (limit-point detection)"},
    {"threads", SA_PARAM_INT, P(threads), "-", "0", 0, 256, 0, NULL,
     "assembly and BLAS threads (0 = the run's thread count)"},
    {"linear_solver", SA_PARAM_CHOICE, P(linear_solver), "-", "auto", 0, 0, 0, "auto|lu",
     "auto: CHOLMOD, UMFPACK LU when not positive definite/unsymmetric; lu: always UMFPACK"},
    {"reuse_rate", SA_PARAM_REAL, P(reuse_rate), "-", "0", 0, 0.9, 0, NULL,
     "reuse the factors while the residual norm falls by this factor per iteration "
     "(0 = full Newton)"},
    {"predictor", SA_PARAM_CHOICE, P(predictor), "-", "new_load", 0, 0, 0,
     "new_load|equilibrium|reuse|extrapolate",
     "first iterate of a substep: converged state with the new load's stiffness, with its own "
     "load, its last factors reused, or the secant extrapolation of the last two states"},
    {"merit", SA_PARAM_CHOICE, P(merit), "-", "lazy", 0, 0, 0, "lazy|energy",
     "line search: lazy (backtrack on inverted elements, NaN, residual growth) or energy "
     "(Armijo on the total potential where it is one)"},
    {"indefinite", SA_PARAM_CHOICE, P(indefinite), "-", "lu", 0, 0, 0, "lu|modify",
     "tangent not positive definite: UMFPACK LU, or Cholesky with the load stiffness reduced "
     "(at a later Newton iterate the step to it is halved first; the increment is cut if "
     "even K_int is indefinite)"},
    {"krylov_max", SA_PARAM_INT, P(krylov_max), "-", "0", 0, 1000, 0, NULL,
     "Krylov iterations on the current tangent, preconditioned by the last factors, before "
     "refactorising (0 = off): PCG on Cholesky factors of a symmetric tangent, else GMRES"},
    {"krylov_rtol", SA_PARAM_REAL, P(krylov_rtol), "-", "1e-3", 1e-12, 0.5, 0, NULL,
     "Krylov stop: linear residual relative to the Newton residual"},
    {"ls_memory", SA_PARAM_INT, P(ls_memory), "-", "1", 1, 8, 0, NULL,
     "energy merit: Armijo test against the largest potential of this many last iterates "
     "(1 = monotone; more lets the full steps of a nearly incompressible solid pass)"},
};
#undef P
const SaParamTable fem_actuator_mesh_table = {
    "mesh", "fem", "FEM mesh of the actuator (selects the fem scene)", mesh_params,
    SA_NPARAMS(mesh_params)};
const SaParamTable fem_actuator_material_table = {"material", "fem",
                                                  "FEM materials per mesh region", mat_params,
                                                  SA_NPARAMS(mat_params)};
const SaParamTable fem_actuator_solver_table = {"solver", "fem", "FEM Newton and linear solver",
                                                solver_params, SA_NPARAMS(solver_params)};

/* A region given a registered law directly: "law(param = value ...)" with its parameters
 * separated by blanks, ';' or ',' and its density as rho. */
typedef struct {
  char law[64];
  int n;
  char names[FEM_LAW_MAX_PARAMS][64];
  const char *pn[FEM_LAW_MAX_PARAMS];
  double v[FEM_LAW_MAX_PARAMS];
  double rho;
} LawSpec;

static int parse_law(char *txt, LawSpec *ls, char *bad, size_t nbad) {
  memset(ls, 0, sizeof *ls);
  ls->rho = NAN;
  char *open = strchr(txt, '('), *close = strrchr(txt, ')');
  char *e = open;
  while (e > txt && (e[-1] == ' ' || e[-1] == '\t')) e--;
  if (!open || !close || close < open || close[1] != '\0' || e == txt || e - txt >= 64) {
    snprintf(bad, nbad, "'%s' is not law(param = value ...)", txt);
    return -1;
  }
  memcpy(ls->law, txt, (size_t)(e - txt));
  *close = '\0';
  for (char *save = NULL, *tok = strtok_r(open + 1, " \t;,", &save); tok;
       tok = strtok_r(NULL, " \t;,", &save)) {
    char *eq = strchr(tok, '=');
    /* "name = value" with blanks: rejoin the pieces */
    char item[128];
    snprintf(item, sizeof item, "%s", tok);
    while (!eq || eq[1] == '\0') {
      char *nx = strtok_r(NULL, " \t;,", &save);
      if (!nx) break;
      size_t l = strlen(item);
      snprintf(item + l, sizeof item - l, "%s", nx);
      eq = strchr(item, '=');
      if (eq && eq[1]) break;
    }
    eq = strchr(item, '=');
    char *end = NULL;
    double v = eq ? strtod(eq + 1, &end) : NAN;
    if (!eq || eq == item || !end || *end || !isfinite(v)) {
      snprintf(bad, nbad, "law %s: '%s' is not param = number", ls->law, item);
      return -1;
    }
    *eq = '\0';
    if (!strcmp(item, "rho")) {
      ls->rho = v;
      continue;
    }
    if (ls->n == FEM_LAW_MAX_PARAMS) {
      snprintf(bad, nbad, "law %s: more than %d parameters", ls->law, FEM_LAW_MAX_PARAMS);
      return -1;
    }
    snprintf(ls->names[ls->n], 64, "%s", item);
    ls->pn[ls->n] = ls->names[ls->n];
    ls->v[ls->n++] = v;
  }
  if (!isfinite(ls->rho) || ls->rho < 0) {
    snprintf(bad, nbad, "law %s: needs its density as rho = value >= 0 [kg/m^3]", ls->law);
    return -1;
  }
  return 0;
}

/* The set the regions map gives region `name`: 0 silicone, 1 limit, 2 ring, 3 a law given
 * directly (ls [out] filled), -1 none, -2 bad syntax or set (bad [out] names the offending
 * entry). Entries are split at commas outside parentheses. */
static int region_set(const char *map, const char *name, char *bad, size_t nbad, LawSpec *ls) {
  const char *sets[] = {"silicone", "limit", "ring"};
  char buf[SA_STR_MAX];
  snprintf(buf, sizeof buf, "%s", map);
  int found = -1, depth = 0;
  char *tok = buf;
  for (char *q = buf;; q++) {
    if (*q == '(') depth++;
    if (*q == ')') depth--;
    if (*q && (*q != ',' || depth > 0)) continue;
    int last = *q == '\0';
    *q = '\0';
    while (*tok == ' ' || *tok == '\t') tok++;
    char *colon = strchr(tok, ':');
    char *end = tok + strlen(tok);
    while (end > tok && (end[-1] == ' ' || end[-1] == '\t')) *--end = '\0';
    if (!*tok && last) break;
    if (!colon || colon == tok) {
      snprintf(bad, nbad, "'%s' is not region:set", tok);
      return -2;
    }
    char *r_end = colon;
    while (r_end > tok && r_end[-1] == ' ') r_end--;
    *r_end = '\0';
    char *set = colon + 1;
    while (*set == ' ') set++;
    int k = -1;
    for (int i = 0; i < 3; i++)
      if (!strcmp(set, sets[i])) k = i;
    LawSpec tmp;
    if (k < 0 && strchr(set, '(')) {
      if (parse_law(set, &tmp, bad, nbad)) return -2;
      if (!fem_law_find(tmp.law)) {
        char list[512];
        fem_law_list(list, sizeof list);
        snprintf(bad, nbad, "region '%.60s': unknown law '%.60s' (registered: %.300s)", tok, tmp.law,
               list);
        return -2;
      }
      k = 3;
    }
    if (k < 0) {
      snprintf(bad, nbad, "set '%s' of region '%s' is not silicone, limit, ring or "
               "law(param = value ... rho = value)", set, tok);
      return -2;
    }
    if (name && !strcmp(tok, name)) {
      found = k;
      if (k == 3 && ls) {
        *ls = tmp;
        for (int i = 0; i < ls->n; i++) ls->pn[i] = ls->names[i]; /* into the copy */
      }
    }
    if (last) break;
    tok = q + 1;
  }
  if (depth != 0) {
    snprintf(bad, nbad, "unbalanced parentheses");
    return -2;
  }
  return found;
}

/* Every law entry of the map builds a valid material (unknown or missing parameters, values out
 * of range): SA_ERR_INPUT naming the entry. */
static int check_law_entries(const char *map, char *bad, size_t nbad) {
  char buf[SA_STR_MAX], names[64][64];
  snprintf(buf, sizeof buf, "%s", map);
  int nn = 0, depth = 0;
  for (char *q = buf, *tok = buf;; q++) { /* region names */
    if (*q == '(') depth++;
    if (*q == ')') depth--;
    if (*q && (*q != ',' || depth > 0)) continue;
    int last = *q == '\0';
    *q = '\0';
    while (*tok == ' ' || *tok == '\t') tok++; /* as region_set trims, or the entry is skipped */
    char *colon = strchr(tok, ':');
    if (colon && nn < 64) {
      char *r = colon;
      while (r > tok && r[-1] == ' ') r--;
      snprintf(names[nn++], 64, "%.*s", (int)(r - tok), tok);
    }
    if (last) break;
    tok = q + 1;
  }
  for (int i = 0; i < nn; i++) {
    LawSpec ls;
    if (region_set(map, names[i], bad, nbad, &ls) != 3) continue;
    FemMaterial m;
    int rc = fem_material_from_law(ls.law, ls.n, ls.pn, ls.v, ls.rho, &m);
    if (!rc) rc = fem_material_check(&m);
    if (rc) {
      snprintf(bad, nbad, "region '%.60s': %.400s", names[i], sa_error_message());
      sa_error_clear();
      return -2;
    }
  }
  return 0;
}

int fem_actuator_load(const SaCase *c, FemActuatorCase *a) {
  SA_CHECK(sa_params_load(&fem_actuator_mesh_table, c, &a->mesh));
  SA_CHECK(sa_params_load(&fem_actuator_material_table, c, &a->mat));
  SA_CHECK(sa_params_load(&fem_actuator_solver_table, c, &a->solver));
  SA_REQUIRE(a->mesh.geo[0], SA_ERR_INPUT, "%s: [mesh] geo: no .geo file given", sa_case_path(c));
  SA_REQUIRE(strcmp(a->mat.model, "mooney_rivlin") || a->mat.c01 > 0, SA_ERR_INPUT,
             "%s: [material] c01 must be > 0 for model = mooney_rivlin", sa_case_path(c));
  char bad[SA_STR_MAX];
  char w[SA_STR_MAX];
  SA_REQUIRE(region_set(a->mat.regions, NULL, bad, sizeof bad, NULL) != -2 &&
                 check_law_entries(a->mat.regions, bad, sizeof bad) == 0,
             SA_ERR_INPUT, "%s: [material] regions (%s): %s", sa_case_path(c),
             sa_case_origin(c, "material", "regions", w), bad);
  return 0;
}

void fem_actuator_write_resolved(const FemActuatorCase *a, FILE *f) {
  sa_params_write(&fem_actuator_mesh_table, &a->mesh, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_material_table, &a->mat, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_solver_table, &a->solver, f);
  fprintf(f, "\n");
}

int fem_actuator_mesh(const FemActuatorCase *a, FemMesh **m) {
  FemGeoParam gp[] = {{"rings", a->mesh.rings}, {"h_band", a->mesh.h_band},
                      {"h_ring", a->mesh.h_ring}};
  double t0 = sa_time_now();
  if (!strcmp(a->mesh.kind, "swept")) {
    const FemMeshParams *q = &a->mesh;
    FemSweptActuator p = fem_swept_actuator_default(q->h, q->h_radial > 0 ? q->h_radial : q->h_band,
                                                    q->h_band, q->h_ring, q->rings);
    p.grade = q->grade;
    SA_CHECK(fem_mesh_actuator_swept(&p, q->order, m));
    SA_CHECK(fem_mesh_check(*m, 1e-9));
    int nf = 0;
    for (int s = 0; s < (*m)->nsurfaces; s++) nf += (*m)->surfaces[s].nfaces;
    double qmin, qmean;
    fem_mesh_quality(*m, -1, &qmin, &qmean);
    sa_log(SA_LOG_INFO, "mesh", "generated %s: %d %s elements, %d nodes, %d regions, %d surfaces "
           "(%d faces), radius ratio min %.3f mean %.3f, %.2f s", (*m)->source, (*m)->nelem,
           (*m)->nen == 10 ? "tet10" : "tet4", (*m)->nnodes, (*m)->nregions, (*m)->nsurfaces, nf,
           qmin, qmean, sa_time_now() - t0);
    sa_timing_add("fem mesh", sa_time_now() - t0);
    return 0;
  }
  SA_CHECK(fem_mesh_generate(a->mesh.geo, 3, gp, a->mesh.h, a->mesh.order, m));
  sa_timing_add("fem mesh", sa_time_now() - t0);
  return 0;
}

int fem_actuator_materials(const FemActuatorCase *a, const FemMesh *m, FemMaterial *mats) {
  const FemMatParams *p = &a->mat;
  char bad[SA_STR_MAX];
  for (int r = 0; r < m->nregions; r++) {
    const char *name = m->region_names[r];
    LawSpec ls;
    int set = region_set(p->regions, name, bad, sizeof bad, &ls);
    SA_REQUIRE(set != -2, SA_ERR_INPUT, "[material] regions: %s", bad);
    SA_REQUIRE(set >= 0, SA_ERR_INPUT, "mesh region '%s' has no material: [material] regions = "
               "%s names no set for it", name, p->regions);
    if (set == 3) { /* a registered law with its parameters given in the map */
      SA_CHECK(fem_material_from_law(ls.law, ls.n, ls.pn, ls.v, ls.rho, &mats[r]));
    } else if (set == 0) { /* the silicone law from the registry; kappa from kappa_ratio and mu0 */
      const char *nm[4] = {"c10", NULL, NULL, "kappa"};
      double v[4] = {p->c10, 0, 0, 1.0};
      int n = 2;
      if (!strcmp(p->model, "yeoh")) nm[1] = "c20", v[1] = p->c20, nm[2] = "c30", v[2] = p->c30, n = 4;
      else if (!strcmp(p->model, "mooney_rivlin")) nm[1] = "c01", v[1] = p->c01, n = 3;
      nm[n - 1] = "kappa", v[n - 1] = 1.0;
      SA_CHECK(fem_material_from_law(p->model, n, nm, v, p->rho, &mats[r]));
      mats[r].kappa = p->kappa_ratio * fem_material_mu0(&mats[r]);
    } else {
      const char *nm[2] = {"e", "nu"};
      double v[2] = {set == 1 ? p->limit_e : p->ring_e, set == 1 ? p->limit_nu : p->ring_nu};
      SA_CHECK(fem_material_from_law("stiff_neohooke", 2, nm, v,
                                     set == 1 ? p->limit_rho : p->ring_rho, &mats[r]));
    }
  }
  return 0;
}

FemSolverParams fem_actuator_solver_params(const FemActuatorCase *a, int run_threads) {
  const FemSolverCaseParams *c = &a->solver;
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = c->rtol;
  prm.max_iter = c->max_iter;
  prm.dl_min = c->dl_min;
  prm.threads = c->threads > 0 ? c->threads : run_threads;
  prm.linsolver = !strcmp(c->linear_solver, "lu") ? FEM_LINSOLVER_LU : FEM_LINSOLVER_AUTO;
  prm.reuse_rate = c->reuse_rate;
  prm.predictor = !strcmp(c->predictor, "equilibrium") ? FEM_PREDICT_EQUILIBRIUM
                  : !strcmp(c->predictor, "reuse")       ? FEM_PREDICT_REUSE
                  : !strcmp(c->predictor, "extrapolate") ? FEM_PREDICT_EXTRAPOLATE
                                                         : FEM_PREDICT_NEW_LOAD;
  prm.merit = !strcmp(c->merit, "energy") ? FEM_MERIT_ENERGY : FEM_MERIT_LAZY;
  prm.indefinite = !strcmp(c->indefinite, "modify") ? FEM_INDEFINITE_MODIFY : FEM_INDEFINITE_LU;
  prm.krylov_max = c->krylov_max;
  prm.krylov_rtol = c->krylov_rtol;
  prm.ls_memory = c->ls_memory;
  return prm;
}
