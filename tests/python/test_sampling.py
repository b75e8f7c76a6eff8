"""Camera sampling through Views.layout (issue 33; mvr render's --fov,
--radius, --margin, --hemisphere, --layout random --seed --min-spacing,
--elevation, --up): each keyword reaches the library, checked on the views'
cameras; bad values are refused in Python, naming the keyword, before any C
call."""
import math

import numpy as np
import pytest

import mvr
from conftest import PEERS

W, H = 160, 120


@pytest.fixture(scope="module")
def scene():
    with mvr.Scene.load(PEERS / "textured.gltf") as s:
        yield s


def bounds(scene):
    lo, hi = np.array(scene.info["bounds_min"]), np.array(scene.info["bounds_max"])
    corners = np.array([[(hi if (k >> a) & 1 else lo)[a] for a in range(3)] for k in range(8)])
    return 0.5 * (lo + hi), corners


def test_yfov_is_the_views_field_of_view(scene):
    for layout in ("ring", "sphere", "random", "stereo"):
        with mvr.Views.layout(scene, layout, count=6, aspect=W / H, yfov=0.6) as views:
            for cam in views.cameras(W, H):
                assert cam.fy == pytest.approx(0.5 * H / math.tan(0.3), rel=1e-12), layout


def test_margin_fits_the_bounding_box(scene):
    _, corners = bounds(scene)
    for up in ("y", "z"):
        with mvr.Views.layout(scene, "sphere", count=20, aspect=W / H, margin=0.1, up=up) as views:
            for cam in views.cameras(W, H):
                uv, z = cam.project(corners)
                assert np.all(z > 0)
                extent = np.max(np.abs(uv - (cam.cx, cam.cy)) / (0.5 * W, 0.5 * H))
                assert extent == pytest.approx(0.9, abs=1e-9)


def test_default_looks_from_above_and_fits_the_box(scene):
    """Issue 35: stereo, ring and grid look down from 30 degrees (or the
    elevation given; 0.0 level) and every layout but cube keeps every corner
    of the bounding box inside 0.95 of the half-image, touching it."""
    _, corners = bounds(scene)
    cases = (("stereo", None, math.radians(30)), ("ring", 0.3, 0.3), ("grid", 0.0, 0.0), ("sphere", None, None),
             ("orbit", None, None), ("random", None, None))
    for layout, elevation, want in cases:
        with mvr.Views.layout(scene, layout, aspect=W / H, elevation=elevation) as views:
            cams = views.cameras(W, H)
            reach = 0.0
            for i, cam in enumerate(cams):
                uv, z = cam.project(corners)
                assert np.all(z > 0)
                extent = np.max(np.abs(uv - (cam.cx, cam.cy)) / (0.5 * W, 0.5 * H))
                assert extent <= 0.95 + 1e-9, (layout, i)
                reach = max(reach, extent)
                if want is not None and (layout != "grid" or i == len(cams) // 2):
                    back = cam.camera_to_world[:3, 2]  # the camera's +Z: from the scene toward it
                    assert math.asin(back[1]) == pytest.approx(want, abs=1e-9), (layout, i)
            assert reach == pytest.approx(0.95, abs=1e-6), layout
    # the sphere fit, level: the framing before issue 35 stays reachable
    with mvr.Views.layout(scene, "stereo", aspect=W / H, elevation=0.0, fit="sphere") as views, \
            mvr.Views.layout(scene, "stereo", aspect=W / H, elevation=0.0) as boxed:
        far = np.linalg.norm(views.cameras(W, H)[0].position - bounds(scene)[0])
        near = np.linalg.norm(boxed.cameras(W, H)[0].position - bounds(scene)[0])
        assert far > near


def test_radius_hemisphere_and_up(scene):
    centre, _ = bounds(scene)
    with mvr.Views.layout(scene, "random", count=30, radius=3.5, hemisphere="upper", up="z", seed=5) as views:
        for cam in views.cameras(W, H):
            o = cam.position - centre
            assert np.linalg.norm(o) == pytest.approx(3.5, rel=1e-12)
            assert o[2] >= -1e-12                         # above the horizon of a Z-up world
            assert abs(cam.camera_to_world[2, 0]) < 1e-12  # the right axis is level
            assert cam.camera_to_world[2, 1] > 0          # the up axis leans to +Z


def test_random_is_seeded_and_spaced(scene):
    def positions(seed, spacing=0.25):
        with mvr.Views.layout(scene, "random", count=40, seed=seed, min_spacing=spacing) as views:
            return np.array([c.position for c in views.cameras(W, H)])

    a, b, other = positions(2 ** 64 - 1), positions(2 ** 64 - 1), positions(1)
    assert np.array_equal(a, b)
    assert not np.any(np.all(a == other, axis=1))
    centre, _ = bounds(scene)
    d = a - centre
    d /= np.linalg.norm(d, axis=1)[:, None]
    cos = np.clip(d @ d.T, -1, 1)
    np.fill_diagonal(cos, -1)
    assert np.arccos(cos.max()) >= 0.25
    with pytest.raises(mvr.Error, match="min_spacing"):
        positions(0, spacing=1.2)


@pytest.mark.parametrize("kwargs, match", [
    (dict(yfov=float("nan")), "yfov"), (dict(yfov=3.2), "yfov"), (dict(yfov=1e-4), "yfov"),
    (dict(radius=-1.0), "radius"), (dict(radius=float("inf")), "radius"),
    (dict(margin=0.95), "margin"), (dict(margin=-0.1), "margin"), (dict(margin=0.1, radius=2.0), "radius"),
    (dict(hemisphere="lower"), "hemisphere"), (dict(hemisphere="upper", layout="ring"), "hemisphere"),
    (dict(seed=-1), "seed"), (dict(seed=2 ** 64), "seed"), (dict(seed=0.5), "seed"),
    (dict(min_spacing=4.0), "min_spacing"), (dict(min_spacing=float("nan")), "min_spacing"),
    (dict(up="x"), "up"), (dict(layout="cube", yfov=1.0), "cube"),
    (dict(elevation=(0.0, 1.6)), "elevation"), (dict(layout="orbit", elevation=(-1.0, math.pi / 2)), "elevation"),
    (dict(layout="stereo", elevation=math.pi / 2), "elevation"), (dict(layout="ring", elevation=(0.1, 0.2)), "elevation"),
    (dict(fit="cone"), "fit"), (dict(fit="sphere", margin=0.1), "fit"), (dict(layout="cube", elevation=0.2), "cube"),
])
def test_bad_sampling_is_refused_in_python(scene, kwargs, match):
    kwargs = dict(kwargs)
    layout = kwargs.pop("layout", "sphere")
    with pytest.raises(ValueError, match=match):
        mvr.Views.layout(scene, layout, **kwargs)
