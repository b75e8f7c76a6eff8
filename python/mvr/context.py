"""The GL side: a context with its renderer, render targets and readback."""
import contextlib
import ctypes
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native as N
from ._common import (I32_MAX, U32_MAX, Error, Handle, PathArg, c_float, c_floats, c_int, c_path, check,
                      check_created, logger)
from .scene import Environment, Scene
from .views import Camera, Views

OUTPUTS = ("color", "depth", "distance", "normal", "ids", "coverage")

# One set of defaults: what `mvr render FILE` and mvr-viewer show a file with
# (apps/mvr/render_options.c, cli_scene.c cli_render_desc_defaults,
# cli_env.c); tests/python/test_defaults.py renders both and compares bytes.
DEFAULT_SIZE = (640, 480)
"""The layers' (width, height): `mvr render`'s --size."""
DEFAULT_CLEAR_COLOR = (0.02, 0.025, 0.035, 1.0)
"""Linear RGBA of uncovered pixels: `mvr render`'s opaque dark sky (--clear)."""
DEFAULT_ENVIRONMENT = "neutral"
"""The built-in neutral studio (--env): most glTF files ship without lights."""

EnvironmentArg = Union[Environment, str, None]
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

    color: Optional[np.ndarray]
    depth: Optional[np.ndarray]
    distance: Optional[np.ndarray]
    normal: Optional[np.ndarray]
    ids: Optional[np.ndarray]
    coverage: Optional[np.ndarray]

    def __init__(self, index: int, camera: Camera, arrays: Mapping[str, np.ndarray]) -> None:
        self.index = index
        self.camera = camera
        for name in OUTPUTS:
            setattr(self, name, arrays.get(name))

    def __getitem__(self, name: str) -> Optional[np.ndarray]:
        """The output by name (KeyError for a name not in OUTPUTS)."""
        if name not in OUTPUTS:
            raise KeyError(name)
        return getattr(self, name)

    def __repr__(self) -> str:
        got = ", ".join("%s %s %s" % (n, getattr(self, n).shape, getattr(self, n).dtype)
                        for n in OUTPUTS if getattr(self, n) is not None)
        return "RenderedView(%d: %s)" % (self.index, got)


class _RenderJob:
    """A render's checked arguments: what the GL gets (desc(), under the
    objects' locks: hold()) and what comes back; close() closes the views
    made for it (views=None)."""

    def __init__(self, scene: Scene, views: Views, own_views: bool, env: Optional[Environment], rd: Any,
                 exposure: "_ExposureChoice", width: int, height: int, samples: int, color_format: int,
                 outputs: Tuple[str, ...], extra: List[str], mask: int, color_float: bool) -> None:
        self.scene, self.views, self._own_views, self.environment = scene, views, own_views, env
        self._rd, self._exposure = rd, exposure
        self.width, self.height, self.samples, self.color_format = width, height, samples, color_format
        self.outputs, self.extra, self.mask, self.color_float = outputs, extra, mask, color_float

    def hold(self, stack: contextlib.ExitStack) -> None:
        """Takes the locks of what the render reads (scene, views,
        environment), in the one order every call takes them."""
        for obj in (self.scene, self.views, self.environment):
            if obj is not None:
                stack.enter_context(obj._lock)

    def desc(self) -> Any:
        """The mvr_render_desc with the environment and the exposure
        applied (hold() first)."""
        rd = self._rd
        if self.environment is not None:
            rd.environment = self.environment.handle
        self._exposure.apply(self.scene, rd)  # after the environment: it weighs in
        return rd

    def close(self) -> None:
        if self._own_views:
            self.views.close()


