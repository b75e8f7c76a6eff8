/* apps: the CLI's JSON reader (apps/mvr/json_read.c) on large hostile
 * input, without GL. A camera file with a million distinct member names in
 * one object (inside the 16 MiB camera file cap) is read, and its members
 * are found by name: the duplicate check is a hash set, no longer a
 * comparison of every name with every earlier one (which took more than
 * 600 s here; ctest's TIMEOUT bounds this test at 120 s). Duplicate names
 * are still refused, compared by their decoded bytes ("a" and "\u0061"),
 * at the end of a million names too; long escaped strings and many small
 * objects are read in bounded time as well. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera_file.h"
#include "json_read.h"
#include "mvr_test.h"

#define MANY_KEYS 1000000u

/* A NeRF transforms.json with MANY_KEYS extra names at its top level
 * ("%06x" of k: all distinct, value k % 1000); dup: the last name repeats
 * the first. Its size into *size. */
static char *many_keys_file(bool dup, size_t *size)
{
    static const char head[] = "{\"fl_x\": 100, \"w\": 64, \"h\": 48,\n";
    static const char tail[] = "\"frames\": [{\"transform_matrix\": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}\n";
    size_t cap = sizeof head + (size_t)MANY_KEYS * 16 + sizeof tail;
    char *text = malloc(cap);
    if (!text)
        return NULL;
    size_t n = sizeof head - 1;
    memcpy(text, head, n);
    for (uint32_t k = 0; k < MANY_KEYS; ++k) {
        uint32_t name = dup && k == MANY_KEYS - 1 ? 0 : k;
        n += (size_t)snprintf(text + n, cap - n, "\"%06x\":%u,%s", name, k % 1000, k % 8 == 7 ? "\n" : "");
    }
    memcpy(text + n, tail, sizeof tail - 1);
    *size = n + sizeof tail - 1;
    return text;
}

static void million_names_in_one_object(mvr_test_state *t)
{
    size_t size = 0;
    char *text = many_keys_file(false, &size);
    CHECK(t, text != NULL);
    if (!text)
        return;
    CHECK_MSG(t, size <= CAMERA_FILE_MAX_BYTES, "the file is %zu bytes, over the camera file cap", size);
    json_value root;
    char why[512] = "";
    CHECK_MSG(t, json_read(text, size, &root, why, sizeof why), "%s", why);
    CHECK_EQ_INT(t, root.type, JSON_OBJECT);
    CHECK_EQ_INT(t, root.count, MANY_KEYS + 4);
    static const uint32_t probes[] = {0, 1, 4095, 500000, 999999};
    for (size_t i = 0; i < sizeof probes / sizeof probes[0]; ++i) {
        char name[16];
        snprintf(name, sizeof name, "%06x", probes[i]);
        const json_value *m = json_member(&root, name);
        CHECK_MSG(t, m && m->type == JSON_NUMBER && m->number == probes[i] % 1000, "member %s", name);
    }
    CHECK(t, json_member(&root, "fffffff") == NULL);
    json_read_free(&root);
    /* the same file through the camera file reader: the extra names are ignored */
    camera_file f;
    CHECK_MSG(t, camera_file_parse(text, size, 64, 48, &f, why, sizeof why), "%s", why);
    CHECK_EQ_INT(t, f.count, 1);
    camera_file_free(&f);
    free(text);
}

