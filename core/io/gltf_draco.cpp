// Draco's decoder behind gltf_draco.h (see there for why it is apart).
#include "gltf_draco.h"

#include <cstdio>
#include <cstring>
#include <memory>
#include <new>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

struct mvr_draco_mesh {
    std::unique_ptr<draco::Mesh> mesh;
};

namespace {

// The running decode's allocations on this thread (see mvr_draco_decode).
struct allocation_count {
    bool active = false;
    uint64_t used = 0, limit = 0;
};
thread_local allocation_count counted;

void *counted_new(std::size_t n, bool array)
{
    if (counted.active) {
        if (n > counted.limit - counted.used)
            throw std::bad_alloc();
        counted.used += n;
    }
    // the nothrow forms: their symbols are not among the renamed ones; the
    // array form for new[] (what frees it is delete[])
    void *p = array ? ::operator new[](n, std::nothrow) : ::operator new(n, std::nothrow);
    if (!p)
        throw std::bad_alloc();
    return p;
}

void say(char *message, size_t size, const std::string &what)
{
    if (message && size)
        std::snprintf(message, size, "%s", what.c_str());
}

template <typename T>
mvr_draco_status convert(const draco::PointAttribute &att, uint32_t points, int comps, void *out, uint32_t *bad)
{
    T tmp[16];
    unsigned char *o = static_cast<unsigned char *>(out);
    for (uint32_t i = 0; i < points; ++i) {
        draco::AttributeValueIndex avi = att.mapped_index(draco::PointIndex(i));
        if (avi.value() >= att.size()) {
            *bad = i;
            return MVR_DRACO_NO_VALUE;
        }
        if (!att.ConvertValue<T>(avi, int8_t(comps), tmp)) {
            *bad = i;
            return MVR_DRACO_DOES_NOT_FIT;
        }
        std::memcpy(o + size_t(i) * size_t(comps) * sizeof(T), tmp, size_t(comps) * sizeof(T));
    }
    return MVR_DRACO_OK;
}

}  // namespace

// What this object's operator new calls became (their definitions here are
// not renamed: only undefined references are).
extern "C" void *mvr_draco_new(std::size_t n)
{
    return counted_new(n, false);
}

extern "C" void *mvr_draco_new_array(std::size_t n)
{
    return counted_new(n, true);
}

extern "C" mvr_draco_status mvr_draco_decode(const void *data, size_t size, uint64_t allocation_limit,
                                             mvr_draco_mesh **out, uint64_t *allocated, char *message,
                                             size_t message_size)
{
    *out = nullptr;
    struct counting {
        uint64_t *allocated;
        explicit counting(uint64_t limit, uint64_t *a) : allocated(a)
        {
            counted.active = true;
            counted.used = 0;
            counted.limit = limit;
        }
        ~counting()
        {
            *allocated = counted.used;
            counted.active = false;
        }
    } count(allocation_limit, allocated);
    try {
        draco::DecoderBuffer buffer;
        buffer.Init(static_cast<const char *>(data), size);
        auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
        if (!type.ok()) {
            say(message, message_size, type.status().error_msg_string());
            return MVR_DRACO_NOT_DRACO;
        }
        if (type.value() != draco::TRIANGULAR_MESH) {
            say(message, message_size, "a point cloud");
            return MVR_DRACO_NOT_A_MESH;
        }
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok() || !decoded.value()) {
            say(message, message_size, decoded.ok() ? std::string("no mesh") : decoded.status().error_msg_string());
            return MVR_DRACO_UNDECODABLE;
        }
        auto *m = new mvr_draco_mesh;
        m->mesh = std::move(decoded).value();
        *out = m;
        return MVR_DRACO_OK;
    } catch (const std::bad_alloc &) {
        say(message, message_size, "out of memory");
        return MVR_DRACO_OUT_OF_MEMORY;
    } catch (...) {
        say(message, message_size, "an exception");
        return MVR_DRACO_UNDECODABLE;
    }
}

extern "C" void mvr_draco_free(mvr_draco_mesh *mesh)
{
    delete mesh;
}

extern "C" uint32_t mvr_draco_points(const mvr_draco_mesh *m)
{
    return m->mesh->num_points();
}

extern "C" uint32_t mvr_draco_faces(const mvr_draco_mesh *m)
{
    return m->mesh->num_faces();
}

extern "C" void mvr_draco_face(const mvr_draco_mesh *m, uint32_t face, uint32_t out[3])
{
    const draco::Mesh::Face &f = m->mesh->face(draco::FaceIndex(face));
    for (int k = 0; k < 3; ++k)
        out[k] = f[size_t(k)].value();
}

extern "C" int mvr_draco_attribute_components(const mvr_draco_mesh *m, uint32_t id)
{
    const draco::PointAttribute *att = m->mesh->GetAttributeByUniqueId(id);
    return att ? int(att->num_components()) : 0;
}

extern "C" mvr_draco_status mvr_draco_attribute_values(const mvr_draco_mesh *m, uint32_t id, int component_type,
                                                       int comps, void *out, uint32_t *bad)
{
    const draco::PointAttribute *att = m->mesh->GetAttributeByUniqueId(id);
    const uint32_t points = m->mesh->num_points();
    if (!att || comps < 1 || comps > 16)
        return MVR_DRACO_NO_VALUE;
    // the attribute's values lie inside its storage; every point maps to one
    const draco::DataBuffer *db = att->buffer();
    uint64_t dt = uint64_t(draco::DataTypeLength(att->data_type()));
    if (!db || dt == 0 || att->size() == 0 || att->byte_stride() <= 0 || att->byte_offset() < 0 ||
        uint64_t(att->byte_offset()) + uint64_t(att->byte_stride()) * (att->size() - 1) +
                uint64_t(att->num_components()) * dt > uint64_t(db->data_size()))
        return MVR_DRACO_SHORT_STORAGE;
    if (!att->is_mapping_identity() && att->indices_map_size() < points) {
        *bad = uint32_t(att->indices_map_size());
        return MVR_DRACO_NO_VALUE;
    }
    switch (component_type) {
    case 5120: return convert<int8_t>(*att, points, comps, out, bad);
    case 5121: return convert<uint8_t>(*att, points, comps, out, bad);
    case 5122: return convert<int16_t>(*att, points, comps, out, bad);
    case 5123: return convert<uint16_t>(*att, points, comps, out, bad);
    case 5125: return convert<uint32_t>(*att, points, comps, out, bad);
    default: return convert<float>(*att, points, comps, out, bad);
    }
}
