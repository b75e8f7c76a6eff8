/* A sharded run's units (run_plan.h): --shard K/N, --resume, --serve and
 * --run-plan. Each unit renders into DIR/.mvr-run/tmp/<id>.<host>.<pid>/
 * (the run's layout), its files are then renamed into DIR, then its record
 * DIR/.mvr-run/units/<id>.json is written (temp, fsync, rename): the
 * record is the commit point, so a unit without one is incomplete whatever
 * files exist, and rendering it again renames the same bytes over them. */
#define _POSIX_C_SOURCE 200809L
#include "run_plan.h"
#include "run_record.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_progress.h" /* cli_now */
#include "commands.h"
#include "json.h"
#include "json_read.h"
#include "sha256.h"

/* What one process of the run holds. */
typedef struct run_ctx {
    const render_options *o;
    const run_plan *plan;
    run_unit_fn fn;
    void *user;
    char worker[320];
    char host[256];
    bool fatal;                  /* no context or renderer: nothing more can render */
    FILE *human;                 /* per-unit lines: stdout, or stderr with --serve */
} run_ctx;

/* ------------------------------------------------------------------ the unit's files */

/* Every regular file under root/rel, as paths relative to root, appended. */
static bool list_files(const char *root, const char *rel, run_files *out)
{
    char path[8192];
    run_format(path, sizeof path, "%s%s%s", root, rel[0] ? "/" : "", rel);
    DIR *d = opendir(path);
    if (!d)
        return errno == ENOENT;
    bool ok = true;
    struct dirent *e;
    while (ok && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char sub[8192], full[8192];
        run_format(sub, sizeof sub, "%s%s%s", rel, rel[0] ? "/" : "", e->d_name);
        run_format(full, sizeof full, "%s/%s", root, sub);
        struct stat st;
        if (lstat(full, &st) != 0)
            ok = false;
        else if (S_ISDIR(st.st_mode))
            ok = list_files(root, sub, out);
        else if (S_ISREG(st.st_mode))
            ok = run_files_add(out, sub, (uint64_t)st.st_size, NULL);
    }
    closedir(d);
    return ok;
}

/* Removes root and what is under it (a unit's temporary directory). */
static void remove_tree(const char *root)
{
    DIR *d = opendir(root);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            char full[8192];
            run_format(full, sizeof full, "%s/%s", root, e->d_name);
            struct stat st;
            if (lstat(full, &st) == 0 && S_ISDIR(st.st_mode))
                remove_tree(full);
            else
                unlink(full);
        }
        closedir(d);
    }
    rmdir(root);
}

/* The unit's files: hashed in the temporary directory, then renamed into
 * DIR (their folders made); false with why. */
static bool commit_files(const char *dir, const char *tmp, run_files *files, char *why, size_t size)
{
    if (!list_files(tmp, "", files)) {
        run_format(why, size, "cannot list %s: %s", tmp, strerror(errno));
        return false;
    }
    run_files_sort(files);
    for (uint32_t k = 0; k < files->count; ++k) {
        run_file *f = &files->items[k];
        char from[8192], to[8192];
        run_format(from, sizeof from, "%s/%s", tmp, f->path);
        run_format(to, sizeof to, "%s/%s", dir, f->path);
        if (!sha256_file(from, f->sha256, &f->bytes)) {
            run_format(why, size, "cannot read %s: %s", from, strerror(errno));
            return false;
        }
        char *slash = strrchr(to, '/');
        *slash = '\0';
        bool made = cli_make_dirs("mvr render", to);
        *slash = '/';
        if (!made || rename(from, to) != 0) {
            run_format(why, size, "cannot move %s to %s: %s", from, to, strerror(errno));
            return false;
        }
    }
    return true;
}

/* ------------------------------------------------------------------ mvr's messages */

/* stderr into a file while a unit renders, so its record can hold mvr's
 * message; the text is passed on to stderr afterwards. */
typedef struct capture {
    int saved;
    char path[8192];
} capture;

static void capture_begin(capture *c, const char *path)
{
    fflush(stderr);
    run_format(c->path, sizeof c->path, "%s", path);
    c->saved = dup(2);
    int fd = c->saved >= 0 ? open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644) : -1;
    if (fd >= 0) {
        dup2(fd, 2);
        close(fd);
    }
}

/* Restores stderr, passes the text on, and keeps its first line that is
 * no warning (else its last) as the message. */
static void capture_end(capture *c, char *message, size_t size)
{
    fflush(stderr);
    if (c->saved >= 0) {
        dup2(c->saved, 2);
        close(c->saved);
    }
    message[0] = '\0';
    FILE *f = fopen(c->path, "rb");
    char line[2048];
    bool chosen = false;
    while (f && fgets(line, sizeof line, f)) {
        fputs(line, stderr);
        line[strcspn(line, "\n")] = '\0';
        if (!line[0] || chosen)
            continue;
        run_format(message, size, "%s", line);
        chosen = strstr(line, "warning") == NULL;
    }
    if (f)
        fclose(f);
    unlink(c->path);
}