static void duplicate_names_refused(mvr_test_state *t)
{
    size_t size = 0;
    char *text = many_keys_file(true, &size);
    CHECK(t, text != NULL);
    if (!text)
        return;
    json_value root;
    char why[512] = "";
    CHECK(t, !json_read(text, size, &root, why, sizeof why));
    /* the million-th name is on line 1 + 1000000 / 8 = 125001 */
    CHECK_MSG(t, strstr(why, "the key \"000000\" appears twice in one object") && strstr(why, "line 125001"), "%s",
              why);
    free(text);

    static const char *const dups[] = {
        "{\"a\": 1, \"a\": 2}",
        "{\"a\": 1, \"\\u0061\": 2}",             /* equal once decoded */
        "{\"\\u00e9\": 1, \"\xc3\xa9\": 2}",      /* U+00E9 escaped and as UTF-8 */
        "{\"\\ud83d\\ude00\": 1, \"\xf0\x9f\x98\x80\": 2}", /* a surrogate pair and its UTF-8 */
        "{\"\": 1, \"\": 2}",
        "[{\"x\": {\"b\": 1, \"c\": 2, \"b\": 3}}]", /* in a nested object */
    };
    for (size_t i = 0; i < sizeof dups / sizeof dups[0]; ++i) {
        why[0] = '\0';
        CHECK_MSG(t, !json_read(dups[i], strlen(dups[i]), &root, why, sizeof why), "accepted %s", dups[i]);
        CHECK_MSG(t, strstr(why, "appears twice in one object") != NULL, "%s: %s", dups[i], why);
    }
    /* past several growths of the set: names k0 .. k99, then k57 again */
    char many[2048];
    size_t n = 0;
    many[n++] = '{';
    for (int k = 0; k < 100; ++k)
        n += (size_t)snprintf(many + n, sizeof many - n, "\"k%d\": %d, ", k, k);
    n += (size_t)snprintf(many + n, sizeof many - n, "\"k57\": 0}");
    CHECK(t, !json_read(many, n, &root, why, sizeof why) && strstr(why, "the key \"k57\" appears twice"));
    /* names that differ, and equal names in different objects, are fine */
    const char *fine = "{\"a\": {\"a\": 1}, \"b\": {\"a\": 2}, \"A\": 3, \"ab\": 4, \"\": 5, \"\\u0062a\": 6}";
    CHECK_MSG(t, json_read(fine, strlen(fine), &root, why, sizeof why), "%s", why);
    const json_value *ba = json_member(json_member(&root, "b"), "a");
    CHECK(t, root.count == 6 && ba && ba->number == 2);
    const json_value *escaped = json_member(&root, "ba");
    CHECK(t, escaped && escaped->number == 6);
    json_read_free(&root);
}

/* One string of 2M escapes (12 MB of text) and an array of 200000 small
 * objects: each read in one pass. */
static void long_strings_and_many_objects(mvr_test_state *t)
{
    const uint32_t escapes = 2000000;
    size_t size = (size_t)escapes * 6 + 2;
    char *text = malloc(size);
    CHECK(t, text != NULL);
    if (!text)
        return;
    text[0] = '"';
    for (uint32_t k = 0; k < escapes; ++k)
        memcpy(text + 1 + (size_t)k * 6, k % 2 ? "\\u00e9" : "\\\\\\\"\\/", 6); /* U+00E9, or \\ \" \/ */
    text[size - 1] = '"';
    json_value v;
    char why[512] = "";
    CHECK_MSG(t, json_read(text, size, &v, why, sizeof why), "%s", why);
    CHECK(t, v.type == JSON_STRING && v.string && strlen(v.string) == (size_t)escapes / 2 * 5);
    CHECK(t, v.string && memcmp(v.string, "\\\"/\xc3\xa9", 5) == 0);
    json_read_free(&v);
    free(text);

    const uint32_t objects = 200000;
    size = (size_t)objects * 32 + 2;
    text = malloc(size);
    CHECK(t, text != NULL);
    if (!text)
        return;
    size_t n = 0;
    text[n++] = '[';
    for (uint32_t k = 0; k < objects; ++k)
        n += (size_t)snprintf(text + n, size - n, "%s{\"x\":%u,\"y\":1,\"z\":2}", k ? "," : "", k % 100);
    text[n++] = ']';
    CHECK_MSG(t, json_read(text, n, &v, why, sizeof why), "%s", why);
    CHECK(t, v.type == JSON_ARRAY && v.count == objects);
    if (v.count == objects) {
        const json_value *x = json_member(&v.items[objects - 1], "x");
        CHECK(t, x && x->number == (objects - 1) % 100);
    }
    json_read_free(&v);
    free(text);
}

MVR_TEST_MAIN(TEST(million_names_in_one_object), TEST(duplicate_names_refused), TEST(long_strings_and_many_objects))
