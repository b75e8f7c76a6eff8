#!/usr/bin/env bash
# scripts/peers/bench_peers.sh: frame time of a peer renderer in Debian's headless Chromium over Mesa's
# EGL (llvmpipe: the GL mvr runs on), interleaved with `mvr bench` of the same file at the same size
# and camera; prints each round's ratio peer / mvr and their median. The peers:
#   threejs  three.js (npm three): MeshStandardMaterial through its GLTFLoader, a RoomEnvironment
#            prefiltered by PMREMGenerator, the file's punctual lights
#   khronos  the Khronos glTF Sample Renderer (npm @khronosgroup/gltf-viewer): its PBR shaders, IBL from
#            tests/data/peers/sky.hdr, the file's punctual lights, no tone map
# Both without anti-aliasing.
#
#   scripts/peers/bench_peers.sh [--peer threejs|khronos] [--file SCENE.gltf|.glb] [--size WxH]
#                                [--views N] [--frames F] [--rounds R] [--settle S] [--mvr PATH] [--out DIR]
#
#   --peer    default threejs
#   --file    default: boxes.gltf from scripts/peers/make_boxes.py (a ground, 36 boxes, a sun, a camera)
#   --size    default 640x480; --views 1 or 2 (the same camera twice: three.js as two viewports of
#             one canvas, the Khronos renderer as two draws of its canvas, mvr as two layers)
#   --frames  default 30; --rounds default 3
#   --settle  seconds to wait before each side's run, default 10: Chromium's processes take seconds
#             to exit, and a run that starts at once shares the cores with them (measured: mvr's
#             DamagedHelmet at 640x480 x 2 views, 30 ms a frame right after Chromium, 21-24 ms after 10 s)
#   --mvr     default build/mvr; --out default a temporary folder (kept: each round's results)
#
# A peer's frame draws every view, then reads back 1 pixel (which waits for the GPU process to
# finish it; nothing is composited); the median of F frames after 5 untimed ones. mvr: `mvr bench
# --cameras` with the camera the peer used (the file's first camera, else the bounding sphere's
# framing), the median wall time of auto/auto/noaa. Wall time on a shared machine is noisy: the
# ratio of interleaved runs is what to quote. Needs chromium, node and npm (scripts/setup --peers);
# the npm packages go to ${MVR_PEERS_DIR:-$HOME/.cache/mvr-peers}, never into the repository.
set -euo pipefail

log() { printf 'bench_peers: %s\n' "$*" >&2; }
die() { printf 'bench_peers: error: %s\n' "$*" >&2; exit 1; }

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=common.sh
. "$here/common.sh"          # the pinned versions, $cache, peers_find_tools, peers_npm_install
root=$(cd "$here/../.." && pwd)
peer=threejs file= size=640x480 views=1 frames=30 rounds=3 settle=10 mvr=$root/build/mvr out=
while [ $# -gt 0 ]; do
    case $1 in
        --peer) shift; peer=${1:-} ;;
        --file) shift; file=${1:-} ;;
        --size) shift; size=${1:-} ;;
        --views) shift; views=${1:-} ;;
        --frames) shift; frames=${1:-} ;;
        --rounds) shift; rounds=${1:-} ;;
        --settle) shift; settle=${1:-} ;;
        --mvr) shift; mvr=${1:-} ;;
        --out) shift; out=${1:-} ;;
        -h|--help) sed -n '2,31p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) die "unknown argument '$1'" ;;
    esac
    shift
done
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || die "--size WxH"
width=${BASH_REMATCH[1]} height=${BASH_REMATCH[2]}
case $views in 1|2) ;; *) die "--views 1 or 2" ;; esac
case $peer in threejs|khronos) ;; *) die "--peer threejs or khronos" ;; esac
[[ $frames =~ ^[0-9]+$ && $frames -ge 5 ]] || die "--frames F (at least 5)"
[[ $rounds =~ ^[0-9]+$ && $rounds -ge 1 ]] || die "--rounds R"
[[ $settle =~ ^[0-9]+$ ]] || die "--settle S (whole seconds)"
[ -x "$mvr" ] || die "no mvr at $mvr (build first, or --mvr PATH)"

peers_find_tools
command -v python3 >/dev/null 2>&1 || die "no python3"

case $peer in
    threejs) peers_npm_install three "$THREE_VERSION" ;;
    khronos) peers_npm_install @khronosgroup/gltf-viewer "$KHRONOS_VERSION" ;;
esac

[ -n "$out" ] || out=$(mktemp -d /tmp/bench_peers.XXXXXX)
mkdir -p "$out"
if [ -z "$file" ]; then
    python3 "$here/make_boxes.py" "$out" >/dev/null
    file=$out/boxes.gltf
fi
[ -f "$file" ] || die "no file $file"
name=$(basename "${file%.*}")
log "$peer: $name, ${width}x${height}, $views view(s), $frames frames, $rounds rounds; $("$chromium_bin" --version | head -n 1); results in $out"

ratios=()
for r in $(seq 1 "$rounds"); do
    t=$out/${peer}_${name}_${size}_v${views}_r$r
    sleep "$settle"
    node "$here/bench_peer.mjs" --peer "$peer" --hdr "$root/tests/data/peers/sky.hdr" --file "$file" --width "$width" --height "$height" --views "$views" \
        --frames "$frames" --warmup 5 --modules "$cache/node_modules" --chromium "$chromium_bin" --out "$t.json"
    m=$out/mvr_${name}_${size}_v${views}_r$r
    sleep "$settle"
    # at least 5 rounds of mvr bench's own interleaving over its configurations
    "$mvr" bench "$file" --cameras "$t.csv" --configs auto/auto/noaa --frames "$frames" --rounds 5 --out "$m" \
        --quiet >"$m.log" 2>&1 \
        || { cat "$m.log" >&2; die "mvr bench failed"; }
    ratio=$(python3 - "$t.json" "$m/results.json" <<'EOF'
import json, sys
peer = json.load(open(sys.argv[1]))
mvr = {c["config"]: c for c in json.load(open(sys.argv[2]))["configurations"]}
m = mvr["auto/auto/noaa"]["wall_ms_median"]
what = (f"three.js {peer['median_ms']:.1f} ms (r{peer['three']}, {'/'.join(peer['materials'])})"
        if "three" in peer else f"Khronos {peer['median_ms']:.1f} ms")
print(f"{peer['median_ms'] / m:.2f} {what}, mvr auto/auto/noaa {m:.1f} ms")
EOF
)
    log "round $r: $peer / mvr = $ratio"
    ratios+=("${ratio%% *}")
done
median=$(printf '%s\n' "${ratios[@]}" | sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}')
printf '%s %s %s %s views: %s / mvr median %s over %s rounds (%s)\n' "$peer" "$name" "$size" "$views" "$peer" "$median" "$rounds" "${ratios[*]}"
