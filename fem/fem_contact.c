/* fem_contact.c - node-to-surface penalty contact with Coulomb friction as an assembly
 * contributor (fem_contact.h has the model; docs/contact.md the method, parameters and
 * measured behaviour).
 *
 * Per slave node (x its position, A its reference tributary area), target geometry g, n and
 * N = dn/dx (plane: g = (x - p).n, N = 0; cylinder wall, slave inside: r = (I - a a)(x - p),
 * rho = |r|, e = r / rho, g = R - rho, n = -e, N = -(I - a a - e e) / rho; flat master
 * triangle: closest point x_c, g = (x - x_c).n):
 *   t_N = -eps_N g  (g < 0),   w = x - a_anchor,  s = n.w,  d = w - s n = P w,
 *   stick t_T = -eps_T d;   slip (eps_T |d| > mu t_N)  t_T = -mu t_N d / |d|,
 *   F = A (t_N n + t_T)  (force of the target on the node).
 * Exact derivatives (rigid targets), with dg/dx = n:
 *   dt_N/dx = -eps_N n,   D = dd/dx = I - s N - n (x) (n + N^T w),
 *   stick dt_T/dx = -eps_T D,  slip dt_T/dx = -mu [dhat (x) dt_N/dx + t_N / |d| (I - dhat dhat) D],
 *   dF/dx = A [n (x) dt_N/dx + t_N N + dt_T/dx].
 * The contributor adds f_c = -F and K_c = -dF/dx (fem_contrib.h: internal-force sign). */
#include "fem_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem_contrib.h"
#include "fem_kernel_quad.h"
#include "sa_error.h"
#include "sa_log.h"

enum { TGT_NONE = 0, TGT_PLANE, TGT_CYLINDER, TGT_MESH };

struct FemContact {
  const FemMesh *m;
  FemContactParams prm;
  char slave[64], master[64];
  int target;
  double pp[3], pn[3];                   /* plane (at the state being evaluated) */
  double pp_c[3], pp_t[3];               /* plane point committed / target (moves with the
                                          * solver's ramp parameter) */
  double cp[3], ca[3], R, smin, smax;    /* cylinder */
  int nt, *tri;                          /* master flat triangles (3 nodes each) */
  int *mrow;      /* master_quadratic: the 6 nodes of each triangle's tri6 face (6 per
                   * triangle); NULL: reactions on the triangle's own 3 nodes */
  double *msubL;  /* master_quadratic: (L0, L1, L2) of each triangle's vertices in its face (9
                   * per triangle) */
  int ns, *snode;                        /* slave nodes */
  double *sarea;                         /* reference tributary areas */
  int *slave_mark;                       /* N: slave index + 1 or 0 */
  /* committed history */
  double *anc;    /* rigid: anchor point (3 per slave) */
  int *anc_f;     /* mesh: anchor triangle (-1: none) */
  int *last_tri; /* mesh: triangle found at the last evaluation (tie-breaking) */
  double *anc_b;  /* mesh: its barycentric coordinates (3 per slave) */
  double *vn;     /* mesh, smooth_normals: unit vertex normals of the master (3 per mesh node) */
  double *lam;    /* augmented Lagrangian: normal pressure multiplier per slave [Pa] (>= 0;
                   * 0 = pure penalty) at the state being evaluated */
  double *anc_m, *anc_bm; /* anchors at fem_contact_mark (anc, anc_b) */
  double pp_m[3], *lam_m, *lamT_m; /* committed plane point and multipliers at the mark */
  int *anc_fm;             /* and anc_f */
  double *sv;    /* fem_contact_save: anc, anc_b, gap_c, tn_c, tt_c, nrm_c, lam_c, lamT_c
                  * (3+3+1+1+3+3+1+3 per slave) */
  int *sv_f;      /* and anc_f */
  FemContactStats sv_st;
  double sv_pp[3];
  double *lamT, *lamT_c, *lamT_t; /* tangential traction multipliers (3 per slave; 0: pure
                                   * penalty stick), at the state being evaluated / committed /
                                   * target, ramped like lam */
  double *lam_c, *lam_t; /* committed / target multipliers: fem_contact_augment sets the target,
                          * the next solve ramps from one to the other with its load factor (so
                          * a cut substep takes a smaller part of the change) */
  /* committed read-back */
  double *gap_c, *tn_c, *tt_c, *nrm_c;
  FemContactStats st;
  FemSolver *s;
  int attached;
};

static void vertex_normals(FemContact *c, const double *x);

FemContactParams fem_contact_params_default(void) {
  FemContactParams p = {0};
  return p;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* p = (I - n n) l: the part of l in the plane normal to the unit vector n. */
static void tangential_part(const double *l, const double n[3], double p[3]) {
  double s = dot3(n, l);
  for (int i = 0; i < 3; i++) p[i] = l[i] - s * n[i];
}

/* A tri6 face's 4 corner/mid-node triangles (local node numbers, orientation kept) and the
 * face coordinates (L0, L1, L2) of its 6 nodes (mid-nodes on edges 01, 12, 20). */
static const int tri6_sub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
static const double tri6_L[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                    {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};

/* The flat (sub-)triangles of a face: tri3 itself, tri6 its 4 corner/mid-node triangles
 * (orientation kept). Returns the count written to t [out] 12. */
static int face_tris(const int *f, int nfn, int *t) {
  if (nfn == 3) {
    memcpy(t, f, 3 * sizeof *t);
    return 1;
  }
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) t[3 * k + i] = f[tri6_sub[k][i]];
  return 4;
}

/* The master nodes that receive the reaction of a slave on triangle t: rows [out] 6; returns
 * their count (3: the triangle's vertices; 6: its tri6 face's nodes, master_quadratic). */
static int master_rows(const FemContact *c, int t, int *rows) {
  if (c->mrow) {
    memcpy(rows, c->mrow + 6 * t, 6 * sizeof *rows);
    return 6;
  }
  memcpy(rows, c->tri + 3 * t, 3 * sizeof *rows);
  return 3;
}

static double tri_area(const double *X, const int *t) {
  double u[3], v[3], n[3];
  for (int i = 0; i < 3; i++) {
    u[i] = X[3 * t[1] + i] - X[3 * t[0] + i];
    v[i] = X[3 * t[2] + i] - X[3 * t[0] + i];
  }
  cross3(u, v, n);
  return 0.5 * sqrt(dot3(n, n));
}

/* int N_a dA over the reference face with nodes f [in] nfn (w [out] nfn): the consistent
 * nodal loads of a unit pressure. The tri6 rule (degree 4) is exact for a flat face, where the
 * corners get 0. On a curved tri6 face (mid-nodes off their edges' midpoints) a corner can get
 * a small negative value: a contact force pulling the node in, i.e. a negative contact
 * stiffness. Such values are set to 0 and the face's weights scaled back to its area. */
static void face_shape_integrals(const double *X, const int *f, int nfn, double *w) {
  const FemKqRule *R = nfn == 3 ? &fem_kq_tri3 : &fem_kq_tri6;
  for (int a = 0; a < nfn; a++) w[a] = 0;
  for (int q = 0; q < R->n; q++) {
    double N[6], dN[6][2], t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0}, n[3];
    fem_kq_tri_shape(nfn, R->L[q], N, dN);
    for (int a = 0; a < nfn; a++)
      for (int i = 0; i < 3; i++) {
        t1[i] += X[3 * f[a] + i] * dN[a][0];
        t2[i] += X[3 * f[a] + i] * dN[a][1];
      }
    cross3(t1, t2, n);
    double da = R->w[q] * sqrt(dot3(n, n));
    for (int a = 0; a < nfn; a++) w[a] += da * N[a];
  }
  double area = 0, kept = 0;
  for (int a = 0; a < nfn; a++) {
    area += w[a];
    w[a] = fmax(w[a], 0.0);
    kept += w[a];
  }
  if (kept > 0)
    for (int a = 0; a < nfn; a++) w[a] *= area / kept;
}

