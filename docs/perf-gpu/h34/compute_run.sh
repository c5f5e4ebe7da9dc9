#!/bin/sh
# One device call (issue 34, this round): the attach bench with the application on the raster
# G-buffer (render-pass attachments; the compute sets followed for a pick by name) and on the
# visibility G-buffer (albedo, normals and eye depth written by compute, copied after its
# dispatches: app/layer/dispatch_copies.cpp), 1920x1080 and 3840x2160; the raster one again with
# GBLENS_LAYER_COMPUTE=0 with EXTRA=raster:0 (no dispatch copies: what following the compute sets costs). $1: the carry folder.
set -u
C=${1:-build-h27}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
{
echo "== the layer's log, raster 1080p"
GBLENS_LAYER_LOG=1 $G attach --layout builtin:gblens --frames 12 -- $G render builtin:temple --size 1920x1080 --frames 40 \
  --gbuffer raster -o /tmp/l.png 2>&1 | grep -E "sent|took" | head -8
for v in raster:1 visibility:1 ${EXTRA:-}; do g=${v%%:*}; c=${v##*:}
  for s in 1920x1080 3840x2160; do
    [ "$c" = 0 ] && [ "$s" = 3840x2160 ] && continue
    echo "== attach $g compute=$c $s"; GBLENS_LAYER_COMPUTE=$c $G bench --only attach --attach-gbuffer $g --attach-size $s \
      --attach-frames 120 --attach-rounds 5 --attach-soak 100 --out /tmp/a_${g}_${c}_$s > /dev/null 2>&1; echo "rc $?"
    cp /tmp/a_${g}_${c}_$s/bench.json $OUT/attach_${g}_${c}_$s.json
  done
done
} > "$OUT/compute.log" 2>&1
echo done
