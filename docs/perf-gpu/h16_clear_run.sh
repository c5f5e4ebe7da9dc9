#!/bin/sh
# Issue 16: the G-buffer cleared in compute (clear_gbuffer) against the render pass's clears,
# A/B/A/B on the H100, gblens bench --only methods (every method, pass times, GPU time).
# MODES="render-pass compute" (the default) or "render-pass auto"; results in $OUT.
set -u
C=${1:-.carry-h18}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
for i in 1 2; do for mode in ${MODES:-render-pass compute}; do
  for cfg in "1920x1080 256" "3840x2160 65536"; do
    set -- $cfg; n=clear_${mode}_${1}_${2}_$i; s=$(date +%s)
    $C/gblens-clear bench --only methods --methods-sizes $1 --methods-lights $2 --methods-forward-max 0 \
      --methods-culling-max 0 --methods-rounds 3 --methods-min-rounds 3 --methods-seconds 20 --gbuffer-clear $mode \
      --out $n > $n.log 2>&1
    echo "$n rc $? in $(( $(date +%s) - s )) s" >> "$OUT/clear_index.txt"; cp "$n/bench.json" "$OUT/$n.json" 2>/dev/null
  done
done; done
echo done
