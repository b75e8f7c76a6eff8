/* mvr render --outputs (render_aovs.h). The .npy format (NumPy's own, version
 * 1.0): the magic "\x93NUMPY", version 1 0, a little-endian uint16 header
 * length, and a Python dict literal padded with spaces to a multiple of 64
 * bytes ending in '\n', then the raw C-order data
 * (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html). */
#include "render_aovs.h"

#include "cli_write.h"
#include "json.h"
#include "render_output.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool render_aovs_parse(const char *list, uint32_t *out_bits)
{
    uint32_t bits = 0;
    const char *p = list;
    while (*p) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        bool found = false;
        if (len == 3 && strncmp(p, "all", 3) == 0) {
            bits |= (MVR_OUTPUT_BIT(MVR_OUTPUT_COUNT) - 1u) & ~MVR_OUTPUT_BIT(MVR_OUTPUT_COLOR);
            found = true;
        }
        for (int k = MVR_OUTPUT_DEPTH; k < MVR_OUTPUT_COUNT && !found; ++k) {
            const char *name = mvr_output_name((mvr_output)k);
            if (strlen(name) == len && strncmp(p, name, len) == 0) {
                bits |= MVR_OUTPUT_BIT(k);
                found = true;
            }
        }
        if (!found) {
            fprintf(stderr, "mvr render: --outputs: unknown output '%.*s' (depth, distance, normal, ids, coverage "
                            "or all)\n", (int)len, p);
            return false;
        }
        p += len;
        if (*p == ',')
            p++;
    }
    if (!bits) {
        fprintf(stderr, "mvr render: --outputs takes a list: depth,distance,normal,ids,coverage or all\n");
        return false;
    }
    *out_bits = bits;
    return true;
}

size_t render_aovs_npy_header(char *buf, size_t size, mvr_output output, uint32_t h, uint32_t w)
{
    /* the data in this machine's byte order, which the descr states; coverage as uint8 */
    uint16_t one = 1;
    bool little = *(const uint8_t *)&one == 1;
    const char *descr = output == MVR_OUTPUT_COVERAGE ? "|u1"
                        : output == MVR_OUTPUT_IDS   ? (little ? "<u4" : ">u4")
                                                     : (little ? "<f4" : ">f4");
    uint32_t channels = output == MVR_OUTPUT_COVERAGE ? 1u : (uint32_t)(mvr_output_pixel_size(output) / 4);
    char dict[128];
    if (channels > 1)
        snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%u, %u, %u), }", descr, h, w,
                 channels);
    else
        snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%u, %u), }", descr, h, w);
    size_t len = strlen(dict);
    size_t total = 10 + len + 1;
    size_t padded = (total + 63) / 64 * 64;
    if (padded > size)
        return 0;
    memcpy(buf, "\x93NUMPY\x01\x00", 8);
    uint16_t hl = (uint16_t)(padded - 10);
    buf[8] = (char)(hl & 0xFF);
    buf[9] = (char)(hl >> 8);
    memcpy(buf + 10, dict, len);
    memset(buf + 10 + len, ' ', padded - total);
    buf[padded - 1] = '\n';
    return padded;
}

/* The .npy of output's h x w array whose rows are given bottom to top (GL
 * order): written top to bottom, as images and arrays run. false with the
 * reason in why. */
static bool write_npy(const char *path, mvr_output output, uint32_t h, uint32_t w, const uint8_t *rows_up,
                      size_t stride, char *why, size_t why_size)
{
    char header[256];
    size_t padded = render_aovs_npy_header(header, sizeof header, output, h, w);
    if (!padded) {
        snprintf(why, why_size, "%s: the .npy header does not fit", path);
        return false;
    }
    cli_write_file out; /* checked, and renamed into place whole */
    if (!cli_write_open(&out, path, why, why_size))
        return false;
    FILE *f = out.f;
    /* rows go out one at a time, last first: a buffer of many rows keeps the writes few
     * (glibc ignores the size of a buffer it allocates itself) */
    char iobuf[1 << 16];
    setvbuf(f, iobuf, _IOFBF, sizeof iobuf);
    bool ok = fwrite(header, 1, padded, f) == padded;
    for (uint32_t y = h; ok && y-- > 0;)
        ok = fwrite(rows_up + (size_t)y * stride, 1, stride, f) == stride;
    return cli_write_close(&out, why, why_size); /* a failed fwrite left the error flag set */
}

bool render_aovs_parse_files(const char *list, uint32_t *out_bits)
{
    static const char *const names[] = {"npy", "png", "exr", "layers"};
    uint32_t bits = 0;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        size_t k = 0;
        while (k < 4 && !(strlen(names[k]) == len && strncmp(p, names[k], len) == 0))
            k++;
        if (k == 4) {
            fprintf(stderr, "mvr render: --output-files: unknown kind '%.*s' (npy, png, exr or layers)\n", (int)len,
                    p);
            return false;
        }
        bits |= 1u << k;
        p += len;
        if (*p == ',')
            p++;
    }
    if (!bits) {
        fprintf(stderr, "mvr render: --output-files takes a list: npy,png,exr,layers\n");
        return false;
    }
    *out_bits = bits;
    return true;
}

