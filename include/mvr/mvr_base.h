/*
 * mvr: the version, results and errors, and the logger every
 * descriptor carries.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_BASE_API_H
#define MVR_BASE_API_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MVR_VERSION_MAJOR 0
#define MVR_VERSION_MINOR 1
#define MVR_VERSION_PATCH 0

/* ------------------------------------------------------------------ results */

typedef enum mvr_result {
    MVR_OK = 0,
    MVR_ERROR_INVALID_ARGUMENT, /* a NULL, out-of-range or inconsistent argument */
    MVR_ERROR_OUT_OF_MEMORY,
    MVR_ERROR_UNSUPPORTED,      /* the build, driver or GL lacks what was asked for */
    MVR_ERROR_NO_DISPLAY,       /* no EGL display / device / platform could be opened */
    MVR_ERROR_CONTEXT,          /* context creation or make-current failed; or a call's context is not
                                   current on this thread, or was destroyed */
    MVR_ERROR_GL,               /* the GL reported an error (glGetError) */
    MVR_ERROR_SHADER,           /* a shader failed to compile or a program to link */
    MVR_ERROR_FRAMEBUFFER,      /* a framebuffer is incomplete */
    MVR_ERROR_IO,               /* a file could not be read or written */
    MVR_ERROR_PARSE,            /* malformed input data */
    MVR_ERROR_INVALID_ASSET,    /* a file that is not valid (glTF, image): the message names the part */
    MVR_ERROR_INTERNAL,         /* a bug in mvr: please report it */
    MVR_RESULT_COUNT_
} mvr_result;

/* "MVR_ERROR_NO_DISPLAY" etc.; never NULL. */
const char *mvr_result_name(mvr_result result);

#define MVR_ERROR_MESSAGE_SIZE 512

/* Filled by create calls that fail before an object exists. */
typedef struct mvr_error {
    mvr_result result;
    char message[MVR_ERROR_MESSAGE_SIZE];
} mvr_error;

/* ------------------------------------------------------------------ logging */

typedef enum mvr_log_level {
    MVR_LOG_DEFAULT = 0, /* as a threshold: MVR_LOG_INFO */
    MVR_LOG_ERROR,
    MVR_LOG_WARNING,
    MVR_LOG_INFO,
    MVR_LOG_DEBUG
} mvr_log_level;

/* Stable message ids, so an application can filter or count kinds of message. */
typedef enum mvr_log_id {
    MVR_LOG_ID_GENERAL = 0,
    MVR_LOG_ID_ERROR_RESULT,       /* a call returned an error; message says what and where */
    MVR_LOG_ID_CONTEXT,            /* context created / provider chosen */
    MVR_LOG_ID_PROVIDER_FALLBACK,  /* the default provider tried one and moved on */
    MVR_LOG_ID_EXTENSION_DROPPED,  /* advertised extension whose entry points did not resolve */
    MVR_LOG_ID_DRIVER_BUG,         /* a known driver bug was detected and is worked around */
    MVR_LOG_ID_GL_DEBUG,           /* a KHR_debug message from the driver */
    MVR_LOG_ID_GL_ERROR,           /* glGetError reported an error */
    MVR_LOG_ID_SHADER              /* shader compile / link log */
} mvr_log_id;

typedef void (*mvr_log_fn)(mvr_log_level level, mvr_log_id id, const char *message,
                           void *user_data);

typedef struct mvr_logger {
    mvr_log_fn fn;          /* NULL: messages are dropped */
    void *user_data;
    mvr_log_level level;    /* most verbose level passed on; 0 = MVR_LOG_INFO */
} mvr_logger;

#ifdef __cplusplus
}
#endif
#endif /* MVR_BASE_API_H */
