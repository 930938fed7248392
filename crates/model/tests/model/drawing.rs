//! Where a model's bodies and point masses are drawn: its own expressions evaluated at the
//! rows, checked against the closed forms of the shipped models' geometry.

use tumble_scenarios::{Scene, StepControl};

use crate::support::{column, run, shipped};

#[test]
fn a_point_mass_is_drawn_where_its_coordinates_put_it() {
    // The spherical pendulum's bob at l (sin θ cos φ, sin θ sin φ, −cos θ), on the sphere of
    // radius l at every row.
    let scene = shipped("spherical-pendulum");
    let (columns, rows) = run(
        scene,
        &[("l", 1.7)],
        "gauss8",
        StepControl::Fixed(0.01),
        2.0,
    );
    let mut params = scene.info().default_params();
    params.set("l", 1.7).unwrap();
    let poses = scene.poses(&params, &rows);
    assert_eq!(poses.len(), rows.len());
    let (theta, phi) = (
        column(&columns, &rows, "theta"),
        column(&columns, &rows, "phi"),
    );
    for (k, pose) in poses.iter().enumerate() {
        let (st, ct) = theta[k].sin_cos();
        let (sp, cp) = phi[k].sin_cos();
        let expected = [1.7 * st * cp, 1.7 * st * sp, -1.7 * ct];
        for i in 0..3 {
            assert!((pose.points[0][i] - expected[i]).abs() < 1e-14, "row {k}");
        }
    }
    let shapes = scene.shapes(&params);
    assert_eq!(shapes.points[0].name, "bob");
    assert_eq!(shapes.points[0].mass, 1.0);
}

#[test]
fn gimbal_bodies_turn_by_their_chains_of_rotations() {
    // The gyroscope's rotor: R = Rz(φ) Rx(θ) Rz(ψ), a rotation (orthogonal, det 1) whose axis
    // R e_z = (sin θ sin φ, −sin θ cos φ, cos θ); its moments at the parameters.
    let scene = shipped("gyroscope-gimbals");
    let (columns, rows) = run(scene, &[], "gauss8", StepControl::Fixed(1e-3), 0.2);
    let params = scene.info().default_params();
    let poses = scene.poses(&params, &rows);
    let shapes = scene.shapes(&params);
    let rotor = shapes
        .bodies
        .iter()
        .position(|b| b.name == "rotor")
        .unwrap();
    assert_eq!(shapes.bodies[rotor].inertia[2][2], 4e-4);
    assert_eq!(shapes.bodies[rotor].com, [0.0, 0.0, 0.05]);
    let (phi, theta) = (
        column(&columns, &rows, "phi"),
        column(&columns, &rows, "theta"),
    );
    for (k, pose) in poses.iter().enumerate() {
        let (r, origin) = pose.bodies[rotor];
        assert_eq!(origin, [0.0; 3]);
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|m| r[m][i] * r[m][j]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((dot - expected).abs() < 1e-14, "row {k}: RᵀR");
            }
        }
        let axis = [r[0][2], r[1][2], r[2][2]];
        let (st, ct) = theta[k].sin_cos();
        let (sp, cp) = phi[k].sin_cos();
        let expected = [st * sp, -st * cp, ct];
        for i in 0..3 {
            assert!((axis[i] - expected[i]).abs() < 1e-14, "row {k}: {axis:?}");
        }
    }
}
