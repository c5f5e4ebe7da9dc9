#!/bin/sh
# The H100 measurements of issue 16 (docs/perf-gpu.md), in one device call: the method comparison
# (deferred, unculled, forward, tiled, clustered) at 720p, 1080p and 4K, and at 1080p/4K with 65536
# lights the same comparison with the lights set up on the CPU and with the fairy sprites drawn
# (rasterized) instead of splatted, for the CPU ms per frame and the fairy pass. Run from the
# checkout the run tool sends, with the carry folder made by make_carry.sh as $1 (default
# .carry-h16); every bench.json and the log go to $OUT as $PREFIX_NAME.json (PREFIX default h16).
# RUNS names the runs (default the first five; h16_retable_run.sh: the main table only;
# h16_inflight_run.sh: frames in flight). EXTRA flags go to every run. (`render` is not
# used: it writes a PNG through OpenImageIO, which the carry folder only stubs.)
set -u
C=${1:-.carry-h16}
for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
OUT=${OUT:-/tmp/out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/device.txt" 2>&1
B="bench --only methods"
P=${PREFIX:-h16}
RUNS=${RUNS:-m720 m1080 m4k setup_cpu fairy_raster}
run() {  # name, then bench flags
  n=$1; shift
  case " $RUNS " in *" $n "*) ;; *) return ;; esac
  echo "== $n: $*"; s=$(date +%s)
  $G $B "$@" ${EXTRA:-} --out "$n"; echo "rc $? in $(( $(date +%s) - s )) s"
  cp "$n/bench.json" "$OUT/${P}_$n.json" 2>/dev/null
}
{
run m720 --methods-sizes 1280x720 --methods-lights 16,256,1024,4096,16384,65536 --methods-forward-max 1024 \
  --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 60
run m1080 --methods-sizes 1920x1080 --methods-lights 256,4096,65536 --methods-forward-max 4096 \
  --methods-rounds 5 --methods-min-rounds 3 --methods-seconds 45
run m4k --methods-sizes 3840x2160 --methods-lights 256,4096,65536 --methods-forward-max 256 \
  --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 60 --methods-culling-max 1e13
run setup_cpu --methods-sizes 1920x1080,3840x2160 --methods-lights 65536 --methods-forward-max 0 \
  --methods-rounds 2 --methods-min-rounds 2 --methods-seconds 20 --methods-culling-max 0 --light-setup cpu
run fairy_raster --methods-sizes 1920x1080,3840x2160 --methods-lights 65536 --methods-forward-max 0 \
  --methods-rounds 2 --methods-min-rounds 2 --methods-seconds 20 --methods-culling-max 0 --fairy-splat raster
# Named only (not in the default RUNS): clustered with the cluster grid filled on the CPU, and the
# raster tone map, against the defaults of the same cells (h16_inflight_run.sh).
run grid --methods-sizes 1920x1080,3840x2160 --methods-lights 256,4096 --methods-forward-max 0 \
  --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 30 --methods-culling-max 0 --cluster-assign cpu
run tonemap_raster --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 --methods-forward-max 0 \
  --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 30 --methods-culling-max 0 --tonemap-pass raster
} > "$OUT/${P}_bench.log" 2>&1
echo done
