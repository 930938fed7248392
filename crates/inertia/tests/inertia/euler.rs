//! The classroom exercise: the tensor of a body turned by the article's ZYZ Euler angles, and
//! the angles that make it diagonal.

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use proptest::prelude::*;
use tumble_inertia::{MassProperties, MassSpec, THandle, off_diagonal_norm};
use tumble_kinematics::euler::EulerConvention;

use crate::common::{rel_err, rotation};

fn asymmetric_body() -> MassProperties {
    let i = Matrix3::new(3.0, -0.4, 0.2, -0.4, 2.0, 0.1, 0.2, 0.1, 4.0);
    MassProperties::try_new(1.5, Point3::new(0.1, 0.2, 0.3), i).unwrap()
}

#[test]
fn turned_tensor_is_r_i_rt_with_r_rz_phi_ry_theta_rz_psi() {
    let body = asymmetric_body();
    let (phi, theta, psi) = (0.7, 1.1, -0.4);
    // Built here from axis-angle rotations, independently of the kinematics crate.
    let r = Rotation3::from_axis_angle(&Vector3::z_axis(), phi)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), theta)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
    let turned = body.turned_zyz(&Vector3::new(phi, theta, psi));
    let expected = r.matrix() * body.inertia() * r.matrix().transpose();
    assert!(rel_err(turned.inertia(), &expected) <= 1e-15);
    assert!((turned.center_of_mass() - r * body.center_of_mass()).norm() <= 1e-15);
}

#[test]
fn principal_euler_angles_make_the_tensor_diagonal() {
    let body = asymmetric_body();
    let decomposition = body.principal_euler_zyz();
    assert!(!decomposition.gimbal_lock);
    let turned = body.turned_zyz(&decomposition.angles);
    assert!(off_diagonal_norm(turned.inertia()) <= 1e-12 * body.inertia().norm());
    let diagonal = turned.inertia().diagonal();
    assert!((diagonal - body.principal().moments).norm() <= 1e-12 * diagonal.norm());
}

#[test]
fn off_diagonal_terms_vanish_linearly_as_the_angles_approach_the_principal_ones() {
    let body = asymmetric_body();
    let target = body.principal_euler_zyz().angles;
    let direction = Vector3::new(0.3, -0.5, 0.8);
    let offs: Vec<f64> = [0.4, 0.2, 0.1, 0.05, 0.025]
        .iter()
        .map(|&d| off_diagonal_norm(body.turned_zyz(&(target + direction * d)).inertia()))
        .collect();
    for pair in offs.windows(2) {
        // First order in the angle error: halving it halves the off-diagonal terms.
        let ratio = pair[0] / pair[1];
        assert!((ratio - 2.0).abs() < 0.15, "ratio {ratio}, {offs:?}");
    }
}

#[test]
fn axis_aligned_body_reports_gimbal_lock_and_its_angles_still_diagonalize() {
    // Box sides 3, 2, 1: moments ascend along x, y, z, so the principal frame is the body
    // frame itself, θ = 0: the ZYZ angles are at gimbal lock.
    let body = MassProperties::solid_box(1.0, &Vector3::new(3.0, 2.0, 1.0)).unwrap();
    let d = body.principal_euler_zyz();
    assert!(d.gimbal_lock);
    let turned = body.turned_zyz(&d.angles);
    assert!(off_diagonal_norm(turned.inertia()) <= 1e-15);
    assert_eq!(turned.inertia().diagonal(), body.principal().moments);
    // The T-handle's principal frame is a quarter turn away: no gimbal lock.
    let handle = THandle::STANDARD
        .mass_properties(MassSpec::Density(1.0))
        .unwrap();
    let d = handle.principal_euler_zyz();
    assert!(!d.gimbal_lock);
    let turned = handle.turned_zyz(&d.angles);
    assert!(off_diagonal_norm(turned.inertia()) <= 1e-12 * handle.inertia().norm());
}

proptest! {
    #![proptest_config(crate::common::proptest_config(64))]

    #[test]
    fn principal_euler_angles_diagonalize_a_body_in_any_orientation(r in rotation()) {
        let body = asymmetric_body().rotated(&r);
        for convention in [EulerConvention::ARTICLE, EulerConvention::GOLDSTEIN] {
            let angles = body.principal_euler_with(&convention).angles;
            let turned = body.turned_with(&convention, &angles);
            prop_assert!(off_diagonal_norm(turned.inertia()) <= 1e-12 * body.inertia().norm());
        }
    }
}
