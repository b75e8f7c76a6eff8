"""Bad arguments are Python errors (issue 32): every count, size, aspect,
sample count, float and output name is checked in Python before any C call,
with a ValueError naming the argument. Before: samples=3 rendered (the GL
rounds up to a count it has), aspect=nan reached the C framing, a NaN
exposure or clear colour reached the renderer, `environment="neutral"`
raised a raw AttributeError."""
import math

import numpy as np
import pytest

import mvr
from conftest import PEERS

NAN, INF = float("nan"), float("inf")


@pytest.fixture(scope="module")
def scene():
    with mvr.Scene.load(PEERS / "textured.gltf") as s:
        yield s


@pytest.fixture(scope="module")
def views(scene):
    with mvr.Views.from_camera(scene) as v:
        yield v


def raises(fn, *words):
    with pytest.raises(ValueError) as e:
        fn()
    for w in words:
        assert w in str(e.value), "%r not in %r" % (w, str(e.value))


@pytest.mark.parametrize("kwargs,words", [
    ({"samples": 3}, ("samples", "3", "MSAA")),
    ({"samples": 6}, ("samples", "6")),
    ({"samples": 2 ** 20}, ("samples",)),           # a power of two past GL_MAX_SAMPLES
    ({"samples": -1}, ("samples", "-1")),
    ({"samples": NAN}, ("samples",)),
    ({"clear_color": (0, NAN, 0, 1)}, ("clear_color[1]", "finite")),
    ({"clear_color": (0, 0)}, ("clear_color", "3 or 4 values")),
    ({"exposure": NAN}, ("exposure", "finite")),
    ({"exposure": 0.0}, ("exposure", "> 0")),
    ({"exposure": -2.0}, ("exposure",)),
    ({"ev100": INF}, ("ev100", "finite")),
    ({"background_blur": 1.5}, ("background_blur", "<= 1")),
    ({"background_blur": NAN}, ("background_blur",)),
    ({"alpha_cutoff": -0.1}, ("alpha_cutoff", ">= 0")),
    ({"outputs": ("color", "depht")}, ("outputs", "'depht'")),
    ({"outputs": ("depth", "depth")}, ("outputs", "'depth'", "twice")),
    ({"outputs": (3,)}, ("outputs", "3")),
    ({"environment": "studio"}, ("environment", "'studio'")),
    ({"environment": 1}, ("environment",)),
    ({"tone_map": "filmic"}, ("tone_map", "filmic")),
    ({"exposure_mode": "manual"}, ("exposure_mode", "manual")),
    ({"color_format": "rgb8"}, ("color_format",)),
])
def test_render_arguments(ctx, scene, views, kwargs, words):
    raises(lambda: ctx.render(scene, views, (8, 8), **kwargs), *words)


def test_supported_sample_counts_render(ctx, scene, views):
    most = ctx.caps["limits"]["max_samples"]
    assert most >= 4
    for n in (0, 1, 2, 4):
        (v,) = ctx.render(scene, views, (8, 8), samples=n)
        assert v.color.shape == (8, 8, 4)
    assert ctx.stats["samples"] == 4


def test_render_object_types(ctx, scene, views):
    with pytest.raises(TypeError, match="scene: an mvr.Scene"):
        ctx.render("textured.gltf", views, (8, 8))
    with pytest.raises(TypeError, match="views: an mvr.Views"):
        ctx.render(scene, [views], (8, 8))
    raises(lambda: ctx.render(scene, None, (0, 8)), "size: width")


