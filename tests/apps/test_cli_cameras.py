#!/usr/bin/env python3
"""ctest: the camera metadata mvr render writes next to its images (cameras.json, transforms.json,
and with --colmap COLMAP's text model).

  python3 test_cli_cameras.py MVR FILE OUT

For sphere, orbit and stereo layouts: one entry per image, named as the images are; random world
points in front of each camera projected the NeRF way (transforms.json: OpenGL camera-to-world,
fl_x, fl_y, cx, cy) land where cameras.json's OpenGL projection x world_to_camera puts them (within
1e-6 pixel), and so do COLMAP's (quaternion and translation of images.txt, PINHOLE parameters of
cameras.txt); camera_to_world inverts world_to_camera; a sphere's views all look at one point.
With --outputs depth,ids (NumPy files, read here without NumPy): every covered pixel of a view,
unprojected the NeRF way with its depth, lands in the other views on pixels whose depth agrees
with its own where it is not hidden (a dataset's multi-view consistency; a flipped row order or a
wrong convention breaks it), and depth > 0 exactly where an ID is. The same through a camera file
(--cameras CSV with off-centre principal points and fx != fy): 95% agree through the file's own
cameras, 47% if the file's intrinsics had been ignored.
Python's standard library only."""
import ast
import json
import math
import struct
import os
import random
import subprocess
import sys

MVR, FILE, OUT = sys.argv[1:4]
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def mat_vec(m, v):
    return [sum(m[r][c] * v[c] for c in range(4)) for r in range(4)]


def mat_mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


