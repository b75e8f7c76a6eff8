// io_hostile's race against the resolver (see hostile_race.hpp). The buffer
// holds one triangle's positions; the outside file's are 1000 units away, so
// the scene's bounds tell, without GL, which file a load read. A resolver
// that checks a path and then opens it by name again (realpath, then open)
// reads the outside file when the swap falls between the two.
#include "hostile_race.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"

namespace hostile {

namespace {

const float outside_x = 1000.0f;   // the outside triangle's x; the inside one's are 0 and 1

std::string triangle_gltf(const std::string &uri)
{
    return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
           "\"min\":[0,0,0],\"max\":[1,1,0]}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
           "\"buffers\":[{\"byteLength\":36,\"uri\":\"" + uri + "\"}]}";
}

void write_triangle(const std::string &path, float x0)
{
    const float p[9] = {x0, 0, 0, x0 + 1, 0, 0, x0, 1, 0};
    write_bytes(path, p, sizeof p);
}

enum class read_from { refused, inside, outside, other };

read_from load_once(const std::string &gltf, const char *allowed_root)
{
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    o.file_access.allowed_root = allowed_root;
    mvr_scene *scene = nullptr;
    mvr_error err;
    if (mvr_gltf_load_file(gltf.c_str(), &o, &scene, nullptr, &err) != MVR_OK)
        return read_from::refused;
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    mvr_scene_destroy(scene);
    if (info.bounds_max[0] >= double(outside_x))
        return read_from::outside;
    return info.bounds_max[0] == 1.0 ? read_from::inside : read_from::other;
}

// Swaps DIR/asset/pos.bin between a hard link of the inside file and a
// symbolic link to the outside one, each put in place by rename(2), so the
// name always exists; until stop.
void swap_until(const std::string &asset, const std::string &outside, const std::atomic<bool> &stop, long *swaps)
{
    const std::string pos = asset + "/pos.bin", file_tmp = asset + "/.swap_file", link_tmp = asset + "/.swap_link";
    const std::string inside = asset + "/inside_real.bin";
    while (!stop.load(std::memory_order_relaxed)) {
        unlink(link_tmp.c_str());
        if (symlink(outside.c_str(), link_tmp.c_str()) == 0 && rename(link_tmp.c_str(), pos.c_str()) == 0)
            ++*swaps;
        unlink(file_tmp.c_str());
        if (link(inside.c_str(), file_tmp.c_str()) == 0 && rename(file_tmp.c_str(), pos.c_str()) == 0)
            ++*swaps;
    }
}

}  // namespace

long race_loads()
{
    const char *env = std::getenv("MVR_HOSTILE_RACE_LOADS");
    long n = env ? std::strtol(env, nullptr, 10) : 0;
    return n >= 1 && n <= 10000000 ? n : 20000;
}

void symlink_swaps_never_read_outside(mvr_test_state *t)
{
    const std::string dir = F().root + "/race", asset = dir + "/asset", outside = dir + "/outside.bin";
    mkdirs(asset);
    write_triangle(outside, outside_x);
    write_triangle(asset + "/inside_real.bin", 0);
    const std::string gltf = asset + "/race.gltf";
    write_text(gltf, triangle_gltf("pos.bin"));
    const std::string pos = asset + "/pos.bin";

    // controls: the detector tells the two files apart
    unlink(pos.c_str());
    CHECK_MSG(t, link((asset + "/inside_real.bin").c_str(), pos.c_str()) == 0, "cannot link %s", pos.c_str());
    CHECK_MSG(t, load_once(gltf, nullptr) == read_from::inside, "race.gltf with pos.bin inside: not read as inside");
    unlink(pos.c_str());
    CHECK_MSG(t, symlink(outside.c_str(), pos.c_str()) == 0, "cannot symlink %s", pos.c_str());
    CHECK_MSG(t, load_once(gltf, nullptr) == read_from::refused, "race.gltf with pos.bin a link out: not refused");
    CHECK_MSG(t, load_once(gltf, dir.c_str()) == read_from::outside,
              "race.gltf with pos.bin a link out and allowed_root = its target's folder: the outside bytes not seen");

    const long loads = race_loads();
    long counts[4] = {0, 0, 0, 0}, swaps = 0;
    std::atomic<bool> stop(false);
    std::thread swapper(swap_until, asset, outside, std::cref(stop), &swaps);
    for (long i = 0; i < loads; ++i)
        ++counts[int(load_once(gltf, nullptr))];
    stop = true;
    swapper.join();
    std::printf("  %ld loads during %ld swaps: %ld read the inside file, %ld refused, %ld read the OUTSIDE file, "
                "%ld other\n",
                loads, swaps, counts[int(read_from::inside)], counts[int(read_from::refused)],
                counts[int(read_from::outside)], counts[int(read_from::other)]);
    CHECK_MSG(t, counts[int(read_from::outside)] == 0, "LEAK: %ld of %ld loads read the file outside the folder",
              counts[int(read_from::outside)], loads);
    CHECK_MSG(t, counts[int(read_from::other)] == 0, "%ld loads read neither file", counts[int(read_from::other)]);
    CHECK_MSG(t, swaps > 0, "the swapping thread swapped nothing");
    unlink(pos.c_str());
}

// The walk that replaced realpath-then-open keeps the links that stay inside
// the folder (relative, absolute, through a folder, chained, climbing with
// ".." and coming back) and refuses those that leave it, unless
// allowed_root admits where they lead.
void symlinks_inside_the_folder_still_resolve(mvr_test_state *t)
{
    const std::string dir = F().root + "/links", asset = dir + "/asset", outside = dir + "/outside.bin";
    mkdirs(asset + "/sub");
    write_triangle(outside, outside_x);
    write_triangle(asset + "/inside_real.bin", 0);
    write_triangle(asset + "/sub/real.bin", 0);
    struct link_case {
        const char *name, *target;   // target "@" = the asset folder's absolute path
    };
    const link_case links[] = {{"rel.bin", "sub/real.bin"},       {"sub/up.bin", "../inside_real.bin"},
                               {"abs.bin", "@/sub/real.bin"},     {"dir", "sub"},
                               {"chain.bin", "rel.bin"},          {"sub/out.bin", "../../outside.bin"},
                               {"abs_out.bin", "@/../outside.bin"}, {"loop_a", "loop_b"},
                               {"loop_b", "loop_a"},             {"dir_up", ".."}};
    for (const link_case &l : links) {
        std::string at = asset + "/" + l.name, target = replace_all(l.target, "@", asset);
        unlink(at.c_str());
        CHECK_MSG(t, symlink(target.c_str(), at.c_str()) == 0, "cannot symlink %s", at.c_str());
    }
    struct expect {
        const char *uri;
        read_from without_root, with_root;   // with allowed_root = dir
    };
    const read_from in = read_from::inside, out = read_from::outside, no = read_from::refused;
    const expect cases[] = {{"rel.bin", in, in},          {"sub/up.bin", in, in},     {"abs.bin", in, in},
                            {"dir/real.bin", in, in},     {"dir/up.bin", in, in},     {"chain.bin", in, in},
                            {"dir_up/asset/rel.bin", no, in},
                            {"sub/out.bin", no, out},     {"abs_out.bin", no, out},   {"loop_a", no, no},
                            {"dir", no, no}};
    for (const expect &e : cases) {
        const std::string gltf = asset + "/links.gltf";
        write_text(gltf, triangle_gltf(e.uri));
        read_from a = load_once(gltf, nullptr), b = load_once(gltf, dir.c_str());
        CHECK_MSG(t, a == e.without_root && b == e.with_root, "%s: read as %d / %d with allowed_root, expected %d / %d",
                  e.uri, int(a), int(b), int(e.without_root), int(e.with_root));
    }
}

}  // namespace hostile
