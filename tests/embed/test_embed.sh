#!/usr/bin/env bash
# ctest: mvr embedded in an application that owns the GL.
#  1. embed (its own EGL context and 2-layer texture array) renders the stereo
#     demo into the same bytes as `mvr render`, and its own code-built scene;
#  2. pure C: mvr_core and mvr_gl need nothing of C++ (no mangled or C++
#     runtime symbol undefined in them, no libstdc++ in embed, a C link line);
#  3. the installed package: `cmake --install`, then a project outside the
#     tree builds embed with find_package(mvr) (static and shared) and with
#     pkg-config (mvr-static), and each renders the same bytes;
#  4. the installed glTF and image libraries: the same outside project and
#     pkg-config (mvr-gltf + mvr-image, mvr-gltf-static + mvr-image-static)
#     build gltf_to_png (C), which loads tests/data/peers/textured.gltf,
#     renders it headless and writes a PNG: four PNGs with a picture, the same
#     bytes; the installed shared libraries export exactly their headers' API.
# Under sanitizers (SANITIZED=ON) the archives carry ASan's instrumentation
# (its own data sections, and symbols only an instrumented link resolves):
# the globals check and the outside consumers are left to the plain build.
# usage: test_embed.sh BUILD_DIR SOURCE_DIR OUT [SANITIZED]
set -u
build=$1 src=$2 out=$3 sanitized=${4:-OFF}
rm -rf "$out"; mkdir -p "$out"
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }
cmp_layers() { # prefix label
    for k in 0 1; do
        if "$build/tests/compare_images" "${1}_$k.ppm" "$out/render/view_000$k.png" --max 0 > /dev/null; then
            ok "$2: layer $k equals mvr render's"
        else
            bad "$2: layer $k differs from mvr render's"; "$build/tests/compare_images" "${1}_$k.ppm" "$out/render/view_000$k.png"
        fi
    done
}
"$build/mvr" render --demo stereo --views 2 --size 320x240 --out "$out/render" --quiet || bad "mvr render"
"$build/embed" --demo stereo --out "$out/embed" > /dev/null && cmp_layers "$out/embed" embed || bad "embed --demo stereo"
"$build/embed" --out "$out/own" > /dev/null && [ -s "$out/own_0.ppm" ] && ok "embed renders its own scene" || bad "embed's own scene"

# 2. pure C
cxx=$(nm -u "$build/libmvr_core.a" "$build/libmvr_gl.a" 2>/dev/null | grep -E ' U (_Z|__cxa_|__gxx_|_Unwind_Resume)' || true)
[ -z "$cxx" ] && ok "mvr_core and mvr_gl need no C++ symbol" || bad "C++ symbols needed: $cxx"
# no global state (no symbol in writable .data or .bss: tables are const),
# no exit, no printing to stdout / stderr (messages go through the logger)
if [ "$sanitized" = ON ]; then
    echo "skipped under sanitizers: the globals check and the installed-package consumers"
else
globals=$(objdump -t "$build/libmvr_core.a" "$build/libmvr_gl.a" | awk '$0 ~ / \.(bss|data)[ .]/ && $0 !~ /data\.rel\.ro/')
[ -z "$globals" ] && ok "no writable globals in mvr_core / mvr_gl" || bad "writable globals: $globals"
fi
calls=$(nm -u "$build/libmvr_core.a" "$build/libmvr_gl.a" | grep -E ' U (exit|_exit|abort|printf|vprintf|puts|putchar|perror|stdout|stderr)$' || true)
[ -z "$calls" ] && ok "no exit, printf, puts, perror, stdout or stderr in mvr_core / mvr_gl" || bad "the libraries call: $calls"
readelf -d "$build/embed" | grep -q 'libstdc++' && bad "embed needs libstdc++" || ok "embed does not need libstdc++"
link="$build/CMakeFiles/embed.dir/link.txt"
if [ -f "$link" ]; then
    first=$(awk '{print $1; exit}' "$link")
    grep -qE -- '-lstdc\+\+|c\+\+|g\+\+' "$link" && bad "embed's link line is C++: $(cat "$link")" || ok "embed links with the C compiler ($first)"
fi

# 3. installed package
[ "$sanitized" = ON ] && exit $fail
prefix="$out/prefix"
cmake --install "$build" --prefix "$prefix" > "$out/install.log" 2>&1 || { bad "cmake --install"; cat "$out/install.log"; }
if cmake -S "$src/tests/embed/consumer" -B "$out/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
        -DEMBED_SOURCE="$src/apps/examples/embed.c" > "$out/consumer.log" 2>&1 &&
   cmake --build "$out/consumer" >> "$out/consumer.log" 2>&1; then
    ok "find_package(mvr) builds embed and gltf_to_png (static and shared)"
    "$out/consumer/embed_static" --demo stereo --out "$out/static" > /dev/null && cmp_layers "$out/static" "installed static" || bad "installed static embed"
    LD_LIBRARY_PATH="$prefix/lib" "$out/consumer/embed_shared" --demo stereo --out "$out/shared" > /dev/null &&
        cmp_layers "$out/shared" "installed libmvr.so" || bad "installed shared embed"
    readelf -d "$out/consumer/embed_shared" | grep -q 'libmvr.so' && ok "embed_shared needs libmvr.so" || bad "embed_shared does not use libmvr.so"
