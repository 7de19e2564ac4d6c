/* ccx_ours.c - our FEM solver on exactly the problem ccx_export hands to CalculiX.
 *
 * Same mesh (fem_mesh_generate with the same .geo, parameters and h; the mesh signature printed
 * by both programs must agree), same materials (silicone Yeoh with kappa = ratio * mu0; stiff
 * regions compressible neo-Hookean from E, nu: the laws ccx_inp.c writes for ccx), clamped
 * surface fixed_end, follower pressure on cavity_wall ramped from 0 to P by fem_solver_solve's
 * adaptive load stepping. Writes BASE.u (one "ux uy uz" line per node) for ccx_post field and
 * prints one summary line:
 *   ours: nodes N dof N elems N sig S substeps N cuts N newton N setup_s T solve_s T
 *         assemble_s T factor_s T n_chol N n_lu N n_reuse N angle_deg A
 * (--verbose: the solver's INFO log, one line per substep, on stderr; --debug: every Newton step)
 *
 * usage: ccx_ours --geo FILE --h H --out BASE [--set NAME=VALUE]... [--kappa-ratio R]
 *          [--c10 ..] [--c20 ..] [--c30 ..] [--pressure P] [--threads N] [--rtol R]
 *          [--dl-init F] [--dl-max F] [--stiff REGION:E:NU]... [--mix-alpha A] [--predictor 0|1|2 (new_load|equilibrium|reuse)]
 *          [--reuse-rate R]
 * --mix-alpha: FemMaterial.mix_alpha of the silicone (0 = default, < 0 = pure P2-P0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_error.h"
#include "sa_log.h"

#define MAX_OPTS 32

/* Mesh signature shared with ccx_export: a position-weighted sum of coordinates and nodes. */
double ccx_mesh_signature(const FemMesh *m);

