## hmsa_rhs.m - right-hand side of the dimensionless Zener HMSA model, written directly from
## the model specification (docs/hmsa_model.md, section 5), independently of hmsa/hmsa_model.c:
##   (1 + 2 c l^-6) l'' - 6 c l^-7 l'^2 + 3 F = 0                                   (E1)
##   xi' = k (l^2 xi^-3 - l^-4 xi^3),  k = 2 beta / eta_bar                          (E2)
##   F = (l - l^-5) + beta (l xi^-2 - l^-5 xi^4) - S + b2(tau) l^-3
##   b2(tau) = sgn b_a^2 sin^2(Omega tau)                          (the `sq` loading)
## State y = [lambda; lambda'; xi]. p: struct with fields c, beta, eta, S, ba, sgn, omega.
function dy = hmsa_rhs (t, y, p)
  l = y(1);
  lp = y(2);
  xi = y(3);
  s = sin (p.omega * t);
  b2 = p.sgn * p.ba * p.ba * s * s;
  l2 = l * l;
  l3 = l2 * l;
  l5 = l3 * l2;
  l6 = l3 * l3;
  xi2 = xi * xi;
  F = (l - 1 / l5) + p.beta * (l / xi2 - xi2 * xi2 / l5) - p.S + b2 / l3;
  lpp = (6 * p.c / (l6 * l) * lp * lp - 3 * F) / (1 + 2 * p.c / l6);
  xip = (2 * p.beta / p.eta) * (l2 / (xi2 * xi) - xi2 * xi / (l2 * l2));
  dy = [lp; lpp; xip];
endfunction
