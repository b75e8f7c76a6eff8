/* mvr render's run-level dataset files, beside the views' images:
 * transforms.json and its splits (dataset_transforms.c) and COLMAP's text
 * model with its 3D points (dataset_colmap.c) and COCO annotations
 * (dataset_coco.c), passes after every view is written, reading the
 * views' files back. Messages go to stderr, prefixed
 * "mvr render". */
#ifndef MVR_APP_DATASET_H
#define MVR_APP_DATASET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mvr/mvr.h"
#include "render_options.h"

/* The first frame's cameras and the scene's bounds, kept for the files
 * written after the last frame (a camera an animation moves has moved by
 * then). */
typedef struct dataset_views {
    uint32_t n;
    mvr_view_camera *cams;       /* n, mvr_view_set_get_camera's at --size */
    bool have_bounds;            /* false: nothing is drawn */
    double bounds_min[3], bounds_max[3];
} dataset_views;

/* Keeps the views' cameras and the scene's world bounds; false (printed)
 * when out of memory or a view has no camera. */
bool dataset_views_capture(dataset_views *d, const render_options *o, const mvr_view_set *views, uint32_t n,
                           const mvr_scene *scene);
void dataset_views_free(dataset_views *d);

/* The name (no folder) of view `view`'s file PREFIX_VVVV.EXT of the first
 * frame (PREFIX_VVVV_f0000.EXT in a sequence), as the writers name them. */
void dataset_file_name(char *buf, size_t size, const render_options *o, const char *prefix, const char *ext,
                       uint32_t view);

/* --split: view k's part, 0 train, 1 val, 2 test, evenly spread and
 * deterministic (exact counts: round(n * fraction) for val and test). */
int dataset_split_of(const render_options *o, uint32_t n, uint32_t view);

/* DIR/transforms.json (and with --split transforms_{train,val,test}.json). */
bool dataset_write_transforms(const render_options *o, const dataset_views *d);

/* DIR/colmap/{cameras,images,points3D}.txt. With depth among --outputs the
 * points are sampled from the written depth_VVVV.npy and view_VVVV images
 * (read back one view at a time) and images.txt lists their 2D points;
 * without, points3D.txt is empty and a warning says so. */
bool dataset_write_colmap(const render_options *o, const dataset_views *d);

/* DIR/annotations/instances.json (one instance per node a view sees, its
 * mesh as category) and instances_mesh.json (one per mesh), COCO's
 * detection format with uncompressed column-major RLE masks, read back from
 * every view's ids_VVVV.npy one view at a time (dataset_coco.c). Without npy
 * among --output-files it writes nothing and warns. */
bool dataset_write_coco(const render_options *o, const dataset_views *d, const mvr_scene *scene);

#endif
