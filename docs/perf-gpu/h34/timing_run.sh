# Issue 34, where a copied frame's cost goes on a real GPU: `gblens bench --only attach` at 1920x1080
# and 3840x2160 with GBLENS_LAYER_TIMESTAMPS=1 (the layer's copies timed on the GPU, per copy
# command: bench.json's layer.copy_gpu), in one device call. Carry: docs/perf-gpu/h27_carry.sh build
# build-h27, this script copied into build-h27; run: sh build-h27/timing_run.sh build-h27.
# Results in $OUT/timing.tar: timing_{1080,4k}.json, timing_bench.log, summary.txt.
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export GBLENS_LAYER_TIMESTAMPS=1
R=/tmp/timing; mkdir -p $R
for size in 1080 4k; do
  S=1920x1080; [ $size = 4k ] && S=3840x2160
  s=$(date +%s)
  LD_LIBRARY_PATH=$PWD/$C/lib $C/gblens bench --only attach --attach-size $S --attach-frames 120 --attach-rounds 3 \
    --attach-soak 100 --out $R/t_$size > $R/t_$size.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> $R/t_$size.log
  { echo "== $S"; cat $R/t_$size.log; } >> $R/timing_bench.log
  cp $R/t_$size/bench.json $R/timing_$size.json
done
nvidia-smi --query-gpu=name,driver_version --format=csv > $R/summary.txt 2>&1
for f in $R/timing_*.json; do python3 - "$f" >> $R/summary.txt <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
def walk(o, path=""):
    if isinstance(o, dict):
        if "copy_gpu" in o and o["copy_gpu"]:
            print(sys.argv[1].split("/")[-1], path, json.dumps(o["copy_gpu"]))
        for k, v in o.items(): walk(v, path + "/" + k)
    elif isinstance(o, list):
        for i, v in enumerate(o): walk(v, path + "/" + str(i))
walk(d)
PY
done
tar -C $R -cf $OUT/timing.tar timing_1080.json timing_4k.json timing_bench.log summary.txt
cat $R/summary.txt | cut -c1-600
