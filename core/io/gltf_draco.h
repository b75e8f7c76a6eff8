/* Draco's mesh decoder behind a narrow C interface (gltf_draco.cpp), the only
 * file that includes Draco. Its object is partially linked with just the
 * members of Draco's static archive that it needs (CMakeLists.txt): Debian's
 * libdraco.so (and the archive's glTF transcoder) carry a second tinygltf of
 * another version and layout, which would interpose on libtinygltf.so's
 * functions wherever it came first in the symbol search order, so no other
 * part of Draco is linked. gltf_codecs.cpp does every glTF-side check. */
#ifndef MVR_GLTF_DRACO_H
#define MVR_GLTF_DRACO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mvr_draco_mesh mvr_draco_mesh;

typedef enum mvr_draco_status {
    MVR_DRACO_OK = 0,
    MVR_DRACO_NOT_DRACO,       /* no Draco header */
    MVR_DRACO_NOT_A_MESH,      /* a point cloud */
    MVR_DRACO_UNDECODABLE,     /* the decoder refused the data */
    MVR_DRACO_OUT_OF_MEMORY,
    MVR_DRACO_NO_VALUE,        /* a point maps to no value of the attribute */
    MVR_DRACO_DOES_NOT_FIT,    /* a value does not fit the component type */
    MVR_DRACO_SHORT_STORAGE    /* the attribute's storage is shorter than its values */
} mvr_draco_status;

/* Decodes a Draco mesh from size bytes. Draco allocates as it goes, by
 * what the data says; every operator new in its code (and this file's) is
 * renamed at build time to mvr_draco_new / mvr_draco_new_array (objcopy
 * --redefine-sym, CMakeLists.txt), which count the bytes on this thread
 * while a decode runs: past allocation_limit in all (frees are not credited)
 * they throw std::bad_alloc and the decode ends with MVR_DRACO_OUT_OF_MEMORY.
 * *allocated: the bytes counted. On failure *out is NULL and message
 * (message_size bytes, may be 0) holds Draco's own words. */
mvr_draco_status mvr_draco_decode(const void *data, size_t size, uint64_t allocation_limit, mvr_draco_mesh **out,
                                  uint64_t *allocated, char *message, size_t message_size);
void mvr_draco_free(mvr_draco_mesh *mesh);
uint32_t mvr_draco_points(const mvr_draco_mesh *mesh);
uint32_t mvr_draco_faces(const mvr_draco_mesh *mesh);
/* The three point indices of face `face` (< mvr_draco_faces), as decoded. */
void mvr_draco_face(const mvr_draco_mesh *mesh, uint32_t face, uint32_t out[3]);
/* Components of the attribute whose unique id is `id`; 0 if there is none. */
int mvr_draco_attribute_components(const mvr_draco_mesh *mesh, uint32_t id);
/* Every point's value of attribute `id` (which exists), `components` values
 * each, as glTF component type `component_type` (5120..5126; integers as
 * they are, integer to float normalized where Draco's attribute is), into
 * out (points x components values). On MVR_DRACO_NO_VALUE or
 * MVR_DRACO_DOES_NOT_FIT, *bad_point is the point. */
mvr_draco_status mvr_draco_attribute_values(const mvr_draco_mesh *mesh, uint32_t id, int component_type,
                                            int components, void *out, uint32_t *bad_point);

#ifdef __cplusplus
}
#endif

#endif
