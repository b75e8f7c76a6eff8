#!/usr/bin/env bash
# ctest (under Xvfb): mvr-viewer shows exactly what the library rendered.
# The stereo demo in the viewer's window: each half of the screenshot equals
# the matching `mvr render` layer within 1/255 (the viewer's RGBA8 target is
# encoded by the shader, mvr render's sRGB target by the GL: one rounding
# apart at most). Then the anaglyph: red from the left eye, green and blue
# from the right. On desktop GL (GLX) and on GLES (EGL).
# With CORPUS (tests/io's generated glTF files), files as mvr render shows
# them (issue 17): the viewer loads, frames, exposes and lights a file with
# mvr render's own code (apps/mvr/cli_scene.c, cli_env.c and the library's
# mvr_view_set_from_camera and mvr_render_desc_choose_exposure), so each
# half of its screenshot equals mvr render's layer within the same 1/255:
# physical_lights.gltf (a 2049 lux sun and a camera: auto-exposed and tone
# mapped; the viewer used to show it white) and scene_graph.glb (two camera
# nodes, lights in plain units: seen from the first camera, exposure 1).
# usage: test_viewer.sh VIEWER MVR COMPARE OUT [CORPUS]
set -u
viewer=$1 mvr=$2 compare=$3 out=$4 corpus=${5:-}
rm -rf "$out"; mkdir -p "$out"
fail=0
check() { if "$@"; then echo "ok: ${*: -1}"; else echo "FAIL: $*"; fail=1; fi; }
"$mvr" render --demo stereo --views 2 --size 320x240 --out "$out/render" --quiet || { echo "FAIL: mvr render"; exit 1; }
for api in desktop gles; do
    if ! "$viewer" --demo stereo --size 640x240 --api "$api" --frames 3 --screenshot "$out/$api.png"; then
        echo "FAIL: mvr-viewer --api $api did not run"; fail=1; continue
    fi
    check "$compare" "$out/$api.png" "$out/render/view_00.png" --crop 0,0,320,240 --max 1
    check "$compare" "$out/$api.png" "$out/render/view_01.png" --crop 320,0,320,240 --max 1
done
"$viewer" --demo stereo --size 320x240 --display anaglyph --frames 2 --screenshot "$out/anaglyph.png" || { echo "FAIL: anaglyph"; fail=1; }
check "$compare" "$out/anaglyph.png" "$out/render/view_00.png" --channels r --max 1
check "$compare" "$out/anaglyph.png" "$out/render/view_01.png" --channels gb --max 1
if [ -n "$corpus" ]; then
    for f in physical_lights.gltf scene_graph.glb; do
        "$mvr" render "$corpus/$f" --views 2 --size 320x240 --out "$out/$f" --quiet || { echo "FAIL: mvr render $f"; fail=1; continue; }
        for api in desktop gles; do
            if ! "$viewer" "$corpus/$f" --size 640x240 --api "$api" --frames 3 --screenshot "$out/$f.$api.png"; then
                echo "FAIL: mvr-viewer $f --api $api did not run"; fail=1; continue
            fi
            check "$compare" "$out/$f.$api.png" "$out/$f/view_00.png" --crop 0,0,320,240 --max 1
            check "$compare" "$out/$f.$api.png" "$out/$f/view_01.png" --crop 320,0,320,240 --max 1
        done
    done
fi
# the environment options are mvr render's: a bad value is named, exit 2
# (checked before any window opens)
expect_usage() {
    local msg; msg=$("$viewer" "$@" 2>&1 >/dev/null); local rc=$?
    if [ $rc -eq 2 ] && printf '%s' "$msg" | grep -q -- "${*: -2:1}"; then echo "ok: viewer $*"
    else echo "FAIL: mvr-viewer $* exits $rc: $msg"; fail=1; fi
}
expect_usage --env-intensity -1
expect_usage --env-rotation nan
expect_usage --background sky
expect_usage --background-blur 2
exit $fail
