/* Built-in demo scenes and their views (see mvr.h). Deterministic: the same
 * bytes on every machine, so golden images can be compared. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"
#include "mvr_math.h"

#define PI 3.14159265358979323846
#define IPD 0.064 /* metres between eyes */

static const char *const demo_names[] = {"stereo", "cube", "city", "ring"};

const char *mvr_demo_name(uint32_t index)
{
    return index < MVR_ARRAY_COUNT(demo_names) ? demo_names[index] : NULL;
}

typedef struct builder {
    mvr_scene *scene;
    mvr_result result;           /* first failure; later calls do nothing */
} builder;

#define TRY(b, call)                     \
    do {                                 \
        if ((b)->result == MVR_OK)       \
            (b)->result = (call);        \
    } while (0)

static mvr_material_id material(builder *b, const mvr_material_desc *d)
{
    mvr_material_id id = {0};
    TRY(b, mvr_scene_add_material(b->scene, d, &id));
    return id;
}

static mvr_image_id image(builder *b, demo_pattern p, uint32_t size, const uint8_t c0[4], const uint8_t c1[4],
                          uint32_t seed)
{
    mvr_image_id id = {0};
    TRY(b, demo_image(b->scene, p, size, c0, c1, seed, &id));
    return id;
}

typedef enum shape { SHAPE_BOX, SHAPE_SPHERE, SHAPE_TORUS, SHAPE_PLANE } shape;

/* A one-primitive mesh of a shape (box/plane half extents in a, b, c). */
static mvr_mesh_id mesh(builder *b, shape s, float a, float bb, float c, mvr_material_id mat, bool colors,
                        const char *name)
{
    mvr_mesh_id id = {0};
    if (b->result != MVR_OK)
        return id;
    demo_mesh m;
    memset(&m, 0, sizeof m);
    switch (s) {
    case SHAPE_BOX: demo_box(&m, a, bb, c, 1.0f); break;
    case SHAPE_SPHERE: demo_sphere(&m, a, 48, 24); break;
    case SHAPE_TORUS: demo_torus(&m, a, bb, 48, 16); break;
    case SHAPE_PLANE: demo_plane(&m, a, c, bb); break;
    }
    if (colors)
        demo_color_by_position(&m);
    TRY(b, demo_mesh_add(b->scene, &m, mat, colors, name, &id));
    demo_mesh_free(&m);
    return id;
}

enum { AXIS_X = 0, AXIS_Y = 1 };

/* A mesh node at (x, y, z), turned by angle about an axis, scaled. */
static void node(builder *b, mvr_mesh_id m, double x, double y, double z, int axis, double angle, double sx,
                 double sy, double sz)
{
    mvr_node_desc d;
    memset(&d, 0, sizeof d);
    d.mesh = m;
    d.translation[0] = x;
    d.translation[1] = y;
    d.translation[2] = z;
    d.rotation[axis] = sin(angle * 0.5);
    d.rotation[3] = cos(angle * 0.5);
    d.scale[0] = sx;
    d.scale[1] = sy;
    d.scale[2] = sz;
    mvr_node_id id = {0};
    TRY(b, mvr_scene_add_node(b->scene, &d, &id));
}

/* A light on a node at position p shining along dir. */
static void light(builder *b, const mvr_light_desc *l, double px, double py, double pz, double dx, double dy,
                  double dz)
{
    mvr_light_id lid = {0};
    TRY(b, mvr_scene_add_light(b->scene, l, &lid));
    mvr_node_desc d;
    memset(&d, 0, sizeof d);
    d.light = lid;
    d.translation[0] = px;
    d.translation[1] = py;
    d.translation[2] = pz;
    /* the light shines along its node's -Z */
    mvr_dquat q = mvr_dquat_look_rotation(mvr_dvec3_make(dx, dy, dz),
                                          fabs(dy) > 0.99 ? mvr_dvec3_make(0, 0, -1) : mvr_dvec3_make(0, 1, 0));
    d.rotation[0] = q.x;
    d.rotation[1] = q.y;
    d.rotation[2] = q.z;
    d.rotation[3] = q.w;
    mvr_node_id id = {0};
    TRY(b, mvr_scene_add_node(b->scene, &d, &id));
}

