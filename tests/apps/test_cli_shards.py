#!/usr/bin/env python3
"""ctest: sharded runs of mvr render (issue 34; docs/guide.md, "Sharded runs").

  python3 test_cli_shards.py MVR PEERS_DIR OUT

- shards 1/3, 2/3, 3/3 of two files (--unit-views 2 of 5 views, so each file is split into units
  that cross the renderer's chunks; --outputs depth,ids, --colmap, --split) run one after another,
  then --merge: OUT/shards equals one plain run's directory byte for byte (all but .mvr-run/ and
  manifest.jsonl); manifest.jsonl lists every unit of the plan once, in order, and each listed
  file's size and sha256 are the file's (hashlib);
- frames split too: 3 views x 3 frames of an animated camera in units of 2 views x 2 frames,
  2 shards + merge == one plain run (frame 0's depth step and cameras in every unit);
- a shard killed (SIGKILL) once its first record is written, then run again with --resume: the
  killed run's records are unchanged, the resumed run renders exactly the units without one, and
  after --merge the directory equals the plain run's;
- a file with a bad accessor and a truncated .glb among good files (no --views: the planner loads
  each file to count its views, so each bad file is one unit): their units are recorded failed
  with mvr's message, the good ones done; the shard exits 1; --merge exits 1 naming both, writes
  the good files' run-level files and says so (not the bad ones');
- --serve: unit numbers on stdin, one JSON record a line on stdout; a done unit asked for again is
  answered from its record, not rendered again; a number out of range is answered with an error;
- refused (exit 2): another plan in the same directory (named), --shard 0/3, 4/3, x/y, --video,
  --stats and --readback sync with --shard, --merge with another option; --run-plan prints the
  plan and renders nothing.
Python's standard library only."""
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time

MVR, PEERS, OUT = sys.argv[1:4]
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args, stdin=None):
    return subprocess.run([MVR, "render"] + [str(a) for a in args], capture_output=True, text=True, input=stdin)


def tree(root):
    """{relative path: bytes} of every file under root but .mvr-run/ and manifest.jsonl."""
    files = {}
    for base, dirs, names in os.walk(root):
        dirs[:] = [d for d in dirs if d != ".mvr-run"]
        for n in names:
            rel = os.path.relpath(os.path.join(base, n), root)
            if rel != "manifest.jsonl":
                with open(os.path.join(base, n), "rb") as f:
                    files[rel] = f.read()
    return files


def same_tree(a, b, what):
    ta, tb = tree(a), tree(b)
    only = sorted(set(ta) ^ set(tb))
    differ = sorted(k for k in set(ta) & set(tb) if ta[k] != tb[k])
    expect(not only and not differ and ta, "%s: only in one: %s; differ: %s" % (what, only[:8], differ[:8]))


def plan_units(d):
    with open(os.path.join(d, ".mvr-run", "plan.json")) as f:
        return json.load(f)["units"]


def records(d):
    units = os.path.join(d, ".mvr-run", "units")
    out = {}
    for n in sorted(os.listdir(units)) if os.path.isdir(units) else []:
        if n.endswith(".json"):
            with open(os.path.join(units, n), "rb") as f:
                out[n] = f.read()
    return out


a, b = os.path.join(PEERS, "spheres.gltf"), os.path.join(PEERS, "textured.gltf")
common = [a, b, "--size", "64x48", "--layout", "orbit", "--views", "5", "--outputs", "depth,ids", "--colmap",
          "--split", "0.6,0.4", "--no-progress", "--quiet"]
plain = os.path.join(OUT, "plain")
r = run(*common, "--out", plain)
expect(r.returncode == 0, "plain run: exit %d: %s" % (r.returncode, r.stderr))
for f in ("spheres/contact_sheet.png", "spheres/transforms.json", "spheres/colmap/images.txt",
          "spheres/annotations/instances.json", "textured/ids.json"):
    expect(os.path.exists(os.path.join(plain, f)), "plain run wrote %s" % f)

# ---------------------------------------------------------------- 3 shards, then the merge
shards = os.path.join(OUT, "shards")
for k in (1, 2, 3):
    r = run(*common, "--unit-views", "2", "--shard", "%d/3" % k, "--out", shards)
    expect(r.returncode == 0, "shard %d/3: exit %d: %s" % (k, r.returncode, r.stderr))
expect(not os.path.exists(os.path.join(shards, "spheres", "contact_sheet.png")),
       "a shard writes no file-level file (the merge does)")
r = run("--merge", shards)
expect(r.returncode == 0, "merge: exit %d: %s" % (r.returncode, r.stderr))
same_tree(plain, shards, "3 shards + merge == one plain run")
units = plan_units(shards)
expect(len(units) == 6, "2 files x 5 views in units of 2 views: 6 units (got %d)" % len(units))
with open(os.path.join(shards, "manifest.jsonl")) as f:
    manifest = [json.loads(line) for line in f]