/* One output's .npy; coverage (float32 0 / 1 as read) stored as uint8. */
static bool write_view_npy(const render_options *o, const render_aov_view *v, mvr_output output, char *why,
                           size_t why_size)
{
    char path[4096];
    if (!render_output_file_name(path, sizeof path, o->out_dir, mvr_output_name(output), v->view, v->frame,
                                 v->frame_digits, "npy")) {
        snprintf(why, why_size, "--out is too long");
        return false;
    }
    if (output == MVR_OUTPUT_COVERAGE) {
        size_t pixels = (size_t)v->width * v->height;
        uint8_t *bytes = malloc(pixels ? pixels : 1);
        if (!bytes) {
            snprintf(why, why_size, "%s: out of memory", path);
            return false;
        }
        const float *cov = v->data[output];
        for (size_t i = 0; i < pixels; ++i)
            bytes[i] = cov[i] > 0.0f;
        bool ok = write_npy(path, output, v->height, v->width, bytes, v->width, why, why_size);
        free(bytes);
        return ok;
    }
    size_t px = mvr_output_pixel_size(output);
    return write_npy(path, output, v->height, v->width, v->data[output], px * v->width, why,
                     why_size);
}

bool render_aovs_write_view(const render_options *o, const render_aov_view *v, char *why, size_t why_size)
{
    uint32_t files = o->output_files ? o->output_files : RENDER_AOV_FILES_DEFAULT;
    for (int k = MVR_OUTPUT_DEPTH; (files & RENDER_AOV_NPY) && k < MVR_OUTPUT_COUNT; ++k)
        if (v->data[k] && !write_view_npy(o, v, (mvr_output)k, why, why_size))
            return false;
    return render_aov_images_write(o, v, why, why_size);
}

bool render_aovs_write(const render_options *o, mvr_renderer *r, mvr_target *t, uint32_t views,
                       uint8_t *const *colors, int64_t frame, int frame_digits)
{
    size_t pixels = (size_t)o->width * o->height;
    size_t offset[MVR_OUTPUT_COUNT] = {0}, bytes = 0;
    for (int k = MVR_OUTPUT_DEPTH; k < MVR_OUTPUT_COUNT; ++k)
        if (o->outputs & MVR_OUTPUT_BIT(k)) {
            offset[k] = bytes;
            bytes += pixels * mvr_output_pixel_size((mvr_output)k);
        }
    uint8_t *buf = malloc(bytes ? bytes : 1);
    if (!buf) {
        fprintf(stderr, "mvr render: --outputs: out of memory\n");
        return false;
    }
    bool ok = true;
    for (uint32_t view = 0; ok && view < views; ++view) {
        render_aov_view v = {.view = view, .frame = frame, .frame_digits = frame_digits, .width = o->width,
                             .height = o->height, .color = colors ? colors[view] : NULL};
        for (int k = MVR_OUTPUT_DEPTH; ok && k < MVR_OUTPUT_COUNT; ++k) {
            if (!(o->outputs & MVR_OUTPUT_BIT(k)))
                continue;
            mvr_output output = (mvr_output)k;
            v.data[k] = buf + offset[k];
            if (mvr_renderer_read_output(r, t, view, output, buf + offset[k],
                                         pixels * mvr_output_pixel_size(output)) != MVR_OK) {
                fprintf(stderr, "mvr render: reading %s of view %u: %s\n", mvr_output_name(output), view,
                        mvr_renderer_last_error(r));
                ok = false;
            }
        }
        char why[4200];
        if (ok && !(ok = render_aovs_write_view(o, &v, why, sizeof why)))
            fprintf(stderr, "mvr render: %s\n", why);
    }
    free(buf);
    return ok;
}

bool render_aovs_write_ids(const char *dir, const mvr_scene *scene)
{
    char path[4096];
    int len = snprintf(path, sizeof path, "%s/ids.json", dir);
    if (len <= 0 || (size_t)len >= sizeof path) {
        fprintf(stderr, "mvr render: cannot write %s/ids.json: the path is too long\n", dir);
        return false;
    }
    cli_write_file out;
    char why[4200];
    if (!cli_write_open(&out, path, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        return false;
    }
    FILE *f = out.f;
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    json_writer jw = {.out = f};
    json_begin_object(&jw, NULL);
    json_string(&jw, "channels", "node, mesh, material, primitive (index in the mesh + 1); 0 = none");
    json_begin_array(&jw, "nodes");
    for (uint32_t k = 1; k <= info.nodes; ++k) {
        mvr_node_id node = {k};
        json_begin_object(&jw, NULL);
        json_int(&jw, "id", k);
        json_string(&jw, "name", mvr_scene_node_name(scene, node));
        json_int(&jw, "mesh", mvr_scene_node_mesh(scene, node).id);
        json_end_object(&jw);
    }
    json_end_array(&jw);
    json_begin_array(&jw, "meshes");
    for (uint32_t k = 1; k <= info.meshes; ++k) {
        json_begin_object(&jw, NULL);
        json_int(&jw, "id", k);
        json_string(&jw, "name", mvr_scene_mesh_name(scene, (mvr_mesh_id){k}));
        json_end_object(&jw);
    }
    json_end_array(&jw);
    json_begin_array(&jw, "materials");
    for (uint32_t k = 1; k <= info.materials; ++k) {
        json_begin_object(&jw, NULL);
        json_int(&jw, "id", k);
        json_string(&jw, "name", mvr_scene_material_name(scene, (mvr_material_id){k}));
        json_end_object(&jw);
    }
    json_end_array(&jw);
    json_end_object(&jw);
    fputc('\n', f);
    if (!cli_write_close(&out, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        return false;
    }
    return true;
}
