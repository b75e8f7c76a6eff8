// io_hostile: hostile glTF files, written by this test into the build tree,
// against the loader's contract for untrusted input (include/mvr/mvr_gltf.h,
// issue 16). Each file is refused with a message naming the object, or loads
// and renders safely: a file outside the asset folder never reaches a pixel,
// no message quotes more than ~80 characters of a value from the file or says
// anything about a file outside the folder, and every load stays inside its
// memory budget by its own accounting.
//
//   io_hostile                    runs the cases
//   io_hostile --write-files DIR  writes the files into DIR (DIR/asset/* plus
//                                 DIR/index.tsv: file, what it is, what the
//                                 loader must do) and exits; scripts/hostile_rss
//                                 renders each through `mvr render`
#include <fcntl.h>
#include <limits.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "gltf_gen.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

#define W 64
#define H 48

namespace {

const uint64_t MiB = uint64_t(1) << 20, GiB = uint64_t(1) << 30;
const int FLOAT = 5126, USHORT = 5123, UINT = 5125;

// Outside files have distinctive sizes: a message that leaks a fact about
// them (e.g. "File size mismatch ... 30012") is caught by these numbers.
const size_t OUTSIDE_BIN_SIZE = 30012, OUTSIDE_PNG_SIZE = 40961;

// ------------------------------------------------------------ small writers

std::string jstr(const std::string &s)
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

// Pseudo-random letters: a value no message has any business quoting.
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

// A solid-color image encoded by OpenImageIO ("png" RGBA or "jpg" RGB).
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

uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = uint8_t(v >> 24), p[1] = uint8_t(v >> 16), p[2] = uint8_t(v >> 8), p[3] = uint8_t(v);
}

// A real (small) PNG whose IHDR claims w x h, with a correct CRC: a decoder
// that trusts the header allocates w * h * 4 bytes before it finds the data short.
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

// A baseline JPEG whose SOF marker claims w x h.
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

struct doc {
    std::vector<std::string> buffers, views, accessors, images, textures, samplers, materials, meshes, nodes,
        scenes, cameras, lights, used, required;
    std::string extra; // raw members, each starting with ','

    static std::string array(const std::vector<std::string> &v)
    {
        std::string s = "[";
        for (size_t i = 0; i < v.size(); ++i)
            s += (i ? "," : "") + v[i];
        return s + "]";
    }
    std::string json() const
    {
        std::string j = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"mvr io_hostile\"}";
        auto member = [&](const char *name, const std::vector<std::string> &v) {
            if (!v.empty())
                j += std::string(",\"") + name + "\":" + array(v);
        };
        member("buffers", buffers);
        member("bufferViews", views);
        member("accessors", accessors);
        member("images", images);
        member("samplers", samplers);
        member("textures", textures);
        member("materials", materials);
        member("meshes", meshes);
        member("cameras", cameras);
        member("nodes", nodes);
        member("scenes", scenes);
        if (!scenes.empty())
            j += ",\"scene\":0";
        if (!lights.empty())
            j += ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":" + array(lights) + "}}";
        std::vector<std::string> u, r;
        for (const auto &e : used)
            u.push_back(jstr(e));
        for (const auto &e : required)
            r.push_back(jstr(e));
        member("extensionsUsed", u);
        member("extensionsRequired", r);
        return j + extra + "}";
    }
    void use(const std::string &e)
    {
        for (const auto &x : used)
            if (x == e)
                return;
        used.push_back(e);
    }
    int add(std::vector<std::string> &list, const std::string &json)
    {
        list.push_back(json);
        return int(list.size() - 1);
    }
};

int put_view(doc &d, std::vector<uint8_t> &bin, int buffer, const void *p, size_t n)
{
    while (bin.size() % 4)
        bin.push_back(0);
    size_t off = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t *>(p), static_cast<const uint8_t *>(p) + n);
    return d.add(d.views, "{\"buffer\":" + std::to_string(buffer) + ",\"byteOffset\":" + std::to_string(off) +
                              ",\"byteLength\":" + std::to_string(n) + "}");
}

int put_accessor(doc &d, int view, int ctype, long long count, const char *type, const std::string &extra = "")
{
    std::string j = "{";
    if (view >= 0)
        j += "\"bufferView\":" + std::to_string(view) + ",";
    j += "\"componentType\":" + std::to_string(ctype) + ",\"count\":" + std::to_string(count) + ",\"type\":\"" +
         type + "\"" + extra + "}";
    return d.add(d.accessors, j);
}

// A quad facing +Z (positions with min/max, normals, uvs, u16 indices) in
// buffer `buffer` (whose bytes are `bin`); returns the primitive's JSON.
// indices: -2 = u16 indices in the buffer, -1 = none, else an accessor index.
std::string quad(doc &d, std::vector<uint8_t> &bin, int buffer, float cx, float cy, float half, int material,
                 const std::string &extra_attributes = "", int indices = -2)
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
    d.add(d.meshes, "{\"primitives\":" + doc::array(prims) + "}");
    d.add(d.nodes, "{\"mesh\":0}");
    d.add(d.scenes, "{\"nodes\":[0]}");
}

// Unlit, so a texture's colour reaches the pixels unchanged.
int unlit(doc &d, int texture, float r = 1, float g = 1, float b = 1)
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
    return "{\"byteLength\":" + std::to_string(length) + ",\"uri\":" + jstr(uri) + "}";
}

// One textured quad: buffer 0 a data URI, image 0 = `image_json`; texture
// < 0: the same quad untextured (the reference a left-out image must equal).
doc textured_doc(const std::string &image_json, bool textured = true, float r = 1, float g = 1, float b = 1)
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

// A quad whose COLOR_0 (4 x VEC4 float) comes from buffer 1 = `uri`.
doc colour_doc(const std::string &uri, uint64_t byte_length)
{
    doc d;
    std::vector<uint8_t> bin;
    d.add(d.views, "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":64}");
    int colour = put_accessor(d, 0, FLOAT, 4, "VEC4");
    one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, -1), ",\"COLOR_0\":" + std::to_string(colour))});
    d.buffers.push_back(data_buffer(bin));
    d.buffers.push_back(uri_buffer(uri, byte_length));
    return d;
}

// ------------------------------------------------------------ GLB framing

struct chunk {
    uint32_t type;
    std::vector<uint8_t> data;
    long long length_delta = 0; // lie about the chunk's length
    bool pad = true;            // pad the data to 4 bytes (spaces for JSON)
};
const uint32_t JSON_CHUNK = 0x4E4F534Au, BIN_CHUNK = 0x004E4942u;

chunk json_chunk(const std::string &j)
{
    return chunk{JSON_CHUNK, std::vector<uint8_t>(j.begin(), j.end())};
}

std::vector<uint8_t> glb(const std::vector<chunk> &chunks, long long total_delta = 0)
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

// A GLB-style document: geometry (and, if png is given, the image) in `bin`
// bound to buffer 0 (uri-less).
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

// ------------------------------------------------------------ the files

struct spelling {
    std::string label;
    std::string pattern;  // @ = the outside file's name, # = an inside file's name
    bool may_be_missing;  // a name that stays inside the folder on POSIX: MVR_ERROR_IO is fine too
    std::string uri(const char *outside, const char *inside) const
    {
        return replace_all(replace_all(pattern, "@", outside), "#", inside);
    }
};

struct hostile_file {
    std::string name; // in DIR/asset
    std::string what;
    std::string expect;
};

struct files {
    std::string root, asset;
    std::vector<hostile_file> list;
    std::vector<spelling> spellings;
    std::string long_value;      // 1.5 MB of letters, in the long_* files
    std::string long_b64_value;  // 50 KB of base64 letters, in the bad data URIs
    std::string path(const std::string &name) const { return asset + "/" + name; }
    void text(const std::string &name, const std::string &content, const std::string &what, const std::string &expect)
    {
        write_text(path(name), content);
        list.push_back({name, what, expect});
    }
    void bytes(const std::string &name, const std::vector<uint8_t> &b, const std::string &what, const std::string &expect)
    {
        write_bytes(path(name), b.data(), b.size());
        list.push_back({name, what, expect});
    }
};

void relink(const std::string &target, const std::string &link)
{
    unlink(link.c_str());
    if (symlink(target.c_str(), link.c_str()) != 0)
        throw std::runtime_error("cannot create symlink " + link);
}

