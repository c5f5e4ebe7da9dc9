#!/usr/bin/env python3
# The pass table of docs/perf-gpu.md ("The lighting toward its floor"): for each cell of a
# `gblens bench --only methods` bench.json, the method auto picked, its frame and GPU ms, and every
# pass that ran with its median GPU ms and the gap before it (before_ms). Usage: passes.py bench.json
import json
import sys

bench = json.load(open(sys.argv[1]))
for cell in bench["methods"]:
    if not cell.get("auto_pick"):
        continue
    ran = [p for p in cell["passes"] if not p.get("skipped") and "ms" in p]
    print(f"{cell['size']} {cell['lights']} lights: {cell['method']} ({cell.get('gbuffer', '?')}), "
          f"frame {cell['frame_ms']['median']:.3f} ms, "
          + (f"steady {cell['steady_ms']['median']:.3f} ms, " if "steady_ms" in cell else "")
          + f"GPU {cell['gpu_ms']['median']:.3f} ms")
    print("   " + ", ".join(f"{p['name']} {p['ms']['median']:.3f} (+{p['before_ms']['median']:.3f} before)"
                            for p in ran if p["ms"]["median"] >= 0.01 or p["before_ms"]["median"] >= 0.01))
