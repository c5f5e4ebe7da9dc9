#!/bin/sh
# The main method table of docs/perf-gpu.md re-measured after the G-buffer clears moved to compute:
# h16_run.sh's m720, m1080 and m4k runs (same cells and budgets; carry folder as $1), written to
# $OUT as retable_*.json and retable_bench.log.
RUNS="m720 m1080 m4k" PREFIX=retable exec sh "$(dirname "$0")/h16_run.sh" "$@"
