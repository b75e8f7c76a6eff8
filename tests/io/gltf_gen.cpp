#include "gltf_gen.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "mvr/mvr.h"

namespace gen {

static const int BYTE = 5120, UBYTE = 5121, SHORT = 5122, USHORT = 5123, UINT = 5125, FLOAT = 5126;

int builder::view(const void *data, size_t n, int stride)
{
    while (bin.size() % 4)
        bin.push_back(0);
    size_t offset = bin.size();
    const auto *p = static_cast<const uint8_t *>(data);
    bin.insert(bin.end(), p, p + n);
    std::string j = "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(n);
    if (stride)
        j += ",\"byteStride\":" + std::to_string(stride);
    return add(buffer_views, j + "}");
}

int builder::accessor(int v, size_t offset, int ctype, long long count, const char *type, bool normalized,
                      const std::string &extra)
{
    std::string j = "{";
    if (v >= 0)
        j += "\"bufferView\":" + std::to_string(v) + ",\"byteOffset\":" + std::to_string(offset) + ",";
    j += "\"componentType\":" + std::to_string(ctype) + ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type +
         "\"";
    if (normalized)
        j += ",\"normalized\":true";
    return add(accessors, j + extra + "}");
}

int builder::floats(const std::vector<float> &v, const char *type)
{
    int comps = std::strcmp(type, "VEC2") == 0 ? 2 : std::strcmp(type, "VEC3") == 0 ? 3 : std::strcmp(type, "VEC4") == 0 ? 4 : 1;
    return accessor(view(v.data(), v.size() * 4), 0, FLOAT, (long long)(v.size() / size_t(comps)), type);
}

int builder::indices16(const std::vector<uint16_t> &v)
{
    return accessor(view(v.data(), v.size() * 2), 0, USHORT, (long long)v.size(), "SCALAR");
}

int doc_lists::add(std::vector<std::string> &list, const std::string &json)
{
    list.push_back(json);
    return int(list.size() - 1);
}

std::string json_array(const std::vector<std::string> &items)
{
    std::string s = "[";
    for (size_t i = 0; i < items.size(); ++i)
        s += (i ? "," : "") + items[i];
    return s + "]";
}

std::string json_string(const std::string &s)
{
    std::string o = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            o += '\\';
            o += char(c);
        } else if (c < 0x20) {
            char b[8];
            std::snprintf(b, sizeof b, "\\u%04x", c);
            o += b;
        } else {
            o += char(c);
        }
    }
    return o + "\"";
}

std::string json_members(const doc_lists &d, int default_scene)
{
    std::string j;
    auto member = [&](const char *name, const std::vector<std::string> &v) {
        if (!v.empty())
            j += std::string(",\"") + name + "\":" + json_array(v);
    };
    member("bufferViews", d.buffer_views);
    member("accessors", d.accessors);
    member("images", d.images);
    member("samplers", d.samplers);
    member("textures", d.textures);
    member("materials", d.materials);
    member("meshes", d.meshes);
    member("cameras", d.cameras);
    member("nodes", d.nodes);
    member("scenes", d.scenes);
    if (!d.scenes.empty())
        j += ",\"scene\":" + std::to_string(default_scene);
    member("skins", d.skins);
    member("animations", d.animations);
    if (!d.lights.empty())
        j += ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":" + json_array(d.lights) + "}}";
    std::vector<std::string> used, required;
    for (const auto &e : d.ext_used)
        used.push_back(json_string(e));
    for (const auto &e : d.ext_required)
        required.push_back(json_string(e));
    member("extensionsUsed", used);
    member("extensionsRequired", required);
    return j;
}

std::string base64(const uint8_t *p, size_t n)
{
    static const char *t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = uint32_t(p[i]) << 16 | (i + 1 < n ? uint32_t(p[i + 1]) << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        out += t[v >> 18 & 63];
        out += t[v >> 12 & 63];
        out += i + 1 < n ? t[v >> 6 & 63] : '=';
        out += i + 2 < n ? t[v & 63] : '=';
    }
    return out;
}

