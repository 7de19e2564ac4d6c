#!/bin/sh
# cook.sh - Cook's membrane (nearly incompressible neo-Hookean, plane strain, dead shear load
# F = 32 N) with CalculiX C3D20R / C3D20 (ccx_cook decks, structured n x n x 1 hex20) and our
# tet10 (cook_ours, n x n x 1 cells of 6 tets), at K/mu = 5000 (the classical benchmark,
# kappa = 400889.8 MPa) and K/mu = 500 (kappa = 500 mu, the actuator's ratio); mu = 80.194 MPa.
# Quantity: u_y of the corner (48, 60). Prints one table per K/mu: dof and u_y per element,
# the relative difference of each row from that element's Richardson limit (from its three
# finest meshes, observed order p = log2(d1/d2)), and C3D20R vs ours at the same n.
# Results and logs: BUILD/cook_runs (K<ratio>_ccx.txt, K<ratio>_ours.txt hold the raw numbers).
# Runs are sequential.
#
# usage: bench/fem/ccx/cook.sh [BUILD_DIR]      (default: /work/main/build-cook)
#   env: NS_CCX (default "2 4 8 16 32 64"), NS_OURS ("4 8 16 32 64"), RATIOS ("5000 500"),
#        ETYPES ("C3D20R C3D20"), CCX_TOL (R_n = C_n of ccx's *CONTROLS, default 1e-6),
#        RUN ("ccx ours": which codes to run; the others' results are reused),
#        TABLES_ONLY=1 (print the tables from the existing result files, run nothing)
set -eu
ROOT=$(cd "$(dirname "$0")/../../.." && pwd)
BUILD=${1:-$ROOT/build-cook}
NS_CCX=${NS_CCX:-"2 4 8 16 32 64"}
NS_OURS=${NS_OURS:-"4 8 16 32 64"}
RUN=${RUN:-"ccx ours"}
RATIOS=${RATIOS:-"5000 500"}
ETYPES=${ETYPES:-"C3D20R C3D20"}
CCX_TOL=${CCX_TOL:-1e-6}
WORK=$BUILD/cook_runs
MU=80.194
export OMP_NUM_THREADS=2
mkdir -p "$WORK"

now() { date +%s.%N; }

run_all() {
  cmake --build "$BUILD" --target ccx_cook cook_ours -j2 >/dev/null
  GEN=$BUILD/bench/fem/ccx/ccx_cook
  OURS=$BUILD/bench/fem/ccx/cook_ours
  case " $RUN " in *" ccx "*) CCX_ETYPES=$ETYPES ;; *) CCX_ETYPES="" ;; esac
  for R in $RATIOS; do
    # the classical benchmark's kappa (K/mu = 4999 to 4 digits), else kappa = R mu
    if [ "$R" = 5000 ]; then KOPT="--kappa 400889.8"; else KOPT="--kappa-ratio $R"; fi
    OUT=$WORK/K${R}_ccx.txt
    case " $RUN " in *" ccx "*) echo "# code element n dof u_y seconds extra" >"$OUT" ;; esac
    for E in $CCX_ETYPES; do
      for n in $NS_CCX; do
        base=K${R}_${E}_n$n
        line=$("$GEN" --n "$n" --out "$WORK/$base" --etype "$E" $KOPT --tol "$CCX_TOL")
        dof=$(echo "$line" | awk '{for (i = 1; i < NF; i++) if ($i == "dof") print $(i + 1)}')
        t0=$(now)
        (cd "$WORK" && ccx -i "$base" >"$base.log" 2>&1) || true
        t1=$(now)
        # last U block of N_A (first node: z = 0) and last clamp reaction total, with their times
        res=$(awk '
          /displacements \(vx,vy,vz\) for set N_A/ {tu = $NF; mode = 1; next}
          /total force \(fx,fy,fz\) for set N_CLAMP/ {tf = $NF; mode = 2; next}
          mode == 1 && NF == 4 {u = $3; mode = 0}
          mode == 2 && NF == 3 {fy = $2; mode = 0}
          END {printf "%s %s %s %s", tu, u, tf, fy}' "$WORK/$base.dat" 2>/dev/null || echo "0 nan 0 nan")
        set -- $res
        ok=$(awk -v t="$1" -v tf="$3" -v fy="$4" 'BEGIN {
          print (t + 0 > 0.999999 && tf + 0 > 0.999999 && (fy + 32 < 1e-4 && fy + 32 > -1e-4)) ? "ok" : "FAILED"}')
        sec=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f", b - a}')
        echo "ccx $E $n $dof $2 $sec RF_y=$4,$ok" >>"$OUT"
        echo "K/mu $R $E n $n dof $dof u_y $2 (${sec}s, clamp RF_y $4, $ok)" >&2
      done
    done
    OUT=$WORK/K${R}_ours.txt
    case " $RUN " in *" ours "*) echo "# code element n dof u_y seconds extra" >"$OUT" ;; *) continue ;; esac
    for n in $NS_OURS; do
      line=$("$OURS" --n "$n" $KOPT)
      echo "$line" | awk -v R="$R" '{
          for (i = 1; i < NF; i++) v[$i] = $(i + 1)
          printf "ours tet10 %s %s %s %s newton=%s\n", v["n"], v["dof"], v["uy"], v["wall_s"], v["newton"]}' >>"$OUT"
      echo "K/mu $R ours n $n: $line" >&2
    done
  done
}