void sparse_file(const std::string &path, uint64_t size)
{
    int fd = open(path.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    if (fd < 0 || ftruncate(fd, off_t(size)) != 0) {
        if (fd >= 0)
            close(fd);
        throw std::runtime_error("cannot create sparse " + path);
    }
    close(fd);
}

std::vector<uint8_t> float_colours(float r, float g, float b, size_t pad_to)
{
    std::vector<uint8_t> out(pad_to, 0);
    float c[16];
    for (int i = 0; i < 4; ++i)
        c[i * 4 + 0] = r, c[i * 4 + 1] = g, c[i * 4 + 2] = b, c[i * 4 + 3] = 1;
    std::memcpy(out.data(), c, sizeof c);
    return out;
}

files write_all(const std::string &root_in)
{
    files f;
    mkdirs(root_in);
    char real[PATH_MAX];
    if (!realpath(root_in.c_str(), real))
        throw std::runtime_error("realpath " + root_in);
    f.root = real;
    f.asset = f.root + "/asset";
    mkdirs(f.asset + "/sub");
    mkdirs(f.root + "/cwd");
    mkdirs(f.root + "/shared_textures");
    const std::string &R = f.root;
    const std::string REFUSE_BUF = "refused: INVALID_ASSET naming buffers[1].uri";
    const std::string DEGRADE_IMG = "loads, images[0] left out (warning), no outside pixel";

    // outside the asset folder: distinctive colours and sizes
    std::vector<uint8_t> magenta = solid_image("png", 16, 16, 255, 0, 255);
    magenta.resize(OUTSIDE_PNG_SIZE, 0); // bytes after IEND: decoders ignore them
    write_bytes(R + "/outside.png", magenta.data(), magenta.size());
    std::vector<uint8_t> outside_bin = float_colours(1, 0, 1, OUTSIDE_BIN_SIZE);
    write_bytes(R + "/outside.bin", outside_bin.data(), outside_bin.size());
    // inside: the prefixes of the NUL spellings
    std::vector<uint8_t> white = solid_image("png", 16, 16, 255, 255, 255);
    write_bytes(f.asset + "/inside.png", white.data(), white.size());
    std::vector<uint8_t> inside_bin = float_colours(1, 1, 1, OUTSIDE_BIN_SIZE);
    write_bytes(f.asset + "/inside.bin", inside_bin.data(), inside_bin.size());
    relink(R + "/outside.png", f.asset + "/link_outside.png");
    relink(R + "/outside.bin", f.asset + "/link_outside.bin");
    relink("..", f.asset + "/link_up");
    relink(R, f.asset + "/link_root");
    relink(R + "/no_such_outside.bin", f.asset + "/link_dangling.bin");
    relink(R + "/no_such_outside.png", f.asset + "/link_dangling.png");
    // only in the current directory of the test (it chdirs there)
    write_bytes(R + "/cwd/only_in_cwd.png", magenta.data(), magenta.size());
    write_bytes(R + "/cwd/only_in_cwd.bin", outside_bin.data(), outside_bin.size());
    // a texture library beside the asset folder (file_access.allowed_root)
    std::vector<uint8_t> cyan = solid_image("png", 16, 16, 0, 200, 255);
    write_bytes(R + "/shared_textures/a.png", cyan.data(), cyan.size());

    f.spellings = {
        {"dotdot", "../@", false},
        {"sub_dotdot", "sub/../../@", false},
        {"pct_dots", "%2e%2e/@", false},
        {"pct_all_upper", "%2E%2E%2F@", false},
        {"pct_slash", "..%2f@", false},
        {"backslash", "..\\@", true},
        {"pct_backslash", "..%5c@", true},
        {"dot_dotdot", "./../@", false},
        {"sub_pct_dots", "sub/%2e%2e/%2e%2e/@", false},
        {"double_pct", "%252e%252e/@", true},
        {"abs_real", R + "/@", false},
        {"abs_pct", "%2F" + R.substr(1) + "/@", false},
        {"etc_passwd", "/etc/passwd", false},
        {"abs_fake", "/abs/path/to/outside/file", false},
        {"file_url", "file://" + R + "/@", false},
        {"file_rel", "file:../@", false},
        {"http", "http://127.0.0.1:1/@", false},
        {"drive", "C:/@", false},
        {"unc", "//host/@", false},
        {"nul_pct", "#%00/../../@", false},
        {"nul_raw", std::string("#") + '\0' + "/../../@", false},
        {"symlink_file", "link_@", false},
        {"symlink_dir_rel", "link_up/@", false},
        {"symlink_dir_abs", "link_root/@", false},
        {"tilde", "~/../@", true}, // "~" is a folder name: back inside, no such file
    };
    struct stat sb;
    uint64_t passwd_size = stat("/etc/passwd", &sb) == 0 ? uint64_t(sb.st_size) : 64;
    for (const spelling &s : f.spellings) {
        std::string bin_uri = s.uri("outside.bin", "inside.bin");
        uint64_t len = s.label == "etc_passwd" ? passwd_size : OUTSIDE_BIN_SIZE;
        f.text("trav_buf_" + s.label + ".gltf", colour_doc(bin_uri, len).json(),
               "buffer 1 (COLOR_0) uri " + s.label, s.may_be_missing ? "refused (INVALID_ASSET or IO) naming buffers[1].uri" : REFUSE_BUF);
        std::string img_uri = s.uri("outside.png", "inside.png");
        f.text("trav_img_" + s.label + ".gltf", textured_doc("{\"uri\":" + jstr(img_uri) + "}").json(),
               "image 0 uri " + s.label, DEGRADE_IMG);
    }
    // a declared byteLength that disagrees with the outside file's size
    f.text("trav_buf_dotdot_length.gltf", colour_doc("../outside.bin", 64).json(),
           "buffer 1 ../outside.bin, byteLength 64 (the file has 30012)", REFUSE_BUF + ", no size in the message");
    // the same refusals where the outside file does not exist: the messages must not differ (no existence oracle)
    f.text("trav_buf_dotdot_nonexistent.gltf", colour_doc("../no_such_outside.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 ../no_such_outside.bin (no such file outside)", REFUSE_BUF + ", as for an existing file");
    f.text("trav_buf_symlink_dangling.gltf", colour_doc("link_dangling.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 a symlink to a missing file outside", REFUSE_BUF + ", as for an existing target");
    f.text("trav_img_dotdot_nonexistent.gltf", textured_doc("{\"uri\":\"../no_such_outside.png\"}").json(),
           "image 0 ../no_such_outside.png", DEGRADE_IMG + ", as for an existing file");
    f.text("trav_img_symlink_dangling.gltf", textured_doc("{\"uri\":\"link_dangling.png\"}").json(),
           "image 0 a symlink to a missing file outside", DEGRADE_IMG + ", as for an existing target");
    // positive controls: the same bytes inside the folder do reach the pixels (the magenta detector works)
    write_bytes(f.asset + "/magenta_inside.png", magenta.data(), magenta.size());
    write_bytes(f.asset + "/magenta_inside.bin", outside_bin.data(), outside_bin.size());
    f.text("control_magenta_image.gltf", textured_doc("{\"uri\":\"magenta_inside.png\"}").json(),
           "control: the outside PNG's bytes inside the folder", "loads, draws magenta");
    f.text("control_magenta_buffer.gltf", colour_doc("magenta_inside.bin", OUTSIDE_BIN_SIZE).json(),
           "control: the outside .bin's bytes inside the folder", "loads, draws magenta");
    f.text("reference.gltf", textured_doc("", false).json(), "the untextured quad (reference)", "loads");
    f.text("cwd_buf.gltf", colour_doc("only_in_cwd.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 uri names a file only in the current directory", "refused (IO) naming buffers[1].uri");
    f.text("cwd_img.gltf", textured_doc("{\"uri\":\"only_in_cwd.png\"}").json(),
           "image 0 uri names a file only in the current directory", DEGRADE_IMG);

    // ---- spoofed images
    std::vector<uint8_t> orange_jpg = solid_image("jpg", 16, 16, 255, 128, 0);
    std::vector<uint8_t> orange_png = solid_image("png", 16, 16, 255, 128, 0);
    write_bytes(f.asset + "/jpeg_named.png", orange_jpg.data(), orange_jpg.size());
    f.text("spoof_jpeg_as_png.gltf", textured_doc("{\"uri\":\"jpeg_named.png\"}").json(),
           "JPEG bytes in a file named .png, no mimeType", "loads, decoded as JPEG (by signature)");
    f.text("spoof_jpeg_mime_png.gltf", textured_doc("{\"uri\":\"jpeg_named.png\",\"mimeType\":\"image/png\"}").json(),
           "JPEG bytes, mimeType image/png", "loads, images[0] left out (mimeType disagrees)");
    {
        std::vector<uint8_t> bin;
        doc d;
        int v = put_view(d, bin, 0, orange_jpg.data(), orange_jpg.size());
        d.add(d.images, "{\"bufferView\":" + std::to_string(v) + ",\"mimeType\":\"image/png\"}");
        d.add(d.textures, "{\"source\":0}");
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, 0))});
        while (bin.size() % 4)
            bin.push_back(0);
        d.buffers.push_back("{\"byteLength\":" + std::to_string(bin.size()) + "}");
        f.bytes("spoof_glb_jpeg_mime_png.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, bin}}),
                "GLB bufferView image: JPEG bytes, mimeType image/png", "loads, images[0] left out");
    }
    f.text("spoof_data_uri_png_jpeg.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + gen::base64(orange_jpg.data(), orange_jpg.size()) + "\"}").json(),
           "data:image/png URI holding JPEG bytes", "safe either way (informational)");
    write_text(f.asset + "/text.png", "This is not a PNG, it is a text file pretending to be one.\n");
    f.text("spoof_text_png.gltf", textured_doc("{\"uri\":\"text.png\"}").json(), "a text file named .png",
           "loads, images[0] left out");
    {
        std::vector<uint8_t> mp4 = {0, 0, 0, 0x18, 'f', 't', 'y', 'p', 'i', 's', 'o', 'm', 0, 0, 2, 0,
                                    'i', 's', 'o', 'm', 'i', 's', 'o', '2', 0, 0, 0x10, 0, 'm', 'd', 'a', 't'};
        std::vector<uint8_t> avi = {'R', 'I', 'F', 'F', 0, 0x10, 0, 0, 'A', 'V', 'I', ' ', 'L', 'I', 'S', 'T'};
        uint32_t seed = 7;
        for (int i = 0; i < 4096; ++i) {
            seed = seed * 1664525u + 1013904223u;
            mp4.push_back(uint8_t(seed >> 24));
            avi.push_back(uint8_t(seed >> 16));
        }
        write_bytes(f.asset + "/movie.mp4", mp4.data(), mp4.size());
        write_bytes(f.asset + "/movie.avi", avi.data(), avi.size());
        write_bytes(f.asset + "/movie_named.png", mp4.data(), mp4.size());
    }
    f.text("spoof_mp4.gltf", textured_doc("{\"uri\":\"movie.mp4\"}").json(), "an MP4 (ftyp box, random data) as image",
           "loads, images[0] left out, no video decoder");
    f.text("spoof_avi.gltf", textured_doc("{\"uri\":\"movie.avi\"}").json(), "an AVI (RIFF header, random data) as image",
           "loads, images[0] left out, no video decoder");
    f.text("spoof_mp4_mime_video.gltf", textured_doc("{\"uri\":\"movie.mp4\",\"mimeType\":\"video/mp4\"}").json(),
           "an MP4 with mimeType video/mp4", "loads, images[0] left out");
    f.text("spoof_mp4_named_png.gltf", textured_doc("{\"uri\":\"movie_named.png\"}").json(), "MP4 bytes named .png",
           "loads, images[0] left out");

    // ---- image bombs
    std::vector<uint8_t> bomb = png_bomb(16384, 16384);
    write_bytes(f.asset + "/bomb_16k.png", bomb.data(), bomb.size());
    f.text("bomb_png_16k.gltf", textured_doc("{\"uri\":\"bomb_16k.png\"}").json(),
           "a PNG of a few hundred bytes whose IHDR says 16384 x 16384 (1 GiB RGBA)",
           "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0], memory_budget");
    f.text("bomb_png_16k_data_uri.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + gen::base64(bomb.data(), bomb.size()) + "\"}").json(),
           "the same PNG bomb in a data URI", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    std::vector<uint8_t> bomb_huge = png_bomb(100000, 100000);
    write_bytes(f.asset + "/bomb_100k.png", bomb_huge.data(), bomb_huge.size());
    f.text("bomb_png_100k.gltf", textured_doc("{\"uri\":\"bomb_100k.png\"}").json(),
           "a PNG whose IHDR says 100000 x 100000 (40 GB RGBA)", "refused or left out, naming images[0]; no allocation");
    std::vector<uint8_t> jbomb = jpeg_bomb(16000, 16000);
    write_bytes(f.asset + "/bomb_16k.jpg", jbomb.data(), jbomb.size());
    f.text("bomb_jpeg_16k.gltf", textured_doc("{\"uri\":\"bomb_16k.jpg\"}").json(),
           "a JPEG whose SOF says 16000 x 16000", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    {
        std::vector<uint8_t> glbbin;
        doc d = glb_doc(glbbin, &bomb);
        f.bytes("bomb_png_16k.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, glbbin}}),
                "the PNG bomb in a GLB bufferView", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    }

    // ---- shared images and buffers
    std::vector<uint8_t> green = solid_image("png", 64, 64, 40, 220, 60);
    write_bytes(f.asset + "/shared.png", green.data(), green.size());
    write_bytes(f.asset + "/sub/shared_sub.png", green.data(), green.size());
    {
        doc d;
        std::vector<uint8_t> bin;
        std::vector<std::string> prims;
        for (int i = 0; i < 8; ++i) {
            d.add(d.images, "{\"uri\":\"shared.png\"}");
            d.add(d.textures, "{\"source\":" + std::to_string(i) + "}");
            prims.push_back(quad(d, bin, 0, -1.5f + float(i % 4), i < 4 ? -0.5f : 0.5f, 0.4f, unlit(d, i)));
        }
        one_mesh(d, prims);
        d.buffers.insert(d.buffers.begin(), data_buffer(bin));
        f.text("same_png_x8.gltf", d.json(), "8 images (8 textures, 8 materials) with uri shared.png",
               "loads, images_decoded == 1");
        // the same file spelled four ways
        const char *uris[4] = {"shared.png", "./shared.png", "shared%2Epng", "sub/../shared.png"};
        for (int i = 0; i < 4; ++i)
            d.images[size_t(i)] = std::string("{\"uri\":\"") + uris[i] + "\"}";
        for (int i = 4; i < 8; ++i)
            d.images[size_t(i)] = std::string("{\"uri\":\"") + uris[i - 4] + "\"}";
        f.text("same_png_spellings.gltf", d.json(), "8 images naming shared.png in four spellings",
               "loads, images_decoded == 1 (the same file)");
    }
    {
        // geometry split over 4 buffers that all name geom.bin
        doc d;
        std::vector<uint8_t> bin;
        std::string prim = quad(d, bin, 0, 0, 0, 0.5f, unlit(d, -1, 0.9f, 0.9f, 0.2f));
        // quad() put POSITION, NORMAL, TEXCOORD_0, indices in views 0..3: one buffer each
        for (int v = 0; v < 4; ++v)
            d.views[size_t(v)] = replace_all(d.views[size_t(v)], "\"buffer\":0", "\"buffer\":" + std::to_string(v));
        one_mesh(d, {prim});
        write_bytes(f.asset + "/geom.bin", bin.data(), bin.size());
        for (int b = 0; b < 4; ++b)
            d.buffers.push_back(uri_buffer("geom.bin", bin.size()));
        f.text("same_bin_x4.gltf", d.json(), "4 buffers with uri geom.bin, each read by a bufferView",
               "loads, buffers_read == 1");
    }

    // ---- huge counts and files
    {
        doc d;
        int pos = put_accessor(d, -1, FLOAT, 16000000, "VEC3", ",\"min\":[0,0,0],\"max\":[0,0,0]");
        d.add(d.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}");
        d.add(d.nodes, "{\"mesh\":0}");
        d.add(d.scenes, "{\"nodes\":[0]}");
        f.text("zeros_16m_positions.gltf", d.json(), "POSITION: 16M VEC3 float, no bufferView (zeros, 192 MB)",
               "with memory_budget 64 MiB: OUT_OF_MEMORY, memory_budget");
        d.accessors[0] = replace_all(d.accessors[0], "16000000", "4000000");
        f.text("zeros_4m_positions.gltf", d.json(), "POSITION: 4M VEC3 float, no bufferView (zeros, 48 MB)",
               "loads; the accounting covers what the process took");
    }
    {
        doc d;
        std::vector<uint8_t> bin;
        int idx = put_accessor(d, -1, UINT, 16000000, "SCALAR");
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, -1, "", idx)});
        d.buffers.push_back(data_buffer(bin));
        f.text("zeros_16m_indices.gltf", d.json(), "indices: 16M u32, no bufferView (zeros, 64 MB)",
               "with memory_budget 64 MiB: OUT_OF_MEMORY, memory_budget");
    }
    sparse_file(f.asset + "/huge.bin", 3 * GiB);
    f.text("huge_sparse_bin.gltf", colour_doc("huge.bin", 3 * GiB).json(),
           "buffer 1: a 3 GiB sparse file, byteLength 3 GiB, read by COLOR_0",
           "refused before reading (max_file_bytes or memory_budget), naming buffers[1]");
    sparse_file(f.asset + "/big100m.bin", 100 * MiB);
    f.text("big_100m_bin.gltf", colour_doc("big100m.bin", 100 * MiB).json(),
           "buffer 1: a 100 MiB sparse file read by COLOR_0",
           "loads by default; memory_budget 64 MiB: OUT_OF_MEMORY naming buffers[1]");

    {
        // 1M JSON numbers (2 MB of text): the parsed JSON is counted before it is parsed
        doc d = textured_doc("", false);
        std::string zeros;
        zeros.reserve(2 * MiB + 16);
        for (int i = 0; i < 1000000; ++i)
            zeros += i ? ",0" : "0";
        d.extra = ",\"extras\":[" + zeros + "]";
        f.text("json_tokens_1m.gltf", d.json(), "1M numbers in extras (2 MB of JSON)",
               "loads by default; memory_budget 16 MiB: OUT_OF_MEMORY, memory_budget");
    }
    {
        // three real 2048x2048 PNGs in three files: 16 MiB each decoded; a
        // 72 MiB budget holds the decoding of one, not all three
        std::vector<uint8_t> big = solid_image("png", 2048, 2048, 200, 40, 40);
        doc d;
        std::vector<uint8_t> b;
        std::vector<std::string> prims;
        for (int i = 0; i < 3; ++i) {
            std::string name = "big2k_" + std::to_string(i) + ".png";
            write_bytes(f.asset + "/" + name, big.data(), big.size());
            d.add(d.images, "{\"uri\":\"" + name + "\"}");
            d.add(d.textures, "{\"source\":" + std::to_string(i) + "}");
            prims.push_back(quad(d, b, 0, -1.0f + float(i), 0, 0.4f, unlit(d, i)));
        }
        one_mesh(d, prims);
        d.buffers.insert(d.buffers.begin(), data_buffer(b));
        f.text("images_2k_x3.gltf", d.json(), "three distinct 2048x2048 PNGs (16 MiB each decoded)",
               "loads by default; memory_budget 72 MiB: OUT_OF_MEMORY naming images[1] or [2] (the budget adds up)");
    }

    // ---- lying GLB chunks
    std::vector<uint8_t> bin;
    doc gd = glb_doc(bin, &orange_png);
    std::string gj = gd.json();
    f.bytes("glb_ok.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}), "a valid GLB with its image in a bufferView",
            "loads, renders the image");
    {
        chunk c{BIN_CHUNK, bin};
        c.length_delta = 1000;
        f.bytes("glb_bin_past_end.glb", glb({json_chunk(gj), c}), "BIN chunk length 1000 past the file", "refused, GLB");
        c.length_delta = 8;
        f.bytes("glb_bin_counts_header.glb", glb({json_chunk(gj), c}), "BIN chunk length counts its own 8-byte header",
                "refused, GLB");
        chunk j = json_chunk(gj + " ");
        while (j.data.size() % 4 != 1)
            j.data.push_back(' ');
        j.pad = false;
        f.bytes("glb_json_unaligned.glb", glb({j, chunk{BIN_CHUNK, bin}}), "JSON chunk length 4k+1 (BIN unaligned)",
                "refused, GLB");
        f.bytes("glb_total_too_big.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}, 100),
                "header total length 100 past the file", "refused, GLB");
        f.bytes("glb_total_too_small.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}, -16),
                "header total length 16 short: BIN chunk ends past it", "refused, GLB");
        chunk huge = json_chunk(gj);
        huge.length_delta = 0xFFFFFFF0ll - (long long)((gj.size() + 3) / 4 * 4);
        f.bytes("glb_json_length_huge.glb", glb({huge, chunk{BIN_CHUNK, bin}}), "JSON chunk length 0xFFFFFFF0",
                "refused, GLB");
        std::vector<uint8_t> unknown(20, 0xAB);
        f.bytes("glb_unknown_chunk.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}, chunk{0x4B4E4B55u, unknown}}),
                "a chunk of unknown type after BIN", "loads (unknown chunks are ignored), renders");
        f.bytes("glb_two_bin.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}, chunk{BIN_CHUNK, bin}}),
                "two BIN chunks", "refused, GLB");
        f.bytes("glb_bin_first.glb", glb({chunk{BIN_CHUNK, bin}, json_chunk(gj)}), "BIN chunk before JSON",
                "refused, GLB");
        f.bytes("glb_json_empty.glb", glb({json_chunk("")}), "JSON chunk of length 0", "refused");
        f.bytes("glb_header_only.glb", glb({}), "a 12-byte GLB header, no chunk", "refused, GLB");
    }
    {
        // buffer 1 uri-less too, read by COLOR_0
        doc d = gd;
        d.buffers.push_back("{\"byteLength\":64}");
        d.add(d.views, "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":64}");
        int colour = put_accessor(d, int(d.views.size()) - 1, FLOAT, 4, "VEC4");
        d.meshes[0] = replace_all(d.meshes[0], "\"TEXCOORD_0\":", "\"COLOR_0\":" + std::to_string(colour) + ",\"TEXCOORD_0\":");
        f.bytes("glb_extra_uriless_buffer.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, bin}}),
                "a second uri-less buffer, read by COLOR_0", "refused naming buffers[1]");
        f.bytes("glb_no_bin_chunk.glb", glb({json_chunk(gj)}), "buffer 0 uri-less and used, no BIN chunk",
                "refused naming buffers[0] (or GLB)");
        std::vector<uint8_t> short_bin(bin.begin(), bin.begin() + long(bin.size() / 2));
        f.bytes("glb_bin_shorter_than_buffer.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, short_bin}}),
                "BIN chunk half of buffer 0's byteLength", "refused naming buffers[0] (or GLB)");
    }

    // ---- node graphs and nesting
    auto graph = [&](const std::string &name, const std::vector<std::string> &nodes, const std::string &scene,
                     const std::string &what, const std::string &expect) {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.meshes, "{\"primitives\":[" + quad(d, b, 0, 0, 0, 0.5f, unlit(d, -1)) + "]}");
        d.buffers.push_back(data_buffer(b));
        d.nodes = nodes;
        if (!scene.empty())
            d.scenes = {scene};
        f.text(name, d.json(), what, expect);
    };
    graph("graph_cycle.gltf", {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"}, "{\"nodes\":[0]}",
          "nodes 0 -> 1 -> 0", "refused naming nodes[");
    graph("graph_self_child.gltf", {"{\"mesh\":0,\"children\":[0]}"}, "{\"nodes\":[0]}", "node 0 its own child",
          "refused naming nodes[0]");
    graph("graph_child_twice.gltf", {"{\"mesh\":0,\"children\":[1,1]}", "{\"mesh\":0}"}, "{\"nodes\":[0]}",
          "node 1 listed twice in node 0's children", "refused naming nodes[1]");
    graph("graph_root_twice.gltf", {"{\"mesh\":0}"}, "{\"nodes\":[0,0]}", "node 0 twice in the scene's roots",
          "refused naming nodes[0]");
    graph("graph_cycle_unreachable.gltf", {"{\"mesh\":0}", "{\"children\":[2]}", "{\"children\":[1]}"},
          "{\"nodes\":[0]}", "a cycle 1 <-> 2 the scene does not reach", "loads or refused; no hang");
    graph("graph_cycle_no_scene.gltf", {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"}, "",
          "no scenes, every node in a cycle (no root)", "loads or refused; no hang");
    {
        std::vector<std::string> chain;
        for (int i = 0; i < 1999; ++i)
            chain.push_back("{\"children\":[" + std::to_string(i + 1) + "],\"translation\":[0,0,0]}");
        chain.push_back("{\"mesh\":0}");
        graph("graph_chain_2000.gltf", chain, "{\"nodes\":[0]}", "a node chain 2000 deep",
              "loads and renders, or refused naming nodes[; no crash");
        chain.clear();
        for (int i = 0; i < 99999; ++i)
            chain.push_back("{\"children\":[" + std::to_string(i + 1) + "]}");
        chain.push_back("{\"mesh\":0}");
        graph("graph_chain_100k.gltf", chain, "{\"nodes\":[0]}", "a node chain 100000 deep",
              "loads or refused naming nodes[; no stack overflow");
    }
    {
        std::string deep = "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
        f.text("deep_json_100k.gltf", deep, "JSON arrays nested 100000 deep", "refused; no stack overflow");
        std::string deep_obj = "{\"asset\":{\"version\":\"2.0\"},\"extras\":";
        for (int i = 0; i < 100000; ++i)
            deep_obj += "{\"a\":";
        deep_obj += "0" + std::string(100000, '}') + "}";
        f.text("deep_json_objects_100k.gltf", deep_obj, "JSON objects nested 100000 deep", "refused; no stack overflow");
        f.bytes("deep_json_100k.glb", glb({json_chunk(deep)}), "the 100000-deep JSON in a GLB", "refused");
    }

    // ---- long strings
    f.long_value = letters(1536 * 1024, 12345);
    const std::string &L = f.long_value;
    f.text("long_buffer_uri.gltf", colour_doc(L + ".bin", 64).json(), "buffer 1 uri 1.5 MB long",
           "refused naming buffers[1].uri, message short");
    f.text("long_image_uri.gltf", textured_doc("{\"uri\":" + jstr(L + ".png") + "}").json(), "image 0 uri 1.5 MB long",
           "loads, images[0] left out, warning short");
    {
        doc d = textured_doc("", false);
        d.nodes[0] = "{\"mesh\":0,\"name\":" + jstr(L) + "}";
        d.meshes[0] = replace_all(d.meshes[0], "{\"primitives\"", "{\"name\":" + jstr(L) + ",\"primitives\"");
        f.text("long_names.gltf", d.json(), "node and mesh names 1.5 MB long", "loads");
        doc e = textured_doc("", false);
        e.required = e.used;
        e.required.push_back(L);
        e.used.push_back(L);
        f.text("long_ext_required.gltf", e.json(), "a required extension named by 1.5 MB", "UNSUPPORTED, message short");
        doc u = textured_doc("", false);
        u.used.push_back(L);
        f.text("long_ext_used.gltf", u.json(), "an optional extension named by 1.5 MB", "loads, warning short");
        doc c = textured_doc("", false);
        c.cameras.push_back("{\"type\":" + jstr(L) + "}");
        f.text("long_camera_type_unused.gltf", c.json(), "an unused camera of type (1.5 MB)", "loads, warning short");
        c.nodes.push_back("{\"camera\":0}");
        c.scenes[0] = "{\"nodes\":[0,1]}";
        f.text("long_camera_type_used.gltf", c.json(), "a used camera of type (1.5 MB)", "refused naming cameras[0], short");
        doc m = textured_doc("{\"uri\":\"shared.png\",\"mimeType\":" + jstr(L) + "}");
        f.text("long_mime_type.gltf", m.json(), "image 0 mimeType 1.5 MB long", "left out or refused, message short");
    }
    f.long_b64_value = base64_letters(50 * 1024, 999);
    f.long_b64_value[25000] = '*'; // not a base64 character: malformed
    f.text("bad_data_uri_image_50k.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + f.long_b64_value + "\"}").json(),
           "image 0: a malformed 50 KB base64 data URI", "loads, images[0] left out, warning short");
    f.text("bad_data_uri_buffer_50k.gltf",
           colour_doc("data:application/octet-stream;base64," + f.long_b64_value, 64).json(),
           "buffer 1: a malformed 50 KB base64 data URI", "refused naming buffers[1], message short");
    f.text("bad_data_uri_buffer_unpadded.gltf",
           colour_doc("data:application/octet-stream;base64," + base64_letters(50 * 1024 + 1, 998), 64).json(),
           "buffer 1: 50 KB of base64 whose length is 1 mod 4 (cannot be base64)", "informational");

    // ---- valid files the loader must accept
    {
        doc d = textured_doc("", false);
        d.buffers.push_back("{\"byteLength\":1024}");
        f.text("valid_unused_uriless_buffer.gltf", d.json(), ".gltf with a uri-less buffer nothing reads", "loads");
        doc h = textured_doc("", false);
        h.buffers.push_back("{\"byteLength\":64,\"uri\":\"http://127.0.0.1:1/x.bin\"}");
        f.text("valid_unused_http_buffer.gltf", h.json(), "an http:// buffer nothing reads", "loads, buffers_read == 1");
        doc r = textured_doc("", false);
        r.buffers.push_back("{\"byteLength\":" + std::to_string(OUTSIDE_BIN_SIZE) + ",\"uri\":\"../outside.bin\"}");
        f.text("valid_unused_outside_buffer.gltf", r.json(), "a ../ buffer nothing reads", "loads, buffers_read == 1");
    }
    {
        doc d;
        std::vector<uint8_t> b;
        int idx = put_accessor(d, -1, USHORT, 6, "SCALAR");
        one_mesh(d, {quad(d, b, 0, 0, 0, 0.5f, unlit(d, -1), "", idx)});
        d.buffers.push_back(data_buffer(b));
        f.text("valid_indices_without_view.gltf", d.json(), "indices accessor without bufferView (all 0)",
               "loads, draws nothing");
    }
    {
        doc d = textured_doc("", false, 0.2f, 0.6f, 0.9f);
        doc p = d;
        std::vector<uint8_t> b;
        doc q;
        quad(q, b, 0, 0, 0, 0.5f, -1);
        std::string enc;
        for (uint8_t c : b) {
            char x[4];
            if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.')
                enc += char(c);
            else
                std::snprintf(x, sizeof x, "%%%02X", c), enc += x;
        }
        p.buffers[0] = "{\"byteLength\":" + std::to_string(b.size()) + ",\"uri\":\"data:application/octet-stream," + enc + "\"}";
        f.text("valid_base64_buffer.gltf", d.json(), "the quad, buffer as a base64 data URI", "loads");
        f.text("valid_plain_data_uri.gltf", p.json(), "the quad, buffer as a percent-encoded (non-base64) data URI",
               "loads, renders like the base64 one");
    }
    {
        doc d = textured_doc("", false);
        d.cameras.push_back("{\"type\":\"perspective\",\"perspective\":{\"yfov\":0,\"znear\":-1}}");
        d.lights.push_back("{\"type\":\"area\",\"intensity\":-5}");
        d.lights.push_back("{\"type\":\"point\",\"intensity\":-5,\"range\":-1}");
        d.use("KHR_lights_punctual");
        f.text("valid_unused_bad_camera_light.gltf", d.json(),
               "unused camera yfov 0 / znear -1, unused lights type area / intensity -5", "loads, warnings");
        d.nodes.push_back("{\"camera\":0}");
        d.scenes[0] = "{\"nodes\":[0,1]}";
        f.text("used_bad_camera.gltf", d.json(), "a node uses the camera with yfov 0", "refused naming cameras[0]");
    }
    f.text("valid_missing_texture.gltf", textured_doc("{\"uri\":\"not_there.png\"}", true, 0.9f, 0.3f, 0.2f).json(),
           "image 0 file missing, baseColorFactor red", "loads, images[0] left out, renders the factor");
    f.text("valid_missing_texture_reference.gltf", textured_doc("", false, 0.9f, 0.3f, 0.2f).json(),
           "the same without texture (reference)", "loads");
    {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.images, "{\"uri\":\"shared.png\"}");
        d.add(d.textures, "{\"source\":0}");
        d.add(d.textures, "{\"source\":0}");
        int m0 = unlit(d, 0), m1 = unlit(d, 1, 0.5f, 0.5f, 1);
        one_mesh(d, {quad(d, b, 0, -0.5f, 0, 0.4f, m0), quad(d, b, 0, 0.5f, 0, 0.4f, m1)});
        d.buffers.insert(d.buffers.begin(), data_buffer(b));
        f.text("valid_shared_texture.gltf", d.json(), "two materials, two textures, one image",
               "loads, images_decoded == 1");
    }
    f.text("valid_inside_dotdot.gltf", textured_doc("{\"uri\":\"sub/../shared.png\"}").json(),
           "image uri sub/../shared.png (stays inside)", "loads, decoded");
    write_bytes(f.asset + "/my tex.png", orange_png.data(), orange_png.size());
    f.text("valid_percent_space.gltf", textured_doc("{\"uri\":\"my%20tex.png\"}").json(),
           "image uri my%20tex.png (file 'my tex.png')", "loads, decoded");
    f.text("widen_allowed_root.gltf", textured_doc("{\"uri\":\"../shared_textures/a.png\"}").json(),
           "image ../shared_textures/a.png", "left out by default; decoded with allowed_root = the parent");
    {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.images, "{\"uri\":\"tex%20ture.png\"}");
        d.add(d.textures, "{\"source\":0}");
        std::string prim = quad(d, b, 0, 0, 0, 0.5f, unlit(d, 0));
        d.buffers.push_back(uri_buffer("geo%20data.bin", b.size()));
        one_mesh(d, {prim});
        f.text("widen_read_callback.gltf", d.json(), "buffer geo%20data.bin, image tex%20ture.png (neither on disk)",
               "fails by default; loads through file_access.read");
        write_bytes(f.asset + "/callback_geometry.bin", b.data(), b.size()); // what the callback serves
        // with file_access.read: absolute paths and schemes never reach it; query and fragment are cut
        doc g;
        std::vector<uint8_t> gb;
        const char *uris[3] = {"/abs/x.png", "http://127.0.0.1:1/x.png", "tex%20ture.png?v=2#f"};
        std::vector<std::string> prims;
        for (int i = 0; i < 3; ++i) {
            g.add(g.images, std::string("{\"uri\":") + jstr(uris[i]) + "}");
            g.add(g.textures, "{\"source\":" + std::to_string(i) + "}");
            prims.push_back(quad(g, gb, 0, -1.0f + float(i), 0, 0.4f, unlit(g, i)));
        }
        one_mesh(g, prims);
        g.buffers.insert(g.buffers.begin(), data_buffer(gb));
        f.text("widen_read_callback_refused.gltf", g.json(), "images /abs/x.png, http://..., tex%20ture.png?v=2#f",
               "file_access.read sees only 'tex ture.png'");
        doc e = textured_doc("{\"uri\":\"%2e%2e/x.png\"}");
        f.text("widen_read_callback_dotdot.gltf", e.json(), "image %2e%2e/x.png",
               "file_access.read receives ../x.png (confinement is the caller's)");
    }

    std::string index = "file\twhat\texpect\n";
    for (const auto &h : f.list)
        index += h.name + "\t" + h.what + "\t" + h.expect + "\n";
    write_text(R + "/index.tsv", index);
    return f;
}

