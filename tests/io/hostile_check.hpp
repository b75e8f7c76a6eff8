// io_hostile's harness (tests/io/test_hostile.cpp holds the cases): the
// files, loads that check what holds for every load, message checks, frames
// of a loaded scene and what is in them, and a file_access.read callback.
#ifndef MVR_HOSTILE_CHECK_HPP
#define MVR_HOSTILE_CHECK_HPP

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "hostile_files.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

namespace hostile {

// The files, written under root on the first call to F().
void set_root(const std::string &root);
const files &F();

// ------------------------------------------------------------ loading

struct outcome {
    mvr_result r = MVR_OK;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    std::vector<std::string> warnings, all_logged;
    double ms = 0; /* CPU time of the load, all threads */
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

// Loads with the given options (the logger is ours) and checks what holds
// for every load: on success the loader's own accounting (a budget in
// force, a peak inside it, the warnings counted); on failure no scene; no
// message or warning longer than 1000 characters.
outcome load(mvr_test_state *t, const std::string &path, mvr_gltf_options o, const char *label = nullptr,
             bool from_memory = false);

mvr_gltf_options defaults();
mvr_gltf_options strict();
mvr_gltf_options budget(uint64_t bytes);

bool has(const std::string &s, const std::string &part);

// Loads every file whose name starts with prefix and that is to be refused
// naming something: MVR_ERROR_INVALID_ASSET, that naming in the message, no
// scene. Returns how many there were.
size_t check_refusals(mvr_test_state *t, const files &f, const std::string &prefix);

// The loader said nothing about a file outside the folder: not its size,
// not that it exists.
void no_outside_facts(mvr_test_state *t, const outcome &o, const char *what, const std::vector<std::string> &sizes);

// No message is 1000 characters or more, none quotes 200 consecutive
// characters of `value`.
void messages_short(mvr_test_state *t, const outcome &o, const std::string &value, const char *what);

// ------------------------------------------------------------ rendering

// Two stereo views (64x48) of the scene, framed on its bounds, on the
// default view path; the layers' bytes (empty without a context or scene).
std::vector<uint8_t> render(mvr_test_state *t, mvr_scene *scene, const char *what);
void release_context();

size_t count_pixels(const std::vector<uint8_t> &px, const std::function<bool(const uint8_t *)> &pred);
bool magenta(const uint8_t *p);
size_t drawn(const std::vector<uint8_t> &px); // pixels unlike the first
// The untextured quad of reference.gltf, rendered once.
const std::vector<uint8_t> &reference_pixels(mvr_test_state *t);

// A load that left image 0 out: it degraded as the contract says and the
// picture is the untextured reference's, without a magenta pixel.
void left_out_and_clean(mvr_test_state *t, const outcome &o, const char *what, bool compare_reference = true);

// ------------------------------------------------------------ file_access.read

// What a read callback serves (by URI) and what it saw.
struct reader_state {
    std::vector<std::string> uris;
    std::map<std::string, std::vector<uint8_t>> serve;
    int reads_ok = 0, releases = 0;
    uint64_t max_bytes_seen = 0;
};

// defaults() with file_access.read and .release serving from s.
mvr_gltf_options with_reader(reader_state &s);

}  // namespace hostile

#endif
