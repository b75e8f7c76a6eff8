#!/usr/bin/env python3
"""ctest: mvr render --cameras FILE (and mvr bench --cameras).

  python3 test_cli_camera_files.py MVR SCENE.gltf OUT

- mvr's own cameras.json, given back to --cameras, renders the same views: byte-equal images and
  cameras.json, for a demo (frustum views) and a glTF file (sphere layout, perspective views); the
  file's image size is the layers' without --size;
- a CSV with off-centre principal points and fx != fy renders views whose written intrinsics are
  the CSV's within 1e-9 (relative) and whose camera_to_world is the CSV's pose within 1e-12; at
  --size twice as large, the intrinsics double (the same fields of view);
- NeRF's transforms.json with camera_angle_x only takes --size; with fl_x .. cy and w, h, its own;
- a cameras.json edited by hand (a camera moved) is rendered from the edited pose, with a note;
- hostile files and conflicting options are refused (exit 2) before any GL, the message naming
  the file, the view, the field and the line.
Python's standard library only."""
import json
import math
import os
import struct
import subprocess
import sys

MVR, SCENE, OUT = sys.argv[1:4]
os.makedirs(OUT, exist_ok=True)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args):
    return subprocess.run([MVR] + [str(a) for a in args], capture_output=True, text=True)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def write(name, text):
    path = os.path.join(OUT, name)
    with open(path, "w", newline="") as f:
        f.write(text)
    return path


def png_size(path):
    head = read(path)[:24]
    return struct.unpack(">II", head[16:24])


def same_files(a, b, names):
    return [n for n in names if not (os.path.exists(os.path.join(a, n)) and os.path.exists(os.path.join(b, n))
                                     and read(os.path.join(a, n)) == read(os.path.join(b, n)))]


def rel(a, b):
    return abs(a - b) / abs(b)


# 1. round trips through mvr's own cameras.json: the same views, the same bytes
for label, source, extra in (("demo", ["--demo", "stereo", "--views", "3"], []),
                             ("file", [SCENE, "--layout", "sphere", "--views", "5"], [SCENE])):
    first, again = os.path.join(OUT, label + "_first"), os.path.join(OUT, label + "_again")
    r = run("render", *source, "--size", "96x72", "--out", first, "--quiet")
    expect(r.returncode == 0, "%s: first render exits %d: %s" % (label, r.returncode, r.stderr))
    cams = json.load(open(os.path.join(first, "cameras.json")))
    expect(all("mvr_view" in f for f in cams["frames"]), "%s: cameras.json has each view's mvr_view" % label)
    args = ["--demo", "stereo"] if label == "demo" else extra
    r = run("render", *args, "--cameras", os.path.join(first, "cameras.json"), "--out", again)
    expect(r.returncode == 0, "%s: --cameras render exits %d: %s" % (label, r.returncode, r.stderr))
    expect("(mvr cameras.json)" in r.stdout, "%s: the summary names the format: %s" % (label, r.stdout))
    n = len(cams["frames"])
    names = ["view_%04d.png" % k for k in range(n)] + ["contact_sheet.png", "cameras.json", "transforms.json"]
    differ = same_files(first, again, names)
    expect(not differ, "%s: the round trip changed %s" % (label, differ))
    expect(png_size(os.path.join(again, "view_0000.png")) == (96, 72), "%s: the file's size is the layers'" % label)

# 2. CSV: off-centre principal points, fx != fy, exactly
csv_views = [  # x, y, z, qx, qy, qz, qw, fx, fy, cx, cy
    (0.0, 0.6, 3.0, 0.0, 0.0, 0.0, 1.0, 120.5, 97.25, 52.75, 21.5),
    (2.5, 1.0, 2.0, -0.0871557427476582, 0.3826834323650898, 0.0, 0.9196926686820518, 88.0, 140.125, 33.0, 41.0),
    (-2.0, 0.3, 1.5, 0.0, -0.5, 0.0, 0.8660254037844386, 60.0, 60.5, 61.25, 30.0),
]
rows = ["x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height,znear"]
rows += [",".join(repr(v) for v in row) + ",90,60,0.05" for row in csv_views]
csv = write("views.csv", "\r\n".join(rows) + "\r\n")


def quat_matrix(x, y, z, w):
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


for size, scale in ((None, 1), ("180x120", 2)):
    out = os.path.join(OUT, "csv_%d" % scale)
    r = run("render", SCENE, "--cameras", csv, "--out", out, "--quiet", *(["--size", size] if size else []))
    expect(r.returncode == 0, "csv x%d: exits %d: %s" % (scale, r.returncode, r.stderr))
    if r.returncode != 0:
        continue
    frames = json.load(open(os.path.join(out, "cameras.json")))["frames"]
    expect(len(frames) == 3, "csv x%d: 3 views" % scale)
    expect(png_size(os.path.join(out, "view_0002.png")) == (90 * scale, 60 * scale), "csv x%d: image size" % scale)
    worst = worst_pose = 0.0
    for f, v in zip(frames, csv_views):
        for key, want in zip(("fl_x", "fl_y", "cx", "cy"), v[7:11]):
            worst = max(worst, rel(f[key], want * scale))
        rot = quat_matrix(*v[3:7])
        c2w = f["camera_to_world"]
        worst_pose = max([worst_pose] + [abs(c2w[i][j] - rot[i][j]) for i in range(3) for j in range(3)] +
                         [abs(c2w[i][3] - v[i]) for i in range(3)])
    expect(worst < 1e-9, "csv x%d: intrinsics off by %g (relative)" % (scale, worst))
    expect(worst_pose < 1e-12, "csv x%d: camera_to_world off by %g" % (scale, worst_pose))

