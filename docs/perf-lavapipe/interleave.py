#!/usr/bin/env python3
# Frame times of several gblens binaries / option sets measured in interleaved rounds (each round
# runs every variant once, in rotated order), so load from other processes hits all alike. Used
# for the cost decomposition in docs/performance.md, where a variant is a patched binary.
# Usage: interleave.py ROUNDS VARIANT...   VARIANT: "[@BINARY] [render options]" (default build/gblens)
# Prints per variant the median frame ms, the median of the light passes' ms and the median over
# rounds of frame / the first variant's frame in the same round.
import json, os, statistics, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BINARY = os.path.join(HERE, "..", "..", "build", "gblens")
PNG = os.path.join(tempfile.mkdtemp(prefix="interleave-"), "frame.png")
LIGHT_PASSES = ("directional_light", "light_mask", "point_lights", "tiled_lighting", "forward")


def frame(variant):
    args = variant.split()
    binary = args.pop(0)[1:] if args and args[0].startswith("@") else DEFAULT_BINARY
    out = subprocess.run([binary, "render", "--size", "1280x720", "--frames", "6", "--stats", "-o", PNG]
                         + args, capture_output=True, text=True, check=True).stdout
    stats = json.loads(out[out.index("{"):])
    lighting = sum(p["ms"] for p in stats["passes"] if p["name"] in LIGHT_PASSES)
    return stats["frame_ms"], lighting


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: interleave.py ROUNDS \"[@BINARY] [render options]\"...")
    rounds, variants = int(sys.argv[1]), sys.argv[2:]
    times = {v: [] for v in variants}
    lighting = {v: [] for v in variants}
    for r in range(rounds):
        for v in variants[r % len(variants):] + variants[:r % len(variants)]:
            t, l = frame(v)
            times[v].append(t)
            lighting[v].append(l)
    first = variants[0]
    for v in variants:
        ratio = statistics.median(a / b for a, b in zip(times[v], times[first]))
        print("%-55s frame %7.1f ms  lighting %7.1f ms  x%.3f" %
              (v or "(defaults)", statistics.median(times[v]), statistics.median(lighting[v]), ratio))


if __name__ == "__main__":
    main()
