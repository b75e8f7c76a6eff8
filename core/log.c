#include <stdio.h>

#include "core_util.h"

static mvr_log_level effective_threshold(mvr_log_level level)
{
    return level == MVR_LOG_DEFAULT ? MVR_LOG_INFO : level;
}

void mvr_log(const mvr_logger *logger, mvr_log_level level, mvr_log_id id, const char *fmt, ...)
{
    if (!logger || !logger->fn || level == MVR_LOG_DEFAULT)
        return;
    if (level > effective_threshold(logger->level))
        return;
    char message[1024];
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(message, sizeof message, fmt, ap);
    va_end(ap);
    logger->fn(level, id, message, logger->user_data);
}