std::string builder::json(container c, const std::string &bin_name) const
{
    std::string j = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"mvr tests\"}";
    if (!bin.empty()) {
        std::string buffer = "{\"byteLength\":" + std::to_string((long long)bin.size() + buffer_length_delta);
        if (!buffer_uri_override.empty())
            buffer += ",\"uri\":\"" + buffer_uri_override + "\"";
        else if (c == container::external_bin)
            buffer += ",\"uri\":\"" + bin_name + "\"";
        else if (c == container::data_uri)
            buffer += ",\"uri\":\"data:application/octet-stream;base64," + base64(bin.data(), bin.size()) + "\"";
        j += ",\"buffers\":[" + buffer + "}]";
    }
    j += json_members(*this, default_scene);
    return j + "}";
}

void write_file(const std::string &path, const void *data, size_t n)
{
    std::ofstream f(path, std::ios::binary);
    f.write(static_cast<const char *>(data), std::streamsize(n));
    if (!f)
        throw std::runtime_error("cannot write " + path);
}

std::vector<uint8_t> read_file(const std::string &path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::string builder::write(const std::string &dir, const std::string &name, container c) const
{
    if (c == container::glb) {
        std::string j = json(c, "");
        while (j.size() % 4)
            j += ' ';
        std::vector<uint8_t> b = bin;
        while (b.size() % 4)
            b.push_back(0);
        uint32_t total = uint32_t(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size()));
        std::vector<uint8_t> out;
        auto put32 = [&](uint32_t v) { out.insert(out.end(), reinterpret_cast<uint8_t *>(&v), reinterpret_cast<uint8_t *>(&v) + 4); };
        out.insert(out.end(), {'g', 'l', 'T', 'F'});
        put32(2);
        put32(total);
        put32(uint32_t(j.size()));
        put32(0x4E4F534Au);
        out.insert(out.end(), j.begin(), j.end());
        if (!b.empty()) {
            put32(uint32_t(b.size()));
            put32(0x004E4942u);
            out.insert(out.end(), b.begin(), b.end());
        }
        std::string path = dir + "/" + name + ".glb";
        write_file(path, out.data(), out.size());
        return path;
    }
    std::string j = json(c, name + ".bin");
    std::string path = dir + "/" + name + ".gltf";
    write_file(path, j.data(), j.size());
    if (c == container::external_bin && !bin.empty())
        write_file(dir + "/" + name + ".bin", bin.data(), bin.size());
    return path;
}

// Encodes size x size pixels (RGBA, or RGB for JPEG) from colour(x, y)
// through a temporary file: the tests decode it from memory.
template <typename Colour>
static std::vector<uint8_t> encode_image(const char *format, int size, Colour colour)
{
    using namespace OIIO;
    bool jpeg = std::strcmp(format, "jpg") == 0;
    int channels = jpeg ? 3 : 4;
    std::vector<uint8_t> px(size_t(size) * size_t(size) * size_t(channels));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            uint8_t rgba[4];
            colour(x, y, rgba);
            std::memcpy(&px[(size_t(y) * size_t(size) + size_t(x)) * size_t(channels)], rgba, size_t(channels));
        }
    std::string path = Filesystem::unique_path(Filesystem::temp_directory_path() + "/mvr-gen-%%%%%%%%." + format);
    auto o = ImageOutput::create(path);
    ImageSpec spec(size, size, channels, TypeDesc::UINT8);
    if (!o || !o->open(path, spec) || !o->write_image(TypeDesc::UINT8, px.data()) || !o->close())
        throw std::runtime_error("cannot encode " + path);
    std::vector<uint8_t> bytes = read_file(path);
    Filesystem::remove(path);
    return bytes;
}

std::vector<uint8_t> checker_image(const char *format, int size, uint8_t r, uint8_t g, uint8_t b, uint8_t a)
{
    return encode_image(format, size, [&](int x, int y, uint8_t *p) {
        bool on = ((x * 4 / size) + (y * 4 / size)) % 2 == 0;
        p[0] = on ? r : uint8_t(255 - r);
        p[1] = on ? g : uint8_t(255 - g);
        p[2] = on ? b : uint8_t(255 - b);
        p[3] = a;
    });
}

std::vector<uint8_t> solid_image(const char *format, int size, uint8_t r, uint8_t g, uint8_t b, uint8_t a)
{
    return encode_image(format, size, [&](int, int, uint8_t *p) {
        p[0] = r;
        p[1] = g;
        p[2] = b;
        p[3] = a;
    });
}

}  // namespace gen
