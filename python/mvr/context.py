"""The GL side: a context with its renderer, render targets and readback."""
import contextlib
import ctypes

import numpy as np

from . import _native as N
from ._common import I32_MAX, U32_MAX, Error, Handle, c_int, c_path, check, check_created, logger

OUTPUTS = ("color", "depth", "distance", "normal", "ids", "coverage")


class RenderedView:
    """One view of a render: numpy arrays, rows top to bottom (image order:
    row 0 is the top of the picture; GL's own readback order is the
    reverse), and the view's Camera.

    color    (H, W, 4) uint8 (the stored bytes: sRGB-encoded for the
             default target) or float32 (color_dtype="float32")
    depth    (H, W) float32: view-space depth along the camera's axis, 0 where nothing
    distance (H, W) float32: distance from the camera centre, 0 where nothing
    normal   (H, W, 3) float32: unit normals (world or camera space), 0 where nothing
    ids      (H, W, 4) uint32: node, mesh, material, primitive ids, 0 where nothing
    coverage (H, W) float32: 1 where a surface was recorded
    Outputs not asked for are None."""

    def __init__(self, index, camera, arrays):
        self.index = index
        self.camera = camera
        for name in OUTPUTS:
            setattr(self, name, arrays.get(name))

    def __getitem__(self, name):
        if name not in OUTPUTS:
            raise KeyError(name)
        return getattr(self, name)

    def __repr__(self):
        got = ", ".join("%s %s %s" % (n, getattr(self, n).shape, getattr(self, n).dtype)
                        for n in OUTPUTS if getattr(self, n) is not None)
        return "RenderedView(%d: %s)" % (self.index, got)


class _RenderJob:
    """A render's checked arguments: what the GL gets (desc(), under the
    objects' locks: hold()) and what comes back."""

    def __init__(self, scene, views, environment, rd, choose_exposure, exposure_mode, tone_map, width, height,
                 samples, color_format, outputs, extra, mask, color_float):
        self.scene, self.views, self.environment = scene, views, environment
        self._rd, self._choose, self._exposure_mode, self._tone_map = rd, choose_exposure, exposure_mode, tone_map
        self.width, self.height, self.samples, self.color_format = width, height, samples, color_format
        self.outputs, self.extra, self.mask, self.color_float = outputs, extra, mask, color_float

    def hold(self, stack):
        """Takes the locks of what the render reads (scene, views,
        environment), in the one order every call takes them."""
        for obj in (self.scene, self.views, self.environment):
            if obj is not None:
                stack.enter_context(obj._lock)

    def desc(self):
        """The mvr_render_desc, with the environment's handle and the
        exposure chosen for the scene (hold() first)."""
        rd = self._rd
        if self.environment is not None:
            rd.environment = self.environment.handle
        if self._choose:
            N.C.mvr_render_desc_choose_exposure(self.scene.handle, ctypes.byref(rd))
        if self._exposure_mode is not None:
            rd.exposure_mode = self._exposure_mode
        if self._tone_map is not None:
            rd.tone_map = self._tone_map
        return rd


class _Target:
    def __init__(self, handle, key):
        self.handle, self.key = handle, key