class _Target:
    def __init__(self, handle: int, key: Tuple[int, ...]) -> None:
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

    def __init__(self, provider: str = "default", *, api: str = "default", device_index: int = 0,
                 debug: bool = False, view_path: str = "auto", material_path: str = "auto", depth_mode: str = "auto",
                 transparency_order: str = "auto", skinning_path: str = "auto",
                 program_cache_dir: Optional[PathArg] = None, disable_culling: bool = False,
                 disable_instancing: bool = False) -> None:
        super().__init__()
        self._renderer: Optional[int] = None
        self._target: Optional[_Target] = None
        # environments named by a string ("neutral", "uniform"), made once:
        # the renderer keeps an environment's prefiltered maps while it is the same one
        self._environments: Dict[str, Environment] = {}
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
            self._release(self.handle)
        except BaseException:
            self.close()
            raise

    def _release(self, h: int) -> None:
        if N.C.mvr_context_release_current is None:  # a libmvr older than the call: stays current
            return
        check(N.C.mvr_context_release_current(h), lambda: N.text(N.C.mvr_context_last_error(h)),
              "mvr_context_release_current")

    @contextlib.contextmanager
    def _current(self) -> Iterator[int]:
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

    def close(self) -> None:
        """Destroys the target, the renderer and the context; waits for a
        call in flight on another thread. Closing twice is fine."""
        with self._lock:
            if self._depth:
                raise Error("mvr.Context.close() from inside a call on the same Context (a logging handler?)")
            super().close()

    def _destroy(self, handle: int) -> None:
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
        for env in self._environments.values():  # no GL in an environment
            env.close()
        self._environments.clear()

    def _renderer_error(self) -> str:
        return N.text(N.C.mvr_renderer_last_error(self._renderer))

    @property
    def caps(self) -> Dict[str, Any]:
        """What the GL offers: renderer, version, max_views (GL_MAX_VIEWS_OVR),
        multiview, software, and the whole mvr_caps as nested dicts."""
        with self._lock:
            return self._caps_locked()

    def _caps_locked(self) -> Dict[str, Any]:
        c = N.C.mvr_context_caps(self.handle).contents

        def as_dict(s: Any) -> Dict[str, Any]:
            d: Dict[str, Any] = {}
            for name in s.field_names():
                v = getattr(s, name)
                d[name] = as_dict(v) if isinstance(v, N.S) else N.text(v) if isinstance(v, bytes) else v
            return d

        d = as_dict(c)
        d.update(max_views=c.limits.max_views_ovr, multiview=bool(c.ext.ovr_multiview2),
                 software=bool(c.is_software))
        return d

    @property
    def provider(self) -> str:
        """The context provider that was made ("surfaceless", "device", ...)."""
        with self._lock:
            return N.text(N.C.mvr_context_provider_name(N.C.mvr_context_get_provider(self.handle)))

    def _target_for(self, width: int, height: int, layers: int, color_format: int, samples: int,
                    outputs_mask: int) -> int:
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
        handle = int(out.value or 0)  # a created target is never NULL
        self._target = _Target(handle, key)
        return handle

    def render(self, scene: Scene, views: Optional[Views] = None, size: Tuple[int, int] = DEFAULT_SIZE, *,
               outputs: Union[str, Sequence[str]] = ("color",), color_dtype: Any = "uint8",
               color_format: str = "default", samples: int = 0,
               clear_color: Sequence[float] = DEFAULT_CLEAR_COLOR, environment: EnvironmentArg = DEFAULT_ENVIRONMENT,
               background: str = "color", background_blur: float = 0.0, exposure: Optional[float] = None,
               exposure_mode: Optional[str] = None, tone_map: Optional[str] = None, ev100: Optional[float] = None,
               choose_exposure: Optional[bool] = None, shadows: str = "default", normal_space: str = "world",
               alpha_cutoff: float = 0.0) -> List[RenderedView]:
        """Renders every view of `views` (view i into layer i) at size =
        (width, height) and returns one RenderedView per view, each with
        the outputs asked for ("color", "depth", "distance", "normal",
        "ids", "coverage") and its camera.

        The defaults are `mvr render`'s for a file (docs/guide.md, Python,
        "Defaults"), so ctx.render(scene) gives its pixels: views None =
        Views.default(scene, size) (the file's first camera as a stereo
        pair, else the stereo framing), size 640 x 480, the neutral studio
        environment, the opaque dark sky DEFAULT_CLEAR_COLOR, the exposure
        and tone map mvr_render_desc_choose_exposure picks, no MSAA.

        color_dtype "uint8" reads the stored bytes, "float32" floats
        (normalized for 8-bit formats); color_format "default" (sRGB
        storage), "rgba8", "rgba16f" or "rgba32f" (linear); samples: MSAA
        samples per pixel: 0 the library's default anti-aliasing (4x MSAA,
        as mvr render; none with extra outputs), 1 none, or a power of two
        up to the GL's GL_MAX_SAMPLES. clear_color: linear RGB or RGBA
        (alpha 1) of what no geometry covers, a display colour (never
        exposed or tone mapped). environment: an mvr.Environment, "neutral" (the
        built-in studio), "uniform" (radiance 1 from everywhere), or None
        (no image-based lighting: the scene's own lights alone); background
        "color", "environment" or "blur" (background_blur: its roughness,
        0 = 0.5). Exposure: with none of exposure, exposure_mode and ev100
        given, the scene's choice (choose_exposure; False: linear, exposure
        1); exposure alone is a linear multiplier, ev100 alone an EV100;
        exposure_mode "linear", "ev100", "camera" or "auto"; tone_map
        "none", "aces" or "pbr_neutral" (default: the chosen one, or
        "pbr_neutral" for "auto" and "none" otherwise, as `mvr render`).
        choose_exposure=True chooses even with exposure options given
        (those still win). shadows: "default" (lights that cast them),
        "all", "off". normal_space: "world" or "camera"; alpha_cutoff: where
        blended surfaces start to count in depth / ids outputs (0 = 0.5)."""
        job = self._prepare(scene, views, size, outputs=outputs, color_dtype=color_dtype,
                            color_format=color_format, samples=samples, clear_color=clear_color,
                            environment=environment, background=background, background_blur=background_blur,
                            exposure=exposure, exposure_mode=exposure_mode, tone_map=tone_map, ev100=ev100,
                            choose_exposure=choose_exposure, shadows=shadows, normal_space=normal_space,
                            alpha_cutoff=alpha_cutoff)
        try:
            with contextlib.ExitStack() as held:
                # the context (current on this thread), then what the render
                # reads: one order everywhere, so two threads never wait on each other
                held.enter_context(self._current())
                job.hold(held)
                layers = len(job.views)
                if layers == 0:
                    raise Error("render: the view set has no views")
                rd = job.desc()
                target = self._target_for(job.width, job.height, layers, job.color_format, job.samples, job.mask)
                check(N.C.mvr_renderer_render(self._renderer, scene.handle, job.views.handle, target,
                                              ctypes.byref(rd)), self._renderer_error, "mvr_renderer_render")
                got = [self._read_view(target, job.views, layer, job.width, job.height, job.outputs, job.extra,
                                       job.color_float)
                       for layer in range(layers)]
        finally:
            job.close()
        return got

    def _prepare(self, scene: Scene, views: Optional[Views], size: Tuple[int, int], *,
                 outputs: Union[str, Sequence[str]], color_dtype: Any, color_format: str, samples: int,
                 clear_color: Sequence[float], environment: EnvironmentArg, background: str, background_blur: float,
                 exposure: Optional[float], exposure_mode: Optional[str], tone_map: Optional[str],
                 ev100: Optional[float], choose_exposure: Optional[bool], shadows: str, normal_space: str,
                 alpha_cutoff: float) -> "_RenderJob":
        """Every argument of a render checked, before the GL (and any
        allocation) sees it: a _RenderJob (close() it)."""
        self.handle  # noqa: B018 - raises once closed
        if not isinstance(scene, Scene):
            raise TypeError("scene: an mvr.Scene expected, got %s" % type(scene).__name__)
        if views is not None and not isinstance(views, Views):
            raise TypeError("views: an mvr.Views (or None: Views.default) expected, got %s" % type(views).__name__)
        # every argument checked before the GL (and any allocation) sees it
        try:
            width, height = size
        except (TypeError, ValueError):
            raise ValueError("size: (width, height) expected, got %r" % (size,)) from None
        width = c_int(width, "size: width", 1, U32_MAX)
        height = c_int(height, "size: height", 1, U32_MAX)
        samples = self._checked_samples(samples)
        color_format_value = N.COLOR_FORMAT(color_format, "color_format")
        outputs, extra = _checked_outputs(outputs)
        mask = 0
        for o in extra:
            mask |= 1 << N.OUTPUT(o)
        if color_dtype not in ("uint8", "float32", np.uint8, np.float32):
            raise ValueError("color_dtype: 'uint8' or 'float32', got %r" % (color_dtype,))
        color_float = np.dtype(color_dtype) == np.float32
        rd = self._render_desc(clear_color, background, background_blur, shadows, normal_space, alpha_cutoff,
                               environment)
        exposure_choice = _ExposureChoice(exposure, exposure_mode, tone_map, ev100, choose_exposure)
        env = self._environment(environment)
        used = Views.default(scene, (width, height)) if views is None else views
        return _RenderJob(scene, used, views is None, env, rd, exposure_choice, width, height,
                          samples, color_format_value, outputs, extra, mask, color_float)

    def _checked_samples(self, samples: Any) -> int:
        """0 (the default), 1 (none), or a power of two up to GL_MAX_SAMPLES: the GL
        would round another count up to one it has, silently."""
        n = c_int(samples, "samples", 0, U32_MAX)
        if n <= 1:
            return n
        with self._lock:
            most = N.C.mvr_context_caps(self.handle).contents.limits.max_samples
        if n & (n - 1) or n > most:
            counts = ", ".join(str(1 << k) for k in range(1, 31) if (1 << k) <= most)
            raise ValueError("samples: %d is not an MSAA count this GL has (0 = default, 1 = none, or %s)" %
                             (n, counts or "none: GL_MAX_SAMPLES is %d" % most))
        return n

    @staticmethod
    def _render_desc(clear_color: Sequence[float], background: str, background_blur: float, shadows: str,
                     normal_space: str, alpha_cutoff: float, environment: EnvironmentArg) -> Any:
        rd = N.desc(N.mvr_render_desc)
        rgba = c_floats(clear_color, (3, 4), "clear_color")
        rd.clear_color[:] = rgba + [1.0] * (4 - len(rgba))
        rd.background = N.BACKGROUND(background, "background")
        if rd.background != N.BACKGROUND("color") and environment is None:
            raise ValueError("background: %r needs an environment (environment is None)" % (background,))
        rd.background_blur = c_float(background_blur, "background_blur", 0.0, 1.0)
        rd.shadows.mode = N.SHADOW_MODE(shadows, "shadows")
        rd.normal_space = N.NORMAL_SPACE(normal_space, "normal_space")
        rd.output_alpha_cutoff = c_float(alpha_cutoff, "alpha_cutoff", 0.0, 1.0)
        return rd

    def _environment(self, environment: EnvironmentArg) -> Optional[Environment]:
        """An Environment for the render's argument: strings name the
        Context's own, made on first use and kept (prefiltered once)."""
        if environment is None or isinstance(environment, Environment):
            return environment
        if isinstance(environment, str) and environment.lower() in ("neutral", "uniform"):
            name = environment.lower()
            with self._lock:
                self.handle  # noqa: B018 - none made for a closed Context
                if name not in self._environments:
                    self._environments[name] = Environment(name)
                return self._environments[name]
        raise ValueError("environment: an mvr.Environment, 'neutral', 'uniform' or None expected, got %r" %
                         (environment,))

    def _read_view(self, target: int, views: Views, layer: int, width: int, height: int, outputs: Sequence[str],
                   extra: Sequence[str], color_float: bool) -> RenderedView:
        arrays: Dict[str, np.ndarray] = {}
        if "color" in outputs:
            arr = output_array("color", height, width, color_float)
            fmt = N.READBACK("rgba32f" if color_float else "rgba8")
            check(N.C.mvr_renderer_read_layer(self._renderer, target, layer, fmt, arr.ctypes.data, arr.nbytes),
                  self._renderer_error, "mvr_renderer_read_layer(%d)" % layer)
            arrays["color"] = arr
        for o in extra:
            arr = output_array(o, height, width, color_float)
            check(N.C.mvr_renderer_read_output(self._renderer, target, layer, N.OUTPUT(o), arr.ctypes.data,
                                               arr.nbytes), self._renderer_error,
                  "mvr_renderer_read_output(%d, %s)" % (layer, o))
            arrays[o] = arr
        # GL rows are bottom to top: image order is top to bottom
        arrays = {k: np.ascontiguousarray(v[::-1]) for k, v in arrays.items()}
        return RenderedView(layer, views.camera(layer, width, height), arrays)

    @property
    def stats(self) -> Dict[str, Any]:
        """The last render's mvr_frame_stats as a dict (paths that ran by name)."""
        s = N.out(N.mvr_frame_stats)
        with self._lock:
            self.handle  # noqa: B018 - raises once closed
            N.C.mvr_renderer_get_stats(self._renderer, ctypes.byref(s))
        d: Dict[str, Any] = {}
        for name in N.mvr_frame_stats.field_names():
            v = getattr(s, name)
            d[name] = list(v) if isinstance(v, ctypes.Array) else v
        d["view_path"] = N.VIEW_PATH.name(s.view_path)
        d["material_path"] = N.MATERIAL_PATH.name(s.material_path)
        d["depth_mode"] = N.DEPTH_MODE.name(s.depth_mode)
        return d


    def render_stream(self, scene: Scene, views: Optional[Views] = None, size: Tuple[int, int] = DEFAULT_SIZE, *,
                      chunk: int = 0, outputs: Union[str, Sequence[str]] = ("color",), color_dtype: Any = "uint8",
                      color_format: str = "default", samples: int = 0,
                      clear_color: Sequence[float] = DEFAULT_CLEAR_COLOR,
                      environment: EnvironmentArg = DEFAULT_ENVIRONMENT, background: str = "color",
                      background_blur: float = 0.0, exposure: Optional[float] = None,
                      exposure_mode: Optional[str] = None, tone_map: Optional[str] = None,
                      ev100: Optional[float] = None, choose_exposure: Optional[bool] = None,
                      shadows: str = "default", normal_space: str = "world",
                      alpha_cutoff: float = 0.0) -> Iterator[RenderedView]:
        """Renders every view of `views` as render() does, but yields the
        RenderedViews one by one, in view order, as their chunk comes back,
        instead of returning them all: memory stays flat in the number of
        views (the ring of two chunk targets and one chunk's arrays; what
        the caller keeps is the caller's). The arguments and defaults are
        render()'s; chunk: views per GL pass (0 = GL_MAX_VIEWS_OVR, fewer
        where a chunk's readback would pass 64 MiB). Every argument is
        checked here, before the first view is rendered. The pixels are
        render()'s, byte for byte, except a shared auto exposure (metered
        over every view first, then fixed, as `mvr render` does) and shadow
        cascades (fitted to each chunk's views). Between two views the
        Context is free for other calls (from this thread or another);
        closing the generator early (break) releases its GL objects."""
        from .stream import Stream
        chunk = c_int(chunk, "chunk", 0, 64)
        job = self._prepare(scene, views, size, outputs=outputs, color_dtype=color_dtype,
                            color_format=color_format, samples=samples, clear_color=clear_color,
                            environment=environment, background=background, background_blur=background_blur,
                            exposure=exposure, exposure_mode=exposure_mode, tone_map=tone_map, ev100=ev100,
                            choose_exposure=choose_exposure, shadows=shadows, normal_space=normal_space,
                            alpha_cutoff=alpha_cutoff)
        try:
            with job.views._lock:
                stream = Stream(self, job, chunk)
        except BaseException:
            job.close()
            raise
        return iter(stream)


