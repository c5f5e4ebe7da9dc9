#!/bin/sh
# Issue 34, the staged ring's tile images (docs/attach.md "Cost"): `gblens bench --only attach` at
# 1920x1080 and 3840x2160 with the attachments copied image to image (the default) and, in the
# same device call, into the device buffer as before (GBLENS_LAYER_TILES=0). $1: the carry folder
# made by docs/perf-gpu/h27_carry.sh. Writes $OUT/{tiles,buffer}_{1080,4k}.json and the log.
set -u
C=${1:-build-h27}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
run() {  # name, GBLENS_LAYER_TILES, then bench flags
  n=$1; t=$2; shift 2
  echo "== $n (GBLENS_LAYER_TILES=$t): $*"; s=$(date +%s)
  GBLENS_LAYER_TILES=$t $G bench --only attach "$@" --out "/tmp/$n"; echo "rc $? in $(( $(date +%s) - s )) s"
  cp "/tmp/$n/bench.json" "$OUT/$n.json" 2>/dev/null
}
{
for k in 1 2; do
run tiles_1080_$k 1 --attach-size 1920x1080 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak 200
run buffer_1080_$k 0 --attach-size 1920x1080 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak 200
done
run tiles_4k 1 --attach-size 3840x2160 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak 100
run buffer_4k 0 --attach-size 3840x2160 --attach-frames ${FRAMES:-120} --attach-rounds ${ROUNDS:-5} --attach-soak 100
} > "$OUT/tiles_bench.log" 2>&1
echo done
