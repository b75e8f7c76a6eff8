#!/usr/bin/env bash
# Benchmark of the view paths: wall and CPU time per frame (bench_views), and
# the submitting thread's instruction count per frame under callgrind, which
# repeats to < 1% on a shared machine (quote that for CPU-side costs).
# usage: tests/bench/run_bench_views.sh [BUILD_DIR] [DEMO] [SIZE] [CALLGRIND_SIZE]
#        (default: build city 640x480 320x240)
set -euo pipefail
build=${1:-build}
demo=${2:-city}
size=${3:-640x480}
cg_size=${4:-320x240}
bench="$build/tests/bench_views"
[ -x "$bench" ] || { echo "run_bench_views: build first ($bench missing)" >&2; exit 1; }
frames=10
# callgrind runs fewer frames: LLVM and the rasterizer threads are slow under valgrind
echo "## wall and CPU time (ms per frame; median and minimum of $frames)"
"$bench" --demo "$demo" --size "$size" --frames "$frames"
echo
cg_frames=2
echo "## instructions of the submitting thread per frame (callgrind, $cg_size, $cg_frames frames)"
printf '%-6s %-10s %14s\n' views path instructions
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for path in multiview loop; do
    for views in 1 2 4 6; do
        out="$tmp/cg.$views.$path"
        valgrind --tool=callgrind --callgrind-out-file="$out" --instr-atstart=no --collect-atstart=no \
            --separate-threads=yes "$bench" --demo "$demo" --size "$cg_size" \
            --frames $cg_frames --only "$views:$path" > /dev/null 2> "$tmp/log" || {
            echo "run_bench_views: valgrind failed:" >&2; tail -5 "$tmp/log" >&2; exit 1; }
        # thread 1 is the submitting thread (the driver's workers are 2, 3, ...)
        total=$(awk '/^totals:/ {print $2}' "$out-01")
        printf '%-6s %-10s %14d\n' "$views" "$path" $((total / cg_frames))
    done
done