int fem_contact_create(const FemMesh *mesh, const char *slave, const FemContactParams *prm,
                       FemContact **out) {
  *out = NULL;
  SA_REQUIRE(mesh && slave && prm, SA_ERR_INPUT, "contact: mesh, slave surface and parameters needed");
  SA_REQUIRE(prm->penalty > 0 && isfinite(prm->penalty), SA_ERR_INPUT,
             "contact: penalty %g must be > 0 [Pa/m]", prm->penalty);
  SA_REQUIRE(prm->penalty_tangent >= 0 && isfinite(prm->penalty_tangent), SA_ERR_INPUT,
             "contact: penalty_tangent %g must be >= 0", prm->penalty_tangent);
  SA_REQUIRE(prm->friction >= 0 && isfinite(prm->friction), SA_ERR_INPUT,
             "contact: friction %g must be >= 0", prm->friction);
  SA_REQUIRE(prm->max_penetration >= 0 && prm->search_radius >= 0, SA_ERR_INPUT,
             "contact: max_penetration and search_radius must be >= 0");
  SA_REQUIRE(prm->slave_weights == FEM_CONTACT_WEIGHTS_LUMPED ||
                 prm->slave_weights == FEM_CONTACT_WEIGHTS_CONSISTENT,
             SA_ERR_INPUT, "contact: slave_weights %d unknown", prm->slave_weights);
  SA_REQUIRE(prm->master_quadratic == 0 || prm->master_quadratic == 1, SA_ERR_INPUT,
             "contact: master_quadratic must be 0 or 1");
  const FemSurface *sf = fem_mesh_find_surface(mesh, slave);
  SA_REQUIRE(sf, SA_ERR_INPUT, "contact: no surface '%s' in the mesh", slave);
  FemContact *c = calloc(1, sizeof *c);
  SA_REQUIRE(c, SA_ERR_MEMORY, "contact");
  *out = c;
  c->m = mesh;
  c->prm = *prm;
  if (c->prm.penalty_tangent == 0) c->prm.penalty_tangent = c->prm.penalty;
  snprintf(c->slave, sizeof c->slave, "%s", slave);
  c->ns = sf->nnodes;
  SA_CALLOC(c->snode, c->ns);
  SA_CALLOC(c->sarea, c->ns);
  SA_CALLOC(c->slave_mark, mesh->nnodes);
  for (int k = 0; k < c->ns; k++) {
    c->snode[k] = sf->nodes[k];
    c->slave_mark[sf->nodes[k]] = k + 1;
  }
  for (int f = 0; f < sf->nfaces; f++) {
    const int *fc = sf->faces + (size_t)f * sf->nfn;
    if (prm->slave_weights == FEM_CONTACT_WEIGHTS_CONSISTENT) {
      double w[6];
      face_shape_integrals(mesh->xyz, fc, sf->nfn, w);
      for (int i = 0; i < sf->nfn; i++) c->sarea[c->slave_mark[fc[i]] - 1] += w[i];
      continue;
    }
    int t[12], nt = face_tris(fc, sf->nfn, t);
    for (int j = 0; j < nt; j++) {
      double a = tri_area(mesh->xyz, t + 3 * j) / 3;
      for (int i = 0; i < 3; i++) c->sarea[c->slave_mark[t[3 * j + i]] - 1] += a;
    }
  }
  SA_CALLOC(c->anc, 3 * c->ns);
  SA_CALLOC(c->anc_f, c->ns);
  SA_CALLOC(c->anc_b, 3 * c->ns);
  SA_CALLOC(c->last_tri, c->ns);
  for (int k = 0; k < c->ns; k++) c->last_tri[k] = -1;
  SA_CALLOC(c->gap_c, c->ns);
  SA_CALLOC(c->tn_c, c->ns);
  SA_CALLOC(c->tt_c, 3 * c->ns);
  SA_CALLOC(c->nrm_c, 3 * c->ns);
  SA_CALLOC(c->lam, c->ns);
  SA_CALLOC(c->lam_c, c->ns);
  SA_CALLOC(c->anc_m, 3 * c->ns);
  SA_CALLOC(c->anc_bm, 3 * c->ns);
  SA_CALLOC(c->anc_fm, c->ns);
  SA_CALLOC(c->lam_t, c->ns);
  SA_CALLOC(c->lamT, 3 * c->ns);
  SA_CALLOC(c->lamT_c, 3 * c->ns);
  SA_CALLOC(c->lamT_t, 3 * c->ns);
  SA_CALLOC(c->lam_m, c->ns);
  SA_CALLOC(c->lamT_m, 3 * c->ns);
  for (int k = 0; k < c->ns; k++) {
    c->anc_f[k] = -1;
    memcpy(c->anc + 3 * k, mesh->xyz + 3 * c->snode[k], 3 * sizeof(double));
  }
  return 0;
}

static int check_target(FemContact *c) {
  SA_REQUIRE(c->target == TGT_NONE || !c->attached, SA_ERR_INPUT,
             "contact '%s': the target kind cannot change after attach", c->slave);
  return 0;
}

