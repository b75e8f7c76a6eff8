/* The program cache's entry files in a folder, for the GL tests that damage,
 * forge or count them (test_program_variants.c, test_program_cache_trust.c). */
#ifndef MVR_PROGRAM_CACHE_FILES_H
#define MVR_PROGRAM_CACHE_FILES_H

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The entries (*.mvrbin, regular or not), sorted, into names[max][512];
 * returns the count. */
static inline uint32_t program_cache_entries(const char *dir, char names[][512], uint32_t max)
{
    uint32_t n = 0;
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < max) {
        size_t len = strlen(e->d_name);
        if (len > 7 && strcmp(e->d_name + len - 7, ".mvrbin") == 0)
            snprintf(names[n++], 512, "%s/%s", dir, e->d_name);
    }
    closedir(d);
    qsort(names, n, 512, (int (*)(const void *, const void *))strcmp);
    return n;
}

#endif