std::string g_root;

const files &F()
{
    static files f = write_all(g_root);
    return f;
}

// ------------------------------------------------------------ loading

struct outcome {
    mvr_result r = MVR_OK;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    std::vector<std::string> warnings, all_logged;
    double ms = 0;
    long rss_growth_kb = 0;
    bool warned(const std::string &part) const
    {
        for (const auto &w : warnings)
            if (w.find(part) != std::string::npos)
                return true;
        return false;
    }
    ~outcome() { mvr_scene_destroy(scene); }
    outcome() = default;
    outcome(const outcome &) = delete;
    outcome &operator=(const outcome &) = delete;
    outcome(outcome &&o) noexcept
        : r(o.r), msg(std::move(o.msg)), scene(o.scene), info(o.info), warnings(std::move(o.warnings)),
          all_logged(std::move(o.all_logged)), ms(o.ms), rss_growth_kb(o.rss_growth_kb)
    {
        o.scene = nullptr;
    }
};

void collect(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    auto *o = static_cast<outcome *>(user);
    o->all_logged.push_back(message);
    if (level == MVR_LOG_WARNING)
        o->warnings.push_back(message);
}

long max_rss_kb()
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

bool is_ok(const outcome &o) { return o.r == MVR_OK; }

// Loads with the given options (the logger is ours) and checks what holds
// for every load: on success the loader's own accounting (a budget in
// force, a peak inside it, the warnings counted); on failure no scene; no
// message or warning longer than 1000 characters.
outcome load(mvr_test_state *t, const std::string &path, mvr_gltf_options o, const char *label = nullptr,
             bool from_memory = false)
{
    outcome out;
    o.logger.fn = collect;
    o.logger.user_data = &out;
    o.logger.level = MVR_LOG_DEBUG;
    mvr_error err;
    std::memset(&err, 0, sizeof err);
    long rss0 = max_rss_kb();
    auto t0 = std::chrono::steady_clock::now();
    if (from_memory) {
        std::vector<uint8_t> bytes = gen::read_file(path);
        out.r = mvr_gltf_load_memory(bytes.data(), bytes.size(), &o, &out.scene, &out.info, &err);
    } else {
        out.r = mvr_gltf_load_file(path.c_str(), &o, &out.scene, &out.info, &err);
    }
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out.rss_growth_kb = max_rss_kb() - rss0;
    out.msg = out.r == MVR_OK ? "" : err.message;
    std::string name = label ? label : path.substr(path.find_last_of('/') + 1);
    std::string first = out.r != MVR_OK ? out.msg : out.warnings.empty() ? "" : "warning: " + out.warnings[0];
    if (first.size() > 150)
        first = first.substr(0, 150) + "...";
    std::printf("  %-34s %-24s %7.1f ms %s\n", name.c_str(), mvr_result_name(out.r), out.ms, first.c_str());
    if (out.r == MVR_OK) {
        uint64_t budget = o.memory_budget ? o.memory_budget : 2 * GiB;
        CHECK_MSG(t, out.scene != nullptr, "%s: MVR_OK without a scene", name.c_str());
        CHECK_MSG(t, out.info.memory_budget == budget, "%s: info.memory_budget %llu, expected %llu", name.c_str(),
                  (unsigned long long)out.info.memory_budget, (unsigned long long)budget);
        CHECK_MSG(t, out.info.memory_peak > 0 && out.info.memory_peak <= out.info.memory_budget,
                  "%s: info.memory_peak %llu (budget %llu)", name.c_str(), (unsigned long long)out.info.memory_peak,
                  (unsigned long long)out.info.memory_budget);
        CHECK_MSG(t, out.info.warnings == out.warnings.size(), "%s: info.warnings %u, logged %zu", name.c_str(),
                  out.info.warnings, out.warnings.size());
    } else {
        CHECK_MSG(t, out.scene == nullptr, "%s: failed but left a scene", name.c_str());
        CHECK_MSG(t, !out.msg.empty() && out.msg.size() < 1000, "%s: message of %zu characters", name.c_str(),
                  out.msg.size());
    }
    for (const auto &w : out.all_logged)
        CHECK_MSG(t, w.size() < 1000, "%s: a log message of %zu characters", name.c_str(), w.size());
    return out;
}

