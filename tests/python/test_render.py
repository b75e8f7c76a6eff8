"""glTF files rendered through the Python package give the C API's bytes:
py_reference renders the same file, framing, environment and exposure
through the C API and writes what mvr_renderer_read_layer (and
mvr_renderer_read_output) return, rows bottom to top; the package's
arrays are the same bytes in image order (rows top to bottom)."""
import numpy as np
import pytest

import mvr
from conftest import PEERS

W, H = 64, 48
CLEAR = (0.1, 0.2, 0.3, 1.0)


def read_camera(path):
    cam = {}
    for line in path.read_text().splitlines():
        key, *vals = line.split()
        cam[key] = [float(v) for v in vals] if len(vals) > 1 else float(vals[0])
    return cam


def c_matrix(cols):
    return np.array(cols).reshape(4, 4).T


def python_render(file, layout, count, view_path, outputs=("color",)):
    with mvr.Context(view_path=view_path) as ctx, mvr.Scene.load(PEERS / file) as scene, \
            mvr.Views.layout(scene, layout, count=count, aspect=W / H) as views, mvr.Environment("neutral") as env:
        # samples=1: no anti-aliasing (the view path asked must run; py_reference pins none too)
        got = ctx.render(scene, views, (W, H), outputs=outputs, environment=env, choose_exposure=True,
                         clear_color=CLEAR, samples=1)
        return got, ctx.stats


@pytest.mark.parametrize("file,layout,count,view_path", [
    ("textured.gltf", "ring", 4, "multiview"),   # one multiview pass
    ("textured.gltf", "ring", 4, "loop"),
    ("spheres.gltf", "stereo", 2, "auto"),
    ("variants.gltf", "orbit", 8, "auto"),       # more views than GL_MAX_VIEWS_OVR on llvmpipe
])
def test_color_and_cameras_equal_the_c_api(reference, out_dir, file, layout, count, view_path):
    reference("render", PEERS / file, out_dir, layout, count, "%dx%d" % (W, H), "neutral", view_path)
    got, stats = python_render(file, layout, count, view_path)
    assert len(got) == count
    if view_path != "auto":
        assert stats["view_path"] == view_path
    for k, v in enumerate(got):
        c = np.fromfile(out_dir / ("color_%d.bin" % k), np.uint8).reshape(H, W, 4)
        assert v.color.shape == (H, W, 4) and v.color.dtype == np.uint8
        assert v.color.flags["C_CONTIGUOUS"]
        # image order: the package's row 0 is GL's last row
        assert np.array_equal(v.color, c[::-1]), "view %d: %d bytes differ from the C API's" % (
            k, int(np.count_nonzero(v.color != c[::-1])))
        # something was drawn: many pixels are not the clear colour (the
        # corner pixel is, in every layout here)
        background = v.color[0, 0]
        assert np.mean(np.any(v.color != background, axis=2)) > 0.05, "view %d is empty" % k
        cam = read_camera(out_dir / ("camera_%d.txt" % k))
        assert (v.camera.width, v.camera.height) == (cam["width"], cam["height"]) == (W, H)
        assert v.camera.perspective == bool(cam["perspective"])
        assert (v.camera.fx, v.camera.fy, v.camera.cx, v.camera.cy) == (cam["fx"], cam["fy"], cam["cx"], cam["cy"])
        for name in ("projection", "world_to_camera", "camera_to_world"):
            assert np.array_equal(getattr(v.camera, name), c_matrix(cam[name])), "view %d %s" % (k, name)


def test_float_color_reads_the_same_layers(ctx):
    with mvr.Scene.load(PEERS / "textured.gltf") as scene, mvr.Views.layout(scene, "stereo", aspect=W / H) as views:
        u8 = ctx.render(scene, views, (W, H), clear_color=CLEAR)
        f32 = ctx.render(scene, views, (W, H), clear_color=CLEAR, color_dtype="float32")
    for a, b in zip(u8, f32):
        assert b.color.dtype == np.float32 and b.color.shape == (H, W, 4)
        # floats as stored: the 8-bit values normalized, in the same rows
        assert np.array_equal(np.round(b.color * 255).astype(np.uint8), a.color)


OUTPUT_FILES = {"depth": (np.float32, ()), "distance": (np.float32, ()), "normal": (np.float32, (3,)),
                "ids": (np.uint32, (4,)), "coverage": (np.float32, ())}


@pytest.mark.parametrize("view_path", ["multiview", "loop"])
def test_outputs_equal_the_c_api(reference, out_dir, view_path):
    names = list(OUTPUT_FILES)
    reference("render", PEERS / "textured.gltf", out_dir, "ring", 4, "%dx%d" % (W, H), "neutral", view_path,
              ",".join(names))
    got, _ = python_render("textured.gltf", "ring", 4, view_path, outputs=["color"] + names)
    for k, v in enumerate(got):
        for name, (dtype, tail) in OUTPUT_FILES.items():
            c = np.fromfile(out_dir / ("%s_%d.bin" % (name, k)), dtype).reshape((H, W) + tail)
            a = v[name]
            assert a.dtype == dtype and a.shape == (H, W) + tail, name
            # bit for bit (a NaN would compare equal to itself here, and fail below)
            assert np.array_equal(a.view(np.uint32), c[::-1].view(np.uint32)), "view %d %s" % (k, name)
        covered = v.coverage > 0.5
        assert 0.05 < covered.mean() < 1.0, "view %d: the model covers part of the view" % k
        assert np.all(np.isfinite(v.depth)) and np.all(v.depth[covered] > 0) and np.all(v.depth[~covered] == 0)
        assert np.all(v.distance[covered] >= v.depth[covered] * (1 - 1e-6))
        assert np.all(v.ids[covered][:, 0] > 0) and np.all(v.ids[~covered] == 0)
        n = np.linalg.norm(v.normal[covered], axis=1)
        assert np.allclose(n, 1.0, atol=1e-3)
