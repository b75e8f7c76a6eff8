#!/usr/bin/env python3
"""ctest python_mypy: `python3 -m mypy` over the package (python/mvr) with its
configuration (python/mypy.ini): the public API's type hints hold. Debian's
python3-mypy, which scripts/setup installs; where it is missing the test is
skipped (exit 77), except under CI=true, where it fails."""
import importlib.util
import os
import pathlib
import subprocess
import sys

source = pathlib.Path(sys.argv[1]).resolve()
if importlib.util.find_spec("mypy") is None:
    print("python_mypy: %s has no mypy (Debian: python3-mypy, which scripts/setup installs)" % sys.executable)
    sys.exit(1 if os.environ.get("CI") == "true" else 77)
config = source / "python" / "mypy.ini"
cmd = [sys.executable, "-m", "mypy", "--no-incremental"]
if config.exists():
    cmd += ["--config-file", str(config)]
cmd.append(str(source / "python" / "mvr"))
p = subprocess.run(cmd, cwd=str(source), capture_output=True, text=True)
print(p.stdout + p.stderr)
sys.exit(p.returncode)
