"""Figures from Python are the command line's files: `Simulation.plot` draws the same PNG and
SVG, byte for byte, as `tumble simulate --plot` for the same run (the run is deterministic, to
the last bit), and `tumble.plot` redraws a saved sweep folder into the files `tumble sweep`
and `tumble plot` write."""

import pathlib

import pytest

import tumble
from test_sweep import SWEEP_TOML

RUN = ["free-hoop", "--integrator", "gauss8", "--dt", "0.01", "--t-end", "2"]


@pytest.mark.parametrize("ext", ["png", "svg"])
def test_simulation_plot_is_the_command_lines_figure_byte_for_byte(cli, tmp_path, ext):
    cli("simulate", *RUN, "-o", "run.csv", "--plot", f"cli.{ext}")
    run = tumble.simulate("free-hoop", integrator="gauss8", dt=0.01, t_end=2.0)
    run.plot(tmp_path / f"py.{ext}")
    cli_bytes = (tmp_path / f"cli.{ext}").read_bytes()
    py_bytes = (tmp_path / f"py.{ext}").read_bytes()
    assert len(cli_bytes) > 1000
    assert py_bytes == cli_bytes
    # The saved CSV redrawn from Python: the same file again.
    tumble.plot(tmp_path / "run.csv", tmp_path / f"again.{ext}")
    assert (tmp_path / f"again.{ext}").read_bytes() == cli_bytes


def test_figure_options_reach_the_figure_as_on_the_command_line(cli, tmp_path):
    cli("simulate", *RUN, "--plot", "cli.png", "--figure-size", "single", "--font-size", "9")
    run = tumble.simulate("free-hoop", integrator="gauss8", dt=0.01, t_end=2.0)
    run.plot(tmp_path / "py.png", figure_size="single", font_size=9)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


def test_plot_redraws_a_sweep_folder_as_the_sweep_drew_it(cli, tmp_path):
    (tmp_path / "small.sweep.toml").write_text(SWEEP_TOML)
    cli("sweep", "small.sweep.toml", "-o", "s", "--check", "off")
    tumble.plot(tmp_path / "s", tmp_path / "map.png")
    assert (tmp_path / "map.png").read_bytes() == (tmp_path / "s" / "tilt-map.png").read_bytes()
    tumble.plot(tmp_path / "s", tmp_path / "slices.svg", figure="slices")
    cli("plot", "s", "--figure", "slices", "-o", "cli-slices.svg")
    assert (tmp_path / "slices.svg").read_bytes() == (tmp_path / "cli-slices.svg").read_bytes()


def test_bad_plot_arguments_are_refused_naming_them(tmp_path):
    run = tumble.simulate("free-hoop", t_end=0.1, check=False)
    with pytest.raises(ValueError, match="png, .svg or .pdf"):
        run.plot(tmp_path / "run.jpg")
    with pytest.raises(ValueError, match="svg_text"):
        run.plot(tmp_path / "run.svg", svg_text="outline")
    with pytest.raises(ValueError, match="no such file or folder"):
        tumble.plot(tmp_path / "missing", tmp_path / "x.png")
    assert not any(pathlib.Path(tmp_path).iterdir())
