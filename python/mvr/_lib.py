"""Finds and loads libmvr.so (and libmvr_image.so, libmvr_gltf.so) with ctypes.

Where the libraries are looked for, first found wins:
  1. $MVR_LIBRARY_DIR, a folder holding libmvr.so.0 (nothing else is tried
     when it is set: a wrong path is an error, not a silent fallback);
  2. the package's own _libs/ folder (a wheel's: pip install .);
  3. the folder `cmake --install` recorded in mvr/_config.py (LIBDIR);
  4. build/ of the source tree this package sits in (python/mvr/../../build),
     the README's build folder;
  5. the dynamic loader's own search (LD_LIBRARY_PATH, ld.so.cache).
libmvr.so.0 is loaded first, so the others find it by its soname wherever
they were installed.
"""
import ctypes
import os
import pathlib

_HERE = pathlib.Path(__file__).resolve().parent
_NAMES = ("mvr", "mvr_image", "mvr_gltf")


def _config_libdir():
    try:
        from . import _config  # written by cmake --install
    except ImportError:
        return None
    return getattr(_config, "LIBDIR", None)


def _search_dirs():
    env = os.environ.get("MVR_LIBRARY_DIR")
    if env:
        return [("MVR_LIBRARY_DIR", pathlib.Path(env))], True
    dirs = [("the package's own libraries", _HERE / "_libs")]
    installed = _config_libdir()
    if installed:
        dirs.append(("the installed package's LIBDIR", pathlib.Path(installed)))
    dirs.append(("the source tree's build folder", _HERE.parent.parent / "build"))
    return dirs, False


def _soname(name):
    return "lib%s.so.0" % name


def _load_all():
    dirs, exclusive = _search_dirs()
    tried = []
    for why, d in dirs:
        path = d / _soname("mvr")
        tried.append("%s (%s)" % (path, why))
        if path.exists():
            return _load_from(d)
    if exclusive:
        raise ImportError("mvr: MVR_LIBRARY_DIR=%s holds no %s" % (dirs[0][1], _soname("mvr")))
    try:
        return _load_from(None)
    except OSError as e:
        tried.append("%s through the dynamic loader (%s)" % (_soname("mvr"), e))
    raise ImportError("mvr: libmvr.so not found; looked for " + "; ".join(tried) +
                      ". Set MVR_LIBRARY_DIR to the folder holding libmvr.so.0 (the build folder, or "
                      "<prefix>/lib of `cmake --install`).")


def _load_from(folder):
    libs = {}
    for name in _NAMES:
        target = str(folder / _soname(name)) if folder is not None else _soname(name)
        try:
            # libmvr.so.0 first: the others find it by its soname, wherever installed
            libs[name] = ctypes.CDLL(target)
        except OSError:
            if name == "mvr":
                raise
            libs[name] = None  # built without MVR_WITH_GLTF / MVR_WITH_IMAGE_IO
    return libs, folder


LIBS, LIBRARY_DIR = _load_all()
core = LIBS["mvr"]
image = LIBS["mvr_image"]
gltf = LIBS["mvr_gltf"]


def fn(lib, name, restype, *argtypes):
    """Declares a C function; None when the library lacks it (an older libmvr)."""
    if lib is None:
        return None
    try:
        f = getattr(lib, name)
    except AttributeError:
        return None
    f.restype = restype
    f.argtypes = list(argtypes)
    return f
