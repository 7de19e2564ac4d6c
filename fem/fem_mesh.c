/* fem_mesh.c - tetrahedral meshes through the Gmsh C API (gmshc.h).
 *
 * Generation: a prelude .geo in a temporary folder defines the parameters (`name = value;`) and
 * includes the .geo, so its `If(!Exists(name))` defaults see them; meshed in 3-D and, for order 2,
 * elevated with curved high-order nodes (Mesh.SecondOrderLinear = 0: mid-nodes on the CAD
 * geometry). Reading: gmshOpen of a .msh. Gmsh is not thread-safe and keeps global state, so
 * every use is one initialize/finalize session under a process-wide mutex.
 *
 * Extraction: elements of every 3-D physical group (one group per volume entity), node tags
 * renumbered compactly over the nodes the volume elements use, tet10 converted from Gmsh's order
 * to VTK's. Gmsh's reference tet10 (gmshModelMeshGetElementProperties(11), checked in
 * tests/fem/mesh) has mid-nodes 4:(0,1) 5:(1,2) 6:(0,2) 7:(0,3) 8:(2,3) 9:(1,3); VTK's are
 * 01, 12, 02, 03, 13, 23, so Gmsh 8 and 9 swap. Elements with negative corner volume are
 * relabelled (corners 1 <-> 2 and their edges) so every element is positively oriented.
 *
 * Surfaces: each triangle of a 2-D physical group is matched (sort-merge on sorted corner
 * triples) with a face of a volume element; the face is stored with that element's nodes in the
 * order whose right-hand normal points away from the element's opposite vertex, i.e. out of the
 * solid. A triangle shared by two elements (an internal surface) takes the lower element index. */
#include "fem_mesh.h"

#include <ctype.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gmshc.h>

#include "sa_error.h"
#include "sa_log.h"
#include "fem_kernel_quad.h"

#define TAG "mesh"

/* ---------------------------------------------------------------------------------------------
 * Reference tetrahedron (VTK order), shape functions and check points. */

/* Outward faces of a positively oriented tet (opposite vertices 3, 2, 0, 1): each row lists
 * corners so that (x1 - x0) x (x2 - x0) points away from the remaining vertex. */
