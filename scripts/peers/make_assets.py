#!/usr/bin/env python3
"""Writes the peer-comparison test assets into tests/data/peers/ (Python 3 standard library only).

  spheres.gltf + spheres.bin   4 x 5 UV spheres (64 x 32 segments, smooth normals): roughness 0, 0.25,
                               0.5, 0.75, 1 across; rows top to bottom: dielectric white, dielectric
                               tinted (0.9, 0.6, 0.3), metal white, metal tinted; one perspective camera
                               (node 20) framing the grid; no lights.
  coated.gltf                  4 x 3 of the spheres' mesh (spheres.bin) with KHR_materials_clearcoat (a rough
                               red dielectric bare, then under a coat of roughness 0, 0.25, 0.5), _ior (a
                               dark glossy dielectric of ior 1, 1.33, 2, 3) and _specular (factor 0, 0.5,
                               a tinted F0, a tinted F0 with ior 1.8); one camera (node 12); no lights.
  glass.gltf                   four glass spheres (KHR_materials_transmission 1: thin and smooth, thin and rough
                               0.3, a _volume of thickness 0.84 absorbing to (0.9, 0.45, 0.2) at 0.6, the same
                               volume clear with _dispersion 8) in front of six coloured bars (the spheres'
                               mesh flattened); one camera (node 10); no lights.
  spec_gloss.gltf              4 x 3 spheres of KHR_materials_pbrSpecularGlossiness: grey / red diffuse with
                               specular 0.04 / 0.3, a copper-like specular colour; glossiness 1, 0.75, 0.5,
                               0.25 across; one camera (node 12); no lights.
  films.gltf + films.bin       4 x 2 UV spheres with texture coordinates and tangents: KHR_materials_iridescence
                               (a dark dielectric under films of 200, 400 and 800 nm, a gold-like metal under
                               400 nm) and KHR_materials_anisotropy (a brushed metal of roughness 0.35:
                               isotropic, strength 0.5 and 1 along the tangent, 1 turned a quarter); one
                               camera (node 8); no lights.
  uniform.hdr                  64 x 32 Radiance RGBE, radiance 1.0 everywhere.
  sky.hdr                      512 x 256 Radiance RGBE (run-length encoded): a blue sky gradient, a
                               warm sun disc of radiance 50, a horizon band and a ground of eight
                               alternating sectors (so that a turn or a mirror of the environment shows).
  diag_axes.hdr                64 x 32 diagnostic environment: a coloured cap around each axis (mvr's
                               convention at rotation 0): +X red, -X green, +Y blue, -Y yellow,
                               +Z magenta, -Z cyan, elsewhere grey 0.05.
  diag_mirror.gltf             one white mirror sphere (metallic 1, roughness 0) and a camera on +Z
                               looking at it: used to work out the environment rotation that makes
                               mvr and the Khronos renderer agree.

Environment mapping used to write the images (mvr's, rotation 0): a world direction d (glTF, +Y up)
reads u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi, v = 0 the top row.

textured.gltf comes from Blender's own glTF exporter: scripts/peers/blender_textured.py.
"""
import base64
import json
import math
import os
import struct
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests', 'data', 'peers')


# ---------------------------------------------------------------- Radiance .hdr

def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return (0, 0, 0, 0)
    f, e = math.frexp(m)          # m = f * 2^e, 0.5 <= f < 1
    s = f * 256.0 / m
    return (int(r * s), int(g * s), int(b * s), e + 128)


def rle_channel(vals):
    """New-style RLE of one channel of one scanline (runs of 3..127 equal bytes, literals up to 128)."""
    out = bytearray()
    i, n = 0, len(vals)
    while i < n:
        # find the next run of at least 3
        j = i
        run_start, run_len = n, 0
        while j < n:
            k = j
            while k + 1 < n and vals[k + 1] == vals[j] and k + 1 - j < 126:
                k += 1
            if k - j + 1 >= 3:
                run_start, run_len = j, k - j + 1
                break
            j = k + 1
        # literals before the run
        while i < run_start:
            cnt = min(128, run_start - i)
            out.append(cnt)
            out.extend(vals[i:i + cnt])
            i += cnt
        if run_len:
            out.append(128 + run_len)
            out.append(vals[run_start])
            i = run_start + run_len
    return bytes(out)


