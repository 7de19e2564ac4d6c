/* ccx_export.c - write the tet10 mesh our FEM solver uses as a CalculiX C3D10 deck.
 *
 * The mesh is made by fem_mesh_generate from the same .geo, parameters and size h as the solver,
 * so both codes see identical nodes and elements. VTK's tet10 order equals CalculiX's C3D10 order
 * (ccx_inp.h); the program does not trust that blindly: every element is checked for positive
 * volume and for each mid-node lying nearest to the midpoint of the edge CalculiX assigns to it.
 * Each pressure face (a boundary tri6 of the load surface) is matched to the owning tet's face
 * number by its corner nodes.
 *
 * usage: ccx_export --geo FILE --h H --out BASE [--set NAME=VALUE]... [--order 2]
 *          [--fix SURF] [--roller SURF:DOF]... [--load SURF] [--tip SURF]
 *          [--c10 PA] [--c20 PA] [--c30 PA] [--kappa-ratio K/MU | --kappa PA]
 *          [--stiff REGION:E:NU]... [--pressure PA] [--inc0 F] [--incmin F] [--incmax F]
 *          [--print-all] [--time-points T1,T2,...]
 * --time-points prints the tip displacements only at these step times (fractions of the load,
 * e.g. 0.25,0.5,0.75,1), which ccx then hits exactly; without it, at every increment.
 * Defaults: the reference actuator (docs: /work/shared/ACTUATOR.md): fix fixed_end, load
 * cavity_wall, tip tip, Yeoh C10 = 0.11 MPa, C20 = 0.02 MPa, kappa = 500 mu0,
 * strain_limit E = 1000 MPa, reinforcement E = 2000 MPa (nu = 0.3). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccx_inp.h"
#include "fem_mesh.h"
#include "sa_error.h"

#define MAX_OPTS 32

/* ccx_sig.c: the mesh signature ccx_ours prints too. */
double ccx_mesh_signature(const FemMesh *m);

typedef struct {
  const char *geo, *out, *fix, *load, *tip, *time_points;
  double h;
  int order;
  int nparams;
  FemGeoParam params[MAX_OPTS];
  char param_names[MAX_OPTS][64];
  int nrollers;
  char roller_surf[MAX_OPTS][64];
  int roller_dof[MAX_OPTS];
  int nstiff;
  char stiff_name[MAX_OPTS][64];
  double stiff_E[MAX_OPTS], stiff_nu[MAX_OPTS];
  double c10, c20, c30, kappa, kappa_ratio, pressure, inc0, incmin, incmax;
  int print_all;
} Options;

static int parse(int argc, char **argv, Options *o)
{
  memset(o, 0, sizeof *o);
  o->order = 2;
  o->fix = "fixed_end";
  o->load = "cavity_wall";
  o->tip = "tip";
  o->c10 = 0.11e6;
  o->c20 = 0.02e6;
  o->kappa_ratio = 500.0;
  o->pressure = 10e3;
  o->inc0 = 0.02;
  o->incmin = 1e-5;
  o->incmax = 0.05;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define OPT(name) (!strcmp(a, name) && v && ++i)
    if (OPT("--geo")) o->geo = v;
    else if (OPT("--out")) o->out = v;
    else if (OPT("--h")) o->h = atof(v);
    else if (OPT("--order")) o->order = atoi(v);
    else if (OPT("--fix")) o->fix = strcmp(v, "none") ? v : NULL;
    else if (OPT("--load")) o->load = v;
    else if (OPT("--tip")) o->tip = v;
    else if (OPT("--c10")) o->c10 = atof(v);
    else if (OPT("--c20")) o->c20 = atof(v);
    else if (OPT("--c30")) o->c30 = atof(v);
    else if (OPT("--kappa")) o->kappa = atof(v);
    else if (OPT("--kappa-ratio")) o->kappa_ratio = atof(v);
    else if (OPT("--pressure")) o->pressure = atof(v);
    else if (OPT("--inc0")) o->inc0 = atof(v);
    else if (OPT("--incmin")) o->incmin = atof(v);
    else if (OPT("--incmax")) o->incmax = atof(v);
    else if (!strcmp(a, "--print-all")) o->print_all = 1;
    else if (OPT("--time-points")) o->time_points = v;
    else if (OPT("--set")) {
      SA_REQUIRE(o->nparams < MAX_OPTS, SA_ERR_INPUT, "too many --set");
      const char *eq = strchr(v, '=');
      SA_REQUIRE(eq && eq - v < 63, SA_ERR_INPUT, "--set wants NAME=VALUE, got %s", v);
      memcpy(o->param_names[o->nparams], v, (size_t)(eq - v));
      o->param_names[o->nparams][eq - v] = 0;
      o->params[o->nparams].name = o->param_names[o->nparams];
      o->params[o->nparams].value = atof(eq + 1);
      o->nparams++;
    } else if (OPT("--roller")) {
      SA_REQUIRE(o->nrollers < MAX_OPTS, SA_ERR_INPUT, "too many --roller");
      const char *c = strrchr(v, ':');
      SA_REQUIRE(c && c - v < 63, SA_ERR_INPUT, "--roller wants SURF:DOF, got %s", v);
      memcpy(o->roller_surf[o->nrollers], v, (size_t)(c - v));
      o->roller_dof[o->nrollers++] = atoi(c + 1);
    } else if (OPT("--stiff")) {
      SA_REQUIRE(o->nstiff < MAX_OPTS, SA_ERR_INPUT, "too many --stiff");
      char buf[128];
      snprintf(buf, sizeof buf, "%s", v);
      char *s1 = strchr(buf, ':'), *s2 = s1 ? strchr(s1 + 1, ':') : NULL;
      SA_REQUIRE(s1 && s2, SA_ERR_INPUT, "--stiff wants REGION:E:NU, got %s", v);
      *s1 = *s2 = 0;
      snprintf(o->stiff_name[o->nstiff], 64, "%.63s", buf);
      o->stiff_E[o->nstiff] = atof(s1 + 1);
      o->stiff_nu[o->nstiff++] = atof(s2 + 1);
    } else
      return SA_ERROR(SA_ERR_INPUT, "unknown or incomplete option %s (see the header of ccx_export.c)", a);
#undef OPT
  }
  SA_REQUIRE(o->geo && o->out && o->h > 0, SA_ERR_INPUT, "need --geo, --out and --h");
  SA_REQUIRE(o->order == 2, SA_ERR_INPUT, "only --order 2 (C3D10) is supported");
  if (o->kappa <= 0) o->kappa = o->kappa_ratio * 2.0 * o->c10;
  return 0;
}

