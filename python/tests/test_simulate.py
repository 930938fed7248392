"""`tumble.simulate` against `tumble simulate` on the same inputs: the same columns, bit for
bit, and the same run record; the DataFrame views; Parquet output read back by pandas and
polars equal to the CSV."""

import json

import numpy as np
import pytest

import tumble
from conftest import ROOT, floats, read_csv, same_bits

CASES = [
    # (scene, Python keywords, the same as flags)
    ("free-hoop", dict(t_end=2.0), ["--t-end", "2"]),
    (
        "spinning-hoop",
        dict(params={"omega0": 3.5, "alpha0": 2.0}, integrator="dop853", tol=1e-10, t_end=1.5),
        ["--set", "omega0=3.5", "--set", "alpha0=2", "--integrator", "dop853", "--tol", "1e-10", "--t-end", "1.5"],
    ),
    (
        str(ROOT / "scenes" / "dumbbell.toml"),
        dict(at=[0.25, 0.5, 1.0], t_end=1.0),
        ["--at", "0.25,0.5,1", "--t-end", "1"],
    ),
    (
        str(ROOT / "models" / "double-pendulum.toml"),
        dict(params={"theta1_0": 0.3}, integrator="vern9", tol=1e-10, t_end=1.0),
        ["--set", "theta1_0=0.3", "--integrator", "vern9", "--tol", "1e-10", "--t-end", "1"],
    ),
]


@pytest.mark.parametrize(
    "scene,keywords,flags", CASES, ids=["free-hoop", "spinning-hoop-dop853", "dumbbell-file-at", "double-pendulum-model"]
)
def test_simulate_columns_equal_the_command_lines_csv_to_the_last_bit(cli, tmp_path, scene, keywords, flags):
    cli("simulate", scene, *flags, "-o", "run.csv")
    expected = read_csv(tmp_path / "run.csv")
    record = json.loads((tmp_path / "run.csv.json").read_text())
    result = tumble.simulate(scene, **keywords)
    assert result.names == list(expected)
    for name in result.names:
        assert same_bits(result[name], floats(expected[name])), name
    assert result.integrator == record["integrator"]
    assert result.dt == record["dt"] and result.tol == record["tol"]
    assert result.t_end == record["t_end"]
    assert (result.steps, result.evaluations) == (record["steps"], record["evaluations"])
    assert result.max_energy_rel_err == record["max_energy_rel_err"]
    assert result.parameters == record["parameters"]
    assert result.version == record["provenance"]["tumble_version"]
    assert len(result) == record["rows"]


@pytest.mark.parametrize(
    "scene,keywords,flags", CASES, ids=["free-hoop", "spinning-hoop-dop853", "dumbbell-file-at", "double-pendulum-model"]
)
def test_the_simulation_holds_the_record_the_command_line_writes_key_for_key(cli, tmp_path, scene, keywords, flags):
    cli("simulate", scene, *flags, "-o", "run.csv")
    written = json.loads((tmp_path / "run.csv.json").read_text())
    result = tumble.simulate(scene, **keywords)
    # The same keys in the same order, at every level: one record type writes both.
    assert list(result.record) == list(written)
    assert list(result.record["provenance"]) == list(written["provenance"])
    assert list(result.record["error_estimate"]) == list(written["error_estimate"])
    # Every value but how and when it was made (the provenance, the wall time, the file).
    for key, value in written.items():
        if key in ("provenance", "wall_time_s", "csv"):
            continue
        assert result.record[key] == value, key
        if key != "columns":
            assert getattr(result, key) == value, key
    assert result.names == written["columns"]
    assert result.csv == "" and result.wall_time_s > 0


def test_a_model_given_as_text_runs_as_its_file_does_bit_for_bit():
    path = ROOT / "models" / "hoop-two-beads.toml"
    from_file = tumble.simulate(str(path), params={"m2": 0.1}, t_end=1.0)
    from_text = tumble.simulate(path.read_text(), params={"m2": 0.1}, t_end=1.0)
    assert from_text.names == from_file.names
    assert "p_phi" in from_text.names
    for name in from_file.names:
        assert same_bits(from_text[name], from_file[name]), name


def test_dataframes_hold_the_same_columns_as_the_arrays():
    pd = pytest.importorskip("pandas")
    pl = pytest.importorskip("polars")
    result = tumble.simulate("free-hoop", t_end=0.5)
    frame = result.to_pandas()
    assert list(frame.columns) == result.names
    polars_frame = result.to_polars()
    assert polars_frame.columns == result.names
    for name in result.names:
        assert same_bits(frame[name].to_numpy(), result[name])
        assert same_bits(polars_frame[name].to_numpy(), result[name])
    assert isinstance(frame, pd.DataFrame) and isinstance(polars_frame, pl.DataFrame)


@pytest.mark.parametrize("how", [["-o", "run.parquet"], ["--format", "parquet", "-o", "run.out"]])
def test_parquet_trajectory_reads_back_equal_to_the_csv_with_its_record(cli, tmp_path, how):
    pd = pytest.importorskip("pandas")
    pl = pytest.importorskip("polars")
    pq = pytest.importorskip("pyarrow.parquet")
    flags = ["spinning-hoop", "--integrator", "dop853", "--tol", "1e-9", "--t-end", "2"]
    cli("simulate", *flags, "-o", "run.csv")
    cli("simulate", *flags, *how)
    path = tmp_path / how[-1]
    expected = read_csv(tmp_path / "run.csv")
    frame = pd.read_parquet(path)
    polars_frame = pl.read_parquet(path)
    assert list(frame.columns) == list(expected) == polars_frame.columns
    for name in expected:
        assert frame[name].dtype == np.float64
        assert same_bits(frame[name].to_numpy(), floats(expected[name])), name
        assert same_bits(polars_frame[name].to_numpy(), floats(expected[name])), name
    metadata = pq.read_metadata(path).metadata
    record = json.loads(metadata[b"tumble"])
    csv_record = json.loads((tmp_path / "run.csv.json").read_text())
    for key in ["scene", "integrator", "tol", "t_end", "steps", "evaluations", "max_energy_rel_err", "parameters", "columns", "rows"]:
        assert record[key] == csv_record[key], key
