"""The public API is typed and documented (issue 32): python/mvr/py.typed is
there (PEP 561), every public class, function, method and property has a
docstring and annotations on every parameter and its return, and mypy
(Debian's python3-mypy, default settings) passes over the package."""
import importlib.util
import inspect
import subprocess
import sys

import pytest

import mvr
from conftest import ROOT

PACKAGE = ROOT / "python" / "mvr"


def public_callables():
    for name in mvr.__all__:
        obj = getattr(mvr, name)
        if inspect.isfunction(obj):
            yield name, obj, False
        elif inspect.isclass(obj):
            yield name, obj, True
            for m, v in vars(obj).items():
                if m.startswith("_") and m not in ("__init__", "__getitem__", "__len__"):
                    continue
                if isinstance(v, property):
                    yield "%s.%s" % (name, m), v.fget, False
                elif isinstance(v, (classmethod, staticmethod)):
                    yield "%s.%s" % (name, m), v.__func__, False
                elif inspect.isfunction(v):
                    yield "%s.%s" % (name, m), v, False


def test_py_typed_marker():
    assert (PACKAGE / "py.typed").is_file()


def test_public_api_is_documented_and_annotated():
    missing_doc, missing_hints = [], []
    for name, fn, is_class in public_callables():
        if is_class:
            if not (fn.__doc__ or "").strip():
                missing_doc.append(name)
            continue
        # __init__'s words are its class's docstring
        if not name.endswith("__init__") and not (fn.__doc__ or "").strip():
            missing_doc.append(name)
        fn = inspect.unwrap(fn)
        sig = inspect.signature(fn)
        for p in sig.parameters.values():
            if p.name not in ("self", "cls") and p.annotation is inspect.Parameter.empty:
                missing_hints.append("%s(%s)" % (name, p.name))
        if sig.return_annotation is inspect.Signature.empty:
            missing_hints.append("%s -> ?" % name)
    assert not missing_doc, "no docstring: " + ", ".join(missing_doc)
    assert not missing_hints, "no annotation: " + ", ".join(missing_hints)


def test_mypy_passes(tmp_path):
    if importlib.util.find_spec("mypy") is None:
        pytest.skip("%s has no mypy: install python3-mypy" % sys.executable)
    p = subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "mypy_cache"), str(PACKAGE)],
                       capture_output=True, text=True, cwd=str(ROOT))
    assert p.returncode == 0, p.stdout + p.stderr
