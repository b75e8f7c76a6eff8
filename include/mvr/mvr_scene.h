/*
 * mvr: scenes built in code: images, materials, meshes, lights,
 * cameras, nodes; skins, morph weights and animations; material variants;
 * what a scene holds and its names.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_SCENE_API_H
#define MVR_SCENE_API_H

#include "mvr/mvr_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ scene
 *
 * A scene is built in code (or by the glTF loader) and owns copies of
 * everything given to it. Ids are small structs (0 = none / invalid), valid
 * for the scene that returned them. Nothing here touches GL: a renderer
 * uploads what it needs when it first draws a scene, and again only what
 * changed (geometry and materials on edits, transforms every frame).
 */

typedef struct mvr_scene mvr_scene;
typedef struct mvr_image_id { uint32_t id; } mvr_image_id;
typedef struct mvr_mesh_id { uint32_t id; } mvr_mesh_id;
typedef struct mvr_material_id { uint32_t id; } mvr_material_id;
typedef struct mvr_node_id { uint32_t id; } mvr_node_id;
typedef struct mvr_light_id { uint32_t id; } mvr_light_id;
typedef struct mvr_camera_id { uint32_t id; } mvr_camera_id;

typedef struct mvr_scene_desc {
    mvr_logger logger;
} mvr_scene_desc;

mvr_result mvr_scene_create(const mvr_scene_desc *desc, mvr_scene **out_scene, mvr_error *out_error);
void mvr_scene_destroy(mvr_scene *scene);
const char *mvr_scene_last_error(const mvr_scene *scene);

/* How an image's texels are stored. RGBA8 (the zero value) is 8-bit RGBA
 * pixels; the others are GPU block formats the GL samples without mvr
 * decoding them: the blocks are uploaded as given (glCompressedTex*), each
 * level ceil(w / bw) * ceil(h / bh) blocks, rows of blocks top first (as a
 * KTX2 file stores them). Whether a texture is sRGB-encoded comes from its
 * role (base color, emissive, ...: GL_COMPRESSED_SRGB8_ETC2 and the like),
 * as for RGBA8; EAC R11 / RG11 have no sRGB form and are sampled as stored.
 * ETC2 and EAC are core in OpenGL ES 3.0 (and desktop GL 4.3); ASTC needs
 * KHR_texture_compression_astc_ldr. An image the renderer's GL cannot
 * sample is drawn with its role's neutral value (white; a flat normal),
 * with a warning naming it (mvr_frame_stats.images_unsampleable). */
typedef enum mvr_image_format {
    MVR_IMAGE_FORMAT_RGBA8 = 0,
    MVR_IMAGE_FORMAT_ETC2_RGB8,        /* 4x4 blocks of 8 bytes */
    MVR_IMAGE_FORMAT_ETC2_RGB8_A1,     /* punch-through alpha; 4x4, 8 bytes */
    MVR_IMAGE_FORMAT_ETC2_RGBA8,       /* ETC2 colour + EAC alpha; 4x4, 16 bytes */
    MVR_IMAGE_FORMAT_EAC_R11,          /* unsigned; 4x4, 8 bytes; samples (r, 0, 0, 1) */
    MVR_IMAGE_FORMAT_EAC_RG11,         /* unsigned; 4x4, 16 bytes; samples (r, g, 0, 1) */
    MVR_IMAGE_FORMAT_ASTC_4x4,         /* ASTC LDR: 16 bytes per block of every size */
    MVR_IMAGE_FORMAT_ASTC_5x4,
    MVR_IMAGE_FORMAT_ASTC_5x5,
    MVR_IMAGE_FORMAT_ASTC_6x5,
    MVR_IMAGE_FORMAT_ASTC_6x6,
    MVR_IMAGE_FORMAT_ASTC_8x5,
    MVR_IMAGE_FORMAT_ASTC_8x6,
    MVR_IMAGE_FORMAT_ASTC_8x8,
    MVR_IMAGE_FORMAT_ASTC_10x5,
    MVR_IMAGE_FORMAT_ASTC_10x6,
    MVR_IMAGE_FORMAT_ASTC_10x8,
    MVR_IMAGE_FORMAT_ASTC_10x10,
    MVR_IMAGE_FORMAT_ASTC_12x10,
    MVR_IMAGE_FORMAT_ASTC_12x12,
    MVR_IMAGE_FORMAT_COUNT
} mvr_image_format;

