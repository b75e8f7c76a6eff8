/* Writes every shader variant of the validation set into a directory, one
 * NAME.vert and NAME.frag per variant, for glslangValidator.
 * usage: dump_shaders DIR MAX_VIEWS */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "shader_gen.h"

static int write_stage(const char *dir, const mvr_shader_variant *v, mvr_shader_stage stage)
{
    char name[96], path[1024], why[256];
    mvr_shader_variant_name(v, name, sizeof name);
    mvr_str_format(path, sizeof path, "%s/%s.%s", dir, name, mvr_shader_stage_name(stage));
    mvr_str_builder sb = {0};
    if (!mvr_shader_source(v, stage, &sb, why, sizeof why)) {
        fprintf(stderr, "dump_shaders: %s: %s\n", name, why);
        mvr_sb_free(&sb);
        return 1;
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "dump_shaders: cannot write %s (errno %d)\n", path, errno);
        mvr_sb_free(&sb);
        return 1;
    }
    size_t length = sb.length;
    size_t written = fwrite(sb.data, 1, length, f);
    int closed = fclose(f);
    mvr_sb_free(&sb);
    return written == length && closed == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: dump_shaders DIR MAX_VIEWS\n");
        return 2;
    }
    uint32_t max_views = (uint32_t)strtoul(argv[2], NULL, 10);
    mvr_shader_variant v;
    unsigned n = 0;
    int failures = 0;
    while (mvr_shader_variant_enumerate(n, max_views, &v)) {
        failures += write_stage(argv[1], &v, MVR_SHADER_STAGE_VERTEX);
        failures += write_stage(argv[1], &v, MVR_SHADER_STAGE_FRAGMENT);
        ++n;
    }
    printf("dump_shaders: %u variants, %u files in %s\n", n, 2 * n, argv[1]);
    return failures ? 1 : 0;
}
