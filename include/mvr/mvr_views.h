/*
 * mvr: view sets (the views one render draws) and the camera
 * metadata of a view.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_VIEWS_API_H
#define MVR_VIEWS_API_H

#include "mvr/mvr_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ view sets */

typedef struct mvr_viewport {
    int32_t x, y;                /* from the bottom-left, in layer pixels */
    uint32_t width, height;      /* 0 = the whole layer */
} mvr_viewport;

typedef struct mvr_view_desc {
    double position[3];          /* world */
    double orientation[4];       /* quaternion x, y, z, w, camera looks along -Z; all zero = identity */
    mvr_projection projection;
    mvr_viewport viewport;
    bool disabled;               /* not rendered (its layer is left as it was) */
    /* Lights this view sees: those whose layers share a bit with these
     * (mvr_light_desc.layers); a masked-out light contributes nothing here.
     * 0 = every layer. */
    uint32_t light_layers;
} mvr_view_desc;

/* Pose helper: a view at eye looking at target with up. */
void mvr_view_look_at(mvr_view_desc *view, const double eye[3], const double target[3],
                      const double up[3]);

typedef struct mvr_view_set mvr_view_set;

/* The most views one view set holds (mvr_view_set_create and the framing
 * functions alike; the CLI's --views and camera files share the cap). */
#define MVR_VIEW_SET_MAX_VIEWS 1024u

typedef struct mvr_view_set_desc {
    uint32_t view_count;
    const mvr_view_desc *views;
    /* The origin the GPU sees as 0: model and view matrices are made relative
     * to it in double precision. false = the centroid of the view positions. */
    bool origin_set;
    double origin[3];
} mvr_view_set_desc;

mvr_result mvr_view_set_create(const mvr_view_set_desc *desc, mvr_view_set **out, mvr_error *out_error);
void mvr_view_set_destroy(mvr_view_set *set);
mvr_result mvr_view_set_update(mvr_view_set *set, uint32_t index, const mvr_view_desc *view);
uint32_t mvr_view_set_count(const mvr_view_set *set);
/* View `index` as given (or last updated), and the set's origin (as given, or
 * the centroid of its views): a set made of some of its views with this
 * origin (origin_set) renders them as the whole set does (what is fitted
 * to all the views of a render, such as shadow cascades and one shared
 * auto-exposure, is then fitted to that set's). Fail on NULL or an index
 * past the end. */
mvr_result mvr_view_set_get_view(const mvr_view_set *set, uint32_t index, mvr_view_desc *out);
mvr_result mvr_view_set_get_origin(const mvr_view_set *set, double out[3]);

/* Camera metadata of a view for data pipelines: what each pixel
 * of its viewport sees, in double, whatever the GPU's relative matrices.
 * Conventions: the world is glTF's (right-handed, +Y up, metres if the file
 * says so); world_to_camera / camera_to_world (column-major) use the OpenGL
 * camera (x right, y up, looking along -Z, as glTF cameras and NeRF's
 * transforms.json); fx, fy, cx, cy are pinhole intrinsics in pixels for the
 * OpenCV / COLMAP camera (x right, y down, looking along +Z): a camera point
 * (X, Y, Z) lands at u = fx X / Z + cx, v = fy Y / Z + cy, measured from the
 * viewport's top-left corner with pixel k covering [k, k + 1) (COLMAP's; its
 * centre is k + 0.5: subtract 0.5 for OpenCV's integer centres).
 * projection: the OpenGL clip matrix (z in [-1, 1]; mvr's reversed-Z is
 * the GPU's business). Orthographic views have no pinhole: perspective is
 * false and fx .. cy are 0. width, height: the view's viewport on a layer of
 * that size. */
typedef struct mvr_view_camera {
    uint32_t width, height;
    bool perspective;
    double fx, fy, cx, cy;
    double projection[16];
    double world_to_camera[16];
    double camera_to_world[16];
} mvr_view_camera;
mvr_result mvr_view_set_get_camera(const mvr_view_set *set, uint32_t index, uint32_t layer_width,
                                   uint32_t layer_height, mvr_view_camera *out);
const char *mvr_view_set_last_error(const mvr_view_set *set);

#ifdef __cplusplus
}
#endif
#endif /* MVR_VIEWS_API_H */
