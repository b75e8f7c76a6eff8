#include <string.h>

#include "block_layout.h"
#include "shader_files.h"
#include "shader_gen.h"

/* Views per uniform block; a larger view set binds the block per chunk. */
#define MVR_SHADER_MAX_VIEWS 64
_Static_assert(MVR_SHADER_MAX_VIEWS == MVR_VIEWS_PER_BLOCK, "the shaders' view arrays are the view block's");

/* A line of a shaders/ file that the named block's declaration replaces. */
#define BLOCK_DIRECTIVE "#mvr_block "

typedef struct feature_define {
    uint32_t bit;
    const char *name;
} feature_define;

static const feature_define mesh_defines[] = {
    {MVR_FEATURE_NORMALS, "MVR_NORMALS"},
    {MVR_FEATURE_TANGENTS, "MVR_TANGENTS"},
    {MVR_FEATURE_UV0, "MVR_UV0"},
    {MVR_FEATURE_UV1, "MVR_UV1"},
    {MVR_FEATURE_COLOR0, "MVR_COLOR0"},
    {MVR_FEATURE_BASE_COLOR_TEX, "MVR_BASE_COLOR_TEX"},
    {MVR_FEATURE_METAL_ROUGH_TEX, "MVR_METAL_ROUGH_TEX"},
    {MVR_FEATURE_NORMAL_TEX, "MVR_NORMAL_TEX"},
    {MVR_FEATURE_OCCLUSION_TEX, "MVR_OCCLUSION_TEX"},
    {MVR_FEATURE_EMISSIVE_TEX, "MVR_EMISSIVE_TEX"},
    {MVR_FEATURE_TEXTURE_TRANSFORM, "MVR_TEXTURE_TRANSFORM"},
    {MVR_FEATURE_ALPHA_MASK, "MVR_ALPHA_MASK"},
    {MVR_FEATURE_ALPHA_BLEND, "MVR_ALPHA_BLEND"},
    {MVR_FEATURE_DOUBLE_SIDED, "MVR_DOUBLE_SIDED"},
    {MVR_FEATURE_UNLIT, "MVR_UNLIT"},
    {MVR_FEATURE_MATERIAL_ARRAYS, "MVR_MATERIAL_ARRAYS"},
    {MVR_FEATURE_SRGB_OUTPUT, "MVR_SRGB_OUTPUT"},
    {MVR_FEATURE_SHADOWS, "MVR_SHADOWS"},
    {MVR_FEATURE_LIGHT_MASKS, "MVR_LIGHT_MASKS"},
    {MVR_FEATURE_SHADOW_CASTER, "MVR_SHADOW_CASTER"},
    {MVR_FEATURE_IBL, "MVR_IBL"},
    {MVR_FEATURE_IBL_REFERENCE, "MVR_IBL_REFERENCE"},
    {MVR_FEATURE_SKIN, "MVR_SKIN"},
    {MVR_FEATURE_SKIN8, "MVR_SKIN8"},
    {MVR_FEATURE_MORPH, "MVR_MORPH"},
    {MVR_FEATURE_SPECULAR, "MVR_SPECULAR"},
    {MVR_FEATURE_CLEARCOAT, "MVR_CLEARCOAT"},
    {MVR_FEATURE_SPEC_GLOSS, "MVR_SPEC_GLOSS"},
    {MVR_FEATURE_TRANSMISSION, "MVR_TRANSMISSION"},
    {MVR_FEATURE_IRIDESCENCE, "MVR_IRIDESCENCE"},
    {MVR_FEATURE_ANISOTROPY, "MVR_ANISOTROPY"},
    {MVR_FEATURE_SHEEN, "MVR_SHEEN"},
};

/* the mesh bits the pre-skinning program shares (MVR_PRESKIN_FEATURES) */
static const feature_define preskin_defines[] = {
    {MVR_FEATURE_NORMALS, "MVR_NORMALS"},
    {MVR_FEATURE_TANGENTS, "MVR_TANGENTS"},
    {MVR_FEATURE_SKIN, "MVR_SKIN"},
    {MVR_FEATURE_SKIN8, "MVR_SKIN8"},
    {MVR_FEATURE_MORPH, "MVR_MORPH"},
};

