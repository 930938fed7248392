//! Angular velocity from Euler angles and rates (space and body frames), and back.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{Matrix3, Vector3};
use num_dual::Dual64;
use proptest::prelude::*;
use tumble_kinematics::so3::vee;
use tumble_kinematics::{EulerConvention, KinematicsError};

/// Ṙ by dual numbers: angles a + ε ȧ.
fn rotation_and_rate(
    conv: EulerConvention,
    a: &Vector3<f64>,
    ad: &Vector3<f64>,
) -> (Matrix3<f64>, Matrix3<f64>) {
    let ang = Vector3::new(
        Dual64::new(a.x, ad.x),
        Dual64::new(a.y, ad.y),
        Dual64::new(a.z, ad.z),
    );
    let r = conv.to_rotation(&ang);
    (r.matrix().map(|x| x.re), r.matrix().map(|x| x.eps))
}

fn any_convention() -> impl Strategy<Value = EulerConvention> {
    (0usize..24).prop_map(|i| EulerConvention::all().nth(i).unwrap())
}

fn angles() -> impl Strategy<Value = Vector3<f64>> {
    (-PI..PI, -PI..PI, -PI..PI).prop_map(|(a, b, c)| Vector3::new(a, b, c))
}

fn rates() -> impl Strategy<Value = Vector3<f64>> {
    (-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0).prop_map(|(a, b, c)| Vector3::new(a, b, c))
}

proptest! {
    #![proptest_config(crate::support::proptest_config(2000))]

    #[test]
    fn space_angular_velocity_is_vee_of_rdot_rt(conv in any_convention(), a in angles(), ad in rates()) {
        let (r, rdot) = rotation_and_rate(conv, &a, &ad);
        let expected = vee(&(rdot * r.transpose()));
        let w = conv.omega_space(&a, &ad);
        prop_assert!((w - expected).norm() <= 1e-14 * (1.0 + ad.norm()), "{conv}: {w} vs {expected}");
    }

    #[test]
    fn body_angular_velocity_is_vee_of_rt_rdot(conv in any_convention(), a in angles(), ad in rates()) {
        let (r, rdot) = rotation_and_rate(conv, &a, &ad);
        let expected = vee(&(r.transpose() * rdot));
        let w = conv.omega_body(&a, &ad);
        prop_assert!((w - expected).norm() <= 1e-14 * (1.0 + ad.norm()), "{conv}: {w} vs {expected}");
        // And ω' = Rᵀ ω.
        prop_assert!((w - r.transpose() * conv.omega_space(&a, &ad)).norm() <= 1e-14 * (1.0 + ad.norm()));
    }

    #[test]
    fn rate_determinant_is_that_of_the_rate_matrices(conv in any_convention(), a in angles()) {
        let d = conv.rate_determinant(&a);
        prop_assert!((conv.rate_matrix_space(&a).determinant() - d).abs() <= 1e-15);
        prop_assert!((conv.rate_matrix_body(&a).determinant() - d).abs() <= 1e-15);
    }

    #[test]
    fn euler_rates_from_angular_velocity_invert_the_rate_map(
        conv in any_convention(), a in angles(), ad in rates()
    ) {
        let det = conv.rate_determinant(&a).abs();
        prop_assume!(det > 1e-3);
        let w = conv.omega_space(&a, &ad);
        let back = conv.try_rates_from_omega_space(&a, &w).unwrap();
        prop_assert!((back - ad).norm() <= 1e-14 * ad.norm().max(1.0) / det);
        let wb = conv.omega_body(&a, &ad);
        let back = conv.try_rates_from_omega_body(&a, &wb).unwrap();
        prop_assert!((back - ad).norm() <= 1e-14 * ad.norm().max(1.0) / det);
    }
}

#[test]
fn article_zyz_space_angular_velocity_formula() {
    // ω = φ̇ ẑ + θ̇ (−sin φ, cos φ, 0) + ψ̇ (sin θ cos φ, sin θ sin φ, cos θ)
    let conv = EulerConvention::ARTICLE;
    let cases: [(f64, f64, f64, f64, f64, f64); 3] = [
        (0.3, 1.1, -2.0, 0.7, -1.3, 4.0),
        (-2.9, 0.2, 0.5, 5.0, 0.0, -2.5),
        (1.0, 2.8, 3.0, -0.1, 2.0, 0.3),
    ];
    for (phi, theta, psi, pd, td, sd) in cases {
        let expected = Vector3::z() * pd
            + Vector3::new(-f64::sin(phi), f64::cos(phi), 0.0) * td
            + Vector3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ) * sd;
        let _ = psi;
        let w = conv.omega_space(&Vector3::new(phi, theta, psi), &Vector3::new(pd, td, sd));
        assert!((w - expected).norm() < 1e-15, "{w} vs {expected}");
    }
}

