"""A scene built in code, seen through a camera given by intrinsics: where
things land in the arrays (image order, the camera metadata's pixels),
what the depth / normal / ids outputs hold there; errors with mvr's
messages; objects released by close() and with-blocks."""
import numpy as np
import pytest

import mvr
from mvr import _native as N
from conftest import PEERS

W, H = 64, 48
K = np.array([[50.0, 0, 32], [0, 50.0, 24], [0, 0, 1]])


def quad(x0, x1, y0, y1, z):
    """Two triangles facing +Z (towards a camera at the origin looking along -Z)."""
    pos = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], np.float32)
    return dict(positions=pos, normals=np.tile([0, 0, 1], (4, 1)), indices=np.array([0, 1, 2, 0, 2, 3], np.uint16))


@pytest.fixture
def two_quads():
    """A red quad above the axis, centred, and a green one low on the left,
    5 m in front of a camera at the origin; unlit, so their colours are exact."""
    s = mvr.Scene()
    red = s.add_material(base_color=(1, 0, 0, 1), unlit=True)
    green = s.add_material(base_color=(0, 1, 0, 1), unlit=True)
    ids = {}
    ids["red_mesh"] = s.add_mesh(material=red, **quad(-1, 1, 0.5, 1.5, 0))
    ids["green_mesh"] = s.add_mesh(material=green, **quad(-3, -2, -1.5, -0.5, 0))
    ids["red_node"] = s.add_node(mesh=ids["red_mesh"], translation=(0, 0, -5), name="red")
    ids["green_node"] = s.add_node(mesh=ids["green_mesh"], translation=(0, 0, -5), name="green")
    ids["red_material"], ids["green_material"] = red, green
    yield s, ids
    s.close()


def pixel_of(camera, point):
    uv, z = camera.project([point])
    return int(uv[0, 1]), int(uv[0, 0])  # row, column


def test_image_order_and_camera_pixels(ctx, two_quads):
    scene, _ = two_quads
    with mvr.Views.from_poses(np.eye(4), K, (W, H)) as views:
        # no environment: unlit colours exact, without the default's tone map
        (v,) = ctx.render(scene, views, (W, H), clear_color=(0, 0, 0, 1), environment=None)
    cam = v.camera
    assert np.allclose(cam.K, K)
    red_at = pixel_of(cam, (0, 1, -5))
    green_at = pixel_of(cam, (-2.5, -1, -5))
    # the red quad is above the axis: the top half of the picture (row 0 at the top)
    assert red_at == (14, 32) and green_at == (34, 7)
    assert tuple(v.color[red_at]) == (255, 0, 0, 255)
    assert tuple(v.color[green_at]) == (0, 255, 0, 255)
    # the red quad covers rows 9..18 and columns 22..41, exactly as K says
    red = np.all(v.color == (255, 0, 0, 255), axis=2)
    rows, cols = np.nonzero(red)
    assert (rows.min(), rows.max(), cols.min(), cols.max()) == (9, 18, 22, 41)
    assert tuple(v.color[40, 60]) == (0, 0, 0, 255)  # the clear colour below right