static const feature_define composite_defines[] = {
    {MVR_FEATURE_SRGB_ENCODE, "MVR_SRGB_ENCODE"},
    {MVR_FEATURE_DOWNSAMPLE, "MVR_DOWNSAMPLE"},
    {MVR_FEATURE_POST, "MVR_POST"},
    {MVR_FEATURE_POST_ACES, "MVR_TONEMAP_ACES"},
    {MVR_FEATURE_POST_PBR_NEUTRAL, "MVR_TONEMAP_PBR_NEUTRAL"},
    {MVR_FEATURE_DITHER, "MVR_DITHER"},
    {MVR_FEATURE_LOG_LUMINANCE, "MVR_LOG_LUMINANCE"},
    {MVR_FEATURE_POST_MSAA, "MVR_POST_MSAA"},
};

static const feature_define environment_defines[] = {
    {MVR_FEATURE_ENV_GGX, "MVR_ENV_GGX"},
    {MVR_FEATURE_ENV_CHARLIE, "MVR_ENV_CHARLIE"},
};

static const feature_define background_defines[] = {
    {MVR_FEATURE_BACKGROUND_SRGB_OUTPUT, "MVR_SRGB_OUTPUT"},
};

typedef struct program_files {
    const char *shared[2];   /* prepended to both stages, in order (NULL = none) */
    const char *vertex_shared; /* prepended to the vertex stage only */
    const char *fragment_shared[13]; /* prepended to the fragment stage only, in order (NULL = none) */
    const char *stage[MVR_SHADER_STAGE_COUNT];
} program_files;

static const feature_define *program_defines(mvr_program_kind program, size_t *count)
{
    switch (program) {
    case MVR_PROGRAM_MESH:
        *count = MVR_ARRAY_COUNT(mesh_defines);
        return mesh_defines;
    case MVR_PROGRAM_COMPOSITE:
        *count = MVR_ARRAY_COUNT(composite_defines);
        return composite_defines;
    case MVR_PROGRAM_ENVIRONMENT:
        *count = MVR_ARRAY_COUNT(environment_defines);
        return environment_defines;
    case MVR_PROGRAM_BACKGROUND:
        *count = MVR_ARRAY_COUNT(background_defines);
        return background_defines;
    case MVR_PROGRAM_PRESKIN:
        *count = MVR_ARRAY_COUNT(preskin_defines);
        return preskin_defines;
    case MVR_PROGRAM_KIND_COUNT:
        break;
    }
    *count = 0;
    return NULL;
}

static bool program_files_of(mvr_program_kind program, program_files *out)
{
    memset(out, 0, sizeof *out);
    out->shared[0] = "common.glsl";
    switch (program) {
    case MVR_PROGRAM_MESH:
        out->shared[1] = "views.glsl";
        out->vertex_shared = "deform.glsl";
        /* each file uses only what the ones before it declare */
        static const char *const mesh_fragment[] = {
            "output.glsl", "environment.glsl", "surface.glsl", "lights.glsl", "shadows.glsl", "brdf.glsl",
            "material_anisotropy.glsl", "material_specular.glsl", "material_iridescence.glsl",
            "material_clearcoat.glsl", "ibl.glsl", "material_transmission.glsl", "material_sheen.glsl",
        };
        _Static_assert(sizeof mesh_fragment == sizeof out->fragment_shared, "fragment_shared holds the mesh's files");
        memcpy(out->fragment_shared, mesh_fragment, sizeof mesh_fragment);
        out->stage[MVR_SHADER_STAGE_VERTEX] = "mesh.vert.glsl";
        out->stage[MVR_SHADER_STAGE_FRAGMENT] = "mesh.frag.glsl";
        return true;
    case MVR_PROGRAM_COMPOSITE:
        out->stage[MVR_SHADER_STAGE_VERTEX] = "composite.vert.glsl";
        out->stage[MVR_SHADER_STAGE_FRAGMENT] = "composite.frag.glsl";
        return true;
    case MVR_PROGRAM_ENVIRONMENT:
        out->fragment_shared[0] = "environment.glsl";
        out->stage[MVR_SHADER_STAGE_VERTEX] = "env_faces.vert.glsl";
        out->stage[MVR_SHADER_STAGE_FRAGMENT] = "env_prefilter.frag.glsl";
        return true;
    case MVR_PROGRAM_BACKGROUND:
        out->shared[1] = "views.glsl";
        out->fragment_shared[0] = "output.glsl";
        out->stage[MVR_SHADER_STAGE_VERTEX] = "background.vert.glsl";
        out->stage[MVR_SHADER_STAGE_FRAGMENT] = "background.frag.glsl";
        return true;
    case MVR_PROGRAM_PRESKIN:
        out->vertex_shared = "deform.glsl";
        out->stage[MVR_SHADER_STAGE_VERTEX] = "preskin.vert.glsl";
        out->stage[MVR_SHADER_STAGE_FRAGMENT] = "preskin.frag.glsl";
        return true;
    case MVR_PROGRAM_KIND_COUNT:
        break;
    }
    return false;
}

