// Replays the fuzz target over a corpus without libFuzzer (any compiler, under
// ctest): the glTF test corpus, written fresh here, plus any directories given.
// A crash or sanitizer report fails the test.
#include <dirent.h>
#include <sys/stat.h>

#include <cstdio>
#include <string>
#include <vector>

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
    unsigned count = 0;
    replay_dir(dir, &count);
    for (int i = 2; i < argc; ++i)
        replay_dir(argv[i], &count);
    std::printf("fuzz_replay: %u files (%zu feature, %zu broken, with truncations) replayed\n", count,
                c.features.size(), c.broken_files.size());
    std::printf("%u passed, 0 failed\n", count);
    return count >= c.features.size() + c.broken_files.size() ? 0 : 1;
}
