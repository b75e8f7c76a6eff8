// io_hostile's harness (see hostile_check.hpp).
#include "hostile_check.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gltf_gen.hpp"
#include "gltf_render.hpp"
#include "hostile_docs.hpp"

namespace hostile {

static std::string g_root;

void set_root(const std::string &root)
{
    g_root = root;
}

const files &F()
{
    static files f = write_all(g_root);
    return f;
}

// ------------------------------------------------------------ loading

static void collect(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    auto *o = static_cast<outcome *>(user);
    o->all_logged.push_back(message);
    if (level == MVR_LOG_WARNING)
        o->warnings.push_back(message);
}

/* The process's CPU time (every thread), not wall time: the time bounds
 * catch a loader that works too hard, and must not fail because another
 * process loaded the machine (graph_chain_100k took 5.1 s of wall time
 * on 2 cores shared with two builds). */
static double cpu_ms()
{
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static long max_rss_kb()
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

outcome load(mvr_test_state *t, const std::string &path, mvr_gltf_options o, const char *label,
             bool from_memory)
{
    outcome out;
    o.logger.fn = collect;
    o.logger.user_data = &out;
    o.logger.level = MVR_LOG_DEBUG;
    mvr_error err;
    std::memset(&err, 0, sizeof err);
    long rss0 = max_rss_kb();
    double t0 = cpu_ms();
    if (from_memory) {
        std::vector<uint8_t> bytes = gen::read_file(path);
        out.r = mvr_gltf_load_memory(bytes.data(), bytes.size(), &o, &out.scene, &out.info, &err);
    } else {
        out.r = mvr_gltf_load_file(path.c_str(), &o, &out.scene, &out.info, &err);
    }
    out.ms = cpu_ms() - t0;
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

size_t check_refusals(mvr_test_state *t, const files &f, const std::string &prefix)
{
    size_t refused = 0;
    for (const auto &h : f.list) {
        if (h.name.rfind(prefix, 0) != 0 || h.refused_naming.empty())
            continue;
        ++refused;
        const char *n = h.name.c_str();
        outcome o = load(t, f.path(h.name), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET, "%s: %s, expected MVR_ERROR_INVALID_ASSET (%s)", n,
                  mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, has(o.msg, h.refused_naming), "%s: the message lacks '%s': %s", n, h.refused_naming.c_str(),
                  o.msg.c_str());
        CHECK_MSG(t, o.scene == nullptr, "%s: a scene on failure", n);
    }
    return refused;
}

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
static bool quotes_value(const std::string &m, const std::string &value)
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

static mvr_context *g_ctx;
static bool g_ctx_failed;

static mvr_context *context(mvr_test_state *t)
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

std::vector<uint8_t> render(mvr_test_state *t, mvr_scene *scene, const char *what)
{
    mvr_context *ctx = context(t);
    if (!ctx || !scene)
        return {};
    static std::string cache;
    cache = F().root + "/program_cache";
    mkdirs(cache);
    return gltf_render::two_layers(t, ctx, scene, MVR_VIEW_PATH_AUTO, what, cache.c_str());
}

void release_context()
{
    mvr_context_destroy(g_ctx);
    g_ctx = nullptr;
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

void left_out_and_clean(mvr_test_state *t, const outcome &o, const char *what, bool compare_reference)
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

// ------------------------------------------------------------ file_access.read

static mvr_result read_cb(const char *uri, uint64_t max_bytes, void **out, size_t *size, void *user)
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

static void release_cb(void *data, void *user)
{
    static_cast<reader_state *>(user)->releases++;
    std::free(data);
}

mvr_gltf_options with_reader(reader_state &s)
{
    mvr_gltf_options o = defaults();
    o.file_access.read = read_cb;
    o.file_access.release = release_cb;
    o.file_access.user_data = &s;
    return o;
}

}  // namespace hostile