def test_outputs_of_a_known_scene(ctx, two_quads):
    scene, ids = two_quads
    # view 0 at the origin; view 1 to the right, turned to face the red quad
    # (camera-space normals then differ from world ones)
    poses = np.stack([np.eye(4), mvr.look_at((4, 1, -1), (0, 1, -5))])
    with mvr.Views.from_poses(poses, K, (W, H)) as views:
        world = ctx.render(scene, views, (W, H), outputs=mvr.OUTPUTS)
        camera = ctx.render(scene, views, (W, H), outputs=("normal",), normal_space="camera")
    v = world[0]
    r, c = pixel_of(v.camera, (0, 1, -5))
    assert v.coverage[r, c] == 1.0 and v.coverage[40, 60] == 0.0
    assert v.depth[r, c] == pytest.approx(5.0, rel=1e-5)
    # the ray through the pixel's centre meets the plane z = -5
    ray = np.array([(c + 0.5 - K[0, 2]) / K[0, 0], (r + 0.5 - K[1, 2]) / K[1, 1], 1.0])
    assert v.distance[r, c] == pytest.approx(5.0 * np.linalg.norm(ray), rel=1e-5)
    assert np.allclose(v.normal[r, c], (0, 0, 1), atol=1e-5)
    assert tuple(v.ids[r, c][:3]) == (ids["red_node"], ids["red_mesh"], ids["red_material"])
    g = pixel_of(v.camera, (-2.5, -1, -5))
    assert tuple(v.ids[g][:3]) == (ids["green_node"], ids["green_mesh"], ids["green_material"])
    assert np.all(v.ids[40, 60] == 0) and v.depth[40, 60] == 0 and np.all(v.normal[40, 60] == 0)
    # view 1: camera-space normals are the world normal turned into the camera
    v1, n1 = world[1], camera[1].normal
    r, c = pixel_of(v1.camera, (0, 1, -5))
    assert v1.coverage[r, c] == 1.0
    assert np.allclose(v1.normal[r, c], (0, 0, 1), atol=1e-5)
    assert np.allclose(n1[r, c], v1.camera.world_to_camera[:3, :3] @ (0, 0, 1), atol=1e-5)
    # the oblique quad's depth at the pixel's centre: where that ray meets z = -5
    # (the direction's camera z is -1, so the ray's parameter is the depth)
    ray = np.array([(c + 0.5 - K[0, 2]) / K[0, 0], -(r + 0.5 - K[1, 2]) / K[1, 1], -1.0])
    origin, direction = v1.camera.position, v1.camera.camera_to_world[:3, :3] @ ray
    t = (-5.0 - origin[2]) / direction[2]
    assert v1.depth[r, c] == pytest.approx(t, rel=1e-5)
    assert v1.distance[r, c] == pytest.approx(t * np.linalg.norm(ray), rel=1e-5)


def test_bad_file_raises_mvrs_message(reference, tmp_path):
    missing = tmp_path / "missing.gltf"
    c_message = reference("load", missing, check=False).stdout.strip()
    assert c_message and c_message != "ok"
    with pytest.raises(mvr.Error) as e:
        mvr.Scene.load(missing)
    assert e.value.message == c_message
    assert e.value.result == "MVR_ERROR_IO"
    assert c_message in str(e.value)
    # a file that is not glTF: the loader's own words, again
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "nodes": [{"mesh": 7}]}')
    c_message = reference("load", bad, check=False).stdout.strip()
    with pytest.raises(mvr.Error) as e:
        mvr.Scene.load(bad)
    assert e.value.message == c_message and "mesh" in c_message


def test_library_errors_carry_their_message():
    with mvr.Scene() as s:
        with pytest.raises(mvr.Error) as e:
            s.add_node(mesh=42)
        assert e.value.result == "MVR_ERROR_INVALID_ARGUMENT"
        assert "mesh" in e.value.message  # mvr_scene_last_error's text, naming what was wrong
        with pytest.raises(mvr.Error) as e:
            s.add_mesh(positions=np.zeros((3, 3)), material=99)
        assert "material" in e.value.message
    with pytest.raises(mvr.Error, match=r"view 0: znear -1 / zfar 0 invalid"):
        # a near plane behind the camera: refused by the view set, in its words
        mvr.Views.from_poses(np.eye(4), K, (W, H), znear=-1.0)
    with pytest.raises(ValueError, match="not a rotation"):
        mvr.Views.from_poses(np.diag([2.0, 1, 1, 1]), K, (W, H))


class Spy:
    def __init__(self, monkeypatch, *names):
        self.calls = []
        for name in names:
            real = getattr(N.C, name)
            monkeypatch.setattr(N.C, name, self._wrap(name, real))

    def _wrap(self, name, real):
        def call(*args):
            self.calls.append((name, args[0]))
            return real(*args)
        return call


