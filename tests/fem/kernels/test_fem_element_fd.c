/* test_fem_element_fd.c - consistency of the tet4/tet10 kernels by central finite differences:
 * fe = dPi/du (FD of the element energy) and Ke = dfe/du (FD of fe), with random distorted
 * geometry (straight-sided tet10: 4-point rule; curved tet10: 8-point rule) and random
 * displacements (det F ~ 0.8..1.3), for each law and for K/mu = 1000 (near-incompressible, where
 * the volumetric term dominates K by 1000x: the tolerance is relative to the largest entry), with
 * the default fluctuation modulus kappa_s = 4 mu0, kappa_s = kappa (K/mu = 3 and the stiff law:
 * displacement element), kappa_s = 0 (pure mean dilatation) and kappa_s = 50 mu0.
 * Central differences with h = 1e-6 (element size 1): truncation ~h^2 |Pi'''| and round-off
 * ~eps |f| / h, both < 1e-8 of the largest entry; rtol 1e-6 leaves margin. Also checked: Ke
 * symmetric, rigid-body invariance (fe sums to zero, Ke annihilates translations), the
 * stress-free reference gives fe = 0 and theta = 1, inversion returns SA_ERR_INVERTED and a
 * degenerate reference element SA_ERR_INPUT.
 * The composite tet10 (FemMaterial.tet10_composite, piecewise linear over 8 sub-tets) gets the
 * same checks for every law, straight and curved, and a Mohr-Coulomb (law object, FEM_LAW_FULL)
 * check in a yielding state: Ke against central differences of fe at fixed history (the law is
 * path dependent and non-associated, so no energy check and no symmetry), h = 1e-7, rtol 1e-6 of
 * max |Ke| (the law's own FD test holds 1e-6 at h = 1e-6; states within ~h of a change of
 * return region are skipped by retrying with another draw). */
#include <stdio.h>
#include <string.h>

#include "fem_element.h"
#include "fem_mohr_coulomb.h"
#include "sa_error.h"
#include "kt_util.h"

static FemElemOut out, outp, outm;

static void check(const char *name, FemElemType t, double curve, const FemMaterial *m)
{
  const int nen = (int)t, nd = 3 * nen;
  char what[200];
  for (int trial = 0; trial < 4; trial++) {
    double X[30], x[30], F0[9];
    kt_random_tet(nen, 0.2, curve, X);
    kt_random_F(0.2, kt_rand(0.8, 1.3), F0);
    for (int a = 0; a < nen; a++)
      for (int i = 0; i < 3; i++)
        x[3 * a + i] = F0[3 * i] * X[3 * a] + F0[3 * i + 1] * X[3 * a + 1] +
                       F0[3 * i + 2] * X[3 * a + 2] + kt_rand(-0.03, 0.03);
    int rc = fem_element_tl(t, X, x, m, NULL, NULL, 1, &out);
    if (rc) {
      fprintf(stderr, "%s trial %d: fem_element_tl returned %d (%s)\n", name, trial, rc,
              sa_error_message());
      kt_fail++;
      sa_error_clear();
      continue;
    }
    double fmax = kt_maxabs(out.fe, nd), Kmax = kt_maxabs(out.Ke, nd * nd), h = 1e-6;
    double sum[3] = {0, 0, 0};
    for (int a = 0; a < nen; a++)
      for (int i = 0; i < 3; i++) sum[i] += out.fe[3 * a + i];
    for (int i = 0; i < 3; i++) {
      snprintf(what, sizeof what, "%s trial %d: sum of fe[%d]", name, trial, i);
      kt_close(what, sum[i], 0, 1e-12 * fmax, 0);
    }
    for (int c = 0; c < nd; c++) {
      double xs = x[c];
      x[c] = xs + h;
      fem_element_tl(t, X, x, m, NULL, NULL, 0, &outp);
      x[c] = xs - h;
      fem_element_tl(t, X, x, m, NULL, NULL, 0, &outm);
      x[c] = xs;
      snprintf(what, sizeof what, "%s trial %d: fe[%d] vs FD of energy", name, trial, c);
      kt_close(what, out.fe[c], (outp.energy - outm.energy) / (2 * h), 1e-6 * fmax, 0);
      for (int r = 0; r < nd; r++) {
        snprintf(what, sizeof what, "%s trial %d: Ke[%d][%d] vs FD of fe", name, trial, r, c);
        kt_close(what, out.Ke[r * nd + c], (outp.fe[r] - outm.fe[r]) / (2 * h), 1e-6 * Kmax, 0);
        snprintf(what, sizeof what, "%s trial %d: Ke symmetry [%d][%d]", name, trial, r, c);
        kt_close(what, out.Ke[r * nd + c], out.Ke[c * nd + r], 1e-12 * Kmax, 0);
      }
    }
    for (int r = 0; r < nd; r++)
      for (int k = 0; k < 3; k++) {
        double s = 0;
        for (int b = 0; b < nen; b++) s += out.Ke[r * nd + 3 * b + k];
        snprintf(what, sizeof what, "%s trial %d: Ke translation row %d dir %d", name, trial, r, k);
        kt_close(what, s, 0, 1e-11 * Kmax, 0);
      }
  }
  /* Stress-free reference. */
  double X[30];
  kt_random_tet(nen, 0.2, curve, X);
  fem_element_tl(t, X, X, m, NULL, NULL, 0, &out);
  snprintf(what, sizeof what, "%s: theta at reference", name);
  kt_close(what, out.theta, 1, 0, 1e-14);
  for (int c = 0; c < nd; c++) {
    snprintf(what, sizeof what, "%s: fe[%d] at reference", name, c);
    kt_close(what, out.fe[c], 0, 1e-13 * (fem_material_mu0(m) + m->kappa), 0); /* round-off in theta - 1 times kappa */
  }
  /* Inversion: mirror one corner through the opposite face plane (x -> -x of node 1). */
  double x[30];
  memcpy(x, X, sizeof x);
  for (int a = 0; a < nen; a++) x[3 * a] = -x[3 * a];
  if (fem_element_tl(t, X, x, m, NULL, NULL, 1, &out) != SA_ERR_INVERTED) {
    fprintf(stderr, "%s: mirrored element not reported as inverted\n", name);
    kt_fail++;
  }
  sa_error_clear();
}

