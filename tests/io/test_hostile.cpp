// io_hostile: hostile glTF files, written by this test into the build tree,
// against the loader's contract for untrusted input (include/mvr/mvr_gltf.h,
// issue 16). Each file is refused with a message naming the object, or loads
// and renders safely: a file outside the asset folder never reaches a pixel,
// no message quotes more than ~80 characters of a value from the file or says
// anything about a file outside the folder, and every load stays inside its
// memory budget by its own accounting.
//
// The files: tests/io/hostile_files.cpp (made of tests/io/hostile_docs.cpp);
// the anim_*, ktx2_*, variants_*, matext_* and codec_* files, each kind with
// its case: hostile_anim.cpp, hostile_ktx2_files.cpp, hostile_variants.cpp,
// hostile_material_ext.cpp, hostile_codecs.cpp; the loads, frames and
// message checks the cases share: hostile_check.cpp.
//
//   io_hostile                    runs the cases
//   io_hostile --write-files DIR  writes the files into DIR (DIR/asset/* plus
//                                 DIR/index.tsv: file, what it is, what the
//                                 loader must do) and exits; scripts/hostile_rss
//                                 renders each through `mvr render`
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gltf_gen.hpp"
#include "hostile_accessors.hpp"
#include "hostile_anim.hpp"
#include "hostile_check.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2_files.hpp"
#include "hostile_variants.hpp"
#include "hostile_material_ext.hpp"
#include "hostile_race.hpp"

