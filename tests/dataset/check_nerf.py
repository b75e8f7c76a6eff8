#!/usr/bin/env python3
"""ctest dataset_nerf: transforms.json read as instant-ngp and nerfstudio
read it, by a reader written to their published field lists, not mvr's:
  - instant-ngp (docs/nerf_dataset_tips.md, "Existing datasets" and the
    loader src/nerf_loader.cu): top-level or per-frame `fl_x`/`fl_y` (or
    `camera_angle_x`), `cx`, `cy`, `w`, `h`; `aabb_scale`; `scale` and
    `offset` (a point p of the file sits at p * scale + offset in its unit
    cube); per frame `file_path`, `transform_matrix` (camera-to-world,
    OpenGL camera: x right, y up, looking along -Z), `depth_path` with
    `integer_depth_scale` (depth = 16-bit value * integer_depth_scale);
  - nerfstudio (docs "Data conventions" and nerfstudio_dataparser.py): the
    same intrinsics and `transform_matrix`, per frame `depth_file_path` and
    `mask_path` (0 = masked out), `train_filenames` / `val_filenames` /
    `test_filenames` for the split.
  check_nerf.py MVR WORK
The reader loads every frame's image, depth PNG and mask PNG and checks:
the split covers every frame once (and transforms_{train,val}.json agree);
each depth pixel unprojected lies in the `aabb`, and inside instant-ngp's
unit cube after scale and offset; and depth reprojects across views: a
pixel of view i, unprojected with its depth and projected into view j,
lands where view j's depth agrees (or behind it: occluded), almost never
in front of it (free space seen by j). Stdlib + numpy."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import png_read  # noqa: E402
import scene_cube  # noqa: E402

failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def field(frame, top, key, default=None):
    """A frame's own value, else the file's (both loaders' rule)."""
    return frame.get(key, top.get(key, default))


def intrinsics(frame, top):
    w, h = int(field(frame, top, "w")), int(field(frame, top, "h"))
    fx = field(frame, top, "fl_x")
    if fx is None:  # instant-ngp: camera_angle_x is the horizontal field of view in radians
        fx = 0.5 * w / np.tan(0.5 * field(frame, top, "camera_angle_x"))
    fy = field(frame, top, "fl_y", fx)
    cx, cy = field(frame, top, "cx", w / 2), field(frame, top, "cy", h / 2)
    return w, h, float(fx), float(fy), float(cx), float(cy)


def load(folder, top, frame):
    w, h, fx, fy, cx, cy = intrinsics(frame, top)
    c2w = np.array(frame["transform_matrix"], float)
    assert c2w.shape == (4, 4)
    image = png_read.read(folder / frame["file_path"])
    # both depth keys, naming the same file
    expect(frame.get("depth_path") == frame.get("depth_file_path"),
           "%s: depth_path %r, depth_file_path %r" % (frame["file_path"], frame.get("depth_path"),
                                                      frame.get("depth_file_path")))
    raw = png_read.read(folder / frame["depth_path"])
    expect(raw.dtype == np.uint16 and raw.shape == (h, w), "%s: depth PNG %s %s" % (frame["depth_path"], raw.dtype,
                                                                                   raw.shape))
    depth = raw.astype(float) * float(top["integer_depth_scale"])
    mask = png_read.read(folder / frame["mask_path"])
    expect(mask.shape == (h, w) and set(np.unique(mask)) <= {0, 255}, "%s: mask values %s" % (
        frame["mask_path"], np.unique(mask)[:8]))
    expect(image.shape[:2] == (h, w), "%s: image %s, frame says %dx%d" % (frame["file_path"], image.shape, w, h))
    return dict(w=w, h=h, fx=fx, fy=fy, cx=cx, cy=cy, c2w=c2w, w2c=np.linalg.inv(c2w), depth=depth,
                mask=mask > 0, step=float(top["integer_depth_scale"]))


def unproject(v, stride=2):
    """World points of view v's covered pixels (every stride-th), OpenGL camera."""
    ys, xs = np.nonzero(v["mask"][::stride, ::stride])
    ys, xs = ys * stride, xs * stride
    d = v["depth"][ys, xs]
    keep = d > 0
    ys, xs, d = ys[keep], xs[keep], d[keep]
    x = (xs + 0.5 - v["cx"]) / v["fx"] * d
    y = -(ys + 0.5 - v["cy"]) / v["fy"] * d
    cam = np.stack([x, y, -d, np.ones_like(d)])
    return (v["c2w"] @ cam)[:3].T


def reproject(points, v):
    """(agree, occluded, in front) counts of points seen from view v."""
    cam = (v["w2c"] @ np.vstack([points.T, np.ones(len(points))]))[:3]
    d = -cam[2]
    ok = d > 1e-6
    u = v["fx"] * cam[0][ok] / d[ok] + v["cx"]
    t = -v["fy"] * cam[1][ok] / d[ok] + v["cy"]
    d = d[ok]
    inside = (u >= 0) & (u < v["w"]) & (t >= 0) & (t < v["h"])
    u, t, d = u[inside].astype(int), t[inside].astype(int), d[inside]
    # only where view v's mask is the same over the 3x3 pixels around: a
    # point a fraction of a pixel off the silhouette tells nothing
    m = np.pad(v["mask"], 1, mode="edge")
    stack = np.stack([m[dy:dy + v["h"], dx:dx + v["w"]] for dy in range(3) for dx in range(3)])
    uniform = (stack.min(axis=0) == stack.max(axis=0))[t, u]
    u, t, d = u[uniform], t[uniform], d[uniform]
    seen = v["depth"][t, u]
    covered = v["mask"][t, u]
    # tolerance: a pixel's footprint on a slanted face plus the PNG's step
    tol = 0.03 * d + 2 * v["step"]
    agree = covered & (np.abs(seen - d) <= tol)
    occluded = covered & (d > seen + tol)
    front = ~covered | (d < seen - tol)  # j sees past where i saw a surface
    return int(agree.sum()), int(occluded.sum()), int(front.sum())


def main():
    mvr, work = sys.argv[1], pathlib.Path(sys.argv[2]).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    scene = scene_cube.write(work / "cube")
    out = work / "out"
    p = subprocess.run([mvr, "render", str(scene), "--layout", "sphere", "--views", "16", "--size", "160x120",
                        "--outputs", "depth,coverage", "--split", "0.75,0.25", "--margin", "0.1", "--quiet",
                        "--out", str(out)], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("dataset_nerf: mvr render failed: %s" % p.stderr)
    top = json.loads((out / "transforms.json").read_text())
    frames = top["frames"]
    expect(len(frames) == 16, "%d frames" % len(frames))
    names = [f["file_path"] for f in frames]
    # the split, nerfstudio's lists and the Blender-style files
    lists = [top.get(k, []) for k in ("train_filenames", "val_filenames", "test_filenames")]
    expect(sorted(sum(lists, [])) == sorted(names), "the split lists do not cover every frame once")
    expect((len(lists[0]), len(lists[1])) == (12, 4), "split %d/%d, expected 12/4" % (len(lists[0]), len(lists[1])))
    for part, listed in zip(("train", "val"), lists):
        sub = json.loads((out / ("transforms_%s.json" % part)).read_text())
        expect([f["file_path"] for f in sub["frames"]] == listed, "transforms_%s.json differs from %s_filenames" %
               (part, part))
    expect(int(top["aabb_scale"]) in (1, 2, 4, 8, 16, 32, 64, 128), "aabb_scale %r" % top["aabb_scale"])
    views = [load(out, top, f) for f in frames]
    lo, hi = np.array(top["aabb"][0]), np.array(top["aabb"][1])
    scale, offset = float(top.get("scale", 1.0)), np.array(top.get("offset", [0.5, 0.5, 0.5]), float)
    cube = 0.5 * int(top["aabb_scale"])  # instant-ngp's box: [0.5 - s/2, 0.5 + s/2]^3
    agree = occluded = front = 0
    for i, v in enumerate(views):
        pts = unproject(v)
        expect(len(pts) > 100, "view %d: %d covered pixels" % (i, len(pts)))
        slack = 0.02 * np.max(hi - lo) + 2 * v["step"]
        expect(np.all(pts >= lo - slack) and np.all(pts <= hi + slack), "view %d: depth points outside the aabb" % i)
        ngp = pts * scale + offset
        expect(np.all(ngp >= 0.5 - cube - slack * scale) and np.all(ngp <= 0.5 + cube + slack * scale),
               "view %d: points outside instant-ngp's box after scale and offset" % i)
        # the two views whose cameras are nearest: they see most of what i sees
        centre = v["c2w"][:3, 3]
        nearest = sorted((np.linalg.norm(u["c2w"][:3, 3] - centre), j) for j, u in enumerate(views) if j != i)
        for _, j in nearest[:2]:
            a, o, f = reproject(pts[::3], views[j])
            agree, occluded, front = agree + a, occluded + o, front + f
    total = agree + occluded + front
    print("reprojection: %d points into neighbouring views: %.1f%% agree, %.1f%% occluded, %.2f%% in front" %
          (total, 100 * agree / total, 100 * occluded / total, 100 * front / total))
    expect(agree > 0.5 * total, "only %d of %d reprojected points agree with the other view's depth" % (agree, total))
    expect(front < 0.02 * total, "%d of %d reprojected points land in front of the other view's surface" %
           (front, total))
    if failures:
        sys.exit("dataset_nerf: %d failure(s)" % len(failures))
    print("dataset_nerf: passed")


main()
