#!/usr/bin/env python3
"""ctest: the dataset files of mvr render (issue 33): names, transforms.json, --split, COLMAP points.

  /usr/bin/python3 test_cli_dataset.py MVR SCENE.gltf OUT

- past 100 views every per-view name (view_VVVV.png, depth_VVVV.npy) sorts in view order;
- transforms.json states aabb, aabb_scale, scale / offset (instant-ngp's), the up axis, and per
  frame depth_file_path / mask_path with --outputs depth; the aabb holds every point unprojected
  from every view's depth, and instant-ngp's box (aabb_scale around 0.5) holds the aabb;
- --normalize puts every camera and the aabb inside [0, 1]^3, the poses being the plain ones
  times the stated scale plus the stated offset;
- --split 0.8,0.1,0.1 and 0.9,0.1: exact counts, disjoint parts covering every view, the
  transforms_{train,val,test}.json frames equal to transforms.json's lists; a bad split exits 2;
- --colmap with depth: points3D.txt holds points whose every track entry names a 2D point of
  images.txt that names the point back and lies within 1 px of the point's projection, with the
  point between the depths the view sees around it (for nearly all); without depth: no points and a warning.
Python's standard library and numpy."""
import json
import math
import os
import subprocess
import sys

import numpy as np

MVR, SCENE, OUT = sys.argv[1:4]
os.makedirs(OUT, exist_ok=True)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def render(name, *args, quiet=True):
    out = os.path.join(OUT, name)
    r = subprocess.run([MVR, "render"] + [str(a) for a in args] + ["--out", out] + (["--quiet"] if quiet else []),
                       capture_output=True, text=True)
    expect(r.returncode == 0, "%s exits 0 (got %d): %s" % (name, r.returncode, r.stderr))
    return out, r


def load(path):
    with open(path) as f:
        return json.load(f)


# names sort in view order past 100 views
out, _ = render("many", SCENE, "--layout", "sphere", "--views", 101, "--size", "16x12", "--outputs", "depth")
views = sorted(n for n in os.listdir(out) if n.startswith("view_"))
expect(views == ["view_%04d.png" % k for k in range(101)], "view names sort in view order: %r" % views[95:105])
depths = sorted(n for n in os.listdir(out) if n.startswith("depth_") and n.endswith(".npy"))
expect(depths == ["depth_%04d.npy" % k for k in range(101)], "depth names sort in view order: %r" % depths[95:105])
frames = load(os.path.join(out, "transforms.json"))["frames"] if os.path.exists(os.path.join(out, "transforms.json")) else []
expect([f["file_path"] for f in frames] == ["view_%04d.png" % k for k in range(101)], "transforms.json names")


def unprojected(out, t, normalize=None):
    """Every depth pixel of every frame, unprojected with the frame's own camera (file coordinates)."""
    pts = []
    for k, f in enumerate(t["frames"]):
        d = np.load(os.path.join(out, "depth_%04d.npy" % k)).astype(np.float64)
        if normalize:
            d = d * normalize
        ys, xs = np.nonzero(d > 0)
        z = d[ys, xs]
        cam = np.stack([(xs + 0.5 - f["cx"]) / f["fl_x"] * z, -(ys + 0.5 - f["cy"]) / f["fl_y"] * z, -z, np.ones_like(z)])
        pts.append((np.array(f["transform_matrix"]) @ cam)[:3].T)
    return np.concatenate(pts)


# transforms.json: fields and consistency
W, H = 96, 72
out, _ = render("plain", SCENE, "--layout", "sphere", "--views", 12, "--size", "%dx%d" % (W, H), "--outputs",
                "depth,coverage")
t = load(os.path.join(out, "transforms.json"))
for key in ("aabb", "aabb_scale", "scale", "offset", "up", "frames"):
    expect(key in t, "transforms.json has %s" % key)