/* Levels of a 16384-texel image's full mip chain. */
#define MVR_IMAGE_MAX_LEVELS 15

/* "rgba8", "etc2_rgb8", ..., "astc_12x12"; "unknown" outside the enum. */
const char *mvr_image_format_name(mvr_image_format format);
/* A format's block: width and height in texels and bytes (RGBA8: 1 x 1, 4
 * bytes). false outside the enum. */
bool mvr_image_format_block(mvr_image_format format, uint32_t *block_width, uint32_t *block_height,
                            uint32_t *block_bytes);
/* The bytes of mip level `level` of a width x height image in format:
 * max(1, width >> level) by max(1, height >> level) texels in whole blocks.
 * false (and *out 0) for a format outside the enum, a level outside the
 * image's chain (floor(log2(max(width, height))) + 1 levels) or a size that
 * overflows. */
bool mvr_image_level_size(mvr_image_format format, uint32_t width, uint32_t height, uint32_t level, uint64_t *out);

typedef struct mvr_image_level {
    const void *data;            /* the level's blocks, copied */
    size_t size;                 /* exactly mvr_image_level_size's bytes */
} mvr_image_level;

/* Images: 8-bit RGBA pixels, rows top to bottom (as image files store
 * them), or (format != RGBA8) GPU blocks with their mip levels. */
typedef struct mvr_image_desc {
    uint32_t width, height;
    const uint8_t *rgba8;        /* RGBA8: width * height * 4 bytes, copied; NULL otherwise */
    const char *name;            /* optional, for messages */
    mvr_image_format format;     /* 0 = RGBA8 */
    /* Block formats: level_count (1..MVR_IMAGE_MAX_LEVELS, at most the full
     * chain) levels, level 0 (width x height) first, each its exact size.
     * Fewer levels than the full chain are fine: a sampler that reads mips
     * reads only those. RGBA8 images leave these 0 (mips are generated). */
    uint32_t level_count;
    mvr_image_level levels[MVR_IMAGE_MAX_LEVELS];
} mvr_image_desc;
mvr_result mvr_scene_add_image(mvr_scene *scene, const mvr_image_desc *desc, mvr_image_id *out);

typedef enum mvr_filter {
    MVR_FILTER_DEFAULT = 0,      /* mag: linear; min: linear-mipmap-linear */
    MVR_FILTER_NEAREST,
    MVR_FILTER_LINEAR,
    MVR_FILTER_NEAREST_MIPMAP_NEAREST,
    MVR_FILTER_LINEAR_MIPMAP_NEAREST,
    MVR_FILTER_NEAREST_MIPMAP_LINEAR,
    MVR_FILTER_LINEAR_MIPMAP_LINEAR
} mvr_filter;

typedef enum mvr_wrap {
    MVR_WRAP_DEFAULT = 0,        /* repeat, as glTF */
    MVR_WRAP_REPEAT,
    MVR_WRAP_CLAMP_TO_EDGE,
    MVR_WRAP_MIRRORED_REPEAT
} mvr_wrap;

typedef struct mvr_sampler_desc {
    mvr_filter mag_filter, min_filter;
    mvr_wrap wrap_s, wrap_t;
} mvr_sampler_desc;

/* KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv. */
typedef struct mvr_texture_transform {
    bool enabled;
    float offset[2];
    float rotation;              /* radians, counter-clockwise */
    float scale[2];              /* 0 = 1 */
} mvr_texture_transform;

typedef struct mvr_texture_ref {
    mvr_image_id image;          /* 0 = no texture in this role */
    mvr_sampler_desc sampler;
    uint32_t texcoord;           /* 0 or 1 */
    mvr_texture_transform transform;
} mvr_texture_ref;

typedef enum mvr_alpha_mode {
    MVR_ALPHA_OPAQUE = 0,
    MVR_ALPHA_MASK,
    MVR_ALPHA_BLEND
} mvr_alpha_mode;

/* glTF 2.0 metallic-roughness material. Factors left at zero take glTF's
 * defaults only where the desc says so (use mvr_material_defaults). */
