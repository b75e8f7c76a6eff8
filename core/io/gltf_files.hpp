// The one way a glTF's URIs become bytes: data: URIs decoded, everything
// else resolved against the asset's folder and confined to it (or to what the
// caller allowed), read by mvr itself within the load's budget.
#ifndef MVR_GLTF_FILES_HPP
#define MVR_GLTF_FILES_HPP

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gltf_internal.hpp"

namespace mvr_gltf {

// Bytes charged to a budget for as long as they live.
struct owned_bytes {
    std::vector<unsigned char> bytes;
    budget *mem = nullptr;
    owned_bytes() = default;
    owned_bytes(const owned_bytes &) = delete;
    owned_bytes &operator=(const owned_bytes &) = delete;
    ~owned_bytes()
    {
        if (mem)
            mem->release(bytes.size());
    }
};
using shared_bytes = std::shared_ptr<const owned_bytes>;

// A URI read: its bytes, a key that is equal for two URIs naming the same
// file (empty for data: URIs), and the media type a data: URI declares.
struct read_result {
    shared_bytes data;
    std::string key;
    std::string media_type;
    bool fresh = false;   // read now (not another URI's bytes shared)
};

// Percent-decodes (RFC 3986, 2.1); false on a malformed escape, or on a NUL
// unless allow_nul (data: URIs carry bytes; a path never holds a NUL).
bool percent_decode(const std::string &in, std::string *out, bool allow_nul);

class file_resolver {
public:
    // base_dir: the asset's folder ("" with allow_files false = memory load
    // without a folder: external files are refused).
    file_resolver(const std::string &base_dir, bool allow_files, const mvr_gltf_file_access &access,
                  uint64_t max_file_bytes, budget &mem);
    ~file_resolver();
    file_resolver(const file_resolver &) = delete;
    file_resolver &operator=(const file_resolver &) = delete;
    // Reads what `uri` (as written in the file) names; `what` names it in
    // messages ("buffers[2].uri"). Refusals, missing files and the budget
    // throw load_error. shared: keep the bytes for other URIs naming the
    // same file (buffers); images are decoded once by key instead.
    read_result read(const std::string &uri, const std::string &what, bool shared);

    // A folder a file may lie under: its real path and a descriptor opened
    // once, from which every walk starts.
    struct root_dir {
        std::string path;
        int fd = -1;
    };

private:
    void open_roots();
    // A descriptor of what a decoded relative path names (not yet known to
    // be a regular file), opened by walking from a root's descriptor one
    // component at a time (gltf_files.cpp); the caller closes it.
    int open_confined(const std::string &decoded, const std::string &uri, const std::string &what);
    read_result read_data_uri(const std::string &uri, const std::string &what);
    shared_bytes read_fd(int fd, uint64_t size, const std::string &uri, const std::string &what);
    shared_bytes read_callback(const std::string &decoded, const std::string &uri, const std::string &what);

    std::string base_;
    bool allow_files_;
    mvr_gltf_file_access access_;
    uint64_t max_file_bytes_;
    budget &mem_;
    std::vector<root_dir> roots_;   // the asset's folder first, then allowed_root
    bool roots_ready_ = false;
    std::map<std::string, shared_bytes> cache_;
};

}  // namespace mvr_gltf

#endif
