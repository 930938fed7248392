//! SO(3): hat/vee, exp/log near 0 and π, quaternion and matrix paths, Cayley map, Jacobians.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};
use num_dual::Dual64;
use proptest::prelude::*;
use tumble_kinematics::KinematicsError;
use tumble_kinematics::so3::{
    angle, cayley, dexp, dexpinv, exp, exp_quat, hat, left_jacobian, left_jacobian_inv, log,
    log_quat, orthogonality_defect, quat_to_rotation, rotation_to_quat, try_cayley_inv, vee,
};

use crate::support::{max_abs_diff, rotation, rotation_vector, unit_vector};

proptest! {
    #![proptest_config(crate::support::proptest_config(2000))]

    #[test]
    fn hat_is_the_cross_product_and_vee_inverts_it(
        a in unit_vector(), b in unit_vector(), s in -10.0f64..10.0
    ) {
        let w = a * s;
        prop_assert!((hat(&w) * b - w.cross(&b)).norm() <= 1e-15 * (1.0 + s.abs()));
        prop_assert_eq!(vee(&hat(&w)), w);
    }

    #[test]
    fn log_inverts_exp_to_1e14_including_near_0_and_pi(w in rotation_vector()) {
        let back = log(&exp(&w));
        let err = (back - w).norm();
        // Absolute 1e-14, and relative 1e-14 for tiny angles.
        prop_assert!(err <= 1e-14 * w.norm().min(1.0), "|ω| = {:e}, error {:e}", w.norm(), err);
    }

    #[test]
    fn exp_inverts_log_to_1e14_including_near_0_and_pi(r in rotation()) {
        let w = log(&r);
        prop_assert!(w.norm() <= PI + 1e-15);
        let err = max_abs_diff(exp(&w).matrix(), r.matrix());
        prop_assert!(err <= 1e-14, "angle {}, error {:e}", w.norm(), err);
    }

    #[test]
    fn exp_agrees_with_nalgebra_axis_angle_rotation(n in unit_vector(), a in 0.0f64..PI) {
        let reference = Rotation3::from_axis_angle(&Unit::new_unchecked(n), a);
        // Two roundings of the same Rodrigues formula: 5.5 ε = 1.2e-15 was the largest
        // difference over 2·10⁷ random cases (1e-15 failed at 200 000 cases), so 2e-15.
        prop_assert!(max_abs_diff(exp(&(n * a)).matrix(), reference.matrix()) <= 2e-15);
    }

    #[test]
    fn quaternion_and_matrix_paths_agree(w in rotation_vector()) {
        let q = exp_quat(&w);
        prop_assert!((q.norm() - 1.0).abs() <= 2.0 * f64::EPSILON);
        prop_assert!(max_abs_diff(quat_to_rotation(&q).matrix(), exp(&w).matrix()) <= 1e-15);
        prop_assert!(max_abs_diff(q.to_rotation_matrix().matrix(), exp(&w).matrix()) <= 1e-15);
        let via_quat = log_quat(&q);
        let via_matrix = log(&exp(&w));
        prop_assert!((via_quat - via_matrix).norm() <= 1e-14 * w.norm().min(1.0));
        // Shepperd's conversion gives back the same quaternion (w ≥ 0 here since |ω| < π).
        let q2 = rotation_to_quat(&exp(&w));
        prop_assert!((q2.coords - q.coords).norm() <= 1e-15);
    }

    #[test]
    fn exp_is_orthogonal_to_round_off(w in rotation_vector(), k in 1.0f64..20.0) {
        // Also beyond π: exp is defined for every ω.
        let r = exp(&(w * k));
        // Round-off level: ‖RᵀR − 𝟙‖_F over nine entries, measured ≤ 2.4e-15 (11 ε).
        prop_assert!(orthogonality_defect(r.matrix()) <= 4e-15);
        prop_assert!((r.matrix().determinant() - 1.0).abs() <= 2e-15);
    }

    #[test]
    fn rotation_angle_is_accurate_near_0_and_pi(w in rotation_vector()) {
        let a = angle(&exp(&w));
        prop_assert!((a - w.norm()).abs() <= 1e-14 * w.norm().min(1.0));
    }

    #[test]
    fn cayley_is_a_rotation_by_twice_atan_half_and_its_inverse_inverts_it(
        n in unit_vector(), s in 0.0f64..100.0
    ) {
        let w = n * s;
        let r = cayley(&w);
        prop_assert!(orthogonality_defect(r.matrix()) <= 4e-16 * (1.0 + s));
        let expected = Rotation3::from_axis_angle(&Unit::new_unchecked(n), 2.0 * (s / 2.0).atan());
        prop_assert!(max_abs_diff(r.matrix(), expected.matrix()) <= 1e-15);
        let back = try_cayley_inv(&r).expect("regular");
        // The inverse is conditioned like tan(φ/2): relative accuracy degrades as s grows.
        prop_assert!((back - w).norm() <= 1e-15 * (1.0 + s) * (1.0 + s * s / 4.0));
    }

    #[test]
    fn dexp_is_the_right_trivialized_derivative_of_exp(
        w in rotation_vector(), wdot in unit_vector()
    ) {
        // d/dt exp(ω + t ω̇) at t = 0 by dual numbers, compared with exp(ω) hat(J_r ω̇).
        let wd = Vector3::new(
            Dual64::new(w.x, wdot.x), Dual64::new(w.y, wdot.y), Dual64::new(w.z, wdot.z),
        );
        let rd = exp(&wd);
        let rdot = rd.matrix().map(|x| x.eps);
        let expected = exp(&w).matrix() * hat(&(dexp(&w) * wdot));
        prop_assert!(max_abs_diff(&rdot, &expected) <= 1e-14, "|ω| = {}", w.norm());
        // Left trivialization: d/dt exp(ω) = hat(J_l ω̇) exp(ω).
        let expected_left = hat(&(left_jacobian(&w) * wdot)) * exp(&w).matrix();
        prop_assert!(max_abs_diff(&rdot, &expected_left) <= 1e-14);
    }

    #[test]
    fn dexpinv_inverts_dexp_below_two_pi(n in unit_vector(), a in 0.0f64..6.0) {
        let w = n * a;
        let i = Matrix3::identity();
        prop_assert!(max_abs_diff(&(dexp(&w) * dexpinv(&w)), &i) <= 1e-14 / (2.0 * PI - a));
        prop_assert!(max_abs_diff(&(left_jacobian(&w) * left_jacobian_inv(&w)), &i) <= 1e-14 / (2.0 * PI - a));
        // J_l(ω) = exp(ω) J_r(ω).
        prop_assert!(max_abs_diff(&left_jacobian(&w), &(exp(&w).matrix() * dexp(&w))) <= 1e-15);
    }
}

