/* The environment's prefiltered cube maps and the DFG table on disk
 * (gl/environment_cache.c), beside the program binaries: the same folder
 * (mvr_renderer_desc.program_cache_dir; none when it is NULL), the same
 * authenticated entry format (core/program_binary_file.h), so an entry is
 * used only when its tag verifies under this user's key, its key (every
 * input of its bytes and the GL's identity) matches and its sizes hold.
 * Anything else is logged and computed again; a missing cache only costs
 * time, and the bytes uploaded from an entry are exactly the ones the GL
 * computed (tests/gl/test_environment_cache.c). */
#ifndef MVR_ENVIRONMENT_CACHE_H
#define MVR_ENVIRONMENT_CACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "context_internal.h"

/* What the maps' bytes depend on (besides the GL and the prefilter's
 * shader sources, which the key adds). */
typedef struct mvr_env_cache_maps {
    const mvr_environment *env;  /* its pixels, width, height, specular_samples, source */
    uint32_t source_size, source_levels; /* the source cube: level k is source_size >> k texels square */
    uint32_t size, levels;       /* the specular chain, likewise */
    bool multiview;              /* the prefilter's path (the same values; kept apart all the same) */
} mvr_env_cache_maps;

/* The DFG table (size x size RG floats, ibl_lut.c's layout): true when the
 * cache held it and `table` is filled. */
bool mvr_env_cache_load_dfg(mvr_renderer *r, uint32_t size, uint32_t samples, float *table);
void mvr_env_cache_store_dfg(mvr_renderer *r, uint32_t size, uint32_t samples, const float *table);

/* Every level of both cubes (RGBA16F storage, already allocated): true
 * when the cache held them and all are uploaded; false leaves them to the
 * prefilter (a partial upload is overwritten by it). */
bool mvr_env_cache_load(mvr_renderer *r, const mvr_env_cache_maps *m, GLuint source, GLuint specular);
/* Reads both cubes back and writes the entry (nothing when a value is no
 * exact half, or the entry would exceed the size an entry may have). */
void mvr_env_cache_store(mvr_renderer *r, const mvr_env_cache_maps *m, GLuint source, GLuint specular);

/* Half floats, exactly: false when f is no half value (or a NaN whose
 * payload a half cannot hold), so nothing inexact is ever stored. */
bool mvr_half_from_float_exact(float f, uint16_t *out);
float mvr_half_to_float(uint16_t h);

#endif
