/* gl: the std140 uniform block layouts the C side packs (the one table of
 * core/block_layout.c, mvr_block_layouts, from which the shaders' block
 * declarations are also generated) are the layouts the GL gives the blocks the
 * shaders declare. For every shader variant of the validation set (and a few
 * more: padded instanced draw blocks, a small material page), each block the
 * program has is found in the table, and each of its members is asked of the
 * GL (glGetUniformIndices, glGetActiveUniformsiv: offset, array stride,
 * matrix stride, type, array size; glGetActiveUniformBlockiv: data size and
 * active member count) and compared with the table. Elements 0, 1 and the
 * last of a block's struct array are checked, so the struct's stride is too.
 *
 * How it was checked that a mismatch fails (each change then restored):
 * - C side, MVR_MATERIAL_EMISSIVE_OFFSET 16u -> 20u (then in core/frame.h): every
 *   mesh variant fails ("mvr_materials: mvr_material_table[0].emissive offset
 *   16, table 20"), and the_table_is_std140 too;
 * - C side, MVR_DRAW_INFO_OFFSET (the former "+ 128") 128u -> 112u: "mvr_draw:
 *   mvr_draws[0].info offset 128, table 112";
 * - C side, MVR_VIEWS_PER_BLOCK 64u -> 32u: mvr_views data size 6144 against
 *   3072, member offsets and array sizes, in mesh and background variants;
 * - GLSL side (when the shaders declared the blocks by hand; now they are
 *   generated from the table), vec4 emissive and vec4 params swapped in
 *   struct mvr_material of shaders/mesh.frag.glsl: 1214 failed checks per context ("emissive
 *   offset 32, table 16");
 * - GLSL side, a vec4 added to struct mvr_light: data size and active
 *   member count ("mvr_lights has 20 active members, the table 16") and the
 *   offsets of element 1. */
#include "gl_test_util.h"
#include "frame.h"
#include "program.h"
#include "shader_gen.h"

typedef struct block_queries {
    PFNGLGETUNIFORMINDICESPROC GetUniformIndices;
    PFNGLGETACTIVEUNIFORMSIVPROC GetActiveUniformsiv;
    PFNGLGETACTIVEUNIFORMBLOCKNAMEPROC GetActiveUniformBlockName;
} block_queries;

/* The entry points the library's table does not load, through the provider. */
static bool load_queries(mvr_context *ctx, block_queries *q)
{
    if (!ctx->ops || !ctx->ops->get_proc)
        return false;
    void *p[3] = {ctx->ops->get_proc("glGetUniformIndices", ctx->provider),
                  ctx->ops->get_proc("glGetActiveUniformsiv", ctx->provider),
                  ctx->ops->get_proc("glGetActiveUniformBlockName", ctx->provider)};
    if (!p[0] || !p[1] || !p[2])
        return false;
    memcpy(&q->GetUniformIndices, &p[0], sizeof p[0]);
    memcpy(&q->GetActiveUniformsiv, &p[1], sizeof p[1]);
    memcpy(&q->GetActiveUniformBlockName, &p[2], sizeof p[2]);
    return true;
}

/* Whether a variant's program declares the block (the shaders' #ifs). */
static bool declares(const mvr_shader_variant *v, const char *block)
{
    bool mesh = v->program == MVR_PROGRAM_MESH;
    if (strcmp(block, "mvr_views") == 0)
        return mesh || v->program == MVR_PROGRAM_BACKGROUND;
    if (strcmp(block, "mvr_draw") == 0 || strcmp(block, "mvr_materials") == 0)
        return mesh;
    if (strcmp(block, "mvr_lights") == 0)
        return mesh && v->directional_lights + v->point_lights + v->spot_lights > 0;
    if (strcmp(block, "mvr_shadows") == 0)
        return mesh && (v->features & MVR_FEATURE_SHADOWS);
    return false;
}

/* Elements of a block's struct array in this variant, and their stride
 * (the shader pads the draw struct to the variant's draw stride). */