namespace {

using namespace hostile;

// ------------------------------------------------------------ cases

void magenta_controls_draw_magenta(mvr_test_state *t)
{
    const files &f = F();
    for (const char *n : {"control_magenta_image.gltf", "control_magenta_buffer.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "%s: %s", n, o.msg.c_str());
        size_t m = count_pixels(render(t, o.scene, n), magenta);
        CHECK_MSG(t, m > 200, "%s: %zu magenta pixels: the detector would miss a leak", n, m);
    }
}

void traversal_buffers_are_refused(mvr_test_state *t)
{
    const files &f = F();
    std::vector<std::string> sizes = {std::to_string(OUTSIDE_BIN_SIZE)};
    struct stat sb;
    if (stat("/etc/passwd", &sb) == 0 && sb.st_size >= 100)
        sizes.push_back(std::to_string(sb.st_size));
    std::vector<std::pair<std::string, bool>> cases;
    for (const auto &s : f.spellings)
        cases.push_back({"trav_buf_" + s.label + ".gltf", s.may_be_missing});
    cases.push_back({"trav_buf_dotdot_length.gltf", false});
    cases.push_back({"trav_buf_dotdot_nonexistent.gltf", false});
    cases.push_back({"trav_buf_symlink_dangling.gltf", false});
    for (const auto &c : cases) {
        const char *n = c.first.c_str();
        {
            mvr_gltf_options mo = defaults();
            mo.base_dir = f.asset.c_str();
            outcome m = load(t, f.path(c.first), mo, (c.first + " (memory, base_dir)").c_str(), true);
            CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET || (c.second && m.r == MVR_ERROR_IO), "%s from memory: %s", n,
                      mvr_result_name(m.r));
            CHECK_MSG(t, has(m.msg, "buffers[1].uri"), "%s from memory: %s", n, m.msg.c_str());
            no_outside_facts(t, m, n, sizes);
        }
        outcome o = load(t, f.path(c.first), defaults());
        bool code_ok = o.r == MVR_ERROR_INVALID_ASSET || (c.second && o.r == MVR_ERROR_IO);
        CHECK_MSG(t, code_ok, "%s: %s, expected MVR_ERROR_INVALID_ASSET%s", n, mvr_result_name(o.r),
                  c.second ? " or MVR_ERROR_IO" : "");
        CHECK_MSG(t, o.r == MVR_OK || has(o.msg, "buffers[1].uri"), "%s: message lacks buffers[1].uri: %s", n,
                  o.msg.c_str());
        no_outside_facts(t, o, n, sizes);
        if (o.r == MVR_OK) {
            size_t m = count_pixels(render(t, o.scene, n), magenta);
            CHECK_MSG(t, m == 0, "%s: LEAK: %zu magenta pixels from the outside buffer", n, m);
        }
    }
}

// The message for a refused URI is the same whether the outside file exists
// or not (names aside): no existence oracle.
std::string neutral(std::string m, const std::vector<std::string> &names)
{
    for (const auto &n : names)
        m = replace_all(m, n, "NAME");
    return m;
}

void refusals_do_not_tell_whether_outside_files_exist(mvr_test_state *t)
{
    const files &f = F();
    struct pair { const char *existing, *missing; };
    const pair pairs[] = {{"trav_buf_dotdot.gltf", "trav_buf_dotdot_nonexistent.gltf"},
                          {"trav_buf_symlink_file.gltf", "trav_buf_symlink_dangling.gltf"},
                          {"trav_img_dotdot.gltf", "trav_img_dotdot_nonexistent.gltf"},
                          {"trav_img_symlink_file.gltf", "trav_img_symlink_dangling.gltf"}};
    const std::vector<std::string> names = {"trav_buf_dotdot_nonexistent", "trav_buf_dotdot", "trav_buf_symlink_dangling",
                                            "trav_buf_symlink_file", "trav_img_dotdot_nonexistent", "trav_img_dotdot",
                                            "trav_img_symlink_dangling", "trav_img_symlink_file", "link_dangling",
                                            "link_outside", "no_such_outside", "outside"};
    for (const auto &p : pairs) {
        for (bool st : {false, true}) {
            mvr_gltf_options o = st ? strict() : defaults();
            outcome a = load(t, f.path(p.existing), o, st ? (std::string(p.existing) + " strict").c_str() : nullptr);
            outcome b = load(t, f.path(p.missing), o, st ? (std::string(p.missing) + " strict").c_str() : nullptr);
            std::string ma = neutral(a.msg + (a.warnings.empty() ? "" : a.warnings[0]), names);
            std::string mb = neutral(b.msg + (b.warnings.empty() ? "" : b.warnings[0]), names);
            CHECK_MSG(t, a.r == b.r && ma == mb, "%s vs %s: the outside file's existence shows:\n    %s: %s\n    %s: %s",
                      p.existing, p.missing, mvr_result_name(a.r), ma.c_str(), mvr_result_name(b.r), mb.c_str());
        }
    }
}

void traversal_images_never_reach_a_pixel(mvr_test_state *t)
{
    const files &f = F();
    std::vector<std::string> sizes = {std::to_string(OUTSIDE_PNG_SIZE)};
    for (const auto &s : f.spellings) {
        std::string name = "trav_img_" + s.label + ".gltf";
        outcome o = load(t, f.path(name), defaults());
        left_out_and_clean(t, o, name.c_str());
        no_outside_facts(t, o, name.c_str(), sizes);
        outcome st = load(t, f.path(name), strict(), (name + " strict").c_str());
        CHECK_MSG(t, st.r == MVR_ERROR_INVALID_ASSET || st.r == MVR_ERROR_IO, "%s strict: %s", name.c_str(),
                  mvr_result_name(st.r));
        CHECK_MSG(t, st.r == MVR_OK || has(st.msg, "images[0]"), "%s strict: message lacks images[0]: %s", name.c_str(),
                  st.msg.c_str());
        no_outside_facts(t, st, name.c_str(), sizes);
        if (st.r == MVR_OK)
            CHECK_MSG(t, count_pixels(render(t, st.scene, name.c_str()), magenta) == 0, "%s strict: LEAK", name.c_str());
    }
}

void current_directory_is_never_searched(mvr_test_state *t)
{
    const files &f = F();
    char old[PATH_MAX];
    if (!getcwd(old, sizeof old) || chdir((f.root + "/cwd").c_str()) != 0) {
        CHECK_MSG(t, 0, "cannot chdir into %s/cwd", f.root.c_str());
        return;
    }
    {
        outcome b = load(t, f.path("cwd_buf.gltf"), defaults());
        CHECK_MSG(t, b.r == MVR_ERROR_IO, "cwd_buf: %s, expected MVR_ERROR_IO (missing inside the folder)",
                  mvr_result_name(b.r));
        CHECK_MSG(t, has(b.msg, "buffers[1].uri"), "cwd_buf: %s", b.msg.c_str());
        if (b.r == MVR_OK)
            CHECK_MSG(t, count_pixels(render(t, b.scene, "cwd_buf"), magenta) == 0, "cwd_buf: LEAK from the cwd");
        outcome i = load(t, f.path("cwd_img.gltf"), defaults());
        left_out_and_clean(t, i, "cwd_img");
        // from memory without a base_dir: external URIs are refused, the cwd is no fallback
        outcome bm = load(t, f.path("cwd_buf.gltf"), defaults(), "cwd_buf (memory, no base_dir)", true);
        CHECK_MSG(t, bm.r != MVR_OK && has(bm.msg, "buffers[1]"), "cwd_buf from memory: %s %s", mvr_result_name(bm.r),
                  bm.msg.c_str());
        outcome im = load(t, f.path("cwd_img.gltf"), defaults(), "cwd_img (memory, no base_dir)", true);
        left_out_and_clean(t, im, "cwd_img from memory");
        // a relative base_dir is relative to the cwd by the caller's choice; an absolute one never falls back to it
        mvr_gltf_options o = defaults();
        o.base_dir = f.asset.c_str();
        outcome ib = load(t, f.path("cwd_img.gltf"), o, "cwd_img (memory, base_dir asset)", true);
        left_out_and_clean(t, ib, "cwd_img from memory with base_dir");
    }
    CHECK(t, chdir(old) == 0);
}

void spoofed_images_decode_by_signature(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("spoof_jpeg_as_png.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0,
                  "jpeg named .png: %s, decoded %u, missing %u", o.msg.c_str(), o.info.images_decoded,
                  o.info.images_missing);
        std::vector<uint8_t> px = render(t, o.scene, "spoof_jpeg_as_png");
        size_t orange = count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 80 && p[1] < 180 && p[2] < 60; });
        CHECK_MSG(t, orange > 200, "jpeg named .png: %zu orange pixels (decoded as what the bytes are)", orange);
    }
    const char *left_out[] = {"spoof_jpeg_mime_png.gltf", "spoof_glb_jpeg_mime_png.glb", "spoof_text_png.gltf",
                              "spoof_mp4.gltf",          "spoof_avi.gltf",              "spoof_mp4_mime_video.gltf",
                              "spoof_mp4_named_png.gltf"};
    for (const char *n : left_out) {
        outcome o = load(t, f.path(n), defaults());
        left_out_and_clean(t, o, n);
        CHECK_MSG(t, o.ms < 2000, "%s: %.0f ms (a decoder tried too hard?)", n, o.ms);
        outcome s = load(t, f.path(n), strict(), (std::string(n) + " strict").c_str());
        CHECK_MSG(t, s.r != MVR_OK && has(s.msg, "images[0]"), "%s strict: %s %s", n, mvr_result_name(s.r),
                  s.msg.c_str());
    }
    // informational: the data URI's media type disagrees with its bytes; either outcome is safe
    outcome d = load(t, f.path("spoof_data_uri_png_jpeg.gltf"), defaults());
    std::printf("    (data:image/png holding JPEG: %s, decoded %u, missing %u)\n", mvr_result_name(d.r),
                d.info.images_decoded, d.info.images_missing);
}