#[test]
fn log_of_a_half_turn_has_length_pi_and_the_right_axis() {
    for n in [
        Vector3::x(),
        Vector3::y(),
        Vector3::z(),
        Vector3::new(1.0, -2.0, 3.0).normalize(),
    ] {
        let r = Rotation3::from_axis_angle(&Unit::new_normalize(n), PI);
        let w = log(&r);
        assert!((w.norm() - PI).abs() < 1e-15);
        // ±n are both valid at exactly π.
        assert!((w.normalize().dot(&n).abs() - 1.0).abs() < 1e-15);
        assert!(max_abs_diff(exp(&w).matrix(), r.matrix()) < 1e-15);
    }
}

#[test]
fn log_keeps_relative_accuracy_for_tiny_angles_and_near_pi() {
    // A tiny rotation: relative accuracy of the recovered vector.
    let w = Vector3::new(3e-13, -1e-13, 2e-13);
    let back = log(&exp(&w));
    assert!((back - w).norm() <= 1e-15 * w.norm(), "{back:?}");
    // 1e-9 short of a half turn, built by nalgebra (independent of our exp).
    let n = Vector3::new(0.0, 0.6, 0.8);
    for delta in [1e-6, 1e-9, 1e-12] {
        let r = Rotation3::from_axis_angle(&Unit::new_normalize(n), PI - delta);
        let back = log(&r);
        assert!(
            (back - n * (PI - delta)).norm() < 1e-15 * PI,
            "δ = {delta}: {back}"
        );
    }
}

#[test]
fn series_and_closed_forms_join_continuously_at_the_small_angle_threshold() {
    let n = Vector3::new(0.48, -0.6, 0.64);
    // The series are used for θ < 0.1 (Jacobian coefficients) and θ/2 < 0.1 (sinc, cos of the
    // half angle). Evaluate on both sides of each threshold, a few ulps apart, so that the
    // function itself changes by less than 1e-16.
    type MatrixOf = fn(&Vector3<f64>) -> Matrix3<f64>;
    let maps: [MatrixOf; 3] = [|w| *exp(w).matrix(), |w| dexp(w), |w| dexpinv(w)];
    for threshold in [0.1, 0.2] {
        let below = n * (threshold * (1.0 - 4.0 * f64::EPSILON));
        let above = n * (threshold * (1.0 + 4.0 * f64::EPSILON));
        for f in maps {
            let jump = max_abs_diff(&f(&below), &f(&above));
            assert!(jump < 1e-15, "jump {jump:e} at {threshold}");
        }
        let jump = (exp_quat(&below).coords - exp_quat(&above).coords).norm();
        assert!(jump < 1e-15, "quaternion jump {jump:e} at {threshold}");
    }
}

#[test]
fn derivatives_of_exp_are_finite_at_the_identity() {
    let wd = Vector3::new(
        Dual64::new(0.0, 1.0),
        Dual64::new(0.0, 0.0),
        Dual64::new(0.0, 0.0),
    );
    let rdot = exp(&wd).matrix().map(|x| x.eps);
    assert_eq!(rdot, hat(&Vector3::x()));
    let back = log(&exp(&wd));
    assert_eq!(back.map(|x| x.eps), Vector3::x());
}

#[test]
fn cayley_inverse_reports_the_half_turn() {
    let r = Rotation3::from_axis_angle(&Vector3::z_axis(), PI);
    match try_cayley_inv(&r) {
        Err(KinematicsError::CayleySingular { one_plus_trace }) => {
            assert!(one_plus_trace.abs() < 1e-15)
        }
        other => panic!("expected CayleySingular, got {other:?}"),
    }
    // Quaternion identity cay⁻¹ = 2 v / w for a regular rotation.
    let q = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 1.0);
    let c = try_cayley_inv(&q.to_rotation_matrix()).unwrap();
    assert!((c - q.vector() * (2.0 / q.w)).norm() < 1e-15);
}
