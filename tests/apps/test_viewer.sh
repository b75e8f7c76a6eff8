#!/usr/bin/env bash
# ctest (under Xvfb): mvr-viewer shows exactly what the library rendered.
# The stereo demo in the viewer's window: each half of the screenshot equals
# the matching `mvr render` layer within 1/255 (the viewer's RGBA8 target is
# encoded by the shader, mvr render's sRGB target by the GL: one rounding
# apart at most). Then the anaglyph: red from the left eye, green and blue
# from the right. On desktop GL (GLX) and on GLES (EGL).
# usage: test_viewer.sh VIEWER MVR COMPARE OUT
set -u
viewer=$1 mvr=$2 compare=$3 out=$4
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
exit $fail
