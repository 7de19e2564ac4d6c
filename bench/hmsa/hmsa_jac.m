## hmsa_jac.m - analytic Jacobian d f / d y of hmsa_rhs.m (for Octave's implicit solvers),
## derived by hand from the same equations (E1)-(E2).
function J = hmsa_jac (t, y, p)
  l = y(1);
  lp = y(2);
  xi = y(3);
  s = sin (p.omega * t);
  b2 = p.sgn * p.ba * p.ba * s * s;
  F = (l - l^-5) + p.beta * (l * xi^-2 - l^-5 * xi^4) - p.S + b2 * l^-3;
  dF_dl = 1 + 5 * l^-6 + p.beta * (xi^-2 + 5 * l^-6 * xi^4) - 3 * b2 * l^-4;
  dF_dxi = p.beta * (-2 * l * xi^-3 - 4 * l^-5 * xi^3);
  M = 1 + 2 * p.c * l^-6;
  N = 6 * p.c * l^-7 * lp^2 - 3 * F;          # lpp = N / M
  dM_dl = -12 * p.c * l^-7;
  dN_dl = -42 * p.c * l^-8 * lp^2 - 3 * dF_dl;
  k = 2 * p.beta / p.eta;
  J = zeros (3, 3);
  J(1, 2) = 1;
  J(2, 1) = (dN_dl * M - N * dM_dl) / M^2;
  J(2, 2) = 12 * p.c * l^-7 * lp / M;
  J(2, 3) = -3 * dF_dxi / M;
  J(3, 1) = k * (2 * l * xi^-3 + 4 * l^-5 * xi^3);
  J(3, 3) = k * (-3 * l^2 * xi^-4 - 3 * l^-4 * xi^2);
endfunction
