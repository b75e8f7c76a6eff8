/* Checked, atomic file writes for the CLI (cli_write.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "cli_write.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static bool refuse(const cli_write_file *w, int err, char *why, size_t why_size)
{
    snprintf(why, why_size, "cannot write %s: %s", w->path, err ? strerror(err) : "a write failed");
    return false;
}

/* A fresh temporary beside w->target: "DIR/.NAME.tmpPID-N", created with
 * O_EXCL so it is never another writer's file; mode: the replaced file's
 * permissions (fopen would keep them), or 0 for a new file's default. */
static int open_temp(cli_write_file *w, mode_t mode)
{
    const char *slash = strrchr(w->target, '/');
    int dir_len = slash ? (int)(slash - w->target) : 1;
    const char *dir = slash ? w->target : ".";
    const char *name = slash ? slash + 1 : w->target;
    if (slash == w->target)
        dir_len = 0; /* a file in "/" */
    for (int attempt = 0; attempt < 100; ++attempt) {
        /* the name cut to 200 bytes keeps the temporary within NAME_MAX (255) */
        int n = snprintf(w->temp, sizeof w->temp, "%.*s/.%.200s.tmp%ld-%d", dir_len, dir, name, (long)getpid(),
                         attempt);
        if (n < 0 || (size_t)n >= sizeof w->temp) {
            errno = ENAMETOOLONG;
            return -1;
        }
        int fd = open(w->temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            if (mode && fchmod(fd, mode) != 0) {
                int err = errno;
                close(fd);
                unlink(w->temp);
                errno = err;
                return -1;
            }
            return fd;
        }
        if (errno != EEXIST)
            return -1;
    }
    errno = EEXIST;
    return -1;
}

bool cli_write_open(cli_write_file *w, const char *path, char *why, size_t why_size)
{
    w->f = NULL; /* before anything can fail */
    w->temp[0] = '\0';
    int n = snprintf(w->path, sizeof w->path, "%s", path);
    if (n < 0 || (size_t)n >= sizeof w->path || !path[0]) {
        snprintf(why, why_size, "cannot write %.200s...: the path is empty or too long", path);
        return false;
    }
    memcpy(w->target, w->path, (size_t)n + 1);
    struct stat st;
    bool atomic = false;
    mode_t mode = 0;
    if (lstat(path, &st) != 0) {
        atomic = errno == ENOENT; /* otherwise the open below names the reason */
    } else if (S_ISREG(st.st_mode)) {
        atomic = true;
        mode = st.st_mode & 07777;
    } else if (S_ISLNK(st.st_mode) && stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
        /* replace the link's target, so the link still points at the new file */
        char real[4096 + 1];
        if (realpath(path, real) && strlen(real) < sizeof w->target) {
            memcpy(w->target, real, strlen(real) + 1);
            atomic = true;
            mode = st.st_mode & 07777;
        }
    }
    if (!atomic) { /* a device, a FIFO, ...: written where it is */
        w->f = fopen(path, "w");
        return w->f ? true : refuse(w, errno, why, why_size);
    }
    int fd = open_temp(w, mode);
    if (fd < 0) {
        w->temp[0] = '\0';
        return refuse(w, errno, why, why_size);
    }
    w->f = fdopen(fd, "w");
    if (!w->f) {
        int err = errno;
        close(fd);
        unlink(w->temp);
        w->temp[0] = '\0';
        return refuse(w, err, why, why_size);
    }
    return true;
}

bool cli_write_close(cli_write_file *w, char *why, size_t why_size)
{
    if (!w->f)
        return refuse(w, EBADF, why, why_size);
    /* a write that failed earlier (its data lost) leaves the error flag set,
     * even where the last flush succeeds */
    bool failed = ferror(w->f) != 0;
    int err = 0;
    if (fflush(w->f) != 0)
        err = errno;
    if (fclose(w->f) != 0 && !err)
        err = errno;
    w->f = NULL;
    if (!err && !failed && w->temp[0] && rename(w->temp, w->target) != 0)
        err = errno;
    bool ok = !err && !failed;
    if (!ok && w->temp[0])
        unlink(w->temp);
    w->temp[0] = '\0';
    return ok ? true : refuse(w, err, why, why_size);
}

void cli_write_abandon(cli_write_file *w)
{
    if (w->f)
        fclose(w->f);
    w->f = NULL;
    if (w->temp[0])
        unlink(w->temp);
    w->temp[0] = '\0';
}
