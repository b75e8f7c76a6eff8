"""ctest python_mvr: runs pytest over tests/python with the interpreter CMake
chose (MVR_PYTHON), less test_dask.py; ctest python_dask (run_pytest.py
--dask): test_dask.py alone. numpy and pytest are Debian's python3-numpy and
python3-pytest, Dask's distributed is python3-distributed, which
scripts/setup installs: where they are missing the test is skipped with that
message (exit 77), except under CI=true, where it fails."""
import importlib.util
import os
import sys


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    args = sys.argv[1:]
    dask = "--dask" in args
    if dask:
        args.remove("--dask")
    needs = {"numpy": "python3-numpy", "pytest": "python3-pytest"}
    if dask:
        needs["distributed"] = "python3-distributed"
    missing = [m for m in needs if importlib.util.find_spec(m) is None]
    if missing:
        print("%s: %s has no %s: install %s (scripts/setup does)"
              % ("python_dask" if dask else "python_mvr", sys.executable, " and ".join(missing),
                 " and ".join(needs[m] for m in missing)))
        sys.exit(1 if os.environ.get("CI") == "true" else 77)

    import pytest

    test_dask = os.path.join(here, "test_dask.py")
    where = [test_dask] if dask else [here, "--ignore=" + test_dask]
    sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "-rs"] + where + args))


# guarded: Dask's worker processes are spawned, and a spawned process imports
# the parent's main module (this file) again
if __name__ == "__main__":
    main()
