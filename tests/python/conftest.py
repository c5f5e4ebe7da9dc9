"""Fixtures of the Python tests (run by `make test` through CTest: /usr/bin/python3 -m pytest, with
PYTHONPATH=build/python and GBLENS_BINARY set). Captures are made here with the gblens binary:
a native one of builtin:temple, a second one that differs, and the committed Blender fixture imported
through builtin:blender-cycles. Everything checked is computed independently of the module."""
import json
import os
import subprocess

import pytest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GBLENS = os.environ.get("GBLENS_BINARY", os.path.join(SOURCE, "build", "gblens"))
SMALL = ["--size", "64x36", "--lights", "6", "--shadow-map-size", "256"]


def run(*args, check=True):
    """Runs the gblens binary; returns (exit code, stdout, stderr)."""
    p = subprocess.run([GBLENS, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"gblens {' '.join(map(str, args))}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def run_json(*args):
    return json.loads(run(*args)[1])


def cli_message(stderr, command):
    """The one line the CLI prints after 'gblens COMMAND: '."""
    lines = [l for l in stderr.splitlines() if l.startswith(f"gblens {command}: ")]
    assert len(lines) == 1, stderr
    return lines[0][len(f"gblens {command}: "):]


@pytest.fixture(scope="session")
def captures(tmp_path_factory):
    """Two native captures of builtin:temple at 64x36 (time 0 and 0.25, primitive ids and stored world
    positions on), one with the default options ("plain") and the Blender fixture imported with its
    shipped layout."""
    root = tmp_path_factory.mktemp("captures")
    a, b, blender, plain = root / "a", root / "b", root / "blender", root / "plain"
    common = [*SMALL, "--primitive-id", "on", "--position", "rgba32f", "--position-space", "world"]
    run("capture", *common, "-o", a)
    run("capture", *common, "--time", "0.25", "-o", b)
    run("capture", *SMALL, "-o", plain)  # the defaults: no primitive ids, positions from depth
    run("import", os.path.join(SOURCE, "tests", "data", "blender", "cycles.exr"), "--layout", "builtin:blender-cycles",
        "-o", blender)
    return {"a": str(a), "b": str(b), "blender": str(blender), "plain": str(plain), "root": root}
