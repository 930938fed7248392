//! The new systems against independent truth: closed forms and conserved quantities computed
//! here from the rows, not from the model's own diagnostics.

use std::f64::consts::FRAC_PI_2;

use tumble_scenarios::{RunOptions, Scene, SceneError, StepControl};

use crate::support::{column, run, shipped};

/// Released with `φ̇² = g/(l cos θ₀)`, the spherical pendulum moves on a cone: θ stays at θ₀
/// and φ turns at that rate.
#[test]
fn spherical_pendulum_keeps_the_conical_orbit_rate() {
    let (g, l, theta0) = (9.81f64, 1.0f64, 0.6f64);
    let rate = (g / (l * theta0.cos())).sqrt();
    let (c, rows) = run(
        shipped("spherical-pendulum"),
        &[("phi_dot0", rate)],
        "gauss8",
        StepControl::Fixed(0.01),
        10.0,
    );
    let (t, theta, phi) = (
        column(&c, &rows, "t"),
        column(&c, &rows, "theta"),
        column(&c, &rows, "phi"),
    );
    let drift = theta.iter().map(|x| (x - theta0).abs()).fold(0.0, f64::max);
    let phase = t
        .iter()
        .zip(&phi)
        .map(|(t, p)| (p - rate * t).abs())
        .fold(0.0, f64::max);
    println!("conical orbit: |theta - theta0| <= {drift:.1e}, |phi - rate t| <= {phase:.1e}");
    assert!(drift < 1e-10 && phase < 1e-9);
}

/// The Foucault pendulum's swing plane turns clockwise (north) at `W sin(lat)`: the azimuth of
/// the swing's turning points, fitted against time.
#[test]
fn foucault_pendulum_precesses_at_w_sin_latitude() {
    let scene = shipped("foucault-pendulum");
    let (w, lat) = (0.01f64, 0.7f64);
    let (c, rows) = run(scene, &[], "gauss8", StepControl::Fixed(0.005), 100.0);
    let (t, x, y) = (
        column(&c, &rows, "t"),
        column(&c, &rows, "x"),
        column(&c, &rows, "y"),
    );
    let (xd, yd) = (column(&c, &rows, "x_dot"), column(&c, &rows, "y_dot"));
    // Turning points: r·v changes sign from + to −; the line of the swing there, as an angle
    // doubled (a line has no direction) and unwrapped.
    let mut samples = Vec::new();
    let mut previous: Option<f64> = None;
    for k in 1..t.len() {
        let rv0 = x[k - 1] * xd[k - 1] + y[k - 1] * yd[k - 1];
        let rv1 = x[k] * xd[k] + y[k] * yd[k];
        if rv0 > 0.0 && rv1 <= 0.0 {
            let s = rv0 / (rv0 - rv1);
            let (xi, yi) = (
                x[k - 1] + s * (x[k] - x[k - 1]),
                y[k - 1] + s * (y[k] - y[k - 1]),
            );
            let mut doubled = (2.0 * xi * yi).atan2(xi * xi - yi * yi);
            if let Some(p) = previous {
                while doubled - p > std::f64::consts::PI {
                    doubled -= 2.0 * std::f64::consts::PI;
                }
                while doubled - p < -std::f64::consts::PI {
                    doubled += 2.0 * std::f64::consts::PI;
                }
            }
            previous = Some(doubled);
            samples.push((t[k - 1] + s * (t[k] - t[k - 1]), 0.5 * doubled));
        }
    }
    let n = samples.len() as f64;
    let (st, sa) = samples
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, z)| (a + t, b + z));
    let (mt, ma) = (st / n, sa / n);
    let (num, den) = samples.iter().fold((0.0, 0.0), |(a, b), (t, z)| {
        (a + (t - mt) * (z - ma), b + (t - mt) * (t - mt))
    });
    let rate = num / den;
    let expected = -w * lat.sin();
    println!(
        "Foucault: swing plane turns at {rate:.6e} rad/s, W sin(lat) = {:.6e} ({} turning points)",
        -expected,
        samples.len()
    );
    assert!(samples.len() > 80);
    assert!(
        ((rate - expected) / expected).abs() < 1e-3,
        "{rate} vs {expected}"
    );
}