static const uint8_t WHITE[4] = {255, 255, 255, 255};

/* The room of the stereo and cube demos: 4 x 3 x 5 m, centered on x and z. */
static void build_room(builder *b)
{
    const uint8_t oak0[4] = {176, 128, 84, 255}, oak1[4] = {122, 82, 50, 255};
    const uint8_t brick[4] = {168, 74, 52, 255}, mortar[4] = {190, 184, 172, 255};
    const uint8_t rough0[4] = {60, 60, 60, 255}, rough1[4] = {250, 250, 250, 255};
    const uint8_t leaf0[4] = {40, 110, 30, 255}, leaf1[4] = {120, 170, 40, 255};

    mvr_material_desc floor = mvr_material_defaults();
    floor.metallic_factor = 0.0f;
    floor.roughness_factor = 0.6f;
    floor.base_color = (mvr_texture_ref){image(b, DEMO_CHECKER, 128, oak0, oak1, 1), {0}, 0, {0}};
    mvr_material_id floor_m = material(b, &floor);

    mvr_material_desc wall = mvr_material_defaults();
    wall.metallic_factor = 0.0f;
    wall.roughness_factor = 0.9f;
    wall.base_color.image = image(b, DEMO_BRICKS, 256, brick, mortar, 7);
    wall.normal.image = image(b, DEMO_BRICKS_NORMAL, 256, WHITE, WHITE, 7);
    wall.normal_scale = 1.0f;
    mvr_material_id wall_m = material(b, &wall);

    mvr_material_desc ceiling = mvr_material_defaults();
    ceiling.base_color_factor[0] = 0.85f, ceiling.base_color_factor[1] = 0.85f, ceiling.base_color_factor[2] = 0.8f;
    ceiling.metallic_factor = 0.0f;
    ceiling.roughness_factor = 1.0f;
    mvr_material_id ceiling_m = material(b, &ceiling);

    /* floor and ceiling, walls: planes are XZ facing +Y, turned by the node */
    mvr_mesh_id floor_mesh = mesh(b, SHAPE_PLANE, 2.0f, 4.0f, 2.5f, floor_m, false, "floor");
    node(b, floor_mesh, 0, 0, 0, AXIS_Y, 0, 1, 1, 1);
    mvr_mesh_id ceiling_mesh = mesh(b, SHAPE_PLANE, 2.0f, 1.0f, 2.5f, ceiling_m, false, "ceiling");
    node(b, ceiling_mesh, 0, 3.0, 0, AXIS_X, PI, 1, 1, 1); /* faces down */
    /* walls from boxes (thin), so both sides and edges are closed */
    mvr_mesh_id side_wall = mesh(b, SHAPE_BOX, 0.05f, 1.5f, 2.5f, wall_m, false, "side wall");
    node(b, side_wall, -2.05, 1.5, 0, AXIS_Y, 0, 1, 1, 1);
    node(b, side_wall, 2.05, 1.5, 0, AXIS_Y, 0, 1, 1, 1);
    mvr_mesh_id end_wall = mesh(b, SHAPE_BOX, 2.0f, 1.5f, 0.05f, wall_m, false, "end wall");
    node(b, end_wall, 0, 1.5, -2.55, AXIS_Y, 0, 1, 1, 1);
    node(b, end_wall, 0, 1.5, 2.55, AXIS_Y, 0, 1, 1, 1);

    /* objects */
    mvr_material_desc gold = mvr_material_defaults();
    gold.base_color_factor[0] = 1.0f, gold.base_color_factor[1] = 0.77f, gold.base_color_factor[2] = 0.34f;
    gold.metallic_factor = 1.0f;
    gold.roughness_factor = 0.3f;
    node(b, mesh(b, SHAPE_SPHERE, 0.45f, 0, 0, material(b, &gold), false, "gold sphere"), -0.9, 0.45, -1.0, AXIS_Y, 0, 1,
         1, 1);

    mvr_material_desc plastic = mvr_material_defaults();
    plastic.base_color_factor[0] = 0.8f, plastic.base_color_factor[1] = 0.1f, plastic.base_color_factor[2] = 0.1f;
    plastic.metallic_factor = 0.0f;
    plastic.roughness_factor = 1.0f;
    plastic.metallic_roughness.image = image(b, DEMO_NOISE, 128, rough0, rough1, 3);
    plastic.occlusion.image = plastic.metallic_roughness.image;
    plastic.occlusion_strength = 0.5f;
    node(b, mesh(b, SHAPE_SPHERE, 0.4f, 0, 0, material(b, &plastic), false, "red sphere"), 0.9, 0.4, -1.6, AXIS_Y, 0, 1,
         1, 1);

    mvr_material_desc painted = mvr_material_defaults();
    painted.metallic_factor = 0.0f;
    painted.roughness_factor = 0.5f;
    node(b, mesh(b, SHAPE_BOX, 0.35f, 0.35f, 0.35f, material(b, &painted), true, "colored box"), 0.1, 0.35, -2.0, AXIS_Y,
         0.6, 1, 1, 1);

    mvr_material_desc glow = mvr_material_defaults();
    glow.base_color_factor[0] = glow.base_color_factor[1] = glow.base_color_factor[2] = 0.1f;
    glow.metallic_factor = 0.0f;
    glow.emissive_factor[0] = 0.2f, glow.emissive_factor[1] = 0.6f, glow.emissive_factor[2] = 1.0f;
    glow.emissive_strength = 2.0f;
    /* the ring turned towards the viewer */
    node(b, mesh(b, SHAPE_TORUS, 0.3f, 0.06f, 0, material(b, &glow), false, "glow torus"), -0.1, 1.45,
                -2.1, AXIS_X, 1.3, 1, 1, 1);

    mvr_material_desc leaf = mvr_material_defaults();
    leaf.metallic_factor = 0.0f;
    leaf.roughness_factor = 0.7f;
    leaf.alpha_mode = MVR_ALPHA_MASK;
    leaf.double_sided = true;
    leaf.base_color.image = image(b, DEMO_LEAF_MASK, 128, leaf0, leaf1, 11);
    leaf.base_color.sampler.wrap_s = leaf.base_color.sampler.wrap_t = MVR_WRAP_CLAMP_TO_EDGE;
    node(b, mesh(b, SHAPE_PLANE, 0.25f, 1.0f, 0.4f, material(b, &leaf), false, "leaf"), 1.4, 1.0, -0.8, AXIS_X,
                1.2, 1, 1, 1);

    mvr_material_desc glass = mvr_material_defaults();
    glass.base_color_factor[0] = 0.6f, glass.base_color_factor[1] = 0.85f, glass.base_color_factor[2] = 0.9f;
    glass.base_color_factor[3] = 0.35f;
    glass.metallic_factor = 0.0f;
    glass.roughness_factor = 0.05f;
    glass.alpha_mode = MVR_ALPHA_BLEND;
    glass.double_sided = true;
    node(b, mesh(b, SHAPE_BOX, 0.4f, 0.5f, 0.02f, material(b, &glass), false, "glass pane"), 0.55, 0.5, -0.55, AXIS_Y,
         -0.35, 1, 1, 1);

    mvr_material_desc marker = mvr_material_defaults();
    marker.base_color_factor[0] = 1.0f, marker.base_color_factor[1] = 0.85f, marker.base_color_factor[2] = 0.0f;
    marker.unlit = true;
    node(b, mesh(b, SHAPE_BOX, 0.08f, 0.08f, 0.08f, material(b, &marker), false, "unlit marker"), 1.2, 0.08, -0.2, AXIS_Y,
         0.3, 1, 1, 1);

    /* lights: a dim sun through the (implied) window, a ceiling bulb, a spot on the spheres */
    mvr_light_desc sun = {MVR_LIGHT_DIRECTIONAL, {1.0f, 0.95f, 0.85f}, 1.5f, 0, 0, 0, false, 0};
    light(b, &sun, 0, 3, 0, 0.4, -1.0, -0.5);
    mvr_light_desc bulb = {MVR_LIGHT_POINT, {1.0f, 0.9f, 0.75f}, 6.0f, 12.0f, 0, 0, false, 0};
    light(b, &bulb, 0.3, 2.6, -0.5, 0, -1, 0);
    mvr_light_desc spot = {MVR_LIGHT_SPOT, {0.8f, 0.9f, 1.0f}, 25.0f, 0, 0.25f, 0.45f, false, 0};
    light(b, &spot, -1.5, 2.8, 1.5, 0.6, -1.2, -1.1);
    float ambient[3] = {0.04f, 0.04f, 0.05f};
    mvr_scene_set_ambient(b->scene, ambient);
}

