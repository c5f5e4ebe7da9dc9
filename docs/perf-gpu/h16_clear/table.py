# The compute-clear A/B tables of docs/perf-gpu.md: python3 table.py compute (or auto); medians per method and size.
import json,glob,sys
rows={}
for f in sorted(glob.glob(sys.argv[1]+'/clear_*.json')):
    b=f.split('/')[-1]
    j=json.load(open(f))
    mode=b.split('_')[1]; cfg='_'.join(b.split('_')[2:4])
    for m in j['methods']:
        if not m.get('measured'): continue
        p={x['name']:x['ms']['median'] for x in m['passes'] if not x.get('skipped')}
        key=(cfg,m['method'],m.get('auto_pick'))
        rows.setdefault(key,{}).setdefault(mode,[]).append((m['frame_ms']['median'],m['gpu_ms']['median'],m['cpu_ms']['median'],sum(p.values()),'clear_gbuffer' in p))
for k,v in sorted(rows.items()):
    print(k)
    for mode,l in v.items():
        for t in l: print('   %-12s frame %8.3f gpu %8.3f cpu %6.3f gap %6.3f compute-clear %s'%(mode,t[0],t[1],t[2],t[1]-t[3],t[4]))
