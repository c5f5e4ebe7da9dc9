# Issue 39, frames that overlap (renderer/frame/side_queue.h): the method bench with the visibility
# pass on the side queue (GBLENS_OVERLAP=auto, the default) and without (off), twice each,
# alternating, in one device call. Carry: docs/perf-gpu/h27_carry.sh build build-h27, this script
# copied into it with docs/perf-gpu/h39b/passes.py; run: sh build-h27/overlap_run.sh build-h27
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt
$G render builtin:temple --method clustered --lights 65536 --size 3840x2160 --frames 3 --stats -o /tmp/o.png > /tmp/render.json 2>&1
grep -A3 '"overlap"' /tmp/render.json > $OUT/summary.txt
for round in 1 2; do for M in off auto; do
  s=$(date +%s)
  GBLENS_OVERLAP=$M $G bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 \
    --methods-forward-max 0 --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 40 --methods-culling-max 0 \
    --out /tmp/b_$M$round > /tmp/${M}_$round.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> /tmp/${M}_$round.log
  { echo "== GBLENS_OVERLAP=$M round $round"; cat /tmp/${M}_$round.log; } >> $OUT/bench.log
  cp /tmp/b_$M$round/bench.json $OUT/${M}_$round.json
done; done
for f in $OUT/*_?.json; do echo "== $f"; python3 $C/passes.py $f; done >> $OUT/summary.txt
cat $OUT/summary.txt
