/* The shaders/ directory, embedded at build time by cmake/embed_shaders.cmake. */
#ifndef MVR_SHADER_FILES_H
#define MVR_SHADER_FILES_H

#include <stddef.h>

typedef struct mvr_shader_file {
    const char *name;   /* file name in shaders/, e.g. "mesh.vert.glsl" */
    const char *text;
    size_t length;
} mvr_shader_file;

extern const mvr_shader_file mvr_shader_files[];
extern const unsigned mvr_shader_file_count;

/* NULL when no such file was embedded. */
const mvr_shader_file *mvr_shader_file_find(const char *name);

#endif
