#!/usr/bin/env python3
"""ctest: several SCENE files in one mvr render run (arguments and --list FILE).

  python3 test_cli_files.py MVR PEERS_DIR OUT

- two good files and a broken one: without --keep-going the run stops at the broken one (the
  first good file rendered into OUT/<stem>/, the second not attempted), exits non-zero and its
  summary names the broken file; with --keep-going both good files are rendered, the exit is
  still non-zero and the summary names the broken file;
- each file's images and cameras.json are byte-equal to a run of that file alone, and its --stats
  (in its own directory) name the same scene, views, size and materials;
- a renderer that cannot be made stops the run even with --keep-going;
- --list: '#' comments, blank lines, blanks around paths and CRLF ends; files whose names repeat
  get their place in the run (a_1, a_3); one file given by --list keeps the one-file layout
  (OUT/view_0000.png); a list that names nothing, or cannot be read, is refused (exit 2).
Python's standard library only."""
import json
import os
import shutil
import subprocess
import sys

MVR, PEERS, OUT = sys.argv[1:4]
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args, env=None):
    return subprocess.run([MVR, "render"] + [str(a) for a in args] + ["--size", "64x48"], capture_output=True,
                          text=True, env=env)


def read(path):
    with open(path, "rb") as f:
        return f.read()


good_a = os.path.join(PEERS, "spheres.gltf")
good_b = os.path.join(PEERS, "textured.gltf")
broken = os.path.join(OUT, "broken.glb")
with open(broken, "wb") as f:
    f.write(b"glTF\x02\x00\x00\x00\xff\xff\xff\x7f not a real binary glTF")
names = ["view_0000.png", "view_0001.png", "contact_sheet.png", "cameras.json", "transforms.json"]

# each file alone, as today (one file: the one-file layout)
alone = {}
for path in (good_a, good_b):
    stem = os.path.splitext(os.path.basename(path))[0]
    out = os.path.join(OUT, "alone_" + stem)
    r = run(path, "--out", out, "--stats", os.path.join(out, "stats.json"), "--quiet")
    expect(r.returncode == 0, "%s alone: exit %d: %s" % (stem, r.returncode, r.stderr))
    alone[stem] = out

# stops at the first failure
out = os.path.join(OUT, "stop")
r = run(good_a, broken, good_b, "--out", out, "--quiet")
expect(r.returncode != 0, "stop: a failed file makes the exit non-zero (got %d)" % r.returncode)
expect(os.path.exists(os.path.join(out, "spheres", "view_0000.png")), "stop: the first file is rendered")
expect(not os.path.exists(os.path.join(out, "textured")), "stop: the file after the failure is not attempted")
expect("mvr_gltf" in r.stderr and "broken.glb" in r.stderr, "stop: mvr's message names the file: %s" % r.stderr)
expect("1 of 3 files rendered, 1 failed: " + broken in r.stderr and "1 not attempted" in r.stderr,
       "stop: the summary: %s" % r.stderr)
expect(not os.path.exists(os.path.join(out, "broken")), "stop: no empty directory for the failed file")

# --keep-going: both good files, the same bytes as alone
out = os.path.join(OUT, "keep")
r = run(good_a, broken, good_b, "--out", out, "--keep-going", "--stats", "stats.json")
expect(r.returncode != 0, "keep-going: still a non-zero exit (got %d)" % r.returncode)
expect("2 of 3 files rendered, 1 failed: " + broken in r.stderr, "keep-going: the summary: %s" % r.stderr)
expect("not attempted" not in r.stderr, "keep-going: every file attempted")
expect(r.stdout.count("mvr render: ") == 2, "keep-going: a summary per rendered file: %s" % r.stdout)
for stem in ("spheres", "textured"):
    differ = [n for n in names if not os.path.exists(os.path.join(out, stem, n)) or
              read(os.path.join(out, stem, n)) != read(os.path.join(alone[stem], n))]
    expect(not differ, "keep-going: %s differs from its run alone in %s" % (stem, differ))
    try:
        many = json.load(open(os.path.join(out, stem, "stats.json")))
        one = json.load(open(os.path.join(alone[stem], "stats.json")))
        # not the view or material path, passes, draws and texture groups: with auto, the one
        # renderer's tuner goes on measuring across files and may pick another path than a
        # one-frame run (the same pixels either way)
        expect(all(many[k] == one[k] for k in ("scene", "views", "width", "height")),
               "keep-going: %s's stats as alone" % stem)
    except (OSError, ValueError, KeyError) as e:
        expect(False, "keep-going: %s's stats.json: %s" % (stem, e))