mvr_gltf_options defaults()
{
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    return o;
}

mvr_gltf_options strict()
{
    mvr_gltf_options o = defaults();
    o.strict = true;
    return o;
}

mvr_gltf_options budget(uint64_t bytes)
{
    mvr_gltf_options o = defaults();
    o.memory_budget = bytes;
    return o;
}

bool has(const std::string &s, const std::string &part) { return s.find(part) != std::string::npos; }

// The loader said nothing about a file outside the folder: not its size,
// not that it exists.
void no_outside_facts(mvr_test_state *t, const outcome &o, const char *what, const std::vector<std::string> &sizes)
{
    std::vector<std::string> texts = o.all_logged;
    texts.push_back(o.msg);
    for (const auto &m : texts) {
        for (const auto &s : sizes)
            CHECK_MSG(t, !has(m, s), "%s: message tells the outside file's size %s: %s", what, s.c_str(), m.c_str());
        CHECK_MSG(t, !has(m, "exists") && !has(m, "File size mismatch") && !has(m, "file size"),
                  "%s: message tells about the outside file: %s", what, m.c_str());
    }
}

// No message quotes 200 consecutive characters of `value`.
bool quotes_value(const std::string &m, const std::string &value)
{
    bool in[256] = {};
    for (unsigned char c : value)
        in[c] = true;
    size_t run = 0;
    for (size_t i = 0; i < m.size(); ++i) {
        run = in[(unsigned char)m[i]] ? run + 1 : 0;
        if (run >= 200 && value.find(m.substr(i + 1 - 200, 200)) != std::string::npos)
            return true;
    }
    return false;
}

