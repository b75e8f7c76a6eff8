# ctest script: `mvr render` and `mvr info` with a node-animated glTF file
# (make_animated_gltf.py: 'slide' moves a box over 0..1 s, 'spin' turns a bar
# over 0..2 s; node TRS animation only, no skins).
# cmake -DMVR=path/to/mvr -DOUT=dir -P test_cli_animation.cmake
include(${CMAKE_CURRENT_LIST_DIR}/cli_expect.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

find_program(PYTHON3 python3)
expect("python3 is on PATH (it writes the test file)" PYTHON3)
set(anim ${OUT}/animated.gltf)
execute_process(COMMAND ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/make_animated_gltf.py ${anim} RESULT_VARIABLE rc
                ERROR_VARIABLE se)
expect("make_animated_gltf.py writes ${anim} (got ${rc}): ${se}" rc EQUAL 0 AND EXISTS ${anim})

# one view of 96x72 into DIR: render_view(DIR ARGS...) -> ${DIR}_hash (the
# PNG's SHA256, empty when the run failed)
function(render_view dir)
  run(rc so se render ${anim} --views 1 --size 96x72 --out ${OUT}/${dir} --quiet ${ARGN})
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

# mvr info FILE: the animations as --animation takes them, no GL needed
run(rc so se info ${anim})
expect("mvr info FILE exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("mvr info counts 2 animations: ${so}" so MATCHES "animations +2")
expect("mvr info lists animation 0 'slide' 0 .. 1 s with 1 channel: ${so}"
       so MATCHES "0 +'slide' +0 [.][.] 1 s, 1 channel")
expect("mvr info lists animation 1 'spin' 0 .. 2 s: ${so}" so MATCHES "1 +'spin' +0 [.][.] 2 s, 1 channel")
expect("mvr info reports skins and joints: ${so}" so MATCHES "skins +0 [(]0 joints[)]")
expect("mvr info reports morph targets: ${so}" so MATCHES "morph targets 0")
run(rc so se info ${anim} --json)
expect("mvr info FILE --json exits 0 (got ${rc}): ${se}" rc EQUAL 0)
string(JSON name ERROR_VARIABLE jerr GET "${so}" animations 1 name)
string(JSON end ERROR_VARIABLE jerr2 GET "${so}" animations 1 end)
string(JSON channels ERROR_VARIABLE jerr3 GET "${so}" animations 0 channels)
expect("--json: animations[1] is 'spin' ending at 2 s (${name}, ${end}; ${jerr} ${jerr2})" name STREQUAL "spin" AND
       end EQUAL 2)
expect("--json: animations[0] has 1 channel (${channels}; ${jerr3})" channels EQUAL 1)
foreach(key skins joints morph_targets nodes meshes)
  string(JSON v ERROR_VARIABLE jerr GET "${so}" ${key})
  expect("--json has ${key} (${jerr})" NOT jerr)
endforeach()
run(rc so se info ${OUT}/nosuch.gltf)
expect("mvr info of a missing file exits 1 (got ${rc}): ${se}" rc EQUAL 1)
run(rc so se info ${anim} --context device)
expect("mvr info FILE --context is refused (got ${rc}): ${se}" rc EQUAL 2 AND se MATCHES "--context is about the GL")
run(rc so se info --help)
expect("mvr info --help documents the FILE form" so MATCHES "mvr info SCENE.gltf")

# no animation option: the rest pose, nothing said about animations
run(rc so se render ${anim} --views 1 --size 96x72 --out ${OUT}/rest --stats ${OUT}/rest/stats.json)
expect("render at rest exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("no animation line at rest: ${so}" NOT so MATCHES "animation ")
if(EXISTS ${OUT}/rest/stats.json)
  file(READ ${OUT}/rest/stats.json stats)
  string(JSON type ERROR_VARIABLE jerr TYPE "${stats}" animation)
  expect("stats: animation is null at rest (${type} ${jerr})" type STREQUAL "NULL")
  foreach(key skinning_path joints morph_targets_active animation_upload_bytes preskin_passes)
    string(JSON v ERROR_VARIABLE jerr GET "${stats}" ${key})
    expect("stats.json has ${key} (${jerr})" NOT jerr)
  endforeach()
  string(JSON path GET "${stats}" skinning_path)
  expect("nothing skinned: skinning_path auto (${path})" path STREQUAL "auto")
endif()

# --time moves the box: two times differ, the same time gives the same bytes
render_view(slide_25 --animation slide --time 0.25)
render_view(slide_75 --animation slide --time 0.75)
render_view(slide_25b --animation slide --time 0.25)
expect("--time 0.25 and 0.75 differ" slide_25_hash AND slide_75_hash AND NOT slide_25_hash STREQUAL slide_75_hash)
expect("--time 0.25 twice: the same bytes" slide_25_hash AND slide_25_hash STREQUAL slide_25b_hash)
# by index as by name
render_view(index_25 --animation 0 --time 0.25)
expect("--animation 0 is --animation slide" index_25_hash AND index_25_hash STREQUAL slide_25_hash)
render_view(spin_1 --animation spin --time 1)
render_view(index1_1 --animation 1 --time 1)
expect("--animation 1 is --animation spin" spin_1_hash AND spin_1_hash STREQUAL index1_1_hash)
render_view(slide_1 --animation slide --time 1)
expect("'spin' at 1 s is not 'slide' at 1 s" spin_1_hash AND NOT spin_1_hash STREQUAL slide_1_hash)
# --time alone plays animation 0
render_view(time_25 --time 0.25)
expect("--time without --animation plays animation 0" time_25_hash AND time_25_hash STREQUAL slide_25_hash)
# after the clip: clamped to its last key, or with --loop wrapped into it
render_view(clamp_5 --animation slide --time 5)
expect("--time 5 holds the last key (= 1 s)" clamp_5_hash AND clamp_5_hash STREQUAL slide_1_hash)
render_view(loop_125 --animation slide --time 1.25 --loop)
expect("--time 1.25 --loop is 0.25 s" loop_125_hash AND loop_125_hash STREQUAL slide_25_hash)
# every animation at once
render_view(all_5 --animation all --time 0.5)
render_view(slide_5 --animation slide --time 0.5)
render_view(spin_5 --animation spin --time 0.5)
expect("--animation all differs from each alone" all_5_hash AND NOT all_5_hash STREQUAL slide_5_hash AND
       NOT all_5_hash STREQUAL spin_5_hash)
# the skinning path changes nothing for a file without skins
render_view(preskin_25 --animation slide --time 0.25 --skinning preskin)
render_view(vertex_25 --animation slide --time 0.25 --skinning vertex)
expect("--skinning preskin: same pixels" preskin_25_hash AND preskin_25_hash STREQUAL slide_25_hash)
expect("--skinning vertex: same pixels" vertex_25_hash AND vertex_25_hash STREQUAL slide_25_hash)

# names that are not there: an error listing the ones there are
run(rc so se render ${anim} --animation nope --out ${OUT}/nope --quiet)
expect("--animation nope exits 2 (got ${rc})" rc EQUAL 2)
expect("--animation nope lists the names: ${se}"
       se MATCHES "no animation named 'nope'. its animations: 0 'slide', 1 'spin'")
run(rc so se render ${anim} --animation 2 --out ${OUT}/two --quiet)
expect("--animation 2 of 2 exits 2 (got ${rc}): ${se}" rc EQUAL 2 AND se MATCHES "has 2 animations [(]0[.][.]1[)]")

# --frames 3 --fps 10: view_VVVV_fFFFF.png at 0, 0.1 and 0.2 s, per view
run(rc so se render ${anim} --views 2 --size 96x72 --frames 3 --fps 10 --out ${OUT}/seq --stats ${OUT}/seq/stats.json)
expect("--frames 3 --fps 10 exits 0 (got ${rc}): ${se}" rc EQUAL 0)
foreach(v 0000 0001)
  foreach(f 0000 0001 0002)
    expect("seq/view_${v}_f${f}.png written" EXISTS ${OUT}/seq/view_${v}_f${f}.png)
  endforeach()
endforeach()
expect("no frame 3" NOT EXISTS ${OUT}/seq/view_0000_f0003.png)
expect("a sequence writes no view_0000.png" NOT EXISTS ${OUT}/seq/view_0000.png)
expect("contact_sheet.png written" EXISTS ${OUT}/seq/contact_sheet.png)
expect("it names the sequence: ${so}" so MATCHES "view_0000_f0000.png [.][.] view_0001_f0002.png [(]3 frames of 2 views[)]")
expect("it names the animation and the times: ${so}" so MATCHES "animation +0 'slide'.*t = 0 [.][.] 0.2 s")
if(EXISTS ${OUT}/seq/view_0000_f0002.png)
  run(rc so se render ${anim} --views 2 --size 96x72 --animation 0 --time 0.1 --out ${OUT}/seq_t01 --quiet)
  file(SHA256 ${OUT}/seq/view_0000_f0001.png f1)
  file(SHA256 ${OUT}/seq/view_0000_f0000.png f0)
  file(SHA256 ${OUT}/seq/view_0000_f0002.png f2)
  file(SHA256 ${OUT}/seq_t01/view_0000.png t01)
  expect("frame 1 is --time 0.1" f1 STREQUAL t01)
  expect("frames 0 and 2 differ" NOT f0 STREQUAL f2)
endif()
if(EXISTS ${OUT}/seq/stats.json)
  file(READ ${OUT}/seq/stats.json stats)
  string(JSON index ERROR_VARIABLE jerr GET "${stats}" animation index)
  string(JSON time ERROR_VARIABLE jerr2 GET "${stats}" animation time)
  string(JSON frames ERROR_VARIABLE jerr3 GET "${stats}" frames)
  expect("stats: animation 0, last time 0.2, 3 frames (${index} ${time} ${frames}; ${jerr} ${jerr2} ${jerr3})"
         index EQUAL 0 AND time MATCHES "^0[.]2" AND frames EQUAL 3)
endif()
# a demo has no animations: --frames renders it as it is
run(rc so se render --demo ring --views 1 --size 32x24 --frames 2 --out ${OUT}/demo_seq --quiet)
expect("--demo ring --frames 2 exits 0 (got ${rc}): ${se}" rc EQUAL 0 AND EXISTS ${OUT}/demo_seq/view_0000_f0001.png)

# bad values: exit 2 with a message naming the option
foreach(bad "--time;-1;--time takes seconds >= 0" "--time;nan;--time takes seconds >= 0"
            "--time;inf;--time takes seconds >= 0" "--time;2s;--time takes seconds >= 0"
            "--fps;0;--fps takes frames per second > 0" "--fps;-30;--fps takes frames per second > 0"
            "--frames;0;--frames takes 1..100000" "--frames;100001;--frames takes 1..100000"
            "--skinning;gpu;--skinning takes auto, vertex or preskin")
  list(GET bad 0 opt)
  list(GET bad 1 val)
  list(GET bad 2 want)
  run(rc so se render ${anim} --frames 2 ${opt} ${val} --out ${OUT}/bad --quiet)
  expect("${opt} ${val} exits 2 (got ${rc})" rc EQUAL 2)
  expect("${opt} ${val}: ${se}" se MATCHES "${want}")
endforeach()
run(rc so se render ${anim} --fps 10 --out ${OUT}/bad --quiet)
expect("--fps without --frames is refused: ${se}" rc EQUAL 2 AND se MATCHES "--fps is for --frames N")
run(rc so se render ${anim} --video ${OUT}/x.mp4 --out ${OUT}/bad --quiet)
expect("--video without --frames is refused: ${se}" rc EQUAL 2 AND se MATCHES "--video needs --frames N")
run(rc so se render --demo ring --animation 0 --out ${OUT}/bad --quiet)
expect("--animation with a demo is refused: ${se}" rc EQUAL 2 AND se MATCHES "--animation is for a SCENE file")

# --video: ffmpeg missing from PATH is named before anything renders
set(saved_path "$ENV{PATH}")
file(MAKE_DIRECTORY ${OUT}/empty_path)
set(ENV{PATH} "${OUT}/empty_path")
run(rc so se render ${anim} --frames 2 --video ${OUT}/novideo.mp4 --out ${OUT}/novideo --quiet)
expect("--video without ffmpeg exits 3 (got ${rc})" rc EQUAL 3)
expect("--video without ffmpeg says so: ${se}" se MATCHES "ffmpeg was not found on PATH")
expect("nothing rendered without ffmpeg" NOT EXISTS ${OUT}/novideo/view_0000_f0000.png)
# a stand-in ffmpeg records how mvr calls it: one run per view, the view's
# numbered sequence at --fps, FILE_view_VVVV.mp4
file(MAKE_DIRECTORY ${OUT}/fake_path)
file(WRITE ${OUT}/fake_path/ffmpeg "#!/bin/sh\necho \"$*\" >> \"${OUT}/fake_path/calls.txt\"\nfor last; do :; done\necho video > \"$last\"\n")
file(CHMOD ${OUT}/fake_path/ffmpeg PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
set(ENV{PATH} "${OUT}/fake_path")
run(rc so se render ${anim} --views 2 --size 64x48 --frames 2 --fps 12.5 --video ${OUT}/clip.mp4 --out ${OUT}/vid)
set(ENV{PATH} "${saved_path}")
expect("--video with ffmpeg exits 0 (got ${rc}): ${se}" rc EQUAL 0)
expect("clip_view_0000.mp4 written" EXISTS ${OUT}/clip_view_0000.mp4)
expect("clip_view_0001.mp4 written" EXISTS ${OUT}/clip_view_0001.mp4)
expect("it names the videos: ${so}" so MATCHES "video +.*clip_view_0000.mp4 [.][.] .*clip_view_0001.mp4")
if(EXISTS ${OUT}/fake_path/calls.txt)
  file(STRINGS ${OUT}/fake_path/calls.txt calls)
  list(LENGTH calls ncalls)
  expect("ffmpeg ran once per view (${ncalls})" ncalls EQUAL 2)
  expect("ffmpeg reads view 0's sequence at 12.5 fps: ${calls}"
         calls MATCHES "-framerate 12.5 -start_number 0 -i [^ ]*/vid/view_0000_f%04d.png .*clip_view_0000.mp4")
else()
  expect("the stand-in ffmpeg ran" FALSE)
endif()
# the real ffmpeg, where there is one
find_program(FFMPEG ffmpeg)
if(FFMPEG)
  run(rc so se render ${anim} --views 1 --size 63x47 --frames 4 --video ${OUT}/real.mp4 --out ${OUT}/real --quiet)
  expect("--video with ffmpeg encodes (got ${rc}): ${se}" rc EQUAL 0 AND EXISTS ${OUT}/real.mp4)
else()
  message("ffmpeg is not on PATH: the real encode is not tested")
endif()

# an animated camera: views made from the file's camera follow it
set(dolly ${OUT}/dolly.gltf)
execute_process(COMMAND ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/make_animated_gltf.py ${dolly} --dolly
                RESULT_VARIABLE rc ERROR_VARIABLE se)
expect("make_animated_gltf.py --dolly writes ${dolly} (got ${rc}): ${se}" rc EQUAL 0 AND EXISTS ${dolly})
foreach(t 0 1)
  run(rc so se render ${dolly} --views 1 --size 96x72 --out ${OUT}/dolly_${t} --quiet --animation dolly --time ${t})
  expect("render --animation dolly --time ${t} exits 0 (got ${rc}): ${se}" rc EQUAL 0)
  run(rc so se render ${dolly} --views 1 --size 96x72 --out ${OUT}/dolly_layout_${t} --quiet --animation dolly
      --time ${t} --layout stereo)
  expect("render --animation dolly --time ${t} --layout stereo exits 0 (got ${rc}): ${se}" rc EQUAL 0)
endforeach()
if(EXISTS ${OUT}/dolly_0/view_0000.png AND EXISTS ${OUT}/dolly_1/view_0000.png)
  file(SHA256 ${OUT}/dolly_0/view_0000.png d0)
  file(SHA256 ${OUT}/dolly_1/view_0000.png d1)
  expect("the file's camera, moved back by its animation, sees the scene smaller at 1 s" NOT d0 STREQUAL d1)
endif()
if(EXISTS ${OUT}/dolly_layout_0/view_0000.png AND EXISTS ${OUT}/dolly_layout_1/view_0000.png)
  file(SHA256 ${OUT}/dolly_layout_0/view_0000.png l0)
  file(SHA256 ${OUT}/dolly_layout_1/view_0000.png l1)
  expect("a layout's views ignore the moving camera (nothing else moves)" l0 STREQUAL l1)
endif()

run(rc so se render --help)
foreach(opt --animation --time --loop --frames --fps --video --skinning)
  expect("render --help lists ${opt}" so MATCHES "\n  ${opt} ")
endforeach()
expect("render --help says --frames plays animation 0" so MATCHES "--frames play animation 0")

expect_summary("CLI animation")