/// With its axis horizontal and the rotor spinning at ω₃, the gyroscope precesses steadily at
/// `Ω = m g l / (I₃ ω₃)`: started so, its axis stays horizontal; started without precession,
/// it nods.
#[test]
fn gyroscope_in_gimbals_precesses_at_mgl_over_i3_omega3() {
    let scene = shipped("gyroscope-gimbals");
    let (m, g, l, i3, spin) = (0.5, 9.81, 0.05, 4e-4, 300.0);
    let omega = m * g * l / (i3 * spin);
    let (c, rows) = run(
        scene,
        &[("precession", omega)],
        "gauss8",
        StepControl::Fixed(1e-3),
        5.0,
    );
    let (t, theta, phi) = (
        column(&c, &rows, "t"),
        column(&c, &rows, "theta"),
        column(&c, &rows, "phi"),
    );
    let nod = theta
        .iter()
        .map(|x| (x - FRAC_PI_2).abs())
        .fold(0.0, f64::max);
    let phase = t
        .iter()
        .zip(&phi)
        .map(|(t, p)| (p - omega * t).abs())
        .fold(0.0, f64::max);
    println!(
        "gyroscope: Omega = {omega:.6} rad/s; axis off horizontal <= {nod:.1e} rad, |phi - Omega t| <= {phase:.1e}"
    );
    assert!(nod < 1e-10 && phase < 1e-9);
    let (c, rows) = run(scene, &[], "gauss8", StepControl::Fixed(1e-3), 1.0);
    let nod = column(&c, &rows, "theta")
        .iter()
        .map(|x| (x - FRAC_PI_2).abs())
        .fold(0.0, f64::max);
    assert!(nod > 1e-4, "released without precession it nods ({nod:e})");
}

/// Two beads on a hoop turning freely about the vertical: the energy and
/// `L_z = (M a²/2 + m₁ a² sin²α₁ + m₂ a² sin²α₂) φ̇`, both computed here from the rows.
#[test]
fn hoop_with_two_beads_conserves_energy_and_lz() {
    let (mm, m1, m2, a, g) = (1.0, 0.2, 0.3, 0.4, 9.81);
    let (c, rows) = run(
        shipped("hoop-two-beads"),
        &[],
        "gauss8",
        StepControl::Fixed(0.005),
        10.0,
    );
    let col = |n: &str| column(&c, &rows, n);
    let (a1, a2, pd, a1d, a2d) = (
        col("alpha1"),
        col("alpha2"),
        col("phi_dot"),
        col("alpha1_dot"),
        col("alpha2_dot"),
    );
    let lz = |k: usize| {
        (mm * a * a / 2.0 + (m1 * a1[k].sin().powi(2) + m2 * a2[k].sin().powi(2)) * a * a) * pd[k]
    };
    let energy = |k: usize| {
        let iz = mm * a * a / 2.0 + (m1 * a1[k].sin().powi(2) + m2 * a2[k].sin().powi(2)) * a * a;
        0.5 * iz * pd[k] * pd[k] + 0.5 * a * a * (m1 * a1d[k] * a1d[k] + m2 * a2d[k] * a2d[k])
            - g * a * (m1 * a1[k].cos() + m2 * a2[k].cos())
    };
    let (lz0, e0) = (lz(0), energy(0));
    let dl = (0..rows.len())
        .map(|k| (lz(k) - lz0).abs())
        .fold(0.0, f64::max)
        / lz0.abs();
    let de = (0..rows.len())
        .map(|k| (energy(k) - e0).abs())
        .fold(0.0, f64::max)
        / e0.abs();
    let model_e = col("energy");
    let agree = (0..rows.len())
        .map(|k| (model_e[k] - energy(k)).abs())
        .fold(0.0, f64::max);
    println!(
        "two beads: L_z drift {dl:.1e}, energy drift {de:.1e}, model energy vs formula {agree:.1e}"
    );
    assert!(dl < 1e-12 && de < 1e-12 && agree < 1e-12);
    // The beads exchange L_z with the hoop: phi_dot changes.
    let spread = pd.iter().fold(0.0f64, |m, x| m.max((x - pd[0]).abs()));
    assert!(spread > 0.1);
}

