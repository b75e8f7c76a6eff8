#include "core_util.h"

const char *mvr_result_name(mvr_result result)
{
    switch (result) {
    case MVR_OK: return "MVR_OK";
    case MVR_ERROR_INVALID_ARGUMENT: return "MVR_ERROR_INVALID_ARGUMENT";
    case MVR_ERROR_OUT_OF_MEMORY: return "MVR_ERROR_OUT_OF_MEMORY";
    case MVR_ERROR_UNSUPPORTED: return "MVR_ERROR_UNSUPPORTED";
    case MVR_ERROR_NO_DISPLAY: return "MVR_ERROR_NO_DISPLAY";
    case MVR_ERROR_CONTEXT: return "MVR_ERROR_CONTEXT";
    case MVR_ERROR_GL: return "MVR_ERROR_GL";
    case MVR_ERROR_SHADER: return "MVR_ERROR_SHADER";
    case MVR_ERROR_FRAMEBUFFER: return "MVR_ERROR_FRAMEBUFFER";
    case MVR_ERROR_IO: return "MVR_ERROR_IO";
    case MVR_ERROR_PARSE: return "MVR_ERROR_PARSE";
    case MVR_ERROR_INVALID_ASSET: return "MVR_ERROR_INVALID_ASSET";
    case MVR_ERROR_INTERNAL: return "MVR_ERROR_INTERNAL";
    case MVR_RESULT_COUNT_: break;
    }
    return "MVR_ERROR_UNKNOWN";
}

mvr_result mvr_error_set(mvr_error *error, mvr_result result, const char *fmt, ...)
{
    if (error) {
        va_list ap;
        va_start(ap, fmt);
        error->result = result;
        mvr_str_vformat(error->message, sizeof error->message, fmt, ap);
        va_end(ap);
    }
    return result;
}

mvr_result mvr_error_record(char *buf, size_t size, const mvr_logger *logger, mvr_result result,
                            const char *fmt, va_list ap)
{
    mvr_str_vformat(buf, size, fmt, ap);
    mvr_log(logger, MVR_LOG_ERROR, MVR_LOG_ID_ERROR_RESULT, "%s: %s", mvr_result_name(result), buf);
    return result;
}
