"""Fixtures of the Python package's tests (ctest python_mvr; by hand:
PYTHONPATH=python python3 -m pytest tests/python, with the README's build/).

MVR_PY_REFERENCE: the C helper tests/python/py_reference.c (default:
build/tests/py_reference); MVR_PY_OUT: where the tests write (default: a
temporary folder per test)."""
import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PEERS = ROOT / "tests" / "data" / "peers"


def pytest_sessionstart(session):
    """MVR_PY_EXPECT_PREFIX (ctest python_package: the suite run by a venv's
    interpreter): the mvr under test must be the one installed there, not
    the source tree's."""
    prefix = os.environ.get("MVR_PY_EXPECT_PREFIX")
    if prefix:
        import mvr
        where = pathlib.Path(mvr.__file__).resolve()
        assert where.is_relative_to(pathlib.Path(prefix).resolve()), (
            "testing %s, not the mvr installed in %s" % (where, prefix))


def reference_path():
    return pathlib.Path(os.environ.get("MVR_PY_REFERENCE", ROOT / "build" / "tests" / "py_reference"))


@pytest.fixture(scope="session")
def reference():
    """Runs the C helper; returns its stdout (asserts it succeeded)."""
    exe = reference_path()
    assert exe.exists(), "%s is missing: build the py_reference target" % exe

    def run(*args, check=True):
        p = subprocess.run([str(exe)] + [str(a) for a in args], capture_output=True, text=True)
        if check:
            assert p.returncode == 0, "py_reference %s: exit %d\n%s%s" % (
                " ".join(map(str, args)), p.returncode, p.stdout, p.stderr)
        return p

    return run


@pytest.fixture(scope="session")
def ctx():
    import mvr
    with mvr.Context() as c:
        yield c


@pytest.fixture
def out_dir(request, tmp_path):
    base = os.environ.get("MVR_PY_OUT")
    if not base:
        return tmp_path
    d = pathlib.Path(base) / request.node.name.replace("[", "_").replace("]", "")
    shutil.rmtree(d, ignore_errors=True)  # a run's directory holds folders too (test_dask)
    d.mkdir(parents=True)
    return d
