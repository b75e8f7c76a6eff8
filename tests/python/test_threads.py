"""A Context from several threads: each call makes the GL context current on
its thread and releases it after (mvr_context_release_current), so renders on
a worker equal the main thread's; close() waits for a render in flight and
later calls raise mvr.ClosedError; two Contexts render on two threads at once.
The close-during-render case runs in a child interpreter, so a crash there
fails this test instead of ending the run."""
import os
import pathlib
import subprocess
import sys
import textwrap
import threading

import numpy as np

import mvr
from conftest import PEERS, ROOT

W, H = 48, 32
FILE = PEERS / "textured.gltf"


def on_thread(fn, *args):
    """fn(*args) on a new thread: its result, or the exception it raised."""
    box = {}

    def run():
        try:
            box["result"] = fn(*args)
        except BaseException as e:  # handed to the caller
            box["error"] = e

    t = threading.Thread(target=run)
    t.start()
    t.join(timeout=300)
    assert not t.is_alive(), "the thread did not finish"
    if "error" in box:
        raise box["error"]
    return box["result"]


def colors(ctx, scene, views):
    """The color layers of a render (the neutral studio lights files without lights)."""
    with mvr.Environment("neutral") as env:
        return [v.color for v in ctx.render(scene, views, (W, H), outputs=("color", "depth"), environment=env,
                                            choose_exposure=True, clear_color=(0, 0, 0, 1))]


def test_render_on_a_worker_thread_equals_the_main_thread():
    with mvr.Context() as ctx, mvr.Scene.load(FILE) as scene, \
            mvr.Views.layout(scene, "ring", count=3, aspect=W / H) as views:
        main = colors(ctx, scene, views)
        worker = on_thread(colors, ctx, scene, views)
        again = colors(ctx, scene, views)  # the worker gave the context back
        # other properties from a worker too
        assert on_thread(lambda: ctx.stats["views"]) == 3
        assert on_thread(lambda: ctx.caps["max_views"]) == ctx.caps["max_views"]
    assert len(worker) == 3
    for k, (a, b, c) in enumerate(zip(main, worker, again)):
        assert np.mean(np.any(a != a[0, 0], axis=2)) > 0.05, "view %d is empty" % k
        assert np.array_equal(a, b), "view %d: the worker's pixels differ" % k
        assert np.array_equal(a, c), "view %d: the main thread's second render differs" % k


CLOSE_DURING_RENDER = textwrap.dedent("""
    import sys, threading
    import mvr
    file = sys.argv[1]
    made, rendering = threading.Event(), threading.Event()
    box = {"ok": 0, "closed": 0, "other": []}

    def worker():
        # the context is made on the worker and used there only
        ctx = mvr.Context()
        box["ctx"] = ctx
        with mvr.Scene.load(file) as scene, mvr.Views.layout(scene, "ring", count=4) as views:
            made.set()
            for _ in range(100000):  # until close() ends it
                try:
                    ctx.render(scene, views, (96, 96), outputs=("color", "depth", "normal"))
                    box["ok"] += 1
                    rendering.set()
                except mvr.ClosedError:
                    box["closed"] += 1
                    break
                except Exception as e:
                    box["other"].append(repr(e))
                    break

    t = threading.Thread(target=worker)
    t.start()
    made.wait(120)
    rendering.wait(120)
    box["ctx"].close()  # while the worker renders: waits for that render
    assert box["ctx"].closed
    t.join(120)
    assert not t.is_alive()
    print("ok=%d closed=%d other=%s" % (box["ok"], box["closed"], box["other"]))
""")


def test_close_during_a_render_on_another_thread_waits_and_later_calls_raise():
    # the package this test imported, and the parent's environment (MVR_LIBRARY_DIR)
    package_dir = str(pathlib.Path(mvr.__file__).resolve().parent.parent)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [package_dir, os.environ.get("PYTHONPATH")])))
    p = subprocess.run([sys.executable, "-c", CLOSE_DURING_RENDER, str(FILE)], capture_output=True, text=True,
                       timeout=300, cwd=str(ROOT), env=env)
    assert p.returncode == 0, "exit %d\n%s%s" % (p.returncode, p.stdout, p.stderr)
    assert "other=[]" in p.stdout, p.stdout  # only ClosedError, never another failure
    ok = int(p.stdout.split("ok=")[1].split()[0])
    closed = int(p.stdout.split("closed=")[1].split()[0])
    assert ok >= 1 and closed == 1, p.stdout


def test_two_contexts_render_on_two_threads_at_once():
    files = [PEERS / "textured.gltf", PEERS / "spheres.gltf"]
    contexts = [mvr.Context(), mvr.Context(view_path="loop")]
    scenes = [mvr.Scene.load(f) for f in files]
    views = [mvr.Views.layout(s, "stereo", aspect=W / H) for s in scenes]
    try:
        alone = [colors(c, s, v) for c, s, v in zip(contexts, scenes, views)]
        start = threading.Barrier(2)
        results = [None, None]

        def run(k):
            start.wait(60)
            results[k] = [colors(contexts[k], scenes[k], views[k]) for _ in range(3)]

        threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(300)
        for k in range(2):
            assert all(np.mean(np.any(a != a[0, 0], axis=2)) > 0.05 for a in alone[k]), "context %d: empty" % k
            assert results[k] is not None, "thread %d failed (see its traceback above)" % k
            for rep in results[k]:
                for a, b in zip(alone[k], rep):
                    assert np.array_equal(a, b), "context %d: a render on its thread differs" % k
    finally:
        for o in views + scenes + contexts:
            o.close()


def test_use_after_close_raises():
    ctx = mvr.Context()
    with mvr.Scene.load(FILE) as scene, mvr.Views.layout(scene, "stereo") as views:
        ctx.close()
        ctx.close()  # twice is fine
        for call in (lambda: ctx.render(scene, views, (8, 8)), lambda: ctx.stats, lambda: ctx.caps,
                     lambda: ctx.provider):
            try:
                call()
            except mvr.ClosedError as e:
                assert "mvr.Context is closed" in str(e)
            else:
                raise AssertionError("a call on a closed Context returned")