def write_hdr(path, width, height, pixel, rle=True):
    """pixel(x, y) -> (r, g, b) linear radiance; y = 0 is the top row (header -Y H +X W)."""
    data = bytearray(b'#?RADIANCE\n# mvr scripts/peers/make_assets.py\nFORMAT=32-bit_rle_rgbe\n\n')
    data += b'-Y %d +X %d\n' % (height, width)
    for y in range(height):
        row = [rgbe(*pixel(x, y)) for x in range(width)]
        if rle and 8 <= width < 32768:
            data += bytes((2, 2, width >> 8, width & 255))
            for c in range(4):
                data += rle_channel(bytes(p[c] for p in row))
        else:
            for p in row:
                data += bytes(p)
    with open(path, 'wb') as f:
        f.write(data)


def dir_of_pixel(x, y, w, h):
    """Centre of pixel (x, y) -> world direction, mvr convention at rotation 0."""
    u = (x + 0.5) / w
    v = (y + 0.5) / h
    phi = (u - 0.5) * 2.0 * math.pi      # atan2(d.x, -d.z)
    theta = v * math.pi                  # acos(d.y)
    st = math.sin(theta)
    return (st * math.sin(phi), math.cos(theta), -st * math.cos(phi))


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


# The sun's direction in the environment image (mvr convention, rotation 0). With mvr's
# --env-rotation 180 (the Khronos renderer's default environmentRotation of 90, see README.md)
# the world sees it at (-x, y, -z) = up, behind the camera on the left: it lights the spheres
# from the upper left front.
SUN_DIR = normalize((0.45, 0.62, -0.64))
SUN_RADIUS_DEG = 4.0
SUN_RADIANCE = (50.0, 42.0, 30.0)


def sky_pixel(d):
    x, y, z = d
    if math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(d, SUN_DIR))))) < math.radians(SUN_RADIUS_DEG):
        return SUN_RADIANCE
    if y >= 0.0:
        # a function of the row only, so each row is one RLE run outside the sun
        t = y
        zen = (0.18, 0.32, 0.75)
        hor = (0.85, 0.90, 1.00)
        k = (1.0 - t) ** 3
        return tuple(zen[i] + (hor[i] - zen[i]) * k for i in range(3))
    # ground: eight alternating sectors of azimuth, darker towards the nadir
    az = math.atan2(x, -z)
    sector = int(math.floor((az + math.pi) / (math.pi / 4.0))) % 8
    base = (0.30, 0.22, 0.14) if sector % 2 == 0 else (0.16, 0.24, 0.12)
    if sector == 0:
        base = (0.45, 0.10, 0.08)          # one red sector: makes a turn or a mirror visible
    k = 1.0 - 0.5 * (-y)
    return tuple(c * k for c in base)


AXIS_CAPS = [((1, 0, 0), (1.0, 0.0, 0.0)), ((-1, 0, 0), (0.0, 1.0, 0.0)),
             ((0, 1, 0), (0.0, 0.0, 1.0)), ((0, -1, 0), (1.0, 1.0, 0.0)),
             ((0, 0, 1), (1.0, 0.0, 1.0)), ((0, 0, -1), (0.0, 1.0, 1.0))]
AXIS_CAP_COS = math.cos(math.radians(35.0))
AXIS_BACKGROUND = (0.05, 0.05, 0.05)


def axes_pixel(d):
    for axis, colour in AXIS_CAPS:
        if sum(a * b for a, b in zip(d, axis)) > AXIS_CAP_COS:
            return colour
    return AXIS_BACKGROUND


# ---------------------------------------------------------------- glTF