typedef struct mvr_material_desc {
    float base_color_factor[4];
    float metallic_factor;
    float roughness_factor;
    float emissive_factor[3];
    float emissive_strength;     /* KHR_materials_emissive_strength; 0 = 1 */
    float normal_scale;          /* 0 = 1 */
    float occlusion_strength;    /* 0 = 1 */
    float alpha_cutoff;          /* 0 = 0.5 */
    mvr_alpha_mode alpha_mode;
    bool double_sided;
    bool unlit;                  /* KHR_materials_unlit */
    mvr_texture_ref base_color, metallic_roughness, normal, occlusion, emissive;
    const char *name;
    /* KHR_materials_ior: the dielectric's index of refraction, F0 =
     * ((ior - 1) / (ior + 1))^2 (also the clearcoat's); 0 = 1.5 (F0 0.04) */
    float ior;
    /* KHR_materials_specular (enabled: the extension is present): factor
     * scales the dielectric's specular (its F0 and F90), color_factor tints
     * its F0 (min(F0(ior) * color, 1)); absent: 1 and (1, 1, 1). texture:
     * its A channel scales factor; color_texture (sRGB): its RGB the color */
    struct mvr_material_specular {
        bool enabled;
        float factor;
        float color_factor[3];
        mvr_texture_ref texture, color_texture;
    } specular;
    /* KHR_materials_clearcoat: a second GGX layer (F0 from ior) over the
     * material; factor 0 = none. texture: R scales factor; roughness_texture:
     * G scales roughness_factor; normal_texture: the coat's own normal map
     * (else the geometry's normal), its xy scaled by normal_scale (0 = 1) */
    struct mvr_material_clearcoat {
        float factor;
        float roughness_factor;
        mvr_texture_ref texture, roughness_texture, normal_texture;
        float normal_scale;
    } clearcoat;
    /* KHR_materials_sheen: a Charlie-distribution sheen layer (fabric);
     * color (0, 0, 0) = none. color_texture (sRGB): RGB scales color_factor;
     * roughness_texture: A scales roughness_factor */
    struct mvr_material_sheen {
        float color_factor[3];
        float roughness_factor;
        mvr_texture_ref color_texture, roughness_texture;
    } sheen;
    /* KHR_materials_transmission: the fraction of light passing through the
     * surface (0 = opaque); texture: R scales factor */
    struct mvr_material_transmission {
        float factor;
        mvr_texture_ref texture;
    } transmission;
    /* KHR_materials_volume: the medium under a transmissive surface.
     * thickness_factor 0 = thin-walled; thickness_texture: G scales it.
     * attenuation_distance 0 = no absorption (the extension's +infinity);
     * attenuation_color: the color white light takes after that distance */
    struct mvr_material_volume {
        float thickness_factor;
        mvr_texture_ref thickness_texture;
        float attenuation_distance;
        float attenuation_color[3];
    } volume;
    /* KHR_materials_dispersion: the Abbe-number spread of ior across
     * wavelengths, as 20 / V (0 = none); only with transmission and volume */
    float dispersion;
    /* KHR_materials_iridescence: a thin film over the base (factor 0 =
     * none); texture: R scales factor; the film's thickness in nanometres is
     * mix(thickness_minimum, thickness_maximum, thickness_texture's G) or
     * thickness_maximum without the texture. mvr_material_defaults: ior 1.3,
     * 100 and 400 nm (the extension's defaults) */
    struct mvr_material_iridescence {
        float factor;
        mvr_texture_ref texture;
        float ior;
        float thickness_minimum, thickness_maximum;
        mvr_texture_ref thickness_texture;
    } iridescence;
    /* KHR_materials_anisotropy: the specular lobe stretched along a
     * direction rotated by rotation (radians, counter-clockwise from the
     * tangent) by strength (0 = isotropic); texture: RG a direction in
     * tangent space ([0, 1] -> [-1, 1]), B scales strength */
    struct mvr_material_anisotropy {
        float strength;
        float rotation;
        mvr_texture_ref texture;
    } anisotropy;
    /* KHR_materials_pbrSpecularGlossiness (archived, still in many files):
     * when enabled, base_color_factor and base_color are the diffuse factor
     * and texture, and the specular color (F0) and glossiness (1 - roughness)
     * come from here; texture (sRGB): RGB scales specular_factor, A
     * glossiness_factor. metallic and roughness are ignored */
    struct mvr_material_spec_gloss {
        bool enabled;
        float specular_factor[3];
        float glossiness_factor;
        mvr_texture_ref texture;
    } spec_gloss;
} mvr_material_desc;

