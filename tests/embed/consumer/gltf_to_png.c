/*
 * An application outside mvr's tree, built against the installed package
 * alone: loads a glTF file (mvr_gltf.h), renders it headless from two framed
 * eyes under the neutral studio (mvr.h), writes the left eye as a PNG
 * (mvr_image.h), then reads the PNG back and checks it holds a picture (the
 * model's size and more than one colour). Pure C.
 * usage: gltf_to_png IN.gltf OUT.png
 */
#include <mvr/mvr.h>
#include <mvr/mvr_gltf.h>
#include <mvr/mvr_image.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { WIDTH = 160, HEIGHT = 120, VIEWS = 2 };

static int fail(const char *what, const char *message)
{
    fprintf(stderr, "gltf_to_png: %s: %s\n", what, message);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gltf_to_png IN.gltf OUT.png\n");
        return 2;
    }
    mvr_error error = {0};
    mvr_scene *scene = NULL;
    mvr_gltf_info info = {0};
    if (mvr_gltf_load_file(argv[1], NULL, &scene, &info, &error) != MVR_OK)
        return fail("mvr_gltf_load_file", error.message);
    printf("loaded %s: %u images decoded, %u buffers read\n", argv[1], info.images_decoded, info.buffers_read);

    mvr_context_desc context_desc = {0};
    mvr_context *context = NULL;
    if (mvr_context_create(&context_desc, &context, &error) != MVR_OK)
        return fail("mvr_context_create", error.message);
    mvr_renderer_desc renderer_desc = {0};
    renderer_desc.context = context;
    mvr_renderer *renderer = NULL;
    if (mvr_renderer_create(&renderer_desc, &renderer, &error) != MVR_OK)
        return fail("mvr_renderer_create", error.message);
    mvr_target_desc target_desc = {0};
    target_desc.width = WIDTH;
    target_desc.height = HEIGHT;
    target_desc.layers = VIEWS;
    mvr_target *target = NULL;
    if (mvr_target_create(renderer, &target_desc, &target) != MVR_OK)
        return fail("mvr_target_create", mvr_renderer_last_error(renderer));
    mvr_framing_desc framing = {0};
    framing.layout = MVR_LAYOUT_STEREO;
    framing.views = VIEWS;
    framing.aspect = (double)WIDTH / HEIGHT;
    mvr_view_set *views = NULL;
    if (mvr_view_set_frame_scene(scene, &framing, &views, &error) != MVR_OK)
        return fail("mvr_view_set_frame_scene", error.message);
    mvr_environment_desc environment_desc = {0};
    environment_desc.source = MVR_ENVIRONMENT_NEUTRAL;
    environment_desc.specular_size = 32;
    environment_desc.specular_samples = 16;
    mvr_environment *environment = NULL;
    if (mvr_environment_create(&environment_desc, &environment, &error) != MVR_OK)
        return fail("mvr_environment_create", error.message);
    mvr_render_desc render_desc = {0};
    render_desc.environment = environment;
    mvr_render_desc_choose_exposure(scene, &render_desc);
    if (mvr_renderer_render(renderer, scene, views, target, &render_desc) != MVR_OK)
        return fail("mvr_renderer_render", mvr_renderer_last_error(renderer));

    size_t size = (size_t)WIDTH * HEIGHT * 4;
    uint8_t *pixels = malloc(size);
    if (!pixels || mvr_renderer_read_layer(renderer, target, 0, MVR_READBACK_RGBA8, pixels, size) != MVR_OK)
        return fail("mvr_renderer_read_layer", mvr_renderer_last_error(renderer));
    mvr_image_view image = {WIDTH, HEIGHT, MVR_PIXEL_U8, true, pixels};
    if (mvr_image_write(argv[2], &image, &error) != MVR_OK)
        return fail("mvr_image_write", error.message);

    mvr_image_data back = {0};
    if (mvr_image_read(argv[2], MVR_PIXEL_U8, &back, &error) != MVR_OK)
        return fail("mvr_image_read", error.message);
    const uint8_t *p = back.pixels;
    size_t differing = 0;
    for (size_t i = 4; i < (size_t)back.width * back.height * 4; i += 4)
        differing += memcmp(p + i, p, 3) != 0;
    int ok = back.width == WIDTH && back.height == HEIGHT && differing > 0;
    printf("wrote %s: %ux%u, %zu pixels differ from the first\n", argv[2], back.width, back.height, differing);
    mvr_image_free(&back);
    free(pixels);
    mvr_environment_destroy(environment);
    mvr_view_set_destroy(views);
    mvr_target_destroy(target);
    mvr_renderer_destroy(renderer);
    mvr_context_destroy(context);
    mvr_scene_destroy(scene);
    return ok ? 0 : fail(argv[2], "holds no picture");
}