int fem_contact_set_master(FemContact *c, const char *master) {
  SA_CHECK(check_target(c));
  const FemSurface *mf = fem_mesh_find_surface(c->m, master);
  SA_REQUIRE(mf, SA_ERR_INPUT, "contact: no master surface '%s' in the mesh", master);
  int per = mf->nfn == 3 ? 1 : 4;
  free(c->tri);
  c->tri = malloc((size_t)3 * per * mf->nfaces * sizeof *c->tri);
  SA_REQUIRE(c->tri, SA_ERR_MEMORY, "contact master triangles");
  c->nt = 0;
  for (int f = 0; f < mf->nfaces; f++)
    c->nt += face_tris(mf->faces + (size_t)f * mf->nfn, mf->nfn, c->tri + 3 * c->nt);
  free(c->mrow);
  free(c->msubL);
  c->mrow = NULL;
  c->msubL = NULL;
  if (mf->nfn == 6 && c->prm.master_quadratic) {
    c->mrow = malloc(sizeof *c->mrow * 6 * (size_t)c->nt);
    c->msubL = malloc(sizeof *c->msubL * 9 * (size_t)c->nt);
    SA_REQUIRE(c->mrow && c->msubL, SA_ERR_MEMORY, "contact master faces");
    for (int f = 0; f < mf->nfaces; f++)
      for (int k = 0; k < 4; k++) {
        int t = 4 * f + k; /* face_tris' order */
        memcpy(c->mrow + 6 * t, mf->faces + (size_t)f * 6, 6 * sizeof *c->mrow);
        for (int j = 0; j < 3; j++)
          memcpy(c->msubL + 9 * t + 3 * j, tri6_L[tri6_sub[k][j]], 3 * sizeof(double));
      }
  }
  snprintf(c->master, sizeof c->master, "%s", master);
  c->target = TGT_MESH;
  free(c->vn);
  c->vn = NULL;
  if (c->prm.smooth_normals) {
    c->vn = calloc(3 * (size_t)c->m->nnodes, sizeof *c->vn);
    SA_REQUIRE(c->vn, SA_ERR_MEMORY, "contact vertex normals");
    vertex_normals(c, c->m->xyz);
  }
  return 0;
}

int fem_contact_set_plane(FemContact *c, const double p[3], const double n[3]) {
  SA_REQUIRE(c->target == TGT_NONE || c->target == TGT_PLANE, SA_ERR_INPUT,
             "contact '%s' already has another target", c->slave);
  double l = sqrt(dot3(n, n));
  SA_REQUIRE(l > 0 && isfinite(l) && isfinite(dot3(p, p)), SA_ERR_INPUT,
             "contact plane: normal must be non-zero and finite");
  for (int i = 0; i < 3; i++) {
    c->pp[i] = c->pp_c[i] = c->pp_t[i] = p[i];
    c->pn[i] = n[i] / l;
  }
  c->target = TGT_PLANE;
  return 0;
}

int fem_contact_move_plane(FemContact *c, const double p[3]) {
  SA_REQUIRE(c->target == TGT_PLANE, SA_ERR_INPUT, "contact '%s': move_plane needs a plane target",
             c->slave);
  SA_REQUIRE(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]), SA_ERR_INPUT,
             "contact '%s': plane target not finite", c->slave);
  memcpy(c->pp_t, p, sizeof c->pp_t);
  return 0;
}

/* Plane point at ramp parameter lam. */
static void plane_at(FemContact *c, double lam) {
  for (int i = 0; i < 3; i++) c->pp[i] = c->pp_c[i] + lam * (c->pp_t[i] - c->pp_c[i]);
}

int fem_contact_set_cylinder(FemContact *c, const double p[3], const double a[3], double R,
                             double smin, double smax) {
  SA_CHECK(check_target(c));
  double l = sqrt(dot3(a, a));
  SA_REQUIRE(l > 0 && isfinite(l) && R > 0 && isfinite(R) && smin < smax, SA_ERR_INPUT,
             "contact cylinder: axis non-zero, radius %g > 0 and smin %g < smax %g needed", R,
             smin, smax);
  for (int i = 0; i < 3; i++) {
    c->cp[i] = p[i];
    c->ca[i] = a[i] / l;
  }
  c->R = R;
  c->smin = smin;
  c->smax = smax;
  c->target = TGT_CYLINDER;
  return 0;
}

/* ------------------------------------------------------------------ the law at one node */

/* Returns 1 when in contact (t_N = lam - eps_N g >= 0, or frozen), 0 otherwise. Inputs: g, n,
 * N (NULL = 0), x, anchor a, area A, the node's multiplier lam (0: pure penalty, in contact
 * when g <= 0) and tangential multiplier lT (3; the stick trial traction is P lT - eps_T d,
 * P = I - n n: 0 is the pure penalty stick); slip_in: -1 decide, 0/1 frozen (finite
 * differences). Outputs: F force of the target on the node, dF = dF/dx (NULL: not wanted), tn,
 * tt (traction), *slip. */
