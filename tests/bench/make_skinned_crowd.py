#!/usr/bin/env python3
"""Writes a skinned, morphed, animated glTF for benchmarking the skinning
paths (mvr bench SCENE, docs/benchmarks.md): a grid of N x N tubes, each its
own skeleton (a chain of B bones up the tube) and skin over one shared mesh
(R rings x S segments, every vertex weighted to its two nearest bones), one
morph target (a bulge, with normal deltas), and one animation that bends
every chain (phase-shifted per tube) and pulses the bulge. Python standard
library only; deterministic.

usage: make_skinned_crowd.py OUT.gltf [--grid N] [--rings R] [--segments S] [--bones B]
"""
import argparse
import base64
import json
import math
import struct


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--grid", type=int, default=4)
    ap.add_argument("--rings", type=int, default=128)
    ap.add_argument("--segments", type=int, default=48)
    ap.add_argument("--bones", type=int, default=8)
    a = ap.parse_args()
    R, S, B, N = a.rings, a.segments, a.bones, a.grid
    height, radius = 4.0, 0.3

    pos, nrm, joints, weights, bulge_p, bulge_n = [], [], [], [], [], []
    for r in range(R):
        y = height * r / (R - 1)
        # the bone below and above this ring, blended linearly between bone centres
        u = y / height * B - 0.5
        j0 = max(0, min(B - 1, int(math.floor(u))))
        j1 = min(B - 1, j0 + 1)
        w1 = max(0.0, min(1.0, u - j0)) if j1 != j0 else 0.0
        bulge = math.exp(-((y - height / 2) / 0.8) ** 2) * 0.25
        for s in range(S):
            a_ = 2 * math.pi * s / S
            c, sn = math.cos(a_), math.sin(a_)
            pos += [radius * c, y, radius * sn]
            nrm += [c, 0.0, sn]
            joints += [j0, j1, 0, 0]
            weights += [1.0 - w1, w1, 0.0, 0.0]
            bulge_p += [bulge * c, 0.0, bulge * sn]
            bulge_n += [0.0, 0.0, 0.0]
    idx = []
    for r in range(R - 1):
        for s in range(S):
            a0, a1 = r * S + s, r * S + (s + 1) % S
            b0, b1 = a0 + S, a1 + S
            idx += [a0, b0, a1, a1, b0, b1]

    blob = bytearray()
    views, accessors = [], []

    def add(data, fmt, count, type_, ctype, target=None, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        off = len(blob)
        blob.extend(struct.pack("<%d%s" % (len(data), fmt), *data))
        v = {"buffer": 0, "byteOffset": off, "byteLength": len(blob) - off}
        if target:
            v["target"] = target
        views.append(v)
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    V = R * S
    mins = [min(pos[i::3]) for i in range(3)]
    maxs = [max(pos[i::3]) for i in range(3)]
    a_pos = add(pos, "f", V, "VEC3", 5126, 34962, (mins, maxs))
    a_nrm = add(nrm, "f", V, "VEC3", 5126, 34962)
    a_j = add(joints, "H", V, "VEC4", 5123, 34962)
    a_w = add(weights, "f", V, "VEC4", 5126, 34962)
    bmins = [min(bulge_p[i::3]) for i in range(3)]
    bmaxs = [max(bulge_p[i::3]) for i in range(3)]
    a_bp = add(bulge_p, "f", V, "VEC3", 5126, 34962, (bmins, bmaxs))
    a_bn = add(bulge_n, "f", V, "VEC3", 5126, 34962)
    a_idx = add(idx, "I", len(idx), "SCALAR", 5125, 34963)
    seg = height / B
    ibm = []
    for j in range(B):
        ibm += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -seg * j, 0, 1]
    a_ibm = add(ibm, "f", B, "MAT4", 5126)
    keys = 9
    times = [2.0 * k / (keys - 1) for k in range(keys)]
    a_t = add(times, "f", keys, "SCALAR", 5126, None, ([0.0], [2.0]))
    a_wv = add([0.5 - 0.5 * math.cos(math.pi * t) for t in times], "f", keys, "SCALAR", 5126)

    nodes, skins, channels, samplers = [], [], [], []
    mesh = {"primitives": [{"attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "JOINTS_0": a_j, "WEIGHTS_0": a_w},
                            "indices": a_idx, "targets": [{"POSITION": a_bp, "NORMAL": a_bn}], "material": 0}],
            "weights": [0.0], "name": "tube"}
    roots = []
    for gy in range(N):
        for gx in range(N):
            k = gy * N + gx
            first = len(nodes)
            for j in range(B):
                nodes.append({"name": "t%d_bone%d" % (k, j), "translation": [0, seg if j else 0, 0]})
                if j:
                    nodes[first + j - 1]["children"] = [first + j]
            nodes[first]["translation"] = [(gx - (N - 1) / 2) * 1.5, 0, (gy - (N - 1) / 2) * 1.5]
            skins.append({"joints": list(range(first, first + B)), "inverseBindMatrices": a_ibm,
                          "skeleton": first})
            body = len(nodes)
            nodes.append({"name": "t%d_body" % k, "mesh": 0, "skin": k})
            roots += [first, body]
            phase = 0.7 * k
            for j in range(1, B):
                rot = []
                for t in times:
                    ang = 0.25 * math.sin(math.pi * t + phase + 0.4 * j)
                    rot += [0.0, 0.0, math.sin(ang / 2), math.cos(ang / 2)]
                samplers.append({"input": a_t, "output": add(rot, "f", keys, "VEC4", 5126)})
                channels.append({"sampler": len(samplers) - 1, "target": {"node": first + j, "path": "rotation"}})
            samplers.append({"input": a_t, "output": a_wv})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": body, "path": "weights"}})
    cam = len(nodes)
    span = 1.5 * N
    nodes.append({"name": "camera", "camera": 0, "translation": [0, height / 2, span + 4.0]})
    roots.append(cam)
    doc = {
        "asset": {"version": "2.0", "generator": "mvr tests/bench/make_skinned_crowd.py"},
        "scene": 0, "scenes": [{"nodes": roots}], "nodes": nodes, "meshes": [mesh], "skins": skins,
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.3, 1], "metallicFactor": 0.0,
                                                "roughnessFactor": 0.5}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "aspectRatio": 1.0, "znear": 0.1}}],
        "animations": [{"name": "sway", "samplers": samplers, "channels": channels}],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(a.out, "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
