/* The renderer's overrides: the check mvr_renderer_create makes (gl/overrides.c). */
#ifndef MVR_OVERRIDES_H
#define MVR_OVERRIDES_H

#include "mvr/mvr.h"

/* Every override field a value its type has. */
mvr_result mvr_overrides_check(const mvr_renderer_overrides *o, mvr_error *error);

#endif
