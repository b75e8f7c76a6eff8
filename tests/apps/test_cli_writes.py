#!/usr/bin/env python3
"""ctest: the files mvr render and mvr bench write fail loudly on a full disk, and never stay half written.

  python3 test_cli_writes.py MVR OUT

- render --stats /dev/full (ENOSPC on every write): exit 1, the message names /dev/full;
- a disk that fills while stats.json is written (RLIMIT_FSIZE between the run's other files and
  stats.json, SIGXFSZ ignored so the write fails with EFBIG): exit 1, the message names stats.json,
  the stats.json already there is left as it was, and no temporary is left behind;
- the same while cameras.json is written (the limit between the images and cameras.json): exit 1
  naming cameras.json, no partial cameras.json;
- bench with plot.gp a link to /dev/full: exit 1, the message names plot.gp (gnuplot is not run on
  a script that was not written whole);
- bench with the disk filling while results.json is written: exit 1 naming results.json, none
  left behind.
The limits are measured from an unhindered run of the same command, not assumed.
Python's standard library only."""
import os
import resource
import shutil
import signal
import subprocess
import sys

MVR, OUT = sys.argv[1:3]
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
failures = []
RENDER = ["render", "--demo", "cube", "--views", "1", "--size", "8x8", "--quiet"]
BENCH = ["bench", "--demo", "cube", "--views", "1", "--size", "8x8", "--frames", "1", "--rounds", "1", "--warmup",
         "0", "--matrix", "quick", "--quiet"]


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(args, fsize=None):
    """mvr with args; fsize: the largest file it may write (RLIMIT_FSIZE), SIGXFSZ ignored so a
    write past it fails with EFBIG instead of killing the process."""
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
    # its own process group, so a hung child (gnuplot reading a script that never ends) goes too
    p = subprocess.Popen([MVR] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True, preexec_fn=limit if fsize else None)
    try:
        out, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return subprocess.CompletedProcess(args, -1, "", "timed out after 120 s")
    return subprocess.CompletedProcess(args, p.returncode, out, err)


def sizes(folder):
    return {name: os.path.getsize(os.path.join(folder, name)) for name in os.listdir(folder)}


def hidden(folder):
    """temporaries (.NAME.tmp...) left in folder"""
    return [name for name in os.listdir(folder) if name.startswith(".")]


def between(base, name, before):
    """a limit above every file in before and below name's size, or None"""
    low = max(base[n] for n in before)
    return (low + base[name]) // 2 if base[name] > low + 1 else None


# --stats to a device that is always full
r = run(RENDER + ["--out", os.path.join(OUT, "full"), "--stats", "/dev/full"])
expect(r.returncode == 1 and "cannot write /dev/full" in r.stderr,
       "--stats /dev/full: exit %d, %r" % (r.returncode, r.stderr))

# what an unhindered run writes, and how large
base_dir = os.path.join(OUT, "render_base")
r = run(RENDER + ["--out", base_dir, "--stats", os.path.join(base_dir, "stats.json")])
expect(r.returncode == 0, "the unhindered render: %d %s" % (r.returncode, r.stderr))
base = sizes(base_dir)

# the disk fills while stats.json is written; the old stats.json stays
fsize = between(base, "stats.json", [n for n in base if n != "stats.json"])
expect(fsize is not None, "stats.json is the largest file of the run: %s" % base)
if fsize:
    folder = os.path.join(OUT, "stats_limited")
    os.makedirs(folder)
    stats = os.path.join(folder, "stats.json")
    with open(stats, "w") as f:
        f.write('{"old": true}\n')
    r = run(RENDER + ["--out", folder, "--stats", stats], fsize)
    expect(r.returncode == 1 and "cannot write %s" % stats in r.stderr and "File too large" in r.stderr,
           "stats.json past the file size limit (%d bytes): exit %d, %r" % (fsize, r.returncode, r.stderr))
    with open(stats) as f:
        kept = f.read()
    expect(kept == '{"old": true}\n', "the stats.json that was there is kept whole: %r" % kept[:80])
    expect(not hidden(folder), "no temporary left: %s" % hidden(folder))

# the disk fills while cameras.json is written (after the images, before transforms.json)
images = [n for n in base if n.endswith(".png")]
fsize = between(base, "cameras.json", images)
expect(fsize is not None, "cameras.json is larger than the images: %s" % base)
if fsize:
    folder = os.path.join(OUT, "cameras_limited")
    r = run(RENDER + ["--out", folder], fsize)
    expect(r.returncode == 1 and "cannot write %s" % os.path.join(folder, "cameras.json") in r.stderr,
           "cameras.json past the limit (%d bytes): exit %d, %r" % (fsize, r.returncode, r.stderr))
    expect(os.path.isdir(folder) and "cameras.json" not in os.listdir(folder) and not hidden(folder),
           "no partial cameras.json nor temporary: %s" % (os.listdir(folder) if os.path.isdir(folder) else None))

# bench: plot.gp on a full device
folder = os.path.join(OUT, "bench_full")
os.makedirs(folder)
os.symlink("/dev/full", os.path.join(folder, "plot.gp"))
r = run(BENCH + ["--out", folder])
expect(r.returncode == 1 and "cannot write %s" % os.path.join(folder, "plot.gp") in r.stderr
       and "No space left on device" in r.stderr, "bench plot.gp on /dev/full: exit %d, %r" % (r.returncode, r.stderr))
expect("plot.png" not in os.listdir(folder), "gnuplot is not run on an unwritten plot.gp")

# bench: the disk fills while results.json is written
base_dir = os.path.join(OUT, "bench_base")
r = run(BENCH + ["--out", base_dir])
expect(r.returncode == 0, "the unhindered bench: %d %s" % (r.returncode, r.stderr))
base = sizes(base_dir)
before = [n for n in base if n.endswith((".csv", ".dat", ".gp")) or n in ("reference.png",)]
fsize = between(base, "results.json", before) if "results.json" in base and before else None
expect(fsize is not None, "results.json is larger than the files bench writes itself: %s" % base)
if fsize:
    folder = os.path.join(OUT, "bench_limited")
    r = run(BENCH + ["--out", folder], fsize)
    expect(r.returncode == 1 and "cannot write %s" % os.path.join(folder, "results.json") in r.stderr,
           "results.json past the limit (%d bytes): exit %d, %r" % (fsize, r.returncode, r.stderr))
    expect(os.path.isdir(folder) and "results.json" not in os.listdir(folder) and not hidden(folder),
           "no partial results.json nor temporary: %s" % (os.listdir(folder) if os.path.isdir(folder) else None))

print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