def uv_sphere(radius, seg_u, seg_v):
    pos, nrm, idx = [], [], []
    for j in range(seg_v + 1):
        th = math.pi * j / seg_v
        for i in range(seg_u + 1):
            ph = 2.0 * math.pi * i / seg_u
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            nrm.append(n)
            pos.append(tuple(radius * c for c in n))
    row = seg_u + 1
    for j in range(seg_v):
        for i in range(seg_u):
            a, b = j * row + i, j * row + i + 1
            c, d = (j + 1) * row + i, (j + 1) * row + i + 1
            if j != 0:
                idx += [a, c, b]
            if j != seg_v - 1:
                idx += [b, c, d]
    return pos, nrm, idx


def sphere_buffers(radius, seg_u, seg_v):
    pos, nrm, idx = uv_sphere(radius, seg_u, seg_v)
    pb = b''.join(struct.pack('<3f', *p) for p in pos)
    nb = b''.join(struct.pack('<3f', *n) for n in nrm)
    ib = b''.join(struct.pack('<H', i) for i in idx)
    while len(ib) % 4:
        ib += b'\0'
    blob = pb + nb + ib
    views = [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(pb), "target": 34962},
        {"buffer": 0, "byteOffset": len(pb), "byteLength": len(nb), "target": 34962},
        {"buffer": 0, "byteOffset": len(pb) + len(nb), "byteLength": len(idx) * 2, "target": 34963},
    ]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
         "min": [-radius] * 3, "max": [radius] * 3},
        {"bufferView": 1, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
    ]
    return blob, views, accessors


