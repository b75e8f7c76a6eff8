"""mvr's PEP 517 build backend: CMake builds the shared libraries, this
module puts them and python/mvr into a wheel (PEP 427). Standard library
only, so `pip install --no-build-isolation .` works in a bare venv with no
network: scikit-build-core is not in a fresh venv (and only in Debian's
backports), and setuptools 66 (a Debian 12 venv's) cannot build a wheel
without the `wheel` package, which a fresh venv does not have either.

What a wheel holds:
  mvr/*.py, mvr/py.typed          the package (python/mvr)
  mvr/_libs/libmvr.so.0           libmvr and mvr's own shared libraries,
  mvr/_libs/libmvr_image.so.0     each under its soname, RUNPATH $ORIGIN
  mvr/_libs/libmvr_gltf.so.0      (the package loads them from there:
  mvr/_libs/libmvr_image_oiio.so   mvr/_lib.py)
  mvr/_bin/mvr                    the `mvr` CLI (mvr's libraries linked in
                                  statically; RUNPATH $ORIGIN/../_libs, where
                                  it finds the image module), which
                                  mvr.dask runs (mvr/dask.py: find_cli)
  mvr-<version>.dist-info/        METADATA, WHEEL, RECORD, top_level.txt
It is tagged py3-none-<platform>: no compiled Python extension (ctypes),
so one wheel serves every Python 3 of the platform it was built on. What
it needs from the system at run time: docs/guide.md ("Installing with pip").

Config settings (pip --config-settings KEY=VALUE, python -m build -CKEY=VALUE):
  build-dir    CMake's build folder (default <source>/build-wheel; kept,
               so a second build only relinks what changed)
  cmake-args   more -D options for CMake, space-separated
  jobs         parallel build jobs (default: CMAKE_BUILD_PARALLEL_LEVEL or
               every CPU)
"""
import base64
import hashlib
import os
import pathlib
import re
import shlex
import subprocess
import sys
import sysconfig
import tarfile
import time
import zipfile

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
PACKAGE = ROOT / "python" / "mvr"
# the shared libraries a wheel carries, under their sonames, by CMake target
LIBRARIES = (
    ("mvr_shared", "libmvr.so.0"),
    ("mvr_image_shared", "libmvr_image.so.0"),
    ("mvr_gltf_shared", "libmvr_gltf.so.0"),
    ("mvr_image_oiio", "libmvr_image_oiio.so"),
)
# the CLI's CMake target, which is also its file name: mvr/_bin/mvr
CLI = "mvr"
# what an sdist leaves out: build folders, VCS data, the GL packages a
# session may keep in .gl/
SDIST_SKIP = re.compile(r"^(build[^/]*|\.git|\.gl|out|__pycache__)(/|$)|/__pycache__(/|$)|\.pyc$")


class BuildError(RuntimeError):
    """A build step failed; the message names it."""


# ------------------------------------------------------------------ metadata

def _project():
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        try:
            import tomli as tomllib  # type: ignore[no-redef]
        except ImportError:
            raise BuildError("building mvr needs Python 3.11 or newer (tomllib), or the tomli package") from None
    with open(ROOT / "pyproject.toml", "rb") as f:
        project = tomllib.load(f)["project"]
    cmake = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"project\(mvr VERSION ([0-9.]+)", cmake)
    if not m or m.group(1) != project["version"]:
        raise BuildError("pyproject.toml's version %s is not CMakeLists.txt's project(mvr VERSION %s)" %
                         (project["version"], m.group(1) if m else "?"))
    return project


def _metadata(project):
    lines = ["Metadata-Version: 2.1", "Name: " + project["name"], "Version: " + project["version"],
             "Summary: " + project["description"]]
    if "requires-python" in project:
        lines.append("Requires-Python: " + project["requires-python"])
    for dep in project.get("dependencies", []):
        lines.append("Requires-Dist: " + dep)
    for key, url in project.get("urls", {}).items():
        lines.append("Project-URL: %s, %s" % (key, url))
    for c in project.get("classifiers", []):
        lines.append("Classifier: " + c)
    return "\n".join(lines) + "\n"


def _platform_tag():
    return re.sub(r"[^A-Za-z0-9]", "_", sysconfig.get_platform())


def _wheel_file(tag):
    return "Wheel-Version: 1.0\nGenerator: mvr_build\nRoot-Is-Purelib: false\nTag: %s\n" % tag


def _dist_info(project):
    return "%s-%s.dist-info" % (project["name"], project["version"])


# ------------------------------------------------------------------ building

def _run(cmd, what):
    print("mvr_build: " + " ".join(shlex.quote(str(c)) for c in cmd), flush=True)
    r = subprocess.run([str(c) for c in cmd], cwd=str(ROOT))
    if r.returncode != 0:
        raise BuildError("%s failed (exit %d): %s" % (what, r.returncode, " ".join(map(str, cmd))))


def _setting(config_settings, key, default=None):
    v = (config_settings or {}).get(key, default)
    if isinstance(v, list):  # given twice: the last wins
        v = v[-1]
    return v