void messages_short(mvr_test_state *t, const outcome &o, const std::string &value, const char *what)
{
    std::vector<std::string> texts = o.all_logged;
    texts.push_back(o.msg);
    for (const auto &m : texts) {
        CHECK_MSG(t, m.size() < 1000, "%s: a message of %zu characters", what, m.size());
        CHECK_MSG(t, !quotes_value(m, value), "%s: a message quotes 200+ characters of the value", what);
    }
}

// ------------------------------------------------------------ rendering

mvr_context *g_ctx;
bool g_ctx_failed;

mvr_context *context(mvr_test_state *t)
{
    if (!g_ctx && !g_ctx_failed) {
        mvr_error err;
        if (mvr_context_create(nullptr, &g_ctx, &err) != MVR_OK) {
            g_ctx_failed = true;
            CHECK_MSG(t, 0, "no GL context: %s", err.message);
        }
    }
    return g_ctx;
}

// Two stereo views (64x48) of the scene, framed on its bounds; the layers' bytes.
std::vector<uint8_t> render(mvr_test_state *t, mvr_scene *scene, const char *what)
{
    std::vector<uint8_t> out;
    mvr_context *ctx = context(t);
    if (!ctx || !scene)
        return out;
    mvr_framing_desc fd = {MVR_LAYOUT_STEREO, 2, 0.2, double(W) / H};
    mvr_view_set *views = nullptr;
    mvr_error err;
    if (mvr_view_set_frame_scene(scene, &fd, &views, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s: framing: %s", what, err.message);
        return out;
    }
    static std::string cache;
    cache = F().root + "/program_cache";
    mkdirs(cache);
    mvr_renderer_desc rd = {};
    rd.context = ctx;
    rd.program_cache_dir = cache.c_str();
    mvr_renderer *r = nullptr;
    mvr_target *target = nullptr;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT};
    mvr_render_desc desc = {{0.05f, 0.05f, 0.08f, 1.0f}, 1.0f, MVR_TONE_MAP_NONE};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, views, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "%s: render: %s", what, r ? mvr_renderer_last_error(r) : err.message);
    if (ok) {
        out.resize(size_t(W) * H * 4 * 2);
        for (uint32_t k = 0; k < 2; ++k)
            CHECK(t, mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, &out[size_t(k) * W * H * 4],
                                             size_t(W) * H * 4) == MVR_OK);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    return out;
}

size_t count_pixels(const std::vector<uint8_t> &px, const std::function<bool(const uint8_t *)> &pred)
{
    size_t n = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4)
        n += pred(&px[i]);
    return n;
}

bool magenta(const uint8_t *p) { return p[0] >= 180 && p[1] <= 90 && p[2] >= 180; }

size_t drawn(const std::vector<uint8_t> &px)
{
    return count_pixels(px, [&](const uint8_t *p) { return p[0] != px[0] || p[1] != px[1] || p[2] != px[2]; });
}

const std::vector<uint8_t> &reference_pixels(mvr_test_state *t)
{
    static std::vector<uint8_t> px;
    if (px.empty()) {
        outcome o = load(t, F().path("reference.gltf"), defaults());
        px = render(t, o.scene, "reference");
        CHECK_MSG(t, drawn(px) > 200, "reference: %zu pixels drawn", drawn(px));
    }
    return px;
}

// A load that left image 0 out: it degraded as the contract says and the
// picture is the untextured reference's, without a magenta pixel.
void left_out_and_clean(mvr_test_state *t, const outcome &o, const char *what, bool compare_reference = true)
{
    CHECK_MSG(t, o.r == MVR_OK, "%s: %s (expected: loads, images[0] left out)", what, o.msg.c_str());
    if (o.r != MVR_OK)
        return;
    CHECK_MSG(t, o.warned("images[0]"), "%s: no warning names images[0]", what);
    CHECK_MSG(t, o.info.images_missing == 1, "%s: info.images_missing %u", what, o.info.images_missing);
    CHECK_MSG(t, o.info.images_decoded == 0, "%s: info.images_decoded %u", what, o.info.images_decoded);
    std::vector<uint8_t> px = render(t, o.scene, what);
    size_t m = count_pixels(px, magenta);
    CHECK_MSG(t, m == 0, "%s: %zu magenta pixels: the outside file reached the picture", what, m);
    if (compare_reference)
        CHECK_MSG(t, !px.empty() && px == reference_pixels(t), "%s: the picture differs from the untextured quad", what);
}

// ------------------------------------------------------------ cases

void magenta_controls_draw_magenta(mvr_test_state *t)
{
    const files &f = F();
    for (const char *n : {"control_magenta_image.gltf", "control_magenta_buffer.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "%s: %s", n, o.msg.c_str());
        size_t m = count_pixels(render(t, o.scene, n), magenta);
        CHECK_MSG(t, m > 200, "%s: %zu magenta pixels: the detector would miss a leak", n, m);
    }
}

void traversal_buffers_are_refused(mvr_test_state *t)
{
    const files &f = F();
    std::vector<std::string> sizes = {std::to_string(OUTSIDE_BIN_SIZE)};
    struct stat sb;
    if (stat("/etc/passwd", &sb) == 0 && sb.st_size >= 100)
        sizes.push_back(std::to_string(sb.st_size));
    std::vector<std::pair<std::string, bool>> cases;
    for (const auto &s : f.spellings)
        cases.push_back({"trav_buf_" + s.label + ".gltf", s.may_be_missing});
    cases.push_back({"trav_buf_dotdot_length.gltf", false});
    cases.push_back({"trav_buf_dotdot_nonexistent.gltf", false});
    cases.push_back({"trav_buf_symlink_dangling.gltf", false});
    for (const auto &c : cases) {
        const char *n = c.first.c_str();
        {
            mvr_gltf_options mo = defaults();
            mo.base_dir = f.asset.c_str();
            outcome m = load(t, f.path(c.first), mo, (c.first + " (memory, base_dir)").c_str(), true);
            CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET || (c.second && m.r == MVR_ERROR_IO), "%s from memory: %s", n,
                      mvr_result_name(m.r));
            CHECK_MSG(t, has(m.msg, "buffers[1].uri"), "%s from memory: %s", n, m.msg.c_str());
            no_outside_facts(t, m, n, sizes);
        }
        outcome o = load(t, f.path(c.first), defaults());
        bool code_ok = o.r == MVR_ERROR_INVALID_ASSET || (c.second && o.r == MVR_ERROR_IO);
        CHECK_MSG(t, code_ok, "%s: %s, expected MVR_ERROR_INVALID_ASSET%s", n, mvr_result_name(o.r),
                  c.second ? " or MVR_ERROR_IO" : "");
        CHECK_MSG(t, o.r == MVR_OK || has(o.msg, "buffers[1].uri"), "%s: message lacks buffers[1].uri: %s", n,
                  o.msg.c_str());
        no_outside_facts(t, o, n, sizes);
        if (o.r == MVR_OK) {
            size_t m = count_pixels(render(t, o.scene, n), magenta);
            CHECK_MSG(t, m == 0, "%s: LEAK: %zu magenta pixels from the outside buffer", n, m);
        }
    }
}

// The message for a refused URI is the same whether the outside file exists
// or not (names aside): no existence oracle.
std::string neutral(std::string m, const std::vector<std::string> &names)
{
    for (const auto &n : names)
        m = replace_all(m, n, "NAME");
    return m;
}

void refusals_do_not_tell_whether_outside_files_exist(mvr_test_state *t)
{
    const files &f = F();
    struct pair { const char *existing, *missing; };
    const pair pairs[] = {{"trav_buf_dotdot.gltf", "trav_buf_dotdot_nonexistent.gltf"},
                          {"trav_buf_symlink_file.gltf", "trav_buf_symlink_dangling.gltf"},
                          {"trav_img_dotdot.gltf", "trav_img_dotdot_nonexistent.gltf"},
                          {"trav_img_symlink_file.gltf", "trav_img_symlink_dangling.gltf"}};
    const std::vector<std::string> names = {"trav_buf_dotdot_nonexistent", "trav_buf_dotdot", "trav_buf_symlink_dangling",
                                            "trav_buf_symlink_file", "trav_img_dotdot_nonexistent", "trav_img_dotdot",
                                            "trav_img_symlink_dangling", "trav_img_symlink_file", "link_dangling",
                                            "link_outside", "no_such_outside", "outside"};
    for (const auto &p : pairs) {
        for (bool st : {false, true}) {
            mvr_gltf_options o = st ? strict() : defaults();
            outcome a = load(t, f.path(p.existing), o, st ? (std::string(p.existing) + " strict").c_str() : nullptr);
            outcome b = load(t, f.path(p.missing), o, st ? (std::string(p.missing) + " strict").c_str() : nullptr);
            std::string ma = neutral(a.msg + (a.warnings.empty() ? "" : a.warnings[0]), names);
            std::string mb = neutral(b.msg + (b.warnings.empty() ? "" : b.warnings[0]), names);
            CHECK_MSG(t, a.r == b.r && ma == mb, "%s vs %s: the outside file's existence shows:\n    %s: %s\n    %s: %s",
                      p.existing, p.missing, mvr_result_name(a.r), ma.c_str(), mvr_result_name(b.r), mb.c_str());
        }
    }
}

