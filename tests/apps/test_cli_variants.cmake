# ctest script: `mvr render --variant` and `mvr info` with a real exporter's file with material
# variants (tests/data/peers/variants.gltf, Blender 3.4.1: scripts/peers/blender_variants.py): a
# board whose left half maps 'red' and 'ruby' to a red material and 'blue' to a blue one; its
# right half has no mappings.
# cmake -DMVR=path/to/mvr -DFILE=variants.gltf -DOUT=dir -P test_cli_variants.cmake
# (which pixels change, and to which colour, is io_variants_file's to check)
include(${CMAKE_CURRENT_LIST_DIR}/cli_expect.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

# one view of 64x64 (the file's camera has aspect 1) into DIR: render_view(DIR ARGS...) ->
# ${DIR}_hash (the PNG's SHA256, empty when the run failed)
function(render_view dir)
  run(rc so se render ${FILE} --views 1 --size 64x64 --out ${OUT}/${dir} --quiet ${ARGN})
  set(hash "")
  if(rc EQUAL 0 AND EXISTS ${OUT}/${dir}/view_0000.png)
    file(SHA256 ${OUT}/${dir}/view_0000.png hash)
  else()
    message("FAIL: render ${ARGN} exits ${rc}: ${se}")
    math(EXPR n_failed "${n_failed} + 1")
    set(n_failed ${n_failed} PARENT_SCOPE)
  endif()
  set(${dir}_hash "${hash}" PARENT_SCOPE)
endfunction()

# mvr info FILE lists the variants in file order (the exporter's: red, ruby, blue)
run(rc so se info ${FILE})
expect("mvr info FILE exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("mvr info counts 3 variants: ${so}" so MATCHES "variants +3")
expect("mvr info lists them in file order: ${so}" so MATCHES "0 +'red'\n +1 +'ruby'\n +2 +'blue'")
run(rc so se info ${FILE} --json)
string(JSON name ERROR_VARIABLE jerr GET "${so}" variants 2 name)
string(JSON count ERROR_VARIABLE jerr2 LENGTH "${so}" variants)
expect("--json: 3 variants, variants[2] is 'blue' (${count} ${name}; ${jerr} ${jerr2})" count EQUAL 3 AND
       name STREQUAL "blue")
run(rc so se render --help)
expect("mvr render --help documents --variant" so MATCHES "--variant V")

render_view(default)
render_view(red --variant red)
render_view(ruby --variant ruby)
render_view(blue --variant blue)
render_view(index2 --variant 2)
render_view(index0 --variant 0)
expect("red and blue differ" red_hash AND blue_hash AND NOT red_hash STREQUAL blue_hash)
expect("red differs from the file's own materials" red_hash AND default_hash AND NOT red_hash STREQUAL default_hash)
expect("ruby maps the red material: the same bytes as red" ruby_hash AND ruby_hash STREQUAL red_hash)
expect("--variant 2 is --variant blue" index2_hash AND index2_hash STREQUAL blue_hash)
expect("--variant 0 is --variant red" index0_hash AND index0_hash STREQUAL red_hash)
# the summary names the variant
run(rc so se render ${FILE} --views 1 --size 64x64 --out ${OUT}/said --variant ruby)
expect("--variant ruby exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("the summary names the variant: ${so}" so MATCHES "variant +1 'ruby' [(]of 3[)]")

# unknown variants: an error listing the ones there are
run(rc so se render ${FILE} --variant green --out ${OUT}/green --quiet)
expect("--variant green exits 2 (got ${rc})" rc EQUAL 2)
expect("--variant green lists the variants: ${se}"
       se MATCHES "no variant named 'green'. its variants: 0 'red', 1 'ruby', 2 'blue'")
run(rc so se render ${FILE} --variant 3 --out ${OUT}/three --quiet)
expect("--variant 3 of 3 exits 2 (got ${rc}): ${se}" rc EQUAL 2 AND se MATCHES "3 variants [(]0[.][.]2[)]")
run(rc so se render --demo stereo --variant red --out ${OUT}/demo --quiet)
expect("--variant with a demo is refused (got ${rc}): ${se}" rc EQUAL 2 AND se MATCHES "--variant is for a SCENE file")

expect_summary("CLI variants")
