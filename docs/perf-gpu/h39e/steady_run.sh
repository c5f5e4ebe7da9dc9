# Issue 39, the frame's steady state (FrameBurst::steadyMs, bench.json steady_ms): the method bench
# with the frames overlapping (GBLENS_OVERLAP=auto, the default) with the default burst of 6 frames
# and with 24, and not overlapping (off, burst 6), in one device call: the bursts' wall throughput
# (frame_ms, with the pipeline's fill over burst - 1) against the GPU clock between frame ends
# (steady_ms); RUNS="auto_6 auto_24" picks. Results in $OUT: device.txt, bench.log, summary.txt, {auto,off}_{6,24}.json.
# Carry: docs/perf-gpu/h27_carry.sh build build-h27, this script and docs/perf-gpu/h39b/passes.py
# copied into it; run: sh build-h27/steady_run.sh build-h27
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt
for run in ${RUNS:-auto_6 auto_24 off_6}; do M=${run%_*}; B=${run#*_}
  s=$(date +%s)
  GBLENS_OVERLAP=$M $G bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 \
    --methods-forward-max 0 --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 40 --methods-culling-max 0 \
    --methods-burst $B --out /tmp/b_${M}_$B > /tmp/${M}_$B.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> /tmp/${M}_$B.log
  { echo "== GBLENS_OVERLAP=$M burst $B"; cat /tmp/${M}_$B.log; } >> $OUT/bench.log
  cp /tmp/b_${M}_$B/bench.json $OUT/${M}_$B.json
done
for f in $OUT/*_*.json; do echo "== $f"; python3 $C/passes.py $f; done > $OUT/summary.txt
cat $OUT/summary.txt
