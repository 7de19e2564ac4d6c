/* ccx_inp.c - CalculiX .inp writer (see ccx_inp.h for the conventions). */
#include "ccx_inp.h"

#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

double ccx_tet_volume(const double *a, const double *b, const double *c, const double *d)
{
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = d[k] - a[k];
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

int ccx_model_add_bc(CcxModel *m, const char *name, int first, int last, int n, const int *nodes)
{
  SA_REQUIRE(m->nbcs < CCX_MAX_BCS, SA_ERR_INPUT, "too many boundary-condition sets");
  SA_REQUIRE(n > 0, SA_ERR_INPUT, "boundary-condition set %s is empty", name);
  CcxBc *b = &m->bcs[m->nbcs];
  snprintf(b->name, sizeof b->name, "%s", name);
  b->first = first;
  b->last = last;
  b->n = n;
  SA_CALLOC(b->nodes, n);
  memcpy(b->nodes, nodes, (size_t)n * sizeof *nodes);
  m->nbcs++;
  return 0;
}

int ccx_model_set_time_points(CcxModel *m, const char *list)
{
  int n = 0;
  for (const char *p = list; *p;) {
    char *end;
    double t = strtod(p, &end);
    SA_REQUIRE(end != p && (*end == ',' || !*end), SA_ERR_INPUT, "bad time-point list %s", list);
    SA_REQUIRE(n < CCX_MAX_TIME_POINTS, SA_ERR_INPUT, "more than %d time points", CCX_MAX_TIME_POINTS);
    SA_REQUIRE(t > 0 && t <= 1 && (!n || t > m->time_points[n - 1]), SA_ERR_INPUT,
               "time points must ascend within (0, 1]: %s", list);
    m->time_points[n++] = t;
    p = *end ? end + 1 : end;
  }
  SA_REQUIRE(n > 0, SA_ERR_INPUT, "empty time-point list");
  m->ntime_points = n;
  return 0;
}

void ccx_model_free(CcxModel *m)
{
  free(m->xyz);
  free(m->conn);
  free(m->region);
  for (int i = 0; i < m->nbcs; ++i) free(m->bcs[i].nodes);
  free(m->load_elem);
  free(m->load_face);
  free(m->tip_nodes);
  free(m->tip_tri);
  memset(m, 0, sizeof *m);
}

/* A list of 1-based numbers, 16 per line (ccx reads at most 16 entries per data line). */
static void write_list(FILE *f, int n, const int *idx)
{
  for (int i = 0; i < n; ++i) fprintf(f, "%d%s", idx[i] + 1, (i % 16 == 15 || i == n - 1) ? "\n" : ",");
}

static int write_inp(const CcxModel *m, FILE *f)
{
  fprintf(f, "** softact CalculiX peer deck (bench/fem/ccx). SI units: m, Pa.\n");
  fprintf(f, "** %d nodes, %d %s elements, %d pressure faces, pressure %.9g Pa\n", m->nnodes,
          m->nelem, m->etype, m->nload, m->pressure);
  /* ccx reads each number from at most 20 characters (Fortran f20.0 on textpart(1:20)): a
   * longer field is cut, so "-8.22540040968911e-05" would become -8.2. %.12e is <= 19. */
  fprintf(f, "*NODE, NSET=NALL\n");
  for (int i = 0; i < m->nnodes; ++i)
    fprintf(f, "%d, %.12e, %.12e, %.12e\n", i + 1, m->xyz[3 * i], m->xyz[3 * i + 1],
            m->xyz[3 * i + 2]);
  /* Elements grouped by region: one *ELEMENT block (and ELSET) per region. */
  for (int r = 0; r < m->nregions; ++r) {
    int count = 0;
    for (int e = 0; e < m->nelem; ++e) count += m->region[e] == r;
    if (!count) continue;
    fprintf(f, "*ELEMENT, TYPE=%s, ELSET=E_%s\n", m->etype, m->regions[r].name);
    for (int e = 0; e < m->nelem; ++e) {
      if (m->region[e] != r) continue;
      const int *c = m->conn + (size_t)m->nen * e;
      fprintf(f, "%d", e + 1);
      /* An element data line holds at most 16 entries: continue on a second line. */
      for (int k = 0; k < m->nen; ++k) fprintf(f, ",%s%d", k == 15 ? "\n" : "", c[k] + 1);
      fprintf(f, "\n");
    }
  }
  for (int b = 0; b < m->nbcs; ++b) {
    fprintf(f, "*NSET, NSET=N_%s\n", m->bcs[b].name);
    write_list(f, m->bcs[b].n, m->bcs[b].nodes);
  }
  if (m->ntip_nodes) {
    fprintf(f, "*NSET, NSET=N_TIP\n");
    write_list(f, m->ntip_nodes, m->tip_nodes);
  }
  for (int r = 0; r < m->nregions; ++r) {
    const CcxRegion *g = &m->regions[r];
    fprintf(f, "*MATERIAL, NAME=M_%s\n", g->name);
    if (!g->stiff) {
      /* Yeoh: W = sum Ci0 (I1b - 3)^i + sum (1/Di)(J - 1)^(2i); D1 = 2/kappa. ccx 2.20
       * (hyperelastics.f) silently replaces every D that is 0 by a default (0.1/mu0)^i, which
       * for D2, D3 adds a large (J - 1)^4 + (J - 1)^6 stiffness; so D2 = D3 = 1e30 (a term
       * 1e-30 (J - 1)^4, nil) stand for "none". */
      fprintf(f, "*HYPERELASTIC, YEOH\n%.12g, %.12g, %.12g, %.12g, 1e30, 1e30\n", m->c10,
              m->c20, m->c30, 2.0 / m->kappa);
    } else {
      double mu = g->E / (2.0 * (1.0 + g->nu)), kappa = g->E / (3.0 * (1.0 - 2.0 * g->nu));
      fprintf(f, "*HYPERELASTIC, NEO HOOKE\n%.12g, %.12g\n", 0.5 * mu, 2.0 / kappa);
    }
    fprintf(f, "*SOLID SECTION, ELSET=E_%s, MATERIAL=M_%s\n", g->name, g->name);
  }
  fprintf(f, "*AMPLITUDE, NAME=RAMP\n0., 0., 1., 1.\n");
  if (m->ntime_points) {
    fprintf(f, "*TIME POINTS, NAME=TP\n");
    for (int i = 0; i < m->ntime_points; ++i)
      fprintf(f, "%.9g%s", m->time_points[i], (i % 8 == 7 || i == m->ntime_points - 1) ? "\n" : ", ");
  }
  fprintf(f, "*STEP, NLGEOM, INC=10000\n*STATIC\n%.9g, 1., %.9g, %.9g\n", m->inc0, m->incmin,
          m->incmax);
  fprintf(f, "*BOUNDARY\n");
  for (int b = 0; b < m->nbcs; ++b)
    fprintf(f, "N_%s, %d, %d\n", m->bcs[b].name, m->bcs[b].first, m->bcs[b].last);
  fprintf(f, "*DLOAD, AMPLITUDE=RAMP\n");
  for (int i = 0; i < m->nload; ++i)
    fprintf(f, "%d, P%d, %.12g\n", m->load_elem[i] + 1, m->load_face[i], m->pressure);
  fprintf(f, "*NODE PRINT, NSET=%s, %s\nU\n", m->print_all ? "NALL" : "N_TIP",
          m->ntime_points ? "TIME POINTS=TP" : "FREQUENCYF=1");
  fprintf(f, "*END STEP\n");
  return ferror(f) ? SA_ERROR(SA_ERR_IO, "write error") : 0;
}

static int write_tip(const CcxModel *m, FILE *f)
{
  fprintf(f, "# softact ccx tip side file: nodes (number x y z), then triangles (3 numbers)\n");
  fprintf(f, "nodes %d\n", m->ntip_nodes);
  for (int i = 0; i < m->ntip_nodes; ++i) {
    const double *x = m->xyz + 3 * (size_t)m->tip_nodes[i];
    fprintf(f, "%d %.15g %.15g %.15g\n", m->tip_nodes[i] + 1, x[0], x[1], x[2]);
  }
  fprintf(f, "triangles %d\n", m->ntip_tri);
  for (int i = 0; i < m->ntip_tri; ++i)
    fprintf(f, "%d %d %d\n", m->tip_tri[3 * i] + 1, m->tip_tri[3 * i + 1] + 1,
            m->tip_tri[3 * i + 2] + 1);
  return ferror(f) ? SA_ERROR(SA_ERR_IO, "write error") : 0;
}

int ccx_model_write(const CcxModel *m, const char *base)
{
  char path[1024];
  snprintf(path, sizeof path, "%s.inp", base);
  FILE *f = fopen(path, "w");
  SA_REQUIRE(f, SA_ERR_IO, "cannot write %s", path);
  int rc = write_inp(m, f);
  if (fclose(f) && !rc) rc = SA_ERROR(SA_ERR_IO, "cannot close %s", path);
  SA_CHECK(rc);
  snprintf(path, sizeof path, "%s.tip", base);
  f = fopen(path, "w");
  SA_REQUIRE(f, SA_ERR_IO, "cannot write %s", path);
  rc = write_tip(m, f);
  if (fclose(f) && !rc) rc = SA_ERROR(SA_ERR_IO, "cannot close %s", path);
  SA_CHECK(rc);
  return 0;
}