tables() {
  for R in $RATIOS; do
    awk -v R="$R" -v mu="$MU" '
      /^#/ {next}
      {
        e = $2; n = $3
        if (!(e in seen)) {seen[e] = 1; order[++ne] = e}
        k = ++cnt[e]; N[e, k] = n; D[e, k] = $4; U[e, k] = $5; S[e, k] = $6; X[e, k] = $7
        un[e, n] = $5; nset[n] = 1
      }
      END {
        printf "\nK/mu = %s (mu = %s MPa, kappa = %s MPa): u_y of the corner (48, 60) [mm]\n", R, mu,
               R == 5000 ? "400889.8" : R * mu
        for (q = 1; q <= ne; q++) {
          e = order[q]; c = cnt[e]
          lim[e] = "nan"
          if (c >= 3) {
            d1 = U[e, c - 1] - U[e, c - 2]; d2 = U[e, c] - U[e, c - 1]
            if (d1 != 0 && d2 != 0 && d1 / d2 > 1) {
              p[e] = log(d1 / d2) / log(2); lim[e] = U[e, c] + d2 / (2 ^ p[e] - 1)
            }
          }
        }
        printf "%5s", "n"
        for (q = 1; q <= ne; q++) printf " | %-24s", order[q] " dof, u_y, vs limit"
        printf " | %s\n", "C3D20R/tet10-1"
        nn = 0
        for (n in nset) ns[++nn] = n + 0
        for (i = 1; i <= nn; i++) for (j = i + 1; j <= nn; j++) if (ns[j] < ns[i]) {t = ns[i]; ns[i] = ns[j]; ns[j] = t}
        for (i = 1; i <= nn; i++) {
          n = ns[i]; printf "%5d", n
          for (q = 1; q <= ne; q++) {
            e = order[q]; hit = 0
            for (k = 1; k <= cnt[e]; k++) if (N[e, k] == n) {
              rel = lim[e] == "nan" ? "    n/a" : sprintf("%+6.2f%%", 100 * (U[e, k] - lim[e]) / lim[e])
              printf " | %6d %9.6f %s", D[e, k], U[e, k], rel; hit = 1
            }
            if (!hit) printf " | %24s", "-"
          }
          if ((("C3D20R", n) in un) && (("tet10", n) in un))
            printf " | %+6.2f%%", 100 * (un["C3D20R", n] / un["tet10", n] - 1)
          printf "\n"
        }
        for (q = 1; q <= ne; q++) {
          e = order[q]
          if (lim[e] == "nan") printf "Richardson %-7s: not available (last three not monotone)\n", e
          else printf "Richardson %-7s (n = %d, %d, %d; order %.2f): %.5f\n", e, N[e, cnt[e] - 2],
                      N[e, cnt[e] - 1], N[e, cnt[e]], p[e], lim[e]
        }
        for (q = 1; q <= ne; q++) for (r = q + 1; r <= ne; r++) {
          a = order[q]; b = order[r]
          if (lim[a] != "nan" && lim[b] != "nan")
            printf "limit %s / limit %s - 1 = %+.3f%%\n", a, b, 100 * (lim[a] / lim[b] - 1)
        }
        printf "wall seconds:"
        for (q = 1; q <= ne; q++) { e = order[q]; printf " %s n=%d %ss;", e, N[e, cnt[e]], S[e, cnt[e]] }
        printf "\n"
      }' "$WORK/K${R}_ccx.txt" "$WORK/K${R}_ours.txt"
  done
}

if [ "${TABLES_ONLY:-0}" != 1 ]; then run_all; fi
tables
