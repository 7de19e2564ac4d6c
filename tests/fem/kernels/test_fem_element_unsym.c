/* test_fem_element_unsym.c - the general (unsymmetric-material) tangent path of fem_element_tl,
 * which a non-associated plasticity law will take. No such law exists yet, so this test compiles
 * the element source with fem_material_symmetric() replaced by a stub returning 0: every block
 * (a, b) of B^T A B is then computed instead of mirrored. For hyperelastic laws the result must
 * still match central FD of fe and be symmetric (same tolerances as test_fem_element_fd). */
#define fem_material_symmetric kt_material_never_symmetric
#include "../../../fem/fem_element.c"
#undef fem_material_symmetric

#include <stdio.h>

#include "kt_util.h"

int kt_material_never_symmetric(const FemMaterial *m)
{
  (void)m;
  return 0;
}

static FemElemOut out, outp, outm;

int main(void)
{
  FemMaterial laws[2] = {{.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 220},
                         {.kind = FEM_MAT_MOONEY_RIVLIN, .c10 = 0.3, .c01 = 0.2, .kappa = 3}};
  char what[160];
  for (int l = 0; l < 2; l++)
    for (int nen = 4; nen <= 10; nen += 6)
      for (int cv = 0; cv < 2; cv++) {
        FemElemType t = nen == 4 ? FEM_TET4 : FEM_TET10;
        int nd = 3 * nen;
        double X[30], x[30], F0[9], h = 1e-6;
        kt_random_tet(nen, 0.2, cv ? 0.05 : 0, X);
        kt_random_F(0.2, kt_rand(0.8, 1.3), F0);
        for (int a = 0; a < nen; a++)
          for (int i = 0; i < 3; i++)
            x[3 * a + i] = F0[3 * i] * X[3 * a] + F0[3 * i + 1] * X[3 * a + 1] +
                           F0[3 * i + 2] * X[3 * a + 2] + kt_rand(-0.03, 0.03);
        if (fem_element_tl(t, X, x, &laws[l], NULL, NULL, 1, &out)) {
          fprintf(stderr, "element failed: %s\n", sa_error_message());
          kt_fail++;
          continue;
        }
        double Kmax = kt_maxabs(out.Ke, nd * nd);
        for (int c = 0; c < nd; c++) {
          double xs = x[c];
          x[c] = xs + h;
          fem_element_tl(t, X, x, &laws[l], NULL, NULL, 0, &outp);
          x[c] = xs - h;
          fem_element_tl(t, X, x, &laws[l], NULL, NULL, 0, &outm);
          x[c] = xs;
          for (int r = 0; r < nd; r++) {
            snprintf(what, sizeof what, "unsym path law %d tet%d curved %d: Ke[%d][%d] vs FD", l,
                     nen, cv, r, c);
            kt_close(what, out.Ke[r * nd + c], (outp.fe[r] - outm.fe[r]) / (2 * h), 1e-6 * Kmax, 0);
            snprintf(what, sizeof what, "unsym path law %d tet%d curved %d: symmetry", l, nen, cv);
            kt_close(what, out.Ke[r * nd + c], out.Ke[c * nd + r], 1e-12 * Kmax, 0);
          }
        }
      }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
