/*
 * mvr: how a scene is shown by default (view layouts, views from
 * a file's camera, the exposure its lights call for) and the demo scenes.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_FRAMING_API_H
#define MVR_FRAMING_API_H

#include "mvr/mvr_renderer.h"
#include "mvr/mvr_scene.h"
#include "mvr/mvr_views.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ framing
 *
 * How a scene is shown by default: views laid out around its bounding
 * box (or sphere), for files without cameras (or when the caller wants a layout
 * instead of the file's camera); views from a camera of the file; the
 * exposure its lights call for.
 */
typedef enum mvr_view_layout {
    MVR_LAYOUT_STEREO = 0,       /* a row of eyes ipd apart in front of the scene, parallel axes */
    MVR_LAYOUT_CUBE,             /* six 90-degree views from the center */
    MVR_LAYOUT_RING,             /* N cameras in a horizontal circle, looking at the center */
    MVR_LAYOUT_GRID,             /* a light-field grid of cameras on a plane, looking at the center */
    MVR_LAYOUT_SPHERE,           /* N cameras spread evenly over a sphere (a Fibonacci lattice), looking at
                                    the center: the capture of a multi-view reconstruction dataset */
    MVR_LAYOUT_ORBIT,            /* a turntable: rings of cameras at rising elevations, looking at the center */
    MVR_LAYOUT_RANDOM            /* N cameras at random over the sphere (or the elevation band), at least
                                    min_spacing apart, looking at the center; the same views for the same seed */
} mvr_view_layout;

/* The world's up axis: the layouts orbit around it and the cameras' up
 * follows it. glTF's is +Y; a Z-up world (Blender's, its transforms.json)
 * renders upright with MVR_UP_Z: there the layouts' "front" (the stereo
 * eyes' side) is -Y, Blender's front view. */
typedef enum mvr_up_axis {
    MVR_UP_Y = 0,
    MVR_UP_Z
} mvr_up_axis;

typedef enum mvr_hemisphere {
    MVR_HEMISPHERE_FULL = 0,
    MVR_HEMISPHERE_UPPER         /* only views at or above the horizon of the scene's centre */
} mvr_hemisphere;

typedef struct mvr_framing_desc {
    mvr_view_layout layout;
    uint32_t views;              /* 0 = the layout's own (stereo 2, cube 6, ring 8, grid 9, sphere 50,
                                    orbit 24); at most MVR_VIEW_SET_MAX_VIEWS */
    double ipd;                  /* stereo: scene units between eyes, in [0, 1e9]; 0 = mvr_stereo_default_ipd of
                                    the framing distance; NaN, infinite, negative or larger is refused */
    double aspect;               /* width / height of the layers, in [1/65536, 65536]; 0 = 1; NaN, infinite,
                                    negative or outside is refused */
    uint32_t rows;               /* orbit: rings (0 = 3), the views shared out among them (the first
                                    rings take the remainder), each ring's azimuths staggered by half a step */
    double elevation_min, elevation_max; /* orbit, radians in (-pi/2, pi/2): the lowest and the highest
                                    ring, evenly between (both 0 = -15 and 60 degrees; one ring: their mean);
                                    sphere and random, in [-pi/2, pi/2]: the band the views lie in (both 0 =
                                    the whole sphere); min <= max, NaN refused */
    /* Camera sampling; each 0 = the default. Angles above the horizon are
     * measured against the plane through the centre normal to `up`. */
    double yfov;                 /* vertical field of view in radians, [1e-3, 3.1]; 0 = 50 degrees (cube:
                                    its faces are 90 degrees, yfov refused) */
    double radius;               /* camera distance from the centre of the scene's bounds, scene units in
                                    (0, 1e9]; 0 = fitted (the bounding box; the sphere with fit_sphere) */
    bool fit_box;                /* fit the bounding box with `margin` as given, 0 included (the box fit is
                                    the default; without fit_box a margin of 0 means
                                    MVR_FRAMING_DEFAULT_MARGIN): each view's distance is the least at
                                    which every corner of the bounds projects inside the image less
                                    `margin` (stereo and grid: one distance for the row or plane, the
                                    least that keeps every corner inside every view); the box then
                                    touches that inset on at least one axis. Not with radius */
    double margin;               /* the box fit: the fraction of the image's half-width and half-height
                                    left free on each side, [0, 0.9]; 0 = MVR_FRAMING_DEFAULT_MARGIN
                                    unless fit_box. Not with radius or fit_sphere */
    mvr_hemisphere hemisphere;   /* sphere, random, orbit: UPPER keeps every view at or above the horizon
                                    (elevations clipped to >= 0); other layouts refuse it */
    uint64_t seed;               /* random: the sequence's seed (any value, 0 included) */
    double min_spacing;          /* random: the least angle in radians between two views' directions from
                                    the centre, [0, pi]; 0 = 0.5 x sqrt(band area / views) (a loose
                                    Poisson-disk spacing); one too large to place every view is refused */
    mvr_up_axis up;              /* the world's up axis (0 = +Y) */
    double elevation;            /* stereo, ring, grid: the angle above the centre's horizon the views look
                                    down from, radians in (-pi/2, pi/2) (negative: from below); 0 =
                                    MVR_FRAMING_DEFAULT_ELEVATION unless level */
    bool level;                  /* stereo, ring, grid: views at the centre's height (elevation exactly 0),
                                    looking along the horizon; not with elevation */
    bool fit_sphere;             /* fit the bounding sphere (5% spare in the narrower direction), not the
                                    box; not with fit_box, margin or radius. fit_sphere with level is
                                    mvr's framing before issue 35 */
} mvr_framing_desc;

