#!/usr/bin/env python3
"""ctest python_mvr: runs pytest over tests/python with the interpreter CMake
chose (MVR_PYTHON). numpy and pytest are Debian's python3-numpy and
python3-pytest, which scripts/setup installs: where they are missing the test
is skipped with that message (exit 77), except under CI=true, where it fails."""
import importlib.util
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
missing = [m for m in ("numpy", "pytest") if importlib.util.find_spec(m) is None]
if missing:
    print("python_mvr: %s has no %s: install python3-numpy and python3-pytest (scripts/setup does)"
          % (sys.executable, " and ".join(missing)))
    sys.exit(1 if os.environ.get("CI") == "true" else 77)

import pytest  # noqa: E402

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "-rs", here] + sys.argv[1:]))
