// Replays the fuzz target over a corpus without libFuzzer (any compiler, under
// ctest): the glTF test corpus and the seeds with external URIs
// (fuzz_files.hpp), written fresh here, plus any directories given. A crash
// or sanitizer report fails the test, and so does a seed whose URIs all name
// files inside the target's base_dir and that does not load without a
// warning (a missing image only warns): the fuzzer's file access would
// otherwise go unexercised.
#include <dirent.h>
#include <sys/stat.h>

#include <cstdio>
#include <string>
#include <vector>

#include "fuzz_files.hpp"
#include "fuzz_gltf.hpp"
#include "gltf_gen.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void replay_dir(const std::string &dir, unsigned *count)
{
    DIR *d = opendir(dir.c_str());
    if (!d)
        return;
    while (dirent *e = readdir(d)) {
        std::string path = dir + "/" + e->d_name;
        struct stat sb;
        if (e->d_name[0] == '.' || stat(path.c_str(), &sb) != 0 || !S_ISREG(sb.st_mode))
            continue;
        std::vector<uint8_t> bytes = gen::read_file(path);
        LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
        // and every prefix length that cuts a structure: the loader sees truncations too
        for (size_t cut = 1; cut < bytes.size(); cut = cut * 2 + 7)
            LLVMFuzzerTestOneInput(bytes.data(), cut);
        ++*count;
    }
    closedir(d);
}

int main(int argc, char **argv)
{
    std::string dir = argc > 1 ? argv[1] : "fuzz_corpus";
    mkdir(dir.c_str(), 0777);
    gen::corpus c = gen::write_corpus(dir);
    std::vector<fuzz::seed> seeds = fuzz::write_seeds(dir);
    unsigned failed = 0;
    for (const fuzz::seed &s : seeds) {
        std::vector<uint8_t> bytes = gen::read_file(s.path);
        mvr_gltf_info info = {};
        mvr_result r = fuzz_gltf_load(bytes.data(), bytes.size(), &info);
        std::printf("  %-28s %s, %u warnings\n", s.path.substr(s.path.find_last_of('/') + 1).c_str(),
                    mvr_result_name(r), info.warnings);
        if (s.inside && (r != MVR_OK || info.warnings)) {
            std::printf("  FAIL: its URIs name files in %s: it must load, image included\n", fuzz::base_dir().c_str());
            ++failed;
        }
    }
    unsigned count = 0;
    replay_dir(dir, &count);
    for (int i = 2; i < argc; ++i)
        replay_dir(argv[i], &count);
    std::printf("fuzz_replay: %u files (%zu feature, %zu with nothing to draw, %zu broken, %zu seeds with external "
                "URIs, with truncations) replayed\n",
                count, c.features.size(), c.nothing_to_draw.size(), c.broken_files.size(), seeds.size());
    std::printf("%u passed, %u failed\n", count, failed);
    return !failed && count >= c.features.size() + c.nothing_to_draw.size() + c.broken_files.size() + seeds.size() ? 0 : 1;
}
