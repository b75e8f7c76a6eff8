// The pieces of io_hostile's files (see hostile_docs.hpp).
#include "hostile_docs.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace hostile {

// ------------------------------------------------------------ small writers

std::string replace_all(std::string s, const std::string &from, const std::string &to)
{
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
    return s;
}

void write_bytes(const std::string &path, const void *p, size_t n)
{
    gen::write_file(path, p, n);
}

void write_text(const std::string &path, const std::string &s)
{
    write_bytes(path, s.data(), s.size());
}

void mkdirs(const std::string &d)
{
    for (size_t at = 1; at != std::string::npos; at = d.find('/', at + 1))
        mkdir(d.substr(0, at).c_str(), 0777);
    mkdir(d.c_str(), 0777);
}

std::string letters(size_t n, uint32_t seed)
{
    std::string s(n, 'a');
    for (size_t i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        s[i] = char('a' + (seed >> 24) % 26);
    }
    return s;
}

std::string base64_letters(size_t n, uint32_t seed)
{
    static const char *t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string s(n, 'A');
    for (size_t i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        s[i] = t[(seed >> 24) % 64];
    }
    return s;
}

std::vector<uint8_t> solid_image(const char *format, int w, int h, uint8_t r, uint8_t g, uint8_t b)
{
    using namespace OIIO;
    bool jpeg = std::strcmp(format, "jpg") == 0;
    int channels = jpeg ? 3 : 4;
    std::vector<uint8_t> px(size_t(w) * size_t(h) * size_t(channels), 255);
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
        px[i * size_t(channels) + 0] = r;
        px[i * size_t(channels) + 1] = g;
        px[i * size_t(channels) + 2] = b;
    }
    std::string path = Filesystem::unique_path(Filesystem::temp_directory_path() + "/mvr-hostile-%%%%%%%%." + format);
    auto o = ImageOutput::create(path);
    ImageSpec spec(w, h, channels, TypeDesc::UINT8);
    if (jpeg)
        spec.attribute("CompressionQuality", 95);
    if (!o || !o->open(path, spec) || !o->write_image(TypeDesc::UINT8, px.data()) || !o->close())
        throw std::runtime_error("cannot encode " + path);
    std::vector<uint8_t> bytes = gen::read_file(path);
    Filesystem::remove(path);
    return bytes;
}

static uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = uint8_t(v >> 24), p[1] = uint8_t(v >> 16), p[2] = uint8_t(v >> 8), p[3] = uint8_t(v);
}

std::vector<uint8_t> png_bomb(uint32_t w, uint32_t h)
{
    std::vector<uint8_t> png = solid_image("png", 4, 4, 10, 200, 30);
    if (png.size() < 33 || std::memcmp(&png[12], "IHDR", 4) != 0)
        throw std::runtime_error("png_bomb: unexpected PNG layout");
    put_be32(&png[16], w);
    put_be32(&png[20], h);
    put_be32(&png[29], crc32(&png[12], 17));
    return png;
}

std::vector<uint8_t> jpeg_bomb(uint16_t w, uint16_t h)
{
    std::vector<uint8_t> jpg = solid_image("jpg", 8, 8, 10, 200, 30);
    for (size_t i = 2; i + 9 < jpg.size();) {
        if (jpg[i] != 0xFF)
            break;
        uint8_t m = jpg[i + 1];
        size_t len = size_t(jpg[i + 2]) << 8 | jpg[i + 3];
        if (m >= 0xC0 && m <= 0xC2) {
            jpg[i + 5] = uint8_t(h >> 8), jpg[i + 6] = uint8_t(h);
            jpg[i + 7] = uint8_t(w >> 8), jpg[i + 8] = uint8_t(w);
            return jpg;
        }
        i += 2 + len;
    }
    throw std::runtime_error("jpeg_bomb: no SOF marker");
}

// ------------------------------------------------------------ glTF documents

std::string doc::json() const
{
    std::string j = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"mvr io_hostile\"}";
    if (!buffers.empty())
        j += ",\"buffers\":" + gen::json_array(buffers);
    return j + gen::json_members(*this, 0) + extra + "}";
}

void doc::use(const std::string &e)
{
    for (const auto &x : ext_used)
        if (x == e)
            return;
    ext_used.push_back(e);
}

int put_view(doc &d, std::vector<uint8_t> &bin, int buffer, const void *p, size_t n)
{
    while (bin.size() % 4)
        bin.push_back(0);
    size_t off = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t *>(p), static_cast<const uint8_t *>(p) + n);
    return d.add(d.buffer_views, "{\"buffer\":" + std::to_string(buffer) + ",\"byteOffset\":" + std::to_string(off) +
                              ",\"byteLength\":" + std::to_string(n) + "}");
}

int put_accessor(doc &d, int view, int ctype, long long count, const char *type, const std::string &extra)
{
    std::string j = "{";
    if (view >= 0)
        j += "\"bufferView\":" + std::to_string(view) + ",";
    j += "\"componentType\":" + std::to_string(ctype) + ",\"count\":" + std::to_string(count) + ",\"type\":\"" +
         type + "\"" + extra + "}";
    return d.add(d.accessors, j);
}

