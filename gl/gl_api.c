#include <string.h>

#include "core_util.h"
#include "gl_api.h"

/* ISO C forbids converting an object pointer to a function pointer; copy the
 * bits instead (POSIX guarantees they have the same representation). */
#define MVR_GL_ASSIGN(dst, ptr) memcpy(&(dst), &(ptr), sizeof(dst))

/* Resolves the names of a "a\0b\0" list, preferring the second on desktop GL. */
static void *load_optional(const char *names, bool desktop, mvr_gl_loader_fn load, void *user_data)
{
    const char *first = names;
    const char *second = first + strlen(first) + 1;
    const char *order[2] = {first, *second ? second : NULL};
    if (desktop && order[1]) {
        order[0] = second;
        order[1] = first;
    }
    for (int i = 0; i < 2; ++i) {
        void *p = order[i] ? load(order[i], user_data) : NULL;
        if (p)
            return p;
    }
    return NULL;
}

bool mvr_gl_api_load(mvr_gl_api_table *gl, mvr_gl_loader_fn load, void *user_data, bool desktop,
                     char *missing, size_t missing_size)
{
    memset(gl, 0, sizeof *gl);
    void *p;
#define MVR_GL_LOAD_CORE(type, name)                                 \
    p = load("gl" #name, user_data);                                 \
    if (!p) {                                                        \
        mvr_str_copy(missing, missing_size, "gl" #name);             \
        return false;                                                \
    }                                                                \
    MVR_GL_ASSIGN(gl->name, p);
    MVR_GL_CORE_FUNCS(MVR_GL_LOAD_CORE)
#undef MVR_GL_LOAD_CORE

#define MVR_GL_LOAD_OPTIONAL(type, name, names)                      \
    p = load_optional(names, desktop, load, user_data);              \
    if (p)                                                           \
        MVR_GL_ASSIGN(gl->name, p);
    MVR_GL_OPTIONAL_FUNCS(MVR_GL_LOAD_OPTIONAL)
#undef MVR_GL_LOAD_OPTIONAL
    return true;
}
