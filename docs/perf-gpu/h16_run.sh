#!/bin/sh
# The H100 measurements of issue 16 (docs/perf-gpu.md), in one device call: the method comparison
# at 720p, 1080p and 4K, CPU time per frame with the lights set up on the CPU and on the GPU, and
# the fairy sprites drawn and splatted. Run from the checkout the run tool sends, with the carry
# folder made by make_carry.sh as $1 (default .carry-h16); results go to $OUT.
set -u
C=${1:-.carry-h16}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
B="bench --only methods --methods-forward-max"
{
$G $B 1024 --methods-sizes 1280x720 --methods-lights 16,256,1024,4096,16384,65536 --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 60 --out m720
$G $B 256 --methods-sizes 1920x1080 --methods-lights 256,4096,65536 --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 45 --out m1080
$G $B 256 --methods-sizes 3840x2160 --methods-lights 256,4096,65536 --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 60 --methods-culling-max 1e13 --out m4k
} > "$OUT/bench.log" 2>&1
for d in m720 m1080 m4k; do cp $d/bench.json "$OUT/$d.json"; done
R="render --frames 20 --stats"
{
for s in 1920x1080 3840x2160; do
  for m in clustered tiled; do
    for l in cpu gpu; do echo "== $s $m --light-setup $l"; $G $R --size $s --lights 65536 --method $m --light-setup $l -o /tmp/x.png; done
  done
  for f in raster compute; do echo "== $s clustered --fairy-splat $f"; $G $R --size $s --lights 65536 --method clustered --fairy-splat $f -o /tmp/x.png; done
  echo "== $s defaults"; $G $R --size $s --lights 65536 -o /tmp/x.png
done
$G render --size 1920x1080 --lights 4096 --fairy-splat raster -o "$OUT/fairy_raster.png"
$G render --size 1920x1080 --lights 4096 --fairy-splat compute -o "$OUT/fairy_compute.png"
} > "$OUT/renders.log" 2>&1
echo done