if all(k in t for k in ("aabb", "aabb_scale", "scale", "offset")):
    lo, hi = np.array(t["aabb"][0]), np.array(t["aabb"][1])
    s = t["aabb_scale"]
    expect(s in (1, 2, 4, 8, 16, 32, 64, 128), "aabb_scale is a power of two: %r" % s)
    expect(t["up"] == [0, 1, 0], "up is glTF's +Y: %r" % t["up"])
    p = unprojected(out, t)
    slack = 1e-4 * float(np.max(hi - lo))
    expect(len(p) > 100 and bool(np.all(p >= lo - slack)) and bool(np.all(p <= hi + slack)),
           "the aabb holds every depth point: %d points, %s .. %s vs %s .. %s" %
           (len(p), p.min(0) if len(p) else None, p.max(0) if len(p) else None, lo, hi))
    ngp = np.stack([lo, hi]) * t["scale"] + np.array(t["offset"])
    expect(bool(np.all(np.abs(ngp - 0.5) <= s / 2 + 1e-9)), "instant-ngp's box holds the aabb: %s, scale %d" % (ngp, s))
    expect(abs(float(np.max(ngp[1] - ngp[0])) - 1.0) < 1e-9, "the aabb's longest side is 1 in instant-ngp's cube")
for k, f in enumerate(t.get("frames", [])):
    expect(f.get("depth_file_path") == "depth_%04d.png" % k, "frame %d depth_file_path: %r" % (k, f.get("depth_file_path")))
    expect(f.get("mask_path") == "mask_%04d.png" % k, "frame %d mask_path: %r" % (k, f.get("mask_path")))

# --normalize: cameras and aabb in [0, 1]^3, the poses the plain ones moved and scaled as stated
out_n, _ = render("normalized", SCENE, "--layout", "sphere", "--views", 12, "--size", "%dx%d" % (W, H), "--outputs",
                  "depth", "--normalize")
tn = load(os.path.join(out_n, "transforms.json"))
norm = tn.get("normalization", {})
expect("scale" in norm and "offset" in norm, "--normalize states its scale and offset: %r" % norm)
if "scale" in norm and "frames" in t:
    eps = 1e-9
    for k, (a, b) in enumerate(zip(t["frames"], tn["frames"])):
        pa, pb = np.array(a["transform_matrix"]), np.array(b["transform_matrix"])
        expect(bool(np.all(pb[:3, 3] >= -eps) and np.all(pb[:3, 3] <= 1 + eps)), "camera %d in the unit cube: %s" % (k, pb[:3, 3]))
        expect(np.allclose(pb[:3, 3], pa[:3, 3] * norm["scale"] + np.array(norm["offset"]), atol=1e-12),
               "camera %d: plain * scale + offset" % k)
        expect(np.array_equal(pb[:3, :3], pa[:3, :3]), "camera %d: the same rotation" % k)
    lo, hi = np.array(tn["aabb"][0]), np.array(tn["aabb"][1])
    expect(bool(np.all(lo >= -eps) and np.all(hi <= 1 + eps)), "normalized aabb in the unit cube: %s %s" % (lo, hi))
    p = unprojected(out_n, tn, norm["scale"])
    expect(bool(np.all(p >= lo - 1e-5) and np.all(p <= hi + 1e-5)), "normalized aabb holds the normalized depth points")

# --split
for split, n, counts in (("0.8,0.1,0.1", 30, (24, 3, 3)), ("0.9,0.1", 20, (18, 2, 0))):
    out, _ = render("split_%d" % n, "--demo", "cube", "--views", n, "--size", "8x8", "--split", split)
    ts = load(os.path.join(out, "transforms.json"))
    lists = [ts.get("%s_filenames" % p, None) for p in ("train", "val", "test")]
    expect([len(x or []) for x in lists] == list(counts), "--split %s: counts %r" % (split, [len(x or []) for x in lists]))
    every = sorted(sum((x or [] for x in lists), []))
    expect(every == ["view_%04d.png" % k for k in range(n)], "--split %s: the parts cover every view once" % split)
    for p, names in zip(("train", "val", "test"), lists):
        path = os.path.join(out, "transforms_%s.json" % p)
        got = [f["file_path"] for f in load(path)["frames"]] if os.path.exists(path) else None
        expect(got == names, "--split %s: transforms_%s.json lists its part" % (split, p))