def test_with_blocks_destroy_what_they_made(monkeypatch, two_quads):
    spy = Spy(monkeypatch, "mvr_context_destroy", "mvr_renderer_destroy", "mvr_target_destroy",
              "mvr_view_set_destroy", "mvr_scene_destroy", "mvr_environment_destroy")
    scene, _ = two_quads
    with mvr.Context() as ctx, mvr.Views.from_poses(np.eye(4), K, (W, H)) as views, mvr.Environment() as env:
        handles = {"mvr_context_destroy": ctx.handle, "mvr_renderer_destroy": ctx._renderer,
                   "mvr_view_set_destroy": views.handle, "mvr_environment_destroy": env.handle}
        ctx.render(scene, views, (W, H), environment=env)
        handles["mvr_target_destroy"] = ctx._target.handle
        assert spy.calls == []
    # each destroyed once, with its own handle; the target and renderer before their context
    assert sorted(spy.calls) == sorted(handles.items())
    order = [name for name, _ in spy.calls]
    assert order.index("mvr_target_destroy") < order.index("mvr_renderer_destroy") < order.index(
        "mvr_context_destroy")
    assert ctx.closed and views.closed and env.closed
    ctx.close()  # a second close does nothing
    assert len(spy.calls) == len(handles)
    # use after close raises
    with pytest.raises(mvr.ClosedError, match="mvr.Context is closed"):
        ctx.render(scene, views, (W, H))
    with pytest.raises(mvr.ClosedError):
        ctx.caps
    with pytest.raises(mvr.ClosedError, match="mvr.Views is closed"):
        len(views)
    with pytest.raises(mvr.ClosedError):
        with ctx:
            pass
    scene_handle = scene.handle
    scene.close()
    assert spy.calls[-1] == ("mvr_scene_destroy", scene_handle)
    with pytest.raises(mvr.ClosedError, match="mvr.Scene is closed"):
        scene.info


def test_context_survives_changing_sizes_and_scenes(ctx, two_quads):
    """One target per (size, layers, format, outputs), remade when they change."""
    scene, _ = two_quads
    with mvr.Views.from_poses(np.eye(4), K, (W, H)) as one, \
            mvr.Views.from_poses(np.stack([np.eye(4)] * 3), K, (W, H)) as three:
        a = ctx.render(scene, one, (W, H))
        b = ctx.render(scene, three, (2 * W, 2 * H))
        c = ctx.render(scene, one, (W, H))
    assert len(b) == 3 and b[2].color.shape == (2 * H, 2 * W, 4)
    assert np.array_equal(a[0].color, c[0].color)
    # at twice the size the same views scale their intrinsics
    assert np.allclose(b[0].camera.K, np.diag([2, 2, 1]) @ K)


def test_scene_queries():
    with mvr.Scene.load(PEERS / "variants.gltf") as s:
        info = s.info
        assert info["meshes"] > 0 and info["nodes"] > 0
        assert info["bounds_min"] == (-1.0, 0.0, 0.0) and info["bounds_max"] == (1.0, 1.0, 0.0)  # a flat card
        assert s.gltf_info["warnings"] >= 0 and s.gltf_info["camera_nodes"] == len(s.camera_nodes)
        names = s.variants
        assert len(names) >= 2
        s.select_variant(names[1])
        with pytest.raises(mvr.Error, match="no-such-variant|variant"):
            s.select_variant("no-such-variant")
        s.select_variant(None)
    with mvr.Scene.load(PEERS / "rigged.gltf") as s:
        anims = s.animations
        assert anims and anims[0][2] > anims[0][1]
        s.apply_animation(0, 0.5 * (anims[0][1] + anims[0][2]))
        s.apply_animation("all", 0.0, loop=True)
        s.reset_pose()


def test_log_goes_to_python_logging(caplog, tmp_path):
    """Warnings reach logging.getLogger("mvr"); a failed call's message is
    the exception's, and is not logged again above DEBUG."""
    f = tmp_path / "made_up.gltf"
    f.write_text('{"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_made_up"], "scenes": [{"nodes": [0]}],'
                 ' "nodes": [{"name": "a"}]}')
    with caplog.at_level("INFO", logger="mvr"):
        with mvr.Scene.load(f) as s:
            assert s.gltf_info["warnings"] == 1
        warnings = [r for r in caplog.records if r.name == "mvr" and r.levelname == "WARNING"]
        assert len(warnings) == 1 and "EXT_made_up" in warnings[0].getMessage()
        caplog.clear()
        with pytest.raises(mvr.Error):
            mvr.Scene.load(tmp_path / "missing.gltf")
        with mvr.Context() as ctx, mvr.Scene() as s, mvr.Views.from_poses(np.eye(4)) as v:
            with pytest.raises(mvr.Error, match="not averaged") as e:
                ctx.render(s, v, (8, 8), outputs=("depth",), samples=4)
            assert e.value.result == "MVR_ERROR_INVALID_ARGUMENT"
        assert not [r for r in caplog.records if r.levelno >= 30], [r.getMessage() for r in caplog.records]