void traversal_images_never_reach_a_pixel(mvr_test_state *t)
{
    const files &f = F();
    std::vector<std::string> sizes = {std::to_string(OUTSIDE_PNG_SIZE)};
    for (const auto &s : f.spellings) {
        std::string name = "trav_img_" + s.label + ".gltf";
        outcome o = load(t, f.path(name), defaults());
        left_out_and_clean(t, o, name.c_str());
        no_outside_facts(t, o, name.c_str(), sizes);
        outcome st = load(t, f.path(name), strict(), (name + " strict").c_str());
        CHECK_MSG(t, st.r == MVR_ERROR_INVALID_ASSET || st.r == MVR_ERROR_IO, "%s strict: %s", name.c_str(),
                  mvr_result_name(st.r));
        CHECK_MSG(t, st.r == MVR_OK || has(st.msg, "images[0]"), "%s strict: message lacks images[0]: %s", name.c_str(),
                  st.msg.c_str());
        no_outside_facts(t, st, name.c_str(), sizes);
        if (st.r == MVR_OK)
            CHECK_MSG(t, count_pixels(render(t, st.scene, name.c_str()), magenta) == 0, "%s strict: LEAK", name.c_str());
    }
}

void current_directory_is_never_searched(mvr_test_state *t)
{
    const files &f = F();
    char old[PATH_MAX];
    if (!getcwd(old, sizeof old) || chdir((f.root + "/cwd").c_str()) != 0) {
        CHECK_MSG(t, 0, "cannot chdir into %s/cwd", f.root.c_str());
        return;
    }
    {
        outcome b = load(t, f.path("cwd_buf.gltf"), defaults());
        CHECK_MSG(t, b.r == MVR_ERROR_IO, "cwd_buf: %s, expected MVR_ERROR_IO (missing inside the folder)",
                  mvr_result_name(b.r));
        CHECK_MSG(t, has(b.msg, "buffers[1].uri"), "cwd_buf: %s", b.msg.c_str());
        if (b.r == MVR_OK)
            CHECK_MSG(t, count_pixels(render(t, b.scene, "cwd_buf"), magenta) == 0, "cwd_buf: LEAK from the cwd");
        outcome i = load(t, f.path("cwd_img.gltf"), defaults());
        left_out_and_clean(t, i, "cwd_img");
        // from memory without a base_dir: external URIs are refused, the cwd is no fallback
        outcome bm = load(t, f.path("cwd_buf.gltf"), defaults(), "cwd_buf (memory, no base_dir)", true);
        CHECK_MSG(t, bm.r != MVR_OK && has(bm.msg, "buffers[1]"), "cwd_buf from memory: %s %s", mvr_result_name(bm.r),
                  bm.msg.c_str());
        outcome im = load(t, f.path("cwd_img.gltf"), defaults(), "cwd_img (memory, no base_dir)", true);
        left_out_and_clean(t, im, "cwd_img from memory");
        // a relative base_dir is relative to the cwd by the caller's choice; an absolute one never falls back to it
        mvr_gltf_options o = defaults();
        o.base_dir = f.asset.c_str();
        outcome ib = load(t, f.path("cwd_img.gltf"), o, "cwd_img (memory, base_dir asset)", true);
        left_out_and_clean(t, ib, "cwd_img from memory with base_dir");
    }
    CHECK(t, chdir(old) == 0);
}

void spoofed_images_decode_by_signature(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("spoof_jpeg_as_png.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0,
                  "jpeg named .png: %s, decoded %u, missing %u", o.msg.c_str(), o.info.images_decoded,
                  o.info.images_missing);
        std::vector<uint8_t> px = render(t, o.scene, "spoof_jpeg_as_png");
        size_t orange = count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 80 && p[1] < 180 && p[2] < 60; });
        CHECK_MSG(t, orange > 200, "jpeg named .png: %zu orange pixels (decoded as what the bytes are)", orange);
    }
    const char *left_out[] = {"spoof_jpeg_mime_png.gltf", "spoof_glb_jpeg_mime_png.glb", "spoof_text_png.gltf",
                              "spoof_mp4.gltf",          "spoof_avi.gltf",              "spoof_mp4_mime_video.gltf",
                              "spoof_mp4_named_png.gltf"};
    for (const char *n : left_out) {
        outcome o = load(t, f.path(n), defaults());
        left_out_and_clean(t, o, n);
        CHECK_MSG(t, o.ms < 2000, "%s: %.0f ms (a decoder tried too hard?)", n, o.ms);
        outcome s = load(t, f.path(n), strict(), (std::string(n) + " strict").c_str());
        CHECK_MSG(t, s.r != MVR_OK && has(s.msg, "images[0]"), "%s strict: %s %s", n, mvr_result_name(s.r),
                  s.msg.c_str());
    }
    // informational: the data URI's media type disagrees with its bytes; either outcome is safe
    outcome d = load(t, f.path("spoof_data_uri_png_jpeg.gltf"), defaults());
    std::printf("    (data:image/png holding JPEG: %s, decoded %u, missing %u)\n", mvr_result_name(d.r),
                d.info.images_decoded, d.info.images_missing);
}

void image_bombs_hit_the_budget(mvr_test_state *t)
{
    const files &f = F();
    const char *bombs[] = {"bomb_png_16k.gltf", "bomb_png_16k_data_uri.gltf", "bomb_jpeg_16k.gltf", "bomb_png_16k.glb"};
    for (const char *n : bombs) {
        for (bool st : {false, true}) {
            mvr_gltf_options o = budget(64 * MiB);
            o.strict = st;
            std::string label = std::string(n) + (st ? " 64M strict" : " 64M");
            outcome r = load(t, f.path(n), o, label.c_str());
            CHECK_MSG(t, r.r == MVR_ERROR_OUT_OF_MEMORY, "%s: %s, expected MVR_ERROR_OUT_OF_MEMORY", label.c_str(),
                      mvr_result_name(r.r));
            CHECK_MSG(t, has(r.msg, "memory_budget") && has(r.msg, "images[0]"), "%s: %s", label.c_str(), r.msg.c_str());
            CHECK_MSG(t, r.rss_growth_kb < 200 * 1024, "%s: peak RSS grew by %ld KB", label.c_str(), r.rss_growth_kb);
        }
    }
    // 40 GB declared: over any budget and over max_image_dimension; refused or left out, never allocated
    outcome h = load(t, f.path("bomb_png_100k.gltf"), defaults());
    CHECK_MSG(t, (h.r == MVR_OK && h.info.images_missing == 1 && h.warned("images[0]")) ||
                     ((h.r == MVR_ERROR_INVALID_ASSET || h.r == MVR_ERROR_OUT_OF_MEMORY) && has(h.msg, "images[0]")),
              "bomb_png_100k: %s %s", mvr_result_name(h.r), h.msg.c_str());
    CHECK_MSG(t, h.rss_growth_kb < 200 * 1024, "bomb_png_100k: peak RSS grew by %ld KB", h.rss_growth_kb);
}

struct reader_state {
    std::vector<std::string> uris;
    std::map<std::string, std::vector<uint8_t>> serve;
    int reads_ok = 0, releases = 0;
    uint64_t max_bytes_seen = 0;
};

mvr_result read_cb(const char *uri, uint64_t max_bytes, void **out, size_t *size, void *user)
{
    auto *s = static_cast<reader_state *>(user);
    s->uris.push_back(uri);
    s->max_bytes_seen = max_bytes;
    auto it = s->serve.find(uri);
    if (it == s->serve.end())
        return MVR_ERROR_IO;
    void *p = std::malloc(it->second.size());
    std::memcpy(p, it->second.data(), it->second.size());
    *out = p;
    *size = it->second.size();
    s->reads_ok++;
    return MVR_OK;
}

void release_cb(void *data, void *user)
{
    static_cast<reader_state *>(user)->releases++;
    std::free(data);
}

void shared_files_are_read_once(mvr_test_state *t)
{
    const files &f = F();
    outcome a = load(t, f.path("same_png_x8.gltf"), defaults());
    CHECK_MSG(t, a.r == MVR_OK && a.info.images_decoded == 1 && a.info.images_missing == 0,
              "same_png_x8: %s decoded %u", a.msg.c_str(), a.info.images_decoded);
    {
        std::vector<uint8_t> px = render(t, a.scene, "same_png_x8");
        size_t g = count_pixels(px, [](const uint8_t *p) { return p[1] > 180 && p[0] < 120 && p[2] < 140; });
        CHECK_MSG(t, g > 200, "same_png_x8: %zu green pixels", g);
    }
    // a budget that holds one decode (64x64 RGBA = 16 KB) with room, not eight... the decode counter is the check
    outcome b = load(t, f.path("same_png_spellings.gltf"), defaults());
    CHECK_MSG(t, b.r == MVR_OK && b.info.images_decoded == 1, "same_png_spellings: %s decoded %u (the same file, four spellings)",
              b.msg.c_str(), b.info.images_decoded);
    outcome c = load(t, f.path("same_bin_x4.gltf"), defaults());
    CHECK_MSG(t, c.r == MVR_OK && c.info.buffers_read == 1, "same_bin_x4: %s buffers_read %u", c.msg.c_str(),
              c.info.buffers_read);
    CHECK_MSG(t, drawn(render(t, c.scene, "same_bin_x4")) > 200, "same_bin_x4: nothing drawn");
    {
        // the file itself read once: through file_access.read, counting calls
        reader_state s;
        s.serve["geom.bin"] = gen::read_file(f.path("geom.bin"));
        mvr_gltf_options o = defaults();
        o.file_access.read = read_cb;
        o.file_access.release = release_cb;
        o.file_access.user_data = &s;
        outcome r = load(t, f.path("same_bin_x4.gltf"), o, "same_bin_x4 (file_access.read)");
        CHECK_MSG(t, r.r == MVR_OK && s.uris.size() == 1 && s.releases == 1, "same_bin_x4: %zu reads, %d releases",
                  s.uris.size(), s.releases);
    }
    outcome d = load(t, f.path("valid_shared_texture.gltf"), defaults());
    CHECK_MSG(t, d.r == MVR_OK && d.info.images_decoded == 1, "valid_shared_texture: %s decoded %u", d.msg.c_str(),
              d.info.images_decoded);
}

