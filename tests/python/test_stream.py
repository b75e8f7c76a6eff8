"""Context.render_stream: render()'s pixels, view by view, in memory flat in
the number of views."""
import os
import subprocess
import sys

import numpy as np
import pytest

import mvr
from conftest import PEERS

SCENE = PEERS / "coated.gltf"
ALL = ("color", "depth", "distance", "normal", "ids", "coverage")


@pytest.fixture(scope="module")
def scene():
    with mvr.Scene.load(SCENE) as s:
        yield s


def test_stream_is_render_byte_for_byte(ctx, scene):
    # 20 views: chunks of GL_MAX_VIEWS_OVR (6 here) and a short last one,
    # more chunks than the ring has targets
    with mvr.Views.layout(scene, "ring", count=20, aspect=4 / 3) as views:
        whole = ctx.render(scene, views, (80, 60), outputs=ALL)
        streamed = ctx.render_stream(scene, views, (80, 60), outputs=ALL)
        got = list(streamed)
    assert [v.index for v in got] == list(range(20))
    for a, b in zip(whole, got):
        for name in ALL:
            assert a[name].dtype == b[name].dtype and a[name].shape == b[name].shape
            assert np.array_equal(a[name], b[name]), "view %d, %s differs" % (a.index, name)
            assert b[name].flags.c_contiguous
        assert np.array_equal(a.camera.K, b.camera.K)
        assert np.array_equal(a.camera.camera_to_world, b.camera.camera_to_world)
    # the picture is not empty: the test compares something
    assert (got[0].ids[..., 0] > 0).mean() > 0.05


@pytest.mark.parametrize("chunk", [1, 4])
def test_stream_chunk_sizes_agree(ctx, scene, chunk):
    with mvr.Views.layout(scene, "ring", count=9, aspect=1.0) as views:
        whole = ctx.render(scene, views, (48, 48), color_dtype="float32")
        got = list(ctx.render_stream(scene, views, (48, 48), color_dtype="float32", chunk=chunk))
    assert len(got) == 9
    for a, b in zip(whole, got):
        assert np.array_equal(a.color, b.color), "view %d differs with chunk=%d" % (a.index, chunk)


def test_stream_shared_auto_exposure_is_metered_over_every_view(ctx, scene):
    # a shared auto exposure spans chunks: the stream meters every view
    # first and renders at that EV100, as one render of every view does
    with mvr.Views.layout(scene, "ring", count=14, aspect=1.0) as views:
        whole = ctx.render(scene, views, (64, 64), exposure_mode="auto", tone_map="aces")
        ev_whole = ctx.stats["exposure_ev100"]
        got = list(ctx.render_stream(scene, views, (64, 64), exposure_mode="auto", tone_map="aces"))
        ev_stream = ctx.stats["exposure_ev100"]
    assert abs(ev_whole - ev_stream) < 0.05, (ev_whole, ev_stream)
    worst = max(int(np.abs(a.color.astype(int) - b.color.astype(int)).max()) for a, b in zip(whole, got))
    assert worst <= 1, worst


def test_stream_checks_arguments_before_rendering(ctx, scene):
    with mvr.Views.layout(scene, "stereo") as views:
        with pytest.raises(ValueError, match="chunk"):
            ctx.render_stream(scene, views, (8, 8), chunk=-1)
        with pytest.raises(ValueError, match="outputs"):
            ctx.render_stream(scene, views, (8, 8), outputs=("colour",))
        with pytest.raises(ValueError, match="size"):
            ctx.render_stream(scene, views, (0, 8))


def test_stream_break_and_close(scene):
    with mvr.Context() as c, mvr.Views.layout(scene, "ring", count=12) as views:
        it = c.render_stream(scene, views, (32, 32))
        first = next(it)
        assert first.index == 0
        # the Context is free between views: a render in the middle
        assert len(c.render(scene, views, (16, 16))) == 12
        it.close()  # a break: the ring's GL objects go
        assert [v.index for v in c.render_stream(scene, views, (32, 32))] == list(range(12))
        it2 = c.render_stream(scene, views, (32, 32))
        next(it2)
        c.close()
        # the views of a chunk already read back may still come; the GL
        # is not touched again
        with pytest.raises(mvr.ClosedError):
            for _ in it2:
                pass


PEAK = r"""
import resource, sys
import mvr
n = int(sys.argv[2])
with mvr.Context() as ctx, mvr.Scene.load(sys.argv[1]) as scene, mvr.Views.layout(scene, "sphere", count=n) as views:
    seen = 0
    for v in ctx.render_stream(scene, views, (256, 256), outputs=("color", "depth", "normal", "ids")):
        assert v.index == seen and v.normal.shape == (256, 256, 3)
        seen += 1
    assert seen == n
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024)
"""


@pytest.mark.skipif("asan" in os.environ.get("LD_PRELOAD", ""), reason="peak RSS means nothing under ASan")
def test_stream_peak_memory_is_flat_in_the_view_count(tmp_path):
    # 1024 views of 256x256 with depth, normals and IDs (2.4 GB of arrays
    # in all) against 64: the ring and one chunk's arrays are all that is
    # held, so the peak may not grow with the views. The bound, 48 MiB,
    # is noise (llvmpipe's own allocations vary by ~15 MiB run to run);
    # a stream holding every view would grow by 2.3 GB. docs/benchmarks.md
    # has the figures.
    def peak(n):
        p = subprocess.run([sys.executable, "-c", PEAK, str(SCENE), str(n)], capture_output=True, text=True,
                           timeout=600)
        assert p.returncode == 0, p.stderr[-3000:]
        return int(p.stdout.split()[-1])

    small, large = peak(64), peak(1024)
    print("peak RSS: 64 views %d MiB, 1024 views %d MiB" % (small, large))
    assert large - small < 48, "1024 views peaked %d MiB, 64 views %d MiB" % (large, small)
    assert large < 512, "1024 views peaked %d MiB" % large
