//! Units: where parameters declare units, a model whose expressions mix unlike quantities, or
//! whose potential, positions or masses have the wrong dimensions, is refused with the key and
//! the units found; the shipped models (all with units) are consistent.

use std::path::PathBuf;

use tumble_model::Model;

fn spherical_pendulum() -> String {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../models/spherical-pendulum.toml");
    std::fs::read_to_string(path).unwrap()
}

fn refusal(text: &str) -> String {
    match Model::parse(text, "pendulum.toml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_potential_that_is_not_an_energy_is_refused() {
    let text = spherical_pendulum().replace(
        "gravity = [\"0\", \"0\", \"-g\"]",
        "gravity = [\"0\", \"0\", \"-g\"]\npotential = \"m*l*cos(theta)\"",
    );
    let e = refusal(&text);
    assert!(e.contains("lagrangian.potential"), "{e}");
    assert!(
        e.contains("has units kg*m, not an energy (kg*m^2/s^2)"),
        "{e}"
    );
    // The same term times g is an energy, and accepted.
    let text = spherical_pendulum().replace(
        "gravity = [\"0\", \"0\", \"-g\"]",
        "potential = \"m*g*l*(1 - cos(theta))\"",
    );
    Model::parse(&text, "pendulum.toml").unwrap();
}

#[test]
fn sums_of_unlike_quantities_and_functions_of_lengths_are_refused() {
    let cases = [
        // (The graph orders a sum's terms its own way.)
        (
            "\"-l*cos(theta)\"]",
            "\"-l*cos(theta) + t\"]",
            "a sum of s and m",
        ),
        (
            "\"l*sin(theta)*cos(phi)\"",
            "\"sin(l)*cos(phi)\"",
            "sin() of a quantity in m",
        ),
        (
            "\"l*sin(theta)*cos(phi)\"",
            "\"l*exp(g)\"",
            "exp() of a quantity in m/s^2",
        ),
    ];
    for (from, to, expect) in cases {
        let text = spherical_pendulum().replacen(from, to, 1);
        assert_ne!(text, spherical_pendulum(), "{from}");
        let e = refusal(&text);
        assert!(e.contains(expect), "{to}: {e}");
        assert!(e.contains("points.bob.position["), "{to}: {e}");
    }
    // A position that is not a length.
    let text = spherical_pendulum().replacen("\"-l*cos(theta)\"]", "\"-l*g\"]", 1);
    let e = refusal(&text);
    assert!(e.contains("has units m^2/s^2, not a length (m)"), "{e}");
}

#[test]
fn an_unknown_unit_is_refused_with_the_units_known() {
    let text = spherical_pendulum().replacen("unit = \"m\"", "unit = \"furlong\"", 1);
    let e = refusal(&text);
    assert!(e.contains("parameters.l.unit"), "{e}");
    assert!(e.contains("unknown unit `furlong`"), "{e}");
    assert!(e.contains("kg, g, m"), "{e}");
}

#[test]
fn without_declared_units_nothing_is_refused() {
    // The same wrong potential, with the parameters' units removed: unknown is never refused.
    let text = spherical_pendulum()
        .replace(", unit = \"kg\"", "")
        .replace(", unit = \"m\"", "")
        .replace(
            "gravity = [\"0\", \"0\", \"-g\"]",
            "gravity = [\"0\", \"0\", \"-g\"]\npotential = \"m*l*cos(theta)\"",
        );
    Model::parse(&text, "pendulum.toml").unwrap();
}
