#!/usr/bin/env bash
# Benchmark of the material paths on the city demo (issue: texture-array
# batcher): arrays vs per-material vs the per-draw baseline, 256x256 per view,
# 1, 2 and 6 views (view path auto). Wall / CPU time per frame, and the
# submitting thread's instructions per frame under callgrind (repeatable).
# usage: tests/bench/run_bench_materials.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
bench="$build/tests/bench_views"
[ -x "$bench" ] || { echo "run_bench_materials: build first ($bench missing)" >&2; exit 1; }
paths="arrays per_material per_draw"
echo "## wall and CPU time (ms per frame, 256x256 per view; median and minimum of 10)"
for p in $paths; do
    "$bench" --demo city --size 256x256 --frames 10 --views 1,2,6 --material-path "$p" | grep -v ' loop '
done
echo
echo "## instructions of the submitting thread per frame (callgrind, 2 frames)"
printf '%-6s %-14s %14s\n' views material_path instructions
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for p in $paths; do
    for views in 1 2 6; do
        out="$tmp/cg.$views.$p"
        valgrind --tool=callgrind --callgrind-out-file="$out" --instr-atstart=no --collect-atstart=no \
            --separate-threads=yes "$bench" --demo city --size 256x256 --frames 2 --material-path "$p" \
            --only "$views:multiview" > /dev/null 2> "$tmp/log" || {
            echo "run_bench_materials: valgrind failed:" >&2; tail -5 "$tmp/log" >&2; exit 1; }
        total=$(awk '/^totals:/ {print $2}' "$out-01")
        printf '%-6s %-14s %14d\n' "$views" "$p" $((total / 2))
    done
done