static void build_city(builder *b)
{
    const uint8_t asphalt0[4] = {70, 70, 74, 255}, asphalt1[4] = {52, 52, 56, 255};
    mvr_material_desc ground = mvr_material_defaults();
    ground.metallic_factor = 0.0f;
    ground.roughness_factor = 0.95f;
    ground.base_color.image = image(b, DEMO_CHECKER, 64, asphalt0, asphalt1, 5);
    node(b, mesh(b, SHAPE_PLANE, 100.0f, 50.0f, 100.0f, material(b, &ground), false, "ground"), 0, 0, 0, AXIS_Y, 0, 1, 1,
         1);
    /* 64 textured facade materials (two texture sizes) + 8 plain ones */
    enum { TEXTURED = 64, PLAIN = 8, GRID = 64 };
    mvr_material_id mats[TEXTURED + PLAIN];
    for (uint32_t i = 0; i < TEXTURED + PLAIN; ++i) {
        uint32_t h = i * 2654435761u;
        mvr_material_desc m = mvr_material_defaults();
        m.metallic_factor = i % 5 == 0 ? 0.8f : 0.0f;
        m.roughness_factor = 0.3f + 0.6f * (float)((h >> 8) % 100) / 100.0f;
        uint8_t wall[4] = {(uint8_t)(90 + (h >> 3) % 120), (uint8_t)(90 + (h >> 11) % 110),
                           (uint8_t)(90 + (h >> 19) % 100), 255};
        uint8_t lit[4] = {(uint8_t)(200 + (h >> 5) % 55), (uint8_t)(190 + (h >> 13) % 60), 140, 255};
        if (i < TEXTURED) {
            /* mixed sizes: three quarters 64x64, a quarter 128x128 (two texture arrays) */
            m.base_color.image = image(b, DEMO_WINDOWS, i % 4 == 3 ? 128 : 64, wall, lit, i);
        } else {
            m.base_color_factor[0] = (float)wall[0] / 255.0f;
            m.base_color_factor[1] = (float)wall[1] / 255.0f;
            m.base_color_factor[2] = (float)wall[2] / 255.0f;
        }
        mats[i] = material(b, &m);
    }
    /* one unit box per material; buildings are scaled instances of them */
    mvr_mesh_id boxes[TEXTURED + PLAIN];
    for (uint32_t i = 0; i < TEXTURED + PLAIN; ++i) {
        boxes[i] = (mvr_mesh_id){0};
        if (b->result != MVR_OK)
            continue;
        demo_mesh m;
        memset(&m, 0, sizeof m);
        demo_box(&m, 0.5f, 0.5f, 0.5f, 1.0f);
        for (uint32_t v = 0; v < m.vertex_count; ++v) /* base at y = 0 */
            m.positions[v * 3 + 1] += 0.5f;
        TRY(b, demo_mesh_add(b->scene, &m, mats[i], false, "building", &boxes[i]));
        demo_mesh_free(&m);
    }
    const double spacing = 3.0;
    for (uint32_t z = 0; z < GRID; ++z)
        for (uint32_t x = 0; x < GRID; ++x) {
            uint32_t h = (x * 73856093u) ^ (z * 19349663u);
            h ^= h >> 13;
            h *= 0x5bd1e995u;
            h ^= h >> 15;
            double height = 2.0 + (double)(h % 1000) / 1000.0 * (x % 9 == 4 && z % 7 == 3 ? 30.0 : 10.0);
            double px = ((double)x - (GRID - 1) * 0.5) * spacing, pz = ((double)z - (GRID - 1) * 0.5) * spacing;
            node(b, boxes[h % (TEXTURED + PLAIN)], px, 0, pz, AXIS_Y, 0, 2.0, height, 2.0);
        }
    mvr_light_desc sun = {MVR_LIGHT_DIRECTIONAL, {1.0f, 0.96f, 0.9f}, 3.0f, 0, 0, 0, false, 0};
    light(b, &sun, 0, 50, 0, -0.5, -1.0, -0.3);
    float ambient[3] = {0.12f, 0.14f, 0.18f};
    mvr_scene_set_ambient(b->scene, ambient);
}

