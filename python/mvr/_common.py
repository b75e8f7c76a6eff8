"""Errors, logging and handle bookkeeping shared by the mvr classes."""
import ctypes
import logging

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
    """Owns one mvr object: close() destroys it once; with-blocks close it."""

    _what = "mvr object"

    def __init__(self):
        self._handle = None

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


def bytes_or_none(s):
    if s is None:
        return None
    return s.encode("utf-8") if isinstance(s, str) else bytes(s)
