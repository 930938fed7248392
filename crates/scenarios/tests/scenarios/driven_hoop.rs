//! `driven-hoop`: the off-axis equilibrium, both small-oscillation frequencies, and the Jacobi
//! integral.

use nalgebra::{Vector1, Vector2};
use tumble_integrators::Direction;
use tumble_scenarios::EulerLagrange;
use tumble_scenarios::scenes::hoop::{DrivenHoop, HoopParams};

use crate::support::{crossing, integrate};

const G: f64 = 9.81;
const A: f64 = 0.5;

fn scene(omega: f64) -> DrivenHoop {
    DrivenHoop::new(HoopParams::new(1.0, 0.1, A, G).unwrap(), omega).unwrap()
}

#[test]
fn off_axis_equilibrium_is_60_degrees_at_omega_squared_2g_over_a() {
    let s = scene((2.0 * G / A).sqrt());
    let alpha = s.off_axis_equilibrium().unwrap();
    assert!((alpha - 60f64.to_radians()).abs() < 1e-14);
    // The AD equations have zero acceleration there, and at 0 and π.
    let el = EulerLagrange::new(s);
    for eq in [0.0, std::f64::consts::PI, alpha] {
        let qdd = el
            .accelerations(0.0, &Vector1::new(eq), &Vector1::new(0.0))
            .unwrap();
        assert!(qdd[0].abs() < 1e-12, "α = {eq}: α̈ = {}", qdd[0]);
    }
    // Below the critical spin there is none.
    assert!(scene(0.9 * (G / A).sqrt()).off_axis_equilibrium().is_none());
}

/// Period of small oscillations about `center`, from successive upward crossings of `center`.
fn measured_period(s: &DrivenHoop, center: f64) -> f64 {
    let mut y = Vector2::new(center + 1e-5, 0.0);
    let mut events = [crossing::<2>(0, center, Direction::Rising)];
    let report = integrate(s, &mut y, 20.0, 1e-13, &mut events);
    let times: Vec<f64> = report.events.iter().map(|e| e.t).collect();
    assert!(times.len() >= 3, "too few crossings: {times:?}");
    (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64
}

#[test]
fn small_oscillations_at_the_bottom_have_omega_squared_g_over_a_minus_omega_squared() {
    let omega = 0.6 * (G / A).sqrt();
    let s = scene(omega);
    let expected = 2.0 * std::f64::consts::PI / (G / A - omega * omega).sqrt();
    let period = measured_period(&s, 0.0);
    // Amplitude 1e-5: the anharmonic correction is O(amplitude²) = 1e-10.
    assert!(
        ((period - expected) / expected).abs() < 1e-8,
        "{period} vs {expected}"
    );
}

#[test]
fn small_oscillations_about_the_off_axis_equilibrium_have_the_textbook_frequency() {
    let omega = (2.0 * G / A).sqrt();
    let s = scene(omega);
    let center = s.off_axis_equilibrium().unwrap();
    let big_omega2 = omega * omega - G * G / (A * A * omega * omega);
    let expected = 2.0 * std::f64::consts::PI / big_omega2.sqrt();
    let period = measured_period(&s, center);
    assert!(
        ((period - expected) / expected).abs() < 1e-8,
        "{period} vs {expected}"
    );
}

#[test]
fn jacobi_integral_is_conserved() {
    let s = scene(7.0);
    let mut y = Vector2::new(0.3, 2.0);
    let j0 = s.jacobi_integral(y[0], y[1]);
    integrate(&s, &mut y, 10.0, 1e-12, &mut []);
    let j1 = s.jacobi_integral(y[0], y[1]);
    assert!(((j1 - j0) / j0).abs() < 1e-10, "{j0} → {j1}");
    // The AD energy is the same integral times m a², less the driven hoop's own (constant)
    // kinetic energy ½ (Ma²/2) ω² that enters L but not the bead's motion.
    let el = EulerLagrange::new(s);
    let e = el.energy(0.0, &Vector1::new(y[0]), &Vector1::new(y[1]));
    let hoop_spin = 0.5 * (0.5 * 1.0 * A * A) * 49.0;
    assert!(
        (e - (0.1 * A * A * j1 - hoop_spin)).abs() < 1e-13,
        "{e} vs {}",
        0.1 * A * A * j1 - hoop_spin
    );
}

/// The closed-form energy the CSV reports is the Lagrangian's energy function `p·q̇ − L` by
/// automatic differentiation, at states all round the hoop, with and without a bead and drive.
#[test]
fn closed_form_energy_equals_the_lagrangian_energy_function() {
    for (m, omega) in [(0.1, 4.4), (0.0, 4.4), (0.3, 0.0), (2.0, 13.0)] {
        let s = DrivenHoop::new(HoopParams::new(1.3, m, A, G).unwrap(), omega).unwrap();
        let el = EulerLagrange::new(s);
        for k in 0..24 {
            let alpha = -3.0 + 0.27 * f64::from(k);
            let alpha_dot = 2.5 * (0.7 * f64::from(k)).sin();
            let t = 0.37 * f64::from(k);
            let ad = el.energy(t, &Vector1::new(alpha), &Vector1::new(alpha_dot));
            let closed = s.energy(alpha, alpha_dot);
            let scale = 1.0 + ad.abs();
            assert!(
                (closed - ad).abs() <= 8.0 * f64::EPSILON * scale,
                "m = {m}, ω = {omega}, α = {alpha}, α̇ = {alpha_dot}: {closed} vs {ad}"
            );
        }
    }
}
