//! Principal moments and axes, degenerate cases, and the realizability check.

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use proptest::prelude::*;
use tumble_inertia::{
    InertiaError, MassProperties, PrincipalAxes, principal_axes, realizable_principal_axes,
};

use crate::common::rotation;

/// Asserts `Qᵀ I Q = diag(moments)` to 1e-12 (relative), `Q` proper orthogonal, moments
/// ascending.
fn check_frame(inertia: &Matrix3<f64>, p: &PrincipalAxes) {
    let q = p.axes.matrix();
    let d = q.transpose() * inertia * q;
    let scale = inertia.norm();
    let mut off = d;
    off.fill_diagonal(0.0);
    assert!(off.norm() <= 1e-12 * scale, "off-diagonal {:e}", off.norm());
    assert!((d.diagonal() - p.moments).norm() <= 1e-12 * scale);
    assert!((q.transpose() * q - Matrix3::identity()).norm() <= 1e-14);
    assert!((q.determinant() - 1.0).abs() <= 1e-14, "not right-handed");
    assert!(p.moments[0] <= p.moments[1] && p.moments[1] <= p.moments[2]);
}

fn realizable_moments() -> impl Strategy<Value = Vector3<f64>> {
    // I1 ≤ I2 ≤ I3 ≤ I1 + I2, spanning four decades of scale.
    (0.01..1.0f64, 0.0..1.0f64, 0.0..1.0f64, -2.0..2.0f64).prop_map(|(a, s, t, e)| {
        let i1 = a;
        let i2 = i1 * (1.0 + 4.0 * s);
        let i3 = i2 + t * i1;
        Vector3::new(i1, i2, i3) * 10f64.powf(e)
    })
}

proptest! {
    #![proptest_config(crate::common::proptest_config(256))]

    #[test]
    fn principal_axes_diagonalize_to_1e_12_and_form_a_right_handed_frame(
        moments in realizable_moments(),
        r in rotation(),
    ) {
        let inertia = r.matrix() * Matrix3::from_diagonal(&moments) * r.matrix().transpose();
        let inertia = (inertia + inertia.transpose()) * 0.5;
        let body = MassProperties::try_new(1.0, Point3::origin(), inertia).unwrap();
        check_frame(&inertia, body.principal());
        let dm = (body.principal().moments - moments).norm();
        prop_assert!(dm <= 1e-13 * moments.norm(), "moments off by {:e}", dm);
    }
}

#[test]
fn sphere_has_three_equal_moments_and_an_orthonormal_right_handed_frame() {
    for body in [
        MassProperties::solid_sphere(3.0, 0.7).unwrap(),
        MassProperties::hollow_sphere(3.0, 0.7).unwrap(),
    ] {
        let p = body.principal();
        check_frame(body.inertia(), p);
        assert_eq!(p.moments[0], p.moments[2]);
        // A diagonal tensor gives the identity frame, not an arbitrary one.
        assert_eq!(*p.axes.matrix(), Matrix3::identity());
    }
    // A sphere turned by any rotation has the same tensor, and a valid frame.
    let sphere = MassProperties::solid_sphere(3.0, 0.7).unwrap();
    let turned = sphere.rotated(&Rotation3::from_euler_angles(0.3, -1.1, 2.0));
    let fresh = principal_axes(turned.inertia()).unwrap();
    check_frame(turned.inertia(), &fresh);
}

#[test]
fn symmetric_cylinder_in_any_orientation_gives_its_axis_and_a_valid_frame() {
    // Long cylinder: I_z (axial) is the smallest moment, the two transverse ones are equal.
    let cylinder = MassProperties::solid_cylinder(2.0, 0.1, 1.0).unwrap();
    for r in [
        Rotation3::identity(),
        Rotation3::from_euler_angles(0.4, 0.9, -0.2),
        Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
    ] {
        let turned = cylinder.rotated(&r);
        let p = principal_axes(turned.inertia()).unwrap();
        check_frame(turned.inertia(), &p);
        assert!((p.moments[1] - p.moments[2]).abs() <= 1e-14 * p.moments[2]);
        // The non-degenerate axis is the cylinder's axis R e_z (up to sign).
        let axis = p.axes.matrix().column(0).into_owned();
        let expected = r * Vector3::z();
        assert!(
            axis.cross(&expected).norm() <= 1e-13,
            "axis {axis:?} vs {expected:?}"
        );
    }
    // Flat disk-like cylinder: the axial moment is the largest and still singled out.
    let disk = MassProperties::solid_cylinder(2.0, 1.0, 0.1).unwrap();
    let p = disk.principal();
    check_frame(disk.inertia(), p);
    assert_eq!(p.moments[0], p.moments[1]);
    assert_eq!(p.axes.matrix().column(2).into_owned(), Vector3::z());
}

