#!/usr/bin/env python3
"""Writes boxes.gltf, the low-poly scene of scripts/peers/bench_peers.sh: a
ground plane and a 6 x 6 grid of boxes (four untextured metallic-roughness
materials), one directional light (KHR_lights_punctual) and a perspective
camera that the ground fills, so a frame is bound by its pixels. The buffer
is embedded (one self-contained file).

    scripts/peers/make_boxes.py OUT_DIR
"""
import base64
import json
import math
import pathlib
import struct
import sys

# a unit cube's 24 vertices (4 a face, flat normals), counter-clockwise seen from outside
_FACES = [((1, 0, 0), (0, 1, 0)), ((-1, 0, 0), (0, 1, 0)), ((0, 1, 0), (0, 0, 1)),
          ((0, -1, 0), (0, 0, 1)), ((0, 0, 1), (1, 0, 0)), ((0, 0, -1), (1, 0, 0))]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _cube():
    pos, nrm, idx = [], [], []
    for n, u in _FACES:
        v = _cross(n, u)
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(0.5 * (n[i] + su * u[i] + sv * v[i]) for i in range(3)))
            nrm.append(n)
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def _quat_look(eye, target):
    """Rotation (x, y, z, w) of a camera at eye looking at target, +Y up (glTF cameras look along -Z)."""
    f = [t - e for t, e in zip(target, eye)]
    ln = math.sqrt(sum(c * c for c in f))
    z = [-c / ln for c in f]                       # camera +Z points away from the target
    x = _cross((0.0, 1.0, 0.0), z)
    lx = math.sqrt(sum(c * c for c in x))
    x = [c / lx for c in x]
    y = _cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # columns x, y, z
    w = math.sqrt(max(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2])) / 2.0
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]


def scene():
    pos, nrm, idx = _cube()
    data = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm)
    data += b"".join(struct.pack("<H", i) for i in idx)
    n_v = len(pos)
    colors = [[0.8, 0.3, 0.2, 1], [0.2, 0.5, 0.8, 1], [0.9, 0.8, 0.3, 1], [0.6, 0.6, 0.6, 1]]
    materials = [{"name": f"box{k}", "pbrMetallicRoughness": {"baseColorFactor": c, "metallicFactor": 0.5 * (k % 2),
                                                             "roughnessFactor": 0.35 + 0.15 * k}}
                 for k, c in enumerate(colors)]
    materials.append({"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.5, 0.45, 1],
                                                                 "metallicFactor": 0.0, "roughnessFactor": 0.8}})
    nodes = [{"mesh": 4, "translation": [0, -0.05, 0], "scale": [40, 0.1, 40], "name": "ground"}]
    for z in range(6):
        for x in range(6):
            h = 0.6 + ((x * 7 + z * 3) % 5) * 0.35
            nodes.append({"mesh": (x + z) % 4, "translation": [(x - 2.5) * 2.0, h / 2, (z - 2.5) * 2.0],
                          "scale": [1.2, h, 1.2]})
    eye, target = [0.0, 6.0, 11.0], [0.0, 0.0, 0.5]
    nodes.append({"camera": 0, "translation": eye, "rotation": _quat_look(eye, target), "name": "camera"})
    nodes.append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "name": "sun",
                  "rotation": _quat_look([0, 0, 0], [-0.4, -1.0, -0.6])})
    return {
        "asset": {"version": "2.0", "generator": "scripts/peers/make_boxes.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1, 0.97, 0.92],
                                                            "intensity": 2.0}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 4 / 3, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": k}]}
                   for k in range(5)],
        "materials": materials,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n_v, "target": 34962},
                        {"buffer": 0, "byteOffset": 12 * n_v, "byteLength": 12 * n_v, "target": 34962},
                        {"buffer": 0, "byteOffset": 24 * n_v, "byteLength": 2 * len(idx), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": n_v, "type": "VEC3",
                       "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
                      {"bufferView": 1, "componentType": 5126, "count": n_v, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
    }


if __name__ == "__main__":
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    out.mkdir(parents=True, exist_ok=True)
    (out / "boxes.gltf").write_text(json.dumps(scene(), indent=1) + "\n")
    print(out / "boxes.gltf")
