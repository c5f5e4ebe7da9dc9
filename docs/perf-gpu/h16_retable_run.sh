#!/bin/sh
# The main method table of docs/perf-gpu.md re-measured after the G-buffer clears moved to compute
# (same cells and budgets as h16_run.sh's m720, m1080 and m4k; carry folder as $1); bench.json of
# each run and the log go to $OUT as retable_*.json.
set -u
C=${1:-.carry-h16}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
run() {  # name, then bench flags
  n=$1; shift
  echo "== $n: $*"; s=$(date +%s)
  $G bench --only methods "$@" --out "$n"; echo "rc $? in $(( $(date +%s) - s )) s"
  cp "$n/bench.json" "$OUT/retable_$n.json" 2>/dev/null
}
{
run m720 --methods-sizes 1280x720 --methods-lights 16,256,1024,4096,16384,65536 --methods-forward-max 1024 \
  --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 60
run m1080 --methods-sizes 1920x1080 --methods-lights 256,4096,65536 --methods-forward-max 4096 \
  --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 45
run m4k --methods-sizes 3840x2160 --methods-lights 256,4096,65536 --methods-forward-max 256 \
  --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 60 --methods-culling-max 1e13
} > "$OUT/retable_bench.log" 2>&1
echo done