#[test]
fn lecture_zxz_body_angular_velocity_formula() {
    // ω' = (φ̇ sinθ sinψ + θ̇ cosψ, φ̇ sinθ cosψ − θ̇ sinψ, φ̇ cosθ + ψ̇)
    let conv = EulerConvention::GOLDSTEIN;
    let cases: [(f64, f64, f64, f64, f64, f64); 3] = [
        (0.3, 1.1, -2.0, 0.7, -1.3, 4.0),
        (-2.9, 0.2, 0.5, 5.0, 0.0, -2.5),
        (1.0, 2.8, 3.0, -0.1, 2.0, 0.3),
    ];
    for (phi, theta, psi, pd, td, sd) in cases {
        let (st, ct, sp, cp) = (
            f64::sin(theta),
            f64::cos(theta),
            f64::sin(psi),
            f64::cos(psi),
        );
        let expected = Vector3::new(pd * st * sp + td * cp, pd * st * cp - td * sp, pd * ct + sd);
        let _ = phi;
        let w = conv.omega_body(&Vector3::new(phi, theta, psi), &Vector3::new(pd, td, sd));
        assert!((w - expected).norm() < 1e-15, "{w} vs {expected}");
    }
}

#[test]
fn spinning_hoop_start_angular_velocity_in_both_frames() {
    // The article's hoop standing vertical (θ = π/2), spun about the lab z axis at φ̇ = 5 rad/s:
    // ω_space = (0, 0, 5); in the body frame the spin axis is R_y(π/2)ᵀ ẑ = (−1, 0, 0)·(−1)…
    let conv = EulerConvention::ARTICLE;
    let a = Vector3::new(0.0, FRAC_PI_2, 0.0);
    let ad = Vector3::new(5.0, 0.0, 0.0);
    assert!((conv.omega_space(&a, &ad) - Vector3::new(0.0, 0.0, 5.0)).norm() < 1e-15);
    // Body x points down (−ẑ) when θ = π/2, so the lab z axis is −x in the body frame.
    assert!((conv.omega_body(&a, &ad) - Vector3::new(-5.0, 0.0, 0.0)).norm() < 1e-15);
}

#[test]
fn euler_rates_report_the_singularity_at_gimbal_lock() {
    for conv in EulerConvention::all() {
        let locks = if conv.sequence.is_proper() {
            [0.0, PI]
        } else {
            [-FRAC_PI_2, FRAC_PI_2]
        };
        for lock in locks {
            for offset in [0.0, 1e-12, 1e-8] {
                let a = Vector3::new(0.4, lock + offset, -1.2);
                let w = Vector3::new(0.3, -0.2, 1.0);
                match conv.try_rates_from_omega_space(&a, &w) {
                    Err(KinematicsError::EulerRateSingular {
                        determinant,
                        middle_angle,
                        ..
                    }) => {
                        assert!(determinant.abs() < 1e-6);
                        assert_eq!(middle_angle, lock + offset);
                    }
                    other => panic!(
                        "{conv} at {lock}+{offset}: expected a singularity error, got {other:?}"
                    ),
                }
                assert!(conv.try_rates_from_omega_body(&a, &w).is_err());
            }
        }
    }
    // The message says what and where.
    let err = EulerConvention::ARTICLE
        .try_rates_from_omega_space(&Vector3::new(0.0, 0.0, 0.0), &Vector3::z())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("intrinsic ZYZ") && err.contains("0 or π"),
        "{err}"
    );
    // Slightly further from the lock than the tolerance: finite rates.
    let r = EulerConvention::ARTICLE
        .try_rates_from_omega_space(&Vector3::new(0.0, 1e-5, 0.0), &Vector3::new(1.0, 0.0, 0.0));
    assert!(r.unwrap().iter().all(|x: &f64| x.is_finite()));
}
