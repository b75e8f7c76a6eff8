/* A sharded run's records (run_record.h). */
#define _POSIX_C_SOURCE 200809L
#include "run_record.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "json_read.h"
#include "run_plan.h"

bool run_files_add(run_files *list, const char *path, uint64_t bytes, const char *sha256)
{
    if (list->count == list->capacity) {
        uint32_t cap = list->capacity ? list->capacity * 2 : 16;
        run_file *items = realloc(list->items, cap * sizeof *items);
        if (!items)
            return false;
        list->items = items;
        list->capacity = cap;
    }
    run_file *f = &list->items[list->count];
    if (!(f->path = strdup(path)))
        return false;
    f->bytes = bytes;
    snprintf(f->sha256, sizeof f->sha256, "%s", sha256 ? sha256 : "");
    list->count++;
    return true;
}

static int compare_paths(const void *a, const void *b)
{
    return strcmp(((const run_file *)a)->path, ((const run_file *)b)->path);
}

void run_files_sort(run_files *list)
{
    if (list->count > 1)
        qsort(list->items, list->count, sizeof *list->items, compare_paths);
}

void run_files_free(run_files *list)
{
    for (uint32_t k = 0; k < list->count; ++k)
        free(list->items[k].path);
    free(list->items);
    memset(list, 0, sizeof *list);
}

bool run_format(char *buf, size_t size, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    int n = vsnprintf(buf, size, format, ap);
    va_end(ap);
    return n >= 0 && (size_t)n < size;
}

char *run_read_text(const char *path, size_t *size_out)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    size_t size = 0, cap = 0, got;
    char buf[65536];
    while ((got = fread(buf, 1, sizeof buf, f)) > 0) {
        if (size + got + 1 > cap) {
            cap = (size + got + 1) * 2;
            char *bigger = realloc(text, cap);
            if (!bigger) {
                free(text);
                fclose(f);
                errno = ENOMEM;
                return NULL;
            }
            text = bigger;
        }
        memcpy(text + size, buf, got);
        size += got;
    }
    bool bad = ferror(f);
    fclose(f);
    if (bad) {
        free(text);
        errno = EIO;
        return NULL;
    }
    if (!text)
        text = calloc(1, 1);
    else
        text[size] = '\0';
    if (size_out)
        *size_out = size;
    return text;
}

/* The record's files array into rec; false when malformed. */
static bool read_files(const json_value *files, run_record *rec)
{
    if (!files || files->type != JSON_ARRAY)
        return false;
    for (uint32_t k = 0; k < files->count; ++k) {
        const json_value *f = &files->items[k];
        const json_value *path = json_member(f, "path"), *bytes = json_member(f, "bytes");
        const json_value *sha = json_member(f, "sha256");
        if (!path || path->type != JSON_STRING || !bytes || bytes->type != JSON_NUMBER || !sha ||
            sha->type != JSON_STRING || strlen(sha->string) != 64 || bytes->number < 0)
            return false;
        if (!run_files_add(&rec->files, path->string, (uint64_t)bytes->number, sha->string))
            return false;
    }
    return true;
}

bool run_record_read(const char *dir, uint32_t unit, run_record *rec, char *why, size_t why_size)
{
    memset(rec, 0, sizeof *rec);
    char id[16], path[8192];
    run_unit_id(unit, id);
    run_format(path, sizeof path, "%s/.mvr-run/units/%s.json", dir, id);
    size_t size = 0;
    char *text = run_read_text(path, &size);
    if (!text) {
        if (errno == ENOENT)
            return true;
        run_format(why, why_size, "cannot read %s: %s", path, strerror(errno));
        return false;
    }
    rec->present = true;
    json_value v;
    char jwhy[256];
    bool ok = json_read(text, size, &v, jwhy, sizeof jwhy);
    if (!ok) {
        run_format(why, why_size, "%s: %s", path, jwhy);
        free(text);
        return false;
    }
    const json_value *n = json_member(&v, "unit"), *status = json_member(&v, "status");
    const json_value *message = json_member(&v, "message");
    ok = n && n->type == JSON_NUMBER && n->number == unit && status && status->type == JSON_STRING &&
         read_files(json_member(&v, "files"), rec);
    if (ok) {
        rec->done = strcmp(status->string, "done") == 0;
        if (message && message->type == JSON_STRING)
            run_format(rec->message, sizeof rec->message, "%s", message->string);
        text[strcspn(text, "\n")] = '\0';
        rec->line = text;
    } else {
        run_format(why, why_size, "%s is no record of unit %s", path, id);
        free(text);
    }
    json_read_free(&v);
    return ok;
}

void run_record_free(run_record *rec)
{
    free(rec->line);
    run_files_free(&rec->files);
    memset(rec, 0, sizeof *rec);
}

bool run_record_files_present(const char *dir, const run_record *rec)
{
    for (uint32_t k = 0; k < rec->files.count; ++k) {
        char path[8192];
        struct stat st;
        run_format(path, sizeof path, "%s/%s", dir, rec->files.items[k].path);
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode) || (uint64_t)st.st_size != rec->files.items[k].bytes)
            return false;
    }
    return true;
}
