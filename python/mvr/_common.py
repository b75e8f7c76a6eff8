"""Errors, logging, handle bookkeeping and argument checks shared by the mvr
classes."""
import ctypes
import functools
import logging
import numbers
import operator
import os
import threading

from . import _native as N

log = logging.getLogger("mvr")


class Error(RuntimeError):
    """A failed mvr call: `message` is mvr's own, `result` its mvr_result name
    (e.g. "MVR_ERROR_IO"); str() gives both."""

    def __init__(self, message, result="MVR_ERROR_INVALID_ARGUMENT"):
        self.message = message
        self.result = result
        super().__init__("%s (%s)" % (message, result) if result else message)


class ClosedError(Error):
    """Use of an mvr object after close() (or after its `with` block)."""

    def __init__(self, what):
        super().__init__("%s is closed" % what, None)


def check(result, message_fn, what):
    """Raises Error for a failed result; message_fn() gives the object's message."""
    if result == 0:
        return
    message = message_fn() if message_fn else ""
    raise Error(message or "%s failed" % what, N.result_name(result))


def check_created(result, err, what):
    if result == 0:
        return
    message = N.text(err.message) if err is not None else ""
    raise Error(message or "%s failed" % what, N.result_name(result))


# mvr log levels -> Python's logging
_LEVELS = {1: logging.ERROR, 2: logging.WARNING, 3: logging.INFO, 4: logging.DEBUG}


_ERROR_RESULT = N.LOG_ID("error_result")


def _forward(level, msg_id, message, user_data):
    # a failed call's own message becomes the mvr.Error it raises: logged
    # again at ERROR it would print twice (logging's last-resort handler)
    py_level = logging.DEBUG if msg_id == _ERROR_RESULT else _LEVELS.get(level, logging.INFO)
    log.log(py_level, "%s", N.text(message))


# one callback for the whole process: ctypes keeps it alive as long as the module
_LOG_CALLBACK = N.LOG_FN(_forward)


def logger():
    """An mvr_logger that forwards to logging.getLogger("mvr"), passing on
    what that logger would show at the time of the call."""
    lg = N.mvr_logger()
    lg.fn = _LOG_CALLBACK
    level = log.getEffectiveLevel()
    lg.level = 4 if level <= logging.DEBUG else 3 if level <= logging.INFO else 2 if level <= logging.WARNING else 1
    return lg


class Handle:
    """Owns one mvr object: close() destroys it once; with-blocks close it.

    Each object has a lock (reentrant): every call that uses the C object
    holds it, and so does close(), which therefore waits for a call in
    flight on another thread instead of freeing what that call reads."""

    _what = "mvr object"

    def __init__(self):
        self._handle = None
        self._lock = threading.RLock()

    def _destroy(self, handle):  # pragma: no cover - each class has its own
        raise NotImplementedError

    @property
    def handle(self):
        """The C pointer (an int); raises ClosedError once closed."""
        if self._handle is None:
            raise ClosedError(self._what)
        return self._handle

    @property
    def closed(self):
        return self._handle is None

    def close(self):
        lock = getattr(self, "_lock", None)  # None: __init__ failed before Handle's
        if lock is None:
            return
        with lock:
            handle, self._handle = self._handle, None
            if handle is not None:
                self._destroy(handle)

    def __enter__(self):
        self.handle  # noqa: B018 - entering a closed object is an error
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: the library may be gone
            pass


def as_c_double(values, n, what):
    vals = [float(v) for v in values]
    if len(vals) != n:
        raise ValueError("%s: %d values expected, got %d" % (what, n, len(vals)))
    return (ctypes.c_double * n)(*vals)


def as_c_float(values, n, what):
    vals = [float(v) for v in values]
    if len(vals) != n:
        raise ValueError("%s: %d values expected, got %d" % (what, n, len(vals)))
    return (ctypes.c_float * n)(*vals)


def locked(method):
    """Runs a Handle's method holding the object's lock (see Handle)."""
    @functools.wraps(method)
    def run(self, *args, **kwargs):
        with self._lock:
            return method(self, *args, **kwargs)
    return run


# the C types' ranges: ctypes wraps a Python int outside them silently
# (-1 becomes 0xFFFFFFFF, 2**33 + 64 becomes 64)
U32_MAX = 2 ** 32 - 1
U64_MAX = 2 ** 64 - 1
I32_MAX = 2 ** 31 - 1


def c_int(value, what, lo, hi):
    """value as a Python int in [lo, hi]; ValueError naming `what` and the
    range otherwise. Integral floats (640.0) pass; 0.5, NaN and non-numbers
    do not."""
    try:
        v = operator.index(value)
    except TypeError:
        v = None
        if isinstance(value, numbers.Real) and not isinstance(value, bool):
            f = float(value)
            if f.is_integer():
                v = int(f)
    if v is None:
        raise ValueError("%s: an integer in [%d, %d] expected, got %r" % (what, lo, hi, value))
    if not lo <= v <= hi:
        raise ValueError("%s: %d is outside the allowed range [%d, %d]" % (what, v, lo, hi))
    return v


def _no_nul(b, what, value):
    if b"\0" in b:
        raise ValueError("%s: %r holds a NUL character, which would cut the string short in C" % (what, value))
    return b


def c_text(s, what):
    """A str (UTF-8) or bytes for a char * argument, None for None;
    ValueError for a NUL inside, TypeError for anything else."""
    if s is None:
        return None
    if isinstance(s, str):
        return _no_nul(s.encode("utf-8"), what, s)
    if isinstance(s, (bytes, bytearray)):
        return _no_nul(bytes(s), what, s)
    raise TypeError("%s: a str or bytes expected, got %s" % (what, type(s).__name__))


def c_path(p, what):
    """A path (str, bytes or os.PathLike) for a char * argument, None for
    None; ValueError for a NUL inside."""
    if p is None:
        return None
    return _no_nul(os.fsencode(p), what, p)
