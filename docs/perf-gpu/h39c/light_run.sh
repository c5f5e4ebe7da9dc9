C=build-h27; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens
for r in 1 2 3; do for s in 1920x1080 3840x2160; do for p in 1 2; do
  GBLENS_LIGHTING_PIXELS=$p $G render builtin:temple --method clustered --lights 65536 --size $s --frames 60 --stats -o /tmp/l.png > /tmp/l.json 2>/dev/null
  python3 -c "
import json,sys
t=open('/tmp/l.json').read(); j=json.loads(t[t.find('{'):])
p={x['name']:x.get('ms',0) for x in j['passes']}
print('pixels=$p $s round $r frame_ms %.3f clustered_lighting %.3f cluster_lists %.3f visibility %.3f fairy_splat %.3f' % (j['frame_ms'], p['clustered_lighting'], p['cluster_lists'], p['visibility'], p['fairy_splat']))"
done; done; done > $OUT/light_summary.txt 2>&1
cat $OUT/light_summary.txt
