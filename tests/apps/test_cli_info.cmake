# ctest script: the mvr CLI's info command, as a user and a machine read it.
# cmake -DMVR=path/to/mvr -DREQUIRE_MULTIVIEW=ON|OFF -DWITH_OSMESA=ON|OFF -P test_cli_info.cmake
include(${CMAKE_CURRENT_LIST_DIR}/cli_expect.cmake)

# --help everywhere, exit 0, on stdout
run(rc so se --help)
expect("mvr --help exits 0 (got ${rc})" rc EQUAL 0)
expect("mvr --help lists the info command" so MATCHES "info")
run(rc so se info --help)
expect("mvr info --help exits 0 (got ${rc})" rc EQUAL 0)
expect("mvr info --help documents --context" so MATCHES "--context")
run(rc so se --version)
expect("mvr --version prints a version: ${so}" so MATCHES "^mvr [0-9]+[.][0-9]+[.][0-9]+")

# usage errors: exit 2 with a message, no crash
run(rc so se)
expect("mvr with no command exits 2 (got ${rc})" rc EQUAL 2)
run(rc so se frobnicate)
expect("unknown command exits 2 (got ${rc})" rc EQUAL 2)
expect("unknown command is named: ${se}" se MATCHES "unknown command 'frobnicate'")
run(rc so se info --context nosuch)
expect("bad provider name exits 2 (got ${rc})" rc EQUAL 2)
expect("bad provider is named: ${se}" se MATCHES "unknown context provider 'nosuch'")
run(rc so se info --device 1)
expect("--device without --context device exits 2 (got ${rc})" rc EQUAL 2)
run(rc so se info --context)
expect("--context without a value exits 2 (got ${rc})" rc EQUAL 2)

# --json is valid JSON with the fields machines read
run(rc so se info --json)
expect("mvr info --json exits 0 (got ${rc}): ${se}" rc EQUAL 0)
string(JSON renderer ERROR_VARIABLE jerr GET "${so}" renderer)
expect("mvr info --json parses: ${jerr}" NOT jerr)
expect("renderer is not empty" renderer)
string(JSON provider ERROR_VARIABLE jerr GET "${so}" provider)
expect("default provider here is surfaceless (got ${provider})" provider STREQUAL "surfaceless")
string(JSON mv2 ERROR_VARIABLE jerr GET "${so}" extensions GL_OVR_multiview2)
string(JSON max_views ERROR_VARIABLE jerr GET "${so}" limits max_views_ovr)
string(JSON layers ERROR_VARIABLE jerr GET "${so}" limits max_array_texture_layers)
expect("max_array_texture_layers >= 256 (got ${layers})" layers GREATER_EQUAL 256)
message("mvr info --json: ${renderer}, GL_OVR_multiview2=${mv2}, max_views_ovr=${max_views}")
if(REQUIRE_MULTIVIEW)
  expect("GL_OVR_multiview2 is true (got ${mv2})" mv2 STREQUAL "ON" OR mv2 STREQUAL "true")
  expect("max_views_ovr >= 2 (got ${max_views})" max_views GREATER_EQUAL 2)
  run(rc so se info --require-multiview)
  expect("--require-multiview passes (got ${rc}): ${se}" rc EQUAL 0)
endif()

# providers by name
run(rc so se info --json --context device)
expect("--context device works here (got ${rc}): ${se}" rc EQUAL 0)
string(JSON dev ERROR_VARIABLE jerr GET "${so}" egl_device)
expect("the device provider names its device (got ${dev})" dev)
if(WITH_OSMESA)
  run(rc so se info --json --context osmesa)
  expect("--context osmesa works (got ${rc}): ${se}" rc EQUAL 0)
  string(JSON api ERROR_VARIABLE jerr GET "${so}" api)
  expect("osmesa gives desktop GL (got ${api})" api STREQUAL "desktop")
endif()

# no display: the pbuffer provider fails with a message, exit 1 (Mesa's EGL);
# an EGL whose default display needs no window system (NVIDIA's) gives a
# working context instead, and info prints its GL
set(ENV{DISPLAY} "")
unset(ENV{DISPLAY})
unset(ENV{WAYLAND_DISPLAY})
run(rc so se info --context pbuffer)
if(rc EQUAL 0)
  expect("pbuffer with a headless default display prints its GL: ${so}" so MATCHES "GL")
else()
  expect("pbuffer without a display exits 1 (got ${rc})" rc EQUAL 1)
  expect("pbuffer failure names the result: ${se}" se MATCHES "MVR_ERROR_NO_DISPLAY")
endif()

expect_summary("CLI")
