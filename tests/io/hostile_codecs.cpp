// io_hostile's compressed-geometry and extension files (see hostile_codecs.hpp).
#include "hostile_codecs.hpp"

#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "gltf_gen.hpp"

namespace hostile {

namespace {

std::string S(long long v)
{
    return std::to_string(v);
}

// Appends bytes to bin, 4-aligned; returns their offset.
size_t append(std::vector<uint8_t> &bin, const void *p, size_t n)
{
    while (bin.size() % 4)
        bin.push_back(0);
    size_t at = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t *>(p), static_cast<const uint8_t *>(p) + n);
    return at;
}

std::string meshopt_view(size_t fallback_offset, size_t length, int stride, size_t at, size_t compressed, size_t count,
                         const char *mode, const char *filter)
{
    std::string ext = "{\"buffer\":0,\"byteOffset\":" + S((long long)at) +
                      ",\"byteLength\":" + S((long long)compressed) + ",\"byteStride\":" + S(stride) +
                      ",\"count\":" + S((long long)count) + ",\"mode\":\"" + mode + "\"" +
                      (filter ? std::string(",\"filter\":\"") + filter + "\"" : "") + "}";
    std::string v =
        "{\"buffer\":1,\"byteOffset\":" + S((long long)fallback_offset) + ",\"byteLength\":" + S((long long)length);
    if (std::string(mode) == "ATTRIBUTES")
        v += ",\"byteStride\":" + S(stride);
    return v + ",\"extensions\":{\"EXT_meshopt_compression\":" + ext + "}}";
}

}  // namespace

doc meshopt_doc(meshopt_parts *parts, const std::vector<uint16_t> &indices)
{
    doc d;
    meshopt_parts m;
    std::vector<uint8_t> bin;  // buffer 0: the compressed streams
    const float pos[12] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
    const float nrm[16] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    int8_t oct[16];
    meshopt_encodeFilterOct(oct, 4, 4, 8, nrm);
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(4, 12) + meshopt_encodeIndexBufferBound(6, 8));
    size_t n = meshopt_encodeVertexBuffer(out.data(), out.size(), pos, 4, 12);
    m.position_bytes = n;
    size_t at_pos = append(bin, out.data(), n);
    n = meshopt_encodeVertexBuffer(out.data(), out.size(), oct, 4, 4);
    size_t n_nrm = n, at_nrm = append(bin, out.data(), n);
    std::vector<unsigned int> idx(indices.begin(), indices.end());
    n = meshopt_encodeIndexBuffer(out.data(), out.size(), idx.data(), idx.size());
    size_t n_idx = n, at_idx = append(bin, out.data(), n);
    // the fallback buffer's layout: 48 bytes of positions, 16 of normals, 12 of indices
    m.position_view =
        d.add(d.buffer_views, meshopt_view(0, 48, 12, at_pos, m.position_bytes, 4, "ATTRIBUTES", nullptr));
    m.normal_view = d.add(d.buffer_views, meshopt_view(48, 16, 4, at_nrm, n_nrm, 4, "ATTRIBUTES", "OCTAHEDRAL"));
    m.index_view = d.add(d.buffer_views,
                         meshopt_view(64, indices.size() * 2, 2, at_idx, n_idx, indices.size(), "TRIANGLES", nullptr));
    m.position = put_accessor(d, m.position_view, FLOAT, 4, "VEC3", ",\"min\":[-0.5,-0.5,0],\"max\":[0.5,0.5,0]");
    m.normal = put_accessor(d, m.normal_view, 5120, 4, "VEC3", ",\"normalized\":true");
    m.indices = put_accessor(d, m.index_view, USHORT, (long long)indices.size(), "SCALAR");
    int mat = unlit(d, -1, 1.0f, 0.5f, 0.0f);
    d.add(d.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + S(m.position) + ",\"NORMAL\":" + S(m.normal) +
                        "},\"indices\":" + S(m.indices) + ",\"material\":" + S(mat) + "}]}");
    d.add(d.nodes, "{\"mesh\":0}");
    d.add(d.scenes, "{\"nodes\":[0]}");
    d.buffers.push_back(data_buffer(bin));
    d.buffers.push_back("{\"byteLength\":76,\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}");
    for (const char *e : {"EXT_meshopt_compression", "KHR_mesh_quantization"}) {
        d.use(e);
        d.ext_required.push_back(e);
    }
    if (parts)
        *parts = m;
    return d;
}

