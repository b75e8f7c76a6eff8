#!/usr/bin/env python3
"""ctest: a flat scene is seen from above by default (issue 35).

  python3 test_cli_framing.py MVR OUT

The scene, written here: a ground plane 40 x 40 units (y = 0) with three unit cubes standing on
it, no camera. The old default (level, the bounding sphere fitted) saw the plane edge-on: 0.4%
of the view, the scene 0.5%. `mvr render FILE --size 320x240 --outputs ids` with every other
option the default (the stereo pair of the library's framing: 30 degrees above, the bounding
box fitted with a 5% margin), and --layout ring and grid: in every view the plane covers >= 25%
of the image (31-34% measured), each cube >= 12 pixels (17-49 measured), the scene as a whole
>= 25% (the issue asks >= 3%), and no cube is cut by the image's edge. Areas come from the COCO
annotations the ID outputs make (one per node a view sees). Python's standard library only."""
import base64
import json
import os
import shutil
import struct
import subprocess
import sys

MVR, OUT = sys.argv[1:3]
W, H = 320, 240
PLANE_MIN, CUBE_MIN_PIXELS, SCENE_MIN = 0.25, 12, 0.25
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def flat_scene(path):
    """The plane (node 'ground') and three cubes ('cube_a' .. 'cube_c'), each mesh its own
    material; positions and indices in one base64 buffer."""
    plane = [(-20, 0, -20), (20, 0, -20), (20, 0, 20), (-20, 0, 20)]
    plane_idx = [0, 2, 1, 0, 3, 2]  # counter-clockwise seen from +Y
    cube = [(x, y, z) for z in (-0.5, 0.5) for y in (0.0, 1.0) for x in (-0.5, 0.5)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    cube_idx = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
    blobs, views, accessors = [], [], []

    def add(data, target):
        off = sum(len(b) for b in blobs)
        blobs.append(data + b"\0" * (-len(data) % 4))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
        return len(views) - 1

    def mesh_accessors(verts, idx):
        pos = add(b"".join(struct.pack("<3f", *v) for v in verts), 34962)
        ind = add(struct.pack("<%dH" % len(idx), *idx), 34963)
        lo = [min(v[k] for v in verts) for k in range(3)]
        hi = [max(v[k] for v in verts) for k in range(3)]
        accessors.append({"bufferView": pos, "componentType": 5126, "count": len(verts), "type": "VEC3",
                          "min": lo, "max": hi})
        accessors.append({"bufferView": ind, "componentType": 5123, "count": len(idx), "type": "SCALAR"})
        return len(accessors) - 2, len(accessors) - 1

    p_pos, p_ind = mesh_accessors(plane, plane_idx)
    c_pos, c_ind = mesh_accessors(cube, cube_idx)
    buf = b"".join(blobs)
    doc = {
        "asset": {"version": "2.0", "generator": "mvr tests/apps/test_cli_framing.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"name": "ground", "mesh": 0},
                  {"name": "cube_a", "mesh": 1, "translation": [-12, 0, -9]},
                  {"name": "cube_b", "mesh": 1, "translation": [0, 0, 0]},
                  {"name": "cube_c", "mesh": 1, "translation": [13, 0, 10]}],
        "meshes": [{"name": "ground", "primitives": [{"attributes": {"POSITION": p_pos}, "indices": p_ind,
                                                      "material": 0}]},
                   {"name": "cube", "primitives": [{"attributes": {"POSITION": c_pos}, "indices": c_ind,
                                                    "material": 1}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.45, 1], "metallicFactor": 0}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
    }
    with open(path, "w") as f:
        json.dump(doc, f)


scene = os.path.join(OUT, "flat.gltf")
flat_scene(scene)
names = {"ground", "cube_a", "cube_b", "cube_c"}
for label, extra in (("default", []), ("ring", ["--layout", "ring", "--views", "4"]),
                     ("grid", ["--layout", "grid", "--views", "4"])):
    out = os.path.join(OUT, label)
    r = subprocess.run([MVR, "render", scene, "--size", "%dx%d" % (W, H), "--outputs", "ids", "--out", out,
                        "--quiet"] + extra, capture_output=True, text=True)
    expect(r.returncode == 0, "%s: mvr render exits %d: %s" % (label, r.returncode, r.stderr))
    if r.returncode != 0:
        continue
    with open(os.path.join(out, "annotations", "instances.json")) as f:
        coco = json.load(f)
    expect(len(coco["images"]) == (2 if label == "default" else 4), "%s: %d views" % (label, len(coco["images"])))
    for image in coco["images"]:
        seen = {a["mvr_node_name"]: a for a in coco["annotations"] if a["image_id"] == image["id"]}
        areas = {n: seen[n]["area"] if n in seen else 0 for n in names}
        total = sum(areas.values()) / float(W * H)
        print("%s view %d: ground %.1f%%, cubes %d / %d / %d pixels, scene %.1f%%" % (
            label, image["id"] - 1, 100.0 * areas["ground"] / (W * H), areas["cube_a"], areas["cube_b"],
            areas["cube_c"], 100.0 * total))
        expect(areas["ground"] >= PLANE_MIN * W * H, "%s view %d: the ground covers %.1f%% (< %.0f%%)" % (
            label, image["id"] - 1, 100.0 * areas["ground"] / (W * H), 100 * PLANE_MIN))
        expect(total >= SCENE_MIN, "%s view %d: the scene covers %.1f%%" % (label, image["id"] - 1, 100 * total))
        for n in ("cube_a", "cube_b", "cube_c"):
            expect(areas[n] >= CUBE_MIN_PIXELS, "%s view %d: %s covers %d pixels" % (
                label, image["id"] - 1, n, areas[n]))
            if n in seen:
                x, y, w, h = seen[n]["bbox"]
                expect(x > 0 and y > 0 and x + w < W and y + h < H, "%s view %d: %s is cut by the edge: bbox %r" % (
                    label, image["id"] - 1, n, seen[n]["bbox"]))

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
