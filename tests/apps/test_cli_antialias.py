#!/usr/bin/env python3
"""ctest: a thin filament stays a continuous line with the default anti-aliasing (issue 35).

  python3 test_cli_antialias.py MVR OUT

The stand-in for AnisotropyBarnLamp's filament (the file is not in the project): a glowing rod
0.005 units thick and 8 long, tilted 8 degrees in the image plane, next to a unit cube that sets
the framing's scale; written here, no camera. At 640x480 with every other option the default
(`mvr render FILE --views 1 --size 640x480`: 4x MSAA, the default framing) the rod projects
about 0.35 pixels wide, so one sample per pixel misses it in most columns. The test finds the
rod's columns (where any render shows it) and asks, column by column, whether the rod lights a
pixel there (> 24/255 above the background in any channel):
  - default: every column lit (a continuous line);
  - --aa none: at least a fifth of the columns dark (it breaks into dots), so the scene really
    is thin enough for the first check to mean something;
  - --aa supersample (2x2, its sample rows 0.5 pixels apart): at most half the dark columns of
    --aa none (a 0.35-pixel line still falls between its rows in places).
Python's standard library and numpy; PNGs read by tests/dataset/png_read.py."""
import base64
import json
import math
import os
import shutil
import struct
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "dataset"))
import numpy as np  # noqa: E402
import png_read  # noqa: E402

MVR, OUT = sys.argv[1:3]
W, H = 640, 480
LIT = 24
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []


def expect(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def box(hx, hy, hz):
    """A box's 24 vertices (4 a face, for flat normals) and 36 indices, counter-clockwise outside."""
    verts, norms, idx = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = [(1, 2), (2, 0), (0, 1)][axis]
            base = len(verts)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign
                p[u], p[v] = a, b
                verts.append((p[0] * hx, p[1] * hy, p[2] * hz))
                norms.append(tuple(float(c) for c in n))
            quad = (0, 1, 2, 0, 2, 3) if sign > 0 else (0, 2, 1, 0, 3, 2)
            idx += [base + q for q in quad]
    return verts, norms, idx


def write_scene(path):
    blobs, views, accessors = [], [], []

    def add(data, target):
        off = sum(len(b) for b in blobs)
        blobs.append(data + b"\0" * (-len(data) % 4))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
        return len(views) - 1

    def mesh(verts, norms, idx):
        first = len(accessors)
        lo = [min(v[k] for v in verts) for k in range(3)]
        hi = [max(v[k] for v in verts) for k in range(3)]
        accessors.append({"bufferView": add(b"".join(struct.pack("<3f", *v) for v in verts), 34962),
                          "componentType": 5126, "count": len(verts), "type": "VEC3", "min": lo, "max": hi})
        accessors.append({"bufferView": add(b"".join(struct.pack("<3f", *n) for n in norms), 34962),
                          "componentType": 5126, "count": len(norms), "type": "VEC3"})
        accessors.append({"bufferView": add(struct.pack("<%dH" % len(idx), *idx), 34963),
                          "componentType": 5123, "count": len(idx), "type": "SCALAR"})
        return first

    rod = mesh(*box(4.0, 0.0025, 0.0025))
    cube = mesh(*box(0.5, 0.5, 0.5))
    tilt = math.radians(8) / 2  # about +Z, the image plane's normal seen from the front
    doc = {
        "asset": {"version": "2.0", "generator": "mvr tests/apps/test_cli_antialias.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "filament", "mesh": 0, "translation": [0, 1.5, 0],
                   "rotation": [0, 0, math.sin(tilt), math.cos(tilt)]},
                  {"name": "cube", "mesh": 1, "translation": [0, -1.0, 0]}],
        "meshes": [{"name": "filament", "primitives": [{"attributes": {"POSITION": rod, "NORMAL": rod + 1},
                                                        "indices": rod + 2, "material": 0}]},
                   {"name": "cube", "primitives": [{"attributes": {"POSITION": cube, "NORMAL": cube + 1},
                                                    "indices": cube + 2, "material": 1}]}],
        "materials": [{"name": "glow", "emissiveFactor": [1, 0.85, 0.5],
                       "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0}},
                      {"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                               "metallicFactor": 0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": sum(len(b) for b in blobs),
                     "uri": "data:application/octet-stream;base64," +
                            base64.b64encode(b"".join(blobs)).decode()}],
    }
    with open(path, "w") as f:
        json.dump(doc, f)


scene = os.path.join(OUT, "filament.gltf")
write_scene(scene)
renders = {}
for name, extra in (("default", []), ("none", ["--aa", "none"]), ("supersample", ["--aa", "supersample"])):
    out = os.path.join(OUT, name)
    cmd = [MVR, "render", scene, "--views", "1", "--size", "%dx%d" % (W, H), "--out", out, "--quiet"] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    expect(r.returncode == 0, "%s exits 0 (%s)" % (" ".join(cmd[1:]), r.stderr.strip()[-300:]))
    if r.returncode == 0:
        renders[name] = png_read.read(os.path.join(out, "view_0000.png"))[:, :, :3].astype(np.int32)
if len(renders) == 3:
    # the background: the top-left corner's colour (the rod and cube are framed in the middle)
    lit = {k: (np.abs(v - v[0, 0]).max(axis=2) > LIT) for k, v in renders.items()}
    # the rod's rows: above the cube (its centre is 2.5 units above the cube's), so the upper
    # part of the image; its columns: where any render lights a pixel in those rows
    rows = slice(0, H // 2)
    cols = np.nonzero(np.logical_or.reduce([m[rows].any(axis=0) for m in lit.values()]))[0]
    expect(len(cols) > W // 2, "the rod spans %d columns (> %d)" % (len(cols), W // 2))
    if len(cols):
        span = np.arange(cols.min(), cols.max() + 1)
        dark = {k: int((~lit[k][rows][:, span].any(axis=0)).sum()) for k in renders}
        expect(dark["default"] == 0, "default: the filament is continuous (%d of %d columns dark)"
               % (dark["default"], len(span)))
        expect(dark["none"] * 5 >= len(span), "--aa none: the filament breaks up (%d of %d columns dark, >= 1/5)"
               % (dark["none"], len(span)))
        expect(dark["supersample"] * 2 <= dark["none"], "--aa supersample: %d columns dark (<= half of none's)"
               % dark["supersample"])
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")
