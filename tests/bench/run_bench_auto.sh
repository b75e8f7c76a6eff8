#!/usr/bin/env bash
# The view-path choice checked by measurement: wall time per frame of the
# multiview, loop and auto paths on the city and stereo demos at 1, 2 and 6
# views and 256x256 and 1024x1024, and auto's loss against the better forced
# path. Each (path) run is its own process, and the three paths are measured
# in turn for several rounds (the best median of the rounds counts), so
# neither start-up order nor a busy neighbour on a shared machine favours one.
# usage: tests/bench/run_bench_auto.sh [BUILD_DIR] [ROUNDS] [FRAMES]
set -euo pipefail
build=${1:-build}
rounds=${2:-3}
frames=${3:-7}
bench="$build/tests/bench_views"
[ -x "$bench" ] || { echo "run_bench_auto: build first ($bench missing)" >&2; exit 1; }

# wall_med (column 8) of one configuration's row, and the path auto ran (column 3)
measure() { # demo size views path
    "$bench" --demo "$1" --size "$2x$2" --frames "$frames" --views "$3" --only "$3:$4" | tail -1
}

printf '%-7s %5s %5s %10s %10s %10s %-10s %9s\n' demo size views multiview loop auto auto_ran auto_loss
worst=0
for demo in city stereo; do
    for size in 256 1024; do
        for views in 1 2 6; do
            declare -A best=([multiview]=1e9 [loop]=1e9 [auto]=1e9)
            ran=
            for ((r = 0; r < rounds; ++r)); do
                for path in multiview loop auto; do
                    row=$(measure "$demo" "$size" "$views" "$path")
                    wall=$(awk '{print $8}' <<< "$row")
                    [ "$path" = auto ] && ran=$(awk '{print $3}' <<< "$row")
                    best[$path]=$(awk -v a="${best[$path]}" -v b="$wall" 'BEGIN {print (b < a) ? b : a}')
                done
            done
            loss=$(awk -v m="${best[multiview]}" -v l="${best[loop]}" -v a="${best[auto]}" \
                'BEGIN {b = (m < l) ? m : l; printf "%.1f", (a / b - 1) * 100}')
            worst=$(awk -v w="$worst" -v x="$loss" 'BEGIN {print (x > w) ? x : w}')
            printf '%-7s %5s %5s %10.2f %10.2f %10.2f %-10s %8s%%\n' "$demo" "$size" "$views" \
                "${best[multiview]}" "${best[loop]}" "${best[auto]}" "$ran" "$loss"
        done
    done
done
echo "# worst auto loss against the better forced path: ${worst}% (the target: at most 5%)"