void image_bombs_hit_the_budget(mvr_test_state *t)
{
    const files &f = F();
    const char *bombs[] = {"bomb_png_16k.gltf", "bomb_png_16k_data_uri.gltf", "bomb_jpeg_16k.gltf", "bomb_png_16k.glb"};
    for (const char *n : bombs) {
        for (bool st : {false, true}) {
            mvr_gltf_options o = budget(64 * MiB);
            o.strict = st;
            std::string label = std::string(n) + (st ? " 64M strict" : " 64M");
            outcome r = load(t, f.path(n), o, label.c_str());
            CHECK_MSG(t, r.r == MVR_ERROR_OUT_OF_MEMORY, "%s: %s, expected MVR_ERROR_OUT_OF_MEMORY", label.c_str(),
                      mvr_result_name(r.r));
            CHECK_MSG(t, has(r.msg, "memory_budget") && has(r.msg, "images[0]"), "%s: %s", label.c_str(), r.msg.c_str());
            CHECK_MSG(t, r.rss_growth_kb < 200 * 1024, "%s: peak RSS grew by %ld KB", label.c_str(), r.rss_growth_kb);
        }
    }
    // 40 GB declared: over any budget and over max_image_dimension; refused or left out, never allocated
    outcome h = load(t, f.path("bomb_png_100k.gltf"), defaults());
    CHECK_MSG(t, (h.r == MVR_OK && h.info.images_missing == 1 && h.warned("images[0]")) ||
                     ((h.r == MVR_ERROR_INVALID_ASSET || h.r == MVR_ERROR_OUT_OF_MEMORY) && has(h.msg, "images[0]")),
              "bomb_png_100k: %s %s", mvr_result_name(h.r), h.msg.c_str());
    CHECK_MSG(t, h.rss_growth_kb < 200 * 1024, "bomb_png_100k: peak RSS grew by %ld KB", h.rss_growth_kb);
}

void shared_files_are_read_once(mvr_test_state *t)
{
    const files &f = F();
    outcome a = load(t, f.path("same_png_x8.gltf"), defaults());
    CHECK_MSG(t, a.r == MVR_OK && a.info.images_decoded == 1 && a.info.images_missing == 0,
              "same_png_x8: %s decoded %u", a.msg.c_str(), a.info.images_decoded);
    {
        std::vector<uint8_t> px = render(t, a.scene, "same_png_x8");
        size_t g = count_pixels(px, [](const uint8_t *p) { return p[1] > 180 && p[0] < 120 && p[2] < 140; });
        CHECK_MSG(t, g > 200, "same_png_x8: %zu green pixels", g);
    }
    // a budget that holds one decode (64x64 RGBA = 16 KB) with room, not eight... the decode counter is the check
    outcome b = load(t, f.path("same_png_spellings.gltf"), defaults());
    CHECK_MSG(t, b.r == MVR_OK && b.info.images_decoded == 1, "same_png_spellings: %s decoded %u (the same file, four spellings)",
              b.msg.c_str(), b.info.images_decoded);
    outcome c = load(t, f.path("same_bin_x4.gltf"), defaults());
    CHECK_MSG(t, c.r == MVR_OK && c.info.buffers_read == 1, "same_bin_x4: %s buffers_read %u", c.msg.c_str(),
              c.info.buffers_read);
    CHECK_MSG(t, drawn(render(t, c.scene, "same_bin_x4")) > 200, "same_bin_x4: nothing drawn");
    {
        // the file itself read once: through file_access.read, counting calls
        reader_state s;
        s.serve["geom.bin"] = gen::read_file(f.path("geom.bin"));
        mvr_gltf_options o = with_reader(s);
        outcome r = load(t, f.path("same_bin_x4.gltf"), o, "same_bin_x4 (file_access.read)");
        CHECK_MSG(t, r.r == MVR_OK && s.uris.size() == 1 && s.releases == 1, "same_bin_x4: %zu reads, %d releases",
                  s.uris.size(), s.releases);
    }
    outcome d = load(t, f.path("valid_shared_texture.gltf"), defaults());
    CHECK_MSG(t, d.r == MVR_OK && d.info.images_decoded == 1, "valid_shared_texture: %s decoded %u", d.msg.c_str(),
              d.info.images_decoded);
}

