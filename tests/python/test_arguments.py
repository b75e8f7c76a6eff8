"""Python arguments that ctypes would change on the way to C: an int outside
its C type wraps silently (memory_budget=-1 became "unlimited", a width of
2**33 + 64 became 64 and then a 32 GiB array) and a NUL inside a string ends
it early (a path "a.gltf\\0x" opened a.gltf). Each is a ValueError naming the
argument (and the allowed range), raised before anything reaches C."""
import numpy as np
import pytest

import mvr
from conftest import PEERS

FILE = PEERS / "textured.gltf"
U32 = "[0, 4294967295]"


@pytest.fixture(scope="module")
def scene():
    with mvr.Scene.load(FILE) as s:
        yield s


@pytest.fixture(scope="module")
def views(scene):
    with mvr.Views.layout(scene, "stereo") as v:
        yield v


def raises(fn, *words):
    with pytest.raises(ValueError) as e:
        fn()
    for w in words:
        assert w in str(e.value), "%r not in %r" % (w, str(e.value))


@pytest.mark.parametrize("kwargs,words", [
    ({"memory_budget": -1}, ("memory_budget", "-1", "[0, 18446744073709551615]")),
    ({"memory_budget": 2 ** 64}, ("memory_budget", "[0, 18446744073709551615]")),
    ({"scene": -1}, ("scene", "[0, 4294967294]")),
    ({"scene": 2 ** 32 - 1}, ("scene", "[0, 4294967294]")),
    ({"scene": 0.5}, ("scene", "an integer")),
    ({"allowed_root": "/tmp\0/etc"}, ("allowed_root", "NUL")),
    ({"base_dir": b"peers\0"}, ("base_dir", "NUL")),
])
def test_load_options(kwargs, words):
    raises(lambda: mvr.Scene.load(FILE, **kwargs), *words)


def test_load_path_with_nul():
    # before: the path ended at the NUL, and textured.gltf loaded
    raises(lambda: mvr.Scene.load(str(FILE) + "\0.png"), "path", "NUL")
    raises(lambda: mvr.Scene.load(bytes(FILE) + b"\0"), "path", "NUL")
    raises(lambda: mvr.Environment.from_file(str(PEERS / "diag_axes.hdr") + "\0x"), "path", "NUL")


@pytest.mark.parametrize("size,words", [
    ((2 ** 33 + 64, 1), ("size: width", "8589934656", "[1, 4294967295]")),
    ((8, -1), ("size: height", "-1", "[1, 4294967295]")),
    ((0, 8), ("size: width", "[1, 4294967295]")),
    ((8.5, 8), ("size: width", "an integer")),
    ((8,), ("size", "(width, height)")),
])
def test_render_size(ctx, scene, views, size, words):
    raises(lambda: ctx.render(scene, views, size), *words)


def test_render_samples(ctx, scene, views):
    raises(lambda: ctx.render(scene, views, (8, 8), samples=-1), "samples", U32)


def test_integral_sizes_still_render(ctx, scene, views):
    got = ctx.render(scene, views, (np.int64(8), 6.0))
    assert got[0].color.shape == (6, 8, 4)


def test_context_arguments():
    raises(lambda: mvr.Context(device_index=2 ** 32), "device_index", "[0, 2147483647]")
    raises(lambda: mvr.Context(device_index=-1), "device_index")
    raises(lambda: mvr.Context(program_cache_dir="/tmp/cache\0x"), "program_cache_dir", "NUL")


@pytest.mark.parametrize("call,words", [
    (lambda s: s.add_light(layers=-1), ("layers", "-1", U32)),
    (lambda s: s.add_node(parent=-1), ("parent", U32)),
    (lambda s: s.add_node(mesh=2 ** 32 + 1), ("mesh", U32)),
    (lambda s: s.add_node(camera=-2), ("camera", U32)),
    (lambda s: s.add_node(name="a\0b"), ("name", "NUL")),
    (lambda s: s.add_material(base_color_texture=-1), ("base_color_texture", U32)),
    (lambda s: s.add_material(name=b"m\0"), ("name", "NUL")),
    (lambda s: s.add_mesh(positions=np.zeros((3, 3)), material=-1), ("material", U32)),
    (lambda s: s.add_mesh(positions=np.zeros((3, 3)), indices=[0.0, 1.5, 2.0]), ("indices", "integer")),
    (lambda s: s.add_mesh(positions=np.zeros((3, 3)), name="mesh\0"), ("name", "NUL")),
    (lambda s: s.add_image(np.zeros((2, 2, 4), np.uint8), name="i\0"), ("name", "NUL")),
    (lambda s: s.set_node_transform(-1), ("node", U32)),
    (lambda s: s.apply_animation(-1, 0.0), ("animation", "[0, 4294967294]")),
    (lambda s: s.apply_animation("walk\0", 0.0), ("animation", "NUL")),
    (lambda s: s.select_variant(-1), ("variant", "[0, 4294967294]")),
    (lambda s: s.select_variant("red\0"), ("variant", "NUL")),
])
def test_scene_arguments(call, words):
    with mvr.Scene() as s:
        raises(lambda: call(s), *words)
        assert s.info["nodes"] == 0 and s.info["lights"] == 0 and s.info["meshes"] == 0  # nothing was added


def test_view_arguments(scene, views):
    # counts: the library's own limit (MVR_VIEW_SET_MAX_VIEWS)
    raises(lambda: mvr.Views.layout(scene, "ring", count=-1), "count", "[0, 1024]")
    raises(lambda: mvr.Views.layout(scene, "orbit", rows=2 ** 32), "rows", U32)
    raises(lambda: views.camera(0, -1, 8), "width", U32)
    raises(lambda: views.camera(0, 8, 2 ** 32 + 8), "height", U32)


def test_environment_arguments():
    # the library's ranges (mvr_environment_desc)
    raises(lambda: mvr.Environment(specular_size=-1), "specular_size", "[0, 1024]")
    raises(lambda: mvr.Environment(specular_samples=2 ** 32), "specular_samples", "[0, 4096]")