r = subprocess.run([MVR, "render", "--demo", "cube", "--split", "0.5,0.6", "--out", os.path.join(OUT, "bad")],
                   capture_output=True, text=True)
expect(r.returncode == 2 and "--split" in r.stderr, "--split 0.5,0.6 exits 2 naming it: %d %s" % (r.returncode, r.stderr))


def read_colmap(out):
    cams, images, points = {}, {}, {}
    with open(os.path.join(out, "colmap", "cameras.txt")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = line.split()
            cams[int(v[0])] = [float(x) for x in v[4:8]]
    with open(os.path.join(out, "colmap", "images.txt")) as f:
        lines = [l.rstrip("\n") for l in f if not l.startswith("#")]
    for i in range(0, len(lines) - 1, 2):
        v = lines[i].split()
        pts = lines[i + 1].split()
        images[int(v[0])] = ([float(x) for x in v[1:8]], int(v[8]), v[9],
                             [(float(pts[j]), float(pts[j + 1]), int(pts[j + 2])) for j in range(0, len(pts), 3)])
    with open(os.path.join(out, "colmap", "points3D.txt")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = line.split()
            track = [(int(v[j]), int(v[j + 1])) for j in range(8, len(v), 2)]
            points[int(v[0])] = (np.array([float(x) for x in v[1:4]]), track)
    return cams, images, points


def rotation(qw, qx, qy, qz):
    return np.array([[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)],
                     [2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)],
                     [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)]])


# COLMAP points3D from depth
W, H = 192, 144
out, _ = render("colmap", SCENE, "--layout", "sphere", "--views", 16, "--size", "%dx%d" % (W, H), "--outputs", "depth",
                "--colmap")
cams, images, points = read_colmap(out)
expect(len(points) >= 16 * 5, "points3D.txt has points: %d" % len(points))
worst, agree, total = 0.0, 0, 0
for pid, (X, track) in points.items():
    expect(len(track) >= 2, "point %d is seen by 2 views or more" % pid)
    for image_id, idx in track:
        q, cam_id, name, pts = images[image_id]
        if idx >= len(pts) or pts[idx][2] != pid:
            expect(False, "point %d: image %d's 2D point %d names it back" % (pid, image_id, idx))
            continue
        fx, fy, cx, cy = cams[cam_id]
        c = rotation(*q[:4]) @ X + np.array(q[4:7])
        u, v = fx * c[0] / c[2] + cx, fy * c[1] / c[2] + cy
        worst = max(worst, math.hypot(u - pts[idx][0], v - pts[idx][1]))
        d = np.load(os.path.join(out, name.replace("view_", "depth_").replace(".png", ".npy")))
        # the point lies on the surface the view sees there: between its pixel's and its
        # neighbours' depths (a hidden point would lie far behind them all)
        y, x = min(int(v), H - 1), min(int(u), W - 1)
        near = d[max(y - 1, 0):y + 2, max(x - 1, 0):x + 2]
        near = near[near > 0]
        agree += len(near) > 0 and near.min() * 0.99 <= c[2] <= near.max() * 1.01
        total += 1
expect(worst <= 1.0, "every point reprojects into its views within 1 px (worst %.3g)" % worst)
print("observations on the seen surface: %d of %d" % (agree, total))
expect(total > 0 and agree >= 0.95 * total, "the views' depths agree with their points: %d of %d" % (agree, total))
for image_id, (q, cam_id, name, pts) in images.items():
    for idx, (x, y, pid) in enumerate(pts):
        ok = pid in points and (image_id, idx) in points[pid][1]
        if not ok:
            expect(False, "image %d 2D point %d: point %d's track lists it" % (image_id, idx, pid))
            break

out, r = render("colmap_nodepth", "--demo", "cube", "--views", 4, "--size", "16x16", "--colmap", quiet=False)
_, _, points = read_colmap(out)
expect(not points and "--outputs depth" in r.stderr, "--colmap without depth: no points, said: %s" % r.stderr)

if failures:
    print("%d dataset checks failed" % len(failures))
    sys.exit(1)
print("dataset files: all checks passed")
