"""`cmake --install` puts the package where python3 finds it under the prefix
(MVR_PYTHON_INSTALL_DIR), and the installed package finds the installed
libmvr.so by itself: no MVR_LIBRARY_DIR, no LD_LIBRARY_PATH."""
import os
import pathlib
import subprocess
import sys

import pytest

SCRIPT = r"""
import sys
import numpy as np
import mvr
print(mvr.__file__)
print(mvr.LIBRARY_DIR)
with mvr.Context() as ctx, mvr.Scene() as s:
    m = s.add_material(base_color=(1, 0, 0, 1), unlit=True)
    mesh = s.add_mesh(positions=[[-1, -1, -3], [1, -1, -3], [0, 1, -3]], material=m)
    s.add_node(mesh=mesh)
    with mvr.Views.from_poses(np.eye(4)) as views:
        (v,) = ctx.render(s, views, (16, 16), environment=None)  # unlit red, exact without a tone map
print(tuple(v.color[8, 8]))
"""


def test_installed_package_finds_its_libraries(tmp_path):
    build = os.environ.get("MVR_BUILD_DIR")
    py_dir = os.environ.get("MVR_PY_INSTALL_DIR")
    if not build or not py_dir:
        pytest.skip("MVR_BUILD_DIR / MVR_PY_INSTALL_DIR unset (ctest sets them)")
    prefix = tmp_path / "prefix"
    # (without the sanitizer build's preloaded ASan runtime: cmake is not ours)
    plain = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    p = subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], capture_output=True, text=True,
                       env=plain)
    assert p.returncode == 0, p.stdout + p.stderr
    site = prefix / py_dir
    assert (site / "mvr" / "__init__.py").exists() and (site / "mvr" / "_config.py").exists()
    assert not list(site.rglob("__pycache__"))
    env = {k: v for k, v in os.environ.items() if k not in ("MVR_LIBRARY_DIR", "PYTHONPATH", "LD_LIBRARY_PATH")}
    env["PYTHONPATH"] = str(site)
    p = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert p.returncode == 0, p.stdout + p.stderr
    module, libdir, pixel = p.stdout.splitlines()[-3:]
    assert pathlib.Path(module).resolve().is_relative_to(site.resolve())
    assert pathlib.Path(libdir).resolve().parent == prefix.resolve()  # <prefix>/lib
    assert pixel == "(255, 0, 0, 255)"


def run_import(package_parent, env_extra, cwd):
    env = {k: v for k, v in os.environ.items() if k not in ("MVR_LIBRARY_DIR", "PYTHONPATH", "LD_LIBRARY_PATH")}
    env.update(env_extra, PYTHONPATH=str(package_parent))
    return subprocess.run([sys.executable, "-c", "import mvr; print(mvr.LIBRARY_DIR)"], capture_output=True,
                          text=True, env=env, cwd=str(cwd))


def test_where_the_package_looks_for_libmvr(tmp_path):
    """A copy of the package outside the tree: MVR_LIBRARY_DIR alone decides
    (an empty folder is an error naming it), else the dynamic loader."""
    import shutil
    import mvr
    src = pathlib.Path(mvr.__file__).parent
    libdir = pathlib.Path(mvr.LIBRARY_DIR) if mvr.LIBRARY_DIR else None
    if libdir is None:
        pytest.skip("this run found libmvr through the dynamic loader")
    shutil.copytree(src, tmp_path / "pkg" / "mvr", ignore=shutil.ignore_patterns("__pycache__", "_config.py", "_libs"))
    p = run_import(tmp_path / "pkg", {"MVR_LIBRARY_DIR": str(libdir)}, tmp_path)
    assert p.returncode == 0 and p.stdout.strip() == str(libdir), p.stderr
    (tmp_path / "empty").mkdir()
    p = run_import(tmp_path / "pkg", {"MVR_LIBRARY_DIR": str(tmp_path / "empty")}, tmp_path)
    assert p.returncode != 0 and "MVR_LIBRARY_DIR=%s holds no libmvr.so.0" % (tmp_path / "empty") in p.stderr
    p = run_import(tmp_path / "pkg", {"LD_LIBRARY_PATH": str(libdir)}, tmp_path)
    assert p.returncode == 0 and p.stdout.strip() == "None", p.stderr
    p = run_import(tmp_path / "pkg", {}, tmp_path)
    if p.returncode != 0:  # unless a libmvr is installed system-wide
        assert "libmvr.so not found" in p.stderr and "MVR_LIBRARY_DIR" in p.stderr