static const int tet_face[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
/* VTK mid-node of edge (a, b). */
static const int tet_mid[4][4] = {{-1, 4, 6, 7}, {4, -1, 5, 8}, {6, 5, -1, 9}, {7, 8, 9, -1}};
/* Gmsh tet10 node k goes to VTK position gmsh_to_vtk[k]. */
static const int gmsh_to_vtk10[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

/* det of the Jacobian d x / d(r, s, t) of element X (3 * nen) at barycentric L, with the
 * kernels' shape functions (fem_kernel_quad.h: one copy of the reference element). */
static double tet_detJ(int nen, const double *X, const double L[4])
{
  double dN[10][3], J[3][3] = {{0}};
  fem_kq_tet_shape(nen, L, NULL, dN);
  for (int a = 0; a < nen; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) J[i][j] += X[3 * a + i] * dN[a][j];
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

/* Check points for det J of a tet10: its corners and every rule the kernels integrate with
 * (4-point for straight, 8-point for curved elements, 14-point for the lumped mass); tet4: the
 * centroid (det J is constant). */
static const FemKqRule *const check_rules[] = {&fem_kq_tet4, &fem_kq_tet8, &fem_kq_tet14};

static void elem_coords(const FemMesh *m, int e, double *X);

/* Smallest det J / 6 over the check points of element e [out] at point *where. */
static double elem_min_detJ(const FemMesh *m, int e, int *where)
{
  double X[30];
  elem_coords(m, e, X);
  if (m->nen == 4) {
    const double L[4] = {0.25, 0.25, 0.25, 0.25};
    *where = 0;
    return tet_detJ(4, X, L) / 6.0;
  }
  double dmin = INFINITY;
  for (int a = 0; a < 4; ++a) {
    double L[4] = {0, 0, 0, 0};
    L[a] = 1.0;
    double d = tet_detJ(10, X, L) / 6.0;
    if (d < dmin) dmin = d, *where = a;
  }
  for (int r = 0, p = 4; r < 3; ++r)
    for (int q = 0; q < check_rules[r]->n; ++q, ++p) {
      double d = tet_detJ(10, X, check_rules[r]->L[q]) / 6.0;
      if (d < dmin) dmin = d, *where = p;
    }
  return dmin;
}

static void elem_coords(const FemMesh *m, int e, double *X)
{
  for (int a = 0; a < m->nen; ++a)
    for (int i = 0; i < 3; ++i) X[3 * a + i] = m->xyz[3 * (size_t)m->conn[(size_t)m->nen * e + a] + i];
}

static double elem_volume(const FemMesh *m, int e)
{
  double X[30];
  elem_coords(m, e, X);
  if (m->nen == 4) {
    const double L[4] = {0.25, 0.25, 0.25, 0.25};
    return tet_detJ(4, X, L) / 6.0;
  }
  /* the 14-point rule (degree 5) is exact for the cubic det J of a curved tet10 */
  double v = 0.0;
  for (int q = 0; q < fem_kq_tet14.n; ++q)
    v += fem_kq_tet14.w[q] * tet_detJ(10, X, fem_kq_tet14.L[q]);
  return v;
}

/* ---------------------------------------------------------------------------------------------
 * Gmsh sessions. */

static pthread_mutex_t gmsh_mutex = PTHREAD_MUTEX_INITIALIZER;

/* Forward Gmsh's log (warnings to WARN, the rest to DEBUG) and copy its error lines into err. */
static void gmsh_drain_log(char *err, size_t nerr)
{
  char **log = NULL;
  size_t n = 0;
  int ierr = 0;
  gmshLoggerGet(&log, &n, &ierr);
  if (ierr) return;
  size_t used = strlen(err);
  for (size_t i = 0; i < n; ++i) {
    const char *s = log[i];
    if (!strncmp(s, "Error", 5)) {
      const char *msg = strchr(s, ':');
      msg = msg ? msg + 1 : s;
      while (*msg == ' ') ++msg;
      if (used + 4 < nerr) {
        int w = snprintf(err + used, nerr - used, "%s%s", used ? "; " : "", msg);
        used = (w > 0 && (size_t)w < nerr - used) ? used + (size_t)w : nerr - 1;
      }
    } else if (!strncmp(s, "Warning", 7)) {
      sa_log(SA_LOG_WARN, TAG, "gmsh: %s", s);
    } else {
      sa_log(SA_LOG_DEBUG, TAG, "gmsh: %s", s);
    }
    gmshFree(log[i]);
  }
  gmshFree(log);
  /* The logger keeps its messages: restart it so the next drain sees only new ones. */
  gmshLoggerStop(&ierr);
  gmshLoggerStart(&ierr);
}

/* Start a session. Locks the Gmsh mutex. */
static int gmsh_begin(const char *src)
{
  char *argv[] = {"softact", NULL};
  int ierr = 0;
  pthread_mutex_lock(&gmsh_mutex);
  gmshInitialize(1, argv, 0, &ierr);
  if (ierr) {
    pthread_mutex_unlock(&gmsh_mutex);
    return SA_ERROR(SA_ERR_LIBRARY, "%s: Gmsh initialisation failed", src);
  }
  /* no terminal output: the logger forwards messages to sa_log (warnings WARN, rest DEBUG) */
  gmshOptionSetNumber("General.Terminal", 0, &ierr);
  gmshLoggerStart(&ierr);
  return 0;
}

/* Write dir/prelude.geo: `name = value;` for every parameter (and h), then Include of the
 * absolute geo path. (Gmsh's `-setnumber` would do the same without a file, but Gmsh keeps
 * command-line numbers for the whole process, so they would leak into later meshes.) */
static int write_prelude(const char *geo, int nparams, const FemGeoParam *params, double h,
                         char *dir, size_t ndir, char *prelude, size_t nprelude)
{
  char abs[4096];
  SA_REQUIRE(realpath(geo, abs), SA_ERR_INPUT, "mesh source '%s' not found", geo);
  SA_REQUIRE(!strchr(abs, '"'), SA_ERR_INPUT, "mesh source path '%s' contains a quote", abs);
  for (int i = 0; i < nparams; ++i) {
    const char *name = params[i].name;
    int ok = name && (isalpha((unsigned char)name[0]) || name[0] == '_');
    for (const char *c = name; ok && *c; ++c) ok = isalnum((unsigned char)*c) || *c == '_';
    SA_REQUIRE(ok && isfinite(params[i].value), SA_ERR_INPUT,
               "%s: bad geometry parameter '%s' = %g", geo, name ? name : "(null)",
               params[i].value);
  }
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, ndir, "%s/softact-geo-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  SA_REQUIRE(mkdtemp(dir), SA_ERR_IO, "cannot create a temporary folder %s", dir);
  snprintf(prelude, nprelude, "%s/prelude.geo", dir);
  FILE *f = fopen(prelude, "w");
  if (!f) {
    rmdir(dir);
    return SA_ERROR(SA_ERR_IO, "cannot write %s", prelude);
  }
  for (int i = 0; i < nparams; ++i) fprintf(f, "%s = %.17g;\n", params[i].name, params[i].value);
  if (h > 0.0) fprintf(f, "h = %.17g;\n", h);
  fprintf(f, "Include \"%s\";\n", abs);
  if (fclose(f)) {
    remove(prelude);
    rmdir(dir);
    return SA_ERROR(SA_ERR_IO, "cannot write %s", prelude);
  }
  return 0;
}

static void gmsh_end(void)
{
  int ierr = 0;
  char err[8] = "";
  gmsh_drain_log(err, sizeof err);
  gmshLoggerStop(&ierr);
  gmshFinalize(&ierr);
  pthread_mutex_unlock(&gmsh_mutex);
}

/* After a Gmsh call: fail with SA_ERR_INPUT naming src and what failed if ierr is set or Gmsh
 * logged an error. */
static int gmsh_status(int ierr, const char *src, const char *what)
{
  char err[1024] = "";
  gmsh_drain_log(err, sizeof err);
  if (ierr || err[0])
    return SA_ERROR(SA_ERR_INPUT, "%s: %s failed: %s", src, what, err[0] ? err : "Gmsh error");
  return 0;
}

/* ---------------------------------------------------------------------------------------------
 * Extraction of the Gmsh model into a FemMesh. */

typedef struct {
  int k[3];  /* sorted corner nodes */
  int owner; /* surface triangle: index into the flat triangle list; tet face: 4 * elem + face */
} FaceKey;

static int facekey_cmp(const void *pa, const void *pb)
{
  const FaceKey *a = pa, *b = pb;
  for (int i = 0; i < 3; ++i)
    if (a->k[i] != b->k[i]) return a->k[i] < b->k[i] ? -1 : 1;
  return a->owner < b->owner ? -1 : a->owner > b->owner;
}

static void sort3(int *k)
{
  int t;
  if (k[0] > k[1]) t = k[0], k[0] = k[1], k[1] = t;
  if (k[1] > k[2]) t = k[1], k[1] = k[2], k[2] = t;
  if (k[0] > k[1]) t = k[0], k[0] = k[1], k[1] = t;
}

static int int_cmp(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Growable array of size_t. */
typedef struct {
  size_t n, cap;
  size_t *v;
} SizeVec;

static int sizevec_append(SizeVec *s, const size_t *v, size_t n)
{
  if (s->n + n > s->cap) {
    size_t cap = s->cap ? s->cap : 1024;
    while (cap < s->n + n) cap *= 2;
    size_t *p = realloc(s->v, cap * sizeof *p);
    if (!p) return SA_ERROR(SA_ERR_MEMORY, "cannot grow an array to %zu entries", cap);
    s->v = p;
    s->cap = cap;
  }
  memcpy(s->v + s->n, v, n * sizeof *v);
  s->n += n;
  return 0;
}

static void group_name(int dim, int tag, char out[64])
{
  char *name = NULL;
  int ierr = 0;
  gmshModelGetPhysicalName(dim, tag, &name, &ierr);
  if (!ierr && name && name[0])
    snprintf(out, 64, "%s", name);
  else
    snprintf(out, 64, "%s_%d", dim == 3 ? "volume" : "surface", tag);
  if (name) gmshFree(name);
}

/* Everything the extraction allocates, freed in one place. */
typedef struct {
  size_t *ntag;       /* Gmsh node tags */
  double *ncoord;     /* their coordinates */
  size_t nn;
  long *tag_to_pos;   /* node tag -> position in ntag (-1 none) */
  size_t maxtag;
  int *dimtags;
  size_t ndimtags;
  SizeVec econn;      /* element node tags (Gmsh order) */
  SizeVec eregion;    /* region per element */
  SizeVec tri;        /* surface triangles: 3 corner tags each */
  SizeVec trisurf;    /* surface index per triangle */
  int *seen_vol;
  size_t nseen;
  FaceKey *fk;
  int *newidx;
} Extract;

static void extract_free(Extract *x)
{
  if (x->ntag) gmshFree(x->ntag);
  if (x->ncoord) gmshFree(x->ncoord);
  if (x->dimtags) gmshFree(x->dimtags);
  free(x->tag_to_pos);
  free(x->econn.v);
  free(x->eregion.v);
  free(x->tri.v);
  free(x->trisurf.v);
  free(x->seen_vol);
  free(x->fk);
  free(x->newidx);
}

static int extract_volumes(Extract *x, const char *src, FemMesh *m)
{
  int ierr = 0, gtype = 0;
  gmshModelGetPhysicalGroups(&x->dimtags, &x->ndimtags, 3, &ierr);
  SA_CHECK(gmsh_status(ierr, src, "listing physical volumes"));
  size_t ng = x->ndimtags / 2;
  SA_REQUIRE(ng > 0, SA_ERR_INPUT, "%s defines no physical volume (3-D physical group)", src);
  SA_CALLOC(m->region_names, ng);
  SA_CALLOC(x->seen_vol, 1);
  m->nregions = (int)ng;
  for (size_t g = 0; g < ng; ++g) {
    int tag = x->dimtags[2 * g + 1];
    group_name(3, tag, m->region_names[g]);
    int *ents = NULL;
    size_t nents = 0;
    gmshModelGetEntitiesForPhysicalGroup(3, tag, &ents, &nents, &ierr);
    SA_CHECK(gmsh_status(ierr, src, "reading a physical volume"));
    int rc = 0;
    for (size_t i = 0; i < nents && !rc; ++i) {
      for (size_t j = 0; j < x->nseen; ++j)
        if (x->seen_vol[j] == ents[i]) {
          rc = SA_ERROR(SA_ERR_INPUT, "%s: volume %d is in two physical volumes (e.g. '%s')", src,
                        ents[i], m->region_names[g]);
          break;
        }
      if (rc) break;
      int *p = realloc(x->seen_vol, (x->nseen + 1) * sizeof *p);
      if (!p) {
        rc = SA_ERROR(SA_ERR_MEMORY, "out of memory");
        break;
      }
      x->seen_vol = p;
      x->seen_vol[x->nseen++] = ents[i];

      int *types = NULL;
      size_t ntypes = 0, **etags = NULL, *etags_n = NULL, etags_nn = 0, **ntags = NULL,
             *ntags_n = NULL, ntags_nn = 0;
      gmshModelMeshGetElements(&types, &ntypes, &etags, &etags_n, &etags_nn, &ntags, &ntags_n,
                               &ntags_nn, 3, ents[i], &ierr);
      rc = gmsh_status(ierr, src, "reading elements");
      for (size_t t = 0; t < ntypes && !rc; ++t) {
        if (types[t] != 4 && types[t] != 11)
          rc = SA_ERROR(SA_ERR_INPUT,
                        "%s: region '%s' has elements of Gmsh type %d; only tetrahedra (4, 11) "
                        "are supported",
                        src, m->region_names[g], types[t]);
        else if (gtype && types[t] != gtype)
          rc = SA_ERROR(SA_ERR_INPUT, "%s mixes tet4 and tet10 elements", src);
        else {
          gtype = types[t];
          size_t nen = gtype == 4 ? 4 : 10, ne = etags_n[t];
          rc = sizevec_append(&x->econn, ntags[t], ne * nen);
          for (size_t e = 0; e < ne && !rc; ++e) rc = sizevec_append(&x->eregion, &g, 1);
        }
      }
      for (size_t t = 0; t < etags_nn; ++t) gmshFree(etags[t]);
      for (size_t t = 0; t < ntags_nn; ++t) gmshFree(ntags[t]);
      gmshFree(types);
      gmshFree(etags);
      gmshFree(etags_n);
      gmshFree(ntags);
      gmshFree(ntags_n);
    }
    gmshFree(ents);
    if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_REQUIRE(gtype != 0, SA_ERR_INPUT, "%s: the physical volumes hold no mesh elements", src);
  m->etype = gtype == 4 ? FEM_TET4 : FEM_TET10;
  m->nen = gtype == 4 ? 4 : 10;
  SA_REQUIRE(x->eregion.n < (size_t)INT32_MAX / 10, SA_ERR_INPUT, "%s: too many elements", src);
  m->nelem = (int)x->eregion.n;
  return 0;
}

static int extract_nodes(Extract *x, const char *src, FemMesh *m)
{
  int ierr = 0;
  double *pc = NULL;
  size_t nc = 0, npc = 0;
  gmshModelMeshGetNodes(&x->ntag, &x->nn, &x->ncoord, &nc, &pc, &npc, -1, -1, 0, 0, &ierr);
  if (pc) gmshFree(pc);
  SA_CHECK(gmsh_status(ierr, src, "reading nodes"));
  x->maxtag = 0;
  for (size_t i = 0; i < x->nn; ++i)
    if (x->ntag[i] > x->maxtag) x->maxtag = x->ntag[i];
  SA_CALLOC(x->tag_to_pos, x->maxtag + 1);
  for (size_t i = 0; i <= x->maxtag; ++i) x->tag_to_pos[i] = -1;
  for (size_t i = 0; i < x->nn; ++i) x->tag_to_pos[x->ntag[i]] = (long)i;

  /* Compact numbering over the nodes of volume elements, in Gmsh's node order. */
  SA_CALLOC(x->newidx, x->nn);
  for (size_t i = 0; i < x->nn; ++i) x->newidx[i] = -1;
  for (size_t k = 0; k < x->econn.n; ++k) {
    size_t t = x->econn.v[k];
    SA_REQUIRE(t <= x->maxtag && x->tag_to_pos[t] >= 0, SA_ERR_INPUT,
               "%s: element node %zu has no coordinates", src, t);
    x->newidx[x->tag_to_pos[t]] = 0;
  }
  int nnodes = 0;
  for (size_t i = 0; i < x->nn; ++i)
    if (x->newidx[i] == 0) x->newidx[i] = nnodes++;
  m->nnodes = nnodes;
  SA_CALLOC(m->xyz, 3 * (size_t)nnodes);
  for (size_t i = 0; i < x->nn; ++i)
    if (x->newidx[i] >= 0) memcpy(m->xyz + 3 * (size_t)x->newidx[i], x->ncoord + 3 * i, 3 * sizeof(double));

  /* Connectivity in VTK order, positively oriented. */
  size_t nen = (size_t)m->nen;
  SA_CALLOC(m->conn, nen * (size_t)m->nelem);
  SA_CALLOC(m->region, m->nelem);
  int nflip = 0;
  for (int e = 0; e < m->nelem; ++e) {
    int *c = m->conn + nen * e;
    for (size_t a = 0; a < nen; ++a) {
      int v = x->newidx[x->tag_to_pos[x->econn.v[nen * e + a]]];
      c[nen == 10 ? (size_t)gmsh_to_vtk10[a] : a] = v;
    }
    m->region[e] = (int)x->eregion.v[e];
    double X[12];
    for (int a = 0; a < 4; ++a) memcpy(X + 3 * a, m->xyz + 3 * (size_t)c[a], 3 * sizeof(double));
    const double L[4] = {0.25, 0.25, 0.25, 0.25};
    if (tet_detJ(4, X, L) < 0.0) {
      int t;
      t = c[1], c[1] = c[2], c[2] = t;
      if (nen == 10) {
        t = c[4], c[4] = c[6], c[6] = t;
        t = c[8], c[8] = c[9], c[9] = t;
      }
      ++nflip;
    }
  }
  if (nflip) sa_log(SA_LOG_DEBUG, TAG, "%s: relabelled %d negatively oriented elements", src, nflip);
  return 0;
}

static int extract_surfaces(Extract *x, const char *src, FemMesh *m)
{
  int ierr = 0;
  int *dt = NULL;
  size_t ndt = 0;
  gmshModelGetPhysicalGroups(&dt, &ndt, 2, &ierr);
  SA_CHECK(gmsh_status(ierr, src, "listing physical surfaces"));
  size_t ns = ndt / 2;
  m->surfaces = calloc(ns ? ns : 1, sizeof *m->surfaces);
  if (!m->surfaces) {
    gmshFree(dt);
    return SA_ERROR(SA_ERR_MEMORY, "out of memory");
  }
  m->nsurfaces = (int)ns;
  int rc = 0;
  for (size_t g = 0; g < ns && !rc; ++g) {
    int tag = dt[2 * g + 1];
    FemSurface *s = &m->surfaces[g];
    group_name(2, tag, s->name);
    s->nfn = m->nen == 10 ? 6 : 3;
    int *ents = NULL;
    size_t nents = 0;
    gmshModelGetEntitiesForPhysicalGroup(2, tag, &ents, &nents, &ierr);
    rc = gmsh_status(ierr, src, "reading a physical surface");
    for (size_t i = 0; i < nents && !rc; ++i) {
      int *types = NULL;
      size_t ntypes = 0, **etags = NULL, *etags_n = NULL, etags_nn = 0, **ntags = NULL,
             *ntags_n = NULL, ntags_nn = 0;
      gmshModelMeshGetElements(&types, &ntypes, &etags, &etags_n, &etags_nn, &ntags, &ntags_n,
                               &ntags_nn, 2, ents[i], &ierr);
      rc = gmsh_status(ierr, src, "reading surface elements");
      for (size_t t = 0; t < ntypes && !rc; ++t) {
        if (types[t] != 2 && types[t] != 9) {
          rc = SA_ERROR(SA_ERR_INPUT, "%s: surface '%s' has elements of Gmsh type %d (not triangles)",
                        src, s->name, types[t]);
          break;
        }
        size_t npe = types[t] == 2 ? 3 : 6;
        for (size_t e = 0; e < etags_n[t] && !rc; ++e) {
          rc = sizevec_append(&x->tri, ntags[t] + npe * e, 3);
          if (!rc) rc = sizevec_append(&x->trisurf, &g, 1);
          ++s->nfaces;
        }
      }
      for (size_t t = 0; t < etags_nn; ++t) gmshFree(etags[t]);
      for (size_t t = 0; t < ntags_nn; ++t) gmshFree(ntags[t]);
      gmshFree(types);
      gmshFree(etags);
      gmshFree(etags_n);
      gmshFree(ntags);
      gmshFree(ntags_n);
    }
    if (ents) gmshFree(ents);
  }
  gmshFree(dt);
  SA_CHECK(rc);
  size_t ntri = x->trisurf.n;
  if (!ntri) return 0;

  /* Keys: surface triangles first (owner = -1 - index), then all element faces; after sorting
   * by (corners, owner) each triangle is followed by its faces in element order. */
  size_t nk = ntri + 4 * (size_t)m->nelem;
  SA_CALLOC(x->fk, nk);
  for (size_t i = 0; i < ntri; ++i) {
    for (int j = 0; j < 3; ++j) {
      size_t t = x->tri.v[3 * i + j];
      long p = t <= x->maxtag ? x->tag_to_pos[t] : -1;
      int v = p >= 0 ? x->newidx[p] : -1;
      const FemSurface *s = &m->surfaces[x->trisurf.v[i]];
      SA_REQUIRE(v >= 0, SA_ERR_INPUT,
                 "%s: surface '%s' has a triangle off the volume mesh (node %zu)", src, s->name, t);
      x->fk[i].k[j] = v;
    }
    sort3(x->fk[i].k);
    x->fk[i].owner = -1 - (int)i;
  }
  for (int e = 0; e < m->nelem; ++e)
    for (int f = 0; f < 4; ++f) {
      FaceKey *k = &x->fk[ntri + 4 * (size_t)e + f];
      for (int j = 0; j < 3; ++j) k->k[j] = m->conn[(size_t)m->nen * e + tet_face[f][j]];
      sort3(k->k);
      k->owner = 4 * e + f;
    }
  qsort(x->fk, nk, sizeof *x->fk, facekey_cmp);

  for (int g = 0; g < m->nsurfaces; ++g) {
    FemSurface *s = &m->surfaces[g];
    SA_CALLOC(s->faces, (size_t)s->nfn * s->nfaces);
    SA_CALLOC(s->face_elem, s->nfaces);
    s->nfaces = 0; /* refilled below */
  }
  /* Triangles of one key run come first (negative owners); the first element face after the
   * run is the owner. */
  size_t i = 0;
  while (i < nk) {
    size_t j = i;
    while (j < nk && !memcmp(x->fk[j].k, x->fk[i].k, sizeof x->fk[i].k)) ++j;
    size_t firstface = i;
    while (firstface < j && x->fk[firstface].owner < 0) ++firstface;
    for (size_t t = i; t < firstface; ++t) {
      size_t tri = (size_t)(-1 - x->fk[t].owner);
      FemSurface *s = &m->surfaces[x->trisurf.v[tri]];
      SA_REQUIRE(firstface < j, SA_ERR_INPUT,
                 "%s: a triangle of surface '%s' is not a face of any volume element (nodes %d %d "
                 "%d); surfaces must bound the physical volumes",
                 src, s->name, x->fk[t].k[0], x->fk[t].k[1], x->fk[t].k[2]);
      int e = x->fk[firstface].owner / 4, f = x->fk[firstface].owner % 4;
      const int *c = m->conn + (size_t)m->nen * e;
      int *out = s->faces + (size_t)s->nfn * s->nfaces;
      const int *lf = tet_face[f];
      for (int a = 0; a < 3; ++a) out[a] = c[lf[a]];
      if (s->nfn == 6)
        for (int a = 0; a < 3; ++a) out[3 + a] = c[tet_mid[lf[a]][lf[(a + 1) % 3]]];
      s->face_elem[s->nfaces++] = e;
    }
    i = j;
  }

  /* Node sets. */
  for (int g = 0; g < m->nsurfaces; ++g) {
    FemSurface *s = &m->surfaces[g];
    size_t n = (size_t)s->nfn * s->nfaces;
    SA_CALLOC(s->nodes, n);
    memcpy(s->nodes, s->faces, n * sizeof(int));
    qsort(s->nodes, n, sizeof(int), int_cmp);
    size_t u = 0;
    for (size_t k = 0; k < n; ++k)
      if (!u || s->nodes[k] != s->nodes[u - 1]) s->nodes[u++] = s->nodes[k];
    s->nnodes = (int)u;
  }
  return 0;
}

/* Build a FemMesh from the current Gmsh model. */
static int extract_mesh(const char *src, FemMesh **out)
{
  FemMesh *m = calloc(1, sizeof *m);
  SA_REQUIRE(m, SA_ERR_MEMORY, "out of memory");
  snprintf(m->source, sizeof m->source, "%s", src);
  Extract x = {0};
  int rc = extract_volumes(&x, src, m);
  if (!rc) rc = extract_nodes(&x, src, m);
  if (!rc) rc = extract_surfaces(&x, src, m);
  extract_free(&x);
  if (rc) {
    fem_mesh_destroy(&m);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = m;
  return 0;
}

/* Curved tet10 elements with det J <= 0 somewhere (a thin part meshed coarsely: a mid-node on a
 * curved face moves off the chord by the sagitta c^2 / (8 R), which can exceed the thickness)
 * get straight edges: their mid-nodes go to the edge midpoints, which makes them as valid as
 * their corner tets. Neighbours share those nodes, so repeat until no element is left. */
static int straighten_inverted(FemMesh *m)
{
  int total = 0;
  for (int pass = 0; pass < 10; ++pass) {
    int n = 0;
    for (int e = 0; e < m->nelem; ++e) {
      int p;
      if (elem_min_detJ(m, e, &p) > 0.0) continue;
      const int *c = m->conn + 10 * (size_t)e;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          for (int i = 0; i < 3; ++i)
            m->xyz[3 * (size_t)c[tet_mid[a][b]] + i] =
                0.5 * (m->xyz[3 * (size_t)c[a] + i] + m->xyz[3 * (size_t)c[b] + i]);
      ++n;
    }
    total += n;
    if (!n) break;
  }
  return total;
}

static int file_readable(const char *path)
{
  FILE *f = path ? fopen(path, "r") : NULL;
  if (!f) return 0;
  fclose(f);
  return 1;
}

static void log_mesh(const FemMesh *m, const char *what, double t0)
{
  double dt = sa_time_now() - t0;
  sa_timing_add("mesh", dt);
  int nf = 0;
  for (int s = 0; s < m->nsurfaces; ++s) nf += m->surfaces[s].nfaces;
  double qmin, qmean;
  fem_mesh_quality(m, -1, &qmin, &qmean);
  sa_log(SA_LOG_INFO, TAG,
         "%s %s: %d %s elements, %d nodes, %d regions, %d surfaces (%d faces), radius ratio "
         "min %.3f mean %.3f, %.2f s",
         what, m->source, m->nelem, m->etype == FEM_TET10 ? "tet10" : "tet4", m->nnodes, m->nregions,
         m->nsurfaces, nf, qmin, qmean, dt);
}

/* ---------------------------------------------------------------------------------------------
 * Public API. */

int fem_mesh_generate(const char *geo_path, int nparams, const FemGeoParam *params, double h,
                      int order, FemMesh **out)
{
  SA_REQUIRE(out, SA_ERR_INPUT, "fem_mesh_generate: no output handle");
  *out = NULL;
  SA_REQUIRE(geo_path && geo_path[0], SA_ERR_INPUT, "no mesh source (.geo) given");
  SA_REQUIRE(file_readable(geo_path), SA_ERR_INPUT, "mesh source '%s' not found or not readable",
             geo_path);
  SA_REQUIRE(order == 1 || order == 2, SA_ERR_INPUT, "%s: element order %d (must be 1 or 2)",
             geo_path, order);
  SA_REQUIRE(nparams == 0 || params, SA_ERR_INPUT, "%s: parameters missing", geo_path);
  SA_REQUIRE(isfinite(h), SA_ERR_INPUT, "%s: bad mesh size h = %g", geo_path, h);
  double t0 = sa_time_now();
  char dir[4096], prelude[4200];
  SA_CHECK(write_prelude(geo_path, nparams, params, h, dir, sizeof dir, prelude, sizeof prelude));
  int ierr = 0, rc = gmsh_begin(geo_path);
  if (rc) {
    remove(prelude);
    rmdir(dir);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  gmshOpen(prelude, &ierr);
  remove(prelude);
  rmdir(dir);
  rc = gmsh_status(ierr, geo_path, "reading the geometry");
  if (!rc) {
    gmshModelMeshGenerate(3, &ierr);
    rc = gmsh_status(ierr, geo_path, "3-D meshing");
  }
  if (!rc && order == 2) {
    /* Mid-nodes on the curved geometry; no high-order optimisation (fem_mesh_check verifies
     * the Jacobians of the result). */
    gmshOptionSetNumber("Mesh.SecondOrderLinear", 0, &ierr);
    gmshOptionSetNumber("Mesh.HighOrderOptimize", 0, &ierr);
    gmshModelMeshSetOrder(2, &ierr);
    rc = gmsh_status(ierr, geo_path, "second-order elevation");
  }
  double t1 = sa_time_now();
  if (!rc) rc = extract_mesh(geo_path, out);
  gmsh_end();
  if (!rc) sa_log(SA_LOG_DEBUG, TAG, "%s: Gmsh %.2f s, extraction %.2f s", geo_path, t1 - t0,
                  sa_time_now() - t1);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  if (order == 2) {
    int n = straighten_inverted(*out);
    if (n)
      sa_log(SA_LOG_WARN, TAG,
             "%s: %d curved tet10 elements had det J <= 0 and were given straight edges (h too "
             "coarse for a thin curved part?)",
             geo_path, n);
  }
  log_mesh(*out, "generated", t0);
  return 0;
}

int fem_mesh_read(const char *msh_path, FemMesh **out)
{
  SA_REQUIRE(out, SA_ERR_INPUT, "fem_mesh_read: no output handle");
  *out = NULL;
  SA_REQUIRE(msh_path && msh_path[0], SA_ERR_INPUT, "no mesh file given");
  SA_REQUIRE(file_readable(msh_path), SA_ERR_INPUT, "mesh file '%s' not found or not readable",
             msh_path);
  double t0 = sa_time_now();
  SA_CHECK(gmsh_begin(msh_path));
  int ierr = 0;
  gmshOpen(msh_path, &ierr);
  int rc = gmsh_status(ierr, msh_path, "reading the mesh");
  if (!rc) rc = extract_mesh(msh_path, out);
  gmsh_end();
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  log_mesh(*out, "read", t0);
  return 0;
}

int fem_mesh_check(const FemMesh *m, double rel_tol)
{
  SA_REQUIRE(m && m->nelem > 0 && (m->nen == 4 || m->nen == 10), SA_ERR_INPUT,
             "fem_mesh_check: empty or invalid mesh");
  for (size_t k = 0; k < (size_t)m->nen * m->nelem; ++k)
    SA_REQUIRE(m->conn[k] >= 0 && m->conn[k] < m->nnodes, SA_ERR_INPUT,
               "mesh %s: element %zu refers to node %d of %d", m->source, k / (size_t)m->nen,
               m->conn[k], m->nnodes);
  /* size scale: mean |volume| (an inverted element must not spoil the scale) */
  double vmean = 0.0;
  for (int e = 0; e < m->nelem; ++e) vmean += fabs(elem_volume(m, e));
  vmean /= m->nelem;
  SA_REQUIRE(vmean > 0.0, SA_ERR_INPUT, "mesh %s: all elements have zero volume", m->source);
  /* det J / 6 is the volume density of the map; compare it with rel_tol times the mean volume. */
  for (int e = 0; e < m->nelem; ++e) {
    int p = 0;
    double d = elem_min_detJ(m, e, &p);
    if (d > rel_tol * vmean) continue;
    const char *rname =
        (m->region && m->region_names && m->region[e] >= 0 && m->region[e] < m->nregions)
            ? m->region_names[m->region[e]]
            : "?";
    double X[30], c[3] = {0, 0, 0};
    elem_coords(m, e, X);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) c[i] += 0.25 * X[3 * a + i];
    return SA_ERROR(SA_ERR_INPUT,
                    "mesh %s: element %d (region '%s', near (%g, %g, %g)) is %s: det J / 6 = %g "
                    "at %s %d, mean element volume %g",
                    m->source, e, rname, c[0], c[1], c[2], d <= 0.0 ? "inverted" : "degenerate", d,
                    m->nen == 4 ? "centroid" : (p < 4 ? "corner" : "check point"),
                    m->nen == 4 ? 0 : (p < 4 ? p : p - 4), vmean);
  }
  return 0;
}

int fem_mesh_find_region(const FemMesh *m, const char *name)
{
  if (!m || !name) return -1;
  for (int r = 0; r < m->nregions; ++r)
    if (!strcmp(m->region_names[r], name)) return r;
  return -1;
}

const FemSurface *fem_mesh_find_surface(const FemMesh *m, const char *name)
{
  if (!m || !name) return NULL;
  for (int s = 0; s < m->nsurfaces; ++s)
    if (!strcmp(m->surfaces[s].name, name)) return &m->surfaces[s];
  return NULL;
}

/* "a, b, c" of the region or surface names into buf. */
static void list_names(const FemMesh *m, int surfaces, char *buf, size_t n)
{
  size_t used = 0;
  buf[0] = '\0';
  int cnt = surfaces ? m->nsurfaces : m->nregions;
  for (int i = 0; i < cnt && used + 1 < n; ++i) {
    const char *name = surfaces ? m->surfaces[i].name : m->region_names[i];
    int w = snprintf(buf + used, n - used, "%s%s", i ? ", " : "", name);
    if (w < 0) break;
    used += (size_t)w;
  }
  if (!cnt) snprintf(buf, n, "none");
}

int fem_mesh_require(const FemMesh *m, int nregions, const char *const *regions, int nsurfaces,
                     const char *const *surfaces)
{
  SA_REQUIRE(m, SA_ERR_INPUT, "fem_mesh_require: no mesh");
  char have_r[512], have_s[1024];
  list_names(m, 0, have_r, sizeof have_r);
  list_names(m, 1, have_s, sizeof have_s);
  for (int i = 0; i < nregions; ++i)
    SA_REQUIRE(fem_mesh_find_region(m, regions[i]) >= 0, SA_ERR_INPUT,
               "mesh %s lacks the region (physical volume) '%s'; regions present: %s; surfaces "
               "present: %s",
               m->source, regions[i], have_r, have_s);
  for (int i = 0; i < nsurfaces; ++i) {
    const FemSurface *s = fem_mesh_find_surface(m, surfaces[i]);
    SA_REQUIRE(s, SA_ERR_INPUT,
               "mesh %s lacks the surface (physical surface) '%s'; surfaces present: %s; regions "
               "present: %s",
               m->source, surfaces[i], have_s, have_r);
    SA_REQUIRE(s->nfaces > 0, SA_ERR_INPUT, "mesh %s: surface '%s' is empty", m->source,
               surfaces[i]);
  }
  return 0;
}

double fem_mesh_volume(const FemMesh *m, int region)
{
  if (!m) return 0.0;
  double v = 0.0;
  for (int e = 0; e < m->nelem; ++e)
    if (region < 0 || m->region[e] == region) v += elem_volume(m, e);
  return v;
}

/* Radius ratio of a tet with corners x[12]: r_in = 3 V / sum(face areas), and with edge vectors
 * a, b, c from corner 0, r_circ = |a^2 (b x c) + b^2 (c x a) + c^2 (a x b)| / (12 V). */
static double tet_radius_ratio(const double *x)
{
  double e[3][3], cr[3][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) e[k][i] = x[3 * (k + 1) + i] - x[i];
  for (int k = 0; k < 3; ++k) {
    const double *u = e[(k + 1) % 3], *v = e[(k + 2) % 3];
    cr[k][0] = u[1] * v[2] - u[2] * v[1];
    cr[k][1] = u[2] * v[0] - u[0] * v[2];
    cr[k][2] = u[0] * v[1] - u[1] * v[0];
  }
  double V6 = e[0][0] * cr[0][0] + e[0][1] * cr[0][1] + e[0][2] * cr[0][2];
  if (V6 <= 0.0) return 0.0;
  double area = 0.0, w[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    area += 0.5 * sqrt(cr[k][0] * cr[k][0] + cr[k][1] * cr[k][1] + cr[k][2] * cr[k][2]);
    double l2 = e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2];
    for (int i = 0; i < 3; ++i) w[i] += l2 * cr[k][i];
  }
  double f[3]; /* face (1, 2, 3) */
  double p[3], q[3];
  for (int i = 0; i < 3; ++i) p[i] = e[1][i] - e[0][i], q[i] = e[2][i] - e[0][i];
  f[0] = p[1] * q[2] - p[2] * q[1];
  f[1] = p[2] * q[0] - p[0] * q[2];
  f[2] = p[0] * q[1] - p[1] * q[0];
  area += 0.5 * sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  double r_in = 0.5 * V6 / area; /* 3 V / A with V = V6 / 6 */
  double r_circ = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) / (2.0 * V6);
  return 3.0 * r_in / r_circ;
}

int fem_mesh_quality(const FemMesh *m, int region, double *qmin, double *qmean)
{
  double lo = INFINITY, sum = 0.0, X[30];
  int worst = -1, n = 0;
  for (int e = 0; m && e < m->nelem; ++e) {
    if (region >= 0 && m->region[e] != region) continue;
    elem_coords(m, e, X);
    double q = tet_radius_ratio(X);
    sum += q;
    ++n;
    if (q < lo) lo = q, worst = e;
  }
  if (qmin) *qmin = n ? lo : 0.0;
  if (qmean) *qmean = n ? sum / n : 0.0;
  return worst;
}

int fem_mesh_add_surface_side(FemMesh *m, const char *surface, const char *region,
                              const char *name)
{
  const FemSurface *S = fem_mesh_find_surface(m, surface);
  SA_REQUIRE(S, SA_ERR_INPUT, "mesh %s has no surface '%s'", m->source, surface);
  int r = fem_mesh_find_region(m, region);
  SA_REQUIRE(r >= 0, SA_ERR_INPUT, "mesh %s has no region '%s'", m->source, region);
  SA_REQUIRE(name && name[0] && strlen(name) < 64 && !fem_mesh_find_surface(m, name),
             SA_ERR_INPUT, "surface name '%s' empty, too long or taken", name ? name : "");
  int nfn = S->nfn, nf = S->nfaces, ne = m->nelem, nen = m->nen;
  int *faces = malloc(sizeof(int) * (size_t)nfn * (nf ? nf : 1));
  int *fel = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
  int *nodes = malloc(sizeof(int) * (size_t)(S->nnodes ? S->nnodes : 1));
  /* corner node -> elements */
  int *ptr = calloc((size_t)m->nnodes + 1, sizeof *ptr), *lst = malloc(sizeof(int) * 4 * (size_t)ne);
  int rc = (faces && fel && nodes && ptr && lst) ? 0 : SA_ERROR(SA_ERR_MEMORY, "surface side");
  if (!rc) {
    for (int e = 0; e < ne; ++e)
      for (int a = 0; a < 4; ++a) ptr[m->conn[(size_t)e * nen + a] + 1]++;
    for (int i = 0; i < m->nnodes; ++i) ptr[i + 1] += ptr[i];
    int *fill = calloc((size_t)m->nnodes, sizeof *fill);
    if (!fill) rc = SA_ERROR(SA_ERR_MEMORY, "surface side");
    for (int e = 0; e < ne && !rc; ++e)
      for (int a = 0; a < 4; ++a) {
        int A = m->conn[(size_t)e * nen + a];
        lst[ptr[A] + fill[A]++] = e;
      }
    free(fill);
  }
  for (int k = 0; k < nf && !rc; ++k) {
    const int *f = S->faces + (size_t)k * nfn;
    int *g = faces + (size_t)k * nfn, e0 = S->face_elem[k];
    if (m->region[e0] == r) { /* already oriented out of this region's element */
      memcpy(g, f, sizeof(int) * (size_t)nfn);
      fel[k] = e0;
      continue;
    }
    int other = -1; /* the element across the face: it holds the three corners too */
    for (int t = ptr[f[0]]; t < ptr[f[0] + 1] && other < 0; ++t) {
      int e = lst[t], hit = 0;
      if (e == e0) continue;
      for (int a = 0; a < 4; ++a) {
        int A = m->conn[(size_t)e * nen + a];
        hit += (A == f[1]) + (A == f[2]);
      }
      if (hit == 2) other = e;
    }
    if (other < 0 || m->region[other] != r) {
      rc = SA_ERROR(SA_ERR_INPUT, "surface '%s' face %d does not bound region '%s'", surface, k,
                    region);
      break;
    }
    /* reversed orientation: corners (0, 2, 1); tri6 mid-nodes of edges 02, 21, 10 */
    g[0] = f[0], g[1] = f[2], g[2] = f[1];
    if (nfn == 6) g[3] = f[5], g[4] = f[4], g[5] = f[3];
    fel[k] = other;
  }
  int nnodes = S->nnodes;
  if (!rc) memcpy(nodes, S->nodes, sizeof(int) * (size_t)nnodes);
  /* S points into m->surfaces: not used after this realloc */
  FemSurface *sv = rc ? NULL : realloc(m->surfaces, sizeof *sv * (size_t)(m->nsurfaces + 1));
  if (!rc && !sv) rc = SA_ERROR(SA_ERR_MEMORY, "surface side");
  free(ptr);
  free(lst);
  if (rc) {
    free(faces), free(fel), free(nodes);
    return rc;
  }
  m->surfaces = sv;
  FemSurface *ns = &m->surfaces[m->nsurfaces++];
  memset(ns, 0, sizeof *ns);
  snprintf(ns->name, sizeof ns->name, "%s", name);
  ns->nfaces = nf;
  ns->nfn = nfn;
  ns->faces = faces;
  ns->face_elem = fel;
  ns->nnodes = nnodes;
  ns->nodes = nodes;
  return 0;
}

int fem_mesh_append(FemMesh *a, const FemMesh *b)
{
  SA_REQUIRE(a->etype == b->etype, SA_ERR_INPUT, "mesh %s (tet%d) and %s (tet%d): one element "
             "type per mesh", a->source, a->nen, b->source, b->nen);
  for (int r = 0; r < b->nregions; ++r)
    SA_REQUIRE(fem_mesh_find_region(a, b->region_names[r]) < 0, SA_ERR_INPUT,
               "region '%s' of %s is already in %s", b->region_names[r], b->source, a->source);
  for (int k = 0; k < b->nsurfaces; ++k)
    SA_REQUIRE(!fem_mesh_find_surface(a, b->surfaces[k].name), SA_ERR_INPUT,
               "surface '%s' of %s is already in %s", b->surfaces[k].name, b->source, a->source);
  int nn = a->nnodes + b->nnodes, ne = a->nelem + b->nelem, nr = a->nregions + b->nregions;
  int ns = a->nsurfaces + b->nsurfaces, on = a->nnodes, oe = a->nelem, orr = a->nregions;
  double *xyz = malloc(sizeof(double) * 3 * (size_t)nn);
  int *conn = malloc(sizeof(int) * (size_t)a->nen * ne), *reg = malloc(sizeof(int) * (size_t)ne);
  char(*rn)[64] = malloc(sizeof *rn * (size_t)(nr ? nr : 1));
  FemSurface *sv = calloc((size_t)(ns ? ns : 1), sizeof *sv);
  int ok = xyz && conn && reg && rn && sv;
  for (int k = 0; ok && k < b->nsurfaces; ++k) {
    const FemSurface *S = b->surfaces + k;
    FemSurface *T = sv + a->nsurfaces + k;
    *T = *S;
    T->faces = malloc(sizeof(int) * (size_t)S->nfn * (S->nfaces ? S->nfaces : 1));
    T->face_elem = malloc(sizeof(int) * (size_t)(S->nfaces ? S->nfaces : 1));
    T->nodes = malloc(sizeof(int) * (size_t)(S->nnodes ? S->nnodes : 1));
    ok = T->faces && T->face_elem && T->nodes;
    for (int i = 0; ok && i < S->nfn * S->nfaces; ++i) T->faces[i] = S->faces[i] + on;
    for (int i = 0; ok && i < S->nfaces; ++i) T->face_elem[i] = S->face_elem[i] + oe;
    for (int i = 0; ok && i < S->nnodes; ++i) T->nodes[i] = S->nodes[i] + on;
  }
  if (!ok) {
    for (int k = 0; sv && k < b->nsurfaces; ++k) {
      free(sv[a->nsurfaces + k].faces);
      free(sv[a->nsurfaces + k].face_elem);
      free(sv[a->nsurfaces + k].nodes);
    }
    free(xyz), free(conn), free(reg), free(rn), free(sv);
    return SA_ERROR(SA_ERR_MEMORY, "appending mesh %s", b->source);
  }
  memcpy(xyz, a->xyz, sizeof(double) * 3 * (size_t)on);
  memcpy(xyz + 3 * (size_t)on, b->xyz, sizeof(double) * 3 * (size_t)b->nnodes);
  memcpy(conn, a->conn, sizeof(int) * (size_t)a->nen * oe);
  for (size_t i = 0; i < (size_t)b->nen * b->nelem; ++i) conn[(size_t)a->nen * oe + i] = b->conn[i] + on;
  for (int e = 0; e < oe; ++e) reg[e] = a->region ? a->region[e] : 0;
  for (int e = 0; e < b->nelem; ++e) reg[oe + e] = (b->region ? b->region[e] : 0) + orr;
  if (orr) memcpy(rn, a->region_names, sizeof *rn * (size_t)orr);
  if (b->nregions) memcpy(rn + orr, b->region_names, sizeof *rn * (size_t)b->nregions);
  if (a->nsurfaces) memcpy(sv, a->surfaces, sizeof *sv * (size_t)a->nsurfaces);
  free(a->xyz), free(a->conn), free(a->region), free(a->region_names), free(a->surfaces);
  a->xyz = xyz, a->conn = conn, a->region = reg, a->region_names = rn, a->surfaces = sv;
  a->nnodes = nn, a->nelem = ne, a->nregions = nr, a->nsurfaces = ns;
  return 0;
}

void fem_mesh_destroy(FemMesh **pm)
{
  if (!pm || !*pm) return;
  FemMesh *m = *pm;
  free(m->xyz);
  free(m->conn);
  free(m->region);
  free(m->region_names);
  for (int s = 0; s < m->nsurfaces && m->surfaces; ++s) {
    free(m->surfaces[s].faces);
    free(m->surfaces[s].face_elem);
    free(m->surfaces[s].nodes);
  }
  free(m->surfaces);
  free(m);
  *pm = NULL;
}
