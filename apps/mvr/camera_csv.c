/* CSV camera files (camera_file.h): a header naming the columns, one view
 * a row; blank lines and '#' comments skipped, "\r\n" ends taken. */
#define _POSIX_C_SOURCE 200809L
#include "camera_file_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { C_X, C_Y, C_Z, C_QX, C_QY, C_QZ, C_QW, C_FX, C_FY, C_CX, C_CY, C_WIDTH, C_HEIGHT, C_ZNEAR, C_COUNT };
static const char *const csv_names[C_COUNT] = {"x",  "y",  "z",  "qx", "qy",    "qz",     "qw",
                                               "fx", "fy", "cx", "cy", "width", "height", "znear"};
#define CSV_REQUIRED 11 /* x .. cy */

/* The next line of text (without its end, '\r' trimmed); false at the end. */
static bool next_line(const char **p, const char *end, const char **line, size_t *len)
{
    if (*p >= end)
        return false;
    const char *s = *p, *e = memchr(s, '\n', (size_t)(end - s));
    if (!e)
        e = end;
    *p = e < end ? e + 1 : end;
    *line = s;
    *len = (size_t)(e - s);
    if (*len && s[*len - 1] == '\r')
        --*len;
    return true;
}

/* Cells of a line split at commas, blanks around each trimmed; at most max. */
static uint32_t split_cells(const char *line, size_t len, const char **cells, size_t *lens, uint32_t max)
{
    uint32_t n = 0;
    size_t i = 0;
    for (;;) {
        size_t start = i;
        while (i < len && line[i] != ',')
            ++i;
        size_t a = start, b = i;
        while (a < b && (line[a] == ' ' || line[a] == '\t'))
            ++a;
        while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t'))
            --b;
        if (n < max) {
            cells[n] = line + a;
            lens[n] = b - a;
        }
        ++n;
        if (i >= len)
            return n;
        ++i;
    }
}

static bool blank_or_comment(const char *line, size_t len)
{
    size_t i = 0;
    while (i < len && (line[i] == ' ' || line[i] == '\t'))
        ++i;
    return i == len || line[i] == '#';
}

/* A cell as a finite decimal number (no hex, no inf or nan, nothing after). */
static bool csv_number(const char *cell, size_t len, double *out)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf)
        return false;
    for (size_t i = 0; i < len; ++i) /* the cell is not NUL-terminated */
        if (!strchr("0123456789+-.eE", cell[i]) || cell[i] == '\0')
            return false;
    memcpy(buf, cell, len);
    buf[len] = '\0';
    char *end = NULL;
    errno = 0;
    double v = strtod(buf, &end);
    if (*end != '\0' || !isfinite(v))
        return false;
    *out = v;
    return true;
}