expect([m["unit"] for m in manifest] == list(range(len(units))), "the manifest lists every unit once, in order")
listed = set()
for m in manifest:
    expect(m["status"] == "done" and m["id"] == "u%06d" % m["unit"] and m["worker"], "record fields: %s" % m)
    for f in m["files"]:
        with open(os.path.join(shards, f["path"]), "rb") as fh:
            data = fh.read()
        expect(len(data) == f["bytes"] and hashlib.sha256(data).hexdigest() == f["sha256"],
               "manifest: %s's size and sha256 are the file's" % f["path"])
        expect(f["path"] not in listed, "manifest: %s listed once" % f["path"])
        listed.add(f["path"])
expect("spheres/view_0004.png" in listed and "textured/depth_0003.npy" in listed, "the units' files listed")

# ---------------------------------------------------------------- frames split too (--unit-frames)
anim = os.path.join(OUT, "anim.gltf")
subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "make_animated_gltf.py"),
                anim, "--dolly"], check=True)
fargs = [anim, "--size", "64x48", "--views", "3", "--animation", "dolly", "--frames", "3", "--fps", "4",
         "--outputs", "depth", "--no-progress", "--quiet"]
r = run(*fargs, "--out", os.path.join(OUT, "frames_plain"))
expect(r.returncode == 0, "frames, plain: exit %d: %s" % (r.returncode, r.stderr))
for k in (1, 2):
    r = run(*fargs, "--unit-views", "2", "--unit-frames", "2", "--shard", "%d/2" % k, "--out",
            os.path.join(OUT, "frames_shards"))
    expect(r.returncode == 0, "frames, shard %d/2: exit %d: %s" % (k, r.returncode, r.stderr))
expect(len(plan_units(os.path.join(OUT, "frames_shards"))) == 4, "2 view ranges x 2 frame ranges: 4 units")
r = run("--merge", os.path.join(OUT, "frames_shards"), "-q")
expect(r.returncode == 0, "frames, merge: exit %d: %s" % (r.returncode, r.stderr))
same_tree(os.path.join(OUT, "frames_plain"), os.path.join(OUT, "frames_shards"),
          "views x frames units (a camera the animation moves, depth PNG steps of frame 0) == one plain run")

