## octave_wp.m - work-precision runs of one Octave solver on the benchmark protocol at one
## forcing frequency (see hmsa_protocol.m), one run per tolerance, timed with tic/toc.
##   out_csv  output file: solver,eta,omega,rtol,atol,seconds,a3,a,lambda,dlambda,xi,steps,nfevals,
##            cpu (seconds: tic/toc wall time; cpu: cputime of the Octave process)
##   solver   "ode45" or "ode15s";  eta  eta_bar;  omega  Omega;  rtols  row vector
##   n_trans, n_meas  forcing periods of transient and of measurement (128 samples per period)
## atol = 1e-2 rtol, as in hmsa_bench.c. Other parameters: c = 1, beta = 2, S = 0, b_a = 0.4,
## sgn = -1 (the seed's resonance case, docs/hmsa_model.md section 8).
function octave_wp (out_csv, solver, eta, omega, rtols, n_trans, n_meas)
  p = struct ("c", 1, "beta", 2, "eta", eta, "S", 0, "ba", 0.4, "sgn", -1, "omega", omega);
  fid = fopen (out_csv, "w");
  fprintf (fid, "solver,eta,omega,rtol,atol,seconds,a3,a,lambda,dlambda,xi,steps,nfevals,cpu\n");
  for rtol = rtols
    atol = 1e-2 * rtol;
    c0 = cputime ();
    tic;
    [a3, a, yend, ns, nf] = hmsa_protocol (p, solver, rtol, atol, n_trans, n_meas, 128);
    el = toc;
    cpu = cputime () - c0;
    fprintf (fid, "%s,%.17g,%.17g,%.3g,%.3g,%.6f,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.6f\n", ...
             solver, eta, omega, rtol, atol, el, a3, a, yend(1), yend(2), yend(3), ns, nf, cpu);
    fflush (fid);
    printf ("[octave] %s eta %g omega %g rtol %g: %.2f s (cpu %.2f s), %d steps\n", solver, eta, ...
            omega, rtol, el, cpu, ns);
    fflush (stdout);
  endfor
  fclose (fid);
endfunction
