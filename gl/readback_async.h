/* Asynchronous readback (gl/readback_async.c). */
#ifndef MVR_READBACK_ASYNC_H
#define MVR_READBACK_ASYNC_H

#include "mvr/mvr.h"

/* Releases every readback's GL objects and detaches it. */
void mvr_readbacks_release(mvr_renderer *r);

#endif