else
    bad "the consumer project does not build"; tail -30 "$out/consumer.log"
fi
gles=$(dirname "$(find /usr/include -name gl3.h -path '*GLES3*' | head -1)")/..
if cc -std=c11 "$src/apps/examples/embed.c" -I"$gles" $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs mvr-static) \
        -o "$out/embed_pc" 2> "$out/pc.log"; then
    "$out/embed_pc" --demo stereo --out "$out/pc" > /dev/null && cmp_layers "$out/pc" "pkg-config mvr-static" || bad "pkg-config embed"
else
    bad "cc with pkg-config mvr-static"; cat "$out/pc.log"
fi

# 4. glTF in, PNG out, from the installed package alone
gltf="$src/tests/data/peers/textured.gltf"
png_ok() { # label program png
    if "$2" "$gltf" "$3" > "$3.log" 2>&1; then ok "$1: $(tail -1 "$3.log")"; else bad "$1"; cat "$3.log"; fi
}
if [ -x "$out/consumer/gltf_to_png_static" ]; then
    png_ok "find_package(mvr) mvr::mvr_gltf (static)" "$out/consumer/gltf_to_png_static" "$out/gltf_cmake_static.png"
    png_ok "find_package(mvr) mvr::mvr_gltf_shared" "$out/consumer/gltf_to_png_shared" "$out/gltf_cmake_shared.png"
    needed=$(readelf -d "$out/consumer/gltf_to_png_shared" | grep -o 'lib[a-z_]*\.so[.0-9]*' | tr '\n' ' ')
    case "$needed" in *libmvr_gltf.so*libmvr_image.so*libmvr.so*) ok "gltf_to_png_shared needs $needed";;
        *) bad "gltf_to_png_shared needs $needed";; esac
    link="$out/consumer/CMakeFiles/gltf_to_png_shared.dir/link.txt"
    grep -qE -- '-lstdc\+\+|c\+\+|g\+\+' "$link" && bad "gltf_to_png_shared's link line is C++" || ok "gltf_to_png_shared links with the C compiler"
fi
pc() { PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config "$@"; }
if cc -std=c11 -Wall -Wextra -Werror "$src/tests/embed/consumer/gltf_to_png.c" $(pc --cflags --libs mvr-gltf mvr-image) \
        -Wl,-rpath,"$prefix/lib" -o "$out/gltf_pc_shared" 2> "$out/pc_gltf.log"; then
    png_ok "pkg-config mvr-gltf mvr-image" "$out/gltf_pc_shared" "$out/gltf_pc_shared.png"
else
    bad "cc with pkg-config mvr-gltf mvr-image"; cat "$out/pc_gltf.log"
fi
if cc -std=c11 -Wall -Wextra -Werror "$src/tests/embed/consumer/gltf_to_png.c" $(pc --cflags --libs mvr-gltf-static mvr-image-static) \
        -o "$out/gltf_pc_static" 2> "$out/pc_gltf_static.log"; then
    png_ok "pkg-config mvr-gltf-static mvr-image-static" "$out/gltf_pc_static" "$out/gltf_pc_static.png"
else
    bad "cc with pkg-config mvr-gltf-static mvr-image-static"; cat "$out/pc_gltf_static.log"
fi
for png in "$out"/gltf_cmake_shared.png "$out"/gltf_pc_shared.png "$out"/gltf_pc_static.png; do
    [ -s "$png" ] && [ -s "$out/gltf_cmake_static.png" ] || continue
    cmp -s "$png" "$out/gltf_cmake_static.png" && ok "$(basename "$png") equals gltf_cmake_static.png" ||
        bad "$(basename "$png") differs from gltf_cmake_static.png"
done
# the shared libraries need no dependency's .pc file or headers to be found
for m in mvr mvr-image mvr-gltf; do
    r=$(pc --print-requires "$m" | tr '\n' ' ')
    echo "$m requires: ${r:-nothing} (private: $(pc --print-requires-private "$m" | tr '\n' ' '))"
done
pc --print-requires --print-requires-private mvr | grep -q osmesa && bad "mvr.pc requires osmesa" || ok "mvr.pc does not require osmesa"
# libmvr's API: the installed mvr.h and the headers it includes (one not
# installed fails the check)
api="$prefix/include/mvr/mvr.h"
for h in $(sed -n 's|^#include "mvr/\(mvr_[a-z_]*\.h\)".*|\1|p' "$api"); do api="$api:$prefix/include/mvr/$h"; done
"$src/tests/embed/check_exports.sh" "$src" "$out/exports" "$prefix/lib/libmvr.so=$api" \
    "$prefix/lib/libmvr_image.so=$src/include/mvr/mvr_image.h" "$prefix/lib/libmvr_gltf.so=$src/include/mvr/mvr_gltf.h" ||
    bad "the installed shared libraries export more or less than their headers declare"
exit $fail
