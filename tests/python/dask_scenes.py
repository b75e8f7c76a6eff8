"""Small glTF files for test_dask.py and scripts/bench_dask: each a box
and a second, smaller box on a child node (two nodes, two meshes, two
materials: the ids outputs have something to tell apart), their sizes,
colours and places varied by the file's number, the buffer embedded as a
data: URI (one self-contained .gltf a file)."""
import base64
import json
import pathlib
import struct

# a unit cube's 24 vertices (4 a face, flat normals) and 36 indices
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
        # counter-clockwise seen from outside: u x v = n
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def scene(k):
    """The glTF JSON (a dict) of file number k."""
    pos, nrm, idx = _cube()
    data = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm)
    data += b"".join(struct.pack("<H", i) for i in idx)
    n_v = len(pos)
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
    c = ((k * 37) % 100) / 100.0
    sx, sy, sz = 1.0 + (k % 5) * 0.2, 0.6 + (k % 3) * 0.3, 1.0 + (k % 7) * 0.1
    return {
        "asset": {"version": "2.0", "generator": "tests/python/dask_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "scale": [sx, sy, sz], "rotation": [0, 0.2 * (k % 4), 0, (1 - 0.04 * (k % 4) ** 2) ** 0.5],
                   "children": [1]},
                  {"mesh": 1, "translation": [0.0, 0.5 + 0.25 * 0.4, 0.0], "scale": [0.4, 0.4, 0.4]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 1}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [c, 0.4, 1 - c, 1], "metallicFactor": 0.1,
                                                "roughnessFactor": 0.6}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8 * c, 0.2, 1], "metallicFactor": 0.0,
                                                "roughnessFactor": 0.3}}],
        "buffers": [{"byteLength": len(data), "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n_v, "target": 34962},
                        {"buffer": 0, "byteOffset": 12 * n_v, "byteLength": 12 * n_v, "target": 34962},
                        {"buffer": 0, "byteOffset": 24 * n_v, "byteLength": 2 * len(idx), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": n_v, "type": "VEC3",
                       "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
                      {"bufferView": 1, "componentType": 5126, "count": n_v, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
    }


def write_scenes(folder, count, prefix="box"):
    """Writes count files folder/<prefix>_KKK.gltf; returns their paths."""
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for k in range(count):
        p = folder / ("%s_%03d.gltf" % (prefix, k))
        p.write_text(json.dumps(scene(k)), encoding="utf-8")
        paths.append(p)
    return paths