void huge_counts_and_files_are_refused_early(mvr_test_state *t)
{
    const files &f = F();
    for (const char *n : {"zeros_16m_positions.gltf", "zeros_16m_indices.gltf"}) {
        outcome o = load(t, f.path(n), budget(64 * MiB), (std::string(n) + " 64M").c_str());
        CHECK_MSG(t, o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget"), "%s: %s %s", n,
                  mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, has(o.msg, "accessor") || has(o.msg, "meshes[0]"), "%s: the message names no object: %s", n,
                  o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 100 * 1024, "%s: peak RSS grew by %ld KB", n, o.rss_growth_kb);
    }
    {
        // under the default budget 48 MB of zeros load; the accounting covers what the process took
        outcome o = load(t, f.path("zeros_4m_positions.gltf"), defaults());
        std::printf("    (zeros_4m_positions: peak %.1f MiB by the load's accounting, process peak RSS grew %.1f MiB)\n",
                    double(o.info.memory_peak) / MiB, double(o.rss_growth_kb) / 1024);
        CHECK_MSG(t, o.r == MVR_OK && o.info.memory_peak >= 4000000ull * 12, "zeros_4m_positions: %s peak %llu",
                  o.msg.c_str(), (unsigned long long)o.info.memory_peak);
        CHECK_MSG(t, o.rss_growth_kb * 1024ll <= (long long)(o.info.memory_peak + 64 * MiB),
                  "zeros_4m_positions: the process grew %ld KB, the load counted a peak of %llu bytes",
                  o.rss_growth_kb, (unsigned long long)o.info.memory_peak);
    }
    {
        outcome o = load(t, f.path("huge_sparse_bin.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "max_file_bytes")) ||
                         (o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget")),
                  "huge_sparse_bin: %s %s", mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, has(o.msg, "buffers[1]"), "huge_sparse_bin: %s", o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 100 * 1024 && o.ms < 1000, "huge_sparse_bin: RSS +%ld KB, %.0f ms: read before refusing?",
                  o.rss_growth_kb, o.ms);
    }
    {
        outcome o = load(t, f.path("big_100m_bin.gltf"), budget(64 * MiB), "big_100m_bin 64M");
        CHECK_MSG(t, o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget") && has(o.msg, "buffers[1]"),
                  "big_100m_bin: %s %s", mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 50 * 1024, "big_100m_bin 64M: peak RSS grew by %ld KB", o.rss_growth_kb);
        mvr_gltf_options m = defaults();
        m.max_file_bytes = MiB;
        outcome c = load(t, f.path("big_100m_bin.gltf"), m, "big_100m_bin max_file_bytes 1M");
        CHECK_MSG(t, c.r == MVR_ERROR_INVALID_ASSET && has(c.msg, "max_file_bytes") && has(c.msg, "buffers[1]"),
                  "big_100m_bin max_file_bytes: %s %s", mvr_result_name(c.r), c.msg.c_str());
        outcome ok = load(t, f.path("big_100m_bin.gltf"), defaults());
        CHECK_MSG(t, ok.r == MVR_OK && ok.info.buffers_read == 2, "big_100m_bin: %s buffers_read %u", ok.msg.c_str(),
                  ok.info.buffers_read);
        CHECK_MSG(t, ok.r != MVR_OK || ok.info.memory_peak >= 100 * MiB, "big_100m_bin: peak %llu does not count the buffer",
                  (unsigned long long)ok.info.memory_peak);
    }
}

void budgets_add_up(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("json_tokens_1m.gltf"), defaults());
        std::printf("    (json_tokens_1m: JSON estimate %.1f MiB, peak %.1f MiB, process peak RSS grew %.1f MiB)\n",
                    double(o.info.json_bytes_estimate) / MiB, double(o.info.memory_peak) / MiB,
                    double(o.rss_growth_kb) / 1024);
        CHECK_MSG(t, o.r == MVR_OK && o.info.json_bytes_estimate > 2 * MiB, "json_tokens_1m: %s, json estimate %llu",
                  o.msg.c_str(), (unsigned long long)o.info.json_bytes_estimate);
        // the accounting is not an under-estimate: what the process took is within what the load counted
        CHECK_MSG(t, o.rss_growth_kb * 1024ll <= (long long)(o.info.memory_peak + 64 * MiB),
                  "json_tokens_1m: the process grew %ld KB, the load counted a peak of %llu bytes", o.rss_growth_kb,
                  (unsigned long long)o.info.memory_peak);
        outcome b = load(t, f.path("json_tokens_1m.gltf"), budget(16 * MiB), "json_tokens_1m 16M");
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget") && has(b.msg, "JSON"),
                  "json_tokens_1m 16M: %s %s", mvr_result_name(b.r), b.msg.c_str());
        CHECK_MSG(t, b.rss_growth_kb < 40 * 1024, "json_tokens_1m 16M: peak RSS grew by %ld KB (parsed anyway?)",
                  b.rss_growth_kb);
    }
    {
        outcome o = load(t, f.path("images_2k_x3.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 3 && o.info.memory_peak >= 48 * MiB,
                  "images_2k_x3: %s decoded %u peak %llu", o.msg.c_str(), o.info.images_decoded,
                  (unsigned long long)o.info.memory_peak);
        // each image fits alone (one decoding at a time); the three held together do not
        outcome b = load(t, f.path("images_2k_x3.gltf"), budget(72 * MiB), "images_2k_x3 72M");
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget") &&
                         (has(b.msg, "images[1]") || has(b.msg, "images[2]")),
                  "images_2k_x3 72M: %s %s", mvr_result_name(b.r), b.msg.c_str());
    }
}

void lying_glb_chunks_are_refused(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("glb_ok.glb"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0, "glb_ok: %s decoded %u",
                  o.msg.c_str(), o.info.images_decoded);
        std::vector<uint8_t> px = render(t, o.scene, "glb_ok");
        CHECK_MSG(t, count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 80 && p[1] < 180 && p[2] < 60; }) > 200,
                  "glb_ok: the image's orange is not drawn");
        outcome u = load(t, f.path("glb_unknown_chunk.glb"), defaults());
        CHECK_MSG(t, u.r == MVR_OK, "glb_unknown_chunk: %s (unknown chunks must be ignored)", u.msg.c_str());
        CHECK_MSG(t, u.r != MVR_OK || render(t, u.scene, "glb_unknown_chunk") == px, "glb_unknown_chunk: renders unlike glb_ok");
    }
    const char *glb_errors[] = {"glb_bin_past_end.glb",    "glb_bin_counts_header.glb", "glb_json_unaligned.glb",
                                "glb_total_too_big.glb",   "glb_total_too_small.glb",   "glb_json_length_huge.glb",
                                "glb_two_bin.glb",         "glb_bin_first.glb",         "glb_header_only.glb"};
    for (const char *n : glb_errors) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "GLB"), "%s: %s %s", n, mvr_result_name(o.r),
                  o.msg.c_str());
        outcome m = load(t, f.path(n), defaults(), (std::string(n) + " (memory)").c_str(), true);
        CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET && has(m.msg, "GLB"), "%s from memory: %s %s", n,
                  mvr_result_name(m.r), m.msg.c_str());
    }
    {
        outcome o = load(t, f.path("glb_json_empty.glb"), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET || o.r == MVR_ERROR_PARSE, "glb_json_empty: %s", mvr_result_name(o.r));
        outcome x = load(t, f.path("glb_extra_uriless_buffer.glb"), defaults());
        CHECK_MSG(t, x.r == MVR_ERROR_INVALID_ASSET && has(x.msg, "buffers[1]"), "glb_extra_uriless_buffer: %s %s",
                  mvr_result_name(x.r), x.msg.c_str());
        for (const char *n : {"glb_no_bin_chunk.glb", "glb_bin_shorter_than_buffer.glb"}) {
            outcome b = load(t, f.path(n), defaults());
            CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && (has(b.msg, "buffers[0]") || has(b.msg, "GLB")), "%s: %s %s", n,
                      mvr_result_name(b.r), b.msg.c_str());
        }
    }
}

void node_graphs_and_deep_nesting_are_safe(mvr_test_state *t)
{
    const files &f = F();
    struct expect { const char *file, *part; };
    const expect refused[] = {{"graph_cycle.gltf", "nodes["},
                              {"graph_self_child.gltf", "nodes[0]"},
                              {"graph_child_twice.gltf", "nodes[1]"},
                              {"graph_root_twice.gltf", "nodes[0]"}};
    for (const auto &e : refused) {
        outcome o = load(t, f.path(e.file), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, e.part), "%s: %s %s", e.file, mvr_result_name(o.r),
                  o.msg.c_str());
    }
    for (const char *n : {"graph_cycle_unreachable.gltf", "graph_cycle_no_scene.gltf", "graph_chain_2000.gltf",
                          "graph_chain_100k.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK || (o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "nodes")), "%s: %s %s", n,
                  mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, o.ms < 5000, "%s: %.0f ms", n, o.ms);
        if (o.r == MVR_OK && std::strcmp(n, "graph_chain_2000.gltf") == 0)
            CHECK_MSG(t, drawn(render(t, o.scene, n)) > 200, "%s: loaded but draws nothing", n);
    }
    for (const char *n : {"deep_json_100k.gltf", "deep_json_objects_100k.gltf", "deep_json_100k.glb"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET || o.r == MVR_ERROR_PARSE, "%s: %s", n, mvr_result_name(o.r));
        outcome m = load(t, f.path(n), defaults(), (std::string(n) + " (memory)").c_str(), true);
        CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET || m.r == MVR_ERROR_PARSE, "%s from memory: %s", n, mvr_result_name(m.r));
    }
}

