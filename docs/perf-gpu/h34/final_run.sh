#!/bin/sh
# One device call (this round, issues 34 and 39): the attach bench with the staged ring's tiles and
# without (GBLENS_LAYER_TILES=0), the application on the raster G-buffer; then the clustered
# lighting pass with one and two pixels an invocation (GBLENS_LIGHTING_PIXELS=1|2), alternating,
# `gblens render --stats` at 1920x1080 and 3840x2160 with 65536 lights. $1: the carry folder.
set -u
C=${1:-build-h27}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
{
for v in tiles:1 buffer:0; do n=${v%%:*}; t=${v##*:}
  for s in 1920x1080 3840x2160; do
    echo "== attach $n $s"; GBLENS_LAYER_TILES=$t $G bench --only attach --attach-size $s --attach-frames 120 --attach-rounds 5 \
      --attach-soak 100 --out /tmp/a_${n}_$s > /dev/null 2>&1; echo "rc $?"; cp /tmp/a_${n}_$s/bench.json $OUT/attach_${n}_$s.json
  done
done
for r in 1 2 3; do for s in 1920x1080 3840x2160; do for p in 1 2; do
  echo "== lighting pixels=$p $s round $r"
  GBLENS_LIGHTING_PIXELS=$p $G render builtin:temple --method clustered --lights 65536 --size $s --frames 60 --stats \
    -o /tmp/l.png > $OUT/light_${p}_${s}_$r.json 2>/dev/null; echo "rc $?"
done; done; done
} > "$OUT/final.log" 2>&1
echo done
