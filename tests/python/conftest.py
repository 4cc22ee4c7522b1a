"""Shared helpers of the Python package's tests: the project's CLI (the C library's reference
results) and its source tree."""
import csv
import json
import os
import subprocess

import numpy as np
import pytest

CLI = os.environ.get("GEOMINT_CLI", os.path.join(os.environ.get("GEOMINT_BUILD_DIR", "build"),
                                                 "geomint"))
SOURCE = os.environ.get("GEOMINT_SOURCE_DIR",
                        os.path.dirname(os.path.dirname(os.path.dirname(__file__))))


def cli_run(tmp_path, problem, method, dt, steps=None, t_end=None, sets=(), every=1):
    """`geomint run ... --out FILE.csv --json`: (JSON summary, CSV rows as an array)."""
    out = tmp_path / "run.csv"
    cmd = [CLI, "run", problem, "--method", method, "--dt", repr(dt), "--every", str(every),
           "--out", str(out), "--json", "--quiet"]
    cmd += ["--steps", str(steps)] if steps is not None else ["--t-end", repr(t_end)]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    with open(out) as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    return json.loads(p.stdout), header, data


@pytest.fixture
def cli():
    if not os.path.exists(CLI):
        pytest.fail(f"the geomint CLI is not at {CLI} (set GEOMINT_CLI)")
    return cli_run