static void build_ring_object(builder *b)
{
    const uint8_t stone0[4] = {150, 148, 140, 255}, stone1[4] = {110, 106, 100, 255};
    const uint8_t t0[4] = {30, 90, 160, 255}, t1[4] = {230, 230, 240, 255};
    mvr_material_desc floor = mvr_material_defaults();
    floor.metallic_factor = 0.0f;
    floor.roughness_factor = 0.8f;
    floor.base_color.image = image(b, DEMO_CHECKER, 128, stone0, stone1, 2);
    node(b, mesh(b, SHAPE_PLANE, 6.0f, 6.0f, 6.0f, material(b, &floor), false, "floor"), 0, 0, 0, AXIS_Y, 0, 1, 1, 1);
    mvr_material_desc pedestal = mvr_material_defaults();
    pedestal.metallic_factor = 0.0f;
    pedestal.roughness_factor = 0.4f;
    node(b, mesh(b, SHAPE_BOX, 0.6f, 0.4f, 0.6f, material(b, &pedestal), true, "pedestal"), 0, 0.4, 0, AXIS_Y, 0.3, 1, 1,
         1);
    mvr_material_desc ring = mvr_material_defaults();
    ring.metallic_factor = 0.0f;
    ring.roughness_factor = 0.35f;
    ring.base_color.image = image(b, DEMO_CHECKER, 128, t0, t1, 9);
    ring.base_color.transform.enabled = true; /* KHR_texture_transform */
    ring.base_color.transform.scale[0] = 2.0f;
    ring.base_color.transform.scale[1] = 1.0f;
    ring.base_color.transform.rotation = 0.3f;
    node(b, mesh(b, SHAPE_TORUS, 0.5f, 0.18f, 0, material(b, &ring), false, "torus"), 0, 1.35, 0, AXIS_X, 0.6, 1, 1, 1);
    mvr_material_desc chrome = mvr_material_defaults();
    chrome.base_color_factor[0] = chrome.base_color_factor[1] = chrome.base_color_factor[2] = 0.95f;
    chrome.roughness_factor = 0.15f;
    node(b, mesh(b, SHAPE_SPHERE, 0.25f, 0, 0, material(b, &chrome), false, "chrome"), 0, 1.35, 0, AXIS_Y, 0, 1, 1, 1);
    mvr_light_desc key = {MVR_LIGHT_DIRECTIONAL, {1.0f, 0.97f, 0.92f}, 2.5f, 0, 0, 0, false, 0};
    light(b, &key, 0, 5, 0, -0.4, -1.0, -0.6);
    mvr_light_desc fill = {MVR_LIGHT_POINT, {0.6f, 0.7f, 1.0f}, 20.0f, 0, 0, 0, false, 0};
    light(b, &fill, 2.5, 3.0, 2.5, 0, -1, 0);
    float ambient[3] = {0.08f, 0.08f, 0.1f};
    mvr_scene_set_ambient(b->scene, ambient);
}