static int node_law(const FemContactParams *p, double A, double g, double lam, const double *lT,
                    const double n[3], const double *N, const double x[3], const double a[3],
                    int frozen, int slip_in, double F[3], double *dF, double *tn_out, double tt[3],
                    int *slip) {
  /* g = 0 with lam = 0 is active (t_N = -0): touching bodies get the contact stiffness */
  if (lam - p->penalty * g < 0 && !frozen) {
    memset(F, 0, 3 * sizeof *F);
    if (dF) memset(dF, 0, 9 * sizeof *dF);
    if (tt) memset(tt, 0, 3 * sizeof *tt);
    *tn_out = 0;
    *slip = 0;
    return 0;
  }
  double eN = p->penalty, eT = p->penalty_tangent, mu = p->friction;
  double tn = lam - eN * g, w[3], d[3], t[3];
  for (int i = 0; i < 3; i++) w[i] = x[i] - a[i];
  double s = dot3(n, w);
  for (int i = 0; i < 3; i++) d[i] = w[i] - s * n[i];
  /* mu = 0: no tangential force at all (the stick set is the single point d = 0, where a
   * stick stiffness would not be the derivative of the zero force around it) */
  /* a slip vector at round-off level (e.g. the reference state, t_N = 0) has no direction:
   * stick */
  double dtiny = 1e-13 * (fabs(x[0]) + fabs(x[1]) + fabs(x[2]) + fabs(a[0]) + fabs(a[1]) + fabs(a[2]));
  /* stick trial traction tr = P lT - eps_T d (with lT = 0: -eps_T d, |tr| = eps_T |d|) */
  double tr[3], nl = lT ? dot3(n, lT) : 0;
  for (int i = 0; i < 3; i++) tr[i] = (lT ? lT[i] - nl * n[i] : 0) - eT * d[i];
  double trn = sqrt(dot3(tr, tr));
  int sl = mu == 0 ? 1 : slip_in >= 0 ? slip_in : (trn > mu * tn && trn > eT * dtiny);
  if (sl && trn == 0 && mu > 0) sl = 0; /* frozen slip with no slip vector: nothing to orient */
  for (int i = 0; i < 3; i++) t[i] = sl ? (mu > 0 ? mu * tn * tr[i] / trn : 0) : tr[i];
  for (int i = 0; i < 3; i++) F[i] = A * (tn * n[i] + t[i]);
  *tn_out = tn;
  if (tt) memcpy(tt, t, 3 * sizeof *t);
  *slip = sl;
  if (!dF) return 1;
  double dtn[3], D[9], Ntw[3] = {0, 0, 0};
  for (int j = 0; j < 3; j++) dtn[j] = -eN * n[j];
  if (N)
    for (int j = 0; j < 3; j++) Ntw[j] = N[0 * 3 + j] * w[0] + N[1 * 3 + j] * w[1] + N[2 * 3 + j] * w[2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      D[3 * i + j] = (i == j) - (N ? s * N[3 * i + j] : 0) - n[i] * (n[j] + Ntw[j]);
  /* dtr/dx = -eps_T D + d(P lT)/dx, d(P lT)_i/dx_j = -N_ij (n.lT) - n_i (lT.N_:j) */
  double dtr[9], Ntl[3] = {0, 0, 0};
  if (N && lT)
    for (int j = 0; j < 3; j++) Ntl[j] = N[0 * 3 + j] * lT[0] + N[1 * 3 + j] * lT[1] + N[2 * 3 + j] * lT[2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      dtr[3 * i + j] = -eT * D[3 * i + j] - (N ? nl * N[3 * i + j] + n[i] * Ntl[j] : 0);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double dt;
      if (!sl) dt = dtr[3 * i + j];
      else if (mu == 0) dt = 0;
      else { /* t = mu t_N tr / |tr| */
        double pd = 0;
        for (int k = 0; k < 3; k++) pd += ((i == k) - tr[i] * tr[k] / (trn * trn)) * dtr[3 * k + j];
        dt = mu * (tr[i] / trn * dtn[j] + tn / trn * pd);
      }
      dF[3 * i + j] = A * (n[i] * dtn[j] + (N ? tn * N[3 * i + j] : 0) + dt);
    }
  return 1;
}

/* Rigid target geometry at x: g, n, N. Returns 0 when the node cannot touch it (outside the
 * cylinder's axial extent or on its axis). */
static int rigid_geom(const FemContact *c, const double x[3], double *g, double n[3], double N[9]) {
  if (c->target == TGT_PLANE) {
    double w[3] = {x[0] - c->pp[0], x[1] - c->pp[1], x[2] - c->pp[2]};
    *g = dot3(w, c->pn);
    memcpy(n, c->pn, 3 * sizeof *n);
    memset(N, 0, 9 * sizeof *N);
    return 1;
  }
  double w[3] = {x[0] - c->cp[0], x[1] - c->cp[1], x[2] - c->cp[2]}, s = dot3(w, c->ca), r[3];
  if (s < c->smin || s > c->smax) return 0;
  for (int i = 0; i < 3; i++) r[i] = w[i] - s * c->ca[i];
  double rho = sqrt(dot3(r, r));
  if (rho <= 1e-12 * c->R) return 0;
  double e[3] = {r[0] / rho, r[1] / rho, r[2] / rho};
  *g = c->R - rho;
  for (int i = 0; i < 3; i++) {
    n[i] = -e[i];
    for (int j = 0; j < 3; j++) N[3 * i + j] = -((i == j) - c->ca[i] * c->ca[j] - e[i] * e[j]) / rho;
  }
  return 1;
}

/* ------------------------------------------------------------------ mesh master */

/* Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5):
 * barycentric coordinates b [out] 3; returns the squared distance. */
static double closest_on_tri(const double *p, const double *A, const double *B, const double *C,
                             double *bc) {
  double ab[3], ac[3], ap[3];
  for (int i = 0; i < 3; i++) {
    ab[i] = B[i] - A[i];
    ac[i] = C[i] - A[i];
    ap[i] = p[i] - A[i];
  }
  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  double u = 0, v = 0; /* weights of B and C */
  if (d1 <= 0 && d2 <= 0) goto done;
  double bp[3], cp[3];
  for (int i = 0; i < 3; i++) {
    bp[i] = p[i] - B[i];
    cp[i] = p[i] - C[i];
  }
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    u = 1;
    goto done;
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    u = d1 / (d1 - d3);
    goto done;
  }
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    v = 1;
    goto done;
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    v = d2 / (d2 - d6);
    goto done;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    v = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u = 1 - v;
    goto done;
  }
  {
    double den = 1 / (va + vb + vc);
    u = vb * den;
    v = vc * den;
  }
done:
  bc[0] = 1 - u - v;
  bc[1] = u;
  bc[2] = v;
  double q2 = 0;
  for (int i = 0; i < 3; i++) {
    double q = A[i] + u * ab[i] + v * ac[i] - p[i];
    q2 += q * q;
  }
  return q2;
}

static void tri_normal(const double *A, const double *B, const double *C, double n[3]) {
  double u[3], v[3];
  for (int i = 0; i < 3; i++) {
    u[i] = B[i] - A[i];
    v[i] = C[i] - A[i];
  }
  cross3(u, v, n);
  double l = sqrt(dot3(n, n));
  for (int i = 0; i < 3; i++) n[i] /= l;
}

/* Closest master triangle to the node at xs (not containing node): index or -1. Ties (a node
 * over a master edge or vertex is equally close to every triangle sharing it) keep the
 * triangle prev of the last evaluation: switching between them from one Newton iterate to the
 * next changes the force distribution by round-off-driven jumps (a residual floor). */
static int mesh_search(const FemContact *c, int node, const double *x, const double *xs, int prev) {
  double best = INFINITY;
  int bt = -1;
  for (int t = 0; t < c->nt; t++) {
    const int *v = c->tri + 3 * t;
    if (v[0] == node || v[1] == node || v[2] == node) continue;
    const double *A = x + 3 * v[0], *B = x + 3 * v[1], *C = x + 3 * v[2];
    /* bounding-sphere reject */
    double ctr[3], r2 = 0, dc = 0;
    for (int i = 0; i < 3; i++) ctr[i] = (A[i] + B[i] + C[i]) / 3;
    for (int k = 0; k < 3; k++) {
      const double *P = x + 3 * v[k];
      double q = 0;
      for (int i = 0; i < 3; i++) q += (P[i] - ctr[i]) * (P[i] - ctr[i]);
      if (q > r2) r2 = q;
    }
    for (int i = 0; i < 3; i++) dc += (xs[i] - ctr[i]) * (xs[i] - ctr[i]);
    double lo = sqrt(dc) - sqrt(r2);
    if (lo > 0 && lo * lo > best) continue;
    double bc[3], d2 = closest_on_tri(xs, A, B, C, bc);
    if (d2 < best) {
      best = d2;
      bt = t;
    }
  }
  if (prev >= 0 && prev != bt && bt >= 0) {
    const int *v = c->tri + 3 * prev;
    double bc[3], d2 = closest_on_tri(xs, x + 3 * v[0], x + 3 * v[1], x + 3 * v[2], bc);
    const double *A = x + 3 * c->tri[3 * bt], *B = x + 3 * c->tri[3 * bt + 1];
    double h2 = (A[0] - B[0]) * (A[0] - B[0]) + (A[1] - B[1]) * (A[1] - B[1]) + (A[2] - B[2]) * (A[2] - B[2]);
    if (d2 <= best + 1e-20 * h2) bt = prev;
  }
  return bt;
}

