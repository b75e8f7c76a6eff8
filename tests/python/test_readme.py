"""The README's Python example runs as written (from the source tree's root)
and prints one line per view."""
import os
import re
import subprocess
import sys

from conftest import ROOT


def readme_example():
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1, "README.md: one Python example expected"
    return blocks[0]


def test_readme_example_runs():
    code = readme_example()
    assert len(code.strip().splitlines()) <= 10
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"))
    p = subprocess.run([sys.executable, "-c", code], cwd=str(ROOT), capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    lines = [line for line in p.stdout.splitlines() if line.startswith("(240, 320, 4)")]
    assert len(lines) == 12, p.stdout