def write_gltf(name, blob, views, accessors, materials, nodes, cameras, scene_nodes, bin_name=None, extensions=None):
    doc = {
        "asset": {"version": "2.0", "generator": "mvr scripts/peers/make_assets.py"},
        "scene": 0,
        "scenes": [{"nodes": scene_nodes}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": m}]}
                   for m in range(len(materials))],
        "materials": materials,
        "cameras": cameras,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    if extensions:
        doc["extensionsUsed"] = extensions
    if bin_name:
        doc["buffers"][0]["uri"] = bin_name
        with open(os.path.join(OUT, bin_name), 'wb') as f:
            f.write(blob)
    else:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    with open(os.path.join(OUT, name), 'w') as f:
        json.dump(doc, f, indent=1)
        f.write('\n')


def make_spheres():
    blob, views, accessors = sphere_buffers(0.42, 64, 32)
    roughness = [0.0, 0.25, 0.5, 0.75, 1.0]
    rows = [("dielectric_white", 0.0, [1.0, 1.0, 1.0, 1.0]),
            ("dielectric_tint", 0.0, [0.9, 0.6, 0.3, 1.0]),
            ("metal_white", 1.0, [1.0, 1.0, 1.0, 1.0]),
            ("metal_tint", 1.0, [0.9, 0.6, 0.3, 1.0])]
    materials, nodes = [], []
    for r, (rname, metal, colour) in enumerate(rows):
        for c, rough in enumerate(roughness):
            materials.append({"name": "%s_r%03d" % (rname, int(rough * 100)),
                              "pbrMetallicRoughness": {"baseColorFactor": colour, "metallicFactor": metal,
                                                       "roughnessFactor": rough}})
            nodes.append({"name": materials[-1]["name"], "mesh": len(nodes),
                          "translation": [c - 2.0, 1.5 - r, 0.0]})
    # one mesh per material (same accessors), so the file stays plain glTF 2.0
    cam_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 8.0]})
    cameras = [{"type": "perspective", "name": "grid",
                "perspective": {"yfov": 0.62, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}]
    write_gltf("spheres.gltf", blob, views, accessors, materials, nodes, cameras,
               list(range(cam_node + 1)), bin_name="spheres.bin")


def make_coated():
    # KHR_materials_clearcoat, _ior and _specular on the spheres' mesh, 4 x 3
    blob, views, accessors = sphere_buffers(0.42, 64, 32)
    red = [0.8, 0.12, 0.08, 1.0]
    dark = [0.05, 0.05, 0.06, 1.0]
    cells = []
    # row 1: a rough red dielectric under a clearcoat of roughness 0, 0.25, 0.5 (and none)
    for cr in (None, 0.0, 0.25, 0.5):
        m = {"name": "coat_%s" % ("none" if cr is None else "r%03d" % int(cr * 100)),
             "pbrMetallicRoughness": {"baseColorFactor": red, "metallicFactor": 0.0, "roughnessFactor": 0.6}}
        if cr is not None:
            m["extensions"] = {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": cr}}
        cells.append(m)
    # row 2: a dark glossy dielectric of ior 1.0, 1.33, 2.0, 3.0
    for ior in (1.0, 1.33, 2.0, 3.0):
        cells.append({"name": "ior_%03d" % int(ior * 100),
                      "pbrMetallicRoughness": {"baseColorFactor": dark, "metallicFactor": 0.0, "roughnessFactor": 0.2},
                      "extensions": {"KHR_materials_ior": {"ior": ior}}})
    # row 3: KHR_materials_specular: factor 0, 0.5, a tinted F0, both with ior 1.8
    for name, ext in (("spec_000", {"specularFactor": 0.0}), ("spec_050", {"specularFactor": 0.5}),
                      ("spec_tint", {"specularColorFactor": [1.0, 0.4, 0.1]}),
                      ("spec_tint_ior", {"specularFactor": 0.8, "specularColorFactor": [0.2, 0.6, 1.0]})):
        m = {"name": name,
             "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.3, 0.3, 1.0], "metallicFactor": 0.0,
                                      "roughnessFactor": 0.3},
             "extensions": {"KHR_materials_specular": ext}}
        if name == "spec_tint_ior":
            m["extensions"]["KHR_materials_ior"] = {"ior": 1.8}
        cells.append(m)
    nodes = []
    for i, m in enumerate(cells):
        r, c = divmod(i, 4)
        nodes.append({"name": m["name"], "mesh": i, "translation": [c - 1.5, 1.0 - r, 0.0]})
    cam_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 6.5]})
    cameras = [{"type": "perspective", "name": "grid",
                "perspective": {"yfov": 0.62, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}]
    write_gltf("coated.gltf", blob, views, accessors, cells, nodes, cameras, list(range(cam_node + 1)),
               bin_name="spheres.bin", extensions=["KHR_materials_clearcoat", "KHR_materials_ior",
                                                   "KHR_materials_specular"])


def make_glass():
    # KHR_materials_transmission, _volume and _dispersion: four glass spheres in front of six coloured
    # bars (the spheres' mesh flattened), so that what they transmit and how they bend it shows
    blob, views, accessors = sphere_buffers(0.42, 64, 32)
    cells, nodes = [], []
    bar_colours = ([0.9, 0.15, 0.1], [0.95, 0.85, 0.2], [0.1, 0.6, 0.2], [0.1, 0.3, 0.9], [0.9, 0.9, 0.9],
                   [0.6, 0.1, 0.6])
    for i, colour in enumerate(bar_colours):
        cells.append({"name": "bar_%d" % i,
                      "pbrMetallicRoughness": {"baseColorFactor": colour + [1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": 0.8}})
        nodes.append({"name": cells[-1]["name"], "mesh": len(nodes), "translation": [-2.5 + i, 0.0, -1.5],
                      "scale": [1.1, 6.0, 0.05]})
    glass = [("thin", 0.0, {}, {}),
             ("rough", 0.3, {}, {}),
             ("volume", 0.0, {"KHR_materials_volume": {"thicknessFactor": 0.84, "attenuationDistance": 0.6,
                                                       "attenuationColor": [0.9, 0.45, 0.2]}}, {}),
             ("dispersion", 0.0, {"KHR_materials_volume": {"thicknessFactor": 0.84},
                                  "KHR_materials_dispersion": {"dispersion": 8.0}}, {})]
    for i, (name, rough, ext, _) in enumerate(glass):
        e = {"KHR_materials_transmission": {"transmissionFactor": 1.0}}
        e.update(ext)
        cells.append({"name": "glass_" + name,
                      "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": rough},
                      "extensions": e})
        nodes.append({"name": cells[-1]["name"], "mesh": len(nodes), "translation": [i - 1.5, 0.0, 0.0]})
    cam_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 4.0]})
    cameras = [{"type": "perspective", "name": "row",
                "perspective": {"yfov": 0.7, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}]
    write_gltf("glass.gltf", blob, views, accessors, cells, nodes, cameras, list(range(cam_node + 1)),
               bin_name="spheres.bin", extensions=["KHR_materials_transmission", "KHR_materials_volume",
                                                   "KHR_materials_dispersion"])


def make_spec_gloss():
    # KHR_materials_pbrSpecularGlossiness (archived): diffuse and specular colours, glossiness 1 .. 0.25
    blob, views, accessors = sphere_buffers(0.42, 64, 32)
    cells, nodes = [], []
    rows = (([0.5, 0.5, 0.5, 1.0], [0.04, 0.04, 0.04]), ([0.6, 0.2, 0.1, 1.0], [0.3, 0.3, 0.3]),
            ([0.05, 0.05, 0.05, 1.0], [0.95, 0.64, 0.54]))
    for r, (diffuse, specular) in enumerate(rows):
        for c, gloss in enumerate((1.0, 0.75, 0.5, 0.25)):
            cells.append({"name": "sg_%d_g%03d" % (r, int(gloss * 100)),
                          "extensions": {"KHR_materials_pbrSpecularGlossiness": {
                              "diffuseFactor": diffuse, "specularFactor": specular, "glossinessFactor": gloss}}})
            nodes.append({"name": cells[-1]["name"], "mesh": len(nodes), "translation": [c - 1.5, 1.0 - r, 0.0]})
    cam_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 6.5]})
    cameras = [{"type": "perspective", "name": "grid",
                "perspective": {"yfov": 0.62, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}]
    write_gltf("spec_gloss.gltf", blob, views, accessors, cells, nodes, cameras, list(range(cam_node + 1)),
               bin_name="spheres.bin", extensions=["KHR_materials_pbrSpecularGlossiness"])


def make_films():
    # KHR_materials_iridescence and _anisotropy on a UV sphere with texture coordinates and tangents
    # (its own buffer, films.bin: the anisotropy direction lives in the tangent frame)
    radius, seg_u, seg_v = 0.42, 64, 32
    pos, nrm, idx = uv_sphere(radius, seg_u, seg_v)
    uvs, tans = [], []
    for j in range(seg_v + 1):
        for i in range(seg_u + 1):
            ph = 2.0 * math.pi * i / seg_u
            uvs.append((i / seg_u, j / seg_v))
            tans.append((-math.sin(ph), 0.0, -math.cos(ph), 1.0))   # dP/du; bitangent n x t: image up
    pb = b''.join(struct.pack('<3f', *p) for p in pos)
    nb = b''.join(struct.pack('<3f', *n) for n in nrm)
    ub = b''.join(struct.pack('<2f', *u) for u in uvs)
    tb = b''.join(struct.pack('<4f', *t) for t in tans)
    ib = b''.join(struct.pack('<H', i) for i in idx)
    while len(ib) % 4:
        ib += b'\0'
    blob = pb + nb + ub + tb + ib
    offs = [0, len(pb), len(pb) + len(nb), len(pb) + len(nb) + len(ub), len(pb) + len(nb) + len(ub) + len(tb)]
    views = [{"buffer": 0, "byteOffset": offs[k], "byteLength": n, "target": 34962}
             for k, n in enumerate((len(pb), len(nb), len(ub), len(tb)))]
    views.append({"buffer": 0, "byteOffset": offs[4], "byteLength": len(idx) * 2, "target": 34963})
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
         "min": [-radius] * 3, "max": [radius] * 3},
        {"bufferView": 1, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
        {"bufferView": 3, "componentType": 5126, "count": len(tans), "type": "VEC4"},
        {"bufferView": 4, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
    ]
    cells = []
    # row 1: a dark dielectric under films of 200, 400 and 800 nm (ior 1.3 ... 1.8), a gold-like metal under 400 nm
    for name, base, metal, film in (("film_200", [0.05, 0.05, 0.05, 1.0], 0.0, {"iridescenceThicknessMaximum": 200.0}),
                                    ("film_400", [0.05, 0.05, 0.05, 1.0], 0.0, {}),
                                    ("film_800", [0.05, 0.05, 0.05, 1.0], 0.0,
                                     {"iridescenceThicknessMaximum": 800.0, "iridescenceIor": 1.8}),
                                    ("film_metal", [0.9, 0.7, 0.3, 1.0], 1.0, {})):
        ext = {"iridescenceFactor": 1.0}
        ext.update(film)
        cells.append({"name": name, "pbrMetallicRoughness": {"baseColorFactor": base, "metallicFactor": metal,
                                                             "roughnessFactor": 0.2},
                      "extensions": {"KHR_materials_iridescence": ext}})
    # row 2: a brushed metal: isotropic, anisotropy 0.5 and 1 along the tangent, 1 turned a quarter
    for name, ext in (("aniso_000", None), ("aniso_050", {"anisotropyStrength": 0.5}),
                      ("aniso_100", {"anisotropyStrength": 1.0}),
                      ("aniso_100_r090", {"anisotropyStrength": 1.0, "anisotropyRotation": math.pi / 2})):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.93, 0.88, 1.0], "metallicFactor": 1.0,
                                                    "roughnessFactor": 0.35}}
        if ext:
            m["extensions"] = {"KHR_materials_anisotropy": ext}
        cells.append(m)
    nodes = []
    for i, m in enumerate(cells):
        r, c = divmod(i, 4)
        nodes.append({"name": m["name"], "mesh": i, "translation": [c - 1.5, 0.5 - r, 0.0]})
    cam_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 6.0]})
    doc = {
        "asset": {"version": "2.0", "generator": "mvr scripts/peers/make_assets.py"},
        "extensionsUsed": ["KHR_materials_iridescence", "KHR_materials_anisotropy"],
        "scene": 0,
        "scenes": [{"nodes": list(range(cam_node + 1))}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3},
                                    "indices": 4, "material": m}]} for m in range(len(cells))],
        "materials": cells,
        "cameras": [{"type": "perspective", "name": "grid",
                     "perspective": {"yfov": 0.62, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob), "uri": "films.bin"}],
    }
    with open(os.path.join(OUT, "films.bin"), 'wb') as f:
        f.write(blob)
    with open(os.path.join(OUT, "films.gltf"), 'w') as f:
        json.dump(doc, f, indent=1)
        f.write('\n')