/// The double pendulum's normal modes for equal masses and rods:
/// `ω² = (g/l)(2 ∓ √2)`, amplitudes `(1, ±√2)`; started at rest in a mode with a small
/// amplitude, `θ₁(t) = A cos ωt`.
#[test]
fn double_pendulum_oscillates_in_its_normal_modes() {
    let g = 9.81f64;
    for sign in [1.0f64, -1.0] {
        let omega = (g * (2.0 - sign * 2f64.sqrt())).sqrt();
        let amp = 1e-4;
        let set = [("theta1_0", amp), ("theta2_0", sign * 2f64.sqrt() * amp)];
        let period = 2.0 * std::f64::consts::PI / omega;
        let (c, rows) = run(
            shipped("double-pendulum"),
            &set,
            "gauss8",
            StepControl::Fixed(0.005),
            3.0 * period,
        );
        let (t, th1, th2) = (
            column(&c, &rows, "t"),
            column(&c, &rows, "theta1"),
            column(&c, &rows, "theta2"),
        );
        let err = t
            .iter()
            .zip(th1.iter().zip(&th2))
            .map(|(t, (a, b))| {
                let c = amp * (omega * t).cos();
                (a - c).abs().max((b - sign * 2f64.sqrt() * c).abs())
            })
            .fold(0.0, f64::max);
        println!(
            "double pendulum mode omega = {omega:.6}: max |theta - mode| / A = {:.1e}",
            err / amp
        );
        assert!(err < 1e-5 * amp, "mode {sign}: {err:e}");
    }
}

/// Gauss–Legendre's observed order on a model (the double pendulum at large amplitude, errors
/// against a much finer run): the method's order within 0.3.
#[test]
fn gauss_legendre_reaches_its_order_on_a_model() {
    let scene = shipped("double-pendulum");
    let final_state = |method: &str, h: f64| {
        let (_, rows) = run(scene, &[], method, StepControl::Fixed(h), 2.0);
        rows.last().unwrap()[1..5].to_vec()
    };
    let reference = final_state("gauss12", 1e-3);
    for (method, order) in [("gauss2", 2.0), ("gauss4", 4.0), ("gauss6", 6.0)] {
        let err = |h: f64| {
            final_state(method, h)
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        };
        let (h1, h2) = if order > 5.0 {
            (0.04, 0.02)
        } else {
            (0.02, 0.01)
        };
        let (e1, e2) = (err(h1), err(h2));
        let observed = (e1 / e2).log2();
        println!("{method}: errors {e1:.2e}, {e2:.2e}: observed order {observed:.2}");
        assert!(
            (observed - order).abs() <= 0.3,
            "{method}: observed order {observed}"
        );
    }
}

/// A model whose mass matrix is singular at its initial state is refused before any step,
/// with the condition number and the coordinate at fault.
#[test]
fn gimbal_lock_at_the_start_is_refused_with_the_coordinate() {
    let scene = shipped("free-hoop-euler");
    let mut params = scene.info().default_params();
    params.set("theta0", 0.0).unwrap();
    let options = RunOptions::default();
    let err = scene
        .run(&params, &options, &mut tumble_scenarios::scene::Discard)
        .unwrap_err();
    let SceneError::ModelRefused { message, .. } = &err else {
        panic!("{err}");
    };
    assert!(message.contains("condition number"), "{message}");
    assert!(message.contains("`theta`"), "{message}");
}