def _build_libraries(config_settings):
    """Configures and builds the shared libraries and the CLI; returns
    {soname: path}, and {"mvr": path} for the CLI."""
    build_dir = pathlib.Path(_setting(config_settings, "build-dir", ROOT / "build-wheel")).resolve()
    extra = shlex.split(_setting(config_settings, "cmake-args", "") or "")
    jobs = str(_setting(config_settings, "jobs", os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or os.cpu_count() or 1))
    # every library finds its neighbours in its own folder ($ORIGIN): the
    # build tree's RUNPATH would name this machine's build folder
    _run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DMVR_BUILD_TESTS=OFF",
          "-DMVR_WITH_VIEWER=OFF", "-DMVR_WITH_PYTHON=OFF", "-DCMAKE_BUILD_WITH_INSTALL_RPATH=ON",
          "-DCMAKE_INSTALL_RPATH=$ORIGIN", "-DMVR_CLI_INSTALL_RPATH=$ORIGIN/../_libs"] + extra,
         "CMake's configure step")
    _run(["cmake", "--build", build_dir, "-j", jobs, "--target"] + [t for t, _ in LIBRARIES] + [CLI],
         "CMake's build")
    found = {}
    if (build_dir / CLI).exists():
        found[CLI] = (build_dir / CLI).resolve()
    for target, soname in LIBRARIES:
        path = build_dir / soname
        if not path.exists():
            if target == "mvr_shared":
                raise BuildError("the build made no %s in %s" % (soname, build_dir))
            continue  # built without MVR_WITH_GLTF / MVR_WITH_IMAGE_IO
        found[soname] = path.resolve()
    return found


def _package_files():
    files = sorted(p for p in PACKAGE.iterdir() if p.is_file() and (p.suffix == ".py" or p.name == "py.typed"))
    # _config.py is cmake --install's note of where it put the libraries
    return [p for p in files if p.name != "_config.py"]


# ------------------------------------------------------------------ the wheel

def _record_hash(data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode("ascii")
    return "sha256=" + digest


class _WheelWriter:
    def __init__(self, path):
        self.zip = zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED)
        self.records = []
        # reproducible: SOURCE_DATE_EPOCH when set, else 1980 (zip's first date)
        epoch = int(os.environ.get("SOURCE_DATE_EPOCH", "315532800"))
        self.date = time.gmtime(max(epoch, 315532800))[:6]

    def add(self, name, data, executable=False):
        info = zipfile.ZipInfo(name, self.date)
        info.compress_type = zipfile.ZIP_DEFLATED
        info.external_attr = ((0o755 if executable else 0o644) | 0o100000) << 16
        self.zip.writestr(info, data)
        self.records.append("%s,%s,%d" % (name, _record_hash(data), len(data)))

    def close(self, record_name):
        self.records.append(record_name + ",,")
        info = zipfile.ZipInfo(record_name, self.date)
        info.external_attr = (0o644 | 0o100000) << 16
        self.zip.writestr(info, "\n".join(self.records) + "\n")
        self.zip.close()


def _write_dist_info(add, project, tag):
    info = _dist_info(project)
    add(info + "/METADATA", _metadata(project).encode())
    add(info + "/WHEEL", _wheel_file(tag).encode())
    add(info + "/top_level.txt", b"mvr\n")
    return info


# ------------------------------------------------------------------ PEP 517 hooks

def get_requires_for_build_wheel(config_settings=None):
    """Nothing beyond the standard library (and cmake, a C/C++ toolchain and
    mvr's Debian packages on the system: scripts/setup)."""
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    project = _project()
    info = pathlib.Path(metadata_directory) / _dist_info(project)
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata(project), encoding="utf-8")
    (info / "WHEEL").write_text(_wheel_file("py3-none-" + _platform_tag()), encoding="utf-8")
    (info / "top_level.txt").write_text("mvr\n", encoding="utf-8")
    return info.name


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    project = _project()
    libraries = _build_libraries(config_settings)
    tag = "py3-none-" + _platform_tag()
    name = "%s-%s-%s.whl" % (project["name"], project["version"], tag)
    out = pathlib.Path(wheel_directory) / name
    tmp = out.with_name(out.name + ".part")
    w = _WheelWriter(tmp)
    try:
        for p in _package_files():
            w.add("mvr/" + p.name, p.read_bytes())
        for soname, path in libraries.items():
            w.add(("mvr/_bin/" if soname == CLI else "mvr/_libs/") + soname, path.read_bytes(), executable=True)
        info = _write_dist_info(w.add, project, tag)
        w.close(info + "/RECORD")
        os.replace(tmp, out)
    except BaseException:
        w.zip.close()
        tmp.unlink(missing_ok=True)
        raise
    print("mvr_build: wrote %s (%d libraries%s)" % (out, len(set(libraries) - {CLI}),
                                                  " and the CLI" if CLI in libraries else ""), flush=True)
    return name


def build_sdist(sdist_directory, config_settings=None):
    """The source tree (less build folders) as <name>-<version>.tar.gz, with
    PKG-INFO: building a wheel from it needs what building from the tree needs."""
    project = _project()
    base = "%s-%s" % (project["name"], project["version"])
    out = pathlib.Path(sdist_directory) / (base + ".tar.gz")

    def files():
        for dirpath, dirnames, filenames in os.walk(ROOT):
            rel_dir = os.path.relpath(dirpath, ROOT)
            rel_dir = "" if rel_dir == "." else rel_dir + "/"
            dirnames[:] = sorted(d for d in dirnames if not SDIST_SKIP.search(rel_dir + d))
            for f in sorted(filenames):
                if not SDIST_SKIP.search(rel_dir + f):
                    yield rel_dir + f

    with tarfile.open(out, "w:gz", format=tarfile.PAX_FORMAT) as tar:
        for rel in files():
            tar.add(str(ROOT / rel), arcname=base + "/" + rel, recursive=False)
        data = _metadata(project).encode()
        info = tarfile.TarInfo(base + "/PKG-INFO")
        info.size, info.mode = len(data), 0o644
        import io
        tar.addfile(info, io.BytesIO(data))
    return out.name


if __name__ == "__main__":  # python3 python/build_backend/mvr_build.py DIR: a wheel into DIR
    sys.exit(0 if build_wheel(sys.argv[1] if len(sys.argv) > 1 else ".") else 1)
