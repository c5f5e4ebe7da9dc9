#!/bin/sh
# Issue 16: what the GPU time between passes (~0.95 ms at 1080p on the H100) depends on.
set -u
C=${1:-.carry-h18}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
i=0
for flags in "" "--primitive-id on" "--position rgba32f" "--accum-format rgba16f" "--fairies off" "--sky off" \
             "--normal-format rgba8-snorm" "--eye-depth off" "--depth-format d24s8" "--path single-pass" "--fairies off --sky off --accum-format rgba16f"; do
  i=$((i+1)); n=gap_$i
  echo "$n: $flags" >> "$OUT/gap_index.txt"
  $C/gblens-sky bench --only methods --methods-sizes 1920x1080 --methods-lights 256 --methods-forward-max 0 \
    --methods-culling-max 0 --methods-rounds 3 --methods-min-rounds 3 --methods-seconds 10 $flags --out $n > $n.log 2>&1
  cp "$n/bench.json" "$OUT/$n.json" 2>/dev/null
done
echo done