/* Force of master triangle t on slave k, with the positions of the slave xs, the triangle's
 * nodes xt (9) and the anchor triangle's nodes xa (9). Fs [out] 3 on the slave, Fm [out] on
 * the master rows (master_rows): Lsub NULL, the triangle's 3 nodes with its linear functions;
 * else Lsub [in] 9, the face coordinates of the triangle's vertices, the tri6 face's 6 nodes
 * with the quadratic functions at the contact point. frozen/slip_in as node_law. Returns
 * active. */
static int mesh_pair(const FemContact *c, int k, const double *xs, const double *xt,
                     const double *xa, const double *vn3, const double *Lsub, int frozen,
                     int slip_in, double *Fs, double *Fm, double *g_out, double *n_out,
                     double *tn, double *tt, int *slip) {
  double bc[3], n[3], xc[3], a[3], g;
  closest_on_tri(xs, xt, xt + 3, xt + 6, bc);
  if (vn3) { /* smooth_normals: the vertex normals interpolated at the closest point */
    for (int i = 0; i < 3; i++) n[i] = bc[0] * vn3[i] + bc[1] * vn3[3 + i] + bc[2] * vn3[6 + i];
    double l = sqrt(dot3(n, n));
    for (int i = 0; i < 3; i++) n[i] /= l;
  } else {
    tri_normal(xt, xt + 3, xt + 6, n);
  }
  for (int i = 0; i < 3; i++) {
    xc[i] = bc[0] * xt[i] + bc[1] * xt[3 + i] + bc[2] * xt[6 + i];
    a[i] = c->anc_b[3 * k] * xa[i] + c->anc_b[3 * k + 1] * xa[3 + i] + c->anc_b[3 * k + 2] * xa[6 + i];
  }
  double w[3] = {xs[0] - xc[0], xs[1] - xc[1], xs[2] - xc[2]};
  g = dot3(w, n);
  /* smooth normals: the slip is the motion of the closest point on the master (the gap vector
   * xs - xc is along the facet normal, not along n, so x - a would carry a spurious slip) */
  int act = node_law(&c->prm, c->sarea[k], g, c->lam[k], c->lamT + 3 * k, n, NULL, vn3 ? xc : xs, a,
                     frozen, slip_in, Fs, NULL, tn, tt, slip);
  if (Lsub) {
    double Lq[3] = {0, 0, 0}, N6[6];
    for (int j = 0; j < 3; j++)
      for (int a = 0; a < 3; a++) Lq[a] += bc[j] * Lsub[3 * j + a];
    fem_kq_tri_shape(6, Lq, N6, NULL);
    for (int a = 0; a < 6; a++)
      for (int i = 0; i < 3; i++) Fm[3 * a + i] = -N6[a] * Fs[i];
  } else {
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) Fm[3 * j + i] = -bc[j] * Fs[i];
  }
  if (g_out) *g_out = g;
  if (n_out) memcpy(n_out, n, 3 * sizeof *n);
  return act;
}

/* Local node list of a pair: slave, triangle, anchor triangle (deduplicated). */
static int pair_nodes(const FemContact *c, int k, int t, int *L, int *rt, int *ra) {
  int nl = 0;
  int cand[7] = {c->snode[k], c->tri[3 * t], c->tri[3 * t + 1], c->tri[3 * t + 2], -1, -1, -1};
  int fa = c->anc_f[k] >= 0 ? c->anc_f[k] : t;
  for (int i = 0; i < 3; i++) cand[4 + i] = c->tri[3 * fa + i];
  int idx[7];
  for (int q = 0; q < 7; q++) {
    int f = -1;
    for (int r = 0; r < nl; r++)
      if (L[r] == cand[q]) f = r;
    if (f < 0) {
      L[nl] = cand[q];
      f = nl++;
    }
    idx[q] = f;
  }
  for (int i = 0; i < 3; i++) {
    rt[i] = idx[1 + i];
    ra[i] = idx[4 + i];
  }
  return nl;
}

static int pair_eval(const FemContact *c, int k, int t, const double *xl, const int *rt,
                     const int *ra, int frozen, int slip_in, double *Fs, double *Fm, double *g,
                     double *n, double *tn, double *tt, int *slip) {
  double xt[9], xa[9], vn3[9];
  if (c->vn)
    for (int i = 0; i < 3; i++) memcpy(vn3 + 3 * i, c->vn + 3 * c->tri[3 * t + i], 3 * sizeof(double));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      xt[3 * i + j] = xl[3 * rt[i] + j];
      xa[3 * i + j] = xl[3 * ra[i] + j];
    }
  return mesh_pair(c, k, xl, xt, xa, c->vn ? vn3 : NULL, c->msubL ? c->msubL + 9 * t : NULL,
                   frozen, slip_in, Fs, Fm, g, n, tn, tt, slip);
}

/* ------------------------------------------------------------------ contributor */


/* smooth_normals: area-weighted unit vertex normals of the master triangles at positions x
 * (held fixed in the finite-difference tangent of a pair: the normal's dependence on the
 * neighbouring master nodes is left out of the tangent). */
static void vertex_normals(FemContact *c, const double *x) {
  if (!c->vn) return;
  for (int t = 0; t < c->nt; t++)
    for (int j = 0; j < 3; j++) memset(c->vn + 3 * c->tri[3 * t + j], 0, 3 * sizeof(double));
  for (int t = 0; t < c->nt; t++) {
    const int *T = c->tri + 3 * t;
    double u[3], w[3], n[3];
    for (int i = 0; i < 3; i++) {
      u[i] = x[3 * T[1] + i] - x[3 * T[0] + i];
      w[i] = x[3 * T[2] + i] - x[3 * T[0] + i];
    }
    cross3(u, w, n);
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) c->vn[3 * T[j] + i] += n[i];
  }
  for (int t = 0; t < c->nt; t++)
    for (int j = 0; j < 3; j++) {
      double *q = c->vn + 3 * c->tri[3 * t + j], l = sqrt(dot3(q, q));
      if (l > 0 && fabs(l - 1) > 1e-15) for (int i = 0; i < 3; i++) q[i] /= l;
    }
}

