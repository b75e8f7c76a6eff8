/* tangents.h: per-vertex tangent frames for meshes that have none. */
#ifndef MVR_TANGENTS_H
#define MVR_TANGENTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Tangents (4 floats per vertex: xyz, w = the bitangent's sign, glTF's
 * B = cross(N, T) w) of an indexed triangle list, as glTF 2.0 asks where a
 * primitive has a normal map and no TANGENT ("SHOULD calculate tangents
 * using default MikkTSpace algorithms"): each triangle's dP/du, projected on
 * a corner's normal plane and normalized, is summed over the corners of a
 * vertex weighted by the corner's angle (MikkTSpace's weighting); w follows
 * the majority of the triangles' UV orientation about the vertex. Vertices
 * that share position, normal and UV (split for other attributes) share
 * their sums, as MikkTSpace welds them. glTF's v runs down the image, so the
 * normal map's +Y is -dP/dv. A vertex with no usable triangle (degenerate
 * UVs) gets any unit vector orthogonal to its normal. false when out of
 * memory (out untouched). */
bool mvr_mesh_tangents(const float *positions, const float *normals, const float *uvs, uint32_t vertex_count,
                       const uint32_t *indices, size_t index_count, float *out);

#endif
