"""Errors, logging, handle bookkeeping and argument checks shared by the mvr
classes."""
import ctypes
import functools
import logging
import math
import numbers
import operator
import os
import threading
from typing import Any, Callable, Iterable, Optional, TypeVar, Union


from . import _native as N

log = logging.getLogger("mvr")
H = TypeVar("H", bound="Handle")
F = TypeVar("F", bound=Callable[..., Any])


class Error(RuntimeError):
    """A failed mvr call: `message` is mvr's own, `result` its mvr_result name
    (e.g. "MVR_ERROR_IO"); str() gives both."""

    def __init__(self, message: str, result: Optional[str] = "MVR_ERROR_INVALID_ARGUMENT") -> None:
        self.message = message
        self.result = result
        super().__init__("%s (%s)" % (message, result) if result else message)


class ClosedError(Error):
    """Use of an mvr object after close() (or after its `with` block)."""

    def __init__(self, what: str) -> None:
        super().__init__("%s is closed" % what, None)


def check(result: int, message_fn: Optional[Callable[[], str]], what: str) -> None:
    """Raises Error for a failed result; message_fn() gives the object's message."""
    if result == 0:
        return
    message = message_fn() if message_fn else ""
    raise Error(message or "%s failed" % what, N.result_name(result))


def check_created(result: int, err: Any, what: str) -> None:
    """Raises Error for a failed create call; err is its mvr_error."""
    if result == 0:
        return
    message = N.text(err.message) if err is not None else ""
    raise Error(message or "%s failed" % what, N.result_name(result))


# mvr log levels -> Python's logging
_LEVELS = {1: logging.ERROR, 2: logging.WARNING, 3: logging.INFO, 4: logging.DEBUG}


_ERROR_RESULT = N.LOG_ID("error_result")


def _forward(level: int, msg_id: int, message: Optional[bytes], user_data: Any) -> None:
    # a failed call's own message becomes the mvr.Error it raises: logged
    # again at ERROR it would print twice (logging's last-resort handler)
    py_level = logging.DEBUG if msg_id == _ERROR_RESULT else _LEVELS.get(level, logging.INFO)
    log.log(py_level, "%s", N.text(message))


# one callback for the whole process: ctypes keeps it alive as long as the module
_LOG_CALLBACK = N.LOG_FN(_forward)


def logger() -> Any:
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

    def __init__(self) -> None:
        self._handle: Optional[int] = None
        self._lock = threading.RLock()

    def _destroy(self, handle: int) -> None:  # pragma: no cover - each class has its own
        raise NotImplementedError

    @property
    def handle(self) -> int:
        """The C pointer (an int); raises ClosedError once closed."""
        if self._handle is None:
            raise ClosedError(self._what)
        return self._handle

    @property
    def closed(self) -> bool:
        """True once close() ran."""
        return self._handle is None

    def close(self) -> None:
        """Destroys the C object (once; closing again does nothing)."""
        lock = getattr(self, "_lock", None)  # None: __init__ failed before Handle's
        if lock is None:
            return
        with lock:
            handle, self._handle = self._handle, None
            if handle is not None:
                self._destroy(handle)

    def __enter__(self: "H") -> "H":
        self.handle  # noqa: B018 - entering a closed object is an error
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # interpreter shutdown: the library may be gone
            pass


def c_float(value: Any, what: str, lo: Optional[float] = None, hi: Optional[float] = None, *,
            lo_open: bool = False) -> float:
    """value as a finite Python float in [lo, hi] (lo excluded with lo_open);
    ValueError naming `what` otherwise: NaN and infinities reach no C call
    (ctypes passes them on silently)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError("%s: a number expected, got %r" % (what, value))
    f = float(value)
    if not math.isfinite(f):
        raise ValueError("%s: a finite number expected, got %r" % (what, value))
    if lo is not None and (f <= lo if lo_open else f < lo):
        raise ValueError("%s: %r must be %s %g" % (what, value, ">" if lo_open else ">=", lo))
    if hi is not None and f > hi:
        raise ValueError("%s: %r must be <= %g" % (what, value, hi))
    return f


def c_floats(values: Iterable[Any], n: Union[int, Iterable[int]], what: str, lo: Optional[float] = None,
             hi: Optional[float] = None) -> list:
    """n finite floats (n: a count, or the counts allowed) from a sequence;
    ValueError naming `what` otherwise."""
    try:
        vals = list(values)
    except TypeError:
        raise ValueError("%s: a sequence of numbers expected, got %r" % (what, values)) from None
    counts = (n,) if isinstance(n, int) else tuple(n)
    if len(vals) not in counts:
        raise ValueError("%s: %s values expected, got %d" % (what, " or ".join(map(str, counts)), len(vals)))
    return [c_float(v, "%s[%d]" % (what, k), lo, hi) for k, v in enumerate(vals)]


def as_c_double(values: Iterable[Any], n: int, what: str) -> Any:
    """n finite numbers as a ctypes double array."""
    return (ctypes.c_double * n)(*c_floats(values, n, what))


def as_c_float(values: Iterable[Any], n: int, what: str, lo: Optional[float] = None) -> Any:
    """n finite numbers (>= lo) as a ctypes float array."""
    return (ctypes.c_float * n)(*c_floats(values, n, what, lo))


def locked(method: F) -> F:
    """Runs a Handle's method holding the object's lock (see Handle)."""
    @functools.wraps(method)
    def run(self: Any, *args: Any, **kwargs: Any) -> Any:
        with self._lock:
            return method(self, *args, **kwargs)
    return run  # type: ignore[return-value]


# the C types' ranges: ctypes wraps a Python int outside them silently
# (-1 becomes 0xFFFFFFFF, 2**33 + 64 becomes 64)
U32_MAX = 2 ** 32 - 1
U64_MAX = 2 ** 64 - 1
I32_MAX = 2 ** 31 - 1


def c_int(value: Any, what: str, lo: int, hi: int) -> int:
    """value as a Python int in [lo, hi]; ValueError naming `what` and the
    range otherwise. Integral floats (640.0) pass; 0.5, NaN and non-numbers
    do not."""
    v: Optional[int]
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


def _no_nul(b: bytes, what: str, value: Any) -> bytes:
    if b"\0" in b:
        raise ValueError("%s: %r holds a NUL character, which would cut the string short in C" % (what, value))
    return b


def c_text(s: Union[str, bytes, bytearray, None], what: str) -> Optional[bytes]:
    """A str (UTF-8) or bytes for a char * argument, None for None;
    ValueError for a NUL inside, TypeError for anything else."""
    if s is None:
        return None
    if isinstance(s, str):
        return _no_nul(s.encode("utf-8"), what, s)
    if isinstance(s, (bytes, bytearray)):
        return _no_nul(bytes(s), what, s)
    raise TypeError("%s: a str or bytes expected, got %s" % (what, type(s).__name__))


PathArg = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]


def c_path(p: Optional[PathArg], what: str) -> Optional[bytes]:
    """A path (str, bytes or os.PathLike) for a char * argument, None for
    None; ValueError for a NUL inside."""
    if p is None:
        return None
    return _no_nul(os.fsencode(p), what, p)