const mvr_shader_file *mvr_shader_file_find(const char *name)
{
    for (unsigned i = 0; i < mvr_shader_file_count; ++i)
        if (strcmp(mvr_shader_files[i].name, name) == 0)
            return &mvr_shader_files[i];
    return NULL;
}

const char *mvr_program_kind_name(mvr_program_kind kind)
{
    switch (kind) {
    case MVR_PROGRAM_MESH: return "mesh";
    case MVR_PROGRAM_COMPOSITE: return "composite";
    case MVR_PROGRAM_ENVIRONMENT: return "environment";
    case MVR_PROGRAM_BACKGROUND: return "background";
    case MVR_PROGRAM_PRESKIN: return "preskin";
    case MVR_PROGRAM_KIND_COUNT: break;
    }
    return NULL;
}

const char *mvr_shader_stage_name(mvr_shader_stage stage)
{
    switch (stage) {
    case MVR_SHADER_STAGE_VERTEX: return "vert";
    case MVR_SHADER_STAGE_FRAGMENT: return "frag";
    case MVR_SHADER_STAGE_COUNT: break;
    }
    return NULL;
}

const char *mvr_shader_feature_define(mvr_program_kind program, uint32_t bit)
{
    size_t count;
    const feature_define *defs = program_defines(program, &count);
    for (size_t i = 0; i < count; ++i)
        if (defs[i].bit == bit)
            return defs[i].name;
    return NULL;
}

uint32_t mvr_shader_feature_mask(mvr_program_kind program)
{
    size_t count;
    const feature_define *defs = program_defines(program, &count);
    uint32_t mask = 0;
    for (size_t i = 0; i < count; ++i)
        mask |= defs[i].bit;
    return mask;
}

