# ctest script: what `mvr bench` renders and remembers (issue 37). A file
# with a camera is benched from it, as mvr render shows it (the default is
# --camera 0, not a layout); --camera and --layout are for a file; the
# reference renders in chunks of views that fit --reference-memory, with
# the same bytes as all at once (the cube demo: no shadows to fit per
# chunk); auto's settled choices are kept in the program cache folder and a
# corrupted entry is ignored with a warning. Tiny sizes and one frame: no
# assertion on times.
# cmake -DMVR=path/to/mvr -DOUT=dir -DDATA=tests/data -P test_cli_bench_views.cmake
include(${CMAKE_CURRENT_LIST_DIR}/cli_expect.cmake)
file(REMOVE_RECURSE ${OUT})
set(quick --size 32x32 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache off)

# the file's camera, as mvr render takes it
set(file ${DATA}/peers/textured.gltf)
foreach(case default camera layout)
  set(extra)
  if(case STREQUAL "camera")
    set(extra --camera 0)
  elseif(case STREQUAL "layout")
    set(extra --layout stereo)
  endif()
  run(rc so se bench ${file} ${quick} ${extra} --out ${OUT}/${case})
  expect("bench ${case} exits 0 (got ${rc}): ${se}" rc EQUAL 0)
  set(md5_${case} "none")
  if(EXISTS ${OUT}/${case}/reference.png)
    file(MD5 ${OUT}/${case}/reference.png md5_${case})
  endif()
endforeach()
expect("a file with a camera is benched from it (${md5_default} = ${md5_camera})"
       md5_default STREQUAL md5_camera AND NOT md5_default STREQUAL "none")
expect("--layout frames it instead (${md5_layout} differs)" NOT md5_layout STREQUAL md5_default)
run(rc so se bench ${file} ${quick} --camera 7 --out ${OUT}/bad)
expect("--camera 7 of a file with one camera fails naming it (${rc}): ${se}"
       NOT rc EQUAL 0 AND se MATCHES "1 camera nodes. --camera 7 is not one")
run(rc so se bench --demo cube ${quick} --camera 0 --out ${OUT}/bad)
expect("--camera is for a file (${rc}): ${se}" rc EQUAL 2 AND se MATCHES "--camera and --layout are for a SCENE file")
run(rc so se bench ${file} ${quick} --camera 0 --layout ring --out ${OUT}/bad)
expect("--camera and --layout conflict (${rc}): ${se}" rc EQUAL 2)

# the reference in chunks: 6 views of 4x4-supersampled 64x64 (1 MiB each) in 1 MiB
run(rc so se bench --demo cube --views 6 --size 64x64 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache off
    --out ${OUT}/whole)
expect("the whole reference exits 0 (got ${rc}): ${se}" rc EQUAL 0)
run(rc so se bench --demo cube --views 6 --size 64x64 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache off
    --reference-memory 1 --out ${OUT}/chunked)
expect("the chunked reference exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("the report says how the reference was rendered: ${so}" so MATCHES "reference rendered in 6 chunks of 1 views")
set(whole none)
set(chunked other)
if(EXISTS ${OUT}/whole/reference.png AND EXISTS ${OUT}/chunked/reference.png)
  file(MD5 ${OUT}/whole/reference.png whole)
  file(MD5 ${OUT}/chunked/reference.png chunked)
endif()
expect("chunks give the reference's bytes (${whole} ${chunked})" whole STREQUAL chunked)
# a reference a view of which does not fit at 4x4: fewer samples, said
run(rc so se bench --demo cube --views 2 --size 128x128 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache off
    --reference-memory 1 --out ${OUT}/smaller)
expect("a reference over the memory at 4x4 exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("and says how it was supersampled: ${so}" so MATCHES "reference supersampled 2x2")

# auto's settled choices remembered beside the program binaries
set(pc ${OUT}/programs)
run(rc so se bench --demo cube --views 2 --size 32x32 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache ${pc}
    --out ${OUT}/first)
expect("the first run exits 0 (got ${rc}): ${se}" rc EQUAL 0)
file(GLOB entries ${pc}/tuner-*.txt)
list(LENGTH entries n)
expect("it remembers auto's choices (${n} entries)" n GREATER 0)
foreach(e ${entries})
  file(READ ${e} text)
  expect("${e} is a tuner entry" text MATCHES "^mvr-tuner 1\nkey [^\n]*\nchosen [01]\nlog_ratio [-0-9.]+\nspread [0-9.]+\nruns [1-8]\ntag [0-9a-f]+\n$")
  string(REGEX REPLACE "runs [1-8]" "runs 9" text "${text}")
  file(WRITE ${e} "${text}")
endforeach()
run(rc so se bench --demo cube --views 2 --size 32x32 --frames 1 --rounds 1 --warmup 0 --quiet --program-cache ${pc}
    --out ${OUT}/second)
expect("a run over corrupted entries exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("and says it ignored them: ${se}" se MATCHES "tuner memory [^\n]*tuner-[0-9a-f]+-u[0-9]+[.]txt: its tag does not verify. ignored")

expect_summary("CLI bench views")