/* Composite tet10 with the Mohr-Coulomb law: a compressed, sheared element from a virgin state,
 * yielding at every sub-tet (cohesion 1e-3 E, phi 30, psi 10). */
static void check_mc_composite(double curve)
{
  const char *nm[] = {"young", "poisson", "friction_angle", "cohesion", "dilation_angle"};
  double v[] = {1.0, 0.3, 30, 1e-3, 10};
  FemMaterial m;
  if (fem_material_from_law("mohr_coulomb", 5, nm, v, 1, &m)) {
    fprintf(stderr, "mohr_coulomb material: %s\n", sa_error_message());
    kt_fail++;
    return;
  }
  m.tet10_composite = 1;
  FemMohrCoulomb p = {1.0, 0.3, 30 * 3.14159265358979323846 / 180, 1e-3,
                      10 * 3.14159265358979323846 / 180, 0, 0};
  double hold[8 * FEM_MC_NHIST], hnew[8 * FEM_MC_NHIST], hs[8 * FEM_MC_NHIST];
  for (int q = 0; q < 8; q++) fem_mc_hist_init(&p, NULL, hold + q * FEM_MC_NHIST);
  char what[200];
  int done = 0;
  for (int trial = 0; trial < 12 && done < 3; trial++) {
    double X[30], x[30], F0[9];
    kt_random_tet(10, 0.2, curve, X);
    kt_random_F(0.05, 1, F0);
    for (int i = 0; i < 3; i++) F0[6 + i] *= 0.97; /* 3 % vertical compression */
    for (int a = 0; a < 10; a++)
      for (int i = 0; i < 3; i++)
        x[3 * a + i] = F0[3 * i] * X[3 * a] + F0[3 * i + 1] * X[3 * a + 1] +
                       F0[3 * i + 2] * X[3 * a + 2] + kt_rand(-0.005, 0.005);
    if (fem_element_tl(FEM_TET10, X, x, &m, hold, hnew, 1, &out)) {
      fprintf(stderr, "MC composite: fem_element_tl failed: %s\n", sa_error_message());
      kt_fail++;
      sa_error_clear();
      return;
    }
    int nyield = 0;
    for (int q = 0; q < 8; q++) nyield += hnew[q * FEM_MC_NHIST + 7] != FEM_MC_ELASTIC;
    /* the perturbed states must return to the same regions (FD across a kink is meaningless) */
    const int nd = 30;
    double h = 1e-7, Kmax = kt_maxabs(out.Ke, nd * nd), Kfd[900];
    int kink = 0;
    for (int c = 0; c < nd && !kink; c++) {
      double xs = x[c];
      x[c] = xs + h;
      fem_element_tl(FEM_TET10, X, x, &m, hold, hs, 0, &outp);
      for (int q = 0; q < 8; q++) kink |= hs[q * FEM_MC_NHIST + 7] != hnew[q * FEM_MC_NHIST + 7];
      x[c] = xs - h;
      fem_element_tl(FEM_TET10, X, x, &m, hold, hs, 0, &outm);
      for (int q = 0; q < 8; q++) kink |= hs[q * FEM_MC_NHIST + 7] != hnew[q * FEM_MC_NHIST + 7];
      x[c] = xs;
      for (int r = 0; r < nd; r++) Kfd[r * nd + c] = (outp.fe[r] - outm.fe[r]) / (2 * h);
    }
    if (kink || nyield < 8) continue;
    for (int c = 0; c < nd; c++)
      for (int r = 0; r < nd; r++) {
        snprintf(what, sizeof what, "MC composite curve %g trial %d: Ke[%d][%d] vs FD of fe",
                 curve, trial, r, c);
        kt_close(what, out.Ke[r * nd + c], Kfd[r * nd + c], 1e-6 * Kmax, 0);
      }
    done++;
  }
  if (done < 3) {
    fprintf(stderr, "MC composite curve %g: only %d of 12 draws yielded at all 8 points away from "
            "a region change\n", curve, done);
    kt_fail++;
  }
}