# ---------------------------------------------------------------- SIGKILL, then --resume
killed = os.path.join(OUT, "killed")
args = common + ["--unit-views", "1", "--shard", "1/1", "--out", killed]
p = subprocess.Popen([MVR, "render"] + args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 60
while time.time() < deadline and p.poll() is None and not records(killed):
    time.sleep(0.005)
p.send_signal(signal.SIGKILL)
p.wait()
before = records(killed)
total = len(plan_units(killed))
expect(0 < len(before) < total, "the shard was killed after its first record, before its last (%d of %d)" %
       (len(before), total))
r = run(*[x for x in args if x != "--quiet"], "--resume")
expect(r.returncode == 0, "resume: exit %d: %s" % (r.returncode, r.stderr))
rendered = sorted(line.split()[2] for line in r.stdout.splitlines() if line.endswith(")") and " done (" in line)
missing = sorted(n[:-5] for n in ("u%06d.json" % u for u in range(total)) if n not in before)
expect(rendered == missing, "resume renders exactly the units without a record: %s, not %s" % (rendered, missing))
expect("%d skipped" % len(before) in r.stdout, "resume: the summary counts the skipped units: %s" % r.stdout)
after = records(killed)
expect(all(after[n] == before[n] for n in before), "resume: the killed run's records are unchanged")
r = run("--merge", killed, "--quiet")
expect(r.returncode == 0, "merge after resume: exit %d: %s" % (r.returncode, r.stderr))
same_tree(plain, killed, "killed + --resume + merge == one plain run")

# ---------------------------------------------------------------- hostile files fail alone
bad = os.path.join(OUT, "bad_accessor.gltf")
with open(bad, "w") as f:
    json.dump({"asset": {"version": "2.0"},
               "buffers": [{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAAAA=="}],
               "bufferViews": [{"buffer": 0, "byteLength": 4}],
               "accessors": [{"bufferView": 0, "componentType": 5126, "count": 100, "type": "VEC3"}],
               "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
               "scenes": [{"nodes": [0]}]}, f)
truncated = os.path.join(OUT, "truncated.glb")
with open(truncated, "wb") as f:
    f.write(b"glTF\x02\x00\x00\x00\xff\xff\x00\x00JSON")
hostile = os.path.join(OUT, "hostile")
hargs = [a, bad, truncated, b, "--size", "64x48", "--layout", "stereo", "--outputs", "ids", "--no-progress",
         "--out", hostile]
r = run(*hargs, "--shard", "1/1")
expect(r.returncode == 1, "a shard with failed units exits 1 (got %d): %s" % (r.returncode, r.stderr))
units = plan_units(hostile)
expect(len(units) == 4 and units[1]["views"] == [0, 0] and units[2]["views"] == [0, 0],
       "a file that does not load while planning is one unit of no views: %s" % units)
recs = {n: json.loads(t) for n, t in records(hostile).items()}
status = [recs["u%06d.json" % u]["status"] for u in range(4)]
expect(status == ["done", "failed", "failed", "done"], "hostile: only the bad files' units fail: %s" % status)
expect("accessor" in recs["u000001.json"].get("message", "") and "bad_accessor.gltf" in recs["u000001.json"]["message"],
       "the failed record holds mvr's message: %s" % recs["u000001.json"].get("message"))
expect("truncated.glb" in recs["u000002.json"].get("message", ""), "the truncated file's message names it: %s" %
       recs["u000002.json"].get("message"))
expect("u000001 failed" in r.stderr and "u000002 failed" in r.stderr, "the failures named by unit: %s" % r.stderr)
r = run("--merge", hostile)
expect(r.returncode == 1, "merge with failed units exits 1 (got %d)" % r.returncode)
expect("u000001" in r.stderr and bad in r.stderr and truncated in r.stderr and "written for 2 of 4 files" in r.stderr,
       "merge names the failed units and files: %s" % r.stderr)
expect(os.path.exists(os.path.join(hostile, "spheres", "contact_sheet.png")) and
       os.path.exists(os.path.join(hostile, "textured", "ids.json")), "merge writes the good files' run-level files")
with open(os.path.join(hostile, "manifest.jsonl")) as f:
    expect(len(f.readlines()) == 4, "the manifest holds the failed records too")

# ---------------------------------------------------------------- --serve
served = os.path.join(OUT, "served")
sargs = [a, "--size", "64x48", "--layout", "orbit", "--views", "4", "--unit-views", "2", "--no-progress",
         "--out", served, "--serve", "--worker", "w7"]
r = run(*sargs, stdin="0\n1\n0\n9\n")
lines = r.stdout.splitlines()
expect(r.returncode == 0 and len(lines) == 4, "serve: one line per unit asked (exit %d): %s" % (r.returncode, lines))
if len(lines) == 4:
    first, second, again, wrong = (json.loads(x) for x in lines)
    expect(first["unit"] == 0 and second["unit"] == 1 and first["status"] == "done" and first["worker"] == "w7",
           "serve: the records: %s %s" % (first, second))
    expect(lines[2] == lines[0], "serve: a done unit is answered with its record")
    expect(wrong["status"] == "error", "serve: a number outside the plan is an error line: %s" % wrong)
expect(r.stderr.count("u000000 done") == 1, "serve: unit 0 rendered once: %s" % r.stderr)
r = run(*sargs, stdin="1\n")
expect(r.returncode == 0 and json.loads(r.stdout)["unit"] == 1 and "done (" not in r.stderr,
       "serve again: a done unit is not rendered again: %s" % r.stderr)

# ---------------------------------------------------------------- refusals
r = run(*common[:6], "6", *common[7:], "--unit-views", "2", "--shard", "1/3", "--out", shards)
expect(r.returncode == 2 and "holds another run's plan" in r.stderr and shards in r.stderr,
       "another plan in the same DIR: exit 2 naming it (got %d): %s" % (r.returncode, r.stderr))
for bad_shard in ("0/3", "4/3", "x/y", "3", "1/0"):
    r = run(a, "--out", os.path.join(OUT, "refused"), "--shard", bad_shard)
    expect(r.returncode == 2 and "--shard" in r.stderr, "--shard %s: exit 2 (got %d)" % (bad_shard, r.returncode))
for extra in (["--video", "v.mp4", "--frames", "2"], ["--stats", "s.json"], ["--readback", "sync"]):
    r = run(a, "--out", os.path.join(OUT, "refused"), "--shard", "1/2", *extra)
    expect(r.returncode == 2 and extra[0] in r.stderr, "%s with --shard: exit 2 naming it (got %d): %s" %
           (extra[0], r.returncode, r.stderr))
r = run("--merge", shards, "--views", "3")
expect(r.returncode == 2, "--merge with another option: exit 2 (got %d)" % r.returncode)
planned = os.path.join(OUT, "planned")
r = run(a, "--size", "64x48", "--views", "4", "--unit-views", "3", "--out", planned, "--run-plan")
expect(r.returncode == 0 and json.loads(r.stdout)["plan_hash"] and len(json.loads(r.stdout)["units"]) == 2,
       "--run-plan prints the plan: %s" % r.stdout[:200])
expect(sorted(os.listdir(planned)) == [".mvr-run"], "--run-plan renders nothing")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("ok")
