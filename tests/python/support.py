"""What the Python tests share: where the sources, the mechflow command and a
temporary folder are (CTest gives them in the environment), and the command
run as a subprocess for the reference numbers."""

import csv
import os
import subprocess
import tempfile

import numpy as np

SOURCE_DIR = os.environ.get("MECHFLOW_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("MECHFLOW_BINARY", "mechflow")
EXAMPLES = os.path.join(SOURCE_DIR, "diagrams", "examples")


def example(name):
    return os.path.join(EXAMPLES, name)


def temp_dir(prefix):
    base = os.environ.get("TEST_TMPDIR") or None
    if base:
        os.makedirs(base, exist_ok=True)
    return tempfile.mkdtemp(prefix=prefix, dir=base)


def mechflow(*args, check=True):
    """Runs the mechflow command; its CompletedProcess (text)."""
    done = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"mechflow {' '.join(args)} exited {done.returncode}: {done.stderr}")
    return done


def read_csv(path):
    """(header, float matrix) of a CSV file mechflow wrote; numbers read back exactly."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]], dtype=float)


def cli_results(diagram, *args):
    """`mechflow run` of `diagram` with `args`: (header, rows) of its results CSV."""
    out = temp_dir("cli_run_")
    mechflow("run", diagram, "--out", out, "--no-plot", "--no-animate", "--quiet", *args)
    name = [f for f in os.listdir(out) if f.endswith(".csv") and not f.endswith(".units.csv")]
    assert len(name) == 1, name
    return read_csv(os.path.join(out, name[0]))


def write(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path
