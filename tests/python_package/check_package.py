#!/usr/bin/env python3
"""ctest python_package: mvr installed the way Python users install things.

  check_package.py SOURCE WORK
1. a venv made from scratch in WORK, `pip install --no-build-isolation
   --no-index SOURCE` into it (the backend builds libmvr with CMake into
   WORK/cmake-build), and the package imports from the venv with no
   MVR_LIBRARY_DIR, PYTHONPATH or LD_LIBRARY_PATH, from outside the tree;
2. the pytest suite (tests/python) run with that venv's interpreter;
3. `python3 -m build --wheel --no-isolation` (the same CMake build folder,
   so nothing is compiled again), the wheel checked (RECORD hashes, the
   libraries' RUNPATH $ORIGIN, every library they need is one the guide
   names as the system's; the CLI mvr/_bin/mvr's RUNPATH $ORIGIN/../_libs),
   installed into a second fresh venv and rendering from there (the
   package and the CLI);
4. `python3 -m build --sdist`: the source without build folders.
The venvs see the system's site-packages (--system-site-packages) for
numpy and pytest (Debian's python3-numpy, python3-pytest): nothing is
fetched from an index. Exit 77 (skipped) where python3-venv or
python3-build is missing, except under CI=true."""
import base64
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile

SOURCE = pathlib.Path(sys.argv[1]).resolve()
WORK = pathlib.Path(sys.argv[2]).resolve()
CMAKE_BUILD = WORK / "cmake-build"
CLEAN_ENV = {k: v for k, v in os.environ.items()
             if k not in ("MVR_LIBRARY_DIR", "PYTHONPATH", "LD_LIBRARY_PATH", "PYTHONHOME", "VIRTUAL_ENV")}
# what the wheel's libraries may need from the system: the C/C++ runtime,
# which every Linux has, and what docs/guide.md ("Installing with pip")
# names, each of which must appear there
RUNTIME = {"libc.so.6", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1", "ld-linux-x86-64.so.2",
           "ld-linux-aarch64.so.1"}
# what the probe renders in a venv: the README's example, smaller
PROBE = r"""
import pathlib, sys
import numpy as np
import mvr
venv = pathlib.Path(sys.prefix).resolve()
assert pathlib.Path(mvr.__file__).resolve().is_relative_to(venv), (mvr.__file__, venv)
assert pathlib.Path(mvr.LIBRARY_DIR).resolve().is_relative_to(venv), (mvr.LIBRARY_DIR, venv)
with mvr.Context() as ctx, mvr.Scene.load(sys.argv[1]) as scene, \
        mvr.Views.layout(scene, "ring", count=4, aspect=4 / 3) as views:
    got = ctx.render(scene, views, (64, 48), outputs=("color", "ids"))
    assert len(got) == 4 and got[0].color.shape == (48, 64, 4)
    assert (got[0].ids[..., 0] > 0).mean() > 0.05, "the object covers under 5% of the view"
print("ok", mvr.__file__)
"""


def skip(why):
    print("python_package: " + why)
    sys.exit(1 if os.environ.get("CI") == "true" else 77)


def run(cmd, **kw):
    print("+ " + " ".join(map(str, cmd)), flush=True)
    p = subprocess.run([str(c) for c in cmd], env=kw.pop("env", CLEAN_ENV), cwd=kw.pop("cwd", WORK),
                       capture_output=True, text=True, **kw)
    if p.returncode != 0:
        print(p.stdout[-6000:], p.stderr[-6000:], sep="\n")
        raise SystemExit("python_package: failed (exit %d): %s" % (p.returncode, " ".join(map(str, cmd))))
    return p


def make_venv(path):
    shutil.rmtree(path, ignore_errors=True)
    p = subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(path)], capture_output=True,
                       text=True)
    if p.returncode != 0:
        skip("%s -m venv failed (Debian: python3-venv, which scripts/setup installs): %s" % (
            sys.executable, p.stderr.strip()[-500:]))
    return path / "bin" / "python"


def guide_libraries():
    """The sonames docs/guide.md's "Installing with pip" section names."""
    text = (SOURCE / "docs" / "guide.md").read_text(encoding="utf-8")
    m = re.search(r"^### Installing with pip\n(.*?)(?=^#)", text, re.S | re.M)
    assert m, "docs/guide.md has no '### Installing with pip' section"
    return set(re.findall(r"`(lib[A-Za-z0-9_+.-]+\.so[.0-9a-z]*)`", m.group(1)))


