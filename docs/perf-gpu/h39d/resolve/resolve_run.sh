# Issue 39 (measured, then reverted): gbuffer_resolve in the side part (beside the previous frame, its targets one image per slot)
# against the binary before it (gblens_prev: gbuffer_resolve in the compute part),
# GBLENS_OVERLAP=auto, two rounds alternating, one device call. Carry: docs/perf-gpu/h27_carry.sh build
# build-h27, the earlier binary copied in as build-h27/gblens_prev, this script and
# docs/perf-gpu/h39b/passes.py beside it; run: sh build-h27/resolve_run.sh build-h27
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt
for round in 1 2; do for B in gblens_prev gblens; do
  s=$(date +%s)
  $C/$B bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 \
    --methods-forward-max 0 --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 40 --methods-culling-max 0 \
    --out /tmp/b_$B$round > /tmp/${B}_$round.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> /tmp/${B}_$round.log
  { echo "== $B round $round"; cat /tmp/${B}_$round.log; } >> $OUT/resolve_bench.log
  cp /tmp/b_$B$round/bench.json $OUT/resolve_${B}_$round.json
done; done
for f in $OUT/resolve_*.json; do echo "== $f"; python3 $C/passes.py $f; done > $OUT/resolve_summary.txt
grep -E '^==|frame' $OUT/resolve_summary.txt
