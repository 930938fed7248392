//! A torus mesh's mass properties converge to the closed form under refinement.

use tumble_inertia::{MassProperties, MassSpec, shapes};

use crate::common::{assert_order, rel_err};

#[test]
fn torus_mesh_moments_converge_to_the_closed_form_at_second_order() {
    let (big, small, density) = (1.0, 0.4, 3.0);
    let volume = 2.0 * std::f64::consts::PI.powi(2) * big * small * small;
    let exact = MassProperties::solid_torus(density * volume, big, small).unwrap();
    // Refine both directions together: n around the axis, n/2 around the tube.
    let ns = [8, 16, 32, 64, 128];
    let mut mass_errors = Vec::new();
    let mut tensor_errors = Vec::new();
    let mut axial_errors = Vec::new();
    let mut transverse_errors = Vec::new();
    for &n in &ns {
        let mesh = shapes::torus_mesh(big, small, n, n / 2).unwrap();
        let body = mesh.mass_properties(MassSpec::Density(density)).unwrap();
        assert!(body.center_of_mass().coords.norm() <= 1e-14);
        let m = body.principal().moments;
        let e = exact.principal().moments;
        mass_errors.push((body.mass() - exact.mass()).abs() / exact.mass());
        tensor_errors.push(rel_err(body.inertia(), exact.inertia()));
        // Ascending: the two transverse moments, then the axial one.
        transverse_errors.push((m[0] - e[0]).abs().max((m[1] - e[1]).abs()) / e[0]);
        axial_errors.push((m[2] - e[2]).abs() / e[2]);
    }
    let hs: Vec<f64> = ns.iter().map(|&n| 1.0 / n as f64).collect();
    assert_order("torus mesh: mass", &hs, &mass_errors, 2.0);
    assert_order("torus mesh: inertia tensor", &hs, &tensor_errors, 2.0);
    assert_order("torus mesh: axial moment I_z", &hs, &axial_errors, 2.0);
    assert_order(
        "torus mesh: transverse moments I_x = I_y",
        &hs,
        &transverse_errors,
        2.0,
    );
}

#[test]
fn torus_mesh_by_total_mass_converges_too() {
    // With the mass fixed, only the distribution's shape error remains: still second order.
    let (big, small) = (2.0, 0.5);
    let exact = MassProperties::solid_torus(5.0, big, small).unwrap();
    let ns = [8, 16, 32, 64];
    let errors: Vec<f64> = ns
        .iter()
        .map(|&n| {
            let mesh = shapes::torus_mesh(big, small, 2 * n, n).unwrap();
            let body = mesh.mass_properties(MassSpec::TotalMass(5.0)).unwrap();
            assert_eq!(body.mass(), 5.0);
            rel_err(body.inertia(), exact.inertia())
        })
        .collect();
    let hs: Vec<f64> = ns.iter().map(|&n| 1.0 / n as f64).collect();
    assert_order(
        "torus mesh at fixed mass: inertia tensor",
        &hs,
        &errors,
        2.0,
    );
}