/* glTF's defaults: base color (1,1,1,1), metallic 1, roughness 1, opaque;
 * the extensions' own defaults (iridescence ior 1.3 and 100-400 nm, volume
 * attenuation color white, spec-gloss factors 1). */
mvr_material_desc mvr_material_defaults(void);
mvr_result mvr_scene_add_material(mvr_scene *scene, const mvr_material_desc *desc,
                                  mvr_material_id *out);

typedef enum mvr_primitive_mode {
    MVR_PRIMITIVE_TRIANGLES = 0,
    MVR_PRIMITIVE_LINES,
    MVR_PRIMITIVE_POINTS
} mvr_primitive_mode;

/* One draw's worth of geometry; arrays are copied. Optional arrays are NULL. */
typedef struct mvr_primitive_desc {
    uint32_t vertex_count;
    const float *positions;      /* 3 per vertex, required */
    const float *normals;        /* 3 per vertex */
    const float *tangents;       /* 4 per vertex (w = bitangent sign) */
    const float *texcoords0;     /* 2 per vertex */
    const float *texcoords1;     /* 2 per vertex */
    const float *colors;         /* 4 per vertex (linear RGBA) */
    uint32_t index_count;        /* 0 = non-indexed */
    const uint16_t *indices16;   /* one of these two when indexed */
    const uint32_t *indices32;
    mvr_primitive_mode mode;
    mvr_material_id material;    /* 0 = the default material */
    /* Skinning (glTF JOINTS_n / WEIGHTS_n): per vertex four joints and four
     * weights per set; set 1 (optional) adds four more influences. A joint
     * is an index into the joints of the skin of the node that draws the
     * mesh (mvr_scene_set_node_skin); an index past that skin's joints is
     * refused when the node is given the skin. Weights must be finite and
     * >= 0; each vertex's are normalised to sum 1 on the way in (a vertex
     * whose weights are all 0 follows joint 0 of its first set, logged as a
     * repair). A mesh with joints drawn by a node without a skin draws its
     * bind pose placed by the node, as glTF asks. */
    const uint16_t *joints0;     /* 4 per vertex */
    const float *weights0;       /* 4 per vertex; with joints0 */
    const uint16_t *joints1;     /* 4 per vertex; only with joints0 */
    const float *weights1;
    /* Morph targets: target_count targets, each with deltas of the same
     * attributes in every target of the primitive (glTF 3.7.2.2). */
    const struct mvr_morph_target_desc *targets;
    uint32_t target_count;
} mvr_primitive_desc;

/* The deltas of one morph target, per vertex of its primitive; NULL = none
 * of that attribute. A target may only move attributes the primitive has
 * (normals and tangents deltas need the primitive's normals and tangents). */
typedef struct mvr_morph_target_desc {
    const float *positions;      /* 3 per vertex */
    const float *normals;        /* 3 per vertex */
    const float *tangents;       /* 3 per vertex: xyz only (w, the handedness, stays) */
} mvr_morph_target_desc;

typedef struct mvr_mesh_desc {
    const mvr_primitive_desc *primitives;
    uint32_t primitive_count;
    const char *name;
    /* Default morph weights (glTF mesh.weights), one per target; every
     * primitive of a mesh with targets has the same target count. NULL = 0. */
    const float *weights;
    uint32_t weight_count;
} mvr_mesh_desc;
mvr_result mvr_scene_add_mesh(mvr_scene *scene, const mvr_mesh_desc *desc, mvr_mesh_id *out);

typedef enum mvr_light_type {
    MVR_LIGHT_DIRECTIONAL = 0,
    MVR_LIGHT_POINT,
    MVR_LIGHT_SPOT
} mvr_light_type;

/* KHR_lights_punctual: the light shines along its node's -Z; intensity in lux
 * (directional) or candela (point, spot). */
typedef struct mvr_light_desc {
    mvr_light_type type;
    float color[3];              /* all zero = white */
    float intensity;
    float range;                 /* 0 = infinite */
    float inner_cone_angle;      /* spot, radians */
    float outer_cone_angle;      /* spot, radians; 0 = pi/4 */
    /* Shadows (directional and spot lights; point lights cast none): drawn
     * when the render's shadow mode is MVR_SHADOWS_DEFAULT and this is true,
     * or the mode is MVR_SHADOWS_ALL. glTF has no such flag: false. */
    bool cast_shadows;
    /* Render layers: the light shines in the views whose light_layers share
     * a bit with these (mvr_view_desc.light_layers). 0 = every layer. A
     * light in no enabled view takes no shadow layer. */
    uint32_t layers;
} mvr_light_desc;
mvr_result mvr_scene_add_light(mvr_scene *scene, const mvr_light_desc *desc, mvr_light_id *out);

