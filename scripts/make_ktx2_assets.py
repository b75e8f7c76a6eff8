#!/usr/bin/env python3
"""scripts/make_ktx2_assets.py: writes tests/data/codecs/etc2*.ktx2, their
PNG twin and a glTF that uses them, with a tiny deterministic ETC2 encoder of
its own (Debian 12 has no ETC2 encoder tool).

Every 4x4 block is one colour, which ETC2 stores exactly:
  - colour: an ETC1-compatible block in differential mode (diff bit 1) with
    zero deltas, both sub-blocks the 5-bit base colour, table codeword 0 and
    every pixel index 0, whose modifier is +2 (OpenGL ES 3.0, C.1.1): each
    channel decodes to clamp(c5 << 3 | c5 >> 2, + 2);
  - alpha: an EAC block (C.1.2) with base codeword A and multiplier 0:
    exactly A for every pixel.
So the PNG twin holds the decoded colours exactly, and the GL's decode of the
blocks must match it bit for bit (the io_gltf_blocks test allows 1/255).

Files (16x16, VK_FORMAT_ETC2_R8G8B8A8_SRGB, every level of the chain):
  etc2.ktx2       no supercompression; level 0: four 8x8 quadrants; levels
                  1..4 each one solid colour of their own (mips are used when
                  a minified view shows those colours, which level 0 lacks)
  etc2_zstd.ktx2  the same levels, each a Zstandard frame (zstd -19, the
                  `zstd` tool; skipped with a note when it is missing)
  etc2.png        level 0's decoded colours (the twin)
  etc2.gltf       an unlit quad whose base colour texture is etc2.ktx2
                  (mimeType image/ktx2), sampled NEAREST
Deterministic: a second run writes the same bytes.
"""
import os
import shutil
import struct
import subprocess
import sys
import zlib

W = H = 16
# level 0 quadrants (top-left, top-right, bottom-left, bottom-right) and
# levels 1..4: 5-bit RGB and 8-bit alpha
QUADRANTS = [(25, 4, 5, 255), (3, 22, 7, 255), (4, 6, 27, 255), (29, 29, 29, 255)]
LEVEL_COLOURS = [None, (31, 0, 31, 255), (0, 31, 31, 255), (31, 31, 0, 255), (12, 12, 12, 255)]


def decoded(c):
    """What a block of 5-bit colour c (and alpha) decodes to, 8 bits per channel."""
    return tuple(min(255, (v << 3 | v >> 2) + 2) for v in c[:3]) + (c[3],)


def etc2_colour_block(c):
    r, g, b = c[:3]
    hi = (r << 27) | (g << 19) | (b << 11) | (0 << 5) | (0 << 2) | (1 << 1) | 0   # deltas 0, codewords 0, diff 1, flip 0
    return struct.pack(">II", hi, 0)   # pixel indices all 0 (modifier +2)


def eac_alpha_block(a):
    return bytes([a, 0x00]) + bytes(6)   # base codeword a, multiplier 0, table 0, indices 0


def block(c):
    return eac_alpha_block(c[3]) + etc2_colour_block(c)   # ETC2_RGBA8: alpha block first


