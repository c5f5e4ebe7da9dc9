# Issue 34, the receiver decoding into the buffers of frames already shown (TexelPool, import.h):
# `gblens bench --only attach` at 1920x1080 and 3840x2160 with the build before it ($1/base) and
# with it ($1), alternating, in one device call. Carry: docs/perf-gpu/h27_carry.sh build build-h27,
# the same for the build before into build-h27/base, this script copied into build-h27; run:
# sh build-h27/pool_run.sh build-h27. Results in $OUT: {base,pool}_{1080,4k}.json, pool_bench.log.
C=${1:-build-h27}; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for size in 1080 4k; do for b in base pool; do
  G=$C/gblens; L=$PWD/$C/lib; [ $b = base ] && G=$C/base/gblens L=$PWD/$C/base/lib
  S=1920x1080; [ $size = 4k ] && S=3840x2160
  s=$(date +%s)
  LD_LIBRARY_PATH=$L $G bench --only attach --attach-size $S --attach-frames 120 --attach-rounds 3 --attach-soak 100 \
    --out /tmp/p_${b}_$size > /tmp/p_${b}_$size.log 2>&1
  echo "rc $? in $(( $(date +%s) - s )) s" >> /tmp/p_${b}_$size.log
  { echo "== $b $S"; cat /tmp/p_${b}_$size.log; } >> $OUT/pool_bench.log
  cp /tmp/p_${b}_$size/bench.json $OUT/${b}_$size.json
done; done
for f in $OUT/base_*.json $OUT/pool_*.json; do python3 -c "
import json,sys; d=json.load(open(sys.argv[1])); a=d.get('attach',{})
def find(o,k):
  if isinstance(o,dict):
    for kk,v in o.items():
      if kk==k: yield v
      yield from find(v,k)
  elif isinstance(o,list):
    for v in o: yield from find(v,k)
print(sys.argv[1].split('/')[-1], 'decode_ms', [round(x,2) for x in find(d,'decode_ms')][:6], 'received', list(find(d,'received'))[:6])
" $f; done