typedef enum mvr_projection_type {
    MVR_PROJECTION_PERSPECTIVE = 0, /* symmetric: yfov + aspect */
    MVR_PROJECTION_FRUSTUM,         /* asymmetric: four angles, as OpenXR's XrFovf */
    MVR_PROJECTION_ORTHOGRAPHIC,
    MVR_PROJECTION_MATRIX           /* explicit, GL conventions (clip z in [-w, w]) */
} mvr_projection_type;

typedef struct mvr_projection {
    mvr_projection_type type;
    double yfov;                 /* perspective, radians; 0 = 60 degrees */
    double aspect;               /* perspective; 0 = the viewport's */
    double angle_left, angle_right, angle_down, angle_up; /* frustum, radians (left/down < 0) */
    double xmag, ymag;           /* orthographic half extents */
    double znear;                /* 0 = 0.05 */
    double zfar;                 /* 0 = infinite (perspective, frustum); orthographic: 0 = 1000 */
    double matrix[16];           /* explicit, column-major */
} mvr_projection;

mvr_result mvr_scene_add_camera(mvr_scene *scene, const mvr_projection *projection,
                                mvr_camera_id *out);

typedef struct mvr_node_desc {
    mvr_node_id parent;          /* 0 = a root */
    double translation[3];
    double rotation[4];          /* quaternion x, y, z, w; all zero = identity */
    double scale[3];             /* all zero = (1, 1, 1) */
    bool use_matrix;             /* take matrix instead of TRS */
    double matrix[16];           /* column-major */
    mvr_mesh_id mesh;
    mvr_light_id light;
    mvr_camera_id camera;
    const char *name;
} mvr_node_desc;
mvr_result mvr_scene_add_node(mvr_scene *scene, const mvr_node_desc *desc, mvr_node_id *out);
/* Moves a node (only transforms are re-sent to the GPU). */
mvr_result mvr_scene_set_node_transform(mvr_scene *scene, mvr_node_id node,
                                        const double translation[3], const double rotation[4],
                                        const double scale[3]);

/* ---- skins, morph weights, animations */

typedef struct mvr_skin_id { uint32_t id; } mvr_skin_id;

/* A glTF skin: joint nodes and the inverse bind matrix of each. Vertex v of
 * a mesh drawn by a node with this skin lands at
 *   sum_i w_i * world(joints[j_i]) * inverse_bind_matrices[j_i] * v
 * (the drawing node's own transform does not apply, as glTF asks), computed
 * per frame in double and narrowed to float relative to the view set's
 * origin. */
typedef struct mvr_skin_desc {
    const mvr_node_id *joints;   /* joint_count nodes, each at most once */
    uint32_t joint_count;        /* 1 .. 65536 */
    const double *inverse_bind_matrices; /* 16 per joint, column-major; NULL = identities */
    mvr_node_id skeleton;        /* optional: the skeleton's root (glTF skin.skeleton); informative */
    const char *name;
} mvr_skin_desc;
mvr_result mvr_scene_add_skin(mvr_scene *scene, const mvr_skin_desc *desc, mvr_skin_id *out);
/* Gives a node (that draws a mesh) a skin; {0} removes it. Refused when a
 * primitive of the node's mesh names a joint past the skin's joints. */
mvr_result mvr_scene_set_node_skin(mvr_scene *scene, mvr_node_id node, mvr_skin_id skin);
/* A node's morph weights (glTF node.weights), one per target of its mesh;
 * count 0 returns to the mesh's default weights. */
mvr_result mvr_scene_set_node_weights(mvr_scene *scene, mvr_node_id node, const float *weights, uint32_t count);

typedef enum mvr_animation_path {
    MVR_ANIMATION_PATH_TRANSLATION = 0, /* 3 values per key */
    MVR_ANIMATION_PATH_ROTATION,        /* 4 (quaternion x, y, z, w) */
    MVR_ANIMATION_PATH_SCALE,           /* 3 */
    MVR_ANIMATION_PATH_WEIGHTS          /* one per morph target of the node's mesh */
} mvr_animation_path;
const char *mvr_animation_path_name(mvr_animation_path path);