std::string quad(doc &d, std::vector<uint8_t> &bin, int buffer, float cx, float cy, float half, int material,
                 const std::string &extra_attributes, int indices)
{
    float pos[12] = {cx - half, cy - half, 0, cx + half, cy - half, 0, cx + half, cy + half, 0, cx - half, cy + half, 0};
    float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    char mm[160];
    std::snprintf(mm, sizeof mm, ",\"min\":[%g,%g,0],\"max\":[%g,%g,0]", double(cx - half), double(cy - half),
                  double(cx + half), double(cy + half));
    int a_pos = put_accessor(d, put_view(d, bin, buffer, pos, sizeof pos), FLOAT, 4, "VEC3", mm);
    int a_nrm = put_accessor(d, put_view(d, bin, buffer, nrm, sizeof nrm), FLOAT, 4, "VEC3");
    int a_uv = put_accessor(d, put_view(d, bin, buffer, uv, sizeof uv), FLOAT, 4, "VEC2");
    if (indices == -2)
        indices = put_accessor(d, put_view(d, bin, buffer, idx, sizeof idx), USHORT, 6, "SCALAR");
    std::string p = "{\"attributes\":{\"POSITION\":" + std::to_string(a_pos) + ",\"NORMAL\":" + std::to_string(a_nrm) +
                    ",\"TEXCOORD_0\":" + std::to_string(a_uv) + extra_attributes + "}";
    if (indices >= 0)
        p += ",\"indices\":" + std::to_string(indices);
    if (material >= 0)
        p += ",\"material\":" + std::to_string(material);
    return p + "}";
}

void one_mesh(doc &d, const std::vector<std::string> &prims)
{
    d.add(d.meshes, "{\"primitives\":" + gen::json_array(prims) + "}");
    d.add(d.nodes, "{\"mesh\":0}");
    d.add(d.scenes, "{\"nodes\":[0]}");
}

int unlit(doc &d, int texture, float r, float g, float b)
{
    d.use("KHR_materials_unlit");
    char f[96];
    std::snprintf(f, sizeof f, "[%g,%g,%g,1]", double(r), double(g), double(b));
    std::string j = std::string("{\"pbrMetallicRoughness\":{\"baseColorFactor\":") + f +
                    ",\"metallicFactor\":0,\"roughnessFactor\":1";
    if (texture >= 0)
        j += ",\"baseColorTexture\":{\"index\":" + std::to_string(texture) + "}";
    return d.add(d.materials, j + "},\"extensions\":{\"KHR_materials_unlit\":{}}}");
}

std::string data_buffer(const std::vector<uint8_t> &bin)
{
    return "{\"byteLength\":" + std::to_string(bin.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
           gen::base64(bin.data(), bin.size()) + "\"}";
}

std::string uri_buffer(const std::string &uri, uint64_t length)
{
    return "{\"byteLength\":" + std::to_string(length) + ",\"uri\":" + gen::json_string(uri) + "}";
}

doc textured_doc(const std::string &image_json, bool textured, float r, float g, float b)
{
    doc d;
    std::vector<uint8_t> bin;
    int tex = -1;
    if (textured) {
        d.add(d.images, image_json);
        tex = d.add(d.textures, "{\"source\":0}");
    }
    one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, tex, r, g, b))});
    d.buffers.insert(d.buffers.begin(), data_buffer(bin));
    return d;
}

doc colour_doc(const std::string &uri, uint64_t byte_length)
{
    doc d;
    std::vector<uint8_t> bin;
    d.add(d.buffer_views, "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":64}");
    int colour = put_accessor(d, 0, FLOAT, 4, "VEC4");
    one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, -1), ",\"COLOR_0\":" + std::to_string(colour))});
    d.buffers.push_back(data_buffer(bin));
    d.buffers.push_back(uri_buffer(uri, byte_length));
    return d;
}

doc image_row_doc(const std::vector<std::string> &images)
{
    doc d;
    std::vector<uint8_t> bin;
    std::vector<std::string> prims;
    for (size_t i = 0; i < images.size(); ++i) {
        d.add(d.images, images[i]);
        d.add(d.textures, "{\"source\":" + std::to_string(i) + "}");
        prims.push_back(quad(d, bin, 0, -1.0f + float(i), 0, 0.4f, unlit(d, int(i))));
    }
    one_mesh(d, prims);
    d.buffers.insert(d.buffers.begin(), data_buffer(bin));
    return d;
}

