# Issue 39, an experiment (not in the tree): images VK_SHARING_MODE_EXCLUSIVE instead of CONCURRENT
# over the graphics and compute families (a binary built with GBLENS_EXP_EXCLUSIVE read in
# renderer/vk/resources.cpp createImage, without the ownership transfers EXCLUSIVE needs: timing
# only, its images are not checked), GBLENS_OVERLAP=auto, against CONCURRENT, two rounds
# alternating, one device call. Does sharing an image between two families cost the raster passes
# (compression) and the hand-over between frames? Carry: docs/perf-gpu/h27_carry.sh build build-h27
# with that binary, this script and docs/perf-gpu/h39b/passes.py; run: sh build-h27/exclusive_run.sh build-h27
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt
for round in 1 2; do for E in concurrent exclusive; do
  s=$(date +%s)
  if [ $E = exclusive ]; then export GBLENS_EXP_EXCLUSIVE=1; else unset GBLENS_EXP_EXCLUSIVE; fi
  $C/gblens bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 \
    --methods-forward-max 0 --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 40 --methods-culling-max 0 \
    --out /tmp/b_$E$round > /tmp/${E}_$round.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> /tmp/${E}_$round.log
  { echo "== $E round $round"; cat /tmp/${E}_$round.log; } >> $OUT/exclusive_bench.log
  cp /tmp/b_$E$round/bench.json $OUT/exclusive_${E}_$round.json
done; done
for f in $OUT/exclusive_*.json; do echo "== $f"; python3 $C/passes.py $f; done > $OUT/exclusive_summary.txt
grep -E '^==|frame|visibility' $OUT/exclusive_summary.txt | cut -c1-400