bool mvr_shader_variant_valid(const mvr_shader_variant *v, char *why, size_t why_size)
{
    if (!v) {
        mvr_str_copy(why, why_size, "variant is NULL");
        return false;
    }
    if (!mvr_program_kind_name(v->program)) {
        mvr_str_format(why, why_size, "unknown program kind %d", (int)v->program);
        return false;
    }
    uint32_t unknown = v->features & ~mvr_shader_feature_mask(v->program);
    if (unknown) {
        mvr_str_format(why, why_size, "feature bits 0x%x are not features of the %s program",
                       (unsigned)unknown, mvr_program_kind_name(v->program));
        return false;
    }
    if (v->num_views > MVR_SHADER_MAX_VIEWS) {
        mvr_str_format(why, why_size, "num_views %u exceeds the view block size %d",
                       (unsigned)v->num_views, MVR_SHADER_MAX_VIEWS);
        return false;
    }
    if (v->directional_lights > MVR_SHADER_MAX_LIGHTS_PER_TYPE ||
        v->point_lights > MVR_SHADER_MAX_LIGHTS_PER_TYPE ||
        v->spot_lights > MVR_SHADER_MAX_LIGHTS_PER_TYPE) {
        mvr_str_format(why, why_size, "more than %d lights of one type",
                       MVR_SHADER_MAX_LIGHTS_PER_TYPE);
        return false;
    }
    if (v->program != MVR_PROGRAM_MESH &&
        (v->directional_lights || v->point_lights || v->spot_lights)) {
        mvr_str_format(why, why_size, "the %s program takes no lights",
                       mvr_program_kind_name(v->program));
        return false;
    }
    if ((v->features & MVR_FEATURE_ALPHA_MASK) && (v->features & MVR_FEATURE_ALPHA_BLEND) &&
        v->program == MVR_PROGRAM_MESH) {
        mvr_str_copy(why, why_size, "alpha mask and alpha blend exclude each other");
        return false;
    }
    if ((v->features & MVR_FEATURE_POST_ACES) && (v->features & MVR_FEATURE_POST_PBR_NEUTRAL) &&
        v->program == MVR_PROGRAM_COMPOSITE) {
        mvr_str_copy(why, why_size, "two tone mapping operators exclude each other");
        return false;
    }
    if (v->material_capacity > MVR_SHADER_MAX_MATERIAL_CAPACITY ||
        (v->material_capacity && v->program != MVR_PROGRAM_MESH)) {
        mvr_str_format(why, why_size, "material capacity %u invalid (mesh only, at most %d)",
                       (unsigned)v->material_capacity, MVR_SHADER_MAX_MATERIAL_CAPACITY);
        return false;
    }
    if (v->draw_stride && (v->draw_stride < 144 || v->draw_stride % 16 || v->draw_stride > 4096 ||
                           v->program != MVR_PROGRAM_MESH)) {
        mvr_str_format(why, why_size, "draw stride %u invalid (mesh only, a multiple of 16 from 144 to 4096)",
                       (unsigned)v->draw_stride);
        return false;
    }
    if ((v->outputs & ~MVR_SHADER_OUT_ALL_) || (v->outputs && v->program != MVR_PROGRAM_MESH) ||
        ((v->outputs & MVR_SHADER_OUT_NORMAL_CAMERA) && !(v->outputs & MVR_SHADER_OUT_NORMAL)) ||
        (v->outputs == MVR_SHADER_OUT_ONLY)) {
        mvr_str_format(why, why_size, "outputs 0x%x invalid (mesh only; camera space needs normals; "
                       "an outputs-only variant needs an output)", (unsigned)v->outputs);
        return false;
    }
    if (v->draw_capacity > MVR_SHADER_MAX_DRAW_CAPACITY || (v->draw_capacity && v->program != MVR_PROGRAM_MESH)) {
        mvr_str_format(why, why_size, "draw capacity %u invalid (mesh only, at most %d)",
                       (unsigned)v->draw_capacity, MVR_SHADER_MAX_DRAW_CAPACITY);
        return false;
    }
    return true;
}

static const char *std140_glsl_type(mvr_std140_type type)
{
    switch (type) {
    case MVR_STD140_VEC4: return "vec4";
    case MVR_STD140_IVEC4: return "ivec4";
    case MVR_STD140_UVEC4: return "uvec4";
    case MVR_STD140_MAT4: return "mat4";
    }
    return "?";
}

static void append_members(mvr_str_builder *out, const mvr_block_layout *b)
{
    for (uint32_t i = 0; i < b->member_count; ++i) {
        const mvr_block_member *m = &b->members[i];
        if (m->array_size > 1)
            mvr_sb_appendf(out, "    %s %s[%u];\n", std140_glsl_type(m->type), m->name, (unsigned)m->array_size);
        else
            mvr_sb_appendf(out, "    %s %s;\n", std140_glsl_type(m->type), m->name);
    }
}

/* The GLSL declaration of a uniform block of the std140 table
 * (block_layout.h): its struct and the block holding an array of it, or the
 * block's own members. */
