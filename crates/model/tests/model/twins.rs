//! The built-in scenes written as model files agree with their hand-written twins at the same
//! method and step: the same physics, to 1e-12.

use tumble_scenarios::scenes::find;
use tumble_scenarios::{Scene, StepControl};

use crate::support::{column, run, shipped};

/// Largest difference of two columns.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "row counts");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// `a` and `b` agree to `tol` relative to the larger of 1 and their largest magnitude.
fn agree(label: &str, a: &[f64], b: &[f64], tol: f64) {
    let scale = a.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let d = max_diff(a, b) / scale;
    println!("{label}: max difference {d:.2e} (relative to {scale:.3})");
    assert!(d <= tol, "{label}: model and built-in differ by {d:e}");
}

#[test]
fn driven_hoop_model_matches_the_builtin() {
    let step = StepControl::Fixed(0.01);
    let (bc, br) = run(find("driven-hoop").unwrap(), &[], "gauss8", step, 10.0);
    let (mc, mr) = run(shipped("driven-hoop"), &[], "gauss8", step, 10.0);
    for name in ["alpha", "alpha_dot", "energy"] {
        agree(
            &format!("driven-hoop {name}"),
            &column(&bc, &br, name),
            &column(&mc, &mr, name),
            1e-12,
        );
    }
    // The Jacobi integral is conserved, and the model says so.
    let info = shipped("driven-hoop").info();
    assert!(
        info.conserved.iter().any(|c| c.contains("Jacobi")),
        "{:?}",
        info.conserved
    );
}

#[test]
fn spinning_hoop_model_matches_the_builtin() {
    let step = StepControl::Fixed(0.01);
    let (bc, br) = run(find("spinning-hoop").unwrap(), &[], "gauss8", step, 10.0);
    let (mc, mr) = run(shipped("spinning-hoop"), &[], "gauss8", step, 10.0);
    for name in ["phi", "alpha", "phi_dot", "alpha_dot", "energy"] {
        agree(
            &format!("spinning-hoop {name}"),
            &column(&bc, &br, name),
            &column(&mc, &mr, name),
            1e-12,
        );
    }
    // phi is cyclic: its momentum is the built-in's L_z.
    agree(
        "spinning-hoop L_z",
        &column(&bc, &br, "Lz"),
        &column(&mc, &mr, "p_phi"),
        1e-12,
    );
}

#[test]
fn free_hoop_euler_model_matches_the_builtin_on_so3() {
    let step = StepControl::Fixed(0.01);
    let (bc, br) = run(find("free-hoop").unwrap(), &[], "gauss8", step, 5.0);
    let (mc, mr) = run(shipped("free-hoop-euler"), &[], "gauss8", step, 5.0);
    for (b, m) in [
        ("energy", "energy"),
        ("tilt", "tilt"),
        ("alpha", "alpha"),
        ("alpha_dot", "alpha_dot"),
        ("Lz", "p_phi"),
    ] {
        agree(
            &format!("free-hoop {b}"),
            &column(&bc, &br, b),
            &column(&mc, &mr, m),
            1e-12,
        );
    }
}

#[test]
fn heavy_top_model_matches_the_builtin() {
    let step = StepControl::Fixed(1e-3);
    let (bc, br) = run(find("heavy-top").unwrap(), &[], "gauss12", step, 2.0);
    let (mc, mr) = run(shipped("heavy-top"), &[], "gauss12", step, 2.0);
    agree(
        "heavy-top energy",
        &column(&bc, &br, "energy"),
        &column(&mc, &mr, "energy"),
        1e-12,
    );
    // The symmetry axis R e_z from the built-in's quaternion.
    let q: Vec<[f64; 4]> = br
        .iter()
        .map(|r| {
            let at = |n: &str| r[bc.iter().position(|c| c == n).unwrap()];
            [at("qw"), at("qx"), at("qy"), at("qz")]
        })
        .collect();
    let axis = [
        q.iter()
            .map(|[w, x, y, z]| 2.0 * (x * z + w * y))
            .collect::<Vec<_>>(),
        q.iter().map(|[w, x, y, z]| 2.0 * (y * z - w * x)).collect(),
        q.iter()
            .map(|[_, x, y, _]| 1.0 - 2.0 * (x * x + y * y))
            .collect(),
    ];
    for (k, name) in ["axis_x", "axis_y", "axis_z"].iter().enumerate() {
        agree(
            &format!("heavy-top {name}"),
            &axis[k],
            &column(&mc, &mr, name),
            1e-12,
        );
    }
    agree(
        "heavy-top L_z",
        &column(&bc, &br, "Lz"),
        &column(&mc, &mr, "p_phi"),
        1e-12,
    );
}

#[test]
fn coriolis_drop_model_matches_the_builtin() {
    let step = StepControl::Fixed(0.01);
    let (bc, br) = run(find("coriolis-drop").unwrap(), &[], "gauss8", step, 4.0);
    let (mc, mr) = run(shipped("coriolis-drop"), &[], "gauss8", step, 4.0);
    for name in ["x", "y", "z", "x_dot", "y_dot", "z_dot", "energy"] {
        agree(
            &format!("coriolis-drop {name}"),
            &column(&bc, &br, name),
            &column(&mc, &mr, name),
            1e-12,
        );
    }
}
