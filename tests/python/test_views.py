"""View sets from numpy poses and intrinsics give those poses and intrinsics
back through mvr_view_set_get_camera; layouts and a file's camera."""
import math

import numpy as np
import pytest

import mvr
from conftest import PEERS


def random_rotation(rng):
    q = rng.normal(size=4)
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def random_poses(rng, n):
    poses = np.tile(np.eye(4), (n, 1, 1))
    for p in poses:
        p[:3, :3] = random_rotation(rng)
        p[:3, 3] = rng.uniform(-100, 100, 3)
    return poses


def test_poses_and_intrinsics_round_trip():
    rng = np.random.default_rng(7)
    n, size = 12, (640, 480)
    poses = random_poses(rng, n)
    ks = np.tile(np.eye(3), (n, 1, 1))
    ks[:, 0, 0] = rng.uniform(200, 900, n)        # fx
    ks[:, 1, 1] = ks[:, 0, 0] * rng.uniform(0.9, 1.1, n)  # fy: non-square pixels
    ks[:, 0, 2] = rng.uniform(250, 390, n)        # cx, off centre
    ks[:, 1, 2] = rng.uniform(180, 300, n)        # cy
    with mvr.Views.from_poses(poses, ks, size) as views:
        assert len(views) == n
        for i, cam in enumerate(views.cameras(*size)):
            assert (cam.width, cam.height) == size and cam.perspective
            assert np.allclose(cam.K, ks[i], rtol=1e-9, atol=1e-9), i
            assert np.allclose(cam.camera_to_world, poses[i], atol=1e-9), i
            assert np.allclose(cam.world_to_camera @ poses[i], np.eye(4), atol=1e-9), i
            # at half the size the intrinsics scale with it
            half = views.camera(i, size[0] // 2, size[1] // 2)
            assert np.allclose(half.K[:2], ks[i][:2] / 2, rtol=1e-9, atol=1e-9)
            # a point in front of the camera lands where K says
            pc = np.array([3.0, -2.0, 25.0])  # OpenCV camera
            world = poses[i] @ np.append(pc * (1, -1, -1), 1)  # OpenCV -> OpenGL camera, then world
            uv, z = cam.project([world[:3]])
            expect = ks[i] @ pc
            assert np.allclose(uv[0], expect[:2] / expect[2], atol=1e-7) and z[0] == pytest.approx(25.0)


def test_opencv_convention_is_the_flipped_opengl_pose():
    rng = np.random.default_rng(3)
    gl = random_poses(rng, 4)
    cv = gl.copy()
    cv[:, :3, 1:3] *= -1  # camera y down, looking along +Z
    k = np.array([[300.0, 0, 160], [0, 300, 120], [0, 0, 1]])
    with mvr.Views.from_poses(gl, k, (320, 240)) as a, \
            mvr.Views.from_poses(cv, k, (320, 240), convention="opencv") as b:
        for i in range(4):
            assert np.allclose(a.camera(i, 320, 240).camera_to_world, b.camera(i, 320, 240).camera_to_world,
                               atol=1e-12)


def test_perspective_without_intrinsics():
    with mvr.Views.from_poses(mvr.look_at((0, 0, 5), (0, 0, 0)), yfov=math.radians(90)) as v:
        cam = v.camera(0, 200, 100)
        # a 90-degree vertical field: fy = height / 2; square pixels
        assert cam.fy == pytest.approx(50.0) and cam.fx == pytest.approx(50.0)
        assert (cam.cx, cam.cy) == pytest.approx((100.0, 50.0))
        assert np.allclose(cam.position, (0, 0, 5))


@pytest.mark.parametrize("bad,match", [
    (dict(camera_to_world=np.diag([1.0, 1, 1, 2])), "last row"),
    (dict(camera_to_world=np.diag([1.0, -1, 1, 1])), "not a rotation"),
    (dict(camera_to_world=np.eye(4), intrinsics=np.array([[100.0, 5, 50], [0, 100, 50], [0, 0, 1]]),
          size=(100, 100)), "no skew"),
    (dict(camera_to_world=np.eye(4), intrinsics=np.eye(3)), "size"),
    (dict(camera_to_world=np.eye(4), intrinsics=np.array([[1e-6, 0, 50], [0, 100, 50], [0, 0, 1]]),
          size=(100, 100)), "90 degrees"),
    (dict(camera_to_world=np.full((4, 4), np.nan)), "NaN"),
    (dict(camera_to_world=np.eye(4), convention="blender"), "convention"),
])
def test_bad_poses_are_refused(bad, match):
    with pytest.raises(ValueError, match=match):
        mvr.Views.from_poses(**bad)


def test_layouts_look_at_the_scene():
    with mvr.Scene.load(PEERS / "textured.gltf") as scene:
        info = scene.info
        centre = 0.5 * (np.array(info["bounds_min"]) + np.array(info["bounds_max"]))
        for layout, count in (("stereo", 2), ("cube", 6), ("ring", 8), ("grid", 9), ("sphere", 50), ("orbit", 24)):
            with mvr.Views.layout(scene, layout) as views:
                assert len(views) == count, layout
        with mvr.Views.layout(scene, "sphere", count=10, aspect=2.0) as views:
            for cam in views.cameras(200, 100):
                uv, z = cam.project([centre])
                assert z[0] > 0 and np.allclose(uv[0], (100, 50), atol=1e-6)
        with pytest.raises(ValueError, match="layout"):
            mvr.Views.layout(scene, "spiral")


def test_views_from_the_files_camera():
    with mvr.Scene.load(PEERS / "textured.gltf") as scene:
        assert len(scene.camera_nodes) == 1
        with mvr.Views.from_camera(scene, 0) as one, mvr.Views.from_camera(scene, 0, count=2, ipd=0.1) as two:
            assert len(one) == 1 and len(two) == 2
            c, l, r = one.camera(0, 100, 100), two.camera(0, 100, 100), two.camera(1, 100, 100)
            # the eyes 0.1 apart along the camera's x axis, about it
            assert np.allclose(r.position - l.position, 0.1 * c.camera_to_world[:3, 0], atol=1e-9)
            assert np.allclose(0.5 * (l.position + r.position), c.position, atol=1e-9)
        with pytest.raises(mvr.Error, match="1 camera nodes"):
            mvr.Views.from_camera(scene, 3)