class Context(Handle):
    """A GL context (mvr_context) with one renderer (mvr_renderer).

    provider: "default" (EGL surfaceless, then device, then pbuffer),
    "surfaceless", "device", "pbuffer" or "osmesa"; api: "default", "gles",
    "desktop". The renderer's options: view_path ("auto", "multiview",
    "loop"), material_path, depth_mode, transparency_order, skinning_path,
    program_cache_dir (a folder for program binaries), disable_culling,
    disable_instancing. close() (or the end of a `with` block) destroys the
    targets, the renderer and the context, releasing their GL objects.

    Threads: a Context renders from any thread, one call at a time. Every
    call that touches it holds the Context's lock, makes the GL context
    current on the calling thread and releases it before returning (an EGL
    context is current on one thread at most), so the next call may come
    from another thread; calls from several threads wait for each other.
    Calls leave no GL context current on the calling thread. close() takes
    the lock too: it waits for a render in flight on another thread, and
    any call after it raises mvr.ClosedError. Two Contexts render on two
    threads at the same time; a Scene, Views or Environment is used by one
    call at a time (each has its own lock)."""

    _what = "mvr.Context"

    def __init__(self, provider="default", *, api="default", device_index=0, debug=False, view_path="auto",
                 material_path="auto", depth_mode="auto", transparency_order="auto", skinning_path="auto",
                 program_cache_dir=None, disable_culling=False, disable_instancing=False):
        super().__init__()
        self._renderer = None
        self._target = None
        self._depth = 0  # nesting of _current() on the thread holding the lock
        self._logger = logger()
        d = N.desc(N.mvr_context_desc)
        d.provider = N.PROVIDER(provider, "provider")
        d.api = N.GL_API(api, "api")
        d.device_index = c_int(device_index, "device_index", 0, I32_MAX)
        cache_dir = c_path(program_cache_dir if program_cache_dir else None, "program_cache_dir")
        d.debug = bool(debug)
        d.logger = self._logger
        out = ctypes.c_void_p()
        err = N.mvr_error()
        check_created(N.C.mvr_context_create(ctypes.byref(d), ctypes.byref(out), ctypes.byref(err)), err,
                      "mvr_context_create")
        self._handle = out.value
        try:
            rd = N.desc(N.mvr_renderer_desc)
            rd.context = self._handle
            rd.logger = self._logger
            rd.view_path = N.VIEW_PATH(view_path, "view_path")
            rd.material_path = N.MATERIAL_PATH(material_path, "material_path")
            rd.depth_mode = N.DEPTH_MODE(depth_mode, "depth_mode")
            rd.transparency_order = N.TRANSPARENCY(transparency_order, "transparency_order")
            rd.skinning_path = N.SKINNING_PATH(skinning_path, "skinning_path")
            self._cache_dir = cache_dir
            rd.program_cache_dir = self._cache_dir
            rd.disable_culling = bool(disable_culling)
            rd.disable_instancing = bool(disable_instancing)
            r = ctypes.c_void_p()
            check_created(N.C.mvr_renderer_create(ctypes.byref(rd), ctypes.byref(r), ctypes.byref(err)), err,
                          "mvr_renderer_create")
            self._renderer = r.value
            # mvr_context_create left it current here: free for any thread
            self._release(self._handle)
        except BaseException:
            self.close()
            raise

    def _release(self, h):
        if N.C.mvr_context_release_current is None:  # a libmvr older than the call: stays current
            return
        check(N.C.mvr_context_release_current(h), lambda: N.text(N.C.mvr_context_last_error(h)),
              "mvr_context_release_current")

    @contextlib.contextmanager
    def _current(self):
        """Holds the lock with the GL context current on this thread; releases
        the GL context when the outermost such block ends."""
        with self._lock:
            h = self.handle  # ClosedError once closed
            if self._depth == 0:
                check(N.C.mvr_context_make_current(h), lambda: N.text(N.C.mvr_context_last_error(h)),
                      "mvr_context_make_current")
            self._depth += 1
            try:
                yield h
            except BaseException:
                self._depth -= 1
                if self._depth == 0:
                    with contextlib.suppress(Error):  # the call's own error says more
                        self._release(h)
                raise
            self._depth -= 1
            if self._depth == 0:
                self._release(h)

    def close(self):
        """Destroys the target, the renderer and the context; waits for a
        call in flight on another thread. Closing twice is fine."""
        with self._lock:
            if self._depth:
                raise Error("mvr.Context.close() from inside a call on the same Context (a logging handler?)")
            super().close()

    def _destroy(self, handle):
        # targets, then the renderer, then the context, with the context
        # current here: each GL object is deleted while its context is
        # current (the library would also accept any order); destroying
        # the context releases it
        N.C.mvr_context_make_current(handle)
        if self._target is not None:
            N.C.mvr_target_destroy(self._target.handle)
            self._target = None
        if self._renderer is not None:
            N.C.mvr_renderer_destroy(self._renderer)
            self._renderer = None
        N.C.mvr_context_destroy(handle)

    def _renderer_error(self):
        return N.text(N.C.mvr_renderer_last_error(self._renderer))

    @property
    def caps(self):
        """What the GL offers: renderer, version, max_views (GL_MAX_VIEWS_OVR),
        multiview, software, and the whole mvr_caps as nested dicts."""
        with self._lock:
            return self._caps_locked()

    def _caps_locked(self):
        c = N.C.mvr_context_caps(self.handle).contents

        def as_dict(s):
            d = {}
            for name in s.field_names():
                v = getattr(s, name)
                d[name] = as_dict(v) if isinstance(v, N.S) else N.text(v) if isinstance(v, bytes) else v
            return d

        d = as_dict(c)
        d.update(max_views=c.limits.max_views_ovr, multiview=bool(c.ext.ovr_multiview2),
                 software=bool(c.is_software))
        return d

    @property
    def provider(self):
        with self._lock:
            return N.text(N.C.mvr_context_provider_name(N.C.mvr_context_get_provider(self.handle)))

    def _target_for(self, width, height, layers, color_format, samples, outputs_mask):
        key = (width, height, layers, color_format, samples, outputs_mask)
        if self._target is not None and self._target.key == key:
            return self._target.handle
        if self._target is not None:
            N.C.mvr_target_destroy(self._target.handle)
            self._target = None
        td = N.desc(N.mvr_target_desc)
        td.width, td.height, td.layers = width, height, layers
        td.color_format = color_format
        td.samples = samples
        td.outputs = outputs_mask
        out = ctypes.c_void_p()
        check(N.C.mvr_target_create(self._renderer, ctypes.byref(td), ctypes.byref(out)), self._renderer_error,
              "mvr_target_create")
        self._target = _Target(out.value, key)
        return out.value

    def render(self, scene, views, size, *, outputs=("color",), color_dtype="uint8", color_format="default",
               samples=0, clear_color=(0, 0, 0, 0), environment=None, background="color", background_blur=0.0,
               exposure=1.0, exposure_mode=None, tone_map=None, ev100=0.0, choose_exposure=False,
               shadows="default", normal_space="world", alpha_cutoff=0.0):
        """Renders every view of `views` (view i into layer i) at size =
        (width, height) and returns one RenderedView per view, each with
        the outputs asked for ("color", "depth", "distance", "normal",
        "ids", "coverage") and its camera.

        color_dtype "uint8" reads the stored bytes, "float32" floats
        (normalized for 8-bit formats); color_format "default" (sRGB
        storage), "rgba8", "rgba16f" or "rgba32f" (linear); samples: MSAA
        samples per pixel (0 = none). clear_color: linear RGBA of what no
        geometry covers (or background "environment" / "blur" with an
        mvr.Environment). exposure: the linear multiplier; exposure_mode
        ("linear", "ev100", "camera", "auto") and tone_map ("none", "aces",
        "pbr_neutral"); choose_exposure=True picks both as `mvr render`
        does for the scene (mvr_render_desc_choose_exposure; an explicit
        exposure_mode or tone_map still wins). shadows: "default" (lights
        that cast them), "all", "off". normal_space: "world" or "camera";
        alpha_cutoff: where blended surfaces start to count in depth / ids
        outputs (0 = 0.5)."""
        job = self._prepare(scene, views, size, outputs=outputs, color_dtype=color_dtype,
                            color_format=color_format, samples=samples, clear_color=clear_color,
                            environment=environment, background=background, background_blur=background_blur,
                            exposure=exposure, exposure_mode=exposure_mode, tone_map=tone_map, ev100=ev100,
                            choose_exposure=choose_exposure, shadows=shadows, normal_space=normal_space,
                            alpha_cutoff=alpha_cutoff)
        with contextlib.ExitStack() as held:
            # the context (current on this thread), then what the render
            # reads: one order everywhere, so two threads never wait on each other
            held.enter_context(self._current())
            job.hold(held)
            layers = len(views)
            if layers == 0:
                raise Error("render: the view set has no views")
            rd = job.desc()
            target = self._target_for(job.width, job.height, layers, job.color_format, job.samples, job.mask)
            check(N.C.mvr_renderer_render(self._renderer, scene.handle, views.handle, target, ctypes.byref(rd)),
                  self._renderer_error, "mvr_renderer_render")
            return [self._read_view(target, views, layer, job.width, job.height, job.outputs, job.extra,
                                    job.color_float)
                    for layer in range(layers)]

    def _prepare(self, scene, views, size, *, outputs, color_dtype, color_format, samples, clear_color, environment,
                 background, background_blur, exposure, exposure_mode, tone_map, ev100, choose_exposure, shadows,
                 normal_space, alpha_cutoff):
        """Every argument of a render checked, before the GL (and any
        allocation) sees it: a _RenderJob."""
        self.handle  # noqa: B018 - raises once closed
        try:
            width, height = size
        except (TypeError, ValueError):
            raise ValueError("size: (width, height) expected, got %r" % (size,)) from None
        width = c_int(width, "size: width", 1, U32_MAX)
        height = c_int(height, "size: height", 1, U32_MAX)
        samples = c_int(samples, "samples", 0, U32_MAX)
        color_format = N.COLOR_FORMAT(color_format, "color_format")
        if isinstance(outputs, str):
            outputs = (outputs,)
        outputs = tuple(outputs)
        for o in outputs:
            if o not in OUTPUTS:
                raise ValueError("outputs: %r is not one of %s" % (o, ", ".join(OUTPUTS)))
        extra = [o for o in outputs if o != "color"]
        mask = 0
        for o in extra:
            mask |= 1 << N.OUTPUT(o)
        if color_dtype not in ("uint8", "float32", np.uint8, np.float32):
            raise ValueError("color_dtype: 'uint8' or 'float32', got %r" % (color_dtype,))
        color_float = np.dtype(color_dtype) == np.float32

        rd = N.desc(N.mvr_render_desc)
        rd.clear_color[:] = [float(c) for c in clear_color]
        rd.exposure = float(exposure)
        rd.ev100 = float(ev100)
        rd.background = N.BACKGROUND(background, "background")
        rd.background_blur = float(background_blur)
        rd.shadows.mode = N.SHADOW_MODE(shadows, "shadows")
        exposure_mode = None if exposure_mode is None else N.EXPOSURE_MODE(exposure_mode, "exposure_mode")
        tone_map = None if tone_map is None else N.TONE_MAP(tone_map, "tone_map")
        rd.normal_space = N.NORMAL_SPACE(normal_space, "normal_space")
        rd.output_alpha_cutoff = float(alpha_cutoff)
        return _RenderJob(scene, views, environment, rd, choose_exposure, exposure_mode, tone_map, width, height,
                          samples, color_format, outputs, extra, mask, color_float)

    def _read_view(self, target, views, layer, width, height, outputs, extra, color_float):
        arrays = {}
        if "color" in outputs:
            arr = np.empty((height, width, 4), np.float32 if color_float else np.uint8)
            fmt = N.READBACK("rgba32f" if color_float else "rgba8")
            check(N.C.mvr_renderer_read_layer(self._renderer, target, layer, fmt, arr.ctypes.data, arr.nbytes),
                  self._renderer_error, "mvr_renderer_read_layer(%d)" % layer)
            arrays["color"] = arr
        for o in extra:
            channels, dtype = N.OUTPUT_PIXEL[o]
            shape = (height, width, channels) if channels > 1 else (height, width)
            arr = np.empty(shape, dtype)
            check(N.C.mvr_renderer_read_output(self._renderer, target, layer, N.OUTPUT(o), arr.ctypes.data,
                                               arr.nbytes), self._renderer_error,
                  "mvr_renderer_read_output(%d, %s)" % (layer, o))
            arrays[o] = arr
        # GL rows are bottom to top: image order is top to bottom
        arrays = {k: np.ascontiguousarray(v[::-1]) for k, v in arrays.items()}
        return RenderedView(layer, views.camera(layer, width, height), arrays)

    @property
    def stats(self):
        """The last render's mvr_frame_stats as a dict (paths that ran by name)."""
        s = N.out(N.mvr_frame_stats)
        with self._lock:
            self.handle  # noqa: B018 - raises once closed
            N.C.mvr_renderer_get_stats(self._renderer, ctypes.byref(s))
        d = {}
        for name in N.mvr_frame_stats.field_names():
            v = getattr(s, name)
            d[name] = list(v) if isinstance(v, ctypes.Array) else v
        d["view_path"] = N.VIEW_PATH.name(s.view_path)
        d["material_path"] = N.MATERIAL_PATH.name(s.material_path)
        d["depth_mode"] = N.DEPTH_MODE.name(s.depth_mode)
        return d

    def render_stream(self, scene, views, size, *, chunk=0, outputs=("color",), color_dtype="uint8",
                      color_format="default", samples=0, clear_color=(0, 0, 0, 0), environment=None,
                      background="color", background_blur=0.0, exposure=1.0, exposure_mode=None, tone_map=None,
                      ev100=0.0, choose_exposure=False, shadows="default", normal_space="world", alpha_cutoff=0.0):
        """Renders every view of `views` as render() does, but yields the
        RenderedViews one by one, in view order, as their chunk comes back,
        instead of returning them all: memory stays flat in the number of
        views (the ring of two chunk targets and one chunk's arrays; what
        the caller keeps is the caller's). The arguments are render()'s;
        chunk: views per GL pass (0 = GL_MAX_VIEWS_OVR, fewer where a
        chunk's readback would pass 64 MiB). Every argument is checked
        here, before the first view is rendered. The pixels are render()'s,
        byte for byte, except a shared auto exposure (metered over every
        view first, then fixed, as `mvr render` does) and shadow cascades
        (fitted to each chunk's views). Between two views the Context is
        free for other calls (from this thread or another); closing the
        generator early (break) releases its GL objects."""
        from .stream import Stream
        job = self._prepare(scene, views, size, outputs=outputs, color_dtype=color_dtype,
                            color_format=color_format, samples=samples, clear_color=clear_color,
                            environment=environment, background=background, background_blur=background_blur,
                            exposure=exposure, exposure_mode=exposure_mode, tone_map=tone_map, ev100=ev100,
                            choose_exposure=choose_exposure, shadows=shadows, normal_space=normal_space,
                            alpha_cutoff=alpha_cutoff)
        chunk = c_int(chunk, "chunk", 0, 64)
        with views._lock:
            stream = Stream(self, job, chunk)
        return iter(stream)
