//! `spinning-hoop`: the article's worked example and the conservation of L_z and energy.

use std::f64::consts::PI;

use nalgebra::SVector;
use tumble_integrators::Direction;
use tumble_scenarios::scenes::hoop::{HoopParams, SpinningHoop};

use crate::support::{crossing, integrate};

#[test]
fn bead_sliding_from_the_top_slows_the_hoop_to_25_over_6() {
    // M = 1, a = 0.4, m = 0.2, φ̇ = 5, the bead (just off) the top: at 45° from the top,
    // L_z = 0.08·5 = (0.08 + 0.2·0.16·½) φ̇ gives φ̇ = 25/6.
    let s = SpinningHoop {
        hoop: HoopParams::new(1.0, 0.2, 0.4, 9.81).unwrap(),
    };
    let delta = 1e-7;
    let mut y = SVector::<f64, 4>::new(0.0, PI - delta, 5.0, 0.0);
    let mut events = [crossing::<4>(1, 0.75 * PI, Direction::Falling)];
    let report = integrate(&s, &mut y, 30.0, 1e-13, &mut events);
    let at45 = &report
        .events
        .first()
        .expect("the bead reaches 45° from the top")
        .state;
    let phi_dot = at45[2];
    // The start off the top changes L_z by O(δ²) = 1e-14.
    assert!((phi_dot - 25.0 / 6.0).abs() < 1e-9, "φ̇ = {phi_dot}");
}

#[test]
fn angular_momentum_and_energy_are_conserved() {
    let s = SpinningHoop {
        hoop: HoopParams::new(1.0, 0.2, 0.4, 9.81).unwrap(),
    };
    let mut y = SVector::<f64, 4>::new(0.0, 0.5, 3.0, 1.0);
    let (l0, e0) = (s.angular_momentum_z(y[1], y[2]), s.energy(y[1], y[2], y[3]));
    integrate(&s, &mut y, 20.0, 1e-12, &mut []);
    let (l1, e1) = (s.angular_momentum_z(y[1], y[2]), s.energy(y[1], y[2], y[3]));
    assert!(
        ((l1 - l0) / l0).abs() < 1e-10 && ((e1 - e0) / e0).abs() < 1e-10,
        "{l0}→{l1}, {e0}→{e1}"
    );
}
