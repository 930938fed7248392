"""Shared helpers: the command-line binary the results are compared with, and readers of its
outputs that keep every bit (CSV numbers are shortest round-trip forms: ``float()`` reads them
back exactly)."""

import csv
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def tumble_bin() -> pathlib.Path:
    """The `tumble` binary: $TUMBLE_BIN, else the workspace's debug build."""
    path = pathlib.Path(os.environ.get("TUMBLE_BIN", ROOT / "target" / "debug" / "tumble"))
    if not path.is_file():
        pytest.fail(f"{path}: build the command line first (cargo build --bin tumble)")
    return path


@pytest.fixture()
def cli(tumble_bin, tmp_path):
    """Runs `tumble ARGS...` in a temporary folder; returns the completed process."""

    def run(*args, check=True):
        done = subprocess.run(
            [str(tumble_bin), *map(str, args)],
            cwd=tmp_path,
            capture_output=True,
            text=True,
        )
        if check and done.returncode != 0:
            raise AssertionError(f"tumble {' '.join(map(str, args))}: {done.stderr}")
        return done

    return run


def error_of(done) -> str:
    """The message a failed command printed (`error: MESSAGE` on stderr)."""
    assert done.returncode != 0, done.stderr
    text = done.stderr.strip()
    assert text.startswith("error: "), text
    return text[len("error: ") :]


def read_csv(path):
    """A CSV file as {column: list of fields}, in order."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [r[k] for r in body] for k, name in enumerate(header)}


def floats(fields):
    """CSV fields as float64, empty fields as NaN."""
    return np.array([float(x) if x != "" else np.nan for x in fields], dtype=np.float64)


def same_bits(a, b) -> bool:
    """Whether two float64 arrays are equal bit for bit (NaNs included)."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    b = np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))