def make_diag_mirror():
    # the spheres' mesh (radius 0.42) and buffer, scaled to radius 1
    blob, views, accessors = sphere_buffers(0.42, 64, 32)
    materials = [{"name": "mirror", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1],
                                                             "metallicFactor": 1.0, "roughnessFactor": 0.0}}]
    nodes = [{"name": "mirror_sphere", "mesh": 0, "scale": [1.0 / 0.42] * 3},
             {"name": "camera", "camera": 0, "translation": [0.0, 0.0, 3.0]}]
    cameras = [{"type": "perspective", "name": "front",
                "perspective": {"yfov": math.radians(60.0), "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}]
    write_gltf("diag_mirror.gltf", blob, views, accessors, materials, nodes, cameras, [0, 1],
               bin_name="spheres.bin")


def main():
    os.makedirs(OUT, exist_ok=True)
    write_hdr(os.path.join(OUT, "uniform.hdr"), 64, 32, lambda x, y: (1.0, 1.0, 1.0), rle=False)
    write_hdr(os.path.join(OUT, "sky.hdr"), 512, 256, lambda x, y: sky_pixel(dir_of_pixel(x, y, 512, 256)))
    write_hdr(os.path.join(OUT, "diag_axes.hdr"), 64, 32, lambda x, y: axes_pixel(dir_of_pixel(x, y, 64, 32)))
    make_spheres()
    make_coated()
    make_glass()
    make_spec_gloss()
    make_films()
    make_diag_mirror()
    for n in sorted(os.listdir(OUT)):
        print("%-22s %8d bytes" % (n, os.path.getsize(os.path.join(OUT, n))))


if __name__ == '__main__':
    main()
