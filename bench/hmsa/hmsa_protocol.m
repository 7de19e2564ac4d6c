## hmsa_protocol.m - one forcing frequency of the benchmark protocol, from rest:
## integrate n_trans forcing periods of transient, then n_meas periods sampled at n_per points
## per period (dense output of the solver at the requested times); the steady amplitudes are
##   a3 = (max lambda3 - min lambda3)/2,  lambda3 = lambda^-2,   a = (max lambda - min lambda)/2
## (docs/hmsa_model.md section 7). The same protocol is implemented in hmsa_bench.c.
##   p       model parameters (see hmsa_rhs.m)
##   solver  "ode45" or "ode15s"
##   rtol, atol  tolerances
## Returns a3, a, the state at the final time, accepted steps and RHS evaluations.
function [a3, a, yend, nsteps, nfevals] = hmsa_protocol (p, solver, rtol, atol, n_trans, n_meas, n_per)
  T = 2 * pi / p.omega;
  tspan = [0, n_trans * T + (0:n_meas * n_per) * (T / n_per)];
  if (strcmp (solver, "ode15s"))
    ## Octave's ode15s (SUNDIALS IDA) stops after 500 steps between two output times and
    ## offers no option to raise that: give it output times every quarter period during the
    ## transient (discarded below; ode45 does not need them).
    tspan = [(0:4 * n_trans - 1) * (T / 4), tspan(2:end)];
  endif
  opts = odeset ("RelTol", rtol, "AbsTol", atol, "Stats", "on");
  f = @(t, y) hmsa_rhs (t, y, p);
  if (strcmp (solver, "ode15s"))
    opts = odeset (opts, "Jacobian", @(t, y) hmsa_jac (t, y, p));
  endif
  y0 = [1; 0; 1];
  txt = evalc ("[t, y] = feval (solver, f, tspan, y0, opts);");
  l = y(end - n_meas * n_per:end, 1);
  l3 = l .^ -2;
  a3 = (max (l3) - min (l3)) / 2;
  a = (max (l) - min (l)) / 2;
  yend = y(end, :);
  nsteps = NaN;
  nfevals = NaN;
  tok = regexp (txt, "successful steps:\\s*(\\d+)", "tokens");
  if (! isempty (tok))
    nsteps = str2double (tok{1}{1});
  endif
  tok = regexp (txt, "function calls:\\s*(\\d+)", "tokens");
  if (! isempty (tok))
    nfevals = str2double (tok{1}{1});
  endif
endfunction
