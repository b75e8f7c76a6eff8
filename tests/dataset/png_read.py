"""A PNG reader for the tests (standard library + numpy): 8- and 16-bit
grayscale, gray+alpha, RGB and RGBA, not interlaced: what mvr writes.
PNG specification (ISO/IEC 15948, W3C PNG 2nd edition): chunks, zlib
stream of the IDAT chunks, one filter byte per row (0 none, 1 sub, 2 up,
3 average, 4 Paeth), samples big-endian."""
import struct
import zlib

import numpy as np

CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}


def read(path):
    """The image as an (H, W) or (H, W, C) uint8 / uint16 array, rows top to bottom."""
    return read_with_header(path)[2]


def read_with_header(path):
    """(bit depth, colour type, the array read() returns)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "%s: not a PNG" % path
    pos, idat, header = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    width, height, depth, color, _, _, interlace = header
    assert depth in (8, 16) and color in CHANNELS and interlace == 0, "%s: unsupported PNG %s" % (path, header)
    bpp = CHANNELS[color] * depth // 8  # bytes per pixel: the filters' unit
    stride = width * bpp
    raw = zlib.decompress(b"".join(idat))
    out = np.zeros((height, stride), np.uint8)
    prev = np.zeros(stride, np.int32)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        if kind == 0:
            cur = line
        elif kind == 2:
            cur = (line + prev) & 0xFF
        else:  # sub, average and Paeth depend on the pixel to the left: byte by byte
            cur = np.zeros(stride, np.int32)
            for i in range(stride):
                left = cur[i - bpp] if i >= bpp else 0
                up = prev[i]
                if kind == 1:
                    pred = left
                elif kind == 3:
                    pred = (left + up) >> 1
                else:
                    ul = prev[i - bpp] if i >= bpp else 0
                    p = left + up - ul
                    pa, pb, pc = abs(p - left), abs(p - up), abs(p - ul)
                    pred = left if pa <= pb and pa <= pc else up if pb <= pc else ul
                cur[i] = (line[i] + pred) & 0xFF
        out[y] = cur
        prev = cur
    if depth == 16:
        img = out.view(">u2").astype(np.uint16)
    else:
        img = out
    channels = CHANNELS[color]
    return depth, color, img.reshape(height, width, channels) if channels > 1 else img.reshape(height, width)
