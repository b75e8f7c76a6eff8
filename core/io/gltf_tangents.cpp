// gltf_tangents.cpp: tangent frames for normal-mapped primitives that come
// without TANGENT. glTF 2.0 (3.7.2.1) says a client SHOULD compute them with
// MikkTSpace from the positions, normals and the normal texture's UVs; the
// Khronos glTF Sample Renderer does (per vertex, before drawing). Without
// them mvr's shader builds a frame per pixel from screen-space derivatives,
// constant over each triangle, whose tangent jumps at every edge: normal-
// mapped creases then shade differently (see docs/peers.md).
#include <cstring>

#include "gltf_convert.hpp"
#include "gltf_internal.hpp"

extern "C" {
#include "tangents.h"
}

namespace mvr_gltf {

void converter::generated_tangents(const tinygltf::Primitive &p, const std::string &pw, prim_data &d)
{
    if (!d.tan.empty() || d.nrm.empty() || d.mode != MVR_PRIMITIVE_TRIANGLES || p.material < 0 ||
        size_t(p.material) >= m.materials.size())
        return;
    const tinygltf::NormalTextureInfo &nt = m.materials[size_t(p.material)].normalTexture;
    if (nt.index < 0 || nt.texCoord < 0 || nt.texCoord > 1)
        return;
    const std::vector<float> &uv = nt.texCoord == 0 ? d.uv0 : d.uv1;
    size_t vcount = d.pos.size() / 3;
    if (uv.size() != vcount * 2)
        return;
    cx.mem.charge(vcount * 4 * sizeof(float), pw + " (tangents generated for its normal map)");
    cx.mesh_bytes += vcount * 4 * sizeof(float);
    std::vector<float> tan(vcount * 4);
    if (!mvr_mesh_tangents(d.pos.data(), d.nrm.data(), uv.data(), uint32_t(vcount), d.idx.data(), d.idx.size(),
                           tan.data())) {
        cx.warn(pw + ": no memory to generate tangents; the normal map uses screen-space derivatives");
        return;
    }
    d.tan = std::move(tan);
}

}  // namespace mvr_gltf