static bool append_block(mvr_str_builder *out, const char *name, char *why, size_t why_size)
{
    const mvr_block_layout *b = mvr_block_layout_find(name);
    if (!b) {
        mvr_str_format(why, why_size, "uniform block %s is not in the std140 layout table", name);
        return false;
    }
    if (!b->element) {
        mvr_sb_appendf(out, "layout(std140) uniform %s {\n", b->block);
        append_members(out, b);
        mvr_sb_append(out, "};\n");
        return true;
    }
    mvr_sb_appendf(out, "struct %s {\n", b->struct_name);
    append_members(out, b);
    if (b->padding)
        mvr_sb_appendf(out, "#if %s > 0\n    vec4 pad[%s];\n#endif\n", b->padding, b->padding);
    mvr_sb_append(out, "};\n");
    mvr_sb_appendf(out, "layout(std140) uniform %s {\n    %s %s[%s];\n};\n", b->block, b->struct_name, b->element,
                   b->element_count);
    return true;
}

/* Appends an embedded file, its "#mvr_block NAME" lines replaced by the
 * blocks' declarations (then #line keeps the file's own line numbers). */
static bool append_file(mvr_str_builder *out, const char *name, char *why, size_t why_size)
{
    const mvr_shader_file *f = mvr_shader_file_find(name);
    if (!f) {
        mvr_str_format(why, why_size, "shader file %s was not embedded", name);
        return false;
    }
    mvr_sb_appendf(out, "#line 1 // %s\n", name);
    unsigned line = 1;
    for (const char *p = f->text; *p; ++line) {
        const char *end = strchr(p, '\n');
        size_t length = end ? (size_t)(end - p) : strlen(p);
        const size_t prefix = sizeof BLOCK_DIRECTIVE - 1;
        if (length > prefix && strncmp(p, BLOCK_DIRECTIVE, prefix) == 0) {
            char block[64];
            mvr_str_format(block, sizeof block, "%.*s", (int)(length - prefix), p + prefix);
            if (!append_block(out, block, why, why_size))
                return false;
            mvr_sb_appendf(out, "#line %u\n", line + 1);
        } else {
            mvr_sb_appendf(out, "%.*s\n", (int)length, p);
        }
        p += end ? length + 1 : length;
    }
    return true;
}

