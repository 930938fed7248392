"""Models from Python as dicts (laid out like a model file) and with SymPy expressions: the
same numbers as the model file, bit for bit where the text is the same; SymPy's printing in
the model language checked against the file's run to round-off and by closed forms."""

import numpy as np
import pytest

import tumble
from conftest import ROOT, same_bits

# models/spherical-pendulum.toml, as a dict.
PENDULUM = {
    "model": {"name": "spherical-pendulum", "summary": "a point mass on a rod about a fixed pivot"},
    "parameters": {
        "m": {"default": 1.0, "unit": "kg", "domain": "positive"},
        "l": {"default": 1.0, "unit": "m", "domain": "positive"},
        "g": {"default": 9.81, "unit": "m/s^2", "domain": "non-negative"},
        "theta0": {"default": 0.6, "unit": "rad"},
        "phi_dot0": {"default": 3.447618564366689, "unit": "rad/s"},
        "theta_dot0": {"default": 0.0, "unit": "rad/s"},
    },
    "coordinates": {
        "theta": {"initial": "theta0", "rate": "theta_dot0"},
        "phi": {"initial": "0", "rate": "phi_dot0"},
    },
    "points": {
        "bob": {
            "mass": "m",
            "position": ["l*sin(theta)*cos(phi)", "l*sin(theta)*sin(phi)", "-l*cos(theta)"],
        }
    },
    "lagrangian": {"gravity": ["0", "0", "-g"]},
    "outputs": {"height": "-l*cos(theta)"},
    "run": {"integrator": "gauss8", "dt": 0.01, "t_end": 10.0},
}


def test_a_model_given_as_a_dict_runs_as_its_file_does_bit_for_bit():
    from_file = tumble.simulate(str(ROOT / "models" / "spherical-pendulum.toml"), t_end=2.0, check=False)
    from_dict = tumble.simulate(PENDULUM, t_end=2.0, check=False)
    assert from_dict.names == from_file.names
    for name in from_file.names:
        assert same_bits(from_dict[name], from_file[name]), name
    text = tumble.model_text(PENDULUM)
    assert "[points]" in text and "l*sin(theta)*cos(phi)" in text
    # The dict's order is the file's: the coordinates are the state in the order written.
    assert text.index("theta = ") < text.index("phi = ")


def test_sympy_expressions_stand_where_the_file_has_text():
    sp = pytest.importorskip("sympy")
    m, l, g, theta, phi = sp.symbols("m l g theta phi")
    model = dict(PENDULUM)
    model["points"] = {
        "bob": {
            "mass": m,
            "position": [l * sp.sin(theta) * sp.cos(phi), l * sp.sin(theta) * sp.sin(phi), -l * sp.cos(theta)],
        }
    }
    # A potential written with powers, a rational and Abs, equal to zero: (l^2 - l^2)*g*m/2 + |0|.
    model["lagrangian"] = {
        "gravity": [0, 0, -g],
        "potential": sp.Rational(1, 2) * m * g * (l**2 / l - sp.sqrt(l**2)) + sp.Abs(sp.Integer(0)) * m,
    }
    text = tumble.model_text(model)
    assert "**" not in text
    from_file = tumble.simulate(str(ROOT / "models" / "spherical-pendulum.toml"), t_end=2.0, check=False)
    from_sympy = tumble.simulate(model, t_end=2.0, check=False)
    for name in ("theta", "phi", "theta_dot", "phi_dot", "height"):
        assert np.max(np.abs(from_sympy[name] - from_file[name])) < 1e-12, name
    # The conical orbit: theta stays at theta0 = 0.6.
    assert np.max(np.abs(from_sympy["theta"] - 0.6)) < 1e-9


def test_sympy_printing_is_the_model_language():
    sp = pytest.importorskip("sympy")
    x, y = sp.symbols("x y")
    text = tumble._sympy_text
    assert text(x**2) == "((x)^(2))"
    assert text(sp.sqrt(x)) == "sqrt(x)"
    assert text(1 / x) == "(1/(x))"
    assert text(sp.Abs(x)) == "abs(x)"
    assert text(sp.E * x) in ("exp(1)*x", "x*exp(1)")
    assert text(sp.Rational(1, 3) * x) in ("(1/3)*x", "x*(1/3)", "x/3")
    assert text(sp.atan2(y, x)) == "atan2(y, x)"
    assert float(eval(text(sp.Float(0.1)))) == 0.1
    assert text(sp.pi * x) in ("pi*x", "x*pi")
    # Numbers become numbers.
    assert tumble.model_text({"parameters": {"a": {"default": sp.Float(2.5)}}}).strip().endswith("a = { default = 2.5 }")


def test_a_value_that_is_not_an_expression_is_refused_naming_its_key():
    model = dict(PENDULUM)
    model["outputs"] = {"height": object()}
    with pytest.raises(TypeError, match=r"outputs\.height"):
        tumble.simulate(model)
    with pytest.raises(TypeError, match="model: expected a dict"):
        tumble.model_text(["not", "a", "dict"])  # type: ignore[arg-type]
