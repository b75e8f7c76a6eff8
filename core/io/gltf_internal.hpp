// Shared by the glTF loader's files: the load context and validated reads.
#ifndef MVR_GLTF_INTERNAL_HPP
#define MVR_GLTF_INTERNAL_HPP

#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mvr/mvr_gltf.h"

namespace mvr_gltf {

// A refusal with the result to return and a message naming the object.
struct load_error : std::runtime_error {
    mvr_result result;
    load_error(mvr_result r, const std::string &msg) : std::runtime_error(msg), result(r) {}
};

[[noreturn]] inline void refuse(const std::string &msg)
{
    throw load_error(MVR_ERROR_INVALID_ASSET, msg);
}

// A value from the file, quoted for a message: at most 80 characters
// (longer values end in "..."), control characters escaped.
std::string quote(const std::string &value);
// A JSON member name from the file for a message path ("attributes." + it):
// as it is if it is a plain identifier of at most 64 characters, else quoted.
std::string key_name(const std::string &key);

struct caps {
    uint64_t max_file_bytes, max_vertices, max_indices;
    uint32_t max_image_dimension, max_nodes, max_images;
};

// The load's memory budget: every allocation the file can make large is
// charged before it is made and released when it is freed.
struct budget {
    uint64_t limit = 0, used = 0, peak = 0;
    void charge(uint64_t bytes, const std::string &what);   // refuses (out of memory) past the limit
    // What a charge past the limit drops first: images decoded ahead and not
    // yet taken (gltf_image_ahead.hpp), which the loader can decode again.
    std::function<void()> drop_spare;
    void release(uint64_t bytes) { used = bytes > used ? 0 : used - bytes; }
};

// Bytes charged to the budget while the object lives.
struct charged {
    budget *b = nullptr;
    uint64_t bytes = 0;
    charged() = default;
    charged(budget &bud, uint64_t n, const std::string &what) : b(&bud), bytes(n) { bud.charge(n, what); }
    charged(const charged &) = delete;
    charged &operator=(const charged &) = delete;
    ~charged() { if (b) b->release(bytes); }
};

// Where a buffer's or an image's bytes come from, as the JSON says (mvr's
// pre-pass takes these out before tinygltf parses the rest: mvr reads every
// byte itself, and only what the scene uses).
struct byte_span {
    const unsigned char *data = nullptr;
    uint64_t size = 0;
};

struct buffer_source {
    bool has_uri = false;
    std::string uri;
    uint64_t byte_length = 0;
    bool meshopt_fallback = false;        // extensions.EXT_meshopt_compression.fallback: true
    bool loaded = false;
    byte_span span;                       // byteLength bytes, once read
    std::shared_ptr<const void> owner;    // keeps them (shared by buffers naming one file)
};

struct image_source {
    bool has_uri = false;
    std::string uri;
    int buffer_view = -1;
    std::string mime_type;
};

// EXT_meshopt_compression on a bufferView, as the pre-pass read it from the
// JSON (tinygltf narrows integers to int); checked when the view is read.
struct meshopt_source {
    std::string problem;                  // what is wrong with the extension's JSON ("" if nothing)
    int64_t buffer = -1, byte_offset = 0, byte_length = 0, byte_stride = 0, count = 0;
    std::string mode, filter = "NONE";
};

// KHR_draco_mesh_compression on a primitive, as the pre-pass read it.
struct draco_source {
    std::string problem;
    int64_t buffer_view = -1;
    std::vector<std::pair<std::string, int64_t>> attributes;   // glTF attribute name -> Draco unique id
};

// KHR_materials_variants as the pre-pass read it (tinygltf narrows its
// integers to int, and drops nulls and empty objects from arrays, which
// would shift the indices that name variants): the root's variant names,
// and per primitive its mappings; problem: what is wrong with the JSON
// ("" if nothing), reported when the root or the primitive is read.
struct variants_source {
    bool present = false;                 // extensions.KHR_materials_variants exists
    std::string problem;
    std::vector<std::string> names;
};

struct variant_mapping_source {
    std::vector<int64_t> variants;
    int64_t material = -1;
};

struct primitive_variants_source {
    std::string problem;
    std::vector<variant_mapping_source> mappings;
};

struct resources {
    std::vector<buffer_source> buffers;
    std::map<int, meshopt_source> meshopt_views;                   // by bufferView
    std::map<std::pair<int, int>, draco_source> draco_primitives;  // by (mesh, primitive)
    variants_source variants;
    std::map<std::pair<int, int>, primitive_variants_source> variant_primitives;  // by (mesh, primitive)
    std::vector<std::string> extensions_required, extensions_used;
    std::vector<image_source> images;
    // accessors without a bufferView (zeros): tinygltf 2.7 refuses such an
    // index accessor, so the pre-pass gives them a placeholder view it drops again
    std::vector<int> viewless_accessors;
    bool placeholder_view = false;    // the last bufferView and buffer are the placeholder's
    // cameras tinygltf would refuse to parse (unknown type, missing fields):
    // replaced by a placeholder, an error only if a node uses them
    std::map<int, std::string> bad_cameras;
    // accessors[i].type strings glTF 2.0 does not define (its schema admits
    // any string): parsed as a placeholder, refused when the accessor is read
    std::map<int, std::string> unknown_accessor_types;
    const unsigned char *bin = nullptr;   // the GLB's BIN chunk (buffer 0), if any
    uint64_t bin_size = 0;
    bool glb = false;
};

class file_resolver;

// Bytes decoded at load (gltf_codecs.cpp), charged to the budget while they live.
struct decoded_bytes {
    charged charge;
    std::vector<unsigned char> bytes;
    decoded_bytes(budget &b, uint64_t n, const std::string &what) : charge(b, n, what) { bytes.resize(size_t(n)); }
};

struct context {
    const tinygltf::Model *model = nullptr;
    caps limits{};
    mvr_logger logger{};
    budget mem;
    resources res;
    file_resolver *files = nullptr;
    uint32_t warnings = 0;
    uint32_t buffers_read = 0;
    uint32_t images_missing = 0, images_decoded = 0;
    bool strict = false;                  // missing images are errors
    uint64_t vertices = 0, indices = 0;   // running totals against the caps
    uint64_t mesh_bytes = 0;              // charged for the mesh being read (released once in the scene)
    bool quantization_declared = false;   // KHR_mesh_quantization in extensionsUsed
    uint32_t channels_ignored = 0;        // animation channels left out (see gltf_animation.cpp)
    // EXT_meshopt_compression bufferViews, decoded on first use and kept for the load
    std::map<int, std::unique_ptr<decoded_bytes>> decoded_views;
    // the KHR_draco_mesh_compression primitive being read: its accessors' data
    // (the accessors' own layout, tightly packed), by accessor (see draco_scope)
    std::map<int, std::unique_ptr<decoded_bytes>> decoded_accessors;
    void warn(const std::string &msg);
    void debug(const std::string &msg);   // MVR_LOG_DEBUG, not counted as a warning
    // The byteLength bytes of buffers[index], read on first use; what names the reader.
    byte_span buffer(int index, const std::string &what);
};

// The bytes of bufferViews[view_index] after checking they lie inside their
// buffer (read on first use); stride 0 = tightly packed.
const unsigned char *view_bytes(context &cx, int view_index, uint64_t *length, uint64_t *stride,
                                const std::string &what);

// Reads accessor `index` as floats, `components` per element (the accessor's
// type must have exactly that many). Normalized integers become [0, 1] or
// [-1, 1] (glTF 2.0 3.11), others convert as they are. Every offset, stride and
// count is checked first, sparse substitution included. `what` names the use
// for messages, e.g. "meshes[3].primitives[0].attributes.NORMAL".
std::vector<float> read_floats(context &cx, int index, int components, const std::string &what,
                               uint32_t allowed_component_types);

// Reads accessor `index` as unsigned indices (SCALAR of UNSIGNED_BYTE / SHORT / INT).
std::vector<uint32_t> read_indices(context &cx, int index, const std::string &what);

// Reads a JOINTS_n accessor: VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT, not
// normalized, widened to uint16 (charged like read_floats' results).
std::vector<uint16_t> read_joints(context &cx, int index, const std::string &what);

// Whether accessor `index` (which must exist) is a normalized integer one;
// refuses an integer accessor that is not normalized where `what` needs it.
void require_normalized(context &cx, int index, const std::string &what);

// What read_floats / read_indices / read_joints charged (cx.mesh_bytes) from
// here on is released when this goes out of scope: for reads whose data the
// scene copies before the next object is read (skins, animations).
struct scoped_reads {
    context &cx;
    uint64_t start;
    explicit scoped_reads(context &c) : cx(c), start(c.mesh_bytes) {}
    scoped_reads(const scoped_reads &) = delete;
    scoped_reads &operator=(const scoped_reads &) = delete;
    ~scoped_reads()
    {
        if (cx.mesh_bytes > start)
            cx.mem.release(cx.mesh_bytes - start);
        cx.mesh_bytes = start;
    }
};

// Bit of a glTF component type in an allowed mask.
uint32_t component_bit(int component_type);
// Bytes of one component (0: not a glTF component type); components of an
// accessor type (0: not a glTF type).
uint32_t component_size(int component_type);
int type_components(int type);

// Fewer texture fetches and varyings for the same pixels, once the scene is
// loaded (core/texture_packing.c): texture coordinate set 1 read as set 0
// where the primitives repeat it, separate occlusion images packed into their
// metallic-roughness image's red channel. Returns the images packed
// (gltf_materials.cpp).
uint32_t pack_textures(context &cx, mvr_scene *scene);
// Every image a material samples, charged to the memory budget for its upload
// (named by the first glTF image that gave it; gltf_materials.cpp).
void charge_texture_uploads(context &cx, const mvr_scene *scene, const std::map<int, mvr_image_id> &images);

// ---- compressed geometry (gltf_codecs.cpp) ----

// The decoded bytes of bufferViews[view_index], which has
// EXT_meshopt_compression (res.meshopt_views): its JSON checked, the
// compressed range read from its source buffer, decoded (and filtered) into
// byteLength bytes, charged to the budget; decoded once per load.
const unsigned char *meshopt_view_bytes(context &cx, int view_index, const std::string &what);

// While it lives, the accessors of primitive `prim` of mesh `mesh` that its
// KHR_draco_mesh_compression names (attributes and indices) read the decoded
// Draco mesh instead of their bufferViews (cx.decoded_accessors); nothing if
// the primitive has no such extension. Counts, component counts, point and
// face indices are checked against the accessors before any is used.
struct draco_scope {
    context &cx;
    draco_scope(context &c, int mesh, int prim, const tinygltf::Primitive &p, const std::string &pw);
    ~draco_scope() { cx.decoded_accessors.clear(); }
    draco_scope(const draco_scope &) = delete;
    draco_scope &operator=(const draco_scope &) = delete;

private:
    void decode(int mesh, int prim, const tinygltf::Primitive &p, const std::string &pw);
};
constexpr uint32_t ANY_FLOAT = 1u << 6;

// Overflow-checked 64-bit arithmetic: refuses with the message on overflow.
uint64_t mul_checked(uint64_t a, uint64_t b, const std::string &what);
uint64_t add_checked(uint64_t a, uint64_t b, const std::string &what);

}  // namespace mvr_gltf

#endif