static void look(mvr_view_desc *v, double ex, double ey, double ez, double tx, double ty, double tz, double ux,
                 double uy, double uz)
{
    const double eye[3] = {ex, ey, ez}, target[3] = {tx, ty, tz}, up[3] = {ux, uy, uz};
    mvr_view_look_at(v, eye, target, up);
}

static void make_views(const char *name, uint32_t n, double aspect, mvr_view_desc *views)
{
    memset(views, 0, n * sizeof *views);
    if (strcmp(name, "stereo") == 0 || strcmp(name, "city") == 0) {
        bool city = name[1] == 'i';
        for (uint32_t i = 0; i < n; ++i) {
            /* a row of eyes IPD apart, parallel axes, asymmetric frusta
             * converging on the scene (as an HMD's eyes) */
            double offset = ((double)i - (double)(n - 1) * 0.5) * IPD;
            mvr_view_desc *v = &views[i];
            if (city)
                look(v, offset, 70.0, 95.0, offset, 0.0, 10.0, 0, 1, 0);
            else
                look(v, offset, 1.55, 2.2, offset, 0.9, -1.2, 0, 1, 0);
            double half_v = 0.45, half_h = atan(tan(half_v) * aspect);
            double skew = n > 1 ? -offset * 0.9 : 0.0; /* toward the center */
            v->projection.type = MVR_PROJECTION_FRUSTUM;
            v->projection.angle_left = -half_h + skew;
            v->projection.angle_right = half_h + skew;
            v->projection.angle_down = -half_v;
            v->projection.angle_up = half_v;
            v->projection.znear = city ? 0.5 : 0.05;
        }
    } else if (strcmp(name, "cube") == 0) {
        /* cube-map faces +X, -X, +Y, -Y, +Z, -Z from the room's center */
        /* upright images (a camera rig), not GL cube-map face orientation */
        static const double dirs[6][6] = {{1, 0, 0, 0, 1, 0}, {-1, 0, 0, 0, 1, 0}, {0, 1, 0, 0, 0, 1},
                                          {0, -1, 0, 0, 0, -1}, {0, 0, 1, 0, 1, 0}, {0, 0, -1, 0, 1, 0}};
        for (uint32_t i = 0; i < n; ++i) {
            const double *d = dirs[i % 6];
            look(&views[i], 0, 1.5, 0, d[0], 1.5 + d[1], d[2], d[3], d[4], d[5]);
            views[i].projection.type = MVR_PROJECTION_FRUSTUM;
            views[i].projection.angle_left = views[i].projection.angle_down = -PI / 4;
            views[i].projection.angle_right = views[i].projection.angle_up = PI / 4;
            views[i].projection.znear = 0.05;
        }
    } else { /* ring */
        for (uint32_t i = 0; i < n; ++i) {
            double a = 2.0 * PI * (double)i / (double)n;
            look(&views[i], 4.0 * sin(a), 2.0, 4.0 * cos(a), 0, 1.0, 0, 0, 1, 0);
            views[i].projection.yfov = 0.75;
            views[i].projection.aspect = aspect;
        }
    }
}

