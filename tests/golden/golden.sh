#!/bin/sh
# Golden captures of builtin:temple: the first line of defence for every change to the renderer.
#
#   tests/golden/golden.sh check      GBLENS WORKDIR   capture now, compare with tests/golden/temple
#   tests/golden/golden.sh perturbed  GBLENS WORKDIR   deliberately changed frames must be caught
#   tests/golden/golden.sh visibility GBLENS WORKDIR   --gbuffer visibility within the same thresholds
#   tests/golden/golden.sh regenerate GBLENS           rewrite tests/golden/temple (after an intended change)
#
# Thresholds (docs/capture-format.md, "Golden captures", says why):
#   warn at any difference; fail where a pixel moves by more than about one step of its
#   target's storage format, on more than 0.1% of the pixels (14 of 14400).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
MODE=$1
GBLENS=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
CAPTURE="capture builtin:temple --size 160x90 --lights 16 --time 2.5 --shadow-map-size 256 --validate"
THRESHOLDS="--warn 0 --failpercent 0.1 --fail 0.004 --fail hdr=0.01 --fail normal_shadow.Normal=0.1
  --fail normal_shadow.Shadow=0.004 --fail depth=1e-6 --fail depth_stencil.HardwareDepth=1e-6 --fail shadow_map=1e-6
  --fail depth_stencil.Stencil=0 --fail coverage_masked=0 --fail coverage_full=0"

case "$MODE" in
regenerate)
  cd "$HERE"
  "$GBLENS" $CAPTURE -o temple
  du -sh temple
  ;;
check)
  WORK=$3
  mkdir -p "$WORK"
  "$GBLENS" $CAPTURE -o "$WORK/temple"
  status=0
  "$GBLENS" compare "$HERE/temple" "$WORK/temple" $THRESHOLDS -o "$WORK/diff" --json "$WORK/report.json" || status=$?
  case $status in
  0) echo "golden: identical to tests/golden/temple" ;;
  1) echo "golden: WARNING: differs from tests/golden/temple within the thresholds (see above)" ;;
  *) echo "golden: FAILED (exit $status); heat maps in $WORK/diff; if the change is intended:"
     echo "  tests/golden/golden.sh regenerate $GBLENS"
     exit 1 ;;
  esac
  ;;
visibility)
  # The visibility buffer's G-buffer (docs/architecture.md) against the raster golden: warnings
  # (one albedo step on textured pixels, normals and depth within rounding) but no failure; its
  # own visibility target is not in the golden.
  WORK=$3
  mkdir -p "$WORK"
  "$GBLENS" $CAPTURE --gbuffer visibility -o "$WORK/visibility"
  status=0
  "$GBLENS" compare "$HERE/temple" "$WORK/visibility" --exclude visibility $THRESHOLDS -q || status=$?
  echo "golden: --gbuffer visibility -> exit $status (0 or 1 expected)"
  [ "$status" -le 1 ]
  ;;
perturbed)
  # Each line: expected exit status, then the options that perturb the frame.
  WORK=$3
  mkdir -p "$WORK"
  failed=0
  while read -r expected options; do
    [ -z "$expected" ] && continue
    "$GBLENS" $CAPTURE $options -o "$WORK/perturbed" </dev/null 2>/dev/null
    status=0
    "$GBLENS" compare "$HERE/temple" "$WORK/perturbed" $THRESHOLDS -q </dev/null || status=$?
    if [ "$status" -eq "$expected" ]; then
      echo "golden: $options -> exit $status, as expected"
    else
      echo "golden: $options -> exit $status, expected $expected"
      failed=1
    fi
  done <<LIST
1 --eye-depth off
2 --time 2.51
2 --stencil-mask shared
3 --shadow-map-size 512
LIST
  exit $failed
  ;;
*)
  echo "usage: golden.sh check|perturbed|visibility GBLENS WORKDIR | golden.sh regenerate GBLENS" >&2
  exit 2
  ;;
esac