static uint32_t element_count(const mvr_shader_variant *v, const mvr_block_layout *b, uint32_t *stride)
{
    *stride = b->size;
    if (strcmp(b->block, "mvr_draw") == 0) {
        if (v->draw_stride > b->size)
            *stride = v->draw_stride;
        return v->draw_capacity ? v->draw_capacity : 1u;
    }
    if (strcmp(b->block, "mvr_materials") == 0)
        return v->material_capacity ? v->material_capacity : MVR_SHADER_DEFAULT_MATERIAL_CAPACITY;
    if (strcmp(b->block, "mvr_lights") == 0)
        return (uint32_t)v->directional_lights + v->point_lights + v->spot_lights;
    return 1;
}

static GLenum gl_type(mvr_std140_type t)
{
    switch (t) {
    case MVR_STD140_VEC4:
        return GL_FLOAT_VEC4;
    case MVR_STD140_IVEC4:
        return GL_INT_VEC4;
    case MVR_STD140_UVEC4:
        return GL_UNSIGNED_INT_VEC4;
    case MVR_STD140_MAT4:
        return GL_FLOAT_MAT4;
    }
    return GL_NONE;
}

/* Compares one block of one linked program with its table entry. */
static void check_block(mvr_test_state *t, mvr_context *ctx, const block_queries *q, GLuint program,
                        const char *variant, const mvr_shader_variant *v, const mvr_block_layout *b,
                        GLuint block_index)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    uint32_t stride = 0, count = element_count(v, b, &stride);
    GLint data_size = 0, active = 0;
    gl->GetActiveUniformBlockiv(program, block_index, GL_UNIFORM_BLOCK_DATA_SIZE, &data_size);
    gl->GetActiveUniformBlockiv(program, block_index, GL_UNIFORM_BLOCK_ACTIVE_UNIFORMS, &active);
    uint32_t want_size = b->element ? count * stride : b->size;
    CHECK_MSG(t, (uint32_t)data_size == want_size, "%s: %s data size %d, table %u", variant, b->block, data_size,
              want_size);
    /* every member of the block is in the table (the draw struct's padding aside) */
    uint32_t padding = b->element && stride > b->size ? 1u : 0u;
    uint32_t want_active = b->element ? count * (b->member_count + padding) : b->member_count;
    CHECK_MSG(t, (uint32_t)active == want_active, "%s: %s has %d active members, the table %u", variant, b->block,
              active, want_active);

    uint32_t elements[3] = {0, 1, count - 1};
    uint32_t element_checks = b->element ? (count > 2 ? 3u : count) : 1u;
    for (uint32_t e = 0; e < element_checks; ++e) {
        for (uint32_t m = 0; m < b->member_count; ++m) {
            const mvr_block_member *mb = &b->members[m];
            char name[160];
            const char *suffix = mb->array_size > 1 ? "[0]" : "";
            if (b->element)
                snprintf(name, sizeof name, "%s[%u].%s%s", b->element, elements[e], mb->name, suffix);
            else
                snprintf(name, sizeof name, "%s%s", mb->name, suffix);
            const GLchar *names[1] = {name};
            GLuint index = GL_INVALID_INDEX;
            q->GetUniformIndices(program, 1, names, &index);
            if (index == GL_INVALID_INDEX) {
                CHECK_MSG(t, 0, "%s: %s: the GL has no %s", variant, b->block, name);
                continue;
            }
            enum { OFFSET, ARRAY_STRIDE, MATRIX_STRIDE, TYPE, SIZE, BLOCK, ROW_MAJOR, QUERIES };
            static const GLenum pnames[QUERIES] = {GL_UNIFORM_OFFSET,      GL_UNIFORM_ARRAY_STRIDE,
                                                   GL_UNIFORM_MATRIX_STRIDE, GL_UNIFORM_TYPE,
                                                   GL_UNIFORM_SIZE,        GL_UNIFORM_BLOCK_INDEX,
                                                   GL_UNIFORM_IS_ROW_MAJOR};
            GLint got[QUERIES];
            for (int k = 0; k < QUERIES; ++k)
                q->GetActiveUniformsiv(program, 1, &index, pnames[k], &got[k]);
            uint32_t offset = (b->element ? elements[e] * stride : 0u) + mb->offset;
            CHECK_MSG(t, (uint32_t)got[OFFSET] == offset, "%s: %s: %s offset %d, table %u", variant, b->block, name,
                      got[OFFSET], offset);
            CHECK_MSG(t, (uint32_t)got[ARRAY_STRIDE] == mb->array_stride, "%s: %s: %s array stride %d, table %u",
                      variant, b->block, name, got[ARRAY_STRIDE], mb->array_stride);
            CHECK_MSG(t, (uint32_t)got[MATRIX_STRIDE] == mb->matrix_stride, "%s: %s: %s matrix stride %d, table %u",
                      variant, b->block, name, got[MATRIX_STRIDE], mb->matrix_stride);
            CHECK_MSG(t, (GLenum)got[TYPE] == gl_type(mb->type), "%s: %s: %s type 0x%x, table 0x%x", variant,
                      b->block, name, (unsigned)got[TYPE], (unsigned)gl_type(mb->type));
            CHECK_MSG(t, (uint32_t)got[SIZE] == mb->array_size, "%s: %s: %s array size %d, table %u", variant,
                      b->block, name, got[SIZE], mb->array_size);
            CHECK_MSG(t, (GLuint)got[BLOCK] == block_index, "%s: %s: %s is in block %d", variant, b->block, name,
                      got[BLOCK]);
            CHECK(t, got[ROW_MAJOR] == 0);
        }
    }
}