bool mvr_shader_source(const mvr_shader_variant *v, mvr_shader_stage stage, mvr_str_builder *out,
                       char *why, size_t why_size)
{
    program_files files;
    if (!mvr_shader_variant_valid(v, why, why_size))
        return false;
    if (!mvr_shader_stage_name(stage) || !program_files_of(v->program, &files)) {
        mvr_str_format(why, why_size, "unknown shader stage %d", (int)stage);
        return false;
    }

    /* multisampled arrays are sampled from GLSL ES 3.20 on */
    bool es32 = v->program == MVR_PROGRAM_COMPOSITE && (v->features & MVR_FEATURE_POST_MSAA);
    mvr_sb_append(out, es32 ? "#version 320 es\n" : "#version 300 es\n");
    if (v->num_views > 0) {
        /* OVR_multiview2 lets gl_ViewID_OVR reach more than gl_Position. */
        mvr_sb_append(out, "#extension GL_OVR_multiview2 : require\n");
        if (stage == MVR_SHADER_STAGE_VERTEX)
            mvr_sb_appendf(out, "layout(num_views = %u) in;\n", (unsigned)v->num_views);
        mvr_sb_appendf(out, "#define MVR_MULTIVIEW 1\n#define MVR_NUM_VIEWS %u\n",
                       (unsigned)v->num_views);
    } else {
        mvr_sb_append(out, "#define MVR_NUM_VIEWS 1\n");
    }
    mvr_sb_appendf(out, "#define MVR_MAX_VIEWS %d\n", MVR_SHADER_MAX_VIEWS);
    if (stage == MVR_SHADER_STAGE_VERTEX)
        mvr_sb_append(out, "#define MVR_VERTEX_STAGE 1\n");
    if (v->program == MVR_PROGRAM_MESH) {
        mvr_sb_appendf(out, "#define MVR_MAX_MATERIALS %u\n",
                       v->material_capacity ? (unsigned)v->material_capacity
                                            : (unsigned)MVR_SHADER_DEFAULT_MATERIAL_CAPACITY);
        mvr_sb_appendf(out, "#define MVR_DRAW_CAPACITY %u\n", v->draw_capacity ? (unsigned)v->draw_capacity : 1u);
        /* vec4s of padding after the 144-byte block: its std140 array stride
         * then equals the ring's block stride */
        mvr_sb_appendf(out, "#define MVR_DRAW_PAD %u\n", v->draw_stride > 144 ? (v->draw_stride - 144u) / 16u : 0u);
        mvr_sb_appendf(out, "#define MVR_MAX_SHADOW_LAYERS %u\n#define MVR_MAX_LIGHTS %u\n",
                       (unsigned)MVR_SHADER_MAX_SHADOW_LAYERS, 3u * MVR_SHADER_MAX_LIGHTS_PER_TYPE);
        mvr_sb_appendf(out,
                       "#define MVR_DIRECTIONAL_LIGHTS %u\n#define MVR_POINT_LIGHTS %u\n"
                       "#define MVR_SPOT_LIGHTS %u\n",
                       v->directional_lights, v->point_lights, v->spot_lights);
        static const feature_define outputs[] = {
            {MVR_SHADER_OUT_GEOMETRY, "MVR_OUT_GEOMETRY"},
            {MVR_SHADER_OUT_NORMAL, "MVR_OUT_NORMAL"},
            {MVR_SHADER_OUT_IDS, "MVR_OUT_IDS"},
            {MVR_SHADER_OUT_NORMAL_CAMERA, "MVR_OUT_NORMAL_CAMERA"},
            {MVR_SHADER_OUT_ONLY, "MVR_OUT_ONLY"},
        };
        for (size_t i = 0; i < MVR_ARRAY_COUNT(outputs); ++i)
            if (v->outputs & outputs[i].bit)
                mvr_sb_appendf(out, "#define %s 1\n", outputs[i].name);
        if (v->outputs & (MVR_SHADER_OUT_GEOMETRY | MVR_SHADER_OUT_NORMAL | MVR_SHADER_OUT_IDS))
            mvr_sb_append(out, "#define MVR_OUTPUTS 1\n");
    }
    size_t count;
    const feature_define *defs = program_defines(v->program, &count);
    for (size_t i = 0; i < count; ++i)
        if (v->features & defs[i].bit)
            mvr_sb_appendf(out, "#define %s 1\n", defs[i].name);

    for (size_t i = 0; i < MVR_ARRAY_COUNT(files.shared); ++i)
        if (files.shared[i] && !append_file(out, files.shared[i], why, why_size))
            return false;
    if (stage == MVR_SHADER_STAGE_VERTEX && files.vertex_shared &&
        !append_file(out, files.vertex_shared, why, why_size))
        return false;
    for (size_t i = 0; stage == MVR_SHADER_STAGE_FRAGMENT && i < MVR_ARRAY_COUNT(files.fragment_shared); ++i)
        if (files.fragment_shared[i] && !append_file(out, files.fragment_shared[i], why, why_size))
            return false;
    if (!append_file(out, files.stage[stage], why, why_size))
        return false;
    if (out->failed) {
        mvr_str_copy(why, why_size, "out of memory while generating shader source");
        return false;
    }
    return true;
}

void mvr_shader_variant_name(const mvr_shader_variant *v, char *out, size_t size)
{
    const char *program = mvr_program_kind_name(v->program);
    char views[16], materials[16] = "", draws[16] = "", stride[16] = "", outputs[16] = "";
    if (v->num_views > 0)
        mvr_str_format(views, sizeof views, "mv%u", (unsigned)v->num_views);
    else
        mvr_str_copy(views, sizeof views, "loop");
    if (v->material_capacity)
        mvr_str_format(materials, sizeof materials, "-m%u", (unsigned)v->material_capacity);
    if (v->draw_capacity > 1)
        mvr_str_format(draws, sizeof draws, "-i%u", (unsigned)v->draw_capacity);
    if (v->draw_stride > 144)
        mvr_str_format(stride, sizeof stride, "-s%u", (unsigned)v->draw_stride);
    if (v->outputs)
        mvr_str_format(outputs, sizeof outputs, "-o%x", (unsigned)v->outputs);
    mvr_str_format(out, size, "%s-%s-f%05x-l%u.%u.%u%s%s%s%s", program ? program : "invalid", views,
                   (unsigned)v->features, v->directional_lights, v->point_lights, v->spot_lights,
                   materials, draws, stride, outputs);
}