/* Multipliers at load factor f of the solve: from the committed to the target ones. */
static void multipliers_at(FemContact *c, double f) {
  for (int k = 0; k < c->ns; k++) c->lam[k] = c->lam_c[k] + f * (c->lam_t[k] - c->lam_c[k]);
  for (int k = 0; k < 3 * c->ns; k++) c->lamT[k] = c->lamT_c[k] + f * (c->lamT_t[k] - c->lamT_c[k]);
}

static int contact_eval(void *ctx, FemAsmView *v) {
  FemContact *c = ctx;
  const double *x = fem_asm_positions(v);
  if (c->target == TGT_MESH) vertex_normals(c, x);
  int wantK = fem_asm_wants_tangent(v);
  if (c->target == TGT_PLANE) plane_at(c, fem_asm_load_factor(v));
  multipliers_at(c, fem_asm_load_factor(v));
  for (int k = 0; k < c->ns; k++) {
    int A = c->snode[k];
    const double *xs = x + 3 * A;
    if (!isfinite(xs[0]) || !isfinite(xs[1]) || !isfinite(xs[2])) return SA_ERR_DOMAIN;
    double F[3], dF[9], tn, g, n[3], N[9];
    int slip;
    if (c->target == TGT_PLANE || c->target == TGT_CYLINDER) {
      if (!rigid_geom(c, xs, &g, n, N)) continue;
      if (!node_law(&c->prm, c->sarea[k], g, c->lam[k], c->lamT + 3 * k, n, N, xs, c->anc + 3 * k,
                    0, -1, F, wantK ? dF : NULL, &tn, NULL, &slip))
        continue;
      if (c->prm.max_penetration > 0 && -g > c->prm.max_penetration) {
        sa_log(SA_LOG_DEBUG, "fem", "contact '%s': node %d penetrates %.3g m > %.3g m", c->slave,
               A, -g, c->prm.max_penetration);
        return SA_ERR_DOMAIN;
      }
      double f[3] = {-F[0], -F[1], -F[2]}, K[9];
      fem_asm_add_force(v, A, f);
      if (wantK) {
        for (int i = 0; i < 9; i++) K[i] = -dF[i];
        fem_asm_add_block(v, A, A, K);
      }
      continue;
    }
    int t = mesh_search(c, A, x, xs, c->last_tri[k]);
    c->last_tri[k] = t;
    if (t < 0) continue;
    int L[7], rt[3], ra[3], nl = pair_nodes(c, k, t, L, rt, ra);
    double xl[21], Fs[3], Fm[18], tt[3];
    for (int r = 0; r < nl; r++) memcpy(xl + 3 * r, x + 3 * L[r], 3 * sizeof(double));
    if (!pair_eval(c, k, t, xl, rt, ra, 0, -1, Fs, Fm, &g, n, &tn, tt, &slip))
      continue;
    if (c->prm.max_penetration > 0 && -g > c->prm.max_penetration) {
      sa_log(SA_LOG_DEBUG, "fem", "contact '%s': node %d penetrates %.3g m > %.3g m", c->slave,
             A, -g, c->prm.max_penetration);
      return SA_ERR_DOMAIN;
    }
    double f[3] = {-Fs[0], -Fs[1], -Fs[2]};
    fem_asm_add_force(v, A, f);
    int rows[7] = {A}, nm = master_rows(c, t, rows + 1);
    for (int j = 0; j < nm; j++) {
      double fm[3] = {-Fm[3 * j], -Fm[3 * j + 1], -Fm[3 * j + 2]};
      fem_asm_add_force(v, rows[1 + j], fm);
    }
    if (!wantK) continue;
    /* central differences of the pair's forces, discrete state frozen */
    const double *P = xl + 3 * rt[0];
    double h = 0;
    for (int j = 1; j < 3; j++) {
      const double *Q = xl + 3 * rt[j];
      double l = sqrt((Q[0] - P[0]) * (Q[0] - P[0]) + (Q[1] - P[1]) * (Q[1] - P[1]) +
                      (Q[2] - P[2]) * (Q[2] - P[2]));
      if (l > h) h = l;
    }
    h *= 1e-7;
    double Kc[7][7][9]; /* rows: slave, master rows; columns: local nodes */
    memset(Kc, 0, sizeof Kc);
    for (int r = 0; r < nl; r++)
      for (int j = 0; j < 3; j++) {
        double Fp[21], Fmn[21], gg, nn[3], tnn, ttt[3];
        int sp;
        double keep = xl[3 * r + j];
        xl[3 * r + j] = keep + h;
        pair_eval(c, k, t, xl, rt, ra, 1, slip, Fp, Fp + 3, &gg, nn, &tnn, ttt, &sp);
        xl[3 * r + j] = keep - h;
        pair_eval(c, k, t, xl, rt, ra, 1, slip, Fmn, Fmn + 3, &gg, nn, &tnn, ttt, &sp);
        xl[3 * r + j] = keep;
        for (int q = 0; q <= nm; q++)
          for (int i = 0; i < 3; i++)
            Kc[q][r][3 * i + j] = -(Fp[3 * q + i] - Fmn[3 * q + i]) / (2 * h);
      }
    for (int q = 0; q <= nm; q++)
      for (int r = 0; r < nl; r++) fem_asm_add_block(v, rows[q], L[r], Kc[q][r]);
  }
  return 0;
}

/* Commit at the accepted positions x: anchors (the elastic tangential slip after the return
 * map is kept, the slipped part is absorbed by moving the anchor) and the read-back state. */
