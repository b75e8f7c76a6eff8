/* apps: SHA-256 (apps/mvr/sha256.c, FIPS 180-4) against the standard's
 * test vectors (FIPS 180-4 examples, NIST CSRC "SHA256.pdf"): "abc", the
 * empty string, the 448-bit and the 896-bit messages, a million 'a's fed
 * in uneven pieces (the block buffering), and a file's digest and size. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mvr_test.h"
#include "sha256.h"

static void vectors(mvr_test_state *t)
{
    static const struct {
        const char *message, *digest;
    } v[] = {
        {"abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
        {"", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
        {"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
         "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
        {"abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu",
         "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1"},
    };
    for (size_t k = 0; k < sizeof v / sizeof *v; ++k) {
        char hex[65];
        sha256_hex(v[k].message, strlen(v[k].message), hex);
        CHECK_MSG(t, strcmp(hex, v[k].digest) == 0, "'%s': %s, not %s", v[k].message, hex, v[k].digest);
    }
}

static void million_a_in_pieces(mvr_test_state *t)
{
    char a[1100]; /* the largest piece: 1059 */
    memset(a, 'a', sizeof a);
    sha256_state s;
    sha256_init(&s);
    size_t left = 1000000, piece = 1;
    while (left > 0) {
        size_t n = piece < left ? piece : left;
        sha256_update(&s, a, n);
        left -= n;
        piece = piece % 997 + 63; /* pieces that straddle the 64-byte blocks */
    }
    char hex[65];
    sha256_final_hex(&s, hex);
    CHECK_MSG(t, strcmp(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0") == 0, "%s", hex);
}

static void a_file(mvr_test_state *t)
{
    const char *path = "sha256_test.txt";
    FILE *f = fopen(path, "wb");
    CHECK(t, f != NULL);
    if (!f)
        return;
    fputs("abc", f);
    fclose(f);
    char hex[65];
    uint64_t size = 0;
    CHECK(t, sha256_file(path, hex, &size));
    CHECK(t, size == 3 && strcmp(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad") == 0);
    remove(path);
    CHECK(t, !sha256_file(path, hex, &size));
}

MVR_TEST_MAIN(TEST(vectors), TEST(million_a_in_pieces), TEST(a_file))
