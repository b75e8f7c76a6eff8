// Validated accessor reads: nothing is read before the bytes it needs are
// known to lie inside the buffer view and the buffer (glTF 2.0, 3.6 and 5.1).
#include <cmath>
#include <cstring>

#include "gltf_accessor_json.hpp"
#include "gltf_internal.hpp"

namespace mvr_gltf {

using tinygltf::Accessor;
using tinygltf::BufferView;

uint64_t mul_checked(uint64_t a, uint64_t b, const std::string &what)
{
    if (a != 0 && b > UINT64_MAX / a)
        refuse(what + ": size overflows");
    return a * b;
}

uint64_t add_checked(uint64_t a, uint64_t b, const std::string &what)
{
    if (b > UINT64_MAX - a)
        refuse(what + ": size overflows");
    return a + b;
}

uint32_t component_bit(int t)
{
    switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return 1u << 0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1u << 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return 1u << 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 1u << 3;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 1u << 4;
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return ANY_FLOAT;
    default: return 0;
    }
}

uint32_t component_size(int t)
{
    switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

int type_components(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

// One element component as float (glTF 2.0, 3.11: normalized integers).
static float component_value(const unsigned char *p, int t, bool normalized)
{
    switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::fmax(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::fmax(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return normalized ? float(double(v) / 4294967295.0) : float(v);
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

const unsigned char *view_bytes(context &cx, int view_index, uint64_t *length, uint64_t *stride,
                                const std::string &what)
{
    const auto &m = *cx.model;
    if (view_index < 0 || size_t(view_index) >= m.bufferViews.size())
        refuse(what + ": bufferView " + std::to_string(view_index) + " does not exist (" +
               std::to_string(m.bufferViews.size()) + " bufferViews)");
    const BufferView &v = m.bufferViews[size_t(view_index)];
    std::string vname = "bufferViews[" + std::to_string(view_index) + "]";
    if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size())
        refuse(what + ": " + vname + " names buffer " + std::to_string(v.buffer) + ", which does not exist");
    uint64_t end = add_checked(uint64_t(v.byteOffset), uint64_t(v.byteLength), vname);
    if (size_t(v.buffer) < cx.res.buffers.size() && end > cx.res.buffers[size_t(v.buffer)].byte_length)
        refuse(what + ": " + vname + " (bytes " + std::to_string(v.byteOffset) + ".." + std::to_string(end) +
               ") reads past the end of buffer " + std::to_string(v.buffer) + " (" +
               std::to_string(cx.res.buffers[size_t(v.buffer)].byte_length) + " bytes)");
    if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4 != 0))
        refuse(what + ": " + vname + " byteStride " + std::to_string(v.byteStride) +
               " is not a multiple of 4 in 4..252");
    *length = uint64_t(v.byteLength);
    *stride = uint64_t(v.byteStride);
    // EXT_meshopt_compression: byteLength decoded bytes in the view's layout
    // (its own buffer may be a fallback without data, never read)
    if (cx.res.meshopt_views.count(view_index))
        return meshopt_view_bytes(cx, view_index, what);
    byte_span data = cx.buffer(v.buffer, what + " (" + vname + ")");
    return data.data + v.byteOffset;
}

// Checks that count elements of elem bytes, stride apart, from offset fit in length.
static void check_span(uint64_t offset, uint64_t stride, uint64_t count, uint64_t elem, uint64_t length,
                       const std::string &what, const std::string &reader, const std::string &view)
{
    if (count == 0)
        return;
    uint64_t last = add_checked(offset, mul_checked(stride, count - 1, what), what);
    uint64_t end = add_checked(last, elem, what);
    if (end > length)
        refuse(what + ": " + reader + " reads past the end of " + view + " (needs " + std::to_string(end) +
               " bytes, has " + std::to_string(length) + ")");
}

// Reads count elements of `comps` components into out (count * comps floats).
static void read_elements(const unsigned char *base, uint64_t stride, uint64_t count, int comps, int ctype,
                          bool normalized, float *out)
{
    uint32_t cs = component_size(ctype);
    for (uint64_t i = 0; i < count; ++i)
        for (int c = 0; c < comps; ++c)
            out[i * uint64_t(comps) + uint64_t(c)] = component_value(base + i * stride + uint64_t(c) * cs, ctype, normalized);
}

// An unsigned index of 1, 2 or 4 bytes.
static uint32_t index_value(const unsigned char *p, uint64_t size)
{
    if (size == 1)
        return p[0];
    if (size == 2) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

static const Accessor &accessor_at(context &cx, int index, const std::string &what)
{
    const auto &m = *cx.model;
    if (index < 0 || size_t(index) >= m.accessors.size())
        refuse(what + ": accessor " + std::to_string(index) + " does not exist (" + std::to_string(m.accessors.size()) +
               " accessors)");
    auto unknown = cx.res.unknown_accessor_types.find(index);
    if (unknown != cx.res.unknown_accessor_types.end())
        refuse(what + ": accessor " + std::to_string(index) + " has type " + quote(unknown->second) +
               ", which glTF 2.0 does not define");
    return m.accessors[size_t(index)];
}

// A sparse accessor's substitution (glTF 2.0, 3.6.2.3), checked: count
// indices and values inside their bufferViews; target() checks each index.
struct sparse_data {
    uint64_t count = 0, index_size = 0;
    const unsigned char *indices = nullptr, *values = nullptr;
    std::string name;
    // Index k, read in order k = 0, 1, ...: inside the accessor and, as glTF
    // 2.0 (accessor.sparse.indices) requires, strictly increasing.
    uint64_t target(uint64_t k, uint64_t accessor_count, const std::string &what)
    {
        uint64_t t = index_value(indices + k * index_size, index_size);
        if (t >= accessor_count)
            refuse(what + ": " + name + ".indices[" + std::to_string(k) + "] = " + std::to_string(t) +
                   " is past the accessor's " + std::to_string(accessor_count) + " elements");
        if (k > 0 && t <= previous)
            refuse(what + ": " + name + ".indices[" + std::to_string(k) + "] = " + std::to_string(t) +
                   " is not greater than indices[" + std::to_string(k - 1) + "] = " + std::to_string(previous) +
                   " (sparse indices must be strictly increasing)");
        previous = t;
        return t;
    }
    uint64_t previous = 0;
};

// ------------------------------------------------------------ the JSON itself

// A member that must be an integer in lo..hi when present (glTF 2.0's schema
// minimums; hi where tinygltf narrows to int). nlohmann holds a non-negative
// integer as unsigned, a negative one as signed.
static void integer_in(const nlohmann::json &o, const char *key, uint64_t lo, uint64_t hi, const std::string &owner)
{
    auto it = o.find(key);
    if (it == o.end())
        return;
    bool ok = it->is_number_integer() && (it->is_number_unsigned() || it->get<int64_t>() >= 0) &&
              it->get<uint64_t>() >= lo && it->get<uint64_t>() <= hi;
    if (!ok)
        refuse(owner + "." + key + " is " + quote(it->dump()) + ", not an integer " +
               (hi == UINT64_MAX ? ">= " + std::to_string(lo) : "in " + std::to_string(lo) + ".." + std::to_string(hi)));
}

static const nlohmann::json *array_member(const nlohmann::json &doc, const char *key)
{
    auto it = doc.find(key);
    return it != doc.end() && it->is_array() ? &*it : nullptr;
}

void check_accessor_json(const nlohmann::json &doc)
{
    const uint64_t any = UINT64_MAX, int_max = INT32_MAX;
    if (const nlohmann::json *views = array_member(doc, "bufferViews")) {
        for (size_t i = 0; i < views->size(); ++i) {
            const nlohmann::json &v = (*views)[i];
            std::string name = "bufferViews[" + std::to_string(i) + "]";
            if (!v.is_object())
                continue;   // tinygltf refuses it
            integer_in(v, "byteOffset", 0, any, name);
            integer_in(v, "byteStride", 0, any, name);
        }
    }
    const nlohmann::json *accessors = array_member(doc, "accessors");
    for (size_t i = 0; accessors && i < accessors->size(); ++i) {
        const nlohmann::json &a = (*accessors)[i];
        std::string name = "accessors[" + std::to_string(i) + "]";
        if (!a.is_object())
            continue;
        integer_in(a, "byteOffset", 0, any, name);
        integer_in(a, "bufferView", 0, int_max, name);
        auto sparse = a.find("sparse");
        if (sparse == a.end() || !sparse->is_object())
            continue;
        // glTF 2.0, accessor.sparse.count: 1 at least, and "MUST NOT be
        // greater than the number of the base accessor elements"
        auto count = a.find("count");
        uint64_t elements = count != a.end() && count->is_number_unsigned() ? count->get<uint64_t>() : 0;
        integer_in(*sparse, "count", 1, elements < int_max ? elements : int_max, name + ".sparse");
        for (const char *part : {"indices", "values"}) {
            auto p = sparse->find(part);
            if (p == sparse->end() || !p->is_object())
                continue;
            std::string pname = name + ".sparse." + part;
            integer_in(*p, "bufferView", 0, int_max, pname);
            integer_in(*p, "byteOffset", 0, int_max, pname);
            integer_in(*p, "componentType", 0, int_max, pname);
        }
    }
}

static sparse_data sparse_of(context &cx, const Accessor &a, uint64_t count, uint64_t elem, const std::string &what,
                             const std::string &aname)
{
    sparse_data sp;
    sp.name = aname + ".sparse";
    // (check_accessor_json refused what tinygltf would narrow; int64 here
    // so that no count prints wrapped)
    int64_t scount = a.sparse.count;
    if (scount <= 0 || uint64_t(scount) > count)
        refuse(what + ": " + sp.name + ".count " + std::to_string(scount) + " is not in 1.." + std::to_string(count));
    sp.count = uint64_t(scount);
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
        refuse(what + ": " + sp.name + " has a negative byteOffset");
    int itype = a.sparse.indices.componentType;
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        refuse(what + ": " + sp.name + ".indices componentType " + std::to_string(itype) + " is not unsigned");
    uint64_t ilen = 0, istride = 0, vlen = 0, vstride = 0;
    const unsigned char *ib =
        view_bytes(cx, a.sparse.indices.bufferView, &ilen, &istride, what + " (" + sp.name + ".indices)");
    const unsigned char *vb =
        view_bytes(cx, a.sparse.values.bufferView, &vlen, &vstride, what + " (" + sp.name + ".values)");
    sp.index_size = component_size(itype);
    check_span(uint64_t(a.sparse.indices.byteOffset), sp.index_size, sp.count, sp.index_size, ilen, what,
               sp.name + ".indices", "bufferView " + std::to_string(a.sparse.indices.bufferView));
    check_span(uint64_t(a.sparse.values.byteOffset), elem, sp.count, elem, vlen, what, sp.name + ".values",
               "bufferView " + std::to_string(a.sparse.values.bufferView));
    sp.indices = ib + a.sparse.indices.byteOffset;
    sp.values = vb + a.sparse.values.byteOffset;
    return sp;
}

std::vector<float> read_floats(context &cx, int index, int components, const std::string &what,
                               uint32_t allowed)
{
    const Accessor &a = accessor_at(cx, index, what);
    std::string aname = "accessor " + std::to_string(index);
    int comps = type_components(a.type);
    if (comps != components)
        refuse(what + ": " + aname + " has " + std::to_string(comps) + " components per element, " +
               std::to_string(components) + " expected");
    if (!(component_bit(a.componentType) & allowed))
        refuse(what + ": " + aname + " has componentType " + std::to_string(a.componentType) +
               ", which this attribute does not allow");
    uint32_t cs = component_size(a.componentType);
    uint64_t count = uint64_t(a.count);
    if (a.count == 0)
        refuse(what + ": " + aname + " has count 0");
    if (count > cx.limits.max_vertices)
        refuse(what + ": " + aname + " count " + std::to_string(count) + " exceeds the cap of " +
               std::to_string(cx.limits.max_vertices) + " (mvr_gltf_options.max_vertices)");
    uint64_t elem = uint64_t(cs) * uint64_t(comps);
    // every check before the allocation: a small file cannot make us allocate
    // for a count its buffers do not hold
    const unsigned char *base = nullptr;
    uint64_t stride = 0, offset = uint64_t(a.byteOffset);
    auto decoded = cx.decoded_accessors.find(index);
    if (decoded != cx.decoded_accessors.end()) {
        // KHR_draco_mesh_compression: the decoded data, tightly packed (the
        // accessor's bufferView and byteOffset are ignored)
        base = decoded->second->bytes.data();
        stride = elem;
        offset = 0;
        check_span(0, stride, count, elem, decoded->second->bytes.size(), what, aname, "the decoded Draco data");
    } else if (a.bufferView >= 0) {
        uint64_t length = 0;
        base = view_bytes(cx, a.bufferView, &length, &stride, what);
        if (stride == 0)
            stride = elem;
        if (stride < elem)
            refuse(what + ": bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(stride) +
                   " is smaller than an element of " + aname + " (" + std::to_string(elem) + " bytes)");
        check_span(uint64_t(a.byteOffset), stride, count, elem, length, what, aname,
                   "bufferView " + std::to_string(a.bufferView));
    }
    uint64_t floats = mul_checked(count, uint64_t(comps), what);
    cx.mem.charge(floats * sizeof(float), what + " (" + aname + ")");
    cx.mesh_bytes += floats * sizeof(float);
    std::vector<float> out(size_t(floats), 0.0f);
    if (base)
        read_elements(base + offset, stride, count, comps, a.componentType, a.normalized, out.data());
    if (a.sparse.isSparse) {
        sparse_data sp = sparse_of(cx, a, count, elem, what, aname);
        uint64_t scount = sp.count;
        std::vector<float> values(size_t(scount) * size_t(comps));
        read_elements(sp.values, elem, scount, comps, a.componentType, a.normalized, values.data());
        for (uint64_t k = 0; k < scount; ++k) {
            uint64_t target = sp.target(k, count, what);
            std::memcpy(&out[size_t(target) * size_t(comps)], &values[size_t(k) * size_t(comps)],
                        size_t(comps) * sizeof(float));
        }
    }
    return out;
}

std::vector<uint32_t> read_indices(context &cx, int index, const std::string &what)
{
    const Accessor &a = accessor_at(cx, index, what);
    std::string aname = "accessor " + std::to_string(index);
    if (a.type != TINYGLTF_TYPE_SCALAR)
        refuse(what + ": " + aname + " is not SCALAR");
    int t = a.componentType;
    if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        refuse(what + ": " + aname + " componentType " + std::to_string(t) + " is not an unsigned integer type");
    uint64_t count = uint64_t(a.count);
    if (count == 0)
        refuse(what + ": " + aname + " has count 0");
    if (count > cx.limits.max_indices)
        refuse(what + ": " + aname + " count " + std::to_string(count) + " exceeds the cap of " +
               std::to_string(cx.limits.max_indices) + " (mvr_gltf_options.max_indices)");
    cx.mem.charge(count * sizeof(uint32_t), what + " (" + aname + ")");
    cx.mesh_bytes += count * sizeof(uint32_t);
    uint64_t cs = component_size(t);
    // glTF 2.0, 3.6.2.1: an accessor without a bufferView is zeros (sparse may replace some)
    std::vector<uint32_t> out(static_cast<size_t>(count), 0u);
    auto decoded = cx.decoded_accessors.find(index);
    if (decoded != cx.decoded_accessors.end()) {
        // KHR_draco_mesh_compression: the decoded indices, tightly packed
        const std::vector<unsigned char> &b = decoded->second->bytes;
        check_span(0, cs, count, cs, b.size(), what, aname, "the decoded Draco data");
        for (uint64_t i = 0; i < count; ++i)
            out[i] = index_value(b.data() + i * cs, cs);
    } else if (a.bufferView >= 0) {
        uint64_t length = 0, stride = 0;
        const unsigned char *base = view_bytes(cx, a.bufferView, &length, &stride, what);
        if (stride != 0 && stride != cs)
            refuse(what + ": index bufferView " + std::to_string(a.bufferView) +
                   " has a byteStride (indices are tightly packed)");
        check_span(uint64_t(a.byteOffset), cs, count, cs, length, what, aname,
                   "bufferView " + std::to_string(a.bufferView));
        const unsigned char *p = base + a.byteOffset;
        for (uint64_t i = 0; i < count; ++i)
            out[i] = index_value(p + i * cs, cs);
    }
    if (a.sparse.isSparse) {
        sparse_data sp = sparse_of(cx, a, count, cs, what, aname);
        for (uint64_t k = 0; k < sp.count; ++k) {
            uint64_t target = sp.target(k, count, what);
            out[size_t(target)] = index_value(sp.values + k * cs, cs);
        }
    }
    return out;
}

void require_normalized(context &cx, int index, const std::string &what)
{
    const Accessor &a = accessor_at(cx, index, what);
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
        refuse(what + ": accessor " + std::to_string(index) + " has integer componentType " +
               std::to_string(a.componentType) + " but is not normalized");
}

std::vector<uint16_t> read_joints(context &cx, int index, const std::string &what)
{
    const Accessor &a = accessor_at(cx, index, what);
    if (a.normalized)
        refuse(what + ": accessor " + std::to_string(index) + " is normalized (joint indices are plain integers)");
    // glTF 2.0, 3.7.2.1: JOINTS_n are VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT;
    // as floats they are exact (< 2^24), then narrowed to what they were
    std::vector<float> f = read_floats(cx, index, 4, what,
                                       component_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
                                           component_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    cx.mem.charge(f.size() * sizeof(uint16_t), what + " (as 16-bit joints)");
    cx.mesh_bytes += f.size() * sizeof(uint16_t);
    std::vector<uint16_t> out(f.size());
    for (size_t i = 0; i < f.size(); ++i)
        out[i] = uint16_t(f[i]);
    // the floats go now: their charge with them
    uint64_t fb = f.size() * sizeof(float);
    std::vector<float>().swap(f);
    cx.mem.release(fb);
    cx.mesh_bytes = cx.mesh_bytes > fb ? cx.mesh_bytes - fb : 0;
    return out;
}

}  // namespace mvr_gltf
