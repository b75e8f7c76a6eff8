#!/usr/bin/python3
"""ctest: mvr render --outputs written as the files people open (--output-files, issue 33).

  test_cli_aov_files.py MVR SCENE OUT [OIIOTOOL]

- default (npy,png): depth_VVVV.png is 16-bit grayscale, round(depth / scale) with a tidy scale
  (1, 2 or 5 x 10^k), within half a step of depth_VVVV.npy on every covered pixel, 0 exactly where
  there is no surface; mask_VVVV.png is 8-bit, 255 exactly where coverage_VVVV.npy (uint8) is 1;
  ids_<kind>_VVVV.png are 16-bit and equal to each channel of ids_VVVV.npy; ids_preview_VVVV.png
  gives each node id one colour, distinct ids distinct colours, black where none; no EXR;
- exr,layers: depth_VVVV.exr holds one float channel Z, layers_VVVV.exr R G B A (half), Z, N.X N.Y N.Z
  (float), id.node id.mesh id.material id.primitive (uint), their values the .npy's (OIIO's iinfo and
  oiiotool read them);
- the streamed and synchronous readbacks write the same PNG and .npy bytes;
- --output-files with an unknown kind is a usage error naming it.
PNG decoding: tests/dataset/png_read.py (PNG spec, ISO/IEC 15948: chunks, filters 0-4)."""
import math
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "dataset"))
import png_read  # noqa: E402

MVR, SCENE, OUT = sys.argv[1:4]
OIIOTOOL = sys.argv[4] if len(sys.argv) > 4 else "oiiotool"
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []
VIEWS, W, H = 4, 64, 48


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def npy(folder, output, view):
    """<output>_VVVV.npy (or the 2-digit name the .npy files had before issue 33's renaming)."""
    path = os.path.join(folder, "%s_%04d.npy" % (output, view))
    return np.load(path if os.path.exists(path) else os.path.join(folder, "%s_%02d.npy" % (output, view)))


def render(out, *extra):
    r = subprocess.run([MVR, "render", SCENE, "--layout", "sphere", "--views", str(VIEWS), "--size", "%dx%d" % (W, H),
                        "--out", out, "--quiet", "--outputs", "all"] + list(extra), capture_output=True, text=True)
    expect(r.returncode == 0, "%s: mvr render exits %d: %s" % (out, r.returncode, r.stderr))
    return r


def read_png(path):
    """(bit depth, colour type, H x W x channels int64 array) of a non-interlaced PNG."""
    depth, ctype, arr = png_read.read_with_header(path)
    return depth, ctype, (arr if arr.ndim == 3 else arr[..., None]).astype(np.int64)


def exr_channels(path):
    """{name: H x W float64 array} from oiiotool --dumpdata, and {name: type} from its channel list."""
    r = subprocess.run([OIIOTOOL, "-v", "--dumpdata:empty=1", path], capture_output=True, text=True)
    expect(r.returncode == 0, "oiiotool reads %s: %s" % (path, r.stderr))
    types, values = {}, {}
    names = []
    pix = []
    one_type = None
    for line in r.stdout.splitlines():
        line = line.strip()
        if " channel, " in line and one_type is None:
            one_type = line.split(" channel, ", 1)[1].split()[0]  # "float openexr": every channel's type
        if line.startswith("channel list:"):
            for item in line[len("channel list:"):].split(","):
                name, _, kind = item.strip().partition(" ")
                names.append(name)
                types[name] = kind.strip("()") or one_type
        elif line.startswith("Pixel ("):
            pix.append([float(x) for x in line.split(":", 1)[1].split()])
    a = np.array(pix).reshape(H, W, len(names))
    for k, name in enumerate(names):
        values[name] = a[:, :, k]
    return types, values


default_out = os.path.join(OUT, "default")
render(default_out)
names = set(os.listdir(default_out))
want_files = ["%s_%04d.png" % (n, v) for v in range(VIEWS) for n in
              ("depth", "mask", "ids_node", "ids_mesh", "ids_material", "ids_primitive", "ids_preview")]
missing = [n for n in want_files if n not in names]
expect(not missing, "default: the PNGs are written (missing %s)" % missing[:8])
if missing:
    sys.exit(1)
