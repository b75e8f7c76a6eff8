#!/usr/bin/env bash
# ctest embed_exports: each shared library exports exactly the functions its
# public headers declare (the same extraction as the build's version scripts,
# cmake/mvr_exports.cmake): no internal mvr_ helper, nothing without the mvr_
# prefix, and no declared function missing. Prints both differences.
# usage: check_exports.sh SOURCE_DIR OUT LIBRARY=HEADER[:HEADER...]...
# (a library whose API is several headers names them all, ':' between)
set -u
src=$1 out=$2; shift 2
mkdir -p "$out"
fail=0
for pair in "$@"; do
    lib=${pair%%=*} headers=${pair#*=}
    name=$(basename "$lib")
    want="$out/$name.api" have="$out/$name.dynsym"
    # the headers' names, for the messages: "mvr.h mvr_base.h ..."
    header="" && IFS=: read -ra paths <<< "$headers"
    for h in "${paths[@]}"; do header="$header${header:+ }$(basename "$h")"; done
    cmake -DHEADERS="${headers//:/;}" -DLIST="$want" -P "$src/cmake/mvr_exports.cmake" ||
        { echo "FAIL: $header: no API list"; fail=1; continue; }
    # every defined dynamic symbol, whatever its kind (functions, data, weak)
    nm -D --defined-only "$lib" | awk '{print $NF}' | sed 's/@.*//' | sort -u > "$have"
    extra=$(comm -13 "$want" "$have") missing=$(comm -23 "$want" "$have")
    echo "$name: $(wc -l < "$have") exported, $(wc -l < "$want") declared in $header"
    if [ -n "$extra" ]; then
        echo "FAIL: $name exports $(echo "$extra" | wc -l) symbols $header does not declare:"
        echo "$extra" | sed 's/^/  + /'
        fail=1
    fi
    if [ -n "$missing" ]; then
        echo "FAIL: $name lacks $(echo "$missing" | wc -l) functions $header declares:"
        echo "$missing" | sed 's/^/  - /'
        fail=1
    fi
    [ -z "$extra$missing" ] && echo "ok: $name exports exactly the API of $header"
done
exit $fail