/* The default framing (every field 0) of every layout but cube: the views
 * look down at the scene from MVR_FRAMING_DEFAULT_ELEVATION (stereo, ring,
 * grid; the others keep their own directions) and stand as close as keeps
 * the 8 corners of its bounding box inside each view less
 * MVR_FRAMING_DEFAULT_MARGIN of the image's half-size on each side, so a
 * ground plane with small objects on it fills the view instead of being
 * seen edge-on. */
#define MVR_FRAMING_DEFAULT_ELEVATION 0.52359877559829887 /* 30 degrees */
#define MVR_FRAMING_DEFAULT_MARGIN 0.05

/* The eye separation for a subject viewing_distance away: 1/30 of it (the
 * stereographers' 1/30 rule), so a 2 cm model and a 100 m scene get the same
 * depth impression; a subject framed 1.9 m away gets 0.064, a human IPD. */
double mvr_stereo_default_ipd(double viewing_distance);

const char *mvr_view_layout_name(mvr_view_layout layout);
mvr_result mvr_view_set_frame_scene(const mvr_scene *scene, const mvr_framing_desc *desc, mvr_view_set **out,
                                    mvr_error *out_error);

/* Views from a camera node of the scene (a file's camera): its world pose
 * and projection (mvr_scene_camera_view) as the centre of a row of `views`
 * eyes (0 = 2, a stereo pair; 1 = the camera itself) along the camera's x
 * axis, ipd apart, with parallel axes and the camera's projection each.
 * ipd 0 = mvr_stereo_default_ipd of the camera's distance to the centre of
 * the scene's bounding sphere (the project's stereo rule, the 1/30 rule,
 * as mvr_view_set_frame_scene applies it to its framing distance); NaN,
 * infinite, negative or over 1e9 is refused. The view set's origin is the camera. */
mvr_result mvr_view_set_from_camera(const mvr_scene *scene, mvr_node_id camera_node, uint32_t views, double ipd,
                                    mvr_view_set **out, mvr_error *out_error);

/* The exposure a scene is shown with by default (mvr render and mvr-viewer
 * both use it): lights in physical units (mvr_scene_lights_physical: a sun
 * of thousands of lux, as exporters write KHR_lights_punctual) give
 * MVR_EXPOSURE_AUTO with MVR_TONE_MAP_KHR_PBR_NEUTRAL, as a camera would
 * expose them; any other scene MVR_EXPOSURE_LINEAR (the light values as
 * authored, `exposure` as the multiplier), with no tone map, or, when
 * desc->environment is set (set it first), Khronos PBR Neutral (the
 * identity below 0.76, highlights rolled off instead of clipped: the
 * Khronos glTF Sample Viewer's default). Writes only exposure_mode and
 * tone_map: an application whose user chose an exposure or a tone map
 * applies that choice after this call. */
void mvr_render_desc_choose_exposure(const mvr_scene *scene, mvr_render_desc *desc);

/* ------------------------------------------------------------------ demo scenes
 *
 * Scenes generated in code (no files), with views to match: the default for
 * `mvr render` and the benchmark's workload.
 *   stereo  a small room with varied materials and lights, eyes 64 mm apart
 *   cube    the room from its center: six 90-degree views (cube-map faces)
 *   city    a grid of thousands of buildings over 64+ textured materials
 *   ring    N cameras in a circle around an object
 */
typedef struct mvr_demo_desc {
    uint32_t views;              /* 0 = the demo's own count (stereo 2, cube 6, city 2, ring 8) */
    uint32_t width, height;      /* layer size, for aspect ratios; 0 = square */
    mvr_logger logger;
} mvr_demo_desc;

/* The i-th demo's name; NULL past the last. */
const char *mvr_demo_name(uint32_t index);
mvr_result mvr_demo_create(const char *name, const mvr_demo_desc *desc, mvr_scene **out_scene,
                           mvr_view_set **out_views, mvr_error *out_error);

#ifdef __cplusplus
}
#endif
#endif /* MVR_FRAMING_API_H */
