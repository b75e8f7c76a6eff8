/* A sharded run's records (run_plan.h): DIR/.mvr-run/units/<id>.json, one
 * JSON line per unit, the files it wrote with their sizes and SHA-256. */
#ifndef MVR_APP_RUN_RECORD_H
#define MVR_APP_RUN_RECORD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct run_file {
    char *path;                  /* relative to DIR */
    uint64_t bytes;
    char sha256[65];
} run_file;

typedef struct run_files {
    run_file *items;
    uint32_t count, capacity;
} run_files;

/* Appends a copy of path (sha256 NULL: ""); false when out of memory. */
bool run_files_add(run_files *list, const char *path, uint64_t bytes, const char *sha256);
/* By path, byte order (the records' order). */
void run_files_sort(run_files *list);
void run_files_free(run_files *list);

typedef struct run_record {
    bool present;                /* the record file exists */
    bool done;                   /* status "done" (else "failed") */
    char *line;                  /* the record's text, without its newline */
    char message[1024];          /* a failed unit's */
    run_files files;
} run_record;

/* DIR/.mvr-run/units/<unit's id>.json into rec (present false when there
 * is none). false with why when it cannot be read or is no record. */
bool run_record_read(const char *dir, uint32_t unit, run_record *rec, char *why, size_t why_size);
void run_record_free(run_record *rec);

/* Whether every file of a done record is in DIR with its recorded size. */
bool run_record_files_present(const char *dir, const run_record *rec);

/* snprintf into buf for paths and messages, where a cut text is no
 * error worth a branch of its own: false when it was cut. */
bool run_format(char *buf, size_t size, const char *format, ...) __attribute__((format(printf, 3, 4)));

/* The whole of a file, NUL-terminated (size optional); NULL with errno
 * when it cannot be read. */
char *run_read_text(const char *path, size_t *size);

#endif