static int run(int argc, char **argv)
{
  const char *geo = NULL, *out = NULL;
  double h = 0, kratio = 500, mix_alpha = 0, c10 = 0.11e6, c20 = 0.02e6, c30 = 0, P = 10e3;
  int nparams = 0, nstiff = 0;
  FemGeoParam params[MAX_OPTS];
  char pnames[MAX_OPTS][64], snames[MAX_OPTS][64];
  double sE[MAX_OPTS], snu[MAX_OPTS];
  FemSolverParams prm = fem_solver_params_default();
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define OPT(name) (!strcmp(a, name) && v && ++i)
    if (OPT("--geo")) geo = v;
    else if (OPT("--out")) out = v;
    else if (OPT("--h")) h = atof(v);
    else if (OPT("--kappa-ratio")) kratio = atof(v);
    else if (OPT("--mix-alpha")) mix_alpha = atof(v);
    else if (OPT("--c10")) c10 = atof(v);
    else if (OPT("--c20")) c20 = atof(v);
    else if (OPT("--c30")) c30 = atof(v);
    else if (OPT("--pressure")) P = atof(v);
    else if (OPT("--threads")) prm.threads = atoi(v);
    else if (OPT("--rtol")) prm.rtol = atof(v);
    else if (OPT("--dl-init")) prm.dl_init = atof(v);
    else if (OPT("--dl-max")) prm.dl_max = atof(v);
    else if (OPT("--predictor")) prm.predictor = (FemPredictor)atoi(v);
    else if (OPT("--reuse-rate")) prm.reuse_rate = atof(v);
    else if (!strcmp(a, "--verbose")) sa_log_set_level(SA_LOG_INFO);
    else if (!strcmp(a, "--debug")) sa_log_set_level(SA_LOG_DEBUG);
    else if (OPT("--set")) {
      const char *eq = strchr(v, '=');
      SA_REQUIRE(nparams < MAX_OPTS && eq && eq - v < 63, SA_ERR_INPUT, "bad --set %s", v);
      memcpy(pnames[nparams], v, (size_t)(eq - v));
      pnames[nparams][eq - v] = 0;
      params[nparams].name = pnames[nparams];
      params[nparams++].value = atof(eq + 1);
    } else if (OPT("--stiff")) {
      char buf[128];
      snprintf(buf, sizeof buf, "%s", v);
      char *s1 = strchr(buf, ':'), *s2 = s1 ? strchr(s1 + 1, ':') : NULL;
      SA_REQUIRE(nstiff < MAX_OPTS && s1 && s2, SA_ERR_INPUT, "bad --stiff %s", v);
      *s1 = *s2 = 0;
      snprintf(snames[nstiff], 64, "%.63s", buf);
      sE[nstiff] = atof(s1 + 1);
      snu[nstiff++] = atof(s2 + 1);
    } else
      return SA_ERROR(SA_ERR_INPUT, "unknown or incomplete option %s", a);
#undef OPT
  }
  SA_REQUIRE(geo && out && h > 0, SA_ERR_INPUT, "need --geo, --out and --h");

  FemMesh *mesh = NULL;
  SA_CHECK(fem_mesh_generate(geo, nparams, params, h, 2, &mesh));
  FemMaterial mats[16];
  int rc = 0;
  SA_REQUIRE(mesh->nregions <= 16, SA_ERR_INPUT, "too many regions");
  for (int r = 0; r < mesh->nregions && !rc; ++r) {
    const char *name = mesh->region_names[r];
    int k = -1;
    for (int i = 0; i < nstiff; ++i)
      if (!strcmp(snames[i], name)) k = i;
    if (k >= 0) mats[r] = fem_material_from_e_nu(sE[k], snu[k], 1000);
    else if (!strcmp(name, "strain_limit")) mats[r] = fem_material_from_e_nu(1000e6, 0.3, 1000);
    else if (!strcmp(name, "reinforcement")) mats[r] = fem_material_from_e_nu(2000e6, 0.3, 1000);
    else if (!strcmp(name, "silicone")) {
      memset(&mats[r], 0, sizeof mats[r]);
      mats[r].kind = FEM_MAT_YEOH;
      mats[r].c10 = c10, mats[r].c20 = c20, mats[r].c30 = c30;
      mats[r].kappa = kratio * 2.0 * c10;
      mats[r].mix_alpha = mix_alpha; /* 0 = FEM_MAT_MIX_ALPHA_DEFAULT, < 0 = pure P2-P0 */
      mats[r].rho = 1130;
    } else
      rc = SA_ERROR(SA_ERR_INPUT, "region %s has no material", name);
  }
  FemSolver *s = NULL;
  double t0 = sa_time_now(), t1 = 0, t2 = 0;
  if (!rc) rc = fem_solver_create(mesh, mats, &prm, &s);
  if (!rc) rc = fem_solver_fix_surface(s, "fixed_end", FEM_XYZ);
  if (!rc) rc = fem_solver_add_pressure_surface(s, "cavity_wall");
  if (!rc) rc = fem_solver_setup(s);
  t1 = sa_time_now();
  if (!rc) rc = fem_solver_set_pressure(s, P);
  if (!rc) rc = fem_solver_solve(s);
  t2 = sa_time_now();
  if (!rc) {
    FemSolveReport rep;
    FemSolverStats st;
    fem_solver_report(s, &rep);
    fem_solver_stats(s, &st);
    const double *u = fem_solver_displacements(s);
    char path[1024];
    snprintf(path, sizeof path, "%s.u", out);
    FILE *f = fopen(path, "w");
    if (!f) rc = SA_ERROR(SA_ERR_IO, "cannot write %s", path);
    if (!rc) {
      fprintf(f, "# softact displacements (ux uy uz per node, mesh order) at p = %.9g Pa\n", P);
      for (int i = 0; i < mesh->nnodes; ++i)
        fprintf(f, "%.12e %.12e %.12e\n", u[3 * i], u[3 * i + 1], u[3 * i + 2]);
      if (fclose(f)) rc = SA_ERROR(SA_ERR_IO, "cannot close %s", path);
    }
    double ang = 0;
    if (!rc) rc = fem_bending_angle(mesh, "tip", fem_solver_positions(s), &ang);
    if (!rc)
      printf("ours: nodes %d dof %d elems %d sig %.12e substeps %d cuts %d newton %d setup_s %.3f "
             "solve_s %.3f assemble_s %.3f factor_s %.3f n_chol %d n_lu %d n_reuse %d angle_deg %.6f\n",
             mesh->nnodes, 3 * mesh->nnodes, mesh->nelem, ccx_mesh_signature(mesh), rep.substeps,
             rep.cuts, rep.newton_iters, t1 - t0, t2 - t1, st.t_assemble, st.t_factor, st.n_chol,
             st.n_lu, st.n_reuse, ang);
  }
  fem_solver_destroy(&s);
  fem_mesh_destroy(&mesh);
  return rc;
}

int main(int argc, char **argv)
{
  sa_log_set_level(SA_LOG_WARN);
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
