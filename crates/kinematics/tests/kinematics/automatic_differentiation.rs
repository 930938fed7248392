//! Dual numbers flow through the kinematics: the Jacobian of ω(φ, θ, ψ; φ̇, θ̇, ψ̇) by num-dual
//! equals the analytic one.

use nalgebra::{Matrix3x6, SVector, Vector3};
use num_dual::{DualSVec64, jacobian};
use tumble_kinematics::EulerConvention;

/// Analytic ∂ω/∂(φ, θ, ψ, φ̇, θ̇, ψ̇) of the article's
/// ω = φ̇ ẑ + θ̇ (−sin φ, cos φ, 0) + ψ̇ (sin θ cos φ, sin θ sin φ, cos θ).
fn analytic(q: &SVector<f64, 6>) -> Matrix3x6<f64> {
    let (phi, theta, _psi, _pd, td, sd) = (q[0], q[1], q[2], q[3], q[4], q[5]);
    let (sp, cp, st, ct) = (phi.sin(), phi.cos(), theta.sin(), theta.cos());
    let d_phi = Vector3::new(-cp, -sp, 0.0) * td + Vector3::new(-st * sp, st * cp, 0.0) * sd;
    let d_theta = Vector3::new(ct * cp, ct * sp, -st) * sd;
    let d_psi = Vector3::zeros();
    let d_pd = Vector3::z();
    let d_td = Vector3::new(-sp, cp, 0.0);
    let d_sd = Vector3::new(st * cp, st * sp, ct);
    Matrix3x6::from_columns(&[d_phi, d_theta, d_psi, d_pd, d_td, d_sd])
}

#[test]
fn jacobian_of_article_angular_velocity_by_dual_numbers_matches_analytic() {
    let conv = EulerConvention::ARTICLE;
    for q in [
        SVector::<f64, 6>::from([0.3, 1.1, -2.0, 0.7, -1.3, 4.0]),
        SVector::<f64, 6>::from([-2.9, 0.2, 0.5, 5.0, 0.0, -2.5]),
        SVector::<f64, 6>::from([1.0, 2.8, 3.0, -0.1, 2.0, 0.3]),
    ] {
        let (w, jac) = jacobian(
            |x: SVector<DualSVec64<6>, 6>| {
                let a = Vector3::new(x[0], x[1], x[2]);
                let ad = Vector3::new(x[3], x[4], x[5]);
                conv.omega_space(&a, &ad)
            },
            &q,
        );
        let expected_w = conv.omega_space(
            &Vector3::new(q[0], q[1], q[2]),
            &Vector3::new(q[3], q[4], q[5]),
        );
        assert!((w - expected_w).norm() < 1e-15);
        let diff = (jac - analytic(&q)).amax();
        assert!(diff < 1e-14, "Jacobian differs by {diff:e}");
    }
}

#[test]
fn body_frame_jacobian_by_dual_numbers_matches_rotated_space_jacobian() {
    // ω' = Rᵀ ω, so ∂ω'/∂q̇ = Rᵀ ∂ω/∂q̇ (the rate matrices).
    let conv = EulerConvention::GOLDSTEIN;
    let q = SVector::<f64, 6>::from([0.4, 0.9, -1.7, 1.0, 2.0, -3.0]);
    let (_, jac) = jacobian(
        |x: SVector<DualSVec64<6>, 6>| {
            conv.omega_body(
                &Vector3::new(x[0], x[1], x[2]),
                &Vector3::new(x[3], x[4], x[5]),
            )
        },
        &q,
    );
    let a = Vector3::new(q[0], q[1], q[2]);
    let rt = conv.to_rotation(&a).transpose();
    let expected = rt * conv.rate_matrix_space(&a);
    assert!((jac.fixed_columns::<3>(3) - expected).amax() < 1e-15);
    assert!((jac.fixed_columns::<3>(3) - conv.rate_matrix_body(&a)).amax() < 1e-15);
}