doc draco_doc(draco_parts *parts, int index_type, const std::function<void(std::vector<uint8_t> &)> &patch)
{
    // the GLB's JSON and BIN chunks; the primitive's extension names the Draco data
    const std::string path = std::string(MVR_CODECS_DIR) + "/draco.glb";
    std::vector<uint8_t> glb = gen::read_file(path);
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        if (at + 4 > glb.size())
            throw std::runtime_error(path + ": truncated");
        std::memcpy(&v, glb.data() + at, 4);
        return v;
    };
    uint32_t json_len = u32(12), bin_at = 20 + json_len + 8;
    nlohmann::json j = nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_len);
    const nlohmann::json &prim = j["meshes"][0]["primitives"][0];
    const nlohmann::json &ext = prim["extensions"]["KHR_draco_mesh_compression"];
    const nlohmann::json &bv = j["bufferViews"][ext["bufferView"].get<size_t>()];
    size_t off = bv.value("byteOffset", size_t(0)), len = bv["byteLength"].get<size_t>();
    if (bin_at + off + len > glb.size())
        throw std::runtime_error(path + ": the Draco bufferView runs past the file");
    draco_parts p;
    p.blob_bytes = len;
    p.points = j["accessors"][prim["attributes"]["POSITION"].get<size_t>()]["count"].get<uint32_t>();
    p.triangles = j["accessors"][prim["indices"].get<size_t>()]["count"].get<uint32_t>() / 3;
    p.position_id = ext["attributes"]["POSITION"].get<uint32_t>();
    p.normal_id = ext["attributes"]["NORMAL"].get<uint32_t>();
    p.tangent_id = ext["attributes"]["TANGENT"].get<uint32_t>();
    p.texcoord_id = ext["attributes"]["TEXCOORD_0"].get<uint32_t>();
    const nlohmann::json &pa = j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];

    doc d;
    std::vector<uint8_t> bin;
    std::vector<uint8_t> blob(glb.begin() + long(bin_at + off), glb.begin() + long(bin_at + off + len));
    if (patch)
        patch(blob);
    p.view = put_view(d, bin, 0, blob.data(), blob.size());
    p.position =
        put_accessor(d, -1, FLOAT, p.points, "VEC3", ",\"min\":" + pa["min"].dump() + ",\"max\":" + pa["max"].dump());
    p.normal = put_accessor(d, -1, FLOAT, p.points, "VEC3");
    p.tangent = put_accessor(d, -1, FLOAT, p.points, "VEC4");
    p.texcoord = put_accessor(d, -1, FLOAT, p.points, "VEC2");
    p.indices = put_accessor(d, -1, index_type, (long long)p.triangles * 3, "SCALAR");
    int mat = unlit(d, -1, 0.0f, 0.5f, 1.0f);
    d.add(d.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + S(p.position) + ",\"NORMAL\":" + S(p.normal) +
                        ",\"TANGENT\":" + S(p.tangent) + ",\"TEXCOORD_0\":" + S(p.texcoord) +
                        "},\"indices\":" + S(p.indices) + ",\"material\":" + S(mat) +
                        ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" + S(p.view) +
                        ",\"attributes\":{\"POSITION\":" + S(p.position_id) + ",\"NORMAL\":" + S(p.normal_id) +
                        ",\"TANGENT\":" + S(p.tangent_id) + ",\"TEXCOORD_0\":" + S(p.texcoord_id) + "}}}}]}");
    d.add(d.nodes, "{\"mesh\":0}");
    d.add(d.scenes, "{\"nodes\":[0]}");
    d.buffers.push_back(data_buffer(bin));
    d.use("KHR_draco_mesh_compression");
    d.ext_required.push_back("KHR_draco_mesh_compression");
    if (parts)
        *parts = p;
    return d;
}

