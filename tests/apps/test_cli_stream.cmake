# ctest script: mvr render --readback stream (the default: chunks of GL_MAX_VIEWS_OVR views through a
# ring of targets, asynchronous readback, encoding on threads) writes the same files as --readback sync
# (one target of every view, each layer read and written in turn), byte for byte: a real exporter's
# model (Blender's Suzanne, tests/data/peers/textured.gltf) seen by 14 views on a sphere (3 chunks on
# llvmpipe's 6 views), with 1, 2 and 3 encoders, as EXR, supersampled, and an animated file's frame
# sequence, and with the extra outputs (--outputs: the same .npy files); the stats say how it ran; the contact sheet of wide views stays within 4096 pixels; names
# grow past 99 views; a terminal gets a progress line (--no-progress and pipes none).
# cmake -DMVR=path/to/mvr -DPEERS=tests/data/peers -DOUT=dir -P test_cli_stream.cmake
include(${CMAKE_CURRENT_LIST_DIR}/cli_expect.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(FILE ${PEERS}/textured.gltf)

# render_into(DIR ARGS...): mvr render ARGS --out OUT/DIR --quiet, which must exit 0
function(render_into dir)
  run(rc so se render ${ARGN} --out ${OUT}/${dir} --quiet)
  if(NOT rc EQUAL 0)
    message("FAIL: render ${ARGN} exits ${rc}: ${se}")
    math(EXPR n_failed "${n_failed} + 1")
  else()
    math(EXPR n_passed "${n_passed} + 1")
  endif()
  set(n_failed ${n_failed} PARENT_SCOPE)
  set(n_passed ${n_passed} PARENT_SCOPE)
endfunction()

# same_files(A B COUNT): every file of OUT/B (the synchronous run) is in OUT/A with the same
# bytes, and there are COUNT of them; EXR files (whose header holds the second they were
# written) with the same pixels, bit for bit (OpenImageIO's idiff; skipped without it)
find_program(IDIFF idiff)
function(same_files a b count)
  file(GLOB_RECURSE files RELATIVE ${OUT}/${b} ${OUT}/${b}/*) # annotations/ too
  list(LENGTH files n)
  set(differ "")
  set(n_differ 0)
  foreach(f ${files})
    if(f MATCHES "[.]exr$" AND IDIFF)
      execute_process(COMMAND ${IDIFF} -fail 0 -warn 0 ${OUT}/${a}/${f} ${OUT}/${b}/${f} RESULT_VARIABLE d
                      OUTPUT_QUIET ERROR_QUIET)
    elseif(f MATCHES "[.]exr$")
      message("idiff not found: ${f} not compared")
      continue()
    else()
      execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/${a}/${f} ${OUT}/${b}/${f} RESULT_VARIABLE d)
    endif()
    if(NOT d EQUAL 0)
      list(APPEND differ ${f})
      math(EXPR n_differ "${n_differ} + 1")
    endif()
  endforeach()
  expect("${a} and ${b}: ${count} files (got ${n})" n EQUAL ${count})
  expect("${a} writes ${b}'s bytes; these differ: ${differ}" n_differ EQUAL 0)
  set(n_failed ${n_failed} PARENT_SCOPE)
  set(n_passed ${n_passed} PARENT_SCOPE)
endfunction()

set(SPHERE ${FILE} --layout sphere --views 14 --size 64x64)
render_into(sync ${SPHERE} --readback sync --stats ${OUT}/sync.json)
render_into(stream ${SPHERE} --stats ${OUT}/stream.json)
render_into(stream1 ${SPHERE} --readback stream --encoders 1)
render_into(stream3 ${SPHERE} --encoders 3)
# 14 views, the contact sheet, cameras.json, transforms.json
same_files(stream sync 17)
same_files(stream1 sync 17)
same_files(stream3 sync 17)

# the stats: every view of the frame, how it came back
file(READ ${OUT}/stream.json js)
string(JSON mode ERROR_VARIABLE e1 GET "${js}" readback mode)
string(JSON chunk ERROR_VARIABLE e2 GET "${js}" readback chunk_views)
string(JSON images ERROR_VARIABLE e3 GET "${js}" readback images)
string(JSON views ERROR_VARIABLE e4 GET "${js}" views)
string(JSON culled ERROR_VARIABLE e5 LENGTH "${js}" culled_per_view)
expect("stream.json: readback stream, 14 images of 14 views, 14 culled counts (${mode} ${images} ${views} ${culled}; ${e1}${e3}${e4}${e5})"
       mode STREQUAL "stream" AND images EQUAL 14 AND views EQUAL 14 AND culled EQUAL 14)
expect("stream.json: chunks of 1 .. 14 views (${chunk} ${e2})" chunk GREATER 0 AND chunk LESS 15)
file(READ ${OUT}/sync.json js)
string(JSON mode ERROR_VARIABLE e1 GET "${js}" readback mode)
expect("sync.json: readback sync (${mode} ${e1})" mode STREQUAL "sync")

# --outputs all: depth, distance, normal, ids and coverage come back through the stream too (one
# more asynchronous readback per output per ring slot), written as the same .npy bytes; and over the
# 2 frames of an animated file (<output>_VVVV_fFFFF.npy)
render_into(aov_sync ${SPHERE} --outputs all --readback sync)
render_into(aov ${SPHERE} --outputs all --stats ${OUT}/aov.json)
# 14 views x (an image, 5 .npy and the default PNGs: depth, mask, 4 ID kinds, the ID preview), the
# contact sheet, cameras.json, transforms.json, ids.json, annotations/instances{,_mesh}.json
same_files(aov aov_sync 188)
file(READ ${OUT}/aov.json js)
string(JSON mode ERROR_VARIABLE e1 GET "${js}" readback mode)
expect("aov.json: --outputs streams (readback ${mode} ${e1})" mode STREQUAL "stream")
set(ANIM_AOV ${PEERS}/rigged.gltf --layout orbit --views 7 --size 32x32 --frames 2 --outputs depth,ids)
render_into(anim_aov_sync ${ANIM_AOV} --readback sync)
render_into(anim_aov ${ANIM_AOV} --encoders 3)
same_files(anim_aov anim_aov_sync 146) # 7 views x 2 frames x (image, 2 .npy, 7 PNGs) + 4 + 2 annotations
# an .npy that cannot be written (a folder in its place) fails the streamed run, naming it
file(MAKE_DIRECTORY ${OUT}/aov_bad/depth_0003.npy)
run(rc so se render ${SPHERE} --outputs depth --out ${OUT}/aov_bad --quiet)
expect("an unwritable depth_0003.npy exits 1, naming it (got ${rc}): ${se}"
       rc EQUAL 1 AND se MATCHES "cannot write [^\n]*depth_0003[.]npy")

# EXR (a float target, linear values; the sheet from the sRGB-encoded floats), supersampling (a
# float target 2x the size, resolved on the encoder threads), and 7 views of an animated file over
# 2 frames (view_VVVV_fFFFF.png)
render_into(exr_sync ${FILE} --layout ring --views 8 --size 48x48 --format exr --readback sync)
render_into(exr ${FILE} --layout ring --views 8 --size 48x48 --format exr)
same_files(exr exr_sync 11)
render_into(ss_sync ${FILE} --layout orbit --views 7 --size 32x32 --supersample 2 --readback sync)
render_into(ss ${FILE} --layout orbit --views 7 --size 32x32 --supersample 2)
same_files(ss ss_sync 10)
set(ANIM ${PEERS}/rigged.gltf --layout orbit --views 7 --size 32x32 --frames 2)
render_into(anim_sync ${ANIM} --readback sync)
render_into(anim ${ANIM})
same_files(anim anim_sync 17)

# wide views: the sheet's tiles shrink to keep it within 4096 pixels a side (6 columns of 1024 would be
# 6164) and 4 megapixels
run(rc so se render ${FILE} --layout ring --views 30 --size 1024x32 --out ${OUT}/wide)
expect("30 wide views exit 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("the summary says the tiles are halved: ${so}" so MATCHES "tiles at 1/2 of the views' size")
if(EXISTS ${OUT}/wide/contact_sheet.png)
  file(READ ${OUT}/wide/contact_sheet.png ihdr OFFSET 16 LIMIT 8 HEX) # PNG: width, height (big-endian)
  string(SUBSTRING "${ihdr}" 0 8 w_hex)
  math(EXPR sheet_w "0x${w_hex}")
  expect("the sheet is 6 tiles of 512 and 5 gaps of 4 wide (got ${sheet_w})" sheet_w EQUAL 3092)
endif()

# many views: 70 tiles of 256 would make 4.8 megapixels (9 x 8 tiles), so they are halved
run(rc so se render --demo cube --views 70 --size 256x256 --out ${OUT}/area)
expect("70 views of 256 exit 0 (got ${rc}): ${se}" rc EQUAL 0 AND so MATCHES "tiles at 1/2 of the views' size")
if(EXISTS ${OUT}/area/contact_sheet.png)
  file(READ ${OUT}/area/contact_sheet.png ihdr OFFSET 16 LIMIT 8 HEX)
  string(SUBSTRING "${ihdr}" 0 8 w_hex)
  string(SUBSTRING "${ihdr}" 8 8 h_hex)
  math(EXPR sheet_w "0x${w_hex}")
  math(EXPR sheet_h "0x${h_hex}")
  expect("70 views: a sheet of 9 x 8 tiles of 128 (got ${sheet_w} x ${sheet_h})" sheet_w EQUAL 1184 AND sheet_h EQUAL 1052)
endif()

# past 99 views the numbers grow a digit
render_into(many --demo cube --views 101 --size 8x8)
expect("view_0100.png after view_0099.png: names sort in view order" EXISTS ${OUT}/many/view_0099.png AND EXISTS ${OUT}/many/view_0100.png)

# bad values are refused before anything runs
run(rc so se render --demo stereo --readback fast --out ${OUT}/bad)
expect("--readback fast exits 2 (got ${rc}): ${se}" rc EQUAL 2 AND se MATCHES "stream")
run(rc so se render --demo stereo --encoders 0 --out ${OUT}/bad)
expect("--encoders 0 exits 2 (got ${rc})" rc EQUAL 2)
run(rc so se render --help)
expect("--help documents --readback, --encoders, --no-progress" so MATCHES "--readback R" AND so MATCHES "--encoders N"
       AND so MATCHES "--no-progress")

# a progress line on a terminal (script(1) gives the run one), none on a pipe or with --no-progress
run(rc so se render ${SPHERE} --out ${OUT}/pipe)
expect("no progress line on a pipe: ${se}" NOT se MATCHES "views/s +ETA")
find_program(SCRIPT script)
if(SCRIPT)
  execute_process(COMMAND ${SCRIPT} -qec "${MVR} render ${FILE} --layout sphere --views 14 --size 64x64 --out ${OUT}/tty"
                          /dev/null RESULT_VARIABLE rc OUTPUT_VARIABLE so ERROR_VARIABLE se)
  expect("on a terminal: a progress line with views/s and the final count (${rc}): ${so}"
         rc EQUAL 0 AND so MATCHES "[[][#.]+[]] [0-9]+/14 views +[0-9.]+ views/s" AND so MATCHES "14/14 views")
  execute_process(COMMAND ${SCRIPT} -qec "${MVR} render ${FILE} --layout sphere --views 14 --size 64x64 --out ${OUT}/tty --no-progress"
                          /dev/null RESULT_VARIABLE rc OUTPUT_VARIABLE so ERROR_VARIABLE se)
  expect("--no-progress: none (${rc}): ${so}" rc EQUAL 0 AND NOT so MATCHES "/14 views")
else()
  message("script(1) not found: the terminal's progress line is not checked")
endif()
expect_summary("mvr render --readback")