doc anim_doc(anim_parts *parts)
{
    doc d;
    std::vector<uint8_t> bin;
    anim_parts a;
    uint8_t joints[16] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    uint8_t weights[16] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0};
    a.joints = put_accessor(d, put_view(d, bin, 0, joints, sizeof joints), UBYTE, 4, "VEC4");
    a.weights = put_accessor(d, put_view(d, bin, 0, weights, sizeof weights), UBYTE, 4, "VEC4", ",\"normalized\":true");
    float t0[12] = {0, 0, 0, 0, 0, 0, 0, 0.1f, 0, 0, 0.1f, 0};
    float t1[12] = {0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0};
    a.target0 = put_accessor(d, put_view(d, bin, 0, t0, sizeof t0), FLOAT, 4, "VEC3");
    a.target1 = put_accessor(d, put_view(d, bin, 0, t1, sizeof t1), FLOAT, 4, "VEC3");
    float ibm[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.5f, 0, 1};
    a.ibm = put_accessor(d, put_view(d, bin, 0, ibm, sizeof ibm), FLOAT, 2, "MAT4");
    float times[3] = {0, 0.5f, 1};
    a.times = put_accessor(d, put_view(d, bin, 0, times, sizeof times), FLOAT, 3, "SCALAR", ",\"min\":[0],\"max\":[1]");
    float tr[9] = {0, 0, 0, 0.25f, 0, 0, 0, 0, 0};
    a.translations = put_accessor(d, put_view(d, bin, 0, tr, sizeof tr), FLOAT, 3, "VEC3");
    int16_t ro[12] = {0, 0, 0, 32767, 0, 0, 23170, 23170, 0, 0, 0, 32767};
    a.rotations = put_accessor(d, put_view(d, bin, 0, ro, sizeof ro), SHORT, 3, "VEC4", ",\"normalized\":true");
    float mw[6] = {0, 0, 1, 0, 0, 1};
    a.morph_weights = put_accessor(d, put_view(d, bin, 0, mw, sizeof mw), FLOAT, 6, "SCALAR");
    a.primitive = quad(d, bin, 0, 0, 0, 0.5f, -1,
                       ",\"JOINTS_0\":" + std::to_string(a.joints) + ",\"WEIGHTS_0\":" + std::to_string(a.weights));
    a.primitive.insert(a.primitive.size() - 1, ",\"targets\":[{\"POSITION\":" + std::to_string(a.target0) +
                                                   "},{\"POSITION\":" + std::to_string(a.target1) + "}]");
    d.add(d.meshes, "{\"primitives\":[" + a.primitive + "],\"weights\":[0.5,0.25]}");
    d.add(d.nodes, "{\"mesh\":0,\"skin\":0,\"weights\":[1,0]}");
    d.add(d.nodes, "{\"children\":[2]}");
    d.add(d.nodes, "{\"translation\":[0,0.5,0]}");
    d.add(d.scenes, "{\"nodes\":[0,1]}");
    d.add(d.skins, "{\"joints\":[1,2],\"inverseBindMatrices\":" + std::to_string(a.ibm) + ",\"skeleton\":1,\"name\":\"rig\"}");
    std::string T = std::to_string(a.times);
    d.add(d.animations,
          "{\"name\":\"wave\",\"samplers\":[{\"input\":" + T + ",\"output\":" + std::to_string(a.translations) +
              ",\"interpolation\":\"LINEAR\"},{\"input\":" + T + ",\"output\":" + std::to_string(a.rotations) +
              "},{\"input\":" + T + ",\"output\":" + std::to_string(a.morph_weights) +
              ",\"interpolation\":\"STEP\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}},"
              "{\"sampler\":1,\"target\":{\"node\":2,\"path\":\"rotation\"}},"
              "{\"sampler\":2,\"target\":{\"node\":0,\"path\":\"weights\"}}]}");
    d.buffers.push_back(data_buffer(bin));
    if (parts)
        *parts = a;
    return d;
}

// ------------------------------------------------------------ GLB framing

chunk json_chunk(const std::string &j)
{
    return chunk{JSON_CHUNK, std::vector<uint8_t>(j.begin(), j.end())};
}

std::vector<uint8_t> glb(const std::vector<chunk> &chunks, long long total_delta)
{
    std::vector<uint8_t> out = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0, 0};
    auto put32 = [&](uint32_t v) {
        for (int k = 0; k < 4; ++k)
            out.push_back(uint8_t(v >> (8 * k)));
    };
    for (const chunk &c : chunks) {
        std::vector<uint8_t> d = c.data;
        while (c.pad && d.size() % 4)
            d.push_back(c.type == JSON_CHUNK ? ' ' : 0);
        put32(uint32_t((long long)d.size() + c.length_delta));
        put32(c.type);
        out.insert(out.end(), d.begin(), d.end());
    }
    uint32_t total = uint32_t((long long)out.size() + total_delta);
    std::memcpy(&out[8], &total, 4);
    return out;
}

doc glb_doc(std::vector<uint8_t> &bin, const std::vector<uint8_t> *png)
{
    doc d;
    int tex = -1;
    if (png) {
        int v = put_view(d, bin, 0, png->data(), png->size());
        d.add(d.images, "{\"bufferView\":" + std::to_string(v) + ",\"mimeType\":\"image/png\"}");
        tex = d.add(d.textures, "{\"source\":0}");
    }
    one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, tex))});
    while (bin.size() % 4)
        bin.push_back(0);
    d.buffers.push_back("{\"byteLength\":" + std::to_string(bin.size()) + "}");
    return d;
}

}  // namespace hostile
