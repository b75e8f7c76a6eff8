# Cross build of the embeddable libraries (mvr_core, mvr_gl) for 64-bit ARM
# Linux with Debian's cross compiler (gcc-aarch64-linux-gnu):
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DMVR_LIBS_ONLY=ON
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# no host .pc files: the device's EGL is linked by name by whoever links the app
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig)
# The Khronos headers (EGL, GLES, KHR) are the same on every architecture,
# but the cross compiler does not search the host's /usr/include: a staging
# directory holds only them.
set(MVR_KHR_STAGING ${CMAKE_BINARY_DIR}/khr-include)
foreach(dir EGL GLES2 GLES3 KHR)
  if(NOT EXISTS ${MVR_KHR_STAGING}/${dir})
    file(MAKE_DIRECTORY ${MVR_KHR_STAGING})
    file(CREATE_LINK /usr/include/${dir} ${MVR_KHR_STAGING}/${dir} SYMBOLIC)
  endif()
endforeach()
set(MVR_EGL_INCLUDE_DIR ${MVR_KHR_STAGING} CACHE PATH "EGL headers (staged)")
set(MVR_GLES3_INCLUDE_DIR ${MVR_KHR_STAGING} CACHE PATH "GLES headers (staged)")
