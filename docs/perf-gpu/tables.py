#!/usr/bin/env python3
# Tables and the log-log plot of docs/perf-gpu.md from the H100 runs of `gblens bench --only
# methods` kept here (one bench.json per run; each cell's methods come from one run, so its ratios
# were measured side by side). The issue-16 runs (h16_*.json, docs/perf-gpu/h16_run.sh) make the
# main table; the earlier runs (h100_*.json, before clustered) supply forward at 65536 lights.
# Usage: python3 docs/perf-gpu/tables.py > /tmp/tables.md
import json, os, subprocess, sys

HERE = os.path.dirname(os.path.abspath(__file__))
MAIN = ["h16_m720.json", "h16_m1080.json", "h16_m4k.json"]
METHODS = ["deferred", "deferred_unculled", "forward", "tiled", "clustered"]
PASSES = ["light_setup", "gbuffer", "directional_light", "point_lights", "tiled_lighting", "cluster_bounds",
          "cluster_bins", "cluster_lists", "clustered_lighting", "forward", "skybox", "fairy_splat", "tonemap"]


def load(f):
    return json.load(open(os.path.join(HERE, f)))


def cells_of(files):
    cells = {}
    for f in files:
        for m in load(f)["methods"]:
            cells.setdefault((m["size"], m["lights"]), {})[m["method"]] = m
    return cells


def size_key(s):
    w, h = s.split("x")
    return int(w) * int(h)


def pass_ms(m, name):
    for p in m.get("passes", []):
        if p["name"] == name and not p["skipped"]:
            return p["ms"]["median"]
    return None


def fmt(v, digits=2):
    return "" if v is None else "%.*f" % (digits, v)


out = sys.stdout
cells = cells_of(MAIN)
out.write("| size | lights | method | frame ms | CPU ms | GPU ms | rounds | x auto | work/ideal | " + " | ".join(PASSES) + " |\n")
out.write("|" + " --- |" * (9 + len(PASSES)) + "\n")
for (size, lights) in sorted(cells, key=lambda c: (size_key(c[0]), c[1])):
    for method in METHODS:
        m = cells[(size, lights)].get(method)
        if m is None:
            continue
        name = method + (" (auto)" if m.get("auto_pick") else "")
        if not m["measured"]:
            out.write("| %s | %d | %s | not measured |%s\n" % (size, lights, name, " |" * (5 + len(PASSES))))
            continue
        c = m.get("culling", {})
        work = fmt(c.get("work_over_ideal")) if c.get("work_over_ideal") else "-"
        out.write("| %s | %d | %s | %.2f | %.2f | %.2f | %d | %.2f | %s | %s |\n" % (
            size, lights, name, m["frame_ms"]["median"], m["cpu_ms"]["median"], m["gpu_ms"]["median"], m["frames"],
            m["time_over_default"], work, " | ".join(fmt(pass_ms(m, p)) for p in PASSES)))

# Light setup on the CPU vs the GPU, and the fairy sprites drawn vs splatted (65536 lights).
out.write("\n| size | method | lights set up on | frame ms | CPU ms | GPU ms | fairies | fairy pass ms |\n")
out.write("|" + " --- |" * 8 + "\n")
variants = [("h16_m1080.json", "GPU (auto)", "splatted (auto)"), ("h16_m4k.json", "GPU (auto)", "splatted (auto)"),
            ("h16_setup_cpu.json", "CPU (--light-setup cpu)", "splatted (auto)"),
            ("h16_fairy_raster.json", "GPU (auto)", "drawn (--fairy-splat raster)")]
rows = []
for f, setup, fairies in variants:
    for m in load(f)["methods"]:
        if m["lights"] == 65536 and m["method"] in ("tiled", "clustered") and m["measured"]:
            fp = pass_ms(m, "fairy_splat") or pass_ms(m, "fairy_lights")
            rows.append((size_key(m["size"]), m["method"], f, "| %s | %s | %s | %.2f | %.2f | %.2f | %s | %.2f |\n" % (
                m["size"], m["method"], setup, m["frame_ms"]["median"], m["cpu_ms"]["median"], m["gpu_ms"]["median"],
                fairies, fp)))
for r in sorted(rows, key=lambda r: (r[0], r[1])):
    out.write(r[3])

# Log-log plot: frame ms vs lights, a colour per method, a dash pattern per size; forward at
# 65536 lights from the earlier runs.
old = cells_of(["h100_1920x1080_65536_forward.json", "h100_3840x2160_65536_forward.json"])
plot_dir = "/tmp/gblens_perf_gpu_plot"
os.makedirs(plot_dir, exist_ok=True)
colours = {"deferred": "#4477aa", "deferred_unculled": "#ee6677", "forward": "#228833", "tiled": "#ccbb44",
           "clustered": "#aa3377"}
sizes = sorted({c[0] for c in cells}, key=size_key)
series = []
for si, size in enumerate(sizes):
    for method in METHODS:
        pts = []
        for source in (cells, old):
            for (s, lights), methods in source.items():
                m = methods.get(method)
                if s == size and m and m["measured"] and not any(p[0] == max(lights, 1) for p in pts):
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