/* All bits of a program except those that exclude each other. */
static uint32_t all_compatible_features(mvr_program_kind program)
{
    uint32_t mask = mvr_shader_feature_mask(program);
    if (program == MVR_PROGRAM_MESH)
        mask &= ~(uint32_t)(MVR_FEATURE_ALPHA_BLEND | MVR_FEATURE_SHADOW_CASTER);
    else if (program == MVR_PROGRAM_COMPOSITE)
        mask &= ~(uint32_t)MVR_FEATURE_POST_PBR_NEUTRAL;
    return mask;
}

bool mvr_shader_variant_enumerate(unsigned index, uint32_t max_views, mvr_shader_variant *out)
{
    /* view counts: loop, multiview 1, 2 and max_views (deduplicated) */
    uint32_t views[4] = {0, 1, 2, max_views};
    unsigned view_count = (max_views > 2) ? 4u : 3u;
    for (int p = 0; p < MVR_PROGRAM_KIND_COUNT; ++p) {
        mvr_program_kind program = (mvr_program_kind)p;
        size_t define_count;
        const feature_define *defs = program_defines(program, &define_count);
        /* feature sets: none, each alone, and (where a program has more than
         * one feature) all compatible ones together, plus (mesh) all with blend
         * instead of mask */
        bool exclusive = program == MVR_PROGRAM_MESH || program == MVR_PROGRAM_COMPOSITE;
        unsigned feature_sets = 1u + (unsigned)define_count + (define_count > 1 ? 1u : 0u) + (exclusive ? 1u : 0u);
        unsigned light_sets = program == MVR_PROGRAM_MESH ? 2u : 1u;
        unsigned per_program = feature_sets * view_count * light_sets;
        if (index >= per_program) {
            index -= per_program;
            continue;
        }
        memset(out, 0, sizeof *out);
        out->program = program;
        unsigned fs = index % feature_sets;
        unsigned rest = index / feature_sets;
        out->num_views = views[rest % view_count];
        unsigned ls = rest / view_count;
        if (fs == 0)
            out->features = 0;
        else if (fs <= define_count)
            out->features = defs[fs - 1].bit;
        else if (fs == define_count + 1)
            out->features = all_compatible_features(program);
        else
            /* the exclusive alternatives: blend instead of mask (mesh),
             * neutral instead of ACES (composite) */
            out->features = program == MVR_PROGRAM_MESH
                                ? (all_compatible_features(program) & ~(uint32_t)MVR_FEATURE_ALPHA_MASK) |
                                      MVR_FEATURE_ALPHA_BLEND
                                : (all_compatible_features(program) & ~(uint32_t)MVR_FEATURE_POST_ACES) |
                                      MVR_FEATURE_POST_PBR_NEUTRAL;
        if (ls == 1) {
            out->directional_lights = 1;
            out->point_lights = 2;
            out->spot_lights = 1;
            /* the lit mesh variants also read instanced draw blocks */
            out->draw_capacity = MVR_SHADER_MAX_DRAW_CAPACITY;
            /* and write every extra output: all features with them, the
             * blended set as the outputs-only pass draws it */
            if (program == MVR_PROGRAM_MESH && fs == define_count + 1)
                out->outputs = MVR_SHADER_OUT_GEOMETRY | MVR_SHADER_OUT_NORMAL | MVR_SHADER_OUT_IDS |
                               MVR_SHADER_OUT_NORMAL_CAMERA;
            else if (program == MVR_PROGRAM_MESH && fs == define_count + 2)
                out->outputs = MVR_SHADER_OUT_GEOMETRY | MVR_SHADER_OUT_NORMAL | MVR_SHADER_OUT_IDS |
                               MVR_SHADER_OUT_ONLY;
        }
        return true;
    }
    return false;
}