void huge_counts_and_files_are_refused_early(mvr_test_state *t)
{
    const files &f = F();
    for (const char *n : {"zeros_16m_positions.gltf", "zeros_16m_indices.gltf"}) {
        outcome o = load(t, f.path(n), budget(64 * MiB), (std::string(n) + " 64M").c_str());
        CHECK_MSG(t, o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget"), "%s: %s %s", n,
                  mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, has(o.msg, "accessor") || has(o.msg, "meshes[0]"), "%s: the message names no object: %s", n,
                  o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 100 * 1024, "%s: peak RSS grew by %ld KB", n, o.rss_growth_kb);
    }
    {
        // under the default budget 48 MB of zeros load; the accounting covers what the process took
        outcome o = load(t, f.path("zeros_4m_positions.gltf"), defaults());
        std::printf("    (zeros_4m_positions: peak %.1f MiB by the load's accounting, process peak RSS grew %.1f MiB)\n",
                    double(o.info.memory_peak) / MiB, double(o.rss_growth_kb) / 1024);
        CHECK_MSG(t, o.r == MVR_OK && o.info.memory_peak >= 4000000ull * 12, "zeros_4m_positions: %s peak %llu",
                  o.msg.c_str(), (unsigned long long)o.info.memory_peak);
        CHECK_MSG(t, o.rss_growth_kb * 1024ll <= (long long)(o.info.memory_peak + 64 * MiB),
                  "zeros_4m_positions: the process grew %ld KB, the load counted a peak of %llu bytes",
                  o.rss_growth_kb, (unsigned long long)o.info.memory_peak);
    }
    {
        outcome o = load(t, f.path("huge_sparse_bin.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "max_file_bytes")) ||
                         (o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget")),
                  "huge_sparse_bin: %s %s", mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, has(o.msg, "buffers[1]"), "huge_sparse_bin: %s", o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 100 * 1024 && o.ms < 1000, "huge_sparse_bin: RSS +%ld KB, %.0f ms: read before refusing?",
                  o.rss_growth_kb, o.ms);
    }
    {
        outcome o = load(t, f.path("big_100m_bin.gltf"), budget(64 * MiB), "big_100m_bin 64M");
        CHECK_MSG(t, o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget") && has(o.msg, "buffers[1]"),
                  "big_100m_bin: %s %s", mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 50 * 1024, "big_100m_bin 64M: peak RSS grew by %ld KB", o.rss_growth_kb);
        mvr_gltf_options m = defaults();
        m.max_file_bytes = MiB;
        outcome c = load(t, f.path("big_100m_bin.gltf"), m, "big_100m_bin max_file_bytes 1M");
        CHECK_MSG(t, c.r == MVR_ERROR_INVALID_ASSET && has(c.msg, "max_file_bytes") && has(c.msg, "buffers[1]"),
                  "big_100m_bin max_file_bytes: %s %s", mvr_result_name(c.r), c.msg.c_str());
        outcome ok = load(t, f.path("big_100m_bin.gltf"), defaults());
        CHECK_MSG(t, ok.r == MVR_OK && ok.info.buffers_read == 2, "big_100m_bin: %s buffers_read %u", ok.msg.c_str(),
                  ok.info.buffers_read);
        CHECK_MSG(t, ok.r != MVR_OK || ok.info.memory_peak >= 100 * MiB, "big_100m_bin: peak %llu does not count the buffer",
                  (unsigned long long)ok.info.memory_peak);
    }
}

void budgets_add_up(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("json_tokens_1m.gltf"), defaults());
        std::printf("    (json_tokens_1m: JSON estimate %.1f MiB, peak %.1f MiB, process peak RSS grew %.1f MiB)\n",
                    double(o.info.json_bytes_estimate) / MiB, double(o.info.memory_peak) / MiB,
                    double(o.rss_growth_kb) / 1024);
        CHECK_MSG(t, o.r == MVR_OK && o.info.json_bytes_estimate > 2 * MiB, "json_tokens_1m: %s, json estimate %llu",
                  o.msg.c_str(), (unsigned long long)o.info.json_bytes_estimate);
        // the accounting is not an under-estimate: what the process took is within what the load counted
        CHECK_MSG(t, o.rss_growth_kb * 1024ll <= (long long)(o.info.memory_peak + 64 * MiB),
                  "json_tokens_1m: the process grew %ld KB, the load counted a peak of %llu bytes", o.rss_growth_kb,
                  (unsigned long long)o.info.memory_peak);
        outcome b = load(t, f.path("json_tokens_1m.gltf"), budget(16 * MiB), "json_tokens_1m 16M");
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget") && has(b.msg, "JSON"),
                  "json_tokens_1m 16M: %s %s", mvr_result_name(b.r), b.msg.c_str());
        CHECK_MSG(t, b.rss_growth_kb < 40 * 1024, "json_tokens_1m 16M: peak RSS grew by %ld KB (parsed anyway?)",
                  b.rss_growth_kb);
    }
    {
        outcome o = load(t, f.path("images_2k_x3.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 3 && o.info.memory_peak >= 48 * MiB,
                  "images_2k_x3: %s decoded %u peak %llu", o.msg.c_str(), o.info.images_decoded,
                  (unsigned long long)o.info.memory_peak);
        // each image fits alone (one decoding at a time); the three held together do not:
        // a 2048^2 RGBA8 copy is 16 MiB and decoding one holds 32 MiB more, so the
        // third needs 2 x 16 + 32 = 64 MiB besides the file: over 56 MiB
        outcome b = load(t, f.path("images_2k_x3.gltf"), budget(56 * MiB), "images_2k_x3 56M");
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget") &&
                         (has(b.msg, "images[1]") || has(b.msg, "images[2]")),
                  "images_2k_x3 56M: %s %s", mvr_result_name(b.r), b.msg.c_str());
    }
}