mvr_result mvr_demo_create(const char *name, const mvr_demo_desc *desc, mvr_scene **out_scene,
                           mvr_view_set **out_views, mvr_error *error)
{
    if (!name || !out_scene || !out_views)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_demo_create: NULL argument");
    *out_scene = NULL;
    *out_views = NULL;
    uint32_t which = 0;
    while (mvr_demo_name(which) && strcmp(mvr_demo_name(which), name) != 0)
        which++;
    if (!mvr_demo_name(which))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_demo_create: no demo '%s' (stereo, cube, city, ring)", name);
    mvr_demo_desc d;
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    static const uint32_t default_views[] = {2, 6, 2, 8};
    uint32_t n = d.views ? d.views : default_views[which];
    if (n > 1024)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_demo_create: %u views (at most 1024)", n);
    double aspect = (d.width && d.height) ? (double)d.width / (double)d.height : 1.0;

    mvr_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.logger = d.logger;
    builder b = {NULL, MVR_OK};
    mvr_result r = mvr_scene_create(&sd, &b.scene, error);
    if (r != MVR_OK)
        return r;
    switch (which) {
    case 0:
    case 1: build_room(&b); break;
    case 2: build_city(&b); break;
    default: build_ring_object(&b); break;
    }
    if (b.result != MVR_OK) {
        mvr_error_set(error, b.result, "mvr_demo_create(%s): %s", name, mvr_scene_last_error(b.scene));
        mvr_scene_destroy(b.scene);
        return b.result;
    }
    mvr_view_desc *views = calloc(n, sizeof *views);
    if (!views) {
        mvr_scene_destroy(b.scene);
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_demo_create: out of memory");
    }
    make_views(name, n, aspect, views);
    mvr_view_set_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.view_count = n;
    vd.views = views;
    r = mvr_view_set_create(&vd, out_views, error);
    free(views);
    if (r != MVR_OK) {
        mvr_scene_destroy(b.scene);
        return r;
    }
    *out_scene = b.scene;
    return MVR_OK;
}
