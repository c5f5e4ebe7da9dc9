#!/usr/bin/env python3
# Tables and the log-log plot of docs/perf-gpu.md from the H100 runs of `gblens bench --only
# methods` kept here (one bench.json per run; each cell's four methods come from one run, so
# its ratios were measured side by side). Usage: python3 docs/perf-gpu/tables.py > /tmp/tables.md
import json, os, subprocess, sys

HERE = os.path.dirname(os.path.abspath(__file__))
# (file, cells it supplies): a cell is (size, lights); the later file wins for a cell it has.
RUNS = ["h100_1280x720.json", "h100_1920x1080.json", "h100_1920x1080_65536_forward.json",
        "h100_3840x2160.json", "h100_3840x2160_65536_forward.json"]
METHODS = ["deferred", "deferred_unculled", "forward", "tiled"]
PASSES = ["gbuffer", "directional_light", "light_mask", "point_lights", "tiled_lighting", "forward", "skybox",
          "fairy_lights", "tonemap"]

cells = {}
for f in RUNS:
    j = json.load(open(os.path.join(HERE, f)))
    by_cell = {}
    for m in j["methods"]:
        by_cell.setdefault((m["size"], m["lights"]), {})[m["method"]] = dict(m, run=f)
    for cell, methods in by_cell.items():
        # a run that measured forward there replaces one that did not
        old = cells.get(cell)
        if old is None or (methods.get("forward", {}).get("measured") and not old.get("forward", {}).get("measured")):
            cells[cell] = methods

def size_key(s):
    w, h = s.split("x")
    return int(w) * int(h)

def ms(m, name):
    for p in m.get("passes", []):
        if p["name"] == name and not p["skipped"]:
            return "%.2f" % p["ms"]["median"]
    return ""

out = sys.stdout
out.write("| size | lights | method | frame ms (median) | rounds | x defaults | work/ideal | " +
          " | ".join(PASSES) + " |\n")
out.write("|" + " --- |" * (7 + len(PASSES)) + "\n")
for (size, lights) in sorted(cells, key=lambda c: (size_key(c[0]), c[1])):
    for method in METHODS:
        m = cells[(size, lights)].get(method)
        if m is None:
            continue
        if not m["measured"]:
            out.write("| %s | %d | %s | not measured | | | | %s |\n" % (size, lights, method, " | " * (len(PASSES) - 1)))
            continue
        work = "%.2f" % m["culling"]["work_over_ideal"] if "culling" in m else "-"
        out.write("| %s | %d | %s | %.2f | %d | %.2f | %s | %s |\n" % (
            size, lights, method, m["frame_ms"]["median"], m["frames"], m["time_over_default"], work,
            " | ".join(ms(m, p) for p in PASSES)))

# Log-log plot: frame ms vs lights, a colour per method, a dash pattern per size.
plot_dir = "/tmp/gblens_perf_gpu_plot"
os.makedirs(plot_dir, exist_ok=True)
colours = {"deferred": "#4477aa", "deferred_unculled": "#ee6677", "forward": "#228833", "tiled": "#ccbb44"}
sizes = sorted({c[0] for c in cells}, key=size_key)
series = []
for si, size in enumerate(sizes):
    for method in METHODS:
        pts = []
        for (s, lights), methods in cells.items():
            m = methods.get(method)
            if s == size and m and m["measured"]:
                pts.append((max(lights, 1), m["frame_ms"]["median"]))
        if not pts:
            continue
        path = os.path.join(plot_dir, "%s_%s.dat" % (method, size))
        with open(path, "w") as f:
            for x, y in sorted(pts):
                f.write("%g %g\n" % (x, y))
        series.append("'%s' using 1:2 with linespoints lw 2 pt 7 lc rgb '%s' dt %d title '%s %s'" % (
            path, colours[method], si + 1, method, size))
png = os.path.join(HERE, "h100_methods_vs_lights.png")
script = ("set terminal pngcairo size 1000,620 font 'DejaVu Sans,10' noenhanced\nset output '%s'\n"
          "set grid lc rgb '#dddddd'\nset logscale xy\nset key outside right\n"
          "set title 'gblens bench --only methods on NVIDIA H100 (builtin:temple): frame time vs point lights'\n"
          "set xlabel 'point lights (log)'\nset ylabel 'frame ms, median (log)'\nplot %s\n" % (png, ", \\\n  ".join(series)))
subprocess.run(["gnuplot"], input=script.encode(), check=True)