void lying_glb_chunks_are_refused(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("glb_ok.glb"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0, "glb_ok: %s decoded %u",
                  o.msg.c_str(), o.info.images_decoded);
        std::vector<uint8_t> px = render(t, o.scene, "glb_ok");
        CHECK_MSG(t, count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 80 && p[1] < 180 && p[2] < 60; }) > 200,
                  "glb_ok: the image's orange is not drawn");
        outcome u = load(t, f.path("glb_unknown_chunk.glb"), defaults());
        CHECK_MSG(t, u.r == MVR_OK, "glb_unknown_chunk: %s (unknown chunks must be ignored)", u.msg.c_str());
        CHECK_MSG(t, u.r != MVR_OK || render(t, u.scene, "glb_unknown_chunk") == px, "glb_unknown_chunk: renders unlike glb_ok");
    }
    const char *glb_errors[] = {"glb_bin_past_end.glb",    "glb_bin_counts_header.glb", "glb_json_unaligned.glb",
                                "glb_total_too_big.glb",   "glb_total_too_small.glb",   "glb_json_length_huge.glb",
                                "glb_two_bin.glb",         "glb_bin_first.glb",         "glb_header_only.glb"};
    for (const char *n : glb_errors) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "GLB"), "%s: %s %s", n, mvr_result_name(o.r),
                  o.msg.c_str());
        outcome m = load(t, f.path(n), defaults(), (std::string(n) + " (memory)").c_str(), true);
        CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET && has(m.msg, "GLB"), "%s from memory: %s %s", n,
                  mvr_result_name(m.r), m.msg.c_str());
    }
    {
        outcome o = load(t, f.path("glb_json_empty.glb"), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET || o.r == MVR_ERROR_PARSE, "glb_json_empty: %s", mvr_result_name(o.r));
        outcome x = load(t, f.path("glb_extra_uriless_buffer.glb"), defaults());
        CHECK_MSG(t, x.r == MVR_ERROR_INVALID_ASSET && has(x.msg, "buffers[1]"), "glb_extra_uriless_buffer: %s %s",
                  mvr_result_name(x.r), x.msg.c_str());
        for (const char *n : {"glb_no_bin_chunk.glb", "glb_bin_shorter_than_buffer.glb"}) {
            outcome b = load(t, f.path(n), defaults());
            CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && (has(b.msg, "buffers[0]") || has(b.msg, "GLB")), "%s: %s %s", n,
                      mvr_result_name(b.r), b.msg.c_str());
        }
    }
}

void node_graphs_and_deep_nesting_are_safe(mvr_test_state *t)
{
    const files &f = F();
    struct expect { const char *file, *part; };
    const expect refused[] = {{"graph_cycle.gltf", "nodes["},
                              {"graph_self_child.gltf", "nodes[0]"},
                              {"graph_child_twice.gltf", "nodes[1]"},
                              {"graph_root_twice.gltf", "nodes[0]"}};
    for (const auto &e : refused) {
        outcome o = load(t, f.path(e.file), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, e.part), "%s: %s %s", e.file, mvr_result_name(o.r),
                  o.msg.c_str());
    }
    for (const char *n : {"graph_cycle_unreachable.gltf", "graph_cycle_no_scene.gltf", "graph_chain_2000.gltf",
                          "graph_chain_100k.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK || (o.r == MVR_ERROR_INVALID_ASSET && has(o.msg, "nodes")), "%s: %s %s", n,
                  mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, o.ms < 5000, "%s: %.0f ms", n, o.ms);
        if (o.r == MVR_OK && std::strcmp(n, "graph_chain_2000.gltf") == 0)
            CHECK_MSG(t, drawn(render(t, o.scene, n)) > 200, "%s: loaded but draws nothing", n);
    }
    for (const char *n : {"deep_json_100k.gltf", "deep_json_objects_100k.gltf", "deep_json_100k.glb"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_INVALID_ASSET || o.r == MVR_ERROR_PARSE, "%s: %s", n, mvr_result_name(o.r));
        outcome m = load(t, f.path(n), defaults(), (std::string(n) + " (memory)").c_str(), true);
        CHECK_MSG(t, m.r == MVR_ERROR_INVALID_ASSET || m.r == MVR_ERROR_PARSE, "%s from memory: %s", n, mvr_result_name(m.r));
    }
}

