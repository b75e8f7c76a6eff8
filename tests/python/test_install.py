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
        (v,) = ctx.render(s, views, (16, 16))
print(tuple(v.color[8, 8]))
"""


def test_installed_package_finds_its_libraries(tmp_path):
    build = os.environ.get("MVR_BUILD_DIR")
    py_dir = os.environ.get("MVR_PY_INSTALL_DIR")
    if not build or not py_dir:
        pytest.skip("MVR_BUILD_DIR / MVR_PY_INSTALL_DIR unset (ctest sets them)")
    prefix = tmp_path / "prefix"
    p = subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], capture_output=True, text=True)
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
