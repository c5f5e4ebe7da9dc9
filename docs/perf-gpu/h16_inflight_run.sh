#!/bin/sh
# The H100 tables of docs/perf-gpu.md with frames in flight (bench bursts of 4: the CPU records a
# frame while the GPU runs the one before), the cluster grid against the occupied clusters, and the
# raster tone map against the compute one: h16_run.sh's m720, m1080, m4k, grid and tonemap_raster
# runs (carry folder as $1), written to $OUT as inflight_*.json and inflight_bench.log.
RUNS=${RUNS:-"m720 m1080 m4k grid tonemap_raster"} PREFIX=inflight EXTRA="--methods-burst 4" exec sh "$(dirname "$0")/h16_run.sh" "$@"