# 3. NeRF: camera_angle_x only (the size from --size), then with its own intrinsics and size
angle = 0.6911112070083618
nerf = write("synthetic.json", json.dumps({"camera_angle_x": angle, "frames": [
    {"file_path": "./train/r_0", "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0.5], [0, 0, 1, 4], [0, 0, 0, 1]]}]}))
out = os.path.join(OUT, "nerf_angle")
r = run("render", SCENE, "--cameras", nerf, "--size", "80x80", "--out", out, "--quiet")
expect(r.returncode == 0, "nerf angle: exits %d: %s" % (r.returncode, r.stderr))
if r.returncode == 0:
    f = json.load(open(os.path.join(out, "cameras.json")))["frames"][0]
    fl = 40 / math.tan(angle / 2)
    expect(rel(f["fl_x"], fl) < 1e-9 and rel(f["fl_y"], fl) < 1e-9 and rel(f["cx"], 40) < 1e-9,
           "nerf angle: fl %r, want %r" % (f["fl_x"], fl))
studio = write("studio.json", json.dumps({"camera_model": "OPENCV", "fl_x": 70.5, "fl_y": 66.0, "cx": 35.5,
                                          "cy": 20.25, "w": 72, "h": 48, "k1": 0, "frames": [
    {"transform_matrix": [[0, 0, 1, 4], [0, 1, 0, 0.5], [-1, 0, 0, 0], [0, 0, 0, 1]]},
    {"cy": 27.0, "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0.5], [0, 0, 1, 4], [0, 0, 0, 1]]}]}))
out = os.path.join(OUT, "nerf_studio")
r = run("render", SCENE, "--cameras", studio, "--out", out, "--quiet")
expect(r.returncode == 0, "nerfstudio: exits %d: %s" % (r.returncode, r.stderr))
if r.returncode == 0:
    frames = json.load(open(os.path.join(out, "cameras.json")))["frames"]
    expect(png_size(os.path.join(out, "view_0001.png")) == (72, 48), "nerfstudio: its own size")
    expect(rel(frames[0]["cy"], 20.25) < 1e-9 and rel(frames[1]["cy"], 27.0) < 1e-9, "nerfstudio: per-frame cy")

# 4. a cameras.json edited by hand: the edited pose wins, with a note
edited_dir = os.path.join(OUT, "file_first")
cams = json.load(open(os.path.join(edited_dir, "cameras.json")))
cams["frames"][1]["camera_to_world"][0][3] += 0.25
edited = write("edited.json", json.dumps(cams))
out = os.path.join(OUT, "edited")
r = run("render", SCENE, "--cameras", edited, "--out", out)
expect(r.returncode == 0, "edited: exits %d: %s" % (r.returncode, r.stderr))
expect("1 view (the first: view 1) no longer matches" in r.stderr, "edited: a note: %s" % r.stderr)
if r.returncode == 0:
    frames = json.load(open(os.path.join(out, "cameras.json")))["frames"]
    want = cams["frames"][1]["camera_to_world"][0][3]
    expect(abs(frames[1]["camera_to_world"][0][3] - want) < 1e-12, "edited: view 1 moved")
    expect(abs(frames[0]["camera_to_world"][0][3] - cams["frames"][0]["camera_to_world"][0][3]) < 1e-12,
           "edited: view 0 where it was")

# 5. refused before any GL: exit 2, the file, the view, the field and the line named
hostile = [
    ("sizes.csv", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height\n0,0,3,0,0,0,1,50,50,32,24,64,48\n"
                  "0,0,3,0,0,0,1,50,50,32,24,64,40\n", ["view 1 (line 3)", "64x40", "64x48", "one size"]),
    ("nan.csv", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy\n0,0,3,0,0,0,1,50,NaN,32,24\n", ["view 0 (line 2)", "fy", "'NaN'"]),
    ("scaled.json", json.dumps({"fl_x": 50, "frames": [
        {"transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]]},
        {"transform_matrix": [[1.5, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]]}]}),
     ["view 1", "transform_matrix", "not orthonormal"]),
    ("missing.json", '{"frames": [\n{"w": 8, "h": 8, "camera_to_world": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}',
     ["view 0 (line 2)", "fl_x", "missing"]),
    ("broken.json", '{"frames": [\n{"fl_x": 1e999}]}', ["line 2", "out of range"]),
]
for name, text, words in hostile:
    path = write(name, text)
    r = run("render", SCENE, "--cameras", path, "--out", os.path.join(OUT, "refused"), "--context", "surfaceless")
    expect(r.returncode == 2, "%s: exit %d (want 2): %s" % (name, r.returncode, r.stderr))
    for w in ["--cameras " + path] + words:
        expect(w in r.stderr, "%s: '%s' not in: %s" % (name, w, r.stderr))
r = run("render", SCENE, "--cameras", os.path.join(OUT, "no_such.csv"))
expect(r.returncode == 2 and "cannot open it" in r.stderr, "a missing file: %s" % r.stderr)
r = run("render", SCENE, "--cameras", csv, "--views", "4")
expect(r.returncode == 2 and "--views" in r.stderr and "--cameras" in r.stderr, "--views conflicts: %s" % r.stderr)
r = run("render", SCENE, "--layout", "ring", "--cameras", csv)
expect(r.returncode == 2 and "--layout" in r.stderr, "--layout conflicts: %s" % r.stderr)
r = run("bench", "--cameras", os.path.join(OUT, "sizes.csv"), "--out", os.path.join(OUT, "bench"))
expect(r.returncode == 2 and "mvr bench: --cameras" in r.stderr and "view 1" in r.stderr,
       "bench refuses the same file: %s" % r.stderr)

print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