for layout, views in (("sphere", 7), ("orbit", 6), ("stereo", 2)):
    out = os.path.join(OUT, layout)
    run = subprocess.run([MVR, "render", FILE, "--layout", layout, "--views", str(views), "--size", "80x60",
                          "--out", out, "--quiet", "--colmap"], capture_output=True, text=True)
    expect(run.returncode == 0, "%s: mvr render exits %d: %s" % (layout, run.returncode, run.stderr))
    if run.returncode != 0:
        continue
    cams = json.load(open(os.path.join(out, "cameras.json")))
    nerf = json.load(open(os.path.join(out, "transforms.json")))
    expect(len(cams["frames"]) == views and len(nerf["frames"]) == views, "%s: %d entries" % (layout, views))
    # COLMAP: camera id -> (fx, fy, cx, cy); image name -> (R, t, camera id)
    colmap_cams, colmap_images = {}, {}
    for line in open(os.path.join(out, "colmap", "cameras.txt")):
        if line.startswith("#") or not line.strip():
            continue
        f = line.split()
        expect(f[1] == "PINHOLE", "%s: camera model %s" % (layout, f[1]))
        colmap_cams[int(f[0])] = [float(x) for x in f[4:8]]
    for line in open(os.path.join(out, "colmap", "images.txt")):
        if line.startswith("#") or not line.strip():
            continue
        f = line.split()
        w, x, y, z = (float(v) for v in f[1:5])
        rot = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
               [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
               [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
        colmap_images[f[9]] = (rot, [float(v) for v in f[5:8]], int(f[8]))
    expect(len(colmap_images) == views and len(colmap_cams) == views, "%s: COLMAP lists %d images, %d cameras" %
           (layout, len(colmap_images), len(colmap_cams)))
    rng = random.Random(7)
    worst = worst_colmap = 0.0
    for c, n in zip(cams["frames"], nerf["frames"]):
        expect(os.path.exists(os.path.join(out, n["file_path"])), "%s: %s exists" % (layout, n["file_path"]))
        expect(c["w"] == 80 and c["h"] == 60, "%s: size %dx%d" % (layout, c["w"], c["h"]))
        c2w, w2c, proj = n["transform_matrix"], c["world_to_camera"], c["projection"]
        ident = mat_mul(c2w, w2c)
        err = max(abs(ident[r][k] - (1.0 if r == k else 0.0)) for r in range(4) for k in range(4))
        expect(err < 1e-12, "%s: camera_to_world x world_to_camera off identity by %g" % (layout, err))
        for _ in range(50):
            # a point in front of the camera (OpenGL camera space: looking along -Z), in the world
            pc = [rng.uniform(-1, 1), rng.uniform(-1, 1), -rng.uniform(0.5, 10), 1.0]
            p = mat_vec(c2w, pc)
            # NeRF: world -> camera with the inverse of transform_matrix (here: world_to_camera), then
            # the pinhole with OpenGL's y up and -Z forward
            x, y, z, _ = mat_vec(w2c, p)
            u = n["fl_x"] * x / -z + n["cx"]
            v = n["fl_y"] * -y / -z + n["cy"]
            # OpenGL: clip = projection x world_to_camera x p, pixels from the top-left corner
            clip = mat_vec(proj, mat_vec(w2c, p))
            ug = (clip[0] / clip[3] + 1) * 0.5 * c["w"]
            vg = (1 - clip[1] / clip[3]) * 0.5 * c["h"]
            worst = max(worst, abs(u - ug), abs(v - vg))
            if n["file_path"] in colmap_images:
                rot, t, cid = colmap_images[n["file_path"]]
                fx, fy, cx, cy = colmap_cams[cid]
                xc = [sum(rot[r][k] * p[k] for k in range(3)) + t[r] for r in range(3)]
                worst_colmap = max(worst_colmap, abs(fx * xc[0] / xc[2] + cx - ug), abs(fy * xc[1] / xc[2] + cy - vg))
    expect(worst < 1e-6, "%s: NeRF and OpenGL projections differ by %g pixel" % (layout, worst))
    expect(len(colmap_images) == views and worst_colmap < 1e-6,
           "%s: COLMAP and OpenGL projections differ by %g pixel" % (layout, worst_colmap))
    if layout == "sphere":
        # every camera's forward axis (-Z of camera_to_world) passes through one point (the scene's centre)
        frames = cams["frames"]
        eye0 = [frames[0]["camera_to_world"][r][3] for r in range(3)]
        fwd0 = [-frames[0]["camera_to_world"][r][2] for r in range(3)]
        d0 = math.sqrt(sum((eye0[r]) ** 2 for r in range(3)))
        # the centre: eye0 + t fwd0 with t the distance to it, the same for every view (they orbit at one radius)
        eye1 = [frames[1]["camera_to_world"][r][3] for r in range(3)]
        fwd1 = [-frames[1]["camera_to_world"][r][2] for r in range(3)]
        # closest approach of the two axes
        w0 = [eye0[r] - eye1[r] for r in range(3)]
        a = sum(f * f for f in fwd0)
        b = sum(fwd0[r] * fwd1[r] for r in range(3))
        cc = sum(f * f for f in fwd1)
        d = sum(fwd0[r] * w0[r] for r in range(3))
        e = sum(fwd1[r] * w0[r] for r in range(3))
        den = a * cc - b * b
        s = (b * e - cc * d) / den
        t = (a * e - b * d) / den
        gap = math.sqrt(sum((eye0[r] + s * fwd0[r] - eye1[r] - t * fwd1[r]) ** 2 for r in range(3)))
        expect(gap < 1e-9 * max(d0, 1.0), "sphere: views 0 and 1 look at points %g apart" % gap)
    print("%-7s %d views: NeRF vs OpenGL projection within %.2g pixel, COLMAP within %.2g" %
          (layout, views, worst, worst_colmap))



def load_npy(path):
    """A NumPy .npy file (version 1.0, C order, little-endian float32 or uint32): (shape, flat values)."""
    data = open(path, "rb").read()
    expect(data[:8] == b"\x93NUMPY\x01\x00", "%s: .npy magic" % path)
    hlen = struct.unpack("<H", data[8:10])[0]
    header = ast.literal_eval(data[10:10 + hlen].decode("latin1"))
    expect((10 + hlen) % 64 == 0 and not header["fortran_order"], "%s: header %r" % (path, header))
    code = {"<f4": "f", "<u4": "I"}[header["descr"]]
    count = 1
    for d in header["shape"]:
        count *= d
    return header["shape"], struct.unpack("<%d%s" % (count, code), data[10 + hlen:10 + hlen + 4 * count])



def cross_view_agreement(cams, depth, W, H):
    """Covered pixels of each view, unprojected with their depth through cams[a] = (camera_to_world
    rows, fx, fy, cx, cy; OpenGL camera, pixel centres from the top-left), projected into the other
    views: how many land on a pixel whose depth is theirs within 2% (where not hidden)."""
    w2c = []
    for c2w, _, _, _, _ in cams:
        r = [[c2w[j][i2] for j in range(3)] for i2 in range(3)]  # R^T, -R^T t
        w2c.append((r, [-sum(r[i2][j] * c2w[j][3] for j in range(3)) for i2 in range(3)]))
    agree = checked = 0
    for a, (c2w, fx, fy, cx, cy) in enumerate(cams):
        for y in range(H):
            for x in range(W):
                z = depth[a][y * W + x]
                if z <= 0:
                    continue
                pc = [(x + 0.5 - cx) / fx * z, -(y + 0.5 - cy) / fy * z, -z]
                p = [sum(c2w[r][k] * pc[k] for k in range(3)) + c2w[r][3] for r in range(3)]
                for b, (_, fxb, fyb, cxb, cyb) in enumerate(cams):
                    if b == a:
                        continue
                    r, t = w2c[b]
                    q = [sum(r[i2][k] * p[k] for k in range(3)) + t[i2] for i2 in range(3)]
                    if q[2] >= 0:
                        continue
                    u = fxb * q[0] / -q[2] + cxb
                    v = fyb * -q[1] / -q[2] + cyb
                    if not (0 <= u < W and 0 <= v < H):
                        continue
                    zb = depth[b][int(v) * W + int(u)]
                    if zb <= 0 or zb < -q[2] * 0.98:
                        continue  # hidden in view b (something nearer), or off the surface's edge
                    checked += 1
                    agree += abs(zb + q[2]) <= 0.02 * -q[2]
    return agree, checked


def quaternion(m):
    """x, y, z, w of a rotation matrix (rows)."""
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return tuple(q)


out = os.path.join(OUT, "outputs")
views = 5
run = subprocess.run([MVR, "render", FILE, "--layout", "sphere", "--views", str(views), "--size", "64x48",
                      "--out", out, "--quiet", "--outputs", "depth,ids"], capture_output=True, text=True)
expect(run.returncode == 0, "outputs: mvr render exits %d: %s" % (run.returncode, run.stderr))
if run.returncode == 0:
    nerf = json.load(open(os.path.join(out, "transforms.json")))
    W, H = 64, 48
    depth, ids, w2c = [], [], []
    for k, n in enumerate(nerf["frames"]):
        shape, d = load_npy(os.path.join(out, "depth_%04d.npy" % k))
        expect(shape == (H, W), "depth_%04d: shape %r" % (k, shape))
        shape, i = load_npy(os.path.join(out, "ids_%04d.npy" % k))
        expect(shape == (H, W, 4), "ids_%04d: shape %r" % (k, shape))
        depth.append(d)
        ids.append(i)
        c2w = n["transform_matrix"]
        # the inverse of a rigid transform: R^T, -R^T t
        r = [[c2w[j][i2] for j in range(3)] for i2 in range(3)]
        t = [-sum(r[i2][j] * c2w[j][3] for j in range(3)) for i2 in range(3)]
        w2c.append((r, t))
        mismatched = sum(1 for p in range(W * H) if (d[p] > 0) != (i[4 * p] != 0))
        expect(mismatched == 0, "view %d: %d pixels where depth and IDs disagree on coverage" % (k, mismatched))
    # ids.json names every node and mesh the IDs use, and a node's mesh is the mesh channel
    names = json.load(open(os.path.join(out, "ids.json")))
    node_mesh = {n["id"]: n["mesh"] for n in names["nodes"]}
    mesh_ids = {m["id"] for m in names["meshes"]}
    seen = set()
    for i in ids:
        for p in range(W * H):
            if i[4 * p]:
                seen.add((i[4 * p], i[4 * p + 1]))
    expect(seen and all(node_mesh.get(n) == m and m in mesh_ids for n, m in seen),
           "outputs: ids.json does not name the (node, mesh) pairs %r" % sorted(seen))
    cams = [(n["transform_matrix"], n["fl_x"], n["fl_y"], n["cx"], n["cy"]) for n in nerf["frames"]]
    agree, checked = cross_view_agreement(cams, depth, W, H)
    frac = agree / checked if checked else 0.0
    expect(checked > 1000 and frac > 0.9,
           "outputs: %d of %d cross-view reprojections agree in depth (%.1f%%)" % (agree, checked, 100 * frac))
    print("outputs %d views: %d cross-view reprojections, %.1f%% agree within 2%% in depth" %
          (views, checked, 100 * frac))

    # A camera file: the same poses as a CSV with intrinsics of its own (off-centre principal points,
    # fx != fy); rendered with --cameras, the views' depth and IDs reproject through the FILE's
    # cameras (not what mvr writes back), as a dataset made from given poses needs.
    csv_path = os.path.join(OUT, "cams.csv")
    file_cams = []
    with open(csv_path, "w") as f:
        f.write("x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height\n")
        for k, (c2w, fx, fy, cx, cy) in enumerate(cams):
            fx2, fy2, cx2, cy2 = fx * (1.0 + 0.05 * k), fy * (1.1 - 0.03 * k), cx + 3.5 - k, cy - 2.25 + 0.5 * k
            qx, qy, qz, qw = quaternion([row[:3] for row in c2w[:3]])
            f.write("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n" %
                    (c2w[0][3], c2w[1][3], c2w[2][3], qx, qy, qz, qw, fx2, fy2, cx2, cy2, W, H))
            file_cams.append((c2w, fx2, fy2, cx2, cy2))
    out_csv = os.path.join(OUT, "outputs_csv")
    run = subprocess.run([MVR, "render", FILE, "--cameras", csv_path, "--out", out_csv, "--quiet",
                          "--outputs", "depth,ids"], capture_output=True, text=True)
    expect(run.returncode == 0, "--cameras: mvr render exits %d: %s" % (run.returncode, run.stderr))
    if run.returncode == 0:
        depth_csv = []
        for k in range(len(file_cams)):
            shape, d = load_npy(os.path.join(out_csv, "depth_%04d.npy" % k))
            expect(shape == (H, W), "--cameras depth_%04d: shape %r" % (k, shape))
            depth_csv.append(d)
        agree, checked = cross_view_agreement(file_cams, depth_csv, W, H)
        frac = agree / checked if checked else 0.0
        expect(checked > 1000 and frac > 0.9, "--cameras: %d of %d cross-view reprojections agree (%.1f%%)" %
               (agree, checked, 100 * frac))
        print("--cameras CSV %d views: %d cross-view reprojections through the file's cameras, %.1f%% agree" %
              (len(file_cams), checked, 100 * frac))

sys.exit(1 if failures else 0)