void long_values_stay_out_of_messages(mvr_test_state *t)
{
    const files &f = F();
    const std::string &L = f.long_value;
    {
        outcome o = load(t, f.path("long_buffer_uri.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_ERROR_IO || o.r == MVR_ERROR_INVALID_ASSET) && has(o.msg, "buffers[1].uri"),
                  "long_buffer_uri: %s", mvr_result_name(o.r));
        messages_short(t, o, L, "long_buffer_uri");
    }
    {
        outcome o = load(t, f.path("long_image_uri.gltf"), defaults());
        left_out_and_clean(t, o, "long_image_uri");
        messages_short(t, o, L, "long_image_uri");
        outcome s = load(t, f.path("long_image_uri.gltf"), strict(), "long_image_uri strict");
        CHECK_MSG(t, s.r != MVR_OK && has(s.msg, "images[0]"), "long_image_uri strict: %s", mvr_result_name(s.r));
        messages_short(t, s, L, "long_image_uri strict");
    }
    {
        outcome o = load(t, f.path("long_names.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "long_names: %s", o.msg.c_str());
        messages_short(t, o, L, "long_names");
    }
    {
        outcome o = load(t, f.path("long_ext_required.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_UNSUPPORTED, "long_ext_required: %s", mvr_result_name(o.r));
        messages_short(t, o, L, "long_ext_required");
        outcome u = load(t, f.path("long_ext_used.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_OK && !u.warnings.empty(), "long_ext_used: %s, %zu warnings", u.msg.c_str(),
                  u.warnings.size());
        messages_short(t, u, L, "long_ext_used");
    }
    {
        outcome o = load(t, f.path("long_camera_type_unused.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warned("cameras[0]"), "long_camera_type_unused: %s (unused cameras only warn)",
                  o.msg.c_str());
        messages_short(t, o, L, "long_camera_type_unused");
        outcome u = load(t, f.path("long_camera_type_used.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_ERROR_INVALID_ASSET && has(u.msg, "cameras[0]"), "long_camera_type_used: %s %s",
                  mvr_result_name(u.r), u.msg.c_str());
        messages_short(t, u, L, "long_camera_type_used");
    }
    {
        outcome o = load(t, f.path("long_mime_type.gltf"), defaults());
        CHECK_MSG(t, (o.r == MVR_OK && o.info.images_missing == 1 && o.warned("images[0]")) ||
                         (o.r != MVR_OK && has(o.msg, "images[0]")),
                  "long_mime_type: %s %s", mvr_result_name(o.r), o.msg.c_str());
        messages_short(t, o, L, "long_mime_type");
    }
    {
        const std::string &B = f.long_b64_value;
        outcome o = load(t, f.path("bad_data_uri_image_50k.gltf"), defaults());
        left_out_and_clean(t, o, "bad_data_uri_image_50k");
        messages_short(t, o, B, "bad_data_uri_image_50k");
        outcome b = load(t, f.path("bad_data_uri_buffer_50k.gltf"), defaults());
        CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && has(b.msg, "buffers[1]"), "bad_data_uri_buffer_50k: %s %s",
                  mvr_result_name(b.r), b.msg.c_str());
        messages_short(t, b, B, "bad_data_uri_buffer_50k");
        // informational: base64 whose length cannot be base64 (1 mod 4)
        outcome u = load(t, f.path("bad_data_uri_buffer_unpadded.gltf"), defaults());
        std::printf("    (base64 of length 1 mod 4 in buffers[1]: %s)\n", mvr_result_name(u.r));
    }
}

void valid_files_load(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("valid_unused_uriless_buffer.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.buffers_read == 1, "valid_unused_uriless_buffer: %s buffers_read %u",
                  o.msg.c_str(), o.info.buffers_read);
        CHECK_MSG(t, o.r != MVR_OK || render(t, o.scene, "valid_unused_uriless_buffer") == reference_pixels(t),
                  "valid_unused_uriless_buffer: renders unlike the reference");
    }
    for (const char *n : {"valid_unused_http_buffer.gltf", "valid_unused_outside_buffer.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.buffers_read == 1, "%s: %s buffers_read %u", n, o.msg.c_str(),
                  o.info.buffers_read);
    }
    {
        outcome o = load(t, f.path("valid_indices_without_view.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "valid_indices_without_view: %s", o.msg.c_str());
        if (o.r == MVR_OK) {
            size_t n = drawn(render(t, o.scene, "valid_indices_without_view"));
            CHECK_MSG(t, n == 0, "valid_indices_without_view: %zu pixels drawn (all indices are 0)", n);
        }
    }
    {
        outcome a = load(t, f.path("valid_base64_buffer.gltf"), defaults());
        outcome b = load(t, f.path("valid_plain_data_uri.gltf"), defaults());
        CHECK_MSG(t, a.r == MVR_OK && b.r == MVR_OK && b.info.buffers_read == 1, "plain data URI: %s / %s",
                  a.msg.c_str(), b.msg.c_str());
        if (a.r == MVR_OK && b.r == MVR_OK) {
            std::vector<uint8_t> pa = render(t, a.scene, "valid_base64_buffer");
            CHECK_MSG(t, drawn(pa) > 200 && render(t, b.scene, "valid_plain_data_uri") == pa,
                      "the percent-encoded data URI renders unlike the base64 one");
        }
    }
    {
        outcome o = load(t, f.path("valid_unused_bad_camera_light.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "valid_unused_bad_camera_light: %s (unused cameras and lights only warn)",
                  o.msg.c_str());
        CHECK_MSG(t, o.warned("cameras[0]") && o.warned("lights[0]") && o.warned("lights[1]"),
                  "valid_unused_bad_camera_light: warnings do not name cameras[0], lights[0], lights[1] (%zu warnings)",
                  o.warnings.size());
        outcome u = load(t, f.path("used_bad_camera.gltf"), defaults());
        CHECK_MSG(t, u.r == MVR_ERROR_INVALID_ASSET && has(u.msg, "cameras[0]"), "used_bad_camera: %s %s",
                  mvr_result_name(u.r), u.msg.c_str());
    }
    {
        outcome o = load(t, f.path("valid_missing_texture.gltf"), defaults());
        outcome r = load(t, f.path("valid_missing_texture_reference.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_missing == 1 && o.warned("images[0]"),
                  "valid_missing_texture: %s missing %u", o.msg.c_str(), o.info.images_missing);
        if (o.r == MVR_OK && r.r == MVR_OK) {
            std::vector<uint8_t> px = render(t, o.scene, "valid_missing_texture");
            size_t red = count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 100 && p[1] < 180 && p[2] < 150; });
            CHECK_MSG(t, red > 200, "valid_missing_texture: %zu pixels of the factor's colour (black texture?)", red);
            CHECK_MSG(t, px == render(t, r.scene, "valid_missing_texture_reference"),
                      "valid_missing_texture: renders unlike the same material without texture");
        }
        outcome s = load(t, f.path("valid_missing_texture.gltf"), strict(), "valid_missing_texture strict");
        CHECK_MSG(t, (s.r == MVR_ERROR_IO || s.r == MVR_ERROR_INVALID_ASSET) && has(s.msg, "images[0]"),
                  "valid_missing_texture strict: %s %s", mvr_result_name(s.r), s.msg.c_str());
    }
    for (const char *n : {"valid_inside_dotdot.gltf", "valid_percent_space.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.info.images_missing == 0,
                  "%s: %s decoded %u missing %u", n, o.msg.c_str(), o.info.images_decoded, o.info.images_missing);
        CHECK_MSG(t, o.r != MVR_OK || render(t, o.scene, n) != reference_pixels(t), "%s: the texture is not drawn", n);
    }
}

void allowed_root_widens_access(mvr_test_state *t)
{
    const files &f = F();
    const std::string p = f.path("widen_allowed_root.gltf");
    outcome d = load(t, p, defaults(), "widen_allowed_root (default)");
    left_out_and_clean(t, d, "widen_allowed_root without allowed_root");
    auto cyan = [](const uint8_t *px) { return px[0] < 60 && px[1] > 170 && px[2] > 220; };
    for (const std::string &root : {f.root, f.root + "/shared_textures"}) {
        mvr_gltf_options o = defaults();
        o.file_access.allowed_root = root.c_str();
        outcome w = load(t, p, o, ("widen_allowed_root " + root.substr(root.find_last_of('/'))).c_str());
        CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1 && w.info.images_missing == 0,
                  "allowed_root %s: %s decoded %u", root.c_str(), w.msg.c_str(), w.info.images_decoded);
        size_t n = count_pixels(render(t, w.scene, "widen_allowed_root"), cyan);
        CHECK_MSG(t, n > 200, "allowed_root %s: %zu cyan pixels", root.c_str(), n);
    }
    // allowed_root below the parent admits nothing else of the parent
    mvr_gltf_options o = defaults();
    std::string lib = f.root + "/shared_textures";
    o.file_access.allowed_root = lib.c_str();
    outcome x = load(t, f.path("trav_img_dotdot.gltf"), o, "trav_img_dotdot (allowed_root lib)");
    left_out_and_clean(t, x, "trav_img_dotdot with allowed_root shared_textures");
    outcome b = load(t, f.path("trav_buf_dotdot.gltf"), o, "trav_buf_dotdot (allowed_root lib)");
    CHECK_MSG(t, b.r == MVR_ERROR_INVALID_ASSET && has(b.msg, "buffers[1].uri"), "trav_buf_dotdot with allowed_root: %s",
              mvr_result_name(b.r));
}

void read_callback_replaces_file_access(mvr_test_state *t)
{
    const files &f = F();
    const std::string p = f.path("widen_read_callback.gltf");
    outcome d = load(t, p, defaults(), "widen_read_callback (default)");
    CHECK_MSG(t, d.r == MVR_ERROR_IO && has(d.msg, "buffers[0].uri"), "without the callback: %s %s",
              mvr_result_name(d.r), d.msg.c_str());
    auto orange = [](const uint8_t *px) { return px[0] > 200 && px[1] > 80 && px[1] < 180 && px[2] < 60; };
    for (bool memory : {false, true}) {
        reader_state s;
        s.serve["geo data.bin"] = gen::read_file(f.path("callback_geometry.bin"));
        s.serve["tex ture.png"] = gen::read_file(f.path("my tex.png"));
        mvr_gltf_options o = with_reader(s);
        {
            outcome w = load(t, p, o, memory ? "widen_read_callback (memory, no base_dir)" : "widen_read_callback", memory);
            CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1, "read callback: %s decoded %u", w.msg.c_str(),
                      w.info.images_decoded);
            std::set<std::string> seen(s.uris.begin(), s.uris.end());
            CHECK_MSG(t, seen.count("geo data.bin") && seen.count("tex ture.png") && seen.size() == 2,
                      "read callback saw %zu URIs (%s ...), expected the two percent-decoded ones", seen.size(),
                      s.uris.empty() ? "none" : s.uris[0].c_str());
            CHECK_MSG(t, s.max_bytes_seen > 0, "read callback: max_bytes 0");
            CHECK_MSG(t, w.r != MVR_OK || count_pixels(render(t, w.scene, "widen_read_callback"), orange) > 200,
                      "read callback: its image is not drawn");
        }
        CHECK_MSG(t, s.releases == s.reads_ok && s.reads_ok >= 2, "read callback: %d reads, %d releases", s.reads_ok,
                  s.releases);
    }
    {
        // a data: URI never reaches the callback; "../" does, decoded (confinement is the caller's)
        reader_state s;
        mvr_gltf_options o = with_reader(s);
        outcome w = load(t, f.path("widen_read_callback_dotdot.gltf"), o);
        CHECK_MSG(t, s.uris.size() == 1 && s.uris[0] == "../x.png", "the callback saw %zu URIs (%s), expected ../x.png",
                  s.uris.size(), s.uris.empty() ? "none" : s.uris[0].c_str());
        left_out_and_clean(t, w, "widen_read_callback_dotdot (callback fails)");
        CHECK_EQ_INT(t, s.releases, 0);
    }
    {
        reader_state s;
        s.serve["tex ture.png"] = gen::read_file(f.path("my tex.png"));
        mvr_gltf_options o = with_reader(s);
        outcome w = load(t, f.path("widen_read_callback_refused.gltf"), o);
        CHECK_MSG(t, s.uris.size() == 1 && s.uris[0] == "tex ture.png",
                  "the callback saw %zu URIs (first '%s'), expected only 'tex ture.png'", s.uris.size(),
                  s.uris.empty() ? "" : s.uris[0].c_str());
        CHECK_MSG(t, w.r == MVR_OK && w.info.images_decoded == 1 && w.info.images_missing == 2 && w.warned("images[0]") &&
                         w.warned("images[1]"),
                  "widen_read_callback_refused: %s decoded %u missing %u", w.msg.c_str(), w.info.images_decoded,
                  w.info.images_missing);
        CHECK_EQ_INT(t, s.releases, s.reads_ok);
    }
}

// Compressed geometry (hostile_codecs.cpp: codec_*, made with meshoptimizer's
// and Draco's own encoders): each broken file refused with a message naming
// the object, never a crash; the valid ones load, draw, and decode inside the
// budget. Extension messages (ext_*): a required extension mvr lacks is named
// (MVR_ERROR_UNSUPPORTED), a used one is warned about once.
void compressed_geometry_is_checked(mvr_test_state *t)
{
    const files &f = F();
    size_t refused = check_refusals(t, f, "codec_");
    CHECK_MSG(t, refused >= 30, "%zu codec_* files refused", refused);
    // valid: an unlit orange quad (meshopt) and blue Suzanne (Draco), framed
    struct valid {
        const char *name;
        bool (*colour)(const uint8_t *);
    };
    const valid files_ok[] = {
        {"codec_meshopt_valid.gltf",
         [](const uint8_t *p) { return p[0] > 200 && p[1] > 100 && p[1] < 220 && p[2] < 40; }},
        {"codec_draco_valid.gltf", [](const uint8_t *p) { return p[0] < 40 && p[1] > 100 && p[2] > 200; }},
    };
    for (const valid &v : files_ok) {
        outcome o = load(t, f.path(v.name), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warnings.empty(), "%s: %s %s", v.name, o.msg.c_str(),
                  o.warnings.empty() ? "" : o.warnings[0].c_str());
        if (!o.scene)
            continue;
        std::vector<uint8_t> px = render(t, o.scene, v.name);
        size_t coloured = count_pixels(px, v.colour);
        CHECK_MSG(t, px.empty() || (coloured > 400 && coloured + 200 > drawn(px)),
                  "%s: %zu of %zu drawn pixels coloured", v.name, coloured, drawn(px));
        // decoded inside the budget: a budget just under the load's own peak refuses it
        outcome b = load(t, f.path(v.name), budget(o.info.memory_peak - 1), (std::string(v.name) + " peak-1").c_str());
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget"), "%s under its peak: %s %s", v.name,
                  mvr_result_name(b.r), b.msg.c_str());
    }
    {
        outcome o = load(t, f.path("codec_meshopt_fallback_unread.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warnings.empty() && o.info.buffers_read == 1,
                  "codec_meshopt_fallback_unread: %s, %zu warnings, %u buffers read", o.msg.c_str(), o.warnings.size(),
                  o.info.buffers_read);
    }
    {
        outcome o = load(t, f.path("codec_meshopt_huge.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_OUT_OF_MEMORY && has(o.msg, "memory_budget") &&
                         has(o.msg, "bufferViews[0].extensions.EXT_meshopt_compression"),
                  "codec_meshopt_huge: %s %s", mvr_result_name(o.r), o.msg.c_str());
        CHECK_MSG(t, o.rss_growth_kb < 64 * 1024, "codec_meshopt_huge: peak RSS grew by %ld KB", o.rss_growth_kb);
    }
    {
        // Draco's own allocations are bounded: a lying count fails fast, within
        // the budget (and under a small budget, by it)
        outcome o = load(t, f.path("codec_draco_allocation_bomb.gltf"), defaults());
        CHECK_MSG(t, o.ms < 2000 && o.rss_growth_kb < 64 * 1024,
                  "codec_draco_allocation_bomb: %.0f ms, RSS grew %ld KB", o.ms, o.rss_growth_kb);
        outcome b = load(t, f.path("codec_draco_allocation_bomb.gltf"), budget(4 * MiB),
                         "codec_draco_allocation_bomb 4M");
        CHECK_MSG(t, b.r == MVR_ERROR_OUT_OF_MEMORY && has(b.msg, "memory_budget") &&
                         has(b.msg, "KHR_draco_mesh_compression"),
                  "codec_draco_allocation_bomb 4M: %s %s", mvr_result_name(b.r), b.msg.c_str());
    }
    for (const char *n : {"ext_required_unknown.gltf", "ext_required_before_parse.gltf"}) {
        outcome o = load(t, f.path(n), defaults());
        CHECK_MSG(t, o.r == MVR_ERROR_UNSUPPORTED && has(o.msg, "requires extension 'EXT_mvr_unknown'"), "%s: %s %s", n,
                  mvr_result_name(o.r), o.msg.c_str());
    }
    {
        outcome o = load(t, f.path("ext_used_unknown.gltf"), defaults());
        size_t named = 0;
        for (const auto &w : o.warnings)
            named += has(w, "'EXT_mvr_optional'");
        CHECK_MSG(t, o.r == MVR_OK && named == 1 && o.warnings.size() == 1,
                  "ext_used_unknown: %s, %zu warnings (%zu naming it)", o.msg.c_str(), o.warnings.size(), named);
    }
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc == 3 && std::strcmp(argv[1], "--write-files") == 0) {
        return hostile::write_files_command(argv[2]);
    }
    if (argc != 1) {
        std::fprintf(stderr, "usage: io_hostile [--write-files DIR]\n");
        return 2;
    }
    hostile::set_root(MVR_HOSTILE_DIR);
    static const mvr_test_case cases[] = {
        TEST(magenta_controls_draw_magenta),
        TEST(traversal_buffers_are_refused),
        TEST(traversal_images_never_reach_a_pixel),
        TEST(refusals_do_not_tell_whether_outside_files_exist),
        TEST(current_directory_is_never_searched),
        TEST(spoofed_images_decode_by_signature),
        TEST(image_bombs_hit_the_budget),
        TEST(shared_files_are_read_once),
        TEST(huge_counts_and_files_are_refused_early),
        TEST(budgets_add_up),
        TEST(lying_glb_chunks_are_refused),
        TEST(node_graphs_and_deep_nesting_are_safe),
        TEST(long_values_stay_out_of_messages),
        TEST(valid_files_load),
        TEST(allowed_root_widens_access),
        TEST(read_callback_replaces_file_access),
        TEST(skins_morphs_and_animations_are_checked),
        TEST(compressed_geometry_is_checked),
        TEST(ktx2_containers_are_checked),
        TEST(material_variants_are_checked),
        TEST(material_extensions_are_checked),
        TEST(accessor_offsets_and_sparse_are_checked),
        TEST(symlink_swaps_never_read_outside),
        TEST(symlinks_inside_the_folder_still_resolve),
    };
    int rc = mvr_test_run(cases, sizeof cases / sizeof cases[0]);
    hostile::release_context();
    return rc;
}
