/*
 * Materials (backend-free): the texture roles a material can sample, the
 * scene's validation of a material desc, and the std140 block the mesh
 * fragment stage reads (layout in block_layout.h, from which the generator
 * declares struct mvr_material; shaders/surface.glsl and material_*.glsl read it).
 */
#ifndef MVR_MATERIAL_H
#define MVR_MATERIAL_H

#include <stdbool.h>
#include <stdint.h>

#include "mvr/mvr.h"

/* The texture roles, in the order of the material block's layer and uv
 * fields. The first five are glTF 2.0's; each has its own feature bit. The
 * extensions' roles are sampled under their extension's feature bit, where
 * the material's block says it has a texture in the role (a uniform branch
 * per draw), so a material without one shares the program. */
typedef enum mvr_texture_role {
    MVR_ROLE_BASE_COLOR = 0,
    MVR_ROLE_METAL_ROUGH,
    MVR_ROLE_NORMAL,
    MVR_ROLE_OCCLUSION,
    MVR_ROLE_EMISSIVE,
    MVR_ROLE_CLEARCOAT,
    MVR_ROLE_CLEARCOAT_ROUGHNESS,
    MVR_ROLE_CLEARCOAT_NORMAL,
    MVR_ROLE_SHEEN_COLOR,
    MVR_ROLE_SHEEN_ROUGHNESS,
    MVR_ROLE_SPECULAR,
    MVR_ROLE_SPECULAR_COLOR,
    MVR_ROLE_TRANSMISSION,
    MVR_ROLE_THICKNESS,
    MVR_ROLE_IRIDESCENCE,
    MVR_ROLE_IRIDESCENCE_THICKNESS,
    MVR_ROLE_ANISOTROPY,
    MVR_ROLE_SPEC_GLOSS,
    MVR_ROLE_COUNT
} mvr_texture_role;

#define MVR_CORE_ROLE_COUNT 5u
/* Distinct KHR_texture_transforms one material can hold (the block's slots). */
#define MVR_MATERIAL_TRANSFORM_SLOTS 8u

/* The texture ref of a role of a material. */
const mvr_texture_ref *mvr_material_role(const mvr_material_desc *m, uint32_t role);
/* "base color", "clearcoat normal", ... */
const char *mvr_role_name(uint32_t role);
/* The sampler uniform of the role (shaders/surface.glsl and material_*.glsl). */
const char *mvr_role_sampler(uint32_t role);
/* Whether a role is stored sRGB-encoded (glTF 2.0 3.9.2 and the extensions:
 * base color, emissive, sheen color, specular color, spec-gloss). */
bool mvr_role_is_srgb(uint32_t role);
/* The feature bit under which a role is sampled: a core role's own, an
 * extension role's extension's. */
uint32_t mvr_role_feature(uint32_t role);

/* The extension feature bits a material needs (SPECULAR, CLEARCOAT, SHEEN,
 * ...): where it departs from glTF 2.0's core model. */
uint32_t mvr_material_extension_features(const mvr_material_desc *m);

/* Whether a material samples a role: it has a texture there and, for an
 * extension's role, needs the extension. */
bool mvr_material_samples_role(const mvr_material_desc *m, uint32_t role);

/* Whether two texture refs fetch the same texels: same image, texture
 * coordinates, sampler and transform. */
bool mvr_texture_refs_fetch_alike(const mvr_texture_ref *a, const mvr_texture_ref *b);

/* Whether a material's occlusion is the red channel of its
 * metallic-roughness texture, fetched alike (glTF 2.0 3.9.3 and 3.9.5 put
 * metalness in B, roughness in G and occlusion in R so that one texture can
 * hold all three; the loader packs separate ones, mvr_scene_pack_occlusion):
 * then the occlusion role is not sampled on its own, and the fragment stage
 * takes the red channel of the metallic-roughness fetch, a texture fetch
 * less per fragment. */
bool mvr_material_occlusion_in_metal_rough(const mvr_material_desc *m);
/* The bit of the material block's uv.w (above the roles' has-a-texture
 * bits) that says so; shaders/mesh.frag.glsl reads it. */
#define MVR_MATERIAL_OCCLUSION_IN_METAL_ROUGH_BIT 30u

/* A dielectric's F0 at normal incidence from its index of refraction. */
float mvr_material_ior_f0(float ior);

/* Packs a material into its std140 block (MVR_MATERIAL_BLOCK_SIZE bytes);
 * layers: the array layer of each role (the batch plan's), NULL where each
 * role has its own 2D texture. */
void mvr_material_pack(const mvr_material_desc *material, const uint16_t *layers, uint8_t *out);

#endif