int main(void)
{
  const double mu = 1;
  FemMaterial laws[] = {
      {.kind = FEM_MAT_NEOHOOKE, .c10 = mu / 2, .kappa = 1000 * mu},
      {.kind = FEM_MAT_NEOHOOKE, .c10 = mu / 2, .kappa = 3 * mu},
      {.kind = FEM_MAT_MOONEY_RIVLIN, .c10 = 0.3, .c01 = 0.2, .kappa = 1000 * mu},
      {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 1000 * 0.22},
      fem_material_from_e_nu(2.6, 0.3, 1),
      {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 220, .mix_alpha = -1},
      {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 220, .mix_alpha = 50}};
  const char *names[] = {"neo-Hooke K/mu=1000", "neo-Hooke K/mu=3", "Mooney-Rivlin K/mu=1000",
                         "Yeoh K/mu=1000", "stiff E,nu", "Yeoh K/mu=1000 pure mean dilatation",
                         "Yeoh K/mu=1000 mix_alpha=50"};
  char name[120];
  for (int l = 0; l < 7; l++) {
    snprintf(name, sizeof name, "tet4 %s", names[l]);
    check(name, FEM_TET4, 0, &laws[l]);
    snprintf(name, sizeof name, "tet10 straight %s", names[l]);
    check(name, FEM_TET10, 0, &laws[l]);
    snprintf(name, sizeof name, "tet10 curved %s", names[l]);
    check(name, FEM_TET10, 0.05, &laws[l]);
    FemMaterial comp = laws[l];
    comp.tet10_composite = 1;
    snprintf(name, sizeof name, "tet10 composite straight %s", names[l]);
    check(name, FEM_TET10, 0, &comp);
    snprintf(name, sizeof name, "tet10 composite curved %s", names[l]);
    check(name, FEM_TET10, 0.05, &comp);
  }
  check_mc_composite(0);
  check_mc_composite(0.05);
  /* Degenerate reference element (node 3 in the plane of 0, 1, 2): a mesh error, not numerical. */
  double Xd[30];
  kt_random_tet(10, 0, 0, Xd);
  for (int a = 0; a < 10; a++) Xd[3 * a + 2] = 0;
  if (fem_element_tl(FEM_TET10, Xd, Xd, &laws[0], NULL, NULL, 1, &out) != SA_ERR_INPUT) {
    fprintf(stderr, "degenerate reference element not reported as SA_ERR_INPUT\n");
    kt_fail++;
  }
  sa_error_clear();
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
