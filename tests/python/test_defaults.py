"""One set of defaults (issue 32): `mvr render FILE` with no options and
Python's ctx.render(scene) give the same pixels, byte for byte (the CLI's
PNGs are the stored bytes of the same sRGB target). Both light a file
without lights with the neutral studio, clear to the CLI's opaque dark sky,
pick the exposure and tone map with mvr_render_desc_choose_exposure, render
640 x 480 without MSAA, from the file's first camera (a stereo pair) or,
without one, the stereo framing. Also: environment strings and None, the
environment's intensity and rotation, and ids -> names."""
import base64
import ctypes
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import mvr
from mvr import _native as N
from conftest import PEERS, ROOT


def cli_path():
    build = pathlib.Path(os.environ.get("MVR_BUILD_DIR", ROOT / "build"))
    return build / "mvr"


def read_png(path):
    """RGBA8 rows top first, through the library's own PNG reader (libpng)."""
    img = N.out(N.mvr_image_data)
    err = N.mvr_error()
    r = N.C.mvr_image_read(str(path).encode(), N.PIXEL_TYPE("u8"), ctypes.byref(img), ctypes.byref(err))
    assert r == 0, N.text(err.message)
    try:
        count = img.height * img.width * 4
        px = np.ctypeslib.as_array(ctypes.cast(img.pixels, ctypes.POINTER(ctypes.c_uint8)), (count,))
        return px.reshape(img.height, img.width, 4).copy()
    finally:
        N.C.mvr_image_free(ctypes.byref(img))


