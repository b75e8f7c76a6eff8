"""mvr.dask.render_dataset on a LocalCluster of 2 worker processes (issue 34):
a worker killed mid-run (SIGKILL) -> the run completes, each unit once in
manifest.jsonl, every file byte-identical to one `mvr render --list` process
(the issue's 50 files x 20 views with depth and ids, at 48x48, 200 units of
5 views); a hostile file fails alone, recorded failed with mvr's message; a
worker's later units go to the serve process it started for its first; a
serve process killed mid-run is started again; `import mvr` needs no Dask.

Dask (Debian's python3-distributed) is optional: without it the cluster's
tests are skipped, except under CI=true, where that is a failure. ctest
python_dask runs this file (python_mvr leaves it out)."""
import importlib.util
import json
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from dask_scenes import write_scenes  # noqa: E402

HAVE_DASK = importlib.util.find_spec("distributed") is not None
if HAVE_DASK:
    import distributed

    import mvr
    import mvr.dask


def need_dask():
    if HAVE_DASK:
        return
    why = "%s has no Dask (distributed): install python3-distributed (scripts/setup does)" % sys.executable
    if os.environ.get("CI") == "true":
        pytest.fail(why, pytrace=False)
    pytest.skip(why)


def test_dask_is_optional():
    """`import mvr` imports no Dask; `import mvr.dask` without it says what to install."""
    blocker = """
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("dask", "distributed"):
            raise ImportError("No module named %r" % name)
sys.meta_path.insert(0, Block())
import mvr
assert not [m for m in sys.modules if m.split(".")[0] in ("dask", "distributed")]
try:
    import mvr.dask
except ImportError as e:
    print(e)
else:
    raise SystemExit("mvr.dask imported without Dask")
"""
    p = subprocess.run([sys.executable, "-c", blocker], capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "install python3-distributed" in p.stdout, p.stdout


# the "done when": 50 files x 20 views, depth and ids, small layers
FILES, VIEWS, SIZE, UNIT_VIEWS = 50, 20, (48, 48), 5
OPTIONS = dict(layout="sphere", views=VIEWS, size=SIZE, outputs=("depth", "ids"))
EXCLUDED = (".mvr-run", "manifest.jsonl")


@pytest.fixture(scope="module")
def client():
    need_dask()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(2)
        yield c


def tree(root):
    """{relative path: bytes} of every file under root but the run's own."""
    root = pathlib.Path(root)
    out = {}
    for p in sorted(root.rglob("*")):
        rel = p.relative_to(root).as_posix()
        if p.is_file() and rel.split("/")[0] not in EXCLUDED:
            out[rel] = p.read_bytes()
    return out


def assert_same_tree(got, want):
    assert sorted(got) == sorted(want), (sorted(set(got) ^ set(want))[:10], len(got), len(want))
    differ = [k for k in want if got[k] != want[k]]
    assert not differ, "%d files differ from one process's: %s" % (len(differ), differ[:10])


def reference(files, out):
    """One `mvr render --list` process over the same files and options."""
    listing = out.parent / (out.name + ".list")
    listing.write_text("".join(os.path.abspath(f) + "\n" for f in files))
    args = [mvr.dask.find_cli(), "render", "--list", str(listing), "--out", str(out), "--quiet",
            "--layout", "sphere", "--views", str(VIEWS), "--size", "%dx%d" % SIZE, "--outputs", "depth,ids"]
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return tree(out)


def serve_pids():
    """On a worker: its serve processes' pids."""
    return [s.proc.pid for s in mvr.dask._SERVERS.values()]


def alive(pid):
    """pid runs (a zombie, dead but not yet reaped, does not count)."""
    try:
        status = pathlib.Path("/proc/%d/status" % pid).read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status


def manifest_units(result):
    assert result.manifest is not None, result.merge_message
    lines = result.manifest.read_text().splitlines()
    return [json.loads(line) for line in lines]


def test_worker_killed_mid_run_same_bytes_as_one_process(client, out_dir):
    files = write_scenes(out_dir / "scenes", FILES)
    run_dir = out_dir / "dask"
    units_dir = run_dir / ".mvr-run" / "units"
    pids = client.run(os.getpid)  # {worker address: pid}
    address, victim = sorted(pids.items())[0]
    state = {}

    def kill_when_records_exist():
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and "result" not in state:
            n = len(list(units_dir.glob("*.json"))) if units_dir.is_dir() else 0
            if n >= 4:
                state["serve_pids"] = client.run(serve_pids, workers=[address])[address]
                os.kill(victim, signal.SIGKILL)
                state["records_at_kill"] = n
                return
            time.sleep(0.01)

    killer = threading.Thread(target=kill_when_records_exist)
    killer.start()
    try:
        state["result"] = result = mvr.dask.render_dataset(files, run_dir, client=client,
                                                           unit_views=UNIT_VIEWS, **OPTIONS)
    finally:
        state.setdefault("result", None)
        killer.join()
    units = [u["unit"] for u in result.plan["units"]]
    assert len(units) == FILES * VIEWS // UNIT_VIEWS
    # the kill happened while units were left to do
    assert "records_at_kill" in state and state["records_at_kill"] < len(units), state
    assert victim not in client.run(os.getpid).values()
    # the killed worker's serve process died with it (PR_SET_PDEATHSIG; stdin EOF)
    assert state["serve_pids"], "the killed worker had no serve process yet"
    for pid in state["serve_pids"]:
        assert not alive(pid), "serve process %d outlived its worker" % pid
    assert result.ok, (result.failed[:3], result.merge_message)
    manifest = manifest_units(result)
    assert [r["unit"] for r in manifest] == units  # each unit once, in unit order
    assert all(r["status"] == "done" for r in manifest)
    assert [r["unit"] for r in result.records] == units
    assert_same_tree(tree(run_dir), reference(files, out_dir / "reference"))


def test_hostile_file_fails_alone(client, out_dir):
    files = write_scenes(out_dir / "scenes", 4)
    hostile = json.loads(files[2].read_text())
    hostile["accessors"][2]["count"] = 100000  # indices far past their buffer view
    files[2].write_text(json.dumps(hostile))
    result = mvr.dask.render_dataset(files, out_dir / "dask", client=client, **OPTIONS)
    by_file = {}
    for r in result.records:
        by_file.setdefault(os.path.basename(r.get("file", "")), []).append(r)
    bad = by_file.pop(files[2].name)
    assert [r["status"] for r in bad] == ["failed"]
    assert "accessor 2 reads past the end of bufferView 2" in bad[0]["message"], bad
    assert sorted(by_file) == sorted(f.name for f in files if f != files[2])
    assert all(r["status"] == "done" for rs in by_file.values() for r in rs)
    assert result.failed == bad and not result.ok
    # --merge names it, and the manifest holds every unit once, the failed one with its message
    assert result.merge_returncode == 1 and files[2].name in result.merge_message, result.merge_message
    manifest = manifest_units(result)
    assert [r["unit"] for r in manifest] == [u["unit"] for u in result.plan["units"]]
    assert [r for r in manifest if r["status"] != "done"] == bad
    # another file list into the same directory is another run's: refused before any task
    with pytest.raises(mvr.Error, match="another run"):
        mvr.dask.render_dataset(files[:2], out_dir / "dask", client=client, **OPTIONS)
    # the good files' views are all there
    for f in files:
        if f != files[2]:
            assert len(list((out_dir / "dask" / f.stem).glob("view_*.png"))) == VIEWS


def test_worker_keeps_one_serve_process(client, out_dir):
    files = write_scenes(out_dir / "scenes", 8)
    result = mvr.dask.render_dataset(files, out_dir / "dask", client=client, unit_views=UNIT_VIEWS, **OPTIONS)
    assert result.ok, (result.failed[:3], result.merge_message)
    n_units = len(result.records)
    assert n_units == 8 * VIEWS // UNIT_VIEWS
    servers = [s for infos in result.servers.values() for s in infos]
    # one serve process a worker, started once, answering all its units
    assert 1 <= len(servers) <= 2 and all(s["starts"] == 1 for s in servers), result.servers
    assert sum(s["units"] for s in servers) == n_units
    assert max(s["units"] for s in servers) >= 2
    workers = {r["worker"] for r in result.records}
    assert len(workers) <= 2


def test_serve_process_killed_is_started_again(client, out_dir):
    """A worker's serve process that dies (SIGKILL) is started again for the
    unit it was given; the run completes, each unit once."""
    files = write_scenes(out_dir / "scenes", 8)
    units_dir = out_dir / "dask" / ".mvr-run" / "units"
    state = {}

    def kill_a_serve_process():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and "result" not in state:
            if units_dir.is_dir() and len(list(units_dir.glob("*.json"))) >= 4:
                pids = [p for ps in client.run(serve_pids).values() for p in ps]
                if pids:
                    os.kill(pids[0], signal.SIGKILL)
                    state["killed"] = pids[0]
                    return
            time.sleep(0.01)

    killer = threading.Thread(target=kill_a_serve_process)
    killer.start()
    try:
        state["result"] = result = mvr.dask.render_dataset(files, out_dir / "dask", client=client,
                                                           unit_views=UNIT_VIEWS, **OPTIONS)
    finally:
        state.setdefault("result", None)
        killer.join()
    assert "killed" in state
    assert result.ok, (result.failed[:3], result.merge_message)
    assert [r["unit"] for r in manifest_units(result)] == [u["unit"] for u in result.plan["units"]]
    starts = sorted(s["starts"] for infos in result.servers.values() for s in infos)
    assert starts[-1] == 2 and starts.count(2) == 1, result.servers
