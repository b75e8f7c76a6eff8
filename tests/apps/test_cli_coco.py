#!/usr/bin/env python3
"""ctest: mvr render's COCO annotations (issue 33 part 3), checked against the ID arrays exactly.

  /usr/bin/python3 test_cli_coco.py MVR SCENE.gltf OUT    (textured.gltf is taken from SCENE's folder)

With --outputs ids, annotations/instances.json (one instance per node a view sees) and
annotations/instances_mesh.json (one per mesh) hold:
- images: one per view, id = view + 1, file_name view_VVVV.png (the file exists), width, height;
- categories: one per mesh of ids.json, id = mesh id, name = its name or "mesh_<id>", supercategory "mesh";
- annotations: exactly one per (view, id) of the ids_VVVV.npy channel (0: node, 1: mesh), unique ids,
  the uncompressed RLE (column-major, zeros first: pycocotools' convention), decoded here, equal to
  (ids[..., channel] == id) pixel for pixel; bbox [x, y, w, h] and area exact; category the node's
  mesh (ids.json); mvr_node_id / mvr_node_name as ids.json says.
A view filled by one node has counts [0, h * w]. Without npy among --output-files: no annotations, a warning, exit 0.
Python's standard library and numpy."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

MVR, SCENE, OUT = sys.argv[1:4]
shutil.rmtree(OUT, ignore_errors=True)  # a file left by an earlier run proves nothing
os.makedirs(OUT)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def render(name, *args):
    out = os.path.join(OUT, name)
    r = subprocess.run([MVR, "render"] + [str(a) for a in args] + ["--out", out], capture_output=True, text=True)
    expect(r.returncode == 0, "%s exits 0 (got %d): %s" % (name, r.returncode, r.stderr))
    return out, r


def load(path):
    with open(path) as f:
        return json.load(f)


def decode_rle(seg):
    """pycocotools' uncompressed RLE: alternating runs of 0 and 1 (zeros first) over the mask
    flattened in column-major order; size is [h, w]."""
    h, w = seg["size"]
    counts = seg["counts"]
    if sum(counts) != h * w or any(c < 0 for c in counts):
        return None
    flat = np.zeros(h * w, dtype=bool)
    at = 0
    for i, c in enumerate(counts):
        if i % 2:
            flat[at:at + c] = True
        at += c
    return flat.reshape((w, h)).T  # column-major: index x * h + y


def check_file(out, coco, channel, views, W, H, ids_json):
    label = os.path.basename(coco)
    expect(os.path.exists(coco), "%s written" % coco)
    if not os.path.exists(coco):
        return 0
    c = load(coco)
    for key in ("info", "images", "categories", "annotations"):
        expect(key in c, "%s has %s" % (label, key))
    images = c.get("images", [])
    expect([i["id"] for i in images] == list(range(1, views + 1)), "%s: image ids 1..%d" % (label, views))
    for i in images:
        expect(i["file_name"] == "view_%04d.png" % (i["id"] - 1) and (i["width"], i["height"]) == (W, H),
               "%s: image %r" % (label, i))
        expect(os.path.exists(os.path.join(out, i["file_name"])), "%s: %s exists" % (label, i["file_name"]))
    meshes = ids_json["meshes"]
    want_categories = [{"id": m["id"], "name": m["name"] or "mesh_%d" % m["id"], "supercategory": "mesh"}
                       for m in meshes]
    expect(c.get("categories") == want_categories, "%s: categories are ids.json's meshes" % label)
    nodes = {n["id"]: n for n in ids_json["nodes"]}
    anns = c.get("annotations", [])
    expect(len({a["id"] for a in anns}) == len(anns), "%s: annotation ids unique" % label)
    seen = {}
    for a in anns:
        key = (a["image_id"], a["mvr_node_id"] if channel == 0 else a["mvr_mesh_id"])
        expect(key not in seen, "%s: one annotation for %r" % (label, key))
        seen[key] = a
    total_multi = 0
    for v in range(views):
        ids = np.load(os.path.join(out, "ids_%04d.npy" % v))
        expect(ids.shape == (H, W, 4) and ids.dtype == np.uint32, "ids_%04d.npy shape %r" % (v, ids.shape))
        plane = ids[..., channel]
        visible = sorted(int(n) for n in np.unique(plane) if n)
        mine = sorted(k[1] for k in seen if k[0] == v + 1)
        expect(mine == visible, "%s view %d: annotated %r, visible %r" % (label, v, mine, visible))
        total_multi += len(visible) > 1
        for n in visible:
            a = seen.get((v + 1, n))
            if not a:
                continue
            want = plane == n
            seg = a["segmentation"]
            expect(seg["size"] == [H, W], "%s view %d id %d: size %r" % (label, v, n, seg["size"]))
            got = decode_rle(seg)
            expect(got is not None and got.shape == want.shape and np.array_equal(got, want),
                   "%s view %d id %d: RLE decodes to the ID mask" % (label, v, n))
            ys, xs = np.nonzero(want)
            bbox = [int(xs.min()), int(ys.min()), int(xs.max() - xs.min() + 1), int(ys.max() - ys.min() + 1)]
            expect(a["bbox"] == bbox, "%s view %d id %d: bbox %r, want %r" % (label, v, n, a["bbox"], bbox))
            expect(a["area"] == int(want.sum()), "%s view %d id %d: area %r" % (label, v, n, a["area"]))
            expect(a["iscrowd"] == 0, "%s: iscrowd 0" % label)
            if channel == 0:
                expect(a["category_id"] == nodes[n]["mesh"], "%s view %d node %d: category its mesh" % (label, v, n))
                expect(a["mvr_node_name"] == nodes[n]["name"], "%s node %d: name" % (label, n))
            else:
                expect(a["category_id"] == n, "%s view %d mesh %d: category the mesh" % (label, v, n))
    expect(total_multi > 0, "%s: some view shows several instances" % label)
    return len(anns)


W, H, VIEWS = 96, 72, 6
out, _ = render("ids", SCENE, "--layout", "sphere", "--views", VIEWS, "--size", "%dx%d" % (W, H), "--outputs", "ids",
                "--quiet")
ids_json = load(os.path.join(out, "ids.json"))
n_nodes = check_file(out, os.path.join(out, "annotations", "instances.json"), 0, VIEWS, W, H, ids_json)
n_meshes = check_file(out, os.path.join(out, "annotations", "instances_mesh.json"), 1, VIEWS, W, H, ids_json)
expect(n_nodes >= VIEWS * 2 and n_meshes >= VIEWS * 2, "annotations written: %d, %d" % (n_nodes, n_meshes))

# a mask that starts at pixel 0 and runs to the last one: counts [0, h * w] (zeros first, even none)
plane = os.path.join(os.path.dirname(SCENE), "textured.gltf")
out, _ = render("full", plane, "--layout", "ring", "--views", 2, "--size", "32x24", "--radius", 0.3, "--outputs", "ids",
                "--quiet")
full_path = os.path.join(out, "annotations", "instances.json")
full = load(full_path).get("annotations", []) if os.path.exists(full_path) else []
expect(len(full) == 2 and all(a["segmentation"]["counts"] == [0, 32 * 24] and a["bbox"] == [0, 0, 32, 24]
                              for a in full), "a full-frame mask: counts [0, h * w]: %r" % full[:1])

# no .npy written: nothing to read the IDs from; a warning, no file
out, r = render("png_only", SCENE, "--views", 2, "--size", "32x24", "--outputs", "ids", "--output-files", "png")
expect(not os.path.exists(os.path.join(out, "annotations", "instances.json")), "no npy: no instances.json")
expect("instances.json" in r.stderr and "npy" in r.stderr, "no npy: a warning names the fix: %r" % r.stderr)

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("ok")