static void contact_commit(void *ctx, const double *x) {
  FemContact *c = ctx;
  if (c->target == TGT_MESH) vertex_normals(c, x);
  if (c->target == TGT_PLANE) {
    double lam = c->s ? fem_solver_load_factor(c->s) : 0.0;
    plane_at(c, lam);
    /* a completed ramp makes the target the committed position */
    if (lam >= 1.0 - 1e-12) memcpy(c->pp_c, c->pp_t, sizeof c->pp_c);
  }
  {
    double f = c->s ? fem_solver_load_factor(c->s) : 0.0;
    multipliers_at(c, f);
    if (f >= 1.0 - 1e-12) {
      memcpy(c->lam_c, c->lam_t, sizeof(double) * (size_t)c->ns);
      memcpy(c->lamT_c, c->lamT_t, sizeof(double) * 3 * (size_t)c->ns);
    }
  }
  FemContactStats st = {0};
  double tsum[3] = {0, 0, 0};
  for (int k = 0; k < c->ns; k++) {
    int A = c->snode[k];
    const double *xs = x + 3 * A;
    double F[3], tn = 0, tt[3] = {0, 0, 0}, g = INFINITY, n[3] = {0, 0, 0}, N[9];
    int slip = 0, act = 0;
    if (c->target == TGT_PLANE || c->target == TGT_CYLINDER) {
      if (rigid_geom(c, xs, &g, n, N)) {
        act = node_law(&c->prm, c->sarea[k], g, c->lam[k], c->lamT + 3 * k, n, N, xs,
                       c->anc + 3 * k, 0, -1, F, NULL, &tn, tt, &slip);
        /* the anchor that makes the stick trial equal the traction carried: P lT - eps_T d =
         * t_T, d = x_c - a (with lT = 0: a = x_c + t_T / eps_T) */
        double pl[3];
        tangential_part(c->lamT + 3 * k, n, pl);
        for (int i = 0; i < 3; i++)
          c->anc[3 * k + i] = xs[i] - g * n[i] + (tt[i] - pl[i]) / c->prm.penalty_tangent;
      } else {
        memcpy(c->anc + 3 * k, xs, 3 * sizeof(double));
      }
    } else if (c->target == TGT_MESH) {
      int t = mesh_search(c, A, x, xs, c->last_tri[k]);
      if (t >= 0) {
        int L[7], rt[3], ra[3], nl = pair_nodes(c, k, t, L, rt, ra);
        double xl[21], Fs[3], Fm[18];
        for (int r = 0; r < nl; r++) memcpy(xl + 3 * r, x + 3 * L[r], 3 * sizeof(double));
        act = pair_eval(c, k, t, xl, rt, ra, 0, -1, Fs, Fm, &g, n, &tn, tt,
                        &slip);
        memcpy(F, Fs, sizeof F);
        /* new anchor a = x_c - d_new = xs - g n + t_T / eps_T, in the triangle's (unclamped)
         * barycentric coordinates */
        const double *P0 = x + 3 * c->tri[3 * t], *P1 = x + 3 * c->tri[3 * t + 1],
                     *P2 = x + 3 * c->tri[3 * t + 2];
        double a[3], e1[3], e2[3], w[3], bq[3], pl[3];
        if (c->vn) closest_on_tri(xs, P0, P1, P2, bq);
        tangential_part(c->lamT + 3 * k, n, pl);
        for (int i = 0; i < 3; i++) {
          /* smooth normals: the anchor follows the closest point (see mesh_pair) */
          double base = c->vn ? bq[0] * P0[i] + bq[1] * P1[i] + bq[2] * P2[i] : xs[i] - g * n[i];
          a[i] = base + (act ? (tt[i] - pl[i]) / c->prm.penalty_tangent : 0);
          e1[i] = P1[i] - P0[i];
          e2[i] = P2[i] - P0[i];
          w[i] = a[i] - P0[i];
        }
        double a11 = dot3(e1, e1), a12 = dot3(e1, e2), a22 = dot3(e2, e2);
        double b1 = dot3(e1, w), b2 = dot3(e2, w), det = a11 * a22 - a12 * a12;
        double u = (a22 * b1 - a12 * b2) / det, vv = (a11 * b2 - a12 * b1) / det;
        c->anc_f[k] = t;
        c->anc_b[3 * k] = 1 - u - vv;
        c->anc_b[3 * k + 1] = u;
        c->anc_b[3 * k + 2] = vv;
      } else {
        c->anc_f[k] = -1;
      }
    }
    c->gap_c[k] = g;
    c->tn_c[k] = act ? tn : 0;
    for (int i = 0; i < 3; i++) {
      c->tt_c[3 * k + i] = act ? tt[i] : 0;
      c->nrm_c[3 * k + i] = n[i];
    }
    if (!act) continue;
    st.n_active++;
    st.n_slip += slip;
    if (-g > st.max_penetration) st.max_penetration = -g;
    for (int i = 0; i < 3; i++) {
      st.force[i] += F[i];
      tsum[i] += c->sarea[k] * tt[i];
    }
    st.normal_force += c->sarea[k] * tn;
    double pl[3], e[3];
    tangential_part(c->lamT + 3 * k, n, pl);
    for (int i = 0; i < 3; i++) e[i] = tt[i] - pl[i];
    st.tangent_slack += c->sarea[k] * sqrt(dot3(e, e)) / c->prm.penalty_tangent;
  }
  st.tangent_force = sqrt(dot3(tsum, tsum));
  c->st = st;
}

static int contact_candidates(void *ctx, const FemMesh *m, FemPairSink *sink) {
  FemContact *c = ctx;
  if (c->target != TGT_MESH || c->prm.search_radius <= 0) return 0;
  double r = c->prm.search_radius;
  for (int k = 0; k < c->ns; k++) {
    const double *xs = m->xyz + 3 * c->snode[k];
    for (int t = 0; t < c->nt; t++) {
      const int *v = c->tri + 3 * t;
      double bc[3];
      if (closest_on_tri(xs, m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], bc) > r * r)
        continue;
      int rows[6], nm = master_rows(c, t, rows);
      for (int j = 0; j < nm; j++) {
        if (rows[j] == c->snode[k]) continue;
        fem_pairs_add(sink, c->snode[k], rows[j]);
        fem_pairs_add(sink, rows[j], c->snode[k]);
      }
    }
  }
  return 0;
}

int fem_contact_attach(FemContact *c, FemSolver *s) {
  SA_REQUIRE(c->target != TGT_NONE, SA_ERR_INPUT, "contact '%s': no target set", c->slave);
  SA_REQUIRE(!c->attached, SA_ERR_INPUT, "contact '%s' is already attached", c->slave);
  SA_REQUIRE(fem_solver_mesh(s) == c->m, SA_ERR_INPUT, "contact '%s': solver has another mesh",
             c->slave);
  /* anchors at the reference configuration (the state before the first step) */
  contact_commit(c, c->m->xyz);
  FemContributor k = {"contact", contact_candidates, contact_eval, c, contact_commit};
  SA_CHECK(fem_solver_add_contributor(s, &k));
  c->s = s;
  c->attached = 1;
  return 0;
}

int fem_contact_set_friction(FemContact *c, double mu) {
  SA_REQUIRE(mu >= 0 && isfinite(mu), SA_ERR_INPUT, "contact '%s': friction %g must be >= 0",
             c->slave, mu);
  c->prm.friction = mu;
  return 0;
}

void fem_contact_stats(const FemContact *c, FemContactStats *st) { *st = c->st; }

/* Uzawa update at the committed state: lam <- <lam - eps_N g>, i.e. the multiplier becomes the
 * pressure the node carried (t_N), so the next solve needs no penetration to carry it. It is
 * the next solve's target; that solve ramps to it. */
