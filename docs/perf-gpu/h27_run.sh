#!/bin/sh
# The H100 measurement of issue 27 (docs/attach.md): `gblens bench --only attach` at 1920x1080 and
# 3840x2160 (gblens render builtin:temple attached: without the layer, idle, streaming four targets
# every frame and every 4th), in one device call, with the carry folder made by h27_carry.sh as $1.
# Every bench.json and the log go to $OUT as h27_*.json and h27_bench.log.
set -u
C=${1:-build-h27}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
run() {  # name, then bench flags
  n=$1; shift
  echo "== $n: $*"; s=$(date +%s)
  $G bench --only attach "$@" --out "$n"; echo "rc $? in $(( $(date +%s) - s )) s"
  cp "$n/bench.json" "$OUT/h27_$n.json" 2>/dev/null
}
{
run a1080 --attach-size 1920x1080 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak ${SOAK:-2000}
run a4k --attach-size 3840x2160 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak 200
} > "$OUT/h27_bench.log" 2>&1
echo done
