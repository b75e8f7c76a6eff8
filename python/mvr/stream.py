"""Context.render_stream: any number of views in bounded memory.

The views go to the GL in chunks (one multiview pass each: at most
GL_MAX_VIEWS_OVR views, never across the library's 64-view blocks), each
into one target of a ring of two, and come back through the library's
asynchronous readback (mvr_readback: a pixel buffer object and a fence per
output), as `mvr render` streams them (apps/mvr/render_stream.c): chunk k+1
is rendered while chunk k's pixels are copied, and chunk k's views are
handed to the caller when its ring target comes round again. What is held
at any time: the ring's two targets and their readback buffers (GL memory:
2 x chunk x the bytes of a view's outputs) and the numpy arrays of the one
chunk being handed out, whatever the number of views; views the caller
keeps are the caller's.

The pixels are render()'s for the same arguments, byte for byte (each chunk
is rendered with the whole set's origin, as in a render of every view),
except where a render of every view at once shares something across views:
a shared auto exposure is metered over every view first (small, chunk by
chunk) and then fixed, as `mvr render` does; shadow cascades fitted to all
views are fitted to each chunk's views instead.
"""
import contextlib
import ctypes

import numpy as np

from . import _native as N
from ._common import Error, check

VIEW_BLOCK = 64               # the library's view blocks (MVR_VIEWS_PER_BLOCK)
RING = 2                      # chunks in flight
SLOT_BUDGET = 64 << 20        # bytes of one chunk's readback before the chunk shrinks
METER_SIZE = 128              # auto-exposure metering: layers at most this on their long side

class _Slot:
    """One ring target with a readback per output, and the chunk it holds."""

    def __init__(self):
        self.target = None
        self.readbacks = []   # per view of the chunk: {output name: mvr_readback}
        self.busy = False
        self.base = self.count = 0


def chunk_size(max_views, views, view_bytes):
    """Views per chunk: one multiview pass (GL_MAX_VIEWS_OVR, at most the
    library's 64-view block), fewer where a chunk's readback would pass
    SLOT_BUDGET (two are in flight)."""
    chunk = max(1, min(max_views, VIEW_BLOCK, views))
    while chunk > 1 and view_bytes * chunk > SLOT_BUDGET:
        chunk -= 1
    return chunk


def chunks(views, chunk):
    """(base, count) of every chunk: never across a 64-view block."""
    base = 0
    while base < views:
        count = min(chunk, views - base, VIEW_BLOCK - base % VIEW_BLOCK)
        yield base, count
        base += count