typedef enum mvr_interpolation {
    MVR_INTERPOLATION_LINEAR = 0,  /* slerp along the shorter arc for rotations */
    MVR_INTERPOLATION_STEP,
    MVR_INTERPOLATION_CUBICSPLINE  /* glTF 2.0 Appendix C; per key in-tangent, value, out-tangent */
} mvr_interpolation;

typedef struct mvr_animation_sampler_desc {
    const float *times;          /* key_count seconds, finite, strictly increasing */
    uint32_t key_count;          /* >= 1 */
    const float *values;         /* value_count floats: key_count * components (x3 for CUBICSPLINE) */
    uint32_t value_count;
    mvr_interpolation interpolation;
} mvr_animation_sampler_desc;

typedef struct mvr_animation_channel_desc {
    uint32_t sampler;            /* index into the animation's samplers */
    mvr_node_id node;
    mvr_animation_path path;
} mvr_animation_channel_desc;

typedef struct mvr_animation_desc {
    const mvr_animation_sampler_desc *samplers;
    uint32_t sampler_count;
    const mvr_animation_channel_desc *channels;
    uint32_t channel_count;
    const char *name;
} mvr_animation_desc;

/* Adds an animation (copied): every sampler's times and values are checked
 * against the channels that read it (component counts, weights against the
 * target count of the node's mesh). *out_index (optional) is its index. */
mvr_result mvr_scene_add_animation(mvr_scene *scene, const mvr_animation_desc *desc, uint32_t *out_index);
uint32_t mvr_scene_animation_count(const mvr_scene *scene);

typedef struct mvr_animation_info {
    const char *name;            /* "" when unnamed; owned by the scene */
    double start, end;           /* seconds: the earliest and latest key of its samplers */
    uint32_t channels, samplers;
} mvr_animation_info;
mvr_result mvr_scene_get_animation_info(const mvr_scene *scene, uint32_t index, mvr_animation_info *out);
/* The index of the first animation with this name; MVR_ERROR_INVALID_ARGUMENT
 * (naming the animations there are) when none has it. */
mvr_result mvr_scene_find_animation(const mvr_scene *scene, const char *name, uint32_t *out_index);

#define MVR_ANIMATION_ALL UINT32_MAX

typedef enum mvr_animation_wrap {
    MVR_ANIMATION_CLAMP = 0,     /* before start: the first keys; after end: the last */
    MVR_ANIMATION_LOOP           /* time wrapped into [start, end) of the animation */
} mvr_animation_wrap;

/* Poses the scene at `time` seconds of animation `index` (MVR_ANIMATION_ALL:
 * every animation, in order, each at that time): the channels' nodes take
 * the sampled translation / rotation / scale / weights. Nodes no channel
 * targets keep their pose. Cheap: no GPU work until the next render, which
 * re-sends joint matrices and weights, never geometry; applying the pose
 * the scene already has (a paused player) changes nothing and sends nothing. */
mvr_result mvr_scene_apply_animation(mvr_scene *scene, uint32_t index, double time, mvr_animation_wrap wrap);
/* Back to the rest pose: the transforms and weights that mvr_scene_add_node,
 * mvr_scene_set_node_transform and mvr_scene_set_node_weights last gave
 * (else the mesh's default weights); animations never change it. */
void mvr_scene_reset_pose(mvr_scene *scene);

/* ---- material variants (KHR_materials_variants)
 *
 * A variant is a named configuration of materials (a product's colours, a
 * night and a day look). Each primitive may map some variants to materials;
 * while a variant is selected, every primitive that maps it draws with the
 * material it maps to, and every other primitive with its own material (the
 * one its mvr_primitive_desc gave). Selecting MVR_VARIANT_DEFAULT, the
 * initial state, draws every primitive with its own material. Selecting is
 * cheap: no geometry is sent again; the next render rebuilds its draws (the
 * material block and texture arrays are re-sent too: a variant can bring
 * materials, textures and shader features no draw had). */

#define MVR_VARIANT_DEFAULT UINT32_MAX

/* Adds a variant (name copied; glTF allows two variants to share a name,
 * mvr_scene_find_variant then gives the first). *out_index (optional) is
 * its index: 0, 1, ... in the order they are added. */
