"""`tumble.inertia` against closed forms (a cube) and against `tumble inertia --json` (the same
numbers); meshes given as arrays of the wrong shape or dtype are refused with the shape
expected."""

import json

import numpy as np
import pytest

import tumble
from conftest import ROOT

# The unit cube [0, 1]^3: vertex x + 2y + 4z at (x, y, z); triangles counter-clockwise seen
# from outside.
CUBE_VERTICES = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=np.float64)
CUBE_FACES = np.array(
    [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
     [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]],
    dtype=np.int64,
)


def cube_obj() -> str:
    lines = [f"v {x} {y} {z}" for x, y, z in CUBE_VERTICES]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in CUBE_FACES]
    return "\n".join(lines) + "\n"


def test_cube_arrays_give_the_closed_form_mass_properties():
    # A solid cube of side 1 and density rho: mass rho, centre (1/2, 1/2, 1/2), inertia m/6 on
    # the diagonal about the centre, all three moments equal.
    body = tumble.inertia((CUBE_VERTICES, CUBE_FACES), density=2.5)
    assert body["mass"] == pytest.approx(2.5, rel=1e-15)
    assert body["volume"] == pytest.approx(1.0, rel=1e-15)
    np.testing.assert_allclose(body["center_of_mass"], [0.5, 0.5, 0.5], rtol=1e-15)
    np.testing.assert_allclose(body["inertia"], np.eye(3) * 2.5 / 6, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(body["principal_moments"], [2.5 / 6] * 3, rtol=1e-14)
    assert body["inertia"].shape == (3, 3) and body["principal_axes"].shape == (3, 3)
    assert tumble.inertia((CUBE_VERTICES, CUBE_FACES), mass=7.0)["mass"] == pytest.approx(7.0, rel=1e-15)


@pytest.mark.parametrize("source", ["t-handle", "cube"])
def test_inertia_equals_the_command_lines_json(cli, tmp_path, source):
    if source == "cube":
        path = tmp_path / "cube.obj"
        path.write_text(cube_obj())
    else:
        path = ROOT / "scenes" / "t-handle.obj"
    expected = json.loads(cli("inertia", path, "--density", "1200", "--json").stdout)
    body = tumble.inertia(path, density=1200.0)
    for key, value in expected.items():
        # The command line prints -0.0 as 0.0; == treats them as equal and every other value
        # must be the same number.
        assert np.array_equal(np.asarray(body[key]), np.asarray(value)), key
    if source == "cube":
        arrays = tumble.inertia((CUBE_VERTICES, CUBE_FACES), density=1200.0)
        for key in expected:
            assert np.array_equal(arrays[key], body[key]), key


@pytest.mark.parametrize(
    "vertices,faces,pattern",
    [
        (CUBE_VERTICES[:, :2], CUBE_FACES, r"vertices: expected an array of shape \(N, 3\).*got shape \(8, 2\)"),
        (CUBE_VERTICES.ravel(), CUBE_FACES, r"vertices: expected an array of shape \(N, 3\)"),
        (CUBE_VERTICES.astype(np.int64), CUBE_FACES, r"vertices: .* of floats .*got dtype int64"),
        (CUBE_VERTICES, CUBE_FACES.astype(np.float64), r"faces: expected an array of shape \(M, 3\) of integers, got dtype float64"),
        (CUBE_VERTICES, CUBE_FACES[:, :2], r"faces: expected an array of shape \(M, 3\).*got shape \(12, 2\)"),
        (CUBE_VERTICES, np.array([[0, 1, -2]] + CUBE_FACES[1:].tolist()), r"faces\[0, 2\] = -2"),
    ],
    ids=["vertices-2-columns", "vertices-flat", "vertices-int", "faces-float", "faces-2-columns", "faces-negative"],
)
def test_mesh_arrays_of_the_wrong_shape_or_dtype_are_refused_with_the_expected_shape(vertices, faces, pattern):
    with pytest.raises(ValueError, match=pattern):
        tumble.inertia((vertices, faces), density=1.0)


def test_an_open_mesh_is_refused_with_the_command_lines_reason(cli, tmp_path):
    lines = cube_obj().splitlines()[:-1]  # drop a triangle: the surface has a hole
    (tmp_path / "open.obj").write_text("\n".join(lines) + "\n")
    cli_message = cli("inertia", "open.obj", check=False).stderr.strip()
    with pytest.raises(ValueError) as raised:
        tumble.inertia(tmp_path / "open.obj")
    # The command line names the file as given (relative to its folder).
    assert cli_message == "error: " + str(raised.value).replace(str(tmp_path / "open.obj"), "open.obj")
    with pytest.raises(ValueError, match="the mesh: "):
        tumble.inertia((CUBE_VERTICES, CUBE_FACES[:-1]))
