# resume_variant.sh - sourced by the FEM-DEM studies in bench/dem/: a poured bed, and one variant
# resumed from it. Uses EXE, CASE, OUT and D (bead diameter) of the calling script.
#   pour_bed BED STROKE key=value ...
# pours, settles and preloads a bed into OUT/BED and goes on over STROKE [m] (a checkpoint is
# written after the 5 preload steps); nothing is done when OUT/BED already has a checkpoint.
pour_bed() {
  pb_bed=$1; pb_stroke=$2; shift 2
  [ -f "$OUT/$pb_bed/checkpoint/state.ckpt" ] && return 0
  pb_sets=""
  for kv in "$@"; do pb_sets="$pb_sets --set $kv"; done
  # shellcheck disable=SC2086
  "$EXE" run $CASE --out "$OUT/$pb_bed" --set grains.diameter=$D --set piston.stroke=$pb_stroke \
    --set coupling.checkpoint_every=5 --set coupling.vtk_every=0 $pb_sets || true
}
#   resume_variant BED LABEL STROKE key=value ...
# copies OUT/BED (a run with a checkpoint after its preload) to OUT/LABEL and resumes it with
# the given keys over STROKE [m]; a variant with a summary.ini is kept (rerun = resume study).
resume_variant() {
  rv_bed=$1; rv_label=$2; rv_stroke=$3; shift 3
  [ -f "$OUT/$rv_label/summary.ini" ] && return 0
  rm -rf "${OUT:?}/$rv_label"
  cp -r "$OUT/$rv_bed" "$OUT/$rv_label"
  rm -f "$OUT/$rv_label/bending.csv" "$OUT/$rv_label/summary.ini"
  rv_sets=""
  for kv in "$@"; do rv_sets="$rv_sets --set $kv"; done
  # shellcheck disable=SC2086
  "$EXE" run $CASE --out "$OUT/$rv_label" --set grains.diameter=$D --set piston.stroke=$rv_stroke \
    --set coupling.vtk_every=0 --set coupling.checkpoint_every=0 --set coupling.resume=true \
    $rv_sets || true
}