# no renderer at all (a bad MVR_VIEW_PATH): nothing more can run, even with --keep-going
r = run(good_a, good_b, "--keep-going", "--out", os.path.join(OUT, "fatal"), "--quiet",
        env=dict(os.environ, MVR_VIEW_PATH="bogus"))
expect(r.returncode == 2 and "MVR_VIEW_PATH=bogus" in r.stderr and "1 not attempted (nothing can render" in r.stderr,
       "fatal: exit %d: %s" % (r.returncode, r.stderr))

# --list: comments, blanks, CRLF, repeated names, together with an argument
copy_dir = os.path.join(OUT, "copy")
os.makedirs(copy_dir)
for n in ("spheres.gltf", "spheres.bin"):
    shutil.copy(os.path.join(PEERS, n), copy_dir)
listing = os.path.join(OUT, "files.txt")
with open(listing, "w", newline="") as f:
    f.write("# the peers\r\n\r\n   %s  \r\n%s\r\n# a copy, the same name\r\n%s\n" %
            (good_a, good_b, os.path.join(copy_dir, "spheres.gltf")))
out = os.path.join(OUT, "listed")
r = run(good_b, "--list", listing, "--out", out, "--quiet")
expect(r.returncode == 0, "list: exit %d: %s" % (r.returncode, r.stderr))
dirs = sorted(os.listdir(out)) if os.path.isdir(out) else []
expect(dirs == ["spheres_2", "spheres_4", "textured_1", "textured_3"], "list: directories %s" % dirs)
if dirs == ["spheres_2", "spheres_4", "textured_1", "textured_3"]:
    expect(read(os.path.join(out, "spheres_2", "view_0000.png")) == read(os.path.join(out, "spheres_4", "view_0000.png")),
           "list: the copy renders as the original")
    expect(read(os.path.join(out, "textured_3", "view_0001.png")) ==
           read(os.path.join(alone["textured"], "view_0001.png")), "list: textured as alone")

# one file by --list: the one-file layout
one = os.path.join(OUT, "one.txt")
with open(one, "w") as f:
    f.write("# just one\n%s\n" % good_a)
out = os.path.join(OUT, "one")
r = run("--list", one, "--out", out, "--quiet")
expect(r.returncode == 0 and os.path.exists(os.path.join(out, "view_0000.png")), "one listed file: OUT/view_0000.png")
expect(not os.path.exists(os.path.join(out, "spheres")), "one listed file: no subdirectory")

# lists refused
empty = os.path.join(OUT, "empty.txt")
with open(empty, "w") as f:
    f.write("# nothing here\n\n")
r = run("--list", empty)
expect(r.returncode == 2 and "names no file" in r.stderr, "an empty list: %d %s" % (r.returncode, r.stderr))
r = run("--list", os.path.join(OUT, "no_such.txt"))
expect(r.returncode == 2 and "cannot open it" in r.stderr, "a missing list: %s" % r.stderr)
with open(os.path.join(OUT, "nul.txt"), "wb") as f:
    f.write(b"a.gltf\nb\x00.gltf\n")
r = run("--list", os.path.join(OUT, "nul.txt"))
expect(r.returncode == 2 and "line 2" in r.stderr and "NUL" in r.stderr, "a NUL in a list: %s" % r.stderr)
r = run("--demo", "cube", "--list", listing)
expect(r.returncode == 2 and "--demo" in r.stderr, "--demo with --list: %s" % r.stderr)

print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
