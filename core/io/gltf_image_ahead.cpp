// Images decoded ahead on a small pool of threads (gltf_image_ahead.hpp says
// what is decoded, when, and how it stays within the budget).
#include "gltf_image_ahead.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <thread>
#include <vector>

namespace mvr_gltf {

namespace {

// One image to decode: where its bytes are and what decode_image would pass.
struct job {
    std::string key;
    const unsigned char *bytes = nullptr;
    uint64_t size = 0;
    std::string mime;
    uint64_t charge = 0;   // the budget decode_image gives the decoder
    uint64_t rgba = 0;     // what the result holds
    mvr_image_data out{};
    bool ok = false;
};

// The threads to use: MVR_DECODE_THREADS, else the online CPUs, at most 8
// (five 2048x2048 JPEGs keep 5 busy; more only adds memory held at once).
unsigned thread_count()
{
    const char *env = std::getenv("MVR_DECODE_THREADS");
    if (env && *env) {
        char *end = nullptr;
        long n = std::strtol(env, &end, 10);
        if (end && *end == '\0' && n >= 1 && n <= 64)
            return unsigned(n);
    }
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    return unsigned(std::clamp(cpus, 1L, 8L));
}

bool png_or_jpeg(const unsigned char *p, uint64_t n)
{
    static const unsigned char png_sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    return (n >= 8 && std::memcmp(p, png_sig, 8) == 0) || (n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF);
}

// The images textures name (source and the extensions' sources), once each.
std::set<int> texture_images(const tinygltf::Model &m)
{
    std::set<int> out;
    for (const tinygltf::Texture &t : m.textures) {
        if (t.source >= 0)
            out.insert(t.source);
        for (const char *e : {"EXT_texture_webp", "KHR_texture_basisu"}) {
            auto it = t.extensions.find(e);
            if (it != t.extensions.end() && it->second.IsObject() && it->second.Has("source") &&
                it->second.Get("source").IsInt())
                out.insert(it->second.Get("source").GetNumberAsInt());
        }
    }
    return out;
}

// The job for image i, where its bytes are at hand and decode_image would
// decode it through mvr_image with this charge; false otherwise (decode_image
// then does all of it, and says what is wrong).
bool make_job(context &cx, const tinygltf::Model &m, int i, job *j)
{
    if (i < 0 || size_t(i) >= cx.res.images.size())
        return false;
    const image_source &src = cx.res.images[size_t(i)];
    int view = src.buffer_view;
    if (view < 0 || size_t(view) >= m.bufferViews.size() || cx.res.meshopt_views.count(view))
        return false;
    int buf = m.bufferViews[size_t(view)].buffer;
    if (buf < 0 || size_t(buf) >= cx.res.buffers.size())
        return false;
    const buffer_source &b = cx.res.buffers[size_t(buf)];
    if (!b.loaded && !(cx.res.glb && buf == 0 && !b.has_uri && cx.res.bin))
        return false;   // its file is read in order, by the loader
    uint64_t stride = 0;
    try {
        j->bytes = view_bytes(cx, view, &j->size, &stride, "images[" + std::to_string(i) + "]");
    } catch (const load_error &) {
        return false;
    }
    j->mime = src.mime_type;
    if (j->size == 0 || j->mime == "image/ktx2" || !png_or_jpeg(j->bytes, j->size))
        return false;
    mvr_image_header h;
    mvr_error err;
    uint64_t cost = 0;
    if (mvr_image_probe(j->bytes, size_t(j->size), j->mime.c_str(), &h, &err) != MVR_OK ||
        h.width > cx.limits.max_image_dimension || h.height > cx.limits.max_image_dimension ||
        mvr_image_decode_cost(j->bytes, size_t(j->size), j->mime.c_str(), &cost, &err) != MVR_OK)
        return false;
    j->rgba = uint64_t(h.width) * h.height * 4;
    j->charge = std::max(cost, 2 * j->rgba);
    j->key = "bufferView:" + std::to_string(view);
    return true;
}

}  // namespace

// The results not yet taken, each charged to the budget (its rgba) until
// taken or dropped.
struct image_ahead {
    context *cx = nullptr;
    budget *mem = nullptr;
    std::map<std::string, job> ready;

    void drop_all()
    {
        if (!ready.empty() && cx)
            cx->debug(std::to_string(ready.size()) + " images decoded ahead dropped (the budget needs their memory); "
                      "decoded again when needed");
        for (auto &r : ready) {
            mvr_image_free(&r.second.out);
            mem->release(r.second.rgba);
        }
        ready.clear();
    }
    ~image_ahead()
    {
        cx = nullptr;   // no note: the load is over
        drop_all();
        mem->drop_spare = nullptr;
    }
};

std::shared_ptr<image_ahead> decode_images_ahead(context &cx, const tinygltf::Model &m)
{
    unsigned threads = thread_count();
    if (threads < 2)
        return nullptr;
    std::vector<job> jobs;
    std::set<std::string> keys;
    uint64_t total = 0;
    for (int i : texture_images(m)) {
        job j;
        if (!make_job(cx, m, i, &j) || keys.count(j.key))
            continue;
        // what all of them hold at once must fit beside what the load holds
        if (j.charge > cx.mem.limit || total > cx.mem.limit - j.charge ||
            cx.mem.used > cx.mem.limit - (total + j.charge))
            continue;
        total += j.charge;
        keys.insert(j.key);
        jobs.push_back(std::move(j));
    }
    if (jobs.size() < 2)
        return nullptr;
    cx.mem.charge(total, "images decoded ahead");   // fits: checked above
    std::atomic<size_t> next{0};
    auto work = [&jobs, &next, &cx] {
        for (size_t k = next++; k < jobs.size(); k = next++) {
            job &j = jobs[k];
            mvr_error err;
            j.ok = mvr_image_decode_within(j.bytes, size_t(j.size), j.mime.c_str(), cx.limits.max_image_dimension,
                                           j.charge, &j.out, &err) == MVR_OK;
        }
    };
    std::vector<std::thread> pool;
    try {
        for (unsigned t = 1; t < threads && t < jobs.size(); ++t)
            pool.emplace_back(work);
    } catch (const std::exception &) {
        // fewer threads than asked (the system refused one): the rest still run
    }
    work();
    for (std::thread &t : pool)
        t.join();
    cx.mem.release(total);
    cx.debug(std::to_string(jobs.size()) + " images decoded ahead on " +
             std::to_string(std::min<size_t>(threads, jobs.size())) + " threads");
    auto ahead = std::make_shared<image_ahead>();
    ahead->cx = &cx;
    ahead->mem = &cx.mem;
    for (job &j : jobs) {
        if (!j.ok)
            continue;   // decoded again in order, where its error is reported
        cx.mem.charge(j.rgba, "images decoded ahead");   // within what was just released
        std::string key = j.key;
        ahead->ready.emplace(key, std::move(j));
    }
    image_ahead *a = ahead.get();
    cx.mem.drop_spare = [a] { a->drop_all(); };
    return ahead;
}

bool take_ahead(image_ahead *ahead, const std::string &key, const unsigned char *bytes, uint64_t size,
                uint64_t charge, mvr_image_data *out)
{
    if (!ahead)
        return false;
    auto it = ahead->ready.find(key);
    if (it == ahead->ready.end())
        return false;
    job &j = it->second;
    bool same = j.bytes == bytes && j.size == size && j.charge == charge;
    if (same)
        *out = j.out;
    else
        mvr_image_free(&j.out);
    ahead->mem->release(j.rgba);
    ahead->ready.erase(it);
    return same;
}

}  // namespace mvr_gltf
