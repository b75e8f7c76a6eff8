#!/usr/bin/env python3
"""Writes a small node-animated glTF file for the CLI and viewer tests.

usage: make_animated_gltf.py OUT.gltf [--dolly]

Two boxes and a camera, one embedded base64 buffer, no skins, no morph
targets (node TRS animation only), two LINEAR animations:
  0 'slide': node 'mover' (red box, upper half of the picture) translates
             from x = -1.5 to x = +1.5 over 0 .. 1 s
  1 'spin':  node 'spinner' (green bar, lower half) turns about +Z from
             0 to 180 degrees over 0 .. 2 s (keys at 0, 1 and 2 s)
The camera at (0, 0, 4.5) looks down -Z at both. --dolly adds animation
  2 'dolly': the camera node moves back from z = 4.5 to z = 8 over 0 .. 1 s
(views made from the file's camera must follow it). The file is the same
bytes on every run.
"""
import base64
import json
import math
import struct
import sys


def box():
    """A unit cube (-0.5..0.5): 24 vertices with face normals, 36 indices."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(positions)
            for a, b in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
                p = [0.0, 0.0, 0.0]
                p[axis] = 0.5 * sign
                p[u], p[v] = a, b
                positions.append(p)
                normals.append(n)
            # counter-clockwise seen from outside: (u, v, n) is right-handed
            if sign > 0:
                indices += [base, base + 1, base + 2, base, base + 2, base + 3]
            else:
                indices += [base, base + 2, base + 1, base, base + 3, base + 2]
    return positions, normals, indices


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--dolly"):
        sys.exit("usage: make_animated_gltf.py OUT.gltf [--dolly]")
    dolly = len(sys.argv) == 3
    positions, normals, indices = box()
    chunks, views, accessors = [], [], []

    def add(data, target=None):
        while sum(len(c) for c in chunks) % 4:
            chunks.append(b"\0")
        offset = sum(len(c) for c in chunks)
        chunks.append(data)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        return len(views) - 1

    def accessor(view, component, count, kind, lo=None, hi=None):
        a = {"bufferView": view, "componentType": component, "count": count, "type": kind}
        if lo is not None:
            a["min"], a["max"] = lo, hi
        accessors.append(a)
        return len(accessors) - 1

    floats = lambda values: struct.pack("<%df" % len(values), *values)
    flat = lambda rows: [x for r in rows for x in r]
    pos = accessor(add(floats(flat(positions)), 34962), 5126, len(positions), "VEC3", [-0.5] * 3, [0.5] * 3)
    nrm = accessor(add(floats(flat(normals)), 34962), 5126, len(normals), "VEC3")
    idx = accessor(add(struct.pack("<%dH" % len(indices), *indices), 34963), 5123, len(indices), "SCALAR")

    slide_t = [0.0, 1.0]
    slide_v = [[-1.5, 0.8, 0.0], [1.5, 0.8, 0.0]]
    spin_t = [0.0, 1.0, 2.0]
    spin_v = []
    for deg in (0.0, 90.0, 180.0):
        h = math.radians(deg) * 0.5
        spin_v.append([0.0, 0.0, math.sin(h), math.cos(h)])
    st = accessor(add(floats(slide_t)), 5126, 2, "SCALAR", [0.0], [1.0])
    sv = accessor(add(floats(flat(slide_v))), 5126, 2, "VEC3")
    rt = accessor(add(floats(spin_t)), 5126, 3, "SCALAR", [0.0], [2.0])
    rv = accessor(add(floats(flat(spin_v))), 5126, 3, "VEC4")
    dv = accessor(add(floats([0.0, 0.0, 4.5, 0.0, 0.0, 8.0])), 5126, 2, "VEC3") if dolly else None

    data = b"".join(chunks)
    doc = {
        "asset": {"version": "2.0", "generator": "mvr tests/apps/make_animated_gltf.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "mover", "mesh": 0, "translation": [-1.5, 0.8, 0.0], "scale": [0.8, 0.8, 0.8]},
            {"name": "spinner", "mesh": 1, "translation": [0.0, -0.8, 0.0], "scale": [2.0, 0.4, 0.4]},
            {"name": "camera", "camera": 0, "translation": [0.0, 0.0, 4.5]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "meshes": [
            {"name": "red box", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx,
                                                "material": 0}]},
            {"name": "green bar", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx,
                                                  "material": 1}]},
        ],
        "materials": [
            {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0,
                                                     "roughnessFactor": 0.6}},
            {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.7, 0.2, 1.0],
                                                       "metallicFactor": 0.0, "roughnessFactor": 0.6}},
        ],
        "animations": [
            {"name": "slide", "samplers": [{"input": st, "output": sv, "interpolation": "LINEAR"}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]},
            {"name": "spin", "samplers": [{"input": rt, "output": rv, "interpolation": "LINEAR"}],
             "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}]},
        ],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")}],
    }
    if dolly:
        doc["animations"].append(
            {"name": "dolly", "samplers": [{"input": st, "output": dv, "interpolation": "LINEAR"}],
             "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}}]})
    with open(sys.argv[1], "w", encoding="ascii") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
