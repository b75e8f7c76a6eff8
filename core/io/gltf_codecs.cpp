// Compressed geometry, decoded at load inside the memory budget:
// EXT_meshopt_compression (bufferViews; meshoptimizer's decoders and
// filters) and KHR_draco_mesh_compression (primitives; Draco's mesh
// decoder). What either decodes is read by the ordinary accessor code
// (gltf_accessors.cpp), so it gets every check a plain accessor gets; what
// is checked here is the extensions' own JSON, their sizes against the
// accessors and buffers, and the decoded indices.
#include <algorithm>
#include <cstring>

#include <meshoptimizer.h>

#include "gltf_draco.h"
#include "gltf_internal.hpp"

namespace mvr_gltf {

std::string key_name(const std::string &key)
{
    bool plain = !key.empty() && key.size() <= 64;
    for (char c : key)
        plain = plain && ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_');
    return plain ? key : quote(key);
}

// ---------------------------------------------------------------- meshopt

const unsigned char *meshopt_view_bytes(context &cx, int view_index, const std::string &what)
{
    auto done = cx.decoded_views.find(view_index);
    if (done != cx.decoded_views.end())
        return done->second->bytes.data();
    const tinygltf::BufferView &v = cx.model->bufferViews[size_t(view_index)];
    const meshopt_source &e = cx.res.meshopt_views.at(view_index);
    const std::string name = "bufferViews[" + std::to_string(view_index) + "].extensions.EXT_meshopt_compression";
    const std::string by = " (read by " + what + ")";
    auto fail = [&](const std::string &why) { refuse(name + ": " + why + by); };
    if (!e.problem.empty())
        fail(e.problem);
    // the extension's rules (EXT_meshopt_compression, "JSON schema updates")
    const uint64_t stride = uint64_t(e.byte_stride), count = uint64_t(e.count);
    const std::string mode = e.mode, filter = e.filter;
    if (mode != "ATTRIBUTES" && mode != "TRIANGLES" && mode != "INDICES")
        fail("mode " + quote(mode) + " is not ATTRIBUTES, TRIANGLES or INDICES");
    if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
        fail("filter " + quote(filter) + " is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    if (mode == "ATTRIBUTES" && (stride % 4 != 0 || stride > 256))
        fail("byteStride " + std::to_string(stride) + " of mode ATTRIBUTES is not a multiple of 4 up to 256");
    if (mode != "ATTRIBUTES" && stride != 2 && stride != 4)
        fail("byteStride " + std::to_string(stride) + " of mode " + mode + " is not 2 or 4");
    if (mode == "TRIANGLES" && count % 3 != 0)
        fail("count " + std::to_string(count) + " of mode TRIANGLES is not a multiple of 3");
    if (mode != "ATTRIBUTES" && filter != "NONE")
        fail("filter " + filter + " with mode " + mode + " (filters are for ATTRIBUTES)");
    if (filter == "OCTAHEDRAL" && stride != 4 && stride != 8)
        fail("byteStride " + std::to_string(stride) + " with filter OCTAHEDRAL is not 4 or 8");
    if (filter == "QUATERNION" && stride != 8)
        fail("byteStride " + std::to_string(stride) + " with filter QUATERNION is not 8");
    if (filter == "EXPONENTIAL" && stride % 4 != 0)
        fail("byteStride " + std::to_string(stride) + " with filter EXPONENTIAL is not a multiple of 4");
    if (v.byteStride != 0 && uint64_t(v.byteStride) != stride)
        fail("byteStride " + std::to_string(stride) + " differs from the bufferView's " + std::to_string(v.byteStride));
    uint64_t size = mul_checked(count, stride, name);
    if (size != uint64_t(v.byteLength))
        fail("count " + std::to_string(count) + " x byteStride " + std::to_string(stride) + " = " +
             std::to_string(size) + " bytes, the bufferView's byteLength is " + std::to_string(v.byteLength));
    // the compressed bytes: inside their buffer, which is not a fallback
    if (size_t(e.buffer) >= cx.res.buffers.size())
        fail("buffer " + std::to_string(e.buffer) + " does not exist (" + std::to_string(cx.res.buffers.size()) +
             " buffers)");
    const buffer_source &src = cx.res.buffers[size_t(e.buffer)];
    if (src.meshopt_fallback)
        fail("buffer " + std::to_string(e.buffer) + " is a fallback buffer (extensions.EXT_meshopt_compression."
             "fallback), which compressed data may not come from");
    uint64_t end = add_checked(uint64_t(e.byte_offset), uint64_t(e.byte_length), name);
    if (end > src.byte_length)
        fail("bytes " + std::to_string(e.byte_offset) + ".." + std::to_string(end) + " run past the end of buffer " +
             std::to_string(e.buffer) + " (" + std::to_string(src.byte_length) + " bytes)");
    byte_span data = cx.buffer(int(e.buffer), name);
    const unsigned char *in = data.data + e.byte_offset;
    const size_t in_size = size_t(e.byte_length);
    // decoded: charged before it is allocated
    auto out = std::make_unique<decoded_bytes>(cx.mem, size, name + " (" + std::to_string(size) + " decoded bytes)");
    int rc = 0;
    if (mode == "ATTRIBUTES")
        rc = meshopt_decodeVertexBuffer(out->bytes.data(), size_t(count), size_t(stride), in, in_size);
    else if (mode == "TRIANGLES")
        rc = meshopt_decodeIndexBuffer(out->bytes.data(), size_t(count), size_t(stride), in, in_size);
    else
        rc = meshopt_decodeIndexSequence(out->bytes.data(), size_t(count), size_t(stride), in, in_size);
    if (rc != 0)
        fail("the " + std::to_string(e.byte_length) + " compressed bytes do not decode as " + mode + " (" +
             std::to_string(count) + " x " + std::to_string(stride) + " bytes; meshoptimizer says " +
             (rc == -1 ? "unsupported version" : "malformed or truncated") + ")");
    if (filter == "OCTAHEDRAL")
        meshopt_decodeFilterOct(out->bytes.data(), size_t(count), size_t(stride));
    else if (filter == "QUATERNION")
        meshopt_decodeFilterQuat(out->bytes.data(), size_t(count), size_t(stride));
    else if (filter == "EXPONENTIAL")
        meshopt_decodeFilterExp(out->bytes.data(), size_t(count), size_t(stride));
    cx.debug(name + ": " + std::to_string(e.byte_length) + " bytes decoded into " + std::to_string(size) + " (" +
             mode + ", filter " + filter + ")");
    const unsigned char *bytes = out->bytes.data();
    cx.decoded_views[view_index] = std::move(out);
    return bytes;
}

// ---------------------------------------------------------------- Draco

// What Draco's decoder may allocate in all, as a multiple of the decoded
// mesh's estimate (plus 16 MiB). Measured on draco_transcoder's output:
// 1.8 x for tests/data/codecs/draco.glb (4 attributes), 1.65 x for the
// spheres of tests/data/peers.
constexpr uint64_t draco_allocation_factor = 16;


draco_scope::draco_scope(context &c, int mesh_index, int prim, const tinygltf::Primitive &p, const std::string &pw)
    : cx(c)
{
    try {
        decode(mesh_index, prim, p, pw);
    } catch (...) {
        cx.decoded_accessors.clear();   // the destructor does not run for a constructor that throws
        throw;
    }
}

void draco_scope::decode(int mesh_index, int prim, const tinygltf::Primitive &p, const std::string &pw)
{
    auto found = cx.res.draco_primitives.find({mesh_index, prim});
    if (found == cx.res.draco_primitives.end())
        return;
    const draco_source &src = found->second;
    const auto &m = *cx.model;
    const std::string name = pw + ".extensions.KHR_draco_mesh_compression";
    if (!src.problem.empty())
        refuse(name + ": " + src.problem);
    // KHR_draco_mesh_compression, "Restrictions on geometry type": TRIANGLES or TRIANGLE_STRIP
    if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP)
        throw load_error(MVR_ERROR_UNSUPPORTED, name + ": mode 5 (TRIANGLE_STRIP) with Draco is not supported");
    if (p.mode != TINYGLTF_MODE_TRIANGLES)
        refuse(name + ": mode " + std::to_string(p.mode) + " (the extension allows TRIANGLES or TRIANGLE_STRIP)");
    if (p.indices < 0)
        refuse(name + ": the primitive has no indices accessor for the decoded triangles");
    auto accessor = [&](int index, const std::string &use) -> const tinygltf::Accessor & {
        if (index < 0 || size_t(index) >= m.accessors.size())
            refuse(use + ": accessor " + std::to_string(index) + " does not exist (" +
                   std::to_string(m.accessors.size()) + " accessors)");
        return m.accessors[size_t(index)];
    };
    // what the decoded mesh must hold, from the accessors: every attribute
    // the extension names is one of the primitive's, all of one count
    struct wanted {
        std::string aw;       // e.g. meshes[0].primitives[0].attributes.NORMAL
        int accessor;
        uint32_t id;          // Draco unique id
        int comps;
        uint32_t cs;
    };
    std::vector<wanted> attrs;
    uint64_t points = 0, bytes_per_point = 0;
    for (const auto &a : src.attributes) {
        std::string aw = name + ".attributes." + key_name(a.first);
        auto it = p.attributes.find(a.first);
        if (it == p.attributes.end())
            refuse(aw + " is not among the primitive's attributes");
        std::string pa = pw + ".attributes." + key_name(a.first);
        const tinygltf::Accessor &acc = accessor(it->second, pa);
        int comps = type_components(acc.type);
        uint32_t cs = component_size(acc.componentType);
        if (comps == 0 || cs == 0)
            refuse(pa + ": accessor " + std::to_string(it->second) + " has type " + std::to_string(acc.type) +
                   " / componentType " + std::to_string(acc.componentType));
        if (points != 0 && uint64_t(acc.count) != points)
            refuse(pa + ": accessor " + std::to_string(it->second) + " has count " + std::to_string(acc.count) +
                   ", the primitive's other Draco attributes " + std::to_string(points));
        if (acc.count == 0)
            refuse(pa + ": accessor " + std::to_string(it->second) + " has count 0");
        points = uint64_t(acc.count);
        bytes_per_point += uint64_t(comps) * 4 + 8;   // Draco keeps values as (at most) 4-byte components
        attrs.push_back({pa, it->second, uint32_t(a.second), comps, cs});
    }
    if (attrs.empty())
        refuse(name + ": attributes names none of the primitive's attributes");
    const tinygltf::Accessor &ia = accessor(p.indices, pw + ".indices");
    const uint64_t corners = uint64_t(ia.count);
    if (points > cx.limits.max_vertices)
        refuse(name + ": " + std::to_string(points) + " points exceed the cap of " +
               std::to_string(cx.limits.max_vertices) + " (mvr_gltf_options.max_vertices)");
    if (corners > cx.limits.max_indices)
        refuse(name + ": " + std::to_string(corners) + " indices exceed the cap of " +
               std::to_string(cx.limits.max_indices) + " (mvr_gltf_options.max_indices)");
    // the decoded mesh (values, point mappings, faces and the decoder's corner
    // table), estimated from the accessors and charged while it lives; a mesh
    // that decodes to other counts is refused below
    uint64_t estimate = add_checked(mul_checked(points, bytes_per_point, name), mul_checked(corners, 16, name), name);
    charged mesh_charge(cx.mem, estimate, name + " (the decoded Draco mesh)");

    uint64_t blob_size = 0, blob_stride = 0;
    const unsigned char *blob = view_bytes(cx, int(src.buffer_view), &blob_size, &blob_stride, name);
    // Draco allocates as the data says; what it may allocate in all (frees
    // not credited) is what a mesh of the accessors' counts plausibly needs
    // (draco_allocation_factor x the estimate + 16 MiB), and
    // never more than the budget has left. A lying count fails fast here
    // instead of filling a 256 MiB bit vector for seconds.
    const uint64_t headroom = cx.mem.limit > cx.mem.used ? cx.mem.limit - cx.mem.used : 0;
    const uint64_t plausible = add_checked(mul_checked(estimate, draco_allocation_factor, name), 16u << 20, name);
    const uint64_t allowance = std::min(headroom, plausible);
    char said[160];
    mvr_draco_mesh *decoded = nullptr;
    uint64_t allocated = 0;
    mvr_draco_status st = mvr_draco_decode(blob, size_t(blob_size), allowance, &decoded, &allocated, said, sizeof said);
    std::unique_ptr<mvr_draco_mesh, void (*)(mvr_draco_mesh *)> mesh(decoded, mvr_draco_free);
    const std::string view = "bufferView " + std::to_string(src.buffer_view);
    if (st == MVR_DRACO_OUT_OF_MEMORY && allowance == headroom)
        cx.mem.charge(headroom + 1, name + " (decoding " + view + ")");   // refuses, naming the budget
    if (st == MVR_DRACO_OUT_OF_MEMORY)
        refuse(name + ": decoding the " + std::to_string(blob_size) + " bytes of " + view + " took more than " +
               std::to_string(allowance >> 20) + " MiB, past what a mesh of the accessors' " + std::to_string(points) +
               " points and " + std::to_string(corners) + " indices needs (" +
               std::to_string(draco_allocation_factor) + " x its estimate + 16 MiB): the data describes another mesh");
    {
        charged transient(cx.mem, allocated, name + " (the decoder's allocations)");   // in the peak
    }
    cx.debug(name + ": the decoder allocated " + std::to_string(allocated) + " bytes (the estimate: " +
             std::to_string(estimate) + ")");
    if (st == MVR_DRACO_NOT_DRACO)
        refuse(name + ": " + view + " is not Draco data (" + quote(said) + ")");
    if (st == MVR_DRACO_NOT_A_MESH)
        refuse(name + ": " + view + " holds a Draco point cloud, not a mesh");
    if (st != MVR_DRACO_OK || !mesh)
        refuse(name + ": the " + std::to_string(blob_size) + " bytes of " + view + " do not decode (Draco says " +
               quote(said) + ")");
    const uint64_t decoded_points = mvr_draco_points(mesh.get()), faces = mvr_draco_faces(mesh.get());
    if (decoded_points != points)
        refuse(name + ": the decoded mesh has " + std::to_string(decoded_points) + " points, the accessors " +
               std::to_string(points));
    if (faces * 3 != corners)
        refuse(pw + ".indices: accessor " + std::to_string(p.indices) + " has count " + std::to_string(corners) +
               ", the decoded mesh has " + std::to_string(faces) + " triangles (" + std::to_string(faces * 3) +
               " indices)");

    // attributes, in each accessor's own layout (the accessor reader applies
    // componentType and normalized as for plain data)
    for (const wanted &w : attrs) {
        const std::string id = "Draco attribute id " + std::to_string(w.id);
        int comps = mvr_draco_attribute_components(mesh.get(), w.id);
        if (comps == 0)
            refuse(w.aw + ": " + id + " (" + name + ") is not in the decoded mesh");
        if (comps != w.comps)
            refuse(w.aw + ": " + id + " has " + std::to_string(comps) + " components; accessor " +
                   std::to_string(w.accessor) + " has " + std::to_string(w.comps));
        const tinygltf::Accessor &acc = m.accessors[size_t(w.accessor)];
        uint64_t n = points * uint64_t(w.comps) * w.cs;
        auto out = std::make_unique<decoded_bytes>(cx.mem, n, w.aw + " (decoded)");
        uint32_t bad = 0;
        mvr_draco_status vs =
            mvr_draco_attribute_values(mesh.get(), w.id, acc.componentType, w.comps, out->bytes.data(), &bad);
        if (vs == MVR_DRACO_NO_VALUE)
            refuse(w.aw + ": " + id + " has no value for decoded point " + std::to_string(bad));
        if (vs == MVR_DRACO_DOES_NOT_FIT)
            refuse(w.aw + ": " + id + "'s value for decoded point " + std::to_string(bad) +
                   " does not fit accessor " + std::to_string(w.accessor) + "'s componentType " +
                   std::to_string(acc.componentType));
        if (vs != MVR_DRACO_OK)
            refuse(w.aw + ": " + id + " has fewer values than it says");
        cx.decoded_accessors[w.accessor] = std::move(out);
    }

    // indices: each inside the decoded points and the accessor's componentType
    int it = ia.componentType;
    uint32_t cs = component_size(it);
    if (ia.type != TINYGLTF_TYPE_SCALAR || (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                            it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                            it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        refuse(pw + ".indices: accessor " + std::to_string(p.indices) + " is not SCALAR of an unsigned integer type");
    uint64_t limit = it == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xFFu
                     : it == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu
                                                                    : 0xFFFFFFFFu;
    auto out = std::make_unique<decoded_bytes>(cx.mem, corners * cs, pw + ".indices (decoded)");
    unsigned char *o = out->bytes.data();
    for (uint64_t f = 0; f < faces; ++f) {
        uint32_t face[3];
        mvr_draco_face(mesh.get(), uint32_t(f), face);
        for (int k = 0; k < 3; ++k) {
            uint64_t v = face[k];
            uint64_t at = f * 3 + uint64_t(k);
            if (v >= points)
                refuse(pw + ".indices: decoded index " + std::to_string(at) + " = " + std::to_string(v) +
                       " is past the " + std::to_string(points) + " decoded points (" + name + ")");
            if (v > limit)
                refuse(pw + ".indices: decoded index " + std::to_string(at) + " = " + std::to_string(v) +
                       " does not fit accessor " + std::to_string(p.indices) + "'s componentType " +
                       std::to_string(it));
            if (cs == 1) {
                o[at] = uint8_t(v);
            } else if (cs == 2) {
                uint16_t s = uint16_t(v);
                std::memcpy(o + at * 2, &s, 2);
            } else {
                uint32_t s = uint32_t(v);
                std::memcpy(o + at * 4, &s, 4);
            }
        }
    }
    cx.decoded_accessors[p.indices] = std::move(out);
    cx.debug(name + ": " + std::to_string(blob_size) + " bytes decoded into " + std::to_string(points) +
             " points and " + std::to_string(faces) + " triangles");
}

}  // namespace mvr_gltf