@pytest.mark.parametrize("kwargs,words", [
    ({"aspect": NAN}, ("aspect", "finite")),
    ({"aspect": 0.0}, ("aspect", ">= 1.52588e-05")),
    ({"aspect": -1.0}, ("aspect",)),
    ({"aspect": INF}, ("aspect",)),
    ({"count": -1}, ("count", "-1", "[0, 1024]")),
    ({"count": 1025}, ("count", "[0, 1024]")),
    ({"count": 2.5}, ("count", "an integer")),
    ({"ipd": NAN}, ("ipd", "finite")),
    ({"ipd": -0.1}, ("ipd", ">= 0")),
    ({"elevation": (0.1, NAN)}, ("elevation[1]", "finite")),
    ({"elevation": (-math.pi / 2, 0.5)}, ("elevation[0]", "(-pi/2, pi/2)")),
    ({"elevation": (0.5, 0.1)}, ("elevation", "(lowest, highest)")),
    ({"elevation": (0.1,)}, ("elevation", "2 values")),
])
def test_layout_arguments(scene, kwargs, words):
    raises(lambda: mvr.Views.layout(scene, "orbit", **kwargs), *words)


def test_camera_and_pose_arguments(scene):
    raises(lambda: mvr.Views.from_camera(scene, 0, count=0), "count", "[1, 1024]")
    raises(lambda: mvr.Views.from_camera(scene, 0, count=-1), "count")
    raises(lambda: mvr.Views.from_camera(scene, 0, count=2, ipd=NAN), "ipd", "finite")
    raises(lambda: mvr.Views.from_poses(np.eye(4), yfov=NAN), "yfov", "finite")
    raises(lambda: mvr.Views.from_poses(np.eye(4), yfov=4.0), "yfov", "below pi")
    raises(lambda: mvr.Views.from_poses(np.eye(4), origin=(0, NAN, 0)), "origin[1]")
    raises(lambda: mvr.Views.from_poses(np.zeros((0, 4, 4))), "pose count", "[1, 1024]")
    K = np.array([[50.0, 0, 32], [0, 50.0, 24], [0, 0, 1]])
    raises(lambda: mvr.Views.from_poses(np.eye(4), K, (64, INF)), "size[1]", "finite")
    raises(lambda: mvr.look_at((0, 0, NAN), (0, 0, -1)), "eye[2]")
    raises(lambda: mvr.Views.default(scene, (640, -480)), "size: height")


@pytest.mark.parametrize("kwargs,words", [
    ({"intensity": 0.0}, ("intensity", "> 0")),
    ({"intensity": NAN}, ("intensity", "finite")),
    ({"rotation": INF}, ("rotation", "finite")),
    ({"color": (1, -1, 1)}, ("color[1]", ">= 0")),
    ({"color": (0, 0, 0)}, ("color", "black")),
    ({"specular_size": 100}, ("specular_size", "power of two")),
    ({"specular_size": 8}, ("specular_size",)),
    ({"specular_samples": 4097}, ("specular_samples", "[0, 4096]")),
])
def test_environment_arguments(kwargs, words):
    raises(lambda: mvr.Environment("uniform", **kwargs), *words)


@pytest.mark.parametrize("call,words", [
    (lambda s: s.add_light(intensity=NAN), ("intensity", "finite")),
    (lambda s: s.add_light(intensity=-1), ("intensity", ">= 0")),
    (lambda s: s.add_light("spot", outer_cone_angle=2.0), ("outer_cone_angle",)),
    (lambda s: s.add_material(roughness=1.5), ("roughness", "<= 1")),
    (lambda s: s.add_material(base_color=(1, NAN, 1, 1)), ("base_color[1]",)),
    (lambda s: s.add_node(translation=(0, INF, 0)), ("translation[1]", "finite")),
    (lambda s: s.add_node(rotation=(0, 0, 0)), ("rotation", "4 values")),
    (lambda s: s.add_camera(yfov=NAN), ("yfov",)),
    (lambda s: s.set_ambient((NAN, 0, 0)), ("ambient[0]",)),
])
def test_scene_float_arguments(call, words):
    with mvr.Scene() as s:
        raises(lambda: call(s), *words)
        assert s.info["nodes"] == 0 and s.info["lights"] == 0  # nothing was added


def test_animation_time(scene):
    with mvr.Scene.load(PEERS / "rigged.gltf") as s:
        raises(lambda: s.apply_animation(0, NAN), "time", "finite")
