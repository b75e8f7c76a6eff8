// The pieces io_hostile's files are made of (tests/io/hostile_files.cpp puts
// them together): glTF documents assembled object by object, GLB framing
// that can lie about its chunks, images (real ones, and bombs whose headers
// claim huge sizes) and small file helpers.
#ifndef MVR_HOSTILE_DOCS_HPP
#define MVR_HOSTILE_DOCS_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gltf_gen.hpp"

namespace hostile {

const uint64_t MiB = uint64_t(1) << 20, GiB = uint64_t(1) << 30;
const int FLOAT = 5126, USHORT = 5123, UINT = 5125, UBYTE = 5121, SHORT = 5122;

// ------------------------------------------------------------ small writers

std::string replace_all(std::string s, const std::string &from, const std::string &to);
void write_bytes(const std::string &path, const void *p, size_t n);
void write_text(const std::string &path, const std::string &s);
void mkdirs(const std::string &d);
// Pseudo-random letters: a value no message has any business quoting.
std::string letters(size_t n, uint32_t seed);
std::string base64_letters(size_t n, uint32_t seed);
// A solid-color image encoded by OpenImageIO ("png" RGBA or "jpg" RGB).
std::vector<uint8_t> solid_image(const char *format, int w, int h, uint8_t r, uint8_t g, uint8_t b);
// A real (small) PNG whose IHDR claims w x h, with a correct CRC: a decoder
// that trusts the header allocates w * h * 4 bytes before it finds the data short.
std::vector<uint8_t> png_bomb(uint32_t w, uint32_t h);
// A baseline JPEG whose SOF marker claims w x h.
std::vector<uint8_t> jpeg_bomb(uint16_t w, uint16_t h);

// ------------------------------------------------------------ glTF documents

// Buffers as a list (buffer 1 may name a file while buffer 0 is a data URI);
// the other lists serialised as gen::builder's are (gen::json_members).
struct doc : gen::doc_lists {
    std::vector<std::string> buffers;
    std::string extra; // raw members, each starting with ','

    std::string json() const;
    void use(const std::string &e); // adds e to extensionsUsed once
};

int put_view(doc &d, std::vector<uint8_t> &bin, int buffer, const void *p, size_t n);
int put_accessor(doc &d, int view, int ctype, long long count, const char *type, const std::string &extra = "");
// A quad facing +Z (positions with min/max, normals, uvs, u16 indices) in
// buffer `buffer` (whose bytes are `bin`); returns the primitive's JSON.
// indices: -2 = u16 indices in the buffer, -1 = none, else an accessor index.
std::string quad(doc &d, std::vector<uint8_t> &bin, int buffer, float cx, float cy, float half, int material,
                 const std::string &extra_attributes = "", int indices = -2);
void one_mesh(doc &d, const std::vector<std::string> &prims);
// Unlit, so a texture's colour reaches the pixels unchanged.
int unlit(doc &d, int texture, float r = 1, float g = 1, float b = 1);
std::string data_buffer(const std::vector<uint8_t> &bin);
std::string uri_buffer(const std::string &uri, uint64_t length);
// One textured quad: buffer 0 a data URI, image 0 = `image_json`; texture
// < 0: the same quad untextured (the reference a left-out image must equal).
doc textured_doc(const std::string &image_json, bool textured = true, float r = 1, float g = 1, float b = 1);
// A quad whose COLOR_0 (4 x VEC4 float) comes from buffer 1 = `uri`.
doc colour_doc(const std::string &uri, uint64_t byte_length);
// A row of quads (centres x = -1, 0, 1, ..., y = 0, half size 0.4), quad i
// textured by image i = images[i]; buffer 0 a data URI.
doc image_row_doc(const std::vector<std::string> &images);

// A skinned, morphed and animated quad, valid (each hostile anim_* file breaks
// one thing of it): node 0 draws mesh 0 (JOINTS_0 u8, joints 0 and 1;
// WEIGHTS_0 normalized u8; two POSITION targets; weights [0.5, 0.25]) with
// skin 0 (joints: nodes 1 and 2, inverse bind matrices) and node.weights
// [1, 0]; node 1 (a root) is node 2's parent. Animation 0 "wave": sampler 0
// translation LINEAR, 1 rotation LINEAR (normalized shorts), 2 weights STEP,
// 3 keys each at 0, 0.5, 1 s; channel k reads sampler k (nodes 1, 2, 0).
struct anim_parts {
    int joints, weights, target0, target1, ibm, times, translations, rotations, morph_weights;
    std::string primitive;   // mesh 0's primitive (with its targets)
};
doc anim_doc(anim_parts *parts = nullptr);

// ------------------------------------------------------------ GLB framing

struct chunk {
    uint32_t type;
    std::vector<uint8_t> data;
    long long length_delta = 0; // lie about the chunk's length
    bool pad = true;            // pad the data to 4 bytes (spaces for JSON)
};
const uint32_t JSON_CHUNK = 0x4E4F534Au, BIN_CHUNK = 0x004E4942u;

chunk json_chunk(const std::string &j);
std::vector<uint8_t> glb(const std::vector<chunk> &chunks, long long total_delta = 0);
// A GLB-style document: geometry (and, if png is given, the image) in `bin`
// bound to buffer 0 (uri-less).
doc glb_doc(std::vector<uint8_t> &bin, const std::vector<uint8_t> *png);

}  // namespace hostile

#endif