int fem_contact_augment(FemContact *c, double *max_penetration, double *overlap_volume) {
  double pen = 0, vol = 0;
  for (int k = 0; k < c->ns; k++) {
    double g = c->gap_c[k];
    if (g < 0) {
      pen = fmax(pen, -g);
      vol += c->sarea[k] * -g;
    }
    /* an unevaluated node (outside a rigid target, no master face) has g = +inf: lam = 0 */
    c->lam_t[k] = fmax(0.0, c->lam_c[k] - c->prm.penalty * g);
    /* tangential: the traction the node carried (0 off contact or frictionless), so that the
     * next solve needs no elastic slip from the step's stick point to carry it */
    for (int i = 0; i < 3; i++) c->lamT_t[3 * k + i] = c->tt_c[3 * k + i];
  }
  if (max_penetration) *max_penetration = pen;
  if (overlap_volume) *overlap_volume = vol;
  return 0;
}

int fem_contact_augment_damp(FemContact *c, double omega) {
  SA_REQUIRE(omega > 0.0 && omega <= 1.0, SA_ERR_INPUT, "contact '%s': damping %g outside (0, 1]",
             c->slave, omega);
  for (int k = 0; k < c->ns; k++) {
    c->lam_t[k] = c->lam_c[k] + omega * (c->lam_t[k] - c->lam_c[k]);
    for (int i = 0; i < 3; i++)
      c->lamT_t[3 * k + i] = c->lamT_c[3 * k + i] + omega * (c->lamT_t[3 * k + i] - c->lamT_c[3 * k + i]);
  }
  return 0;
}

/* A pending multiplier update dropped: target and current = committed. */
static void cancel_augment(FemContact *c) {
  size_t n = sizeof(double) * (size_t)c->ns;
  memcpy(c->lam_t, c->lam_c, n);
  memcpy(c->lam, c->lam_c, n);
  memcpy(c->lamT_t, c->lamT_c, 3 * n);
  memcpy(c->lamT, c->lamT_c, 3 * n);
}

/* The stick anchors (anc, anc_b, anc_f) of one set of arrays into another. */
static void copy_anchors(const FemContact *c, double *anc, double *anc_b, int *anc_f,
                         const double *from_anc, const double *from_b, const int *from_f) {
  memcpy(anc, from_anc, sizeof(double) * 3 * (size_t)c->ns);
  memcpy(anc_b, from_b, sizeof(double) * 3 * (size_t)c->ns);
  memcpy(anc_f, from_f, sizeof(int) * (size_t)c->ns);
}

/* The saved state: anchors, then the read-back gap_c, tn_c, tt_c, nrm_c, lam_c and lamT_c. */
enum { SV_PER = 3 + 3 + 1 + 1 + 3 + 3 + 1 + 3 };
static void sv_copy(FemContact *c, int save) {
  double *arr[] = {c->gap_c, c->tn_c, c->tt_c, c->nrm_c, c->lam_c, c->lamT_c};
  int w[] = {1, 1, 3, 3, 1, 3};
  double *sb = c->sv + 3 * (size_t)c->ns, *p = c->sv + 6 * (size_t)c->ns;
  if (save) copy_anchors(c, c->sv, sb, c->sv_f, c->anc, c->anc_b, c->anc_f);
  else copy_anchors(c, c->anc, c->anc_b, c->anc_f, c->sv, sb, c->sv_f);
  for (int a = 0; a < 6; a++) {
    size_t n = sizeof(double) * (size_t)w[a] * (size_t)c->ns;
    if (save) memcpy(p, arr[a], n);
    else memcpy(arr[a], p, n);
    p += (size_t)w[a] * (size_t)c->ns;
  }
  if (save) {
    c->sv_st = c->st;
    memcpy(c->sv_pp, c->pp_c, sizeof c->sv_pp);
  } else {
    c->st = c->sv_st;
    memcpy(c->pp_c, c->sv_pp, sizeof c->sv_pp);
    cancel_augment(c);
  }
}

int fem_contact_save(FemContact *c) {
  if (!c->sv) {
    c->sv = malloc(sizeof(double) * SV_PER * (size_t)c->ns);
    c->sv_f = malloc(sizeof(int) * (size_t)c->ns);
    SA_REQUIRE(c->sv && c->sv_f, SA_ERR_MEMORY, "contact '%s': saved state", c->slave);
  }
  sv_copy(c, 1);
  return 0;
}

int fem_contact_restore(FemContact *c) {
  SA_REQUIRE(c->sv, SA_ERR_INPUT, "contact '%s': fem_contact_restore without a save", c->slave);
  sv_copy(c, 0);
  return 0;
}

void fem_contact_mark(FemContact *c) {
  copy_anchors(c, c->anc_m, c->anc_bm, c->anc_fm, c->anc, c->anc_b, c->anc_f);
  memcpy(c->pp_m, c->pp_c, sizeof c->pp_m);
  memcpy(c->lam_m, c->lam_c, sizeof(double) * (size_t)c->ns);
  memcpy(c->lamT_m, c->lamT_c, sizeof(double) * 3 * (size_t)c->ns);
}

void fem_contact_rewind(FemContact *c) {
  fem_contact_restore_mark(c);
  memcpy(c->pp_c, c->pp_m, sizeof c->pp_c);
  memcpy(c->lam_c, c->lam_m, sizeof(double) * (size_t)c->ns);
  memcpy(c->lamT_c, c->lamT_m, sizeof(double) * 3 * (size_t)c->ns);
  multipliers_at(c, 0.0);
  if (c->target == TGT_PLANE) plane_at(c, 0.0);
}

void fem_contact_restore_mark(FemContact *c) {
  copy_anchors(c, c->anc, c->anc_b, c->anc_f, c->anc_m, c->anc_bm, c->anc_fm);
}

int fem_contact_slaves(const FemContact *c, const int **node, const double **area,
                       const double **gap, const double **tn, const double **tt,
                       const double **normal) {
  if (node) *node = c->snode;
  if (area) *area = c->sarea;
  if (gap) *gap = c->gap_c;
  if (tn) *tn = c->tn_c;
  if (tt) *tt = c->tt_c;
  if (normal) *normal = c->nrm_c;
  return c->ns;
}

void fem_contact_destroy(FemContact **cp) {
  if (!cp || !*cp) return;
  FemContact *c = *cp;
  void *p[] = {c->last_tri, c->tri, c->mrow, c->msubL, c->snode, c->sarea, c->slave_mark, c->anc, c->anc_f, c->anc_b,
               c->gap_c, c->tn_c, c->tt_c, c->nrm_c, c->vn, c->lam,
               c->lam_c, c->lam_t, c->lamT, c->lamT_c, c->lamT_t, c->lam_m, c->lamT_m, c->anc_m,
               c->anc_bm, c->anc_fm,
               c->sv, c->sv_f};
  for (size_t i = 0; i < sizeof p / sizeof *p; i++) free(p[i]);
  free(c);
  *cp = NULL;
}
