/* Helpers the demo scenes are built with: meshes with normals, tangents and
 * UVs, and procedural textures. Backend-free. */
#ifndef MVR_DEMO_BUILDER_H
#define MVR_DEMO_BUILDER_H

#include "core_util.h"

/* A mesh being generated: arrays grow as vertices and triangles are added. */
typedef struct demo_mesh {
    float *positions, *normals, *tangents, *uv0, *colors;
    uint32_t *indices;
    uint32_t vertex_count, index_count, vertex_cap, index_cap;
    bool failed;
} demo_mesh;

void demo_mesh_free(demo_mesh *m);
/* Adds to the scene as a one-primitive mesh; colors only if with_colors. */
mvr_result demo_mesh_add(mvr_scene *scene, demo_mesh *m, mvr_material_id material, bool with_colors,
                         const char *name, mvr_mesh_id *out);

/* Axis-aligned box centered at 0 with half extents; uv repeats uv_scale per face. */
void demo_box(demo_mesh *m, float hx, float hy, float hz, float uv_scale);
/* UV sphere of radius r. */
void demo_sphere(demo_mesh *m, float r, uint32_t slices, uint32_t stacks);
/* Torus around Y: ring radius R, tube radius r. */
void demo_torus(demo_mesh *m, float R, float r, uint32_t segments, uint32_t sides);
/* Quad in the XZ plane facing +Y, half extents hx, hz; uv repeats uv_scale. */
void demo_plane(demo_mesh *m, float hx, float hz, float uv_scale);
/* Sets every vertex color from a function of the position (for COLOR_0 demos). */
void demo_color_by_position(demo_mesh *m);

/* Procedural images (RGBA8), added to the scene. */
typedef enum demo_pattern {
    DEMO_CHECKER,       /* two colors */
    DEMO_BRICKS,        /* mortar + bricks with per-brick tint */
    DEMO_BRICKS_NORMAL, /* tangent-space normal map of DEMO_BRICKS' relief */
    DEMO_NOISE,         /* value noise (roughness / occlusion maps) */
    DEMO_WINDOWS,       /* facade: windows in rows */
    DEMO_LEAF_MASK      /* alpha-tested leaf shapes on transparent */
} demo_pattern;

mvr_result demo_image(mvr_scene *scene, demo_pattern pattern, uint32_t size, const uint8_t a[4],
                      const uint8_t b[4], uint32_t seed, mvr_image_id *out);

#endif