typedef struct layout_counts {
    unsigned variants, skipped;
    unsigned blocks[8]; /* per table entry: variants that had it */
} layout_counts;

static void check_variant(mvr_test_state *t, mvr_context *ctx, const block_queries *q, const mvr_shader_variant *v,
                          layout_counts *counts)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    char variant[96];
    mvr_shader_variant_name(v, variant, sizeof variant);
    GLuint program = 0;
    mvr_result res = mvr_gl_program_build(ctx, v, &program);
    CHECK_MSG(t, res == MVR_OK, "%s: %s", variant, mvr_context_last_error(ctx));
    if (res != MVR_OK)
        return;
    counts->variants++;
    uint32_t layout_count = 0;
    const mvr_block_layout *layouts = mvr_block_layouts(&layout_count);
    /* every block the program has is in the table */
    GLint blocks = 0;
    gl->GetProgramiv(program, GL_ACTIVE_UNIFORM_BLOCKS, &blocks);
    for (GLint i = 0; i < blocks; ++i) {
        char name[64] = "";
        q->GetActiveUniformBlockName(program, (GLuint)i, (GLsizei)sizeof name, NULL, name);
        bool known = false;
        for (uint32_t k = 0; k < layout_count; ++k)
            known = known || strcmp(layouts[k].block, name) == 0;
        CHECK_MSG(t, known, "%s: block %s is not in the layout table", variant, name);
    }
    for (uint32_t k = 0; k < layout_count; ++k) {
        const mvr_block_layout *b = &layouts[k];
        GLuint index = gl->GetUniformBlockIndex(program, b->block);
        bool want = declares(v, b->block);
        CHECK_MSG(t, (index != GL_INVALID_INDEX) == want, "%s: block %s %s", variant, b->block,
                  want ? "missing" : "unexpected");
        if (index == GL_INVALID_INDEX)
            continue;
        check_block(t, ctx, q, program, variant, v, b, index);
        if (k < MVR_ARRAY_COUNT(counts->blocks))
            counts->blocks[k]++;
    }
    gl->DeleteProgram(program);
    CHECK_EQ_INT(t, (int)gl->GetError(), GL_NO_ERROR);
}

