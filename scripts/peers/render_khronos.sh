#!/usr/bin/env bash
# scripts/peers/render_khronos.sh: renders tests/data/peers/khronos_*.png and manifest.json with the
# Khronos glTF Sample Renderer (npm @khronosgroup/gltf-viewer) in Debian's headless Chromium, through
# ANGLE on Mesa's EGL (llvmpipe: the same GL that mvr's tests run on). See tests/data/peers/README.md.
#
#   scripts/peers/render_khronos.sh [--assets] [--precision highp|as-is] [--out DIR]
#
#   --assets       first regenerate the test assets (scripts/peers/make_assets.py; textured.gltf,
#                  sheen.gltf and principled.gltf with Blender's glTF exporter: needs Debian's
#                  blender and python3-numpy)
#   --precision    highp (default): the renderer's shaders get highp int/sampler precision, without
#                  which llvmpipe collapses its IBL prefilter; as-is: unchanged (for the record)
#   --out DIR      write the PNGs and manifest.json there instead of tests/data/peers
#
# Needs chromium, node and npm (scripts/setup --peers installs them). The npm packages go to
# ${MVR_PEERS_DIR:-$HOME/.cache/mvr-peers}, never into the repository.
set -euo pipefail

log() { printf 'render_khronos: %s\n' "$*"; }
die() { printf 'render_khronos: error: %s\n' "$*" >&2; exit 1; }

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=common.sh
. "$here/common.sh"          # the pinned versions, $cache, peers_find_tools, peers_npm_install
root=$(cd "$here/../.." && pwd)
data=$root/tests/data/peers
command_line="scripts/peers/render_khronos.sh${*:+ $*}"

assets=0
precision=highp
out=$data
while [ $# -gt 0 ]; do
    case $1 in
        --assets) assets=1 ;;
        --precision) shift; precision=${1:-} ;;
        --precision=*) precision=${1#--precision=} ;;
        --out) shift; out=${1:-}; [ -n "$out" ] || die "--out DIR" ;;
        -h|--help) sed -n '2,15p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) die "unknown argument '$1'" ;;
    esac
    shift
done
case $precision in highp|as-is) ;; *) die "--precision highp|as-is" ;; esac

peers_find_tools
peers_npm_install @khronosgroup/gltf-viewer "$KHRONOS_VERSION"

if [ $assets -eq 1 ]; then
    log "regenerating the assets"
    python3 "$here/make_assets.py" "$data"
    command -v blender >/dev/null 2>&1 || die "textured.gltf needs Blender's glTF exporter: apt-get install blender python3-numpy"
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    blender -b --factory-startup --python "$here/blender_textured.py" -- "$data" "$tmp" >"$tmp/blender.log" 2>&1 \
        || { cat "$tmp/blender.log" >&2; die "blender failed"; }
    grep -q 'wrote .*textured.gltf' "$tmp/blender.log" || { cat "$tmp/blender.log" >&2; die "blender wrote no textured.gltf"; }
    blender -b --factory-startup --python "$here/blender_sheen.py" -- "$data" "$tmp" >"$tmp/blender_sheen.log" 2>&1 \
        || { cat "$tmp/blender_sheen.log" >&2; die "blender failed (sheen)"; }
    grep -q 'wrote .*sheen.gltf' "$tmp/blender_sheen.log" || { cat "$tmp/blender_sheen.log" >&2; die "blender wrote no sheen.gltf"; }
    blender -b --factory-startup --python "$here/blender_principled.py" -- "$data" "$tmp" >"$tmp/blender_principled.log" 2>&1 \
        || { cat "$tmp/blender_principled.log" >&2; die "blender failed (principled)"; }
    grep -q 'wrote .*principled.gltf' "$tmp/blender_principled.log" || { cat "$tmp/blender_principled.log" >&2; die "blender wrote no principled.gltf"; }
fi

log "rendering with $("$chromium_bin" --version 2>/dev/null | head -n 1)"
start=$(date +%s)
mkdir -p "$out"
node "$here/render_khronos.mjs" --data "$data" --out "$out" --modules "$cache/node_modules" --chromium "$chromium_bin" \
    --precision "$precision" --command "$command_line"
log "done in $(( $(date +%s) - start )) s"
