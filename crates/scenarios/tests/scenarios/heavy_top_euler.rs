//! The AD Lagrangian of the heavy top reproduces the textbook equations of the symmetric
//! (Lagrange) top at random states (Goldstein §5.7): the θ equation and the conservation of
//! `p_φ` and `p_ψ`.

use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;
use tumble_scenarios::EulerLagrange;
use tumble_scenarios::scenes::top::HeavyTopEuler;

proptest! {
    #![proptest_config(crate::support::proptest_config(500))]

    #[test]
    fn ad_heavy_top_reproduces_the_symmetric_top_equations(
        phi in -3.0f64..3.0, theta in 0.2f64..2.9, psi in -3.0f64..3.0,
        pd in -5.0f64..5.0, td in -5.0f64..5.0, sd in -50.0f64..50.0,
        i1 in 1.0f64..6.0, i3 in 0.5f64..2.0, mgl in 0.0f64..30.0,
    ) {
        let top = HeavyTopEuler {
            inertia: Matrix3::from_diagonal(&Vector3::new(i1, i1, i3)),
            weight: mgl,
            center_of_mass: Vector3::new(0.0, 0.0, 1.0),
        };
        let el = EulerLagrange::new(top);
        let q = Vector3::new(phi, theta, psi);
        let qd = Vector3::new(pd, td, sd);
        let a = el.accelerations(0.0, &q, &qd).unwrap();
        let (st, ct) = theta.sin_cos();
        let w3 = sd + pd * ct;
        // Goldstein: I₁ θ̈ = I₁ φ̇² sin θ cos θ − I₃ ω₃ φ̇ sin θ + m g l sin θ.
        let theta_dd = (i1 * pd * pd * st * ct - i3 * w3 * pd * st + mgl * st) / i1;
        let scale = 1.0 + theta_dd.abs() + a.amax();
        prop_assert!((a[1] - theta_dd).abs() <= 1e-11 * scale, "{} vs {theta_dd}", a[1]);
        // ṗ_ψ = I₃ (ψ̈ + φ̈ cos θ − φ̇ θ̇ sin θ) = 0.
        let ppsi_dot = i3 * (a[2] + a[0] * ct - pd * td * st);
        prop_assert!(ppsi_dot.abs() <= 1e-11 * scale * i3 * (1.0 + sd.abs()));
        // ṗ_φ = d/dt [I₁ φ̇ sin²θ + I₃ ω₃ cos θ] = 0.
        let pphi_dot = i1 * (a[0] * st * st + 2.0 * pd * st * ct * td) - i3 * w3 * st * td;
        prop_assert!(pphi_dot.abs() <= 1e-10 * scale * (i1 + i3) * (1.0 + sd.abs()));
        // Momenta from the AD machinery match the closed forms.
        let p = el.momenta(0.0, &q, &qd);
        prop_assert!((p[2] - i3 * w3).abs() <= 1e-12 * (1.0 + (i3 * w3).abs()));
        prop_assert!((p[0] - (i1 * pd * st * st + i3 * w3 * ct)).abs() <= 1e-12 * (1.0 + p[0].abs()));
    }
}