static void check_all(mvr_test_state *t, mvr_context *ctx)
{
    block_queries q;
    if (!load_queries(ctx, &q)) {
        CHECK_MSG(t, 0, "glGetUniformIndices / glGetActiveUniformsiv did not load");
        return;
    }
    const mvr_caps *c = mvr_context_caps(ctx);
    uint32_t max_views = c->ext.ovr_multiview2 ? (uint32_t)c->limits.max_views_ovr : 0;
    layout_counts counts = {0};
    mvr_shader_variant v;
    for (unsigned i = 0; mvr_shader_variant_enumerate(i, max_views ? max_views : 1, &v); ++i) {
        if (v.num_views > max_views) {
            counts.skipped++; /* multiview variant on a GL without it */
            continue;
        }
        check_variant(t, ctx, &q, &v, &counts);
    }
    /* what the renderer builds beyond the validation set: instanced draw
     * blocks padded to a 256-byte uniform offset alignment, a material page
     * of a small GL_MAX_UNIFORM_BLOCK_SIZE, shadows with one light */
    const mvr_shader_variant extra[] = {
        {.program = MVR_PROGRAM_MESH, .directional_lights = 1, .draw_capacity = 8, .draw_stride = 256},
        {.program = MVR_PROGRAM_MESH, .point_lights = 3, .draw_capacity = 2, .draw_stride = 160,
         .material_capacity = 5},
        {.program = MVR_PROGRAM_MESH, .features = MVR_FEATURE_SHADOWS | MVR_FEATURE_LIGHT_MASKS, .spot_lights = 1,
         .material_capacity = 1},
    };
    for (size_t i = 0; i < MVR_ARRAY_COUNT(extra); ++i)
        check_variant(t, ctx, &q, &extra[i], &counts);

    uint32_t layout_count = 0;
    const mvr_block_layout *layouts = mvr_block_layouts(&layout_count);
    printf("  %s: %u variants, %u multiview variants not applicable; blocks checked:", c->version, counts.variants,
           counts.skipped);
    for (uint32_t k = 0; k < layout_count; ++k) {
        printf(" %s x%u", layouts[k].block, counts.blocks[k]);
        CHECK_MSG(t, counts.blocks[k] > 0, "no variant declares %s", layouts[k].block);
    }
    printf("\n");
    CHECK(t, counts.variants > 20);
}

static void layouts_on_gles(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_GLES, NULL);
    if (ctx)
        check_all(t, ctx);
    mvr_context_destroy(ctx);
}

static void layouts_on_osmesa_desktop(mvr_test_state *t)
{
    if (!mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA))
        SKIP(t, "this build has no OSMesa provider");
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_OSMESA, MVR_GL_API_DEFAULT, NULL);
    if (ctx)
        check_all(t, ctx);
    mvr_context_destroy(ctx);
}

/* The table itself: std140 rules (16-byte aligned vec4 / ivec4 / mat4
 * members, ascending and not overlapping, the size covering the last one). */
static void the_table_is_std140(mvr_test_state *t)
{
    uint32_t count = 0;
    const mvr_block_layout *layouts = mvr_block_layouts(&count);
    CHECK_EQ_INT(t, (int)count, 5);
    for (uint32_t k = 0; k < count; ++k) {
        const mvr_block_layout *b = &layouts[k];
        uint32_t end = 0;
        for (uint32_t m = 0; m < b->member_count; ++m) {
            const mvr_block_member *mb = &b->members[m];
            uint32_t extent = mb->array_size > 1 ? mb->array_size * mb->array_stride : mb->size;
            CHECK_MSG(t, mb->offset % 16 == 0 && mb->offset >= end, "%s.%s at %u", b->block, mb->name, mb->offset);
            CHECK_MSG(t, mb->array_size <= 1 || mb->array_stride >= mb->size, "%s.%s", b->block, mb->name);
            end = mb->offset + extent;
        }
        CHECK_MSG(t, b->size % 16 == 0 && b->size >= end, "%s: size %u, members end at %u", b->block, b->size, end);
    }
}

MVR_TEST_MAIN(TEST(the_table_is_std140), TEST(layouts_on_gles), TEST(layouts_on_osmesa_desktop))