#[test]
fn diagonal_tensor_gives_a_signed_permutation_in_ascending_order() {
    let inertia = Matrix3::from_diagonal(&Vector3::new(3.0, 1.0, 2.0));
    let p = realizable_principal_axes(&inertia).unwrap();
    assert_eq!(p.moments, Vector3::new(1.0, 2.0, 3.0));
    // Axes: y (moment 1), z (moment 2), x (moment 3); y × z = x, right-handed.
    let expected = Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]);
    assert_eq!(*p.axes.matrix(), expected);
}

#[test]
fn realizability_check_gives_each_violation_its_own_error() {
    let o = Point3::origin();
    let diag = |a: f64, b: f64, c: f64| Matrix3::from_diagonal(&Vector3::new(a, b, c));
    // No mass distribution has moments 1, 1, 3 (I1 + I2 < I3), in any order.
    for m in [
        diag(1.0, 1.0, 3.0),
        diag(3.0, 1.0, 1.0),
        diag(1.0, 3.0, 1.0),
    ] {
        assert!(matches!(
            MassProperties::try_new(1.0, o, m),
            Err(InertiaError::TriangleInequality { .. })
        ));
    }
    assert!(matches!(
        MassProperties::try_new(1.0, o, diag(-1.0, 2.0, 2.0)),
        Err(InertiaError::NotPositiveDefinite { .. })
    ));
    // A zero moment: a rod is fine as an idealized part, not as a rigid body.
    assert!(matches!(
        MassProperties::try_new(1.0, o, diag(0.0, 1.0, 1.0)),
        Err(InertiaError::NotPositiveDefinite { .. })
    ));
    assert!(MassProperties::try_new_idealized(1.0, o, diag(0.0, 1.0, 1.0)).is_ok());
    assert!(matches!(
        MassProperties::try_new_idealized(1.0, o, diag(-1e-3, 1.0, 1.0)),
        Err(InertiaError::NotPositiveDefinite { .. })
    ));
    let mut skew = diag(2.0, 2.0, 2.0);
    skew[(0, 1)] = 0.1;
    assert!(matches!(
        MassProperties::try_new(1.0, o, skew),
        Err(InertiaError::NotSymmetric { row: 0, col: 1, .. })
    ));
    let mut nan = diag(2.0, 2.0, 2.0);
    nan[(2, 1)] = f64::NAN;
    assert!(matches!(
        MassProperties::try_new(1.0, o, nan),
        Err(InertiaError::NonFiniteInertia { row: 2, col: 1, .. })
    ));
    assert!(matches!(
        MassProperties::try_new(0.0, o, diag(1.0, 1.0, 1.0)),
        Err(InertiaError::NonPositiveMass { .. })
    ));
    assert!(matches!(
        MassProperties::try_new(f64::NAN, o, diag(1.0, 1.0, 1.0)),
        Err(InertiaError::NonFiniteMass { .. })
    ));
    assert!(matches!(
        MassProperties::try_new(
            1.0,
            Point3::new(0.0, f64::INFINITY, 0.0),
            diag(1.0, 1.0, 1.0)
        ),
        Err(InertiaError::NonFiniteCenterOfMass { .. })
    ));
    // Messages say what is wrong.
    let e = MassProperties::try_new(1.0, o, diag(1.0, 1.0, 3.0)).unwrap_err();
    assert!(e.to_string().contains("triangle inequality"), "{e}");
}

#[test]
fn planar_bodies_on_the_triangle_equality_are_accepted_despite_round_off() {
    // Hoop and disk: I1 + I2 = I3 exactly; turned in space, round-off puts the computed
    // moments a few ulps on either side.
    for body in [
        MassProperties::thin_hoop(1.3, 0.7).unwrap(),
        MassProperties::thin_disk(1.3, 0.7).unwrap(),
    ] {
        for r in [
            Rotation3::from_euler_angles(0.1, 0.2, 0.3),
            Rotation3::from_euler_angles(2.0, -1.0, 0.7),
        ] {
            let turned = body.rotated(&r);
            let again = MassProperties::try_new(1.3, Point3::origin(), *turned.inertia());
            assert!(again.is_ok(), "{again:?}");
        }
    }
}
