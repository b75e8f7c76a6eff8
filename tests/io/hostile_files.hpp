// io_hostile's files: hostile glTF files (traversal, spoofed images, bombs,
// lying GLB chunks, deep graphs, long values, ...) and the valid ones beside
// them, written into ROOT/asset with the outside files they aim at, and the
// index ROOT/index.tsv (file, what it is, what the loader must do).
// tests/io/test_hostile.cpp checks the loader against them; `io_hostile
// --write-files DIR` writes them for scripts/hostile_rss.
#ifndef MVR_HOSTILE_FILES_HPP
#define MVR_HOSTILE_FILES_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hostile {

// Outside files have distinctive sizes: a message that leaks a fact about
// them (e.g. "File size mismatch ... 30012") is caught by these numbers.
const size_t OUTSIDE_BIN_SIZE = 30012, OUTSIDE_PNG_SIZE = 40961;

// One way of spelling a URI that leaves the asset folder.
struct spelling {
    std::string label;
    std::string pattern;  // @ = the outside file's name, # = an inside file's name
    bool may_be_missing;  // a name that stays inside the folder on POSIX: MVR_ERROR_IO is fine too
    std::string uri(const char *outside, const char *inside) const;
};

struct hostile_file {
    std::string name; // in DIR/asset
    std::string what;
    std::string expect;
    // for files refused with MVR_ERROR_INVALID_ASSET by what they are (the
    // skin / morph / animation ones): a part of the message naming the object
    std::string refused_naming;
};

struct files {
    std::string root, asset;
    std::vector<hostile_file> list;
    std::vector<spelling> spellings;
    std::string long_value;      // 1.5 MB of letters, in the long_* files
    std::string long_b64_value;  // 50 KB of base64 letters, in the bad data URIs
    std::string path(const std::string &name) const { return asset + "/" + name; }
    // Writes DIR/asset/name and lists it in the index.
    void text(const std::string &name, const std::string &content, const std::string &what, const std::string &expect,
              const std::string &refused_naming = "");
    void bytes(const std::string &name, const std::vector<uint8_t> &b, const std::string &what,
               const std::string &expect);
};

// Writes every file under root (made if missing); throws on failure.
files write_all(const std::string &root);

// `io_hostile --write-files DIR`: writes the files, says where; the exit status.
int write_files_command(const char *dir);

}  // namespace hostile

#endif
