"""`tumble.sweep` against `tumble sweep` on the same sweep: the DataFrame equals results.csv
(numbers bit for bit, undefined metrics as NaN, status and reason as text); `--format parquet`
writes results.parquet, which pandas and polars read back equal to results.csv."""

import json

import numpy as np
import pytest

import tumble
from conftest import floats, read_csv, same_bits

# A small grid on the free hoop: 3 x 2 points, 2 s each.
SWEEP = {
    "scene": "free-hoop",
    "parameters": {"m": 0.1},
    "run": {"integrator": "gauss8", "dt": 0.01, "t_end": 2.0},
    "axes": [
        {"parameter": "omega0", "range": [1.0, 4.0], "count": 3},
        {"parameter": "alpha0", "range": [0.5, 1.5], "count": 2},
    ],
    "metrics": {
        "record": ["max_tilt", "final_tilt", "time_tilt_exceeds", "max_energy_rel_err"],
        "tilt_threshold": 0.2,
    },
}

SWEEP_TOML = """scene = "free-hoop"

[parameters]
m = 0.1

[run]
integrator = "gauss8"
dt = 0.01
t_end = 2.0

[[axes]]
parameter = "omega0"
range = [1.0, 4.0]
count = 3

[[axes]]
parameter = "alpha0"
range = [0.5, 1.5]
count = 2

[metrics]
record = ["max_tilt", "final_tilt", "time_tilt_exceeds", "max_energy_rel_err"]
tilt_threshold = 0.2
"""


def assert_equal_to_csv(columns, expected):
    """`columns` ({name: array}) equals a results.csv read by `read_csv`."""
    assert list(columns) == list(expected)
    for name, fields in expected.items():
        got = np.asarray(columns[name])
        if name in ("status", "reason"):
            assert [str(x) for x in got] == fields, name
        else:
            assert same_bits(got.astype(np.float64), floats(fields)), name


@pytest.mark.parametrize("source", ["dict", "file"])
def test_sweep_dataframe_equals_the_command_lines_results_csv(cli, tmp_path, source):
    pytest.importorskip("pandas")
    (tmp_path / "small.sweep.toml").write_text(SWEEP_TOML)
    cli("sweep", "small.sweep.toml", "-o", "cli", "--threads", "2", "--check", "off")
    expected = read_csv(tmp_path / "cli" / "results.csv")
    spec = SWEEP if source == "dict" else tmp_path / "small.sweep.toml"
    frame = tumble.sweep(spec, threads=2, progress=False)
    assert len(frame) == 6
    assert frame["index"].dtype == np.int64
    assert_equal_to_csv({c: frame[c].to_numpy() for c in frame.columns}, expected)
    assert frame.attrs["points"] == 6 and frame.attrs["failed"] == 0


def test_sweep_output_folder_holds_the_same_results_csv_and_resumes(cli, tmp_path):
    (tmp_path / "small.sweep.toml").write_text(SWEEP_TOML)
    cli("sweep", "small.sweep.toml", "-o", "cli", "--check", "off")
    seen = []
    tumble.sweep(SWEEP, output=tmp_path / "py", progress=lambda *p: seen.append(p), frame="dict")
    assert seen and seen[-1] == (6, 6, 0)
    assert (tmp_path / "py" / "results.csv").read_bytes() == (tmp_path / "cli" / "results.csv").read_bytes()
    again = tumble.sweep(SWEEP, output=tmp_path / "py", resume=True, progress=False, frame="dict")
    assert list(again["index"]) == list(range(6))


def test_parquet_results_read_back_equal_to_results_csv_with_the_manifest(cli, tmp_path):
    pd = pytest.importorskip("pandas")
    pl = pytest.importorskip("polars")
    pq = pytest.importorskip("pyarrow.parquet")
    (tmp_path / "small.sweep.toml").write_text(SWEEP_TOML)
    cli("sweep", "small.sweep.toml", "-o", "cli", "--check", "off", "--format", "parquet")
    expected = read_csv(tmp_path / "cli" / "results.csv")
    path = tmp_path / "cli" / "results.parquet"
    frame = pd.read_parquet(path)
    assert_equal_to_csv({c: frame[c].to_numpy() for c in frame.columns}, expected)
    polars_frame = pl.read_parquet(path)
    # polars keeps an undefined metric as null; as floats it is NaN, as in the CSV.
    assert_equal_to_csv(
        {c: polars_frame[c].to_numpy() if polars_frame[c].dtype != pl.Float64 else polars_frame[c].fill_null(np.nan).to_numpy() for c in polars_frame.columns},
        expected,
    )
    schema = pq.read_schema(path)
    assert str(schema.field("index").type) == "int64"
    assert str(schema.field("max_tilt").type) == "double" and schema.field("max_tilt").nullable
    assert str(schema.field("status").type) == "string"
    manifest = json.loads(pq.read_metadata(path).metadata[b"tumble"])
    assert manifest == json.loads((tmp_path / "cli" / "manifest.json").read_text())


def test_sweep_dict_with_a_value_of_the_wrong_type_names_its_key():
    bad = dict(SWEEP, run={"integrator": "gauss8", "dt": object(), "t_end": 2.0})
    with pytest.raises(TypeError, match=r"run\.dt"):
        tumble.sweep(bad, progress=False)
