"""Refused inputs: the same reasons as the command line (named as Python names the argument),
TypeError/ValueError naming the key, and run failures with their time and state."""

import pytest

import tumble
from conftest import error_of


def test_an_unknown_scene_is_refused_with_the_command_lines_message(cli):
    with pytest.raises(ValueError) as raised:
        tumble.simulate("no-such-scene")
    assert str(raised.value) == error_of(cli("simulate", "no-such-scene", check=False))


@pytest.mark.parametrize("key,value", [("a", -1.0), ("no_such_parameter", 1.0)])
def test_a_bad_parameter_is_refused_with_the_command_lines_reason_naming_the_key(cli, key, value):
    with pytest.raises(ValueError) as raised:
        tumble.simulate("free-hoop", params={key: value})
    message = error_of(cli("simulate", "free-hoop", "--set", f"{key}={value:g}", check=False))
    assert message.startswith(f"--set {key}={value:g}: ")
    assert str(raised.value) == f"params['{key}']: " + message.split(": ", 1)[1]


@pytest.mark.parametrize(
    "keywords,flags,flag,keyword",
    [
        (dict(dt=-0.01), ["--dt", "-0.01"], "--dt -0.01", "dt=-0.01"),
        (dict(t_end=-1.0), ["--t-end", "-1"], "--t-end -1", "t_end=-1"),
        (dict(integrator="no-such-method"), ["--integrator", "no-such-method"], "--integrator", "integrator"),
        (dict(dt=0.5), ["--dt", "0.5"], "--dt 0.5 or smaller", "dt=0.5 or smaller"),
    ],
    ids=["negative-step", "negative-horizon", "unknown-integrator", "coarse-step"],
)
def test_a_bad_run_option_is_refused_with_the_command_lines_reason(cli, keywords, flags, flag, keyword):
    with pytest.raises(ValueError) as raised:
        tumble.simulate("spinning-hoop", params={"omega0": 40.0}, **keywords)
    message = error_of(cli("simulate", "spinning-hoop", "--set", "omega0=40", *flags, check=False))
    python = str(raised.value)
    # The one difference: options are named as each caller names them.
    words = {flag: keyword, "--integrator dop853": "integrator='dop853'", "pass --allow-coarse-step": "pass allow_coarse_step=True"}
    if keywords.get("dt") == 0.5:
        # The suggested step is computed, not given: rename only the flags.
        words = {"--dt ": "dt=", "--integrator dop853": "integrator='dop853'", "pass --allow-coarse-step": "pass allow_coarse_step=True"}
    for cli_words, python_words in words.items():
        message = message.replace(cli_words, python_words)
    assert python == message


def test_a_failed_run_raises_simulation_error_with_the_command_lines_message_and_state(cli):
    with pytest.raises(tumble.SimulationError) as raised:
        tumble.simulate("spinning-hoop", integrator="dop853", tol=1e-12, t_end=10.0, max_steps=20)
    message = error_of(cli("simulate", "spinning-hoop", "--integrator", "dop853", "--tol", "1e-12", "--t-end", "10", "--max-steps", "20", "-o", "run.csv", check=False))
    assert str(raised.value) == message
    assert "state: phi = " in message


def test_a_bad_scene_file_is_refused_with_the_command_lines_message(cli, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('scene = "free-hoop"\n[parameters]\nomega0 = "fast"\n')
    with pytest.raises(ValueError) as raised:
        tumble.simulate(path)
    assert str(raised.value) == error_of(cli("simulate", path, check=False))


def test_a_bad_sweep_file_is_refused_with_the_command_lines_message(cli, tmp_path):
    path = tmp_path / "bad.sweep.toml"
    path.write_text('scene = "free-hoop"\n[run]\ndt = 0.01\nt_end = 1.0\nintegrator = "gauss8"\n[[axes]]\nparameter = "omega"\nrange = [1.0, 2.0]\ncount = 2\n')
    with pytest.raises(ValueError) as raised:
        tumble.sweep(path, progress=False)
    assert str(raised.value) == error_of(cli("sweep", path, "-o", "out", check=False))


def test_values_of_the_wrong_type_raise_type_error_naming_the_key():
    with pytest.raises(TypeError, match=r"params\['omega0'\]: expected a number, got str"):
        tumble.simulate("free-hoop", params={"omega0": "fast"})
    with pytest.raises(TypeError, match="dt"):
        tumble.simulate("free-hoop", dt="small")
    with pytest.raises(TypeError, match="no_such_keyword"):
        tumble.simulate("free-hoop", no_such_keyword=1)
    with pytest.raises(ValueError, match="dt and tol"):
        tumble.simulate("free-hoop", dt=0.01, tol=1e-9)