expect(not any(n.endswith(".exr") for n in names), "default: no EXR files: %s" % sorted(names))
scales = set()
for v in range(VIEWS):
    vv = "%04d" % v
    depth = npy(default_out, "depth", v)
    cov = npy(default_out, "coverage", v)
    ids = npy(default_out, "ids", v)
    expect(cov.dtype == np.uint8 and set(np.unique(cov)) <= {0, 1}, "coverage_%s.npy is uint8 0/1 (%s)" % (vv, cov.dtype))
    expect((cov == 1).sum() > W * H // 20, "view %s: something is covered" % vv)
    bits, ctype, dpng = read_png(os.path.join(default_out, "depth_%s.png" % vv))
    expect(bits == 16 and ctype == 0, "depth_%s.png: 16-bit grayscale (got %d-bit type %d)" % (vv, bits, ctype))
    dpng = dpng[:, :, 0]
    surface = depth > 0
    expect(np.array_equal(dpng == 0, ~surface), "depth_%s.png: 0 exactly where there is no surface" % vv)
    # the scale: the depth of the covered pixels over their steps, snapped to a tidy value
    est = float(np.median(depth[surface] / dpng[surface]))
    decade = 10.0 ** math.floor(math.log10(est))
    scale = min((m * decade for m in (1, 2, 5, 10)), key=lambda s: abs(s - est))
    scales.add(scale)
    expect(abs(scale - est) < 1e-3 * scale, "depth_%s.png: the scale %.9g is a tidy value (1, 2, 5 x 10^k)" % (vv, est))
    err = np.abs(dpng[surface] * scale - depth[surface])
    expect(dpng.max() < 65535 and float(err.max()) <= 0.5 * scale * (1 + 1e-6),
           "depth_%s.png: within half a step of the .npy (worst %.3g of scale %.3g)" % (vv, float(err.max()), scale))
    expect(float(depth.max()) / scale > 1000, "depth_%s.png: over 1000 steps over the depths seen" % vv)
    bits, ctype, mask = read_png(os.path.join(default_out, "mask_%s.png" % vv))
    expect(bits == 8 and ctype == 0, "mask_%s.png: 8-bit grayscale" % vv)
    expect(np.array_equal(mask[:, :, 0], np.where(cov == 1, 255, 0)), "mask_%s.png: 255 exactly where covered" % vv)
    for k, kind in enumerate(("node", "mesh", "material", "primitive")):
        bits, ctype, ipng = read_png(os.path.join(default_out, "ids_%s_%s.png" % (kind, vv)))
        expect(bits == 16 and ctype == 0, "ids_%s_%s.png: 16-bit grayscale" % (kind, vv))
        expect(np.array_equal(ipng[:, :, 0], ids[:, :, k]), "ids_%s_%s.png equals ids_%s.npy[..., %d]" % (kind, vv, vv, k))
        expect(("ids_%s_hi_%s.png" % (kind, vv)) not in names, "ids under 65536: no ids_%s_hi_%s.png" % (kind, vv))
    bits, ctype, prev = read_png(os.path.join(default_out, "ids_preview_%s.png" % vv))
    expect(bits == 8 and ctype == 6, "ids_preview_%s.png: RGBA8" % vv)
    colour = {}
    consistent = True
    for node, rgb in zip(ids[:, :, 0].ravel(), prev[:, :, :3].reshape(-1, 3)):
        consistent = consistent and tuple(rgb) == colour.setdefault(int(node), tuple(rgb))
    expect(consistent, "ids_preview_%s.png: one colour per node id" % vv)
    expect(colour.get(0, (0, 0, 0)) == (0, 0, 0), "ids_preview_%s.png: black where no node" % vv)
    lit = [c for n, c in colour.items() if n]
    expect(len(lit) >= 2 and len(set(lit)) == len(lit), "ids_preview_%s.png: distinct ids, distinct colours %r" % (vv, colour))
expect(len(scales) == 1, "one depth scale per run: %r" % scales)

# the synchronous readback writes the same bytes
sync_out = os.path.join(OUT, "sync")
render(sync_out, "--readback", "sync")
differ = [n for n in sorted(names) if (n.endswith(".png") or n.endswith(".npy")) and
          open(os.path.join(default_out, n), "rb").read() != open(os.path.join(sync_out, n), "rb").read()]
expect(not differ, "stream and sync differ in %s" % differ)

# EXR: the depth alone, and one file of named layers
exr_out = os.path.join(OUT, "exr")
render(exr_out, "--output-files", "exr,layers")
names = set(os.listdir(exr_out))
expect(not any(n.endswith(".npy") or n.startswith("depth_") and n.endswith(".png") for n in names),
       "exr,layers: no .npy or depth PNG: %s" % sorted(names))
for v in range(VIEWS):
    vv = "%04d" % v
    depth = npy(default_out, "depth", v)
    normal = npy(default_out, "normal", v)
    ids = npy(default_out, "ids", v)
    types, ch = exr_channels(os.path.join(exr_out, "depth_%s.exr" % vv))
    expect(types == {"Z": "float"}, "depth_%s.exr: one float channel Z (%r)" % (vv, types))
    expect("Z" in ch and np.allclose(ch["Z"], depth, rtol=0, atol=1e-6), "depth_%s.exr: Z is the depth" % vv)
    types, ch = exr_channels(os.path.join(exr_out, "layers_%s.exr" % vv))
    want = {"R": "half", "G": "half", "B": "half", "A": "half", "Z": "float", "N.X": "float", "N.Y": "float",
            "N.Z": "float", "id.node": "uint", "id.mesh": "uint", "id.material": "uint", "id.primitive": "uint"}
    expect(types == want, "layers_%s.exr: channels %r" % (vv, types))
    if types != want:
        continue
    expect(np.allclose(ch["Z"], depth, rtol=0, atol=1e-6), "layers_%s.exr: Z is the depth" % vv)
    for k, axis in enumerate("XYZ"):
        expect(np.allclose(ch["N." + axis], normal[:, :, k], rtol=0, atol=1e-6), "layers_%s.exr: N.%s" % (vv, axis))
    # oiiotool prints a uint channel normalised to [0, 1]: scaled back in floats first (exact for these ids)
    id_names = ",".join("id." + kind for kind in ("node", "mesh", "material", "primitive"))
    scaled = os.path.join(exr_out, "ids_scaled_%s.exr" % vv)
    r = subprocess.run([OIIOTOOL, os.path.join(exr_out, "layers_%s.exr" % vv), "--ch", id_names, "--mulc",
                        "4294967295", "-d", "float", "-o", scaled], capture_output=True, text=True)
    expect(r.returncode == 0, "oiiotool scales the ids of layers_%s.exr: %s" % (vv, r.stderr))
    _, ch_ids = exr_channels(scaled)
    for k, kind in enumerate(("node", "mesh", "material", "primitive")):
        got = ch_ids.get("id." + kind)
        expect(got is not None and np.array_equal(np.rint(got).astype(np.int64), ids[:, :, k]),
               "layers_%s.exr: id.%s is ids_%s.npy[..., %d]" % (vv, kind, vv, k))
    # colour: the view's sRGB bytes, decoded to linear (half precision)
    view_png = [n for n in os.listdir(exr_out) if n.startswith("view_") and n.endswith(".png")]
    view_png.sort()
    _, _, rgba = read_png(os.path.join(exr_out, view_png[v]))
    c = rgba[:, :, 0] / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    expect(np.allclose(ch["R"], lin, rtol=2e-3, atol=1e-4), "layers_%s.exr: R is the colour, linear" % vv)
    expect(np.allclose(ch["A"], rgba[:, :, 3] / 255.0, atol=1e-3), "layers_%s.exr: A is the alpha" % vv)

r = subprocess.run([MVR, "render", SCENE, "--outputs", "depth", "--output-files", "npy,tiff", "--out",
                    os.path.join(OUT, "bad")], capture_output=True, text=True)
expect(r.returncode == 2 and "'tiff'" in r.stderr, "an unknown --output-files kind: exit 2 naming it (%d: %s)" %
       (r.returncode, r.stderr))

print("%d passed, %d failed" % (1 if not failures else 0, 1 if failures else 0))
sys.exit(1 if failures else 0)