void long_values_stay_out_of_messages(mvr_test_state *t)
{
    const files &f = F();
    const std::string &L = f.long_value;
    {
        outcome o = load(t, f.path("long_buffer_uri.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_ERROR_IO || o.r == MVR_ERROR_INVALID_ASSET) && has(o.msg, "buffers[1].uri"),
                  "long_buffer_uri: %s", mvr_result_name(o.r));
        messages_short(t, o, L, "long_buffer_uri");
    }
    {
        outcome o = load(t, f.path("long_image_uri.gltf"), defaults());
        left_out_and_clean(t, o, "long_image_uri");
        messages_short(t, o, L, "long_image_uri");
        outcome s = load(t, f.path("long_image_uri.gltf"), strict(), "long_image_uri strict");
        CHECK_MSG(t, s.r != MVR_OK && has(s.msg, "images[0]"), "long_image_uri strict: %s", mvr_result_name(s.r));
        messages_short(t, s, L, "long_image_uri strict");
    }
    {
        outcome o = load(t, f.path("long_names.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "long_names: %s", o.msg.c_str());
        messages_short(t, o, L, "long_names");
    }
    {
        outcome o = load(t, f.path("long_ext_required.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_UNSUPPORTED, "long_ext_required: %s", mvr_result_name(o.r));
        messages_short(t, o, L, "long_ext_required");
        outcome u = load(t, f.path("long_ext_used.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_OK && !u.warnings.empty(), "long_ext_used: %s, %zu warnings", u.msg.c_str(),
                  u.warnings.size());
        messages_short(t, u, L, "long_ext_used");
    }
    {
        outcome o = load(t, f.path("long_camera_type_unused.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warned("cameras[0]"), "long_camera_type_unused: %s (unused cameras only warn)",
                  o.msg.c_str());
        messages_short(t, o, L, "long_camera_type_unused");
        outcome u = load(t, f.path("long_camera_type_used.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_ERROR_INVALID_ASSET && has(u.msg, "cameras[0]"), "long_camera_type_used: %s %s",
                  mvr_result_name(u.r), u.msg.c_str());
        messages_short(t, u, L, "long_camera_type_used");
    }
    {
        outcome o = load(t, f.path("long_mime_type.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_OK && o.info.images_missing == 1 && o.warned("images[0]")) ||
                         (o.r != MVR_OK && has(o.msg, "images[0]")),
                  "long_mime_type: %s %s", mvr_result_name(o.r), o.msg.c_str());
        messages_short(t, o, L, "long_mime_type");
    }
    {
        const std::string &B = f.long_b64_value;
        outcome o = load(t, f.path("bad_data_uri_image_50k.gltf"), defaults());
        left_out_and_clean(t, o, "bad_data_uri_image_50k");
        messages_short(t, o, B, "bad_data_uri_image_50k");
        outcome b = load(t, f.path("bad_data_uri_buffer_50k.gltf"), defaults());
        CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && has(b.msg, "buffers[1]"), "bad_data_uri_buffer_50k: %s %s",
                  mvr_result_name(b.r), b.msg.c_str());
        messages_short(t, b, B, "bad_data_uri_buffer_50k");
        // informational: base64 whose length cannot be base64 (1 mod 4)
        outcome u = load(t, f.path("bad_data_uri_buffer_unpadded.gltf"), defaults());
        std::printf("    (base64 of length 1 mod 4 in buffers[1]: %s)\n", mvr_result_name(u.r));
    }
}

void valid_files_load(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("valid_unused_uriless_buffer.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.buffers_read == 1, "valid_unused_uriless_buffer: %s buffers_read %u",
                  o.msg.c_str(), o.info.buffers_read);
        CHECK_MSG(t, o.r != MVR_OK || render(t, o.scene, "valid_unused_uriless_buffer") == reference_pixels(t),
                  "valid_unused_uriless_buffer: renders unlike the reference");
    }
    for (const char *n : {"valid_unused_http_buffer.gltf", "valid_unused_outside_buffer.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.buffers_read == 1, "%s: %s buffers_read %u", n, o.msg.c_str(),
                  o.info.buffers_read);
    }
    {
        outcome o = load(t, f.path("valid_indices_without_view.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "valid_indices_without_view: %s", o.msg.c_str());
        if (o.r == MVR_OK) {
            size_t n = drawn(render(t, o.scene, "valid_indices_without_view"));
            CHECK_MSG(t, n == 0, "valid_indices_without_view: %zu pixels drawn (all indices are 0)", n);
        }
    }
    {
        outcome a = load(t, f.path("valid_base64_buffer.gltf"), defaults());
        outcome b = load(t, f.path("valid_plain_data_uri.gltf"), defaults());
        CHECK_MSG(t, a.r == MVR_OK && b.r == MVR_OK && b.info.buffers_read == 1, "plain data URI: %s / %s",
                  a.msg.c_str(), b.msg.c_str());
        if (a.r == MVR_OK && b.r == MVR_OK) {
            std::vector<uint8_t> pa = render(t, a.scene, "valid_base64_buffer");
            CHECK_MSG(t, drawn(pa) > 200 && render(t, b.scene, "valid_plain_data_uri") == pa,
                      "the percent-encoded data URI renders unlike the base64 one");
        }
    }
    {
        outcome o = load(t, f.path("valid_unused_bad_camera_light.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "valid_unused_bad_camera_light: %s (unused cameras and lights only warn)",
                  o.msg.c_str());
        CHECK_MSG(t, o.warned("cameras[0]") && o.warned("lights[0]") && o.warned("lights[1]"),
                  "valid_unused_bad_camera_light: warnings do not name cameras[0], lights[0], lights[1] (%zu warnings)",
                  o.warnings.size());
        outcome u = load(t, f.path("used_bad_camera.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_ERROR_INVALID_ASSET && has(u.msg, "cameras[0]"), "used_bad_camera: %s %s",
                  mvr_result_name(u.r), u.msg.c_str());
    }
    {
        outcome o = load(t, f.path("valid_missing_texture.gltf"), defaults());
        outcome r = load(t, f.path("valid_missing_texture_reference.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_missing == 1 && o.warned("images[0]"),
                  "valid_missing_texture: %s missing %u", o.msg.c_str(), o.info.images_missing);
        if (o.r == MVR_OK && r.r == MVR_OK) {
            std::vector<uint8_t> px = render(t, o.scene, "valid_missing_texture");
            size_t red = count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 100 && p[1] < 180 && p[2] < 150; });
            CHECK_MSG(t, red > 200, "valid_missing_texture: %zu pixels of the factor's colour (black texture?)", red);
            CHECK_MSG(t, px == render(t, r.scene, "valid_missing_texture_reference"),
                      "valid_missing_texture: renders unlike the same material without texture");
        }
        outcome s = load(t, f.path("valid_missing_texture.gltf"), strict(), "valid_missing_texture strict");
        CHECK_MSG(t, (s.r == MVR_ERROR_IO || s.r == MVR_ERROR_INVALID_ASSET) && has(s.msg, "images[0]"),
                  "valid_missing_texture strict: %s %s", mvr_result_name(s.r), s.msg.c_str());
    }
    for (const char *n : {"valid_inside_dotdot.gltf", "valid_percent_space.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0,
                  "%s: %s decoded %u missing %u", n, o.msg.c_str(), o.info.images_decoded, o.info.images_missing);
        CHECK_MSG(t, o.r != MVR_OK || render(t, o.scene, n) != reference_pixels(t), "%s: the texture is not drawn", n);
    }
}

void allowed_root_widens_access(mvr_test_state *t)
{
    const files &f = F();
    const std::string p = f.path("widen_allowed_root.gltf");
    outcome d = load(t, p, defaults(), "widen_allowed_root (default)");
    left_out_and_clean(t, d, "widen_allowed_root without allowed_root");
    auto cyan = [](const uint8_t *px) { return px[0] < 60 && px[1] > 170 && px[2] > 220; };
    for (const std::string &root : {f.root, f.root + "/shared_textures"}) {
        mvr_gltf_options o = defaults();
        o.file_access.allowed_root = root.c_str();
        outcome w = load(t, p, o, ("widen_allowed_root " + root.substr(root.find_last_of('/'))).c_str());
        CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1 && w.info.images_missing == 0,
                  "allowed_root %s: %s decoded %u", root.c_str(), w.msg.c_str(), w.info.images_decoded);
        size_t n = count_pixels(render(t, w.scene, "widen_allowed_root"), cyan);
        CHECK_MSG(t, n > 200, "allowed_root %s: %zu cyan pixels", root.c_str(), n);
    }
    // allowed_root below the parent admits nothing else of the parent
    mvr_gltf_options o = defaults();
    std::string lib = f.root + "/shared_textures";
    o.file_access.allowed_root = lib.c_str();
    outcome x = load(t, f.path("trav_img_dotdot.gltf"), o, "trav_img_dotdot (allowed_root lib)");
    left_out_and_clean(t, x, "trav_img_dotdot with allowed_root shared_textures");
    outcome b = load(t, f.path("trav_buf_dotdot.gltf"), o, "trav_buf_dotdot (allowed_root lib)");
    CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && has(b.msg, "buffers[1].uri"), "trav_buf_dotdot with allowed_root: %s",
              mvr_result_name(b.r));
}

void read_callback_replaces_file_access(mvr_test_state *t)
{
    const files &f = F();
    const std::string p = f.path("widen_read_callback.gltf");
    outcome d = load(t, p, defaults(), "widen_read_callback (default)");
    CHECK_MSG(t, d.r == MVR_ERROR_IO && has(d.msg, "buffers[0].uri"), "without the callback: %s %s",
              mvr_result_name(d.r), d.msg.c_str());
    auto orange = [](const uint8_t *px) { return px[0] > 200 && px[1] > 80 && px[1] < 180 && px[2] < 60; };
    for (bool memory : {false, true}) {
        reader_state s;
        s.serve["geo data.bin"] = gen::read_file(f.path("callback_geometry.bin"));
        s.serve["tex ture.png"] = gen::read_file(f.path("my tex.png"));
        mvr_gltf_options o = defaults();
        o.file_access.read = read_cb;
        o.file_access.release = release_cb;
        o.file_access.user_data = &s;
        {
            outcome w = load(t, p, o, memory ? "widen_read_callback (memory, no base_dir)" : "widen_read_callback", memory);
            CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1, "read callback: %s decoded %u", w.msg.c_str(),
                      w.info.images_decoded);
            std::set<std::string> seen(s.uris.begin(), s.uris.end());
            CHECK_MSG(t, seen.count("geo data.bin") && seen.count("tex ture.png") && seen.size() == 2,
                      "read callback saw %zu URIs (%s ...), expected the two percent-decoded ones", seen.size(),
                      s.uris.empty() ? "none" : s.uris[0].c_str());
            CHECK_MSG(t, s.max_bytes_seen > 0, "read callback: max_bytes 0");
            CHECK_MSG(t, w.r != MVR_OK || count_pixels(render(t, w.scene, "widen_read_callback"), orange) > 200,
                      "read callback: its image is not drawn");
        }
        CHECK_MSG(t, s.releases == s.reads_ok && s.reads_ok >= 2, "read callback: %d reads, %d releases", s.reads_ok,
                  s.releases);
    }
    {
        // a data: URI never reaches the callback; "../" does, decoded (confinement is the caller's)
        reader_state s;
        mvr_gltf_options o = defaults();
        o.file_access.read = read_cb;
        o.file_access.release = release_cb;
        o.file_access.user_data = &s;
        outcome w = load(t, f.path("widen_read_callback_dotdot.gltf"), o);
        CHECK_MSG(t, s.uris.size() == 1 && s.uris[0] == "../x.png", "the callback saw %zu URIs (%s), expected ../x.png",
                  s.uris.size(), s.uris.empty() ? "none" : s.uris[0].c_str());
        left_out_and_clean(t, w, "widen_read_callback_dotdot (callback fails)");
        CHECK_EQ_INT(t, s.releases, 0);
    }
    {
        reader_state s;
        s.serve["tex ture.png"] = gen::read_file(f.path("my tex.png"));
        mvr_gltf_options o = defaults();
        o.file_access.read = read_cb;
        o.file_access.release = release_cb;
        o.file_access.user_data = &s;
        outcome w = load(t, f.path("widen_read_callback_refused.gltf"), o);
        CHECK_MSG(t, s.uris.size() == 1 && s.uris[0] == "tex ture.png",
                  "the callback saw %zu URIs (first '%s'), expected only 'tex ture.png'", s.uris.size(),
                  s.uris.empty() ? "" : s.uris[0].c_str());
        CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1 && w.info.images_missing == 2 && w.warned("images[0]") &&
                         w.warned("images[1]"),
                  "widen_read_callback_refused: %s decoded %u missing %u", w.msg.c_str(), w.info.images_decoded,
                  w.info.images_missing);
        CHECK_EQ_INT(t, s.releases, s.reads_ok);
    }
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc == 3 && std::strcmp(argv[1], "--write-files") == 0) {
        try {
            files f = write_all(argv[2]);
            std::printf("io_hostile: %zu hostile files in %s (listed in %s/index.tsv)\n", f.list.size(),
                        f.asset.c_str(), f.root.c_str());
            return 0;
        } catch (const std::exception &e) {
            std::fprintf(stderr, "io_hostile: %s\n", e.what());
            return 1;
        }
    }
    if (argc != 1) {
        std::fprintf(stderr, "usage: io_hostile [--write-files DIR]\n");
        return 2;
    }
    g_root = MVR_HOSTILE_DIR;
    static const mvr_test_case cases[] = {
        TEST(magenta_controls_draw_magenta),
        TEST(traversal_buffers_are_refused),
        TEST(traversal_images_never_reach_a_pixel),
        TEST(refusals_do_not_tell_whether_outside_files_exist),
        TEST(current_directory_is_never_searched),
        TEST(spoofed_images_decode_by_signature),
        TEST(image_bombs_hit_the_budget),
        TEST(shared_files_are_read_once),
        TEST(huge_counts_and_files_are_refused_early),
        TEST(budgets_add_up),
        TEST(lying_glb_chunks_are_refused),
        TEST(node_graphs_and_deep_nesting_are_safe),
        TEST(long_values_stay_out_of_messages),
        TEST(valid_files_load),
        TEST(allowed_root_widens_access),
        TEST(read_callback_replaces_file_access),
    };
    int rc = mvr_test_run(cases, sizeof cases / sizeof cases[0]);
    mvr_context_destroy(g_ctx);
    return rc;
}
