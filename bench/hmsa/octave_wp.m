## octave_wp.m - work-precision runs of one Octave solver on the benchmark protocol at one
## forcing frequency (see hmsa_protocol.m), one run per tolerance, timed with tic/toc.
##   out_csv  output file: solver,eta,omega,rtol,atol,seconds,a3,a,lambda,dlambda,xi,steps,nfevals
##   solver   "ode45" or "ode15s";  eta  eta_bar;  omega  Omega;  rtols  row vector
##   n_trans, n_meas  forcing periods of transient and of measurement (128 samples per period)
## atol = 1e-2 rtol, as in hmsa_bench.c. Other parameters: c = 1, beta = 2, S = 0, b_a = 0.4,
## sgn = -1 (the seed's resonance case, docs/hmsa_model.md section 8).
function octave_wp (out_csv, solver, eta, omega, rtols, n_trans, n_meas)
  p = struct ("c", 1, "beta", 2, "eta", eta, "S", 0, "ba", 0.4, "sgn", -1, "omega", omega);
  fid = fopen (out_csv, "w");
  fprintf (fid, "solver,eta,omega,rtol,atol,seconds,a3,a,lambda,dlambda,xi,steps,nfevals\n");
  for rtol = rtols
    atol = 1e-2 * rtol;
    tic;
    [a3, a, yend, ns, nf] = hmsa_protocol (p, solver, rtol, atol, n_trans, n_meas, 128);
    el = toc;
    fprintf (fid, "%s,%.17g,%.17g,%.3g,%.3g,%.6f,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n", ...
             solver, eta, omega, rtol, atol, el, a3, a, yend(1), yend(2), yend(3), ns, nf);
    fflush (fid);
    printf ("[octave] %s eta %g omega %g rtol %g: %.2f s, %d steps\n", solver, eta, omega, ...
            rtol, el, ns);
    fflush (stdout);
  endfor
  fclose (fid);
endfunction