mvr_result mvr_scene_add_variant(mvr_scene *scene, const char *name, uint32_t *out_index);
uint32_t mvr_scene_variant_count(const mvr_scene *scene);
/* Its name, owned by the scene; NULL past the end. */
const char *mvr_scene_variant_name(const mvr_scene *scene, uint32_t index);
/* The index of the first variant with this name; MVR_ERROR_INVALID_ARGUMENT
 * (naming the variants there are) when none has it. */
mvr_result mvr_scene_find_variant(const mvr_scene *scene, const char *name, uint32_t *out_index);

typedef struct mvr_variant_mapping {
    uint32_t variant;            /* a variant's index */
    mvr_material_id material;    /* drawn with it while that variant is selected; 0 = the default material */
} mvr_variant_mapping;

/* Gives primitive `primitive` (its index in the mesh's desc) of `mesh` its
 * mappings (copied), replacing those it had; count 0 removes them. Each
 * variant at most once per primitive. Applies at once if a variant is
 * selected. */
mvr_result mvr_scene_set_primitive_variants(mvr_scene *scene, mvr_mesh_id mesh, uint32_t primitive,
                                            const mvr_variant_mapping *mappings, uint32_t count);
/* Selects variant `index`, or MVR_VARIANT_DEFAULT. Selecting the variant
 * already selected (or one that changes no primitive's material) changes
 * nothing and makes no work for the renderer. */
mvr_result mvr_scene_select_variant(mvr_scene *scene, uint32_t index);
/* The selected variant's index, or MVR_VARIANT_DEFAULT. */
uint32_t mvr_scene_selected_variant(const mvr_scene *scene);

/* Ambient light: uniform radiance from every direction (linear RGB). */
void mvr_scene_set_ambient(mvr_scene *scene, const float rgb[3]);

typedef struct mvr_scene_info {
    uint32_t images, materials, meshes, primitives, nodes, lights, cameras;
    uint32_t skins, joints, animations, morph_targets; /* joints and targets summed over skins / primitives */
    double bounds_min[3], bounds_max[3]; /* world space, of every drawn primitive */
    /* the brightest light of each type (directional lux; point and spot
     * candela; color's largest channel times intensity) */
    float max_light_intensity[3];
} mvr_scene_info;
/* True when the lights are in physical units at a scale exposure 1 would
 * blow out (a directional light over 20 lux, or a point or spot light over
 * 100 candela: a tool's export of a real scene, as KHR_lights_punctual
 * asks), so an auto-exposed, tone-mapped render is the one to show. */
bool mvr_scene_lights_physical(const mvr_scene *scene);
void mvr_scene_get_info(const mvr_scene *scene, mvr_scene_info *out);
/* What the extra outputs' IDs (MVR_OUTPUT_IDS) name: ids run 1..count of
 * mvr_scene_info. Names are "" when unnamed (owned by the scene); NULL for
 * an id the scene does not have. */
const char *mvr_scene_node_name(const mvr_scene *scene, mvr_node_id node);
const char *mvr_scene_mesh_name(const mvr_scene *scene, mvr_mesh_id mesh);
const char *mvr_scene_material_name(const mvr_scene *scene, mvr_material_id material);
/* The mesh a node draws (0: none or no such node). */
mvr_mesh_id mvr_scene_node_mesh(const mvr_scene *scene, mvr_node_id node);

/* Nodes that carry a camera, in node order. */
uint32_t mvr_scene_camera_node_count(const mvr_scene *scene);
/* Degenerate values repaired on the way in, each logged as a warning: NaN,
 * infinite or zero-length normals and tangents, NaN UVs and colors, NaN,
 * denormal or out-of-range material factors, zero quaternions. (NaN or
 * infinite positions and transforms are refused.) */
uint32_t mvr_scene_sanitized_count(const mvr_scene *scene);
mvr_node_id mvr_scene_camera_node(const mvr_scene *scene, uint32_t index); /* {0} past the end */

/* The world pose of a camera node, with its camera's projection, as a view. */
struct mvr_view_desc;
mvr_result mvr_scene_camera_view(const mvr_scene *scene, mvr_node_id camera_node,
                                 struct mvr_view_desc *out_view);

#ifdef __cplusplus
}
#endif
#endif /* MVR_SCENE_API_H */
