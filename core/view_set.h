/* View sets: N views with double-precision poses, and the per-view matrices
 * the GPU sees (relative to the set's origin, narrowed to float). */
#ifndef MVR_VIEW_SET_H
#define MVR_VIEW_SET_H

#include "core_util.h"
#include "mvr_math.h"

struct mvr_view_set {
    mvr_view_desc *views;
    uint32_t count;
    bool origin_set;
    mvr_dvec3 origin;            /* as given, or the centroid of view positions */
    uint64_t version;
    char last_error[MVR_ERROR_MESSAGE_SIZE];
};

/* The viewport a view renders to in a layer of width x height. */
mvr_viewport mvr_view_viewport(const mvr_view_desc *view, uint32_t width, uint32_t height);

/* Projection (double) of a view for its viewport; reversed = reversed-Z with
 * clip z in [0, 1], else GL's standard convention (finite far enforced). */
mvr_dmat4 mvr_view_projection(const mvr_view_desc *view, mvr_viewport vp, bool reversed);

/* The view-projection (double) of a view, relative to origin: what the GPU
 * gets (narrowed) and what culling tests against. */
mvr_dmat4 mvr_view_relative_view_proj(const mvr_view_desc *view, mvr_dvec3 origin, mvr_viewport vp, bool reversed);

/* view_proj relative to origin (float) and the eye position relative to origin. */
void mvr_view_gpu_matrices(const mvr_view_desc *view, mvr_dvec3 origin, mvr_viewport vp,
                           bool reversed, float view_proj[16], float eye_rel[4]);
/* The view matrix relative to origin (float): world (relative) to the
 * view's OpenGL camera, for the extra outputs' depth and normals. */
void mvr_view_gpu_view_matrix(const mvr_view_desc *view, mvr_dvec3 origin, float view_matrix[16]);

#endif