/* Stiff-region table: command line first, then the reference design. */
static int region_law(const Options *o, const char *name, CcxRegion *g)
{
  snprintf(g->name, sizeof g->name, "%s", name);
  for (int i = 0; i < o->nstiff; ++i)
    if (!strcmp(o->stiff_name[i], name)) {
      g->stiff = 1;
      g->E = o->stiff_E[i];
      g->nu = o->stiff_nu[i];
      return 0;
    }
  if (!strcmp(name, "silicone")) g->stiff = 0;
  else if (!strcmp(name, "strain_limit")) g->stiff = 1, g->E = 1000e6, g->nu = 0.3;
  else if (!strcmp(name, "reinforcement")) g->stiff = 1, g->E = 2000e6, g->nu = 0.3;
  else return SA_ERROR(SA_ERR_INPUT, "region %s has no material (give --stiff %s:E:NU)", name, name);
  return 0;
}

/* CalculiX C3D10 edges (0-based corners) of mid-nodes 4..9 and faces (corner triples). */
static const int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
static const int kFace[4][3] = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}};

/* Order check: positive corner volume, and each mid-node nearest to the midpoint of its own
 * edge among all six edge midpoints (curved boundary edges move a mid-node off the chord by a
 * small fraction of the edge, far less than the distance to another edge's midpoint). */
static int check_element(const FemMesh *m, int e)
{
  const int *c = m->conn + 10 * (size_t)e;
  const double *X[10];
  for (int k = 0; k < 10; ++k) X[k] = m->xyz + 3 * (size_t)c[k];
  double vol = ccx_tet_volume(X[0], X[1], X[2], X[3]);
  SA_REQUIRE(vol > 0, SA_ERR_INPUT, "element %d has corner volume %g <= 0", e, vol);
  for (int k = 0; k < 6; ++k) {
    int best = -1;
    double dbest = INFINITY;
    for (int j = 0; j < 6; ++j) {
      double d = 0;
      for (int q = 0; q < 3; ++q) {
        double mid = 0.5 * (X[kEdge[j][0]][q] + X[kEdge[j][1]][q]);
        d += (X[4 + k][q] - mid) * (X[4 + k][q] - mid);
      }
      if (d < dbest) dbest = d, best = j;
    }
    SA_REQUIRE(best == k, SA_ERR_INPUT, "element %d: mid-node %d sits on edge %d, not %d", e,
               4 + k, best, k);
  }
  return 0;
}

static int face_number(const FemMesh *m, int e, const int *fn)
{
  const int *c = m->conn + 10 * (size_t)e;
  for (int f = 0; f < 4; ++f) {
    int hit = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) hit += c[kFace[f][a]] == fn[b];
    if (hit == 3) return f + 1;
  }
  return 0;
}

static int surface(const FemMesh *mesh, const char *name, const FemSurface **s)
{
  *s = fem_mesh_find_surface(mesh, name);
  SA_REQUIRE(*s, SA_ERR_INPUT, "mesh has no surface %s", name);
  return 0;
}