def output_array(name: str, height: int, width: int, color_float: bool) -> np.ndarray:
    """An uninitialised array for one view's output as the library reads it
    back: colour (H, W, 4) uint8 or float32, the others in their own type
    (N.OUTPUT_PIXEL: (H, W) or (H, W, channels))."""
    if name == "color":
        return np.empty((height, width, 4), np.float32 if color_float else np.uint8)
    channels, dtype = N.OUTPUT_PIXEL[name]
    return np.empty((height, width, channels) if channels > 1 else (height, width), dtype)


def _checked_outputs(outputs: Union[str, Sequence[str]]) -> Tuple[Tuple[str, ...], List[str]]:
    """The output names asked for (each known, none twice) and those other than colour."""
    if isinstance(outputs, str):
        outputs = (outputs,)
    try:
        names = tuple(outputs)
    except TypeError:
        raise ValueError("outputs: a sequence of %s expected, got %r" % (", ".join(OUTPUTS), outputs)) from None
    for o in names:
        if not isinstance(o, str) or o not in OUTPUTS:
            raise ValueError("outputs: %r is not one of %s" % (o, ", ".join(OUTPUTS)))
        if names.count(o) > 1:
            raise ValueError("outputs: %r is asked for twice" % (o,))
    return names, [o for o in names if o != "color"]