void codec_files(files &f)
{
    // ---- EXT_meshopt_compression
    meshopt_parts m;
    f.text("codec_meshopt_valid.gltf", meshopt_doc(&m).json(),
           "a quad: POSITION, NORMAL (OCTAHEDRAL filter) and indices meshopt-compressed; fallback buffer without data",
           "loads and renders");
    auto mo = [&](const std::string &name, const std::string &what, const std::string &naming,
                  const std::function<void(doc &)> &change) {
        doc d = meshopt_doc();
        change(d);
        f.text("codec_meshopt_" + name + ".gltf", d.json(), what, "refused naming " + naming, naming);
    };
    const std::string PV = "bufferViews[" + S(m.position_view) + "].extensions.EXT_meshopt_compression: ";
    const std::string NV = "bufferViews[" + S(m.normal_view) + "].extensions.EXT_meshopt_compression: ";
    const std::string IV = "bufferViews[" + S(m.index_view) + "].extensions.EXT_meshopt_compression: ";
    auto in_view = [](int view, const std::string &from, const std::string &to) {
        return [=](doc &d) { d.buffer_views[size_t(view)] = replace_all(d.buffer_views[size_t(view)], from, to); };
    };
    std::string plen = "\"byteLength\":" + S((long long)m.position_bytes);
    mo("truncated", "the POSITION stream's byteLength cut to half",
       PV + "the " + S((long long)m.position_bytes / 2) + " compressed bytes do not decode as ATTRIBUTES",
       in_view(m.position_view, plen, "\"byteLength\":" + S((long long)m.position_bytes / 2)));
    mo("truncated_indices", "the index stream's byteLength is 4",
       IV + "the 4 compressed bytes do not decode as TRIANGLES", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.index_view)];
           size_t at = v.find("\"byteLength\":", v.find("EXT_meshopt_compression"));
           size_t end = v.find(',', at);
           v = v.substr(0, at) + "\"byteLength\":4" + v.substr(end);
       });
    mo("count", "POSITION's count 5 (the bufferView holds 48 bytes = 4 x 12)",
       PV + "count 5 x byteStride 12 = 60 bytes, the bufferView's byteLength is 48",
       in_view(m.position_view, "\"count\":4", "\"count\":5"));
    // (a count near the real one may decode, to garbage the accessor does
    // not read: the stream does not record its count; 4 decoded as 20 does)
    mo("count_consistent", "POSITION's count 1000 and bufferView byteLength 12000: a stream of 4 decoded as 1000",
       PV + "the " + S((long long)m.position_bytes) + " compressed bytes do not decode", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.position_view)];
           v = replace_all(replace_all(v, "\"count\":4", "\"count\":1000"), "\"byteOffset\":0,\"byteLength\":48",
                           "\"byteOffset\":0,\"byteLength\":12000");
           d.buffers[1] = replace_all(d.buffers[1], "76", "12028");
       });
    mo("stride", "POSITION's byteStride 10 (ATTRIBUTES needs a multiple of 4)",
       PV + "byteStride 10 of mode ATTRIBUTES is not a multiple of 4", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.position_view)];
           size_t ext = v.find("EXT_meshopt_compression");
           v = v.substr(0, ext) + replace_all(v.substr(ext), "\"byteStride\":12", "\"byteStride\":10");
       });
    mo("stride_parent", "the extension's byteStride 16, the bufferView's 12",
       PV + "byteStride 16 differs from the bufferView's 12", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.position_view)];
           size_t ext = v.find("EXT_meshopt_compression");
           v = v.substr(0, ext) + replace_all(v.substr(ext), "\"byteStride\":12", "\"byteStride\":16");
       });
    mo("index_stride", "indices with byteStride 3", IV + "byteStride 3 of mode TRIANGLES is not 2 or 4",
       in_view(m.index_view, "\"byteStride\":2", "\"byteStride\":3"));
    mo("triangles_count", "TRIANGLES with count 5", IV + "count 5 of mode TRIANGLES is not a multiple of 3",
       [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.index_view)];
           v = replace_all(replace_all(v, "\"count\":6", "\"count\":5"), "\"byteLength\":12,", "\"byteLength\":10,");
       });
    mo("filter_stride", "filter OCTAHEDRAL on the 12-byte positions",
       PV + "byteStride 12 with filter OCTAHEDRAL is not 4 or 8",
       in_view(m.position_view, "\"mode\":\"ATTRIBUTES\"", "\"mode\":\"ATTRIBUTES\",\"filter\":\"OCTAHEDRAL\""));
    mo("filter_quaternion", "filter QUATERNION on the 4-byte normals",
       NV + "byteStride 4 with filter QUATERNION is not 8", in_view(m.normal_view, "OCTAHEDRAL", "QUATERNION"));
    mo("filter_unknown", "filter 'SPLINE'", NV + "filter 'SPLINE' is not NONE",
       in_view(m.normal_view, "OCTAHEDRAL", "SPLINE"));
    mo("filter_on_indices", "filter EXPONENTIAL on TRIANGLES", IV + "filter EXPONENTIAL with mode TRIANGLES",
       in_view(m.index_view, "\"mode\":\"TRIANGLES\"", "\"mode\":\"TRIANGLES\",\"filter\":\"EXPONENTIAL\""));
    mo("mode", "mode 'LINES'", IV + "mode 'LINES' is not ATTRIBUTES, TRIANGLES or INDICES",
       in_view(m.index_view, "\"TRIANGLES\"", "\"LINES\""));
    mo("source_past_end", "the POSITION stream at byteOffset 4000 of a smaller buffer 0",
       PV + "bytes 4000.." + S(4000 + (long long)m.position_bytes) + " run past the end of buffer 0",
       in_view(m.position_view, "{\"buffer\":0,\"byteOffset\":0,", "{\"buffer\":0,\"byteOffset\":4000,"));
    mo("source_missing", "the POSITION stream in buffer 7 (2 buffers)", PV + "buffer 7 does not exist",
       in_view(m.position_view, "{\"buffer\":0,", "{\"buffer\":7,"));
    mo("from_fallback", "the POSITION stream in the fallback buffer", PV + "buffer 1 is a fallback buffer",
       in_view(m.position_view, "{\"buffer\":0,", "{\"buffer\":1,"));
    mo("json_types", "the POSITION stream's count is a string", PV + "count is not an integer",
       in_view(m.position_view, "\"count\":4", "\"count\":\"4\""));
    mo("json_zero", "the POSITION stream's count is 0", PV + "count is not an integer in 1..",
       in_view(m.position_view, "\"count\":4", "\"count\":0"));
    mo("json_missing", "the POSITION stream has no mode", PV + "mode is missing",
       in_view(m.position_view, ",\"mode\":\"ATTRIBUTES\"", ""));
    mo("json_huge", "the POSITION stream's count is 2^64 + 4", PV + "count is not an integer",
       in_view(m.position_view, "\"count\":4", "\"count\":18446744073709551620"));
    mo("fallback_read", "NORMAL's bufferView without the extension, on the fallback buffer",
       "buffers[1] is EXT_meshopt_compression's fallback buffer and has no data", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(m.normal_view)];
           v = v.substr(0, v.find(",\"extensions\"")) + "}";
       });
    {
        meshopt_parts q;
        doc d = meshopt_doc(&q, {0, 1, 2, 0, 2, 7});
        f.text("codec_meshopt_index_out_of_range.gltf", d.json(), "the decoded indices name vertex 7 of 4",
               "refused naming the index",
               "meshes[0].primitives[0].indices: accessor " + S(q.indices) + " element 5 = 7 is past the 4 vertices");
    }
    {
        // gltfpack -cf: the extension only used, the fallback buffer a file; a
        // loader that decodes never reads it (here it does not even exist)
        doc d = meshopt_doc();
        d.buffers[1] = "{\"uri\":\"missing_fallback.bin\",\"byteLength\":76,"
                       "\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}";
        d.ext_required.clear();
        d.ext_required.push_back("KHR_mesh_quantization");
        f.text("codec_meshopt_fallback_unread.gltf", d.json(),
               "EXT_meshopt_compression used, not required; the fallback buffer names a missing file",
               "loads without reading the fallback (buffers_read 1), no warning");
    }
    {
        // 2^28 positions: the decoded view is 3 GiB, over the default budget (2 GiB)
        doc d = meshopt_doc();
        std::string &v = d.buffer_views[size_t(m.position_view)];
        v = replace_all(replace_all(v, "\"count\":4", "\"count\":268435456"), "\"byteLength\":48",
                        "\"byteLength\":3221225472");
        d.buffers[1] = replace_all(d.buffers[1], "\"byteLength\":76", "\"byteLength\":3221225600");
        f.text("codec_meshopt_huge.gltf", d.json(),
               "POSITION's view: 2^28 elements of 12 bytes from a short stream (the accessor reads 4)",
               "MVR_ERROR_OUT_OF_MEMORY naming the view, before anything is decoded");
    }

    // ---- KHR_draco_mesh_compression
    draco_parts p;
    f.text("codec_draco_valid.gltf", draco_doc(&p).json(),
           "draco.glb's Suzanne (POSITION, NORMAL, TANGENT, TEXCOORD_0, indices; accessors without bufferViews)",
           "loads and renders");
    const std::string DR = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    auto dr = [&](const std::string &name, const std::string &what, const std::string &naming,
                  const std::function<void(doc &)> &change) {
        doc d = draco_doc();
        change(d);
        f.text("codec_draco_" + name + ".gltf", d.json(), what, "refused naming " + naming, naming);
    };
    auto in_mesh = [](const std::string &from, const std::string &to) {
        return [=](doc &d) { d.meshes[0] = replace_all(d.meshes[0], from, to); };
    };
    // in the extension's JSON only (its attribute ids may equal the primitive's accessor indices)
    auto in_ext = [](const std::string &from, const std::string &to) {
        return [=](doc &d) {
            std::string &s = d.meshes[0];
            size_t at = s.find("KHR_draco_mesh_compression");
            s = s.substr(0, at) + replace_all(s.substr(at), from, to);
        };
    };
    dr("truncated", "the Draco blob's bufferView cut to half",
       DR + ": the " + S((long long)p.blob_bytes / 2) + " bytes of bufferView " + S(p.view) + " do not decode",
       [&](doc &d) {
           std::string &v = d.buffer_views[size_t(p.view)];
           v = replace_all(v, "\"byteLength\":" + S((long long)p.blob_bytes),
                           "\"byteLength\":" + S((long long)p.blob_bytes / 2));
       });
    dr("header_only", "the Draco blob's bufferView is its first 11 bytes",
       DR + ": the 11 bytes of bufferView " + S(p.view) + " do not decode", [&](doc &d) {
           std::string &v = d.buffer_views[size_t(p.view)];
           v = replace_all(v, "\"byteLength\":" + S((long long)p.blob_bytes), "\"byteLength\":11");
       });
    dr("not_draco", "the Draco bufferView holds other bytes", DR + ": bufferView 1 is not Draco data", [&](doc &d) {
        std::vector<uint8_t> junk(64, 0x5A);
        std::vector<uint8_t> bin2;
        put_view(d, bin2, 1, junk.data(), junk.size());
        d.buffers.push_back(data_buffer(bin2));
        d.meshes[0] = replace_all(d.meshes[0], "\"bufferView\":" + S(p.view), "\"bufferView\":1");
    });
    dr("attribute_missing", "POSITION's Draco attribute id is 9 (not in the data)",
       "attributes.POSITION: Draco attribute id 9 (" + DR + ") is not in the decoded mesh",
       in_ext("\"attributes\":{\"POSITION\":" + S(p.position_id) + ",", "\"attributes\":{\"POSITION\":9,"));
    dr("attribute_not_in_primitive", "the extension names COLOR_0, which the primitive lacks",
       DR + ".attributes.COLOR_0 is not among the primitive's attributes",
       in_ext(",\"TEXCOORD_0\":" + S(p.texcoord_id) + "}", ",\"TEXCOORD_0\":" + S(p.texcoord_id) + ",\"COLOR_0\":5}"));
    dr("attribute_id_type", "POSITION's Draco attribute id is -1", DR + ": attributes.POSITION is not an integer",
       in_ext("\"attributes\":{\"POSITION\":" + S(p.position_id) + ",", "\"attributes\":{\"POSITION\":-1,"));
    dr("components", "the NORMAL accessor is VEC2 (Draco's attribute has 3 components)",
       "attributes.NORMAL: Draco attribute id " + S(p.normal_id) + " has 3 components; accessor " + S(p.normal) +
           " has 2",
       [&](doc &d) { d.accessors[size_t(p.normal)] = replace_all(d.accessors[size_t(p.normal)], "VEC3", "VEC2"); });
    dr("count", "the accessors say " + S(p.points + 1) + " points",
       DR + ": the decoded mesh has " + S(p.points) + " points, the accessors " + S(p.points + 1), [&](doc &d) {
           for (int a : {p.position, p.normal, p.tangent, p.texcoord})
               d.accessors[size_t(a)] =
                   replace_all(d.accessors[size_t(a)], "\"count\":" + S(p.points), "\"count\":" + S(p.points + 1));
       });
    dr("count_mixed", "TEXCOORD_0's accessor count differs from POSITION's",
       "attributes.TEXCOORD_0: accessor " + S(p.texcoord) + " has count " + S(p.points + 1), [&](doc &d) {
           d.accessors[size_t(p.texcoord)] =
               replace_all(d.accessors[size_t(p.texcoord)], "\"count\":" + S(p.points), "\"count\":" + S(p.points + 1));
       });
    dr("indices_count", "the indices accessor says 3 indices",
       "meshes[0].primitives[0].indices: accessor " + S(p.indices) + " has count 3, the decoded mesh has " +
           S(p.triangles) + " triangles",
       [&](doc &d) {
           d.accessors[size_t(p.indices)] =
               replace_all(d.accessors[size_t(p.indices)], "\"count\":" + S(p.triangles * 3), "\"count\":3");
       });
    dr("no_indices", "the primitive has no indices", DR + ": the primitive has no indices accessor",
       in_mesh(",\"indices\":" + S(p.indices), ""));
    dr("mode_points", "mode POINTS", DR + ": mode 0", in_mesh("\"material\":", "\"mode\":0,\"material\":"));
    dr("view_missing", "the extension's bufferView is 9", DR + ": bufferView 9 does not exist",
       in_mesh("\"bufferView\":" + S(p.view), "\"bufferView\":9"));
    dr("json", "the extension's attributes is an array", DR + ": attributes is missing or not an object", [&](doc &d) {
        std::string &s = d.meshes[0];
        size_t at = s.find("\"attributes\":{\"POSITION\":" + S(p.position_id));
        size_t end = s.find('}', at);
        s = s.substr(0, at) + "\"attributes\":[1,2]" + s.substr(end + 1);
    });
    {
        // one byte of the texture coordinates' prediction data changed: Draco
        // reads a count of 2^31 orientations from it and would fill a 256 MiB
        // bit vector for seconds before failing
        doc d = draco_doc(nullptr, USHORT, [](std::vector<uint8_t> &b) {
            if (b.size() > 666 && b[666] == 74)
                b[666] = 62;
        });
        f.text("codec_draco_allocation_bomb.gltf", d.json(), "draco.glb's data with byte 666 changed from 74 to 62",
               "refused fast, Draco's allocations stopped at what the accessors' mesh needs",
               DR + ": decoding the " + S((long long)p.blob_bytes) + " bytes of bufferView 0 took more than");
    }
    {
        draco_parts g;
        doc d = draco_doc(&g, UBYTE);
        f.text("codec_draco_index_type.gltf", d.json(),
               "the Draco mesh of " + S(g.points) + " points with UNSIGNED_BYTE indices",
               "refused naming the decoded index", "does not fit accessor " + S(g.indices) + "'s componentType 5121");
    }

    // ---- extension messages
    {
        doc d = meshopt_doc();
        d.ext_required.push_back("EXT_mvr_unknown");
        d.use("EXT_mvr_unknown");
        f.text("ext_required_unknown.gltf", d.json(), "requires EXT_mvr_unknown",
               "MVR_ERROR_UNSUPPORTED naming 'EXT_mvr_unknown'");
        doc e = draco_doc();
        for (int k = 0; k < 2; ++k)
            e.ext_used.push_back("EXT_mvr_optional");  // listed twice: warned once
        e.meshes[0] = replace_all(e.meshes[0], "\"extensions\":{", "\"extensions\":{\"EXT_mvr_optional\":{\"x\":1},");
        f.text("ext_used_unknown.gltf", e.json(), "uses (not requires) EXT_mvr_optional, listed twice",
               "loads; one warning naming 'EXT_mvr_optional'");
        // tinygltf 2.7 refuses a sampler of wrong type before mvr looks: the
        // unsupported required extension is named first all the same
        doc g = draco_doc();
        g.ext_required.push_back("EXT_mvr_unknown");
        g.use("EXT_mvr_unknown");
        g.add(g.samplers, "{\"magFilter\":\"LINEAR\"}");
        f.text("ext_required_before_parse.gltf", g.json(),
               "requires EXT_mvr_unknown and has a sampler tinygltf refuses",
               "MVR_ERROR_UNSUPPORTED naming 'EXT_mvr_unknown'");
    }
}

}  // namespace hostile