static int build(const Options *o, const FemMesh *mesh, CcxModel *m)
{
  SA_REQUIRE(mesh->etype == FEM_TET10, SA_ERR_INPUT, "mesh is not tet10");
  for (int e = 0; e < mesh->nelem; ++e) SA_CHECK(check_element(mesh, e));
  m->etype = "C3D10";
  m->nen = 10;
  m->nnodes = mesh->nnodes;
  SA_CALLOC(m->xyz, 3 * (size_t)mesh->nnodes);
  memcpy(m->xyz, mesh->xyz, 3 * (size_t)mesh->nnodes * sizeof(double));
  m->nelem = mesh->nelem;
  SA_CALLOC(m->conn, 10 * (size_t)mesh->nelem);
  memcpy(m->conn, mesh->conn, 10 * (size_t)mesh->nelem * sizeof(int));
  SA_CALLOC(m->region, mesh->nelem);
  memcpy(m->region, mesh->region, (size_t)mesh->nelem * sizeof(int));
  SA_REQUIRE(mesh->nregions <= CCX_MAX_REGIONS, SA_ERR_INPUT, "too many regions");
  m->nregions = mesh->nregions;
  for (int r = 0; r < mesh->nregions; ++r) SA_CHECK(region_law(o, mesh->region_names[r], &m->regions[r]));
  const FemSurface *s;
  if (o->fix) {
    SA_CHECK(surface(mesh, o->fix, &s));
    SA_CHECK(ccx_model_add_bc(m, "FIX", 1, 3, s->nnodes, s->nodes));
  }
  for (int i = 0; i < o->nrollers; ++i) {
    SA_CHECK(surface(mesh, o->roller_surf[i], &s));
    char name[32];
    snprintf(name, sizeof name, "ROLLER%d", i);
    SA_CHECK(ccx_model_add_bc(m, name, o->roller_dof[i], o->roller_dof[i], s->nnodes, s->nodes));
  }
  SA_CHECK(surface(mesh, o->load, &s));
  m->nload = s->nfaces;
  SA_CALLOC(m->load_elem, s->nfaces);
  SA_CALLOC(m->load_face, s->nfaces);
  for (int i = 0; i < s->nfaces; ++i) {
    const int *fn = s->faces + (size_t)s->nfn * i;
    int e = s->face_elem[i], f = face_number(mesh, e, fn);
    SA_REQUIRE(f > 0, SA_ERR_INPUT, "face %d of %s is not a face of its element %d", i, o->load, e);
    /* The surface's face is oriented out of the solid; CalculiX's face f of a positive tet has
     * its outward normal by construction, so only the node set has to match. Check the
     * orientation anyway: the fourth corner must lie behind the face. */
    const int *c = mesh->conn + 10 * (size_t)e;
    int opp = -1;
    for (int k = 0; k < 4; ++k)
      if (c[k] != fn[0] && c[k] != fn[1] && c[k] != fn[2]) opp = c[k];
    double v = ccx_tet_volume(mesh->xyz + 3 * (size_t)fn[0], mesh->xyz + 3 * (size_t)fn[1],
                              mesh->xyz + 3 * (size_t)fn[2], mesh->xyz + 3 * (size_t)opp);
    SA_REQUIRE(v < 0, SA_ERR_INPUT, "face %d of %s is not oriented out of element %d", i, o->load, e);
    m->load_elem[i] = e;
    m->load_face[i] = f;
  }
  SA_CHECK(surface(mesh, o->tip, &s));
  m->ntip_nodes = s->nnodes;
  SA_CALLOC(m->tip_nodes, s->nnodes);
  memcpy(m->tip_nodes, s->nodes, (size_t)s->nnodes * sizeof(int));
  /* tri6 (corners 0..2, mids 3:(01) 4:(12) 5:(20)) -> 4 flat triangles, same orientation. */
  SA_REQUIRE(s->nfn == 6, SA_ERR_INPUT, "tip faces are not tri6");
  m->ntip_tri = 4 * s->nfaces;
  SA_CALLOC(m->tip_tri, 3 * (size_t)m->ntip_tri);
  static const int sub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  for (int i = 0; i < s->nfaces; ++i)
    for (int t = 0; t < 4; ++t)
      for (int k = 0; k < 3; ++k) m->tip_tri[3 * (4 * i + t) + k] = s->faces[6 * i + sub[t][k]];
  m->c10 = o->c10;
  m->c20 = o->c20;
  m->c30 = o->c30;
  m->kappa = o->kappa;
  m->pressure = o->pressure;
  m->inc0 = o->inc0;
  m->incmin = o->incmin;
  m->incmax = o->incmax;
  m->print_all = o->print_all;
  if (o->time_points) SA_CHECK(ccx_model_set_time_points(m, o->time_points));
  return 0;
}

static int run(int argc, char **argv)
{
  Options o;
  SA_CHECK(parse(argc, argv, &o));
  FemMesh *mesh = NULL;
  SA_CHECK(fem_mesh_generate(o.geo, o.nparams, o.params, o.h, o.order, &mesh));
  CcxModel m;
  memset(&m, 0, sizeof m);
  int rc = build(&o, mesh, &m);
  if (!rc) rc = ccx_model_write(&m, o.out);
  if (!rc)
    printf("ccx_export: %s.inp: %d nodes (%d dof), %d C3D10, %d pressure faces, kappa %.6g Pa, "
           "sig %.12e\n", o.out, m.nnodes, 3 * m.nnodes, m.nelem, m.nload, m.kappa,
           ccx_mesh_signature(mesh));
  ccx_model_free(&m);
  fem_mesh_destroy(&mesh);
  return rc;
}

int main(int argc, char **argv)
{
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
