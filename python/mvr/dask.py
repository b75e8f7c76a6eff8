"""Render a dataset on a Dask cluster: mvr.dask.render_dataset(files, out, ...).

The run is the `mvr render` CLI's: the client asks `mvr render ARGS --out DIR
--run-plan` for the run's units (file x view range x frame range, decided up
front), submits one Dask task per unit, gathers the units' records as they
complete, then runs `mvr render --merge DIR`, which checks every unit and
writes the run-level files (cameras.json, transforms.json, ids.json, ...)
and DIR/manifest.jsonl. The directory is the one the CLI writes
(docs/guide.md, "Dask"; the run directory: "Sharding").

On a worker, a task hands its unit number to a long-lived `mvr render ARGS
--out DIR --serve` process that the worker process keeps for the run (one
EGL context, renderer and program cache for its life), so units after a
worker's first pay no start-up. A unit is committed by its record
(DIR/.mvr-run/units/<id>.json): a task that Dask runs again after its worker
died renders nothing when the unit is already done, and a half-written unit
is rendered again. A unit that fails (a hostile file) comes back as a
failed record with mvr's message and is not retried.

Dask is optional: `import mvr` never imports it; this module needs Dask's
distributed (Debian: python3-distributed).
"""
from __future__ import annotations

import collections
import ctypes
import hashlib
import json
import os
import pathlib
import selectors
import shutil
import signal
import subprocess
import threading
import time
import uuid
from dataclasses import dataclass, field
from typing import Any, Deque, Dict, Iterable, List, Optional, Sequence, Tuple, Union

try:
    import distributed  # type: ignore[import]
except ImportError as _e:  # pragma: no cover - depends on the machine
    raise ImportError("mvr.dask needs Dask's distributed package: install python3-distributed "
                      "(Debian; scripts/setup does) or `pip install distributed` (%s)" % _e) from _e

from ._common import Error

__all__ = ["RunResult", "find_cli", "render_dataset"]

PathLike = Union[str, "os.PathLike[str]"]
Record = Dict[str, Any]

DEFAULT_TIMEOUT = 3600.0


# ------------------------------------------------------------------ the CLI

def find_cli(mvr_cli: Optional[PathLike] = None) -> str:
    """The `mvr` CLI's path: mvr_cli when given, else $MVR_CLI, else the
    package's own mvr/_bin/mvr (a wheel's), else `mvr` next to the libmvr.so
    the package loaded (the build tree), else `mvr` on PATH. Raises
    FileNotFoundError naming where it looked."""
    tried = []
    for why, cand in _cli_candidates(mvr_cli):
        if cand is None:
            continue
        tried.append("%s (%s)" % (cand, why))
        path = pathlib.Path(cand)
        if path.is_file() and os.access(path, os.X_OK):
            return str(path.resolve())
        if why in ("mvr_cli", "$MVR_CLI"):
            raise FileNotFoundError("mvr.dask: %s=%s is not an executable file" % (why, cand))
    on_path = shutil.which("mvr")
    if on_path:
        return on_path
    tried.append("mvr on PATH")
    raise FileNotFoundError("mvr.dask: the mvr CLI was not found; looked at " + "; ".join(tried) +
                            ". Pass mvr_cli= or set MVR_CLI to the `mvr` executable.")


def _cli_candidates(mvr_cli: Optional[PathLike]) -> List[Tuple[str, Optional[str]]]:
    if mvr_cli is not None:
        return [("mvr_cli", os.fspath(mvr_cli))]
    env = os.environ.get("MVR_CLI")
    if env:
        return [("$MVR_CLI", env)]
    here = pathlib.Path(__file__).resolve().parent
    out: List[Tuple[str, Optional[str]]] = [("the package's own CLI", str(here / "_bin" / "mvr"))]
    from ._lib import LIBRARY_DIR  # the folder libmvr.so.0 came from (None: the loader's search)
    if LIBRARY_DIR is not None:
        out.append(("next to the loaded libmvr", str(pathlib.Path(LIBRARY_DIR) / "mvr")))
    return out


def _run_args(list_file: str, layout: Optional[str], views: Optional[int], size: Optional[Tuple[int, int]],
              outputs: Sequence[str], unit_views: Optional[int], extra_args: Sequence[str]) -> List[str]:
    """`mvr render` arguments of the run, less --out and the mode."""
    args = ["render", "--list", list_file, "--quiet"]
    if layout is not None:
        args += ["--layout", str(layout)]
    if views is not None:
        args += ["--views", str(int(views))]
    if size is not None:
        args += ["--size", "%dx%d" % (int(size[0]), int(size[1]))]
    aovs = [o for o in outputs if o != "color"]  # the colour image is always written
    if aovs:
        args += ["--outputs", ",".join(aovs)]
    if unit_views is not None:
        args += ["--unit-views", str(int(unit_views))]
    return args + [str(a) for a in extra_args]


