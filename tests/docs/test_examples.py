#!/usr/bin/env python3
"""ctest docs_examples: every example README.md marks runs against this build
and leaves the files it promises.

An example is a fenced code block right after an HTML comment:

    <!-- example: out/x/view_0000.png out/x/colmap/cameras.txt -->   files it writes
    <!-- example -->                                                 no files promised
    <!-- example: viewer -->                                         an mvr-viewer command

Each runs in a fresh folder that holds `build` (this build), `tests` and
`python` (the source tree's), so the README's paths work as written. The
commands run as written with two things appended to keep the test short (about
10 s on 2 cores): `--size 64x48 --quiet` to each `build/mvr render` (the README
gives full sizes; the last --size wins), and to a viewer command `--size 256x96
--frames 2 --screenshot FILE` under tests/run_with_xvfb.sh, then FILE must
exist. The viewer example is skipped, saying so, where Xvfb or mvr-viewer is
missing; the Python one where the interpreter has no numpy. A command that
exits non-zero, or a promised file that is missing, fails the test.

It also checks that `mvr-viewer --help` names only options it accepts (in its
option table or in the text): each one given alone gets a usage message of
its own, never "unknown option".

usage: test_examples.py SOURCE_DIR BUILD_DIR [--python PY | --no-python] [--python-env K=V]
                        [--viewer VIEWER]
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

EXAMPLE = re.compile(r"<!-- example(?::\s*(?P<spec>[^>]*?))?\s*-->\s*\n```(?P<lang>\w+)\n(?P<body>.*?)```", re.S)
FAST = ["--size", "64x48", "--quiet"]


def examples(readme):
    """(language, commands or code, promised files, is_viewer) per marked block"""
    found = []
    for m in EXAMPLE.finditer(open(readme).read()):
        spec = (m.group("spec") or "").split()
        viewer = spec == ["viewer"]
        body = m.group("body")
        if m.group("lang") == "sh":
            body = [shlex.split(line) for line in body.replace("\\\n", " ").splitlines() if line.strip()]
        found.append((m.group("lang"), body, [] if viewer else spec, viewer))
    return found


def run(cmd, cwd, env=None, label=None):
    t = time.time()
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=120)
    print("  %s (%.1f s, exit %d)" % (label or " ".join(cmd), time.time() - t, p.returncode))
    if p.returncode != 0:
        print(p.stdout[-3000:] + p.stderr[-3000:])
    return p.returncode == 0


def check_viewer_help(viewer):
    """every option mvr-viewer --help names, in its table or its text, is one it accepts"""
    help_text = subprocess.run([viewer, "--help"], capture_output=True, text=True, timeout=30).stdout
    options = sorted(set(re.findall(r"(?<![\w-])--[a-z][\w-]*", help_text)))
    if len(options) < 10:
        print("FAIL: mvr-viewer --help lists %d options:\n%s" % (len(options), help_text))
        return False
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    ok = True
    for opt in options:
        if opt == "--help":
            continue
        # alone: a value missing, or a SCENE needed; no window can open without a display
        p = subprocess.run([viewer, opt], capture_output=True, text=True, timeout=60, env=env)
        if "unknown option" in p.stderr:
            print("FAIL: mvr-viewer --help lists %s, which it refuses: %s" % (opt, p.stderr.strip()))
            ok = False
    print("mvr-viewer --help: %d options, %s" % (len(options), "each accepted" if ok else "some refused"))
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("source")
    ap.add_argument("build")
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--viewer")
    ap.add_argument("--no-python", action="store_true", help="this build has no Python package")
    ap.add_argument("--python-env", action="append", default=[], metavar="KEY=VALUE",
                    help="for the Python example only (the sanitizer build preloads ASan's runtime)")
    a = ap.parse_args()
    source, build = os.path.abspath(a.source), os.path.abspath(a.build)
    found = examples(os.path.join(source, "README.md"))
    kinds = {"sh": sum(1 for e in found if e[0] == "sh" and not e[3]), "python": sum(1 for e in found if e[0] == "python"),
             "viewer": sum(1 for e in found if e[3])}
    print("README.md: %d examples (%d shell, %d Python, %d viewer)" % (len(found), kinds["sh"], kinds["python"],
                                                                       kinds["viewer"]))
    # the five of README's "Five examples": a marker lost to an edit must not pass unnoticed
    if kinds["sh"] < 3 or kinds["python"] < 1 or kinds["viewer"] < 1:
        print("FAIL: README.md should mark at least 3 shell, 1 Python and 1 viewer example")
        return 1
    work = tempfile.mkdtemp(prefix="mvr_docs_")
    for name, target in (("build", build), ("tests", os.path.join(source, "tests")),
                         ("python", os.path.join(source, "python"))):
        os.symlink(target, os.path.join(work, name))
    fail = 0
    start = time.time()
    for k, (lang, body, files, viewer) in enumerate(found):
        print("example %d (%s%s)" % (k + 1, lang, ", viewer" if viewer else ""))
        ok = True
        if lang == "python":
            probe = subprocess.run([a.python, "-c", "import numpy"], capture_output=True)
            if a.no_python or probe.returncode != 0:
                print("  skipped: %s" % ("this build has no Python package" if a.no_python else
                                         "%s has no numpy" % a.python))
                continue
            env = dict(os.environ, PYTHONPATH=os.path.join(work, "python"), MVR_LIBRARY_DIR=build,
                       PYTHONDONTWRITEBYTECODE="1")
            env.update(kv.split("=", 1) for kv in a.python_env)
            ok = run([a.python, "-c", body], work, env, "%s -c <README's Python example>" % a.python)
        elif viewer:
            if not shutil.which("Xvfb") or not a.viewer:
                print("  skipped: %s" % ("no Xvfb on PATH" if a.viewer else "mvr-viewer is not built"))
                continue
            for i, cmd in enumerate(body):
                if cmd[0] != "build/mvr-viewer":
                    print("FAIL: a viewer example runs build/mvr-viewer, not %s" % cmd[0])
                    ok = False
                    continue
                shot = "out/viewer_%d_%d.png" % (k, i)
                os.makedirs(os.path.join(work, "out"), exist_ok=True)
                xvfb = os.path.join(source, "tests", "run_with_xvfb.sh")
                ok = run([xvfb] + cmd + ["--size", "256x96", "--frames", "2", "--screenshot", shot], work) and ok
                files = files + [shot]
        else:
            for cmd in body:
                if cmd[:2] == ["build/mvr", "render"]:
                    cmd = cmd + FAST
                ok = run(cmd, work) and ok
        for f in files:
            if not os.path.isfile(os.path.join(work, f)):
                print("FAIL: example %d promises %s, which it did not write" % (k + 1, f))
                ok = False
        if not ok:
            print("FAIL: example %d" % (k + 1))
            fail = 1
    if a.viewer and not check_viewer_help(a.viewer):
        fail = 1
    shutil.rmtree(work, ignore_errors=True)
    print("docs_examples: %s in %.1f s" % ("FAILED" if fail else "ok", time.time() - start))
    return fail


if __name__ == "__main__":
    sys.exit(main())
