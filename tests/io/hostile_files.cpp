// io_hostile's files (see hostile_files.hpp), made of the pieces in
// hostile_docs.cpp.
#include "hostile_files.hpp"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "hostile_accessors.hpp"
#include "hostile_anim.hpp"
#include "hostile_codecs.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2_files.hpp"
#include "hostile_variants.hpp"
#include "hostile_material_ext.hpp"

namespace hostile {

using gen::json_string;

// ------------------------------------------------------------ the files

std::string spelling::uri(const char *outside, const char *inside) const
{
    return replace_all(replace_all(pattern, "@", outside), "#", inside);
}

void files::text(const std::string &name, const std::string &content, const std::string &what,
                 const std::string &expect, const std::string &refused_naming)
{
    write_text(path(name), content);
    list.push_back({name, what, expect, refused_naming});
}

void files::bytes(const std::string &name, const std::vector<uint8_t> &b, const std::string &what,
                  const std::string &expect)
{
    write_bytes(path(name), b.data(), b.size());
    list.push_back({name, what, expect, ""});
}

static void relink(const std::string &target, const std::string &link)
{
    unlink(link.c_str());
    if (symlink(target.c_str(), link.c_str()) != 0)
        throw std::runtime_error("cannot create symlink " + link);
}

static void sparse_file(const std::string &path, uint64_t size)
{
    int fd = open(path.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    if (fd < 0 || ftruncate(fd, off_t(size)) != 0) {
        if (fd >= 0)
            close(fd);
        throw std::runtime_error("cannot create sparse " + path);
    }
    close(fd);
}

static std::vector<uint8_t> float_colours(float r, float g, float b, size_t pad_to)
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
        f.text("trav_img_" + s.label + ".gltf", textured_doc("{\"uri\":" + json_string(img_uri) + "}").json(),
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
            d.buffer_views[size_t(v)] =
                replace_all(d.buffer_views[size_t(v)], "\"buffer\":0", "\"buffer\":" + std::to_string(v));
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
        std::vector<std::string> images;
        for (int i = 0; i < 3; ++i) {
            std::string name = "big2k_" + std::to_string(i) + ".png";
            write_bytes(f.asset + "/" + name, big.data(), big.size());
            images.push_back("{\"uri\":\"" + name + "\"}");
        }
        f.text("images_2k_x3.gltf", image_row_doc(images).json(),
               "three distinct 2048x2048 PNGs (16 MiB each decoded)",
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
        d.add(d.buffer_views, "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":64}");
        int colour = put_accessor(d, int(d.buffer_views.size()) - 1, FLOAT, 4, "VEC4");
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
    f.text("long_image_uri.gltf", textured_doc("{\"uri\":" + json_string(L + ".png") + "}").json(),
           "image 0 uri 1.5 MB long",
           "loads, images[0] left out, warning short");
    {
        doc d = textured_doc("", false);
        d.nodes[0] = "{\"mesh\":0,\"name\":" + json_string(L) + "}";
        d.meshes[0] = replace_all(d.meshes[0], "{\"primitives\"", "{\"name\":" + json_string(L) + ",\"primitives\"");
        f.text("long_names.gltf", d.json(), "node and mesh names 1.5 MB long", "loads");
        doc e = textured_doc("", false);
        e.ext_required = e.ext_used;
        e.ext_required.push_back(L);
        e.ext_used.push_back(L);
        f.text("long_ext_required.gltf", e.json(), "a required extension named by 1.5 MB", "UNSUPPORTED, message short");
        doc u = textured_doc("", false);
        u.ext_used.push_back(L);
        f.text("long_ext_used.gltf", u.json(), "an optional extension named by 1.5 MB", "loads, warning short");
        doc c = textured_doc("", false);
        c.cameras.push_back("{\"type\":" + json_string(L) + "}");
        f.text("long_camera_type_unused.gltf", c.json(), "an unused camera of type (1.5 MB)", "loads, warning short");
        c.nodes.push_back("{\"camera\":0}");
        c.scenes[0] = "{\"nodes\":[0,1]}";
        f.text("long_camera_type_used.gltf", c.json(), "a used camera of type (1.5 MB)", "refused naming cameras[0], short");
        doc m = textured_doc("{\"uri\":\"shared.png\",\"mimeType\":" + json_string(L) + "}");
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
        std::vector<std::string> images;
        for (const char *uri : {"/abs/x.png", "http://127.0.0.1:1/x.png", "tex%20ture.png?v=2#f"})
            images.push_back("{\"uri\":" + json_string(uri) + "}");
        f.text("widen_read_callback_refused.gltf", image_row_doc(images).json(), "images /abs/x.png, http://..., tex%20ture.png?v=2#f",
               "file_access.read sees only 'tex ture.png'");
        doc e = textured_doc("{\"uri\":\"%2e%2e/x.png\"}");
        f.text("widen_read_callback_dotdot.gltf", e.json(), "image %2e%2e/x.png",
               "file_access.read receives ../x.png (confinement is the caller's)");
    }

    anim_files(f);
    codec_files(f);   // hostile_codecs.cpp: compressed geometry, extension messages
    variant_files(f); // hostile_variants.cpp: KHR_materials_variants
    material_ext_files(f); // hostile_material_ext.cpp: the PBR extensions
    ktx2_files(f);
    accessor_files(f); // hostile_accessors.cpp: offsets, sparse indices and counts

    std::string index = "file\twhat\texpect\n";
    for (const auto &h : f.list)
        index += h.name + "\t" + h.what + "\t" + h.expect + "\n";
    write_text(R + "/index.tsv", index);
    return f;
}

int write_files_command(const char *dir)
{
    try {
        files f = write_all(dir);
        std::printf("io_hostile: %zu hostile files in %s (listed in %s/index.tsv)\n", f.list.size(), f.asset.c_str(),
                    f.root.c_str());
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "io_hostile: %s\n", e.what());
        return 1;
    }
}

}  // namespace hostile