def cli_render(path, out_dir):
    """`mvr render FILE --out DIR`: nothing else given."""
    exe = cli_path()
    if not exe.exists():
        pytest.skip("%s is missing (a build without the CLI)" % exe)
    p = subprocess.run([str(exe), "render", str(path), "--out", str(out_dir)], capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    return sorted(out_dir.glob("view_*.png"))


def lit_box(path):
    """A glTF of a box on a floor, no camera, lit by a 5000 lux sun
    (KHR_lights_punctual, physical units: auto exposure and PBR Neutral by
    default) and no material (glTF's default: white, rough, metallic 1)."""
    # a cube's 6 faces, 4 vertices each with their normal, and a floor quad
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = [a for a in range(3) if a != axis]
            base = len(pos)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = sign * 0.5, du * 0.5, dv * 0.5
                p[1] += 0.5
                pos.append(p)
                nrm.append(n)
            tri = [0, 1, 2, 0, 2, 3]
            # counter-clockwise seen from outside: flip where u x v points inward
            cross = np.cross(np.eye(3)[u], np.eye(3)[v])[axis] * sign
            idx += [base + k for k in (tri if cross > 0 else [0, 2, 1, 0, 3, 2])]
    base = len(pos)
    for x, z in ((-3, 3), (3, 3), (3, -3), (-3, -3)):
        pos.append([x, 0.0, z])
        nrm.append([0.0, 1.0, 0.0])
    idx += [base + k for k in (0, 1, 2, 0, 2, 3)]
    p = np.array(pos, np.float32)
    blob = p.tobytes() + np.array(nrm, np.float32).tobytes() + np.array(idx, np.uint16).tobytes()
    n_v, n_i = len(pos), len(idx)
    gltf = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 5000.0}]}},
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": n_v * 12},
                        {"buffer": 0, "byteOffset": n_v * 12, "byteLength": n_v * 12},
                        {"buffer": 0, "byteOffset": n_v * 24, "byteLength": n_i * 2}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": n_v, "type": "VEC3",
                       "min": p.min(axis=0).tolist(), "max": p.max(axis=0).tolist()},
                      {"bufferView": 1, "componentType": 5126, "count": n_v, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": n_i, "type": "SCALAR"}],
        "meshes": [{"name": "box_and_floor", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                                             "indices": 2}]}],
        "nodes": [{"name": "box", "mesh": 0},
                  # the sun from above and to the side: -Z turned down 60 degrees about X, then about Y
                  {"name": "sun", "rotation": [-0.4330127, 0.25, 0.1160254, 0.8580127],
                   "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "scenes": [{"nodes": [0, 1]}],
    }
    path.write_text(json.dumps(gltf))
    return path


def assert_same_bytes(cli_pngs, got):
    assert len(cli_pngs) == len(got) == 2  # a stereo pair, from the camera or the framing
    for k, (png, v) in enumerate(zip(cli_pngs, got)):
        c = read_png(png)
        assert v.color.shape == c.shape == (480, 640, 4)
        diff = np.count_nonzero(np.any(v.color != c, axis=2))
        assert diff == 0, "view %d: %d of %d pixels differ from `mvr render`'s" % (k, diff, 640 * 480)


@pytest.mark.parametrize("name", ["textured.gltf", "spheres.gltf"])
def test_python_defaults_render_the_clis_pixels(out_dir, name):
    """Files with a camera and no lights: the neutral studio, PBR Neutral."""
    pngs = cli_render(PEERS / name, out_dir)
    with mvr.Context() as ctx, mvr.Scene.load(PEERS / name) as scene:
        got = ctx.render(scene)
        assert ctx.stats["tone_mapper"] == N.TONE_MAP("pbr_neutral")
        # the same defaults spelled out: the views and size `mvr render` uses
        with mvr.Views.from_camera(scene, 0, count=2) as views:
            explicit = ctx.render(scene, views, (640, 480))
    assert_same_bytes(pngs, got)
    assert_same_bytes(pngs, explicit)
    for v in got:
        # lit (the issue: object mean RGB 8-14 without an environment) and an opaque sky behind
        covered = np.any(v.color != v.color[0, 0], axis=2)
        assert covered.mean() > 0.05 and v.color[covered][:, :3].mean() > 40
        sky = v.color[0, 0]  # the clear colour, tone mapped like the rest: opaque, dark, bluish
        assert sky[3] == 255 and 0 < sky[0] < sky[1] < sky[2] < 64
        assert np.array_equal(v.color[-1, -1], sky) and np.array_equal(v.color[0, -1], sky)


def test_python_defaults_render_the_clis_pixels_without_a_camera(out_dir, tmp_path):
    """No camera: the stereo framing at 640 / 480; lights in physical units:
    auto exposure with PBR Neutral (the environment adds to the sun)."""
    path = lit_box(tmp_path / "lit_box.gltf")
    pngs = cli_render(path, out_dir)
    with mvr.Context() as ctx, mvr.Scene.load(path) as scene:
        assert scene.camera_nodes == []
        got = ctx.render(scene)
        stats = ctx.stats
        # a Context of its own: a second frame in one Context pre-exposes by
        # the first frame's auto exposure, not the lights' guess, and may
        # round 1 LSB apart from the CLI's single frame (issue 35's framing:
        # 6677 pixels)
        with mvr.Context() as fresh, mvr.Views.layout(scene, "stereo", aspect=640 / 480) as views:
            explicit = fresh.render(scene, views, (640, 480))
    assert stats["exposure_mode"] == N.EXPOSURE_MODE("auto") and stats["tone_mapper"] == N.TONE_MAP("pbr_neutral")
    assert_same_bytes(pngs, got)
    assert_same_bytes(pngs, explicit)


def test_environment_strings_and_none(ctx):
    with mvr.Scene.load(PEERS / "textured.gltf") as scene, mvr.Views.from_camera(scene) as views, \
            mvr.Environment("neutral") as neutral, mvr.Environment("uniform") as uniform:
        size = (64, 48)
        by_name = ctx.render(scene, views, size, environment="neutral")[0].color
        # the Context makes "neutral" once: the renderer's prefiltered maps are reused
        ctx.render(scene, views, size)
        assert ctx.stats["env_prefilter_passes"] == 0
        by_object = ctx.render(scene, views, size, environment=neutral)[0].color
        assert np.array_equal(by_name, by_object)
        assert np.array_equal(ctx.render(scene, views, size, environment="uniform")[0].color,
                              ctx.render(scene, views, size, environment=uniform)[0].color)
        # None: no image-based lighting; the file has no lights, so it is black but for the sky
        dark = ctx.render(scene, views, size, environment=None, clear_color=(0, 0, 0, 1))[0].color
        assert dark[..., :3].max() < 16 < by_name[..., :3].max()
        with pytest.raises(ValueError, match="environment: .*'neutral', 'uniform' or None.*'studio'"):
            ctx.render(scene, views, size, environment="studio")
        with pytest.raises(ValueError, match="background: 'environment' needs an environment"):
            ctx.render(scene, views, size, environment=None, background="environment")


def test_environment_intensity_and_rotation(ctx):
    with mvr.Environment("neutral", intensity=2.0, rotation=30.0) as env:
        assert (env.intensity, env.rotation) == (2.0, 30.0)
        env.intensity, env.rotation = 0.5, -90.0
        assert (env.intensity, env.rotation) == (0.5, -90.0)
        with pytest.raises(ValueError, match="intensity"):
            env.intensity = 0.0
        with pytest.raises(ValueError, match="rotation"):
            env.rotation = float("nan")
        assert (env.intensity, env.rotation) == (0.5, -90.0)  # unchanged by the refused values
    with mvr.Scene.load(PEERS / "textured.gltf") as scene, mvr.Views.from_camera(scene) as views, \
            mvr.Environment("neutral") as env:
        one = ctx.render(scene, views, (64, 48), environment=env)[0].color.astype(int)
        env.intensity = 0.25
        quarter = ctx.render(scene, views, (64, 48), environment=env)[0].color.astype(int)
        env.intensity, env.rotation = 1.0, 90.0
        turned = ctx.render(scene, views, (64, 48), environment=env)[0].color.astype(int)
    covered = np.any(one != one[0, 0], axis=2)
    assert quarter[covered][:, :3].mean() < one[covered][:, :3].mean() - 20
    assert np.count_nonzero(np.any(turned != one, axis=2)) > 0.05 * covered.sum()


def test_ids_to_names(ctx, tmp_path):
    path = lit_box(tmp_path / "lit_box.gltf")
    with mvr.Scene.load(path) as scene, mvr.Views.layout(scene, "stereo", aspect=4 / 3) as views:
        (v, _) = ctx.render(scene, views, (64, 48), outputs=("ids",))
        seen = {int(i) for i in np.unique(v.ids[..., 0]) if i}
        assert seen and all(scene.node_name(i) == "box" for i in seen)
        assert {scene.mesh_name(int(i)) for i in np.unique(v.ids[..., 1]) if i} == {"box_and_floor"}
        assert scene.names == {"nodes": {1: "box", 2: "sun"}, "meshes": {1: "box_and_floor"},
                               "materials": {}}
        with pytest.raises(KeyError, match="node 3: the scene has 2 nodes"):
            scene.node_name(3)
        with pytest.raises(KeyError, match="node 0"):
            scene.node_name(0)
        with pytest.raises(ValueError, match="node"):
            scene.node_name(-1)
