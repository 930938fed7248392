"""`tumble.scenes()` and `tumble.integrators()` list what the command line lists;
`tumble.work_precision` measures the order a method is known to have."""

import json

import numpy as np
import pytest

import tumble


def test_scenes_and_integrators_equal_the_command_lines_json(cli):
    assert tumble.scenes() == json.loads(cli("scenes", "--json").stdout)
    assert tumble.integrators() == json.loads(cli("integrators", "--json").stdout)


def test_work_precision_ladder_of_rk4_shows_fourth_order():
    # Classical Runge-Kutta is of order 4: halving the step divides the final error by about
    # 2^4, so log(error) against log(dt) has slope 4 once the step is small (the asymptotic
    # regime) and while round-off is far below.
    frame = tumble.work_precision("driven-hoop", integrators=["rk4"], t_end=2.0, max_seconds=0.05, frame="dict")
    dt, error = frame["dt"], frame["error"]
    resolved = (error > 1e-11) & (error < 1e-4)
    assert resolved.sum() >= 3, (dt, error)
    slope = np.polyfit(np.log(dt[resolved]), np.log(error[resolved]), 1)[0]
    assert 3.7 < slope < 4.3, slope
    assert set(frame["integrator"]) == {"rk4"}
    assert (frame["wall_time_s"] > 0).all()
    assert set(frame["order"]) == {"4"} and (frame["repeats"] > 0).all()


def test_work_precision_rows_have_the_columns_of_the_command_lines_csv(cli, tmp_path):
    # One record type writes work-precision.csv and Python's rows: the same columns, in order.
    cli("work-precision", "free-hoop", "--integrators", "dop853", "--t-end", "1", "--max-seconds", "0.01", "-o", "wp")
    header = (tmp_path / "wp" / "work-precision.csv").read_text().splitlines()[0].split(",")
    frame = tumble.work_precision("free-hoop", integrators=["dop853"], t_end=1.0, max_seconds=0.01, frame="dict")
    assert list(frame) == header
    assert frame["dt"].dtype == np.float64 and np.isnan(frame["dt"]).all()
    assert (frame["tol"] > 0).all() and frame["steps"].dtype == np.int64


def test_work_precision_refuses_a_method_the_scene_does_not_take():
    with pytest.raises(ValueError, match="integrators: `no-such` cannot run scene `driven-hoop`"):
        tumble.work_precision("driven-hoop", integrators=["no-such"])