def level_blocks(level):
    lw, lh = max(1, W >> level), max(1, H >> level)
    bx, by = (lw + 3) // 4, (lh + 3) // 4
    out = bytearray()
    for y in range(by):   # rows of blocks top first
        for x in range(bx):
            if level == 0:
                q = (2 if y * 4 >= H // 2 else 0) + (1 if x * 4 >= W // 2 else 0)
                out += block(QUADRANTS[q])
            else:
                out += block(LEVEL_COLOURS[level])
    return bytes(out)


def ktx2(levels, zstd_levels=None):
    """A KTX 2.0 file (KTX File Format Specification 2.0) of ETC2_R8G8B8A8_SRGB."""
    n = len(levels)
    stored = zstd_levels if zstd_levels is not None else levels
    # data format descriptor: one basic block, ETC2 colour model, sRGB, two samples
    samples = [(0, 63, 15), (64, 63, 2)]   # (bitOffset, bitLength - 1, channel): alpha, colour
    block_size = 24 + 16 * len(samples)
    dfd = struct.pack("<I", 4 + block_size)
    dfd += struct.pack("<IHH", 0, 2, block_size)             # vendor 0 / type 0, version 2, size
    dfd += bytes([161, 1, 2, 0])                            # ETC2, BT709 primaries, sRGB transfer, flags
    dfd += bytes([3, 3, 0, 0])                              # 4x4x1x1 block
    dfd += bytes([16, 0, 0, 0, 0, 0, 0, 0])                 # bytesPlane0 16
    for off, length, ch in samples:
        dfd += struct.pack("<HBB", off, length, ch) + bytes(4) + struct.pack("<II", 0, 0xFFFFFFFF)
    header_len = 80 + 24 * n
    dfd_offset = header_len
    data = bytearray(dfd)
    end = dfd_offset + len(dfd)
    index = [None] * n
    body = bytearray()
    align = 16 if zstd_levels is None else 1   # mipPadding: lcm(16, 4) without supercompression
    pos = end
    for lv in range(n - 1, -1, -1):   # smallest first
        pad = (-pos) % align
        body += bytes(pad)
        pos += pad
        index[lv] = (pos, len(stored[lv]), len(levels[lv]))
        body += stored[lv]
        pos += len(stored[lv])
    head = bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A])
    head += struct.pack("<9I", 152, 1, W, H, 0, 0, 1, n, 0 if zstd_levels is None else 2)
    head += struct.pack("<4I2Q", dfd_offset, len(dfd), 0, 0, 0, 0)
    for off, length, raw in index:
        head += struct.pack("<3Q", off, length, raw)
    assert len(head) == header_len
    return bytes(head) + bytes(data) + bytes(body)


def png(pixels, w, h):
    raw = b"".join(b"\0" + bytes(pixels[y * w * 4:(y + 1) * w * 4]) for y in range(h))

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def gltf(image_uri, mime):
    import base64
    import json
    pos = struct.pack("<12f", -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0)
    nrm = struct.pack("<12f", *([0, 0, 1] * 4))
    uv = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3) + bytes(4)
    buf = pos + nrm + uv + idx
    doc = {
        "asset": {"version": "2.0", "generator": "mvr scripts/make_ktx2_assets.py"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0},
                       "extensions": {"KHR_materials_unlit": {}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728}],
        "images": [{"uri": image_uri, "mimeType": mime}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
    return json.dumps(doc, indent=1, sort_keys=True) + "\n"


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "tests", "data", "codecs")
    os.makedirs(out, exist_ok=True)
    levels = [level_blocks(lv) for lv in range(5)]

    def write(name, data, mode="wb"):
        with open(os.path.join(out, name), mode) as f:
            f.write(data)
    write("etc2.ktx2", ktx2(levels))
    if shutil.which("zstd"):
        z = [subprocess.run(["zstd", "-q", "-19", "-c", "--no-check"], input=lv, stdout=subprocess.PIPE,
                            check=True).stdout for lv in levels]
        write("etc2_zstd.ktx2", ktx2(levels, z))
    else:
        print("make_ktx2_assets: zstd missing: etc2_zstd.ktx2 not written", file=sys.stderr)
    px = bytearray(W * H * 4)
    for y in range(H):
        for x in range(W):
            q = (2 if y >= H // 2 else 0) + (1 if x >= W // 2 else 0)
            px[(y * W + x) * 4:(y * W + x) * 4 + 4] = bytes(decoded(QUADRANTS[q]))
    write("etc2.png", png(px, W, H))
    write("etc2.gltf", gltf("etc2.ktx2", "image/ktx2"), "w")
    for lv in range(1, 5):
        print("level %d: %s" % (lv, decoded(LEVEL_COLOURS[lv])))
    print("quadrants: %s" % [decoded(q) for q in QUADRANTS])


if __name__ == "__main__":
    main()