class _ExposureChoice:
    """render()'s exposure arguments, checked, applied to a render desc as
    `mvr render` applies its options: the scene's choice
    (mvr_render_desc_choose_exposure) unless one is given; a given mode
    without a tone map gets PBR Neutral for "auto", none otherwise."""

    def __init__(self, exposure: Optional[float], mode: Optional[str], tone_map: Optional[str],
                 ev100: Optional[float], choose: Optional[bool]) -> None:
        self.exposure = 1.0 if exposure is None else c_float(exposure, "exposure", 0.0, lo_open=True)
        self.ev100 = None if ev100 is None else c_float(ev100, "ev100")
        self.mode = None if mode is None else N.EXPOSURE_MODE(mode, "exposure_mode")
        if self.mode is None and self.ev100 is not None:
            self.mode = N.EXPOSURE_MODE("ev100")
        elif self.mode is None and exposure is not None:
            self.mode = N.EXPOSURE_MODE("linear")
        self.tone_map = None if tone_map is None else N.TONE_MAP(tone_map, "tone_map")
        self.choose = self.mode is None if choose is None else bool(choose)

    def apply(self, scene: Scene, rd: Any) -> None:
        rd.exposure = self.exposure
        rd.ev100 = self.ev100 or 0.0
        if self.choose:
            N.C.mvr_render_desc_choose_exposure(scene.handle, ctypes.byref(rd))
        else:
            rd.exposure_mode = N.EXPOSURE_MODE("linear")
            rd.tone_map = N.TONE_MAP("none")
        if self.mode is not None:
            rd.exposure_mode = self.mode
            if not self.choose:
                auto = self.mode == N.EXPOSURE_MODE("auto")
                rd.tone_map = N.TONE_MAP("pbr_neutral" if auto else "none")
        if self.tone_map is not None:
            rd.tone_map = self.tone_map
