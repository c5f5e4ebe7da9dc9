#!/bin/sh
# Issue 16: the sky written by the compute lighting passes (gblens-sky) against the skybox raster
# pass (gblens), A/B/A/B, tiled and clustered at 1920x1080/256 and 3840x2160/65536 on the H100.
set -u
C=${1:-.carry-h18}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
{
for i in 1 2; do for b in gblens gblens-sky; do
  for cfg in "1920x1080 256" "3840x2160 65536"; do
    set -- $cfg; n=sky_${b}_${1}_${2}_$i; echo "== $n"; s=$(date +%s)
    $C/$b bench --only methods --methods-sizes $1 --methods-lights $2 --methods-forward-max 0 \
      --methods-culling-max 0 --methods-rounds 3 --methods-min-rounds 3 --methods-seconds 20 --out $n > /dev/null 2>&1
    echo "rc $? in $(( $(date +%s) - s )) s"; cp "$n/bench.json" "$OUT/$n.json" 2>/dev/null
  done
done; done
} > "$OUT/sky_bench.log" 2>&1
echo done