class Stream:
    """The generator behind Context.render_stream (see there)."""

    def __init__(self, ctx, job, chunk):
        self.ctx, self.job = ctx, job
        self.views = len(job.views)
        if self.views == 0:
            raise Error("render_stream: the view set has no views")
        w, h = job.width, job.height
        self.read_format = N.READBACK("rgba32f" if job.color_float else "rgba8")
        self.color_bytes = w * h * (16 if job.color_float else 4)
        view_bytes = (self.color_bytes if "color" in job.outputs else 0) + sum(
            w * h * N.C.mvr_output_pixel_size(N.OUTPUT(o)) for o in job.extra)
        with ctx._lock:
            max_views = ctx._caps_locked()["max_views"]
        self.chunk = chunk or chunk_size(max_views, self.views, view_bytes)
        self.slots = []
        self.meter = None

    # ---------------------------------------------------------------- GL objects

    def _make_slots(self, n):
        r = self.ctx._renderer
        for _ in range(n):
            slot = _Slot()
            self.slots.append(slot)
            td = N.desc(N.mvr_target_desc)
            td.width, td.height, td.layers = self.job.width, self.job.height, self.chunk
            td.color_format, td.samples, td.outputs = self.job.color_format, self.job.samples, self.job.mask
            out = ctypes.c_void_p()
            check(N.C.mvr_target_create(r, ctypes.byref(td), ctypes.byref(out)), self.ctx._renderer_error,
                  "mvr_target_create")
            slot.target = out.value
            # one readback per view and output: each view's pixels are
            # copied straight into its own arrays (no chunk-sized buffer)
            for _ in range(self.chunk):
                per_view = {}
                slot.readbacks.append(per_view)
                for name in self.job.outputs:
                    rb = ctypes.c_void_p()
                    check(N.C.mvr_readback_create(r, ctypes.byref(rb)), self.ctx._renderer_error,
                          "mvr_readback_create")
                    per_view[name] = rb.value

    def _release(self):
        for slot in self.slots:
            for per_view in slot.readbacks:
                for rb in per_view.values():
                    N.C.mvr_readback_destroy(rb)
            N.C.mvr_target_destroy(slot.target)
        self.slots = []
        if self.meter is not None:
            N.C.mvr_target_destroy(self.meter)
            self.meter = None

    def _part(self, base, count):
        """Views [base, base + count) with the whole set's origin: they
        render as in a render of every view."""
        vh = self.job.views.handle
        part = (N.mvr_view_desc * count)()
        for k in range(count):
            check(N.C.mvr_view_set_get_view(vh, base + k, ctypes.byref(part[k])), lambda: N.text(N.C.mvr_view_set_last_error(vh)),
                  "mvr_view_setN.C.mvr_view_set_get_view(%d)" % (base + k))
        d = N.desc(N.mvr_view_set_desc)
        d.view_count, d.views, d.origin_set = count, part, True
        check(N.C.mvr_view_set_get_origin(vh, d.origin), lambda: N.text(N.C.mvr_view_set_last_error(vh)), "mvr_view_set_get_origin")
        out, err = ctypes.c_void_p(), N.mvr_error()
        check(N.C.mvr_view_set_create(ctypes.byref(d), ctypes.byref(out), ctypes.byref(err)),
              lambda: N.text(err.message), "views %d .. %d" % (base, base + count - 1))
        return out.value

    def _render(self, rd, target, base, count):
        part = self._part(base, count)
        try:
            check(N.C.mvr_renderer_render(self.ctx._renderer, self.job.scene.handle, part, target, ctypes.byref(rd)),
                  self.ctx._renderer_error, "mvr_renderer_render (views %d .. %d)" % (base, base + count - 1))
        finally:
            N.C.mvr_view_set_destroy(part)

    # ---------------------------------------------------------------- exposure

    def _metered(self, rd):
        """A shared auto exposure over chunks: every view rendered small,
        its log2 luminance pooled as one render pools them
        (mvr_frame_stats.exposure_log2_luminance), then one fixed EV100."""
        w, h = self.job.width, self.job.height
        longest = max(w, h)
        if longest > METER_SIZE:
            w, h = max(1, w * METER_SIZE // longest), max(1, h * METER_SIZE // longest)
        td = N.desc(N.mvr_target_desc)
        td.width, td.height, td.layers = w, h, self.chunk
        out = ctypes.c_void_p()
        check(N.C.mvr_target_create(self.ctx._renderer, ctypes.byref(td), ctypes.byref(out)),
              self.ctx._renderer_error, "the exposure metering target")
        self.meter = out.value
        total, measured, first_ev = 0.0, 0, None
        st = N.out(N.mvr_frame_stats)
        for base, count in chunks(self.views, self.chunk):
            self._render(rd, self.meter, base, count)
            N.C.mvr_renderer_get_stats(self.ctx._renderer, ctypes.byref(st))
            if first_ev is None:
                first_ev = st.exposure_ev100
            total += st.exposure_log2_luminance * st.exposure_measured_views
            measured += st.exposure_measured_views
        N.C.mvr_target_destroy(self.meter)
        self.meter = None
        if measured == 0:
            return first_ev  # nothing lit anywhere: the renderer's own answer
        key = rd.exposure_key if rd.exposure_key > 0 else 0.18
        lo, hi = (rd.ev100_min, rd.ev100_max) if (rd.ev100_min, rd.ev100_max) != (0.0, 0.0) else (-8.0, 24.0)
        ev = total / measured - np.log2(1.2 * key) - rd.exposure_compensation
        return min(max(ev, lo), hi)

    # ---------------------------------------------------------------- the ring

    def _begin(self, slot, base, count):
        r = self.ctx._renderer
        for k in range(count):
            for name, rb in slot.readbacks[k].items():
                d = N.desc(N.mvr_read_desc)
                d.first_layer, d.layer_count, d.format, d.output = k, 1, self.read_format, N.OUTPUT(name)
                check(N.C.mvr_renderer_begin_read(r, slot.target, ctypes.byref(d), rb), self.ctx._renderer_error,
                      "reading view %d (%s)" % (base + k, name))
        slot.busy, slot.base, slot.count = True, base, count

    def _harvest(self, slot):
        """The slot's chunk as RenderedViews (its reads waited for)."""
        from .context import RenderedView, output_array
        job, r = self.job, self.ctx._renderer
        h, w = job.height, job.width
        out = []
        for k in range(slot.count):
            index = slot.base + k
            arrays = {}
            for name, rb in slot.readbacks[k].items():
                arr = output_array(name, h, w, job.color_float)
                check(N.C.mvr_renderer_finish_read(r, rb, arr.ctypes.data, arr.nbytes), self.ctx._renderer_error,
                      "reading view %d (%s)" % (index, name))
                # GL rows are bottom to top: image order is top to bottom
                # (numpy copies the overlapping rows through a temporary)
                arr[:] = arr[::-1]
                arrays[name] = arr
            out.append(RenderedView(index, job.views.camera(index, w, h), arrays))
        slot.busy = False
        return out

    def _step(self, state):
        """Renders chunks until one comes back; its views (None at the end)."""
        with contextlib.ExitStack() as held:
            held.enter_context(self.ctx._current())
            self.job.hold(held)
            if state["rd"] is None:
                rd = self.job.desc()
                if rd.exposure_mode == N.EXPOSURE_MODE("auto") and not rd.exposure_per_view and \
                        self.views > self.chunk:
                    ev = self._metered(rd)
                    rd.exposure_mode = N.EXPOSURE_MODE("ev100")
                    rd.ev100 = ev + rd.exposure_compensation  # the renderer's EV100 has it already
                state["rd"] = rd
                plan = list(chunks(self.views, self.chunk))
                self._make_slots(min(RING, len(plan)))
                state["plan"], state["next"], state["serial"] = plan, 0, 0
            plan = state["plan"]
            while state["next"] < len(plan):
                slot = self.slots[state["serial"] % len(self.slots)]
                if slot.busy:
                    return self._harvest(slot)  # its target comes round again: read it out first
                base, count = plan[state["next"]]
                self._render(state["rd"], slot.target, base, count)
                self._begin(slot, base, count)
                state["next"] += 1
                state["serial"] += 1
            # everything rendered: what is in flight, oldest first
            for k in range(len(self.slots)):
                slot = self.slots[(state["serial"] + k) % len(self.slots)]
                if slot.busy:
                    return self._harvest(slot)
            return None

    def __iter__(self):
        state = {"rd": None}
        try:
            while True:
                views = self._step(state)
                if views is None:
                    return
                # handed out without the locks: the caller may render meanwhile
                yield from views
        finally:
            self._close()

    def _close(self):
        self.job.close()  # the views made for it (views=None)
        if not self.slots and self.meter is None:
            return
        with self.ctx._lock:
            if self.ctx._handle is None:  # closed: its renderer released the GL objects
                self._release()
                return
            with self.ctx._current():
                self._release()
