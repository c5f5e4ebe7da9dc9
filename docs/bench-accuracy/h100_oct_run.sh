#!/bin/sh
# Issue 18: the G-buffer pass's GPU time with octahedral nearest vs precise encoding on the H100,
# A/B/A/B, 1080p and 4K, 256 lights, clustered (auto). Writes oct_*.json and the log to $OUT.
set -u
C=${1:-.carry-h18}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
{
for i in 1 2; do for e in nearest precise; do
  n=oct_${e}_$i; echo "== $n"; s=$(date +%s)
  $G bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256 --methods-forward-max 0 \
    --methods-culling-max 0 --methods-rounds 3 --methods-min-rounds 3 --methods-seconds 20 --oct-encoding $e --out $n
  echo "rc $? in $(( $(date +%s) - s )) s"; cp "$n/bench.json" "$OUT/$n.json" 2>/dev/null
done; done
} > "$OUT/oct_bench.log" 2>&1
echo done