/* ------------------------------------------------------------------ records */

/* The record as one JSON line (and its newline). */
static void write_record(FILE *out, const run_ctx *r, uint32_t u, bool done, const char *message,
                         const run_files *files, double seconds)
{
    const run_unit *t = &r->plan->units[u];
    const char *file = r->plan->files[t->file];
    char id[16];
    run_unit_id(u, id);
    fprintf(out, "{\"unit\": %u, \"id\": \"%s\", \"file\": ", u, id);
    json_escaped(out, file ? file : r->o->demo);
    fprintf(out, ", \"file_index\": %u, \"views\": [%u, %u], \"frames\": [%u, %u], \"status\": \"%s\"", t->file,
            t->v0, t->v1, t->f0, t->f1, done ? "done" : "failed");
    if (!done) {
        fputs(", \"message\": ", out);
        json_escaped(out, message);
    }
    fputs(", \"files\": [", out);
    for (uint32_t k = 0; done && k < files->count; ++k) {
        fputs(k ? ", {\"path\": " : "{\"path\": ", out);
        json_escaped(out, files->items[k].path);
        fprintf(out, ", \"bytes\": %llu, \"sha256\": \"%s\"}", (unsigned long long)files->items[k].bytes,
                files->items[k].sha256);
    }
    fprintf(out, "], \"seconds\": %.3f, \"worker\": ", seconds);
    json_escaped(out, r->worker);
    fputs("}\n", out);
}

/* text into path through a temporary, fsync'd, renamed: a reader sees the
 * old file or the whole new one. */
