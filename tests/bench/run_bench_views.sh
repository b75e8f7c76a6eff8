#!/usr/bin/env bash
# Benchmark of the view paths: wall and CPU time per frame (bench_views), and
# the submitting thread's instruction count per frame under callgrind, which
# repeats to < 1% on a shared machine (quote that for CPU-side costs).
# usage: tests/bench/run_bench_views.sh [BUILD_DIR] [DEMO] [SIZE]   (default: build city 640x480)
set -euo pipefail
build=${1:-build}
demo=${2:-city}
size=${3:-640x480}
bench="$build/tests/bench_views"
[ -x "$bench" ] || { echo "run_bench_views: build first ($bench missing)" >&2; exit 1; }
frames=10
echo "## wall and CPU time (ms per frame; median and minimum of $frames)"
"$bench" --demo "$demo" --size "$size" --frames "$frames"
echo
echo "## instructions of the submitting thread per frame (callgrind, $((frames / 2)) frames)"
printf '%-6s %-10s %14s\n' views path instructions
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for path in multiview loop; do
    for views in 1 2 4 6; do
        out="$tmp/cg.$views.$path"
        valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no \
            --toggle-collect=measured_frames "$bench" --demo "$demo" --size "$size" \
            --frames $((frames / 2)) --only "$views:$path" > /dev/null 2> "$tmp/log" || {
            echo "run_bench_views: valgrind failed:" >&2; tail -5 "$tmp/log" >&2; exit 1; }
        total=$(awk '/^totals:/ {print $2}' "$out")
        printf '%-6s %-10s %14d\n' "$views" "$path" $((total / (frames / 2)))
    done
done