bool camf_parse_csv(camf_report *rp, const char *text, size_t size, uint32_t width, uint32_t height, camera_file *f)
{
    const char *p = text, *end = text + size, *line = NULL;
    size_t len = 0;
    uint32_t line_no = 0;
    if (size >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        p += 3;
    if (memchr(text, '\0', size))
        return camf_refuse(rp, "a NUL byte in a text file (not a camera file)");
    /* the header: the first line that is neither blank nor a comment */
    bool have_header = false;
    while (!have_header && next_line(&p, end, &line, &len)) {
        ++line_no;
        have_header = !blank_or_comment(line, len);
    }
    uint32_t header_line = line_no;
    if (!have_header)
        return camf_refuse(rp, "no views: the file is empty (a CSV camera file starts with a header: %s)",
                           "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy[,width,height,znear]");
    const char *cells[C_COUNT + 1];
    size_t lens[C_COUNT + 1];
    int column_of[C_COUNT];
    for (int k = 0; k < C_COUNT; ++k)
        column_of[k] = -1;
    uint32_t columns = split_cells(line, len, cells, lens, C_COUNT + 1);
    if (columns > C_COUNT)
        return camf_refuse(rp,
                           "line %u: the header has %u columns; the known ones are %u: x, y, z, qx, qy, qz, qw, fx, "
                           "fy, cx, cy, width, height, znear",
                           line_no, columns, C_COUNT);
    for (uint32_t c = 0; c < columns; ++c) {
        int k = 0;
        while (k < C_COUNT && !(strlen(csv_names[k]) == lens[c] && memcmp(csv_names[k], cells[c], lens[c]) == 0))
            ++k;
        char shown[48];
        camf_show_cell(shown, sizeof shown, cells[c], lens[c]);
        if (k == C_COUNT)
            return camf_refuse(rp,
                               "line %u: column %u '%s' is not one of x, y, z, qx, qy, qz, qw, fx, fy, cx, cy, width, "
                               "height, znear (is this a CSV camera file?)",
                               line_no, c + 1, shown);
        if (column_of[k] >= 0)
            return camf_refuse(rp, "line %u: column '%s' appears twice", line_no, shown);
        column_of[k] = (int)c;
    }
    for (int k = 0; k < CSV_REQUIRED; ++k)
        if (column_of[k] < 0)
            return camf_refuse(rp,
                               "line %u: the header has no column '%s' (x, y, z, qx, qy, qz, qw, fx, fy, cx, cy are "
                               "needed)",
                               line_no, csv_names[k]);
    if ((column_of[C_WIDTH] >= 0) != (column_of[C_HEIGHT] >= 0))
        return camf_refuse(rp, "line %u: the header has %s without %s", line_no,
                           column_of[C_WIDTH] >= 0 ? "width" : "height", column_of[C_WIDTH] >= 0 ? "height" : "width");
    f->format = "CSV";
    uint32_t cap = 0;
    while (next_line(&p, end, &line, &len)) {
        ++line_no;
        if (blank_or_comment(line, len))
            continue;
        uint32_t k = f->count;
        char where[64];
        snprintf(where, sizeof where, "view %u (line %u)", k, line_no);
        if (k == CAMERA_FILE_MAX_VIEWS)
            return camf_refuse(rp, "%s: more than %u views", where, CAMERA_FILE_MAX_VIEWS);
        if (k == cap) {
            cap = cap ? cap * 2 : 16;
            mvr_view_desc *views = realloc(f->views, cap * sizeof *views);
            if (!views)
                return camf_refuse(rp, "out of memory");
            f->views = views;
        }
        uint32_t n = split_cells(line, len, cells, lens, C_COUNT + 1);
        if (n != columns)
            return camf_refuse(rp, "%s: %u cells; the header has %u columns", where, n, columns);
        double val[C_COUNT] = {0};
        for (int c = 0; c < C_COUNT; ++c) {
            if (column_of[c] < 0)
                continue;
            int i = column_of[c];
            if (!csv_number(cells[i], lens[i], &val[c])) {
                char shown[48];
                camf_show_cell(shown, sizeof shown, cells[i], lens[i]);
                return camf_refuse(rp, "%s: %s: '%s' is not a finite number", where, csv_names[c], shown);
            }
        }
        uint32_t w = width, h = height;
        if (column_of[C_WIDTH] >= 0) {
            for (int c = C_WIDTH; c <= C_HEIGHT; ++c)
                if (!(val[c] >= 1 && val[c] <= CAMERA_FILE_MAX_SIDE && val[c] == floor(val[c])))
                    return camf_refuse(rp, "%s: %s: %g is not an image side in pixels (a whole number, 1..%u)", where,
                                       csv_names[c], val[c], CAMERA_FILE_MAX_SIDE);
            w = (uint32_t)val[C_WIDTH];
            h = (uint32_t)val[C_HEIGHT];
            if (!camf_same_size(rp, f, where, k, w, h))
                return false;
        }
        mvr_view_desc *v = &f->views[k];
        memset(v, 0, sizeof *v);
        memcpy(v->position, &val[C_X], sizeof v->position);
        static const char *names[4] = {"fx", "fy", "cx", "cy"};
        if (!camf_check_position(rp, where, "x, y, z", v->position) ||
            !camf_unit_quaternion(rp, where, "qx, qy, qz, qw", &val[C_QX], v->orientation) ||
            !camf_check_znear(rp, where, "znear", val[C_ZNEAR]) ||
            !camf_frustum_from_pinhole(rp, where, names, val[C_FX], val[C_FY], val[C_CX], val[C_CY], w, h, val[C_ZNEAR],
                                       &v->projection))
            return false;
        f->count++;
    }
    if (f->count == 0)
        return camf_refuse(rp, "no views: the header (line %u) is not followed by any row", header_line);
    return true;
}