def check_wheel(wheel):
    with zipfile.ZipFile(wheel) as z:
        names = set(z.namelist())
        record = next(n for n in names if n.endswith(".dist-info/RECORD"))
        rows = [line.split(",") for line in z.read(record).decode().splitlines() if line]
        assert {r[0] for r in rows} == names, "RECORD lists %s, the wheel holds %s" % (
            sorted({r[0] for r in rows} ^ names), sorted(names))
        for name, digest, size in rows:
            if name == record:
                continue
            data = z.read(name)
            want = "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            assert digest == want and int(size) == len(data), "RECORD's hash or size of %s is wrong" % name
        libs = sorted(n for n in names if n.startswith("mvr/_libs/"))
        assert "mvr/_libs/libmvr.so.0" in libs and "mvr/py.typed" in names and "mvr/stream.py" in names, names
        out = WORK / "wheel-libs"
        shutil.rmtree(out, ignore_errors=True)
        z.extractall(out, members=libs + ["mvr/_bin/mvr"])
    # the CLI (mvr.dask runs it) finds the package's libraries in ../_libs
    dyn = run(["readelf", "-d", out / "mvr/_bin/mvr"]).stdout
    assert re.findall(r"\((?:RUNPATH|RPATH)\).*\[(.*)\]", dyn) == ["$ORIGIN/../_libs"], dyn
    allowed = RUNTIME | guide_libraries()
    for lib in libs:
        dyn = run(["readelf", "-d", out / lib]).stdout
        runpath = re.findall(r"\((?:RUNPATH|RPATH)\).*\[(.*)\]", dyn)
        assert runpath == ["$ORIGIN"], "%s: RUNPATH %s, expected $ORIGIN only" % (lib, runpath)
        own = {pathlib.Path(n).name for n in libs}
        for needed in re.findall(r"\(NEEDED\).*\[(.*)\]", dyn):
            assert needed in own or needed in allowed, (
                "%s needs %s, which neither the wheel carries nor docs/guide.md names" % (lib, needed))
    print("wheel: %s, %d libraries, %d files, RECORD and RUNPATH checked" % (wheel.name, len(libs), len(names)))


def main():
    WORK.mkdir(parents=True, exist_ok=True)
    scene = SOURCE / "tests" / "data" / "peers" / "coated.gltf"
    # 1. pip install into a fresh venv
    py = make_venv(WORK / "venv-pip")
    run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--config-settings",
         "build-dir=%s" % CMAKE_BUILD, SOURCE])
    print(run([py, "-c", PROBE, scene]).stdout.strip())
    # README's Python section: its commands are these, and its example runs
    # with the venv's interpreter (in a folder whose tests/ is the source's,
    # for the example's relative paths)
    readme = (SOURCE / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("**4. Python"):readme.index("**5. ")]
    commands = re.search(r"```sh\n(.*?)```", section, re.S).group(1).split("\n")
    assert commands[:2] == ["python3 -m venv --system-site-packages venv",
                            "venv/bin/pip install --no-build-isolation ."], commands
    example = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    folder = WORK / "readme"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir()
    (folder / "tests").symlink_to(SOURCE / "tests")
    out = run([py, "-c", example], cwd=folder).stdout
    assert out.count("(240, 320, 4)") == 12, out[-2000:]
    print("README's Python example: ran from the venv")
    # 2. the pytest suite with the venv's interpreter (the venv's mvr: the
    # tests' folder is on sys.path, the package's source folder is not)
    env = dict(CLEAN_ENV, MVR_PY_OUT=str(WORK / "pytest-out"), PYTHONDONTWRITEBYTECODE="1",
               MVR_PY_EXPECT_PREFIX=str(WORK / "venv-pip"))
    p = run([py, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", SOURCE / "tests" / "python"], env=env)
    print(p.stdout.strip().splitlines()[-1])
    # 3. a wheel, checked and installed into a second venv
    has_build = subprocess.run([sys.executable, "-c", "import build"], capture_output=True).returncode == 0
    if not has_build:
        skip("%s has no 'build' module (Debian: python3-build, which scripts/setup installs)" % sys.executable)
    dist = WORK / "dist"
    shutil.rmtree(dist, ignore_errors=True)
    run([sys.executable, "-m", "build", "--wheel", "--no-isolation", "-Cbuild-dir=%s" % CMAKE_BUILD, "--outdir",
         dist, SOURCE])
    wheels = list(dist.glob("mvr-*.whl"))
    assert len(wheels) == 1, wheels
    check_wheel(wheels[0])
    py2 = make_venv(WORK / "venv-wheel")
    run([py2, "-m", "pip", "install", "--no-index", wheels[0]])
    print(run([py2, "-c", PROBE, scene]).stdout.strip())
    # the wheel's CLI, as mvr.dask finds it, renders from the venv
    cli = run([py2, "-c", "import mvr, pathlib; print(pathlib.Path(mvr.__file__).parent / '_bin' / 'mvr')"])
    run([cli.stdout.strip(), "render", scene, "--size", "64x48", "--out", WORK / "wheel-cli-out", "--quiet"])
    print("wheel's CLI: rendered from %s" % cli.stdout.strip())
    # 4. an sdist: the source, no build folders, PKG-INFO
    run([sys.executable, "-m", "build", "--sdist", "--no-isolation", "--outdir", dist, SOURCE])
    sdists = list(dist.glob("mvr-*.tar.gz"))
    assert len(sdists) == 1, sdists
    with tarfile.open(sdists[0]) as t:
        members = [m.name.split("/", 1)[1] for m in t.getmembers() if "/" in m.name]
    for want in ("pyproject.toml", "CMakeLists.txt", "python/mvr/__init__.py", "python/build_backend/mvr_build.py",
                 "PKG-INFO", "include/mvr/mvr.h"):
        assert want in members, "the sdist lacks %s" % want
    stray = [m for m in members if re.match(r"build[^/]*/|\.git/", m)]
    assert not stray, "the sdist holds build output: %s" % stray[:5]
    print("sdist: %s, %d files" % (sdists[0].name, len(members)))
    print("python_package: passed")


main()
