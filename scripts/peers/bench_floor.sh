#!/usr/bin/env bash
# scripts/peers/bench_floor.sh: what mvr's frame is made of, by taking the lighting apart: scratch
# builds of the committed HEAD whose mesh fragment stage writes less, benched in interleaved rounds
# with one fixed configuration (docs/benchmarks.md, "The texture floor"):
#   base      mvr as it is
#   textures  every texture fetch the frame makes (the material's, and the environment's specular
#             cube at the reflection and its DFG table where there is image-based light), summed
#             into the output: no lighting arithmetic
#   fetches   the material's texture fetches alone, summed
#   floor     a constant colour: rasterization, depth test, the colour write (the raster floor)
# A frame cannot cost less than what it must fetch: where `textures` is as slow as `base`, only
# fewer texels (other pixels) can make it faster.
#
#   scripts/peers/bench_floor.sh --file SCENE --cameras CAMERAS.csv [--config VIEW/MATERIAL/noaa]
#                                [--rounds R] [--frames F] [--work DIR]
#
#   --cameras  a camera file as `mvr bench --cameras` takes it (bench_peers.sh leaves the peer's in
#              its --out folder); --config default multiview/per_material/noaa (the path auto
#              settles on: see results.json's auto.chosen / material_chosen)
#   --rounds   default 3; --frames default 15; --work default a temporary folder (the sources, the
#              build and the four binaries; kept, and used again by a later run at the same HEAD)
# Prints each variant's GPU (timer) ms per round. Needs the build dependencies (scripts/setup).
set -euo pipefail

die() { printf 'bench_floor: error: %s\n' "$*" >&2; exit 1; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
file= cameras= config=multiview/per_material/noaa rounds=3 frames=15 work=
while [ $# -gt 0 ]; do
    case $1 in
        --file) shift; file=${1:-} ;;
        --cameras) shift; cameras=${1:-} ;;
        --config) shift; config=${1:-} ;;
        --rounds) shift; rounds=${1:-} ;;
        --frames) shift; frames=${1:-} ;;
        --work) shift; work=${1:-} ;;
        -h|--help) sed -n '2,23p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) die "unknown argument '$1'" ;;
    esac
    shift
done
[ -f "$file" ] || die "--file SCENE (a glTF file) is needed"
[ -f "$cameras" ] || die "--cameras CAMERAS.csv is needed"
[[ $rounds =~ ^[1-9][0-9]*$ ]] || die "--rounds R"
[[ $frames =~ ^[1-9][0-9]*$ ]] || die "--frames F"
[[ $config =~ ^[a-z_]+/[a-z_]+/noaa$ ]] || die "--config VIEW/MATERIAL/noaa"
file=$(realpath "$file") cameras=$(realpath "$cameras")
[ -n "$work" ] || work=$(mktemp -d /tmp/mvr-floor-XXXXXX)
mkdir -p "$work/src"
work=$(realpath "$work")

# the committed sources (what HEAD renders), built once; each variant rebuilds the embedded shaders;
# a --work folder that already holds this HEAD's four binaries is benched again without building
head=$(git -C "$root" rev-parse HEAD)
variants="base textures fetches floor"
built=true
for v in $variants; do [ -x "$work/mvr_$v" ] || built=false; done
[ "$(cat "$work/head" 2>/dev/null)" = "$head" ] || built=false
build_variants() {
    rm -f "$work/head"
    git -C "$root" archive HEAD | tar -x -C "$work/src"
    cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$work/configure.log" 2>&1 ||
        die "configure failed: $work/configure.log"
    frag=$work/src/shaders/mesh.frag.glsl
    cp "$frag" "$work/mesh.frag.glsl.orig"
    for v in $variants; do
        cp "$work/mesh.frag.glsl.orig" "$frag"
        python3 - "$frag" "$v" <<'EOF'
import sys
path, variant = sys.argv[1], sys.argv[2]
src = open(path).read()
out = 'o_color = mvr_output(vec4(color + emissive, base.a));'
if src.count(out) != 1:
    sys.exit('bench_floor: mesh.frag.glsl no longer ends its lit main with "%s"' % out)
material = '''vec3 floor_sum = base.rgb + emissive;
#ifdef MVR_METAL_ROUGH_TEX
    floor_sum += mr.rgb;
#endif
#ifdef MVR_NORMAL_TEX
    floor_sum += tn;
#endif
'''
environment = '''#if defined(MVR_IBL) && !defined(MVR_IBL_REFERENCE)
    floor_sum += textureLod(mvr_env_specular, mvr_env_rotation * reflect(-v, n), roughness * mvr_env_max_lod).rgb;
    floor_sum.rg += texture(mvr_env_dfg, clamp(vec2(dot(n, v), roughness), 0.0, 1.0)).rg;
#endif
'''
write = 'o_color = vec4(floor_sum * 0.2, 1.0);'
replacement = {
    'base': out,
    'textures': material + environment + '    ' + write,
    'fetches': material + '    ' + write,
    'floor': 'o_color = vec4(0.5, 0.5, 0.5, 1.0);',
}[variant]
open(path, 'w').write(src.replace(out, replacement))
EOF
        cmake --build "$work/build" --target mvr -j "$(nproc)" > "$work/build_$v.log" 2>&1 || die "build of $v failed: $work/build_$v.log"
        cp "$work/build/mvr" "$work/mvr_$v"
    done
    echo "$head" > "$work/head"
}
$built || build_variants

printf 'bench_floor: %s, %s, %s, %s frames; GPU ms per round\n' "$(basename "$file")" "$(basename "$cameras")" \
    "$config" "$frames"
declare -A times
for r in $(seq 1 "$rounds"); do
    for v in $variants; do
        out=$work/run_${v}_$r
        rm -rf "$out"
        "$work/mvr_$v" bench "$file" --cameras "$cameras" --configs "$config" --frames "$frames" --warmup 3 \
            --rounds 1 --reference-memory 16 --out "$out" > "$out.log" 2>&1 || die "mvr bench ($v) failed: $out.log"
        # the configuration's row: name, [* on the Pareto front], path ran, wall, q1..q3, cpu, gpu
        ms=$(awk -v c="$config" '$1 == c { print ($2 == "*") ? $7 : $6 }' "$out.log")
        [ -n "$ms" ] || die "no $config row in $out.log"
        times[$v]="${times[$v]:-} $ms"
    done
done
for v in $variants; do
    printf '%-9s%s\n' "$v" "${times[$v]}"
done