static bool write_atomic(const char *path, const char *text, size_t size, const char *host)
{
    char temp[8400];
    run_format(temp, sizeof temp, "%s.%s.%ld.tmp", path, host, (long)getpid());
    int fd = open(temp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
        return false;
    bool ok = true;
    for (size_t done = 0; ok && done < size;) {
        ssize_t w = write(fd, text + done, size - done);
        ok = w > 0;
        done += ok ? (size_t)w : 0;
    }
    ok = fsync(fd) == 0 && ok;
    ok = close(fd) == 0 && ok;
    if (ok && rename(temp, path) == 0)
        return true;
    unlink(temp);
    return false;
}

/* ------------------------------------------------------------------ one unit */

/* Renders unit u into its temporary directory, moves its files into DIR
 * and writes its record; *line (malloc'd) is the record. true when done. */
static bool render_unit(run_ctx *r, uint32_t u, char **line)
{
    const render_options *o = r->o;
    const run_unit *t = &r->plan->units[u];
    char id[16], tmp[8192], out_dir[8400], log[8400], message[1024] = "";
    run_unit_id(u, id);
    run_format(tmp, sizeof tmp, "%s/.mvr-run/tmp/%s.%s.%ld", o->out_dir, id, r->host, (long)getpid());
    remove_tree(tmp); /* a process with this pid before (another boot) */
    const char *rel = r->plan->dirs[t->file];
    run_format(out_dir, sizeof out_dir, "%s%s%s", tmp, rel[0] ? "/" : "", rel);
    run_format(log, sizeof log, "%s.log", tmp);
    render_options uo = *o;
    uo.unit = true, uo.view_first = t->v0, uo.view_end = t->v1, uo.frame_first = t->f0, uo.frame_end = t->f1;
    uo.out_dir = out_dir;
    double start = cli_now();
    capture c;
    capture_begin(&c, log);
    int rc = r->fn(r->user, &uo, r->plan->files[t->file], out_dir, &r->fatal);
    capture_end(&c, message, sizeof message);
    run_files files = {0};
    bool done = rc == MVR_EXIT_OK;
    if (done && t->v1 == 0) {
        run_format(message, sizeof message, "mvr render: %s did not load while the run was planned",
                 r->plan->files[t->file] ? r->plan->files[t->file] : o->demo);
        done = false;
    }
    if (done && !commit_files(o->out_dir, tmp, &files, message, sizeof message))
        done = false;
    if (!done && !message[0])
        run_format(message, sizeof message, "mvr render: the unit failed (exit %d)", rc);
    remove_tree(tmp);
    char *text = NULL;
    size_t size = 0;
    FILE *mem = open_memstream(&text, &size);
    bool ok = mem != NULL;
    if (mem) {
        write_record(mem, r, u, done, message, &files, cli_now() - start);
        ok = fclose(mem) == 0;
    }
    run_files_free(&files);
    char path[8400];
    run_format(path, sizeof path, "%s/.mvr-run/units/%s.json", o->out_dir, id);
    if (!ok || !write_atomic(path, text, size, r->host)) {
        fprintf(stderr, "mvr render: %s: cannot write its record %s: %s\n", id, path, strerror(errno));
        done = false;
    }
    if (done)
        fprintf(r->human, "mvr render: %s done (%s, views %u..%u, frames %u..%u)\n", id,
                r->plan->files[t->file] ? r->plan->files[t->file] : o->demo, t->v0, t->v1, t->f0, t->f1);
    else
        fprintf(stderr, "mvr render: %s failed: %s\n", id, message);
    fflush(r->human);
    if (text && size)
        text[size - 1] = '\0'; /* the newline */
    *line = text;
    return done;
}

/* Whether unit u has a done record whose files are all there; *line (when
 * asked) its text. */
static bool unit_done(const run_ctx *r, uint32_t u, char **line)
{
    run_record rec;
    char why[512];
    if (!run_record_read(r->o->out_dir, u, &rec, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s (rendered again)\n", why);
        return false;
    }
    bool done = rec.present && rec.done && run_record_files_present(r->o->out_dir, &rec);
    if (done && line) {
        *line = rec.line;
        rec.line = NULL;
    }
    run_record_free(&rec);
    return done;
}

/* ------------------------------------------------------------------ shards and serving */

/* --shard K/N (and --resume alone: every unit). */
static int run_shard(run_ctx *r)
{
    const render_run_options *run = &r->o->run;
    uint32_t k = run->shard_n ? run->shard_k - 1 : 0, n = run->shard_n ? run->shard_n : 1;
    uint32_t rendered = 0, skipped = 0, failed = 0, left = 0;
    for (uint32_t u = k; u < r->plan->unit_count; u += n) {
        if (r->fatal) {
            ++left;
            continue;
        }
        if (run->resume && unit_done(r, u, NULL)) {
            ++skipped;
            continue;
        }
        char *line = NULL;
        if (render_unit(r, u, &line))
            ++rendered;
        else
            ++failed;
        free(line);
    }
    FILE *out = failed || left ? stderr : stdout;
    if (failed || left || !r->o->quiet) {
        fprintf(out, "mvr render: shard %u/%u: %u unit%s rendered, %u skipped (done before), %u failed", k + 1, n,
                rendered, rendered == 1 ? "" : "s", skipped, failed);
        if (left)
            fprintf(out, ", %u not attempted (nothing can render without a context and a renderer)", left);
        fputc('\n', out);
    }
    return failed || left ? MVR_EXIT_FAILURE : MVR_EXIT_OK;
}

/* --serve: a unit number a line on stdin, its record a line on stdout. */
static int run_serve(run_ctx *r)
{
    char buf[128];
    while (fgets(buf, sizeof buf, stdin)) {
        buf[strcspn(buf, "\r\n")] = '\0';
        if (!buf[0])
            continue;
        uint32_t u = 0;
        char *line = NULL;
        if (!cli_parse_u32(buf, 0, r->plan->unit_count ? r->plan->unit_count - 1 : 0, &u) ||
            !r->plan->unit_count) {
            printf("{\"unit\": null, \"status\": \"error\", \"message\": ");
            char why[256];
            run_format(why, sizeof why, "not a unit number of this run (0..%u): %s", r->plan->unit_count - 1, buf);
            json_escaped(stdout, why);
            printf("}\n");
        } else if (unit_done(r, u, &line) || (render_unit(r, u, &line), line != NULL)) {
            printf("%s\n", line);
        }
        free(line);
        fflush(stdout);
        if (r->fatal)
            return MVR_EXIT_FAILURE;
    }
    return MVR_EXIT_OK;
}

int run_units_main(const render_options *o, const render_inputs *in, run_unit_fn fn, void *user)
{
    run_plan plan;
    if (!run_plan_make(o, in, &plan)) {
        run_plan_free(&plan);
        return MVR_EXIT_FAILURE;
    }
    int rc = run_plan_settle(o->out_dir, &plan);
    if (rc == MVR_EXIT_OK && o->run.plan)
        fputs(plan.text, stdout);
    char path[8192];
    run_format(path, sizeof path, "%s/.mvr-run/units", o->out_dir);
    if (rc == MVR_EXIT_OK && !o->run.plan && !cli_make_dirs("mvr render", path))
        rc = MVR_EXIT_FAILURE;
    run_format(path, sizeof path, "%s/.mvr-run/tmp", o->out_dir);
    if (rc == MVR_EXIT_OK && !o->run.plan && !cli_make_dirs("mvr render", path))
        rc = MVR_EXIT_FAILURE;
    if (rc == MVR_EXIT_OK && !o->run.plan) {
        run_ctx r = {.o = o, .plan = &plan, .fn = fn, .user = user, .human = o->run.serve ? stderr : stdout};
        if (gethostname(r.host, sizeof r.host - 1) != 0 || !r.host[0])
            run_format(r.host, sizeof r.host, "localhost");
        for (char *p = r.host; *p; ++p)
            if (*p == '/')
                *p = '_';
        if (o->run.worker)
            run_format(r.worker, sizeof r.worker, "%s", o->run.worker);
        else
            run_format(r.worker, sizeof r.worker, "%s:%ld", r.host, (long)getpid());
        if (o->quiet && !o->run.serve)
            r.human = fopen("/dev/null", "w");
        rc = r.human ? (o->run.serve ? run_serve(&r) : run_shard(&r)) : MVR_EXIT_FAILURE;
        if (r.human && r.human != stdout && r.human != stderr)
            fclose(r.human);
    }
    run_plan_free(&plan);
    return rc;
}
