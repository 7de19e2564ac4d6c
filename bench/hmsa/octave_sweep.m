## octave_sweep.m - the frequency sweep of the benchmark with an Octave solver: n_omega
## frequencies evenly spaced on [w_lo, w_hi], each started from rest, n_trans periods of
## transient and n_meas periods measured (default 140 + 40 = 180 forcing periods each, see
## hmsa_protocol.m); eta_bar = eta,
## c = 1, beta = 2, S = 0, b_a = 0.4, sgn = -1, atol = 1e-2 rtol.
## Writes out_csv: omega,a3,a,lambda,dlambda,xi,steps,nfevals,seconds,cpu and the last lines
## "# total_seconds=<tic/toc of the whole sweep>", "# total_cpu=<cputime of the whole sweep>".
function octave_sweep (out_csv, solver, rtol, eta, n_omega, w_lo, w_hi, n_trans, n_meas)
  if (nargin < 9)
    n_trans = 140;
    n_meas = 40;
  endif
  p = struct ("c", 1, "beta", 2, "eta", eta, "S", 0, "ba", 0.4, "sgn", -1, "omega", 0);
  atol = 1e-2 * rtol;
  omegas = linspace (w_lo, w_hi, n_omega);
  fid = fopen (out_csv, "w");
  fprintf (fid, "omega,a3,a,lambda,dlambda,xi,steps,nfevals,seconds,cpu\n");
  c_all = cputime ();
  t_all = tic;
  for w = omegas
    p.omega = w;
    c1 = cputime ();
    t1 = tic;
    [a3, a, yend, ns, nf] = hmsa_protocol (p, solver, rtol, atol, n_trans, n_meas, 128);
    el = toc (t1);
    fprintf (fid, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.6f,%.6f\n", w, a3, a, yend(1), ...
             yend(2), yend(3), ns, nf, el, cputime () - c1);
    fflush (fid);
  endfor
  total = toc (t_all);
  total_cpu = cputime () - c_all;
  fprintf (fid, "# total_seconds=%.6f\n# total_cpu=%.6f\n", total, total_cpu);
  fclose (fid);
  printf ("[octave] %s sweep of %d frequencies at rtol %g: %.2f s (cpu %.2f s)\n", solver, ...
          n_omega, rtol, total, total_cpu);
endfunction