# ------------------------------------------------------------------ the worker side

def _set_parent_death_signal() -> None:
    """preexec_fn: the server gets SIGKILL when the thread that started it
    (which lives exactly as long as the server: _Server's keeper) dies with
    its process; Linux only, silently skipped elsewhere."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


class _ServerDied(Exception):
    pass


class _Server:
    """One `mvr render ARGS --out DIR --serve` process: unit numbers in on
    stdin, one JSON record a line out on stdout, human output on stderr
    (its last lines kept for messages)."""

    def __init__(self, cmd: List[str]) -> None:
        self.cmd = cmd
        self.stderr: Deque[str] = collections.deque(maxlen=40)
        self.buffer = b""
        self.units = 0
        started = threading.Event()
        box: List[Any] = []

        def keeper() -> None:
            # the process is started from a thread that waits for it: the
            # parent-death signal fires when this thread ends, which is when
            # the server has exited or the worker process died
            try:
                box.append(subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                            stderr=subprocess.PIPE, bufsize=0,
                                            preexec_fn=_set_parent_death_signal))
            except BaseException as e:  # noqa: B902 - handed to the caller
                box.append(e)
                return
            finally:
                started.set()
            box[0].wait()

        threading.Thread(target=keeper, name="mvr-serve-keeper", daemon=True).start()
        started.wait()
        if isinstance(box[0], BaseException):
            raise box[0]
        self.proc: subprocess.Popen[bytes] = box[0]
        self.drain = threading.Thread(target=self._drain_stderr, name="mvr-serve-stderr", daemon=True)
        self.drain.start()

    def _drain_stderr(self) -> None:
        assert self.proc.stderr is not None
        for line in iter(self.proc.stderr.readline, b""):
            self.stderr.append(line.decode("utf-8", "replace").rstrip("\n"))

    def alive(self) -> bool:
        return self.proc.poll() is None

    def message(self) -> str:
        tail = "; ".join(s for s in self.stderr if s.strip())
        code = self.proc.poll()
        what = "exited with status %s" % code if code is not None else "stopped answering"
        return "mvr --serve %s%s" % (what, (": " + tail) if tail else "")

    def render(self, unit: int, timeout: Optional[float]) -> Record:
        """Sends one unit number; returns its record (raises _ServerDied when
        the process ends first, TimeoutError after timeout seconds)."""
        assert self.proc.stdin is not None and self.proc.stdout is not None
        try:
            self.proc.stdin.write(b"%d\n" % unit)
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError) as e:
            raise _ServerDied(str(e)) from e
        deadline = None if timeout is None else time.monotonic() + timeout
        fd = self.proc.stdout.fileno()
        with selectors.DefaultSelector() as sel:
            sel.register(fd, selectors.EVENT_READ)
            while b"\n" not in self.buffer:
                left = None if deadline is None else deadline - time.monotonic()
                if left is not None and left <= 0:
                    raise TimeoutError("unit %d: no answer from mvr --serve in %g s" % (unit, timeout or 0))
                if not sel.select(left):
                    continue
                chunk = os.read(fd, 65536)
                if not chunk:
                    self.proc.wait()
                    self.drain.join(timeout=5)  # its last words, for the message
                    raise _ServerDied(self.message())
                self.buffer += chunk
        line, _, self.buffer = self.buffer.partition(b"\n")
        self.units += 1
        try:
            record = json.loads(line)
        except ValueError as e:
            raise _ServerDied("mvr --serve answered unit %d with no JSON record: %r" % (unit, line[:200])) from e
        if not isinstance(record, dict):
            raise _ServerDied("mvr --serve answered unit %d with %r" % (unit, line[:200]))
        return record

    def close(self) -> None:
        if self.proc.stdin is not None:
            try:
                self.proc.stdin.close()
            except OSError:
                pass
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


# the worker process's servers, by the run's command line, and how many
# times each was started (render_dataset reports both: RunResult.servers)
_SERVERS: Dict[Tuple[str, ...], _Server] = {}
_STARTS: Dict[Tuple[str, ...], int] = {}
_LOCK = threading.Lock()


def _close_run(out: str) -> List[Dict[str, Any]]:
    """Ends this process's serve processes of the run into `out` (stdin
    EOF); returns what each did (pid, units answered, starts)."""
    with _LOCK:
        keys = [k for k in _SERVERS if k[-5:-3] == ("--out", out)]
        closing = [(k, _SERVERS.pop(k), _STARTS.pop(k)) for k in keys]
    info = []
    for k, s, starts in closing:
        s.close()
        info.append({"pid": s.proc.pid, "units": s.units, "starts": starts})
    return info


def _failed(unit: int, message: str, worker: str) -> Record:
    return {"unit": unit, "id": "u%06d" % unit, "status": "failed", "message": message, "worker": worker}


def _render_unit(cli: str, args: Tuple[str, ...], out: str, unit: int, timeout: Optional[float]) -> Record:
    """The Dask task: renders unit `unit` of the run in this worker process's
    serve process (started on its first unit, restarted once if it died)."""
    try:
        name = str(distributed.get_worker().name)
    except ValueError:  # not on a worker (client.run, a test): this process
        name = "pid%d" % os.getpid()
    if not os.path.isfile(cli):  # the client's path is not on this machine
        cli = find_cli()
    cmd = (cli,) + tuple(args) + ("--out", out, "--serve", "--worker", name)
    for attempt in range(2):
        with _LOCK:
            server = _SERVERS.get(cmd)
            if server is None or not server.alive():
                server = _Server(list(cmd))
                _SERVERS[cmd] = server
                _STARTS[cmd] = _STARTS.get(cmd, 0) + 1
        try:
            return server.render(unit, timeout)
        except TimeoutError as e:
            server.proc.kill()
            return _failed(unit, str(e), name)
        except _ServerDied as e:
            server.proc.kill()
            if attempt == 1:
                return _failed(unit, str(e), name)
    raise AssertionError("unreachable")


# ------------------------------------------------------------------ the client side

@dataclass
class RunResult:
    """What render_dataset did: every unit's record (in unit order; a unit
    whose task itself failed gets a failed record with Dask's error), the run
    directory, the manifest DIR/manifest.jsonl (failed units' records in
    it too; None when the merge wrote none), the merge's exit status (1
    when a unit failed) and messages, the plan (`--run-plan`'s JSON), and
    by Dask worker address the serve processes its worker process ran for
    the run (pid, units answered, how many times it was started: 1 unless
    one died), which the run ends."""
    out: pathlib.Path
    records: List[Record]
    manifest: Optional[pathlib.Path]
    merge_returncode: int
    merge_message: str
    plan: Dict[str, Any] = field(default_factory=dict)
    servers: Dict[str, List[Dict[str, Any]]] = field(default_factory=dict)

    @property
    def done(self) -> List[Record]:
        """The records of the units that were rendered."""
        return [r for r in self.records if r.get("status") == "done"]

    @property
    def failed(self) -> List[Record]:
        """The records of the units that failed, each with mvr's message."""
        return [r for r in self.records if r.get("status") != "done"]

    @property
    def ok(self) -> bool:
        """Every unit done and the merge wrote the run-level files."""
        return not self.failed and self.merge_returncode == 0


def _plan(cli: str, args: Sequence[str], out: str) -> Dict[str, Any]:
    p = subprocess.run([cli] + list(args) + ["--out", out, "--run-plan"], capture_output=True, text=True)
    if p.returncode != 0:
        raise Error("mvr render --run-plan failed (exit %d): %s" % (p.returncode, (p.stderr or p.stdout).strip()))
    try:
        plan = json.loads(p.stdout)
    except ValueError as e:
        raise Error("mvr render --run-plan printed no JSON plan: %r" % p.stdout[:200]) from e
    if not isinstance(plan, dict) or not isinstance(plan.get("units"), list):
        raise Error("mvr render --run-plan printed a plan with no unit list")
    return plan


def _unit_number(unit: Any) -> int:
    if isinstance(unit, dict):
        for k in ("unit", "number"):
            if k in unit:
                return int(unit[k])
        return int(str(unit["id"]).lstrip("u"))
    return int(unit)


def _write_list(out: pathlib.Path, files: Iterable[PathLike]) -> str:
    """The run's file list (absolute paths: workers elsewhere have another
    working directory) as DIR/.mvr-run/files-<its sha256>.txt: another
    list is another file, so a directory of another run keeps its own (and
    the CLI refuses the new run's plan there)."""
    lines = [os.path.abspath(os.fspath(f)) for f in files]
    if not lines:
        raise ValueError("render_dataset: no files")
    for f in lines:
        if "\n" in f or f.lstrip().startswith("#"):
            raise ValueError("render_dataset: %r cannot be a line of a --list file" % f)
    run_dir = out / ".mvr-run"
    run_dir.mkdir(parents=True, exist_ok=True)
    text = "".join(f + "\n" for f in lines)
    path = run_dir / ("files-%s.txt" % hashlib.sha256(text.encode("utf-8")).hexdigest()[:16])
    if not path.is_file():
        tmp = run_dir / ("%s.%d" % (path.name, os.getpid()))
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    return str(path)


def render_dataset(files: Iterable[PathLike], out: PathLike, *, layout: Optional[str] = None,
                   views: Optional[int] = None, size: Optional[Tuple[int, int]] = None,
                   outputs: Sequence[str] = (), client: Optional[Any] = None, unit_views: Optional[int] = None,
                   extra_args: Sequence[str] = (), mvr_cli: Optional[PathLike] = None,
                   timeout: Optional[float] = DEFAULT_TIMEOUT, retries: int = 3) -> RunResult:
    """Renders glTF files into the run directory `out` on a Dask cluster,
    as `mvr render --list FILES --out OUT [options]` would in one process.

    files: the glTF/GLB paths (each to OUT/<its name>/ when more than one).
    layout, views, size, outputs: `--layout`, `--views`, `--size WxH`,
    `--outputs` (e.g. ("depth", "ids"); "color" is always written).
    unit_views: `--unit-views`: views per unit (default: a file per unit).
    extra_args: more `mvr render` options, as the CLI spells them.
    client: a distributed.Client; None starts a LocalCluster of one worker
    process per core (one thread each) for the call and closes it after.
    mvr_cli: the `mvr` executable (default: find_cli()).
    timeout: seconds one unit may take before it is recorded failed.
    retries: Dask's retries of a unit's task that raised (the serve process
    could not be started there); a task whose worker process died is given
    to another worker by Dask's scheduler (distributed.scheduler.allowed-
    failures times, default 3). A unit that fails in mvr is recorded
    failed, not retried.

    Returns a RunResult; raises mvr.Error when the run cannot be planned
    (a bad option, or OUT holds another run's plan)."""
    cli = find_cli(mvr_cli)
    out_dir = pathlib.Path(os.path.abspath(os.fspath(out)))
    list_file = _write_list(out_dir, files)
    args = tuple(_run_args(list_file, layout, views, size, outputs, unit_views, extra_args))
    plan = _plan(cli, args, str(out_dir))
    units = [_unit_number(u) for u in plan["units"]]

    cluster = None
    if client is None:
        cluster = distributed.LocalCluster(n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
    try:
        records = _gather(client, cli, args, str(out_dir), units, plan, timeout, retries)
        servers = client.run(_close_run, str(out_dir), on_error="ignore")
    finally:
        if cluster is not None:
            client.close()
            cluster.close()

    manifest = out_dir / "manifest.jsonl"
    if manifest.is_file():  # an earlier call's: the merge writes it again
        manifest.unlink()
    merge = subprocess.run([cli, "render", "--merge", str(out_dir), "--quiet"], capture_output=True, text=True)
    return RunResult(out=out_dir, records=records, manifest=manifest if manifest.is_file() else None,
                     merge_returncode=merge.returncode, merge_message=(merge.stderr + merge.stdout).strip(),
                     plan=plan, servers=servers)


def _gather(client: Any, cli: str, args: Tuple[str, ...], out: str, units: List[int], plan: Dict[str, Any],
            timeout: Optional[float], retries: int) -> List[Record]:
    # a fresh key per call: a later call over the same plan (resuming) must
    # run its tasks, not find an earlier call's results
    tag = "%s-%s" % (str(plan.get("plan_hash", "run"))[:12], uuid.uuid4().hex[:8])
    futures = {client.submit(_render_unit, cli, args, out, u, timeout, key="mvr-%s-u%06d" % (tag, u),
                             pure=False, retries=retries): u for u in units}
    records: Dict[int, Record] = {}
    for fut in distributed.as_completed(list(futures)):
        u = futures[fut]
        try:
            records[u] = fut.result()
        except Exception as e:  # the task itself failed (KilledWorker: its workers kept dying)
            records[u] = _failed(u, "Dask: %s: %s" % (type(e).__name__, e), "")
    return [records[u] for u in units]
