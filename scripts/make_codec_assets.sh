#!/usr/bin/env bash
# scripts/make_codec_assets.sh: regenerates tests/data/codecs, the compressed
# versions of tests/data/peers/textured.gltf that tests/io/test_gltf_codecs.cpp
# renders against the plain file, with the real encoders (scripts/setup
# installs both): Debian's gltfpack 0.18 (meshoptimizer) and draco_transcoder
# (Draco 1.5.5). Both are deterministic: a second run writes the same bytes.
#
#   meshopt_float.glb  gltfpack -cc -noq   EXT_meshopt_compression of the float data
#   meshopt.glb        gltfpack -cc        KHR_mesh_quantization + EXT_meshopt_compression
#                                          (OCTAHEDRAL filter on normals and tangents;
#                                          a fallback buffer without data)
#   draco.glb          draco_transcoder    KHR_draco_mesh_compression, Draco's default
#                                          quantization (drops the file's camera)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
in=$root/tests/data/peers/textured.gltf
out=$root/tests/data/codecs
for tool in gltfpack draco_transcoder; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "make_codec_assets: $tool missing (scripts/setup installs it)" >&2
        exit 1
    fi
done
mkdir -p "$out"
gltfpack -i "$in" -o "$out/meshopt_float.glb" -cc -noq
gltfpack -i "$in" -o "$out/meshopt.glb" -cc
draco_transcoder -i "$in" -o "$out/draco.glb" > /dev/null
ls -l "$out"/*.glb
