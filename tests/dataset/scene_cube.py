"""A textured cube as glTF, for structure-from-motion checks: every face
carries a seeded random texture (RGB texels, linearly filtered, so SIFT
finds blobs at several scales). Standard library only.

    import scene_cube; path = scene_cube.write(folder)   # folder/cube.gltf
"""
import base64
import json
import pathlib
import random
import struct
import zlib

TEXELS = 40          # per side of the texture
SEED = 33


def _png(width, height, rgb_rows):
    """An 8-bit RGB PNG (PNG spec: signature, IHDR, IDAT of filtered rows, IEND)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(row) for row in rgb_rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def _texture():
    rng = random.Random(SEED)
    rows = []
    for _ in range(TEXELS):
        rows.append([rng.randrange(256) for _ in range(TEXELS * 3)])
    return _png(TEXELS, TEXELS, rows)


def _cube():
    """24 vertices (4 per face) with normals and UVs, 36 indices."""
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos)
            for (a, b) in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u_axis], p[v_axis] = sign, float(a), float(b)
                pos.append(p)
                nrm.append(n)
                uv.append([(a + 1) / 2, (b + 1) / 2])
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            idx += [base + k for k in quad]
    return pos, nrm, uv, idx


def write(folder):
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    pos, nrm, uv, idx = _cube()
    blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm) + \
        b"".join(struct.pack("<2f", *t) for t in uv) + b"".join(struct.pack("<H", i) for i in idx)
    n = len(pos)
    views = [(0, 12 * n), (12 * n, 12 * n), (24 * n, 8 * n), (32 * n, 2 * len(idx))]
    gltf = {
        "asset": {"version": "2.0", "generator": "mvr tests/dataset/scene_cube.py"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "cube"}],
        "meshes": [{"name": "cube", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                     "indices": 3, "material": 0}]}],
        "materials": [{"name": "noise", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                                 "metallicFactor": 0.0, "roughnessFactor": 0.9}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],
        "images": [{"uri": "noise.png"}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": length} for o, length in views],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [-1, -1, -1],
             "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
        ],
    }
    (folder / "noise.png").write_bytes(_texture())
    path = folder / "cube.gltf"
    path.write_text(json.dumps(gltf, indent=1))
    return path
