//! Shift (parallel axis, both ways), rotation and combination, against point-mass sums.

use nalgebra::{Matrix3, Point3, Vector3};
use proptest::prelude::*;
use tumble_inertia::{InertiaError, MassProperties, PointMass, parallel_axis_term};

use crate::common::{rel_err, rotation, vector};

/// The tensor of point masses about `o`, summed directly: `Σ m (|r|² 𝟙 − r rᵀ)`, `r = p − o`.
fn direct_sum(points: &[PointMass], o: &Point3<f64>) -> Matrix3<f64> {
    points.iter().fold(Matrix3::zeros(), |acc, p| {
        let r = p.position - o;
        acc + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * p.mass
    })
}

fn cloud() -> impl Strategy<Value = Vec<PointMass>> {
    prop::collection::vec(
        (0.1..5.0f64, vector(2.0)).prop_map(|(m, p)| PointMass::new(m, Point3::from(p))),
        4..40,
    )
}

proptest! {
    #![proptest_config(crate::common::proptest_config(128))]

    #[test]
    fn parallel_axis_shift_matches_the_point_mass_sum_about_any_point(
        points in cloud(),
        o in vector(3.0),
    ) {
        let o = Point3::from(o);
        let body = MassProperties::from_point_masses(&points).unwrap();
        let direct = direct_sum(&points, &o);
        let err = rel_err(&body.inertia_about(&o), &direct);
        prop_assert!(err <= 1e-12, "I_O off by {:e}", err);
        // About its own centre, the direct sum is the central tensor.
        let central = direct_sum(&points, &body.center_of_mass());
        prop_assert!(rel_err(body.inertia(), &central) <= 1e-12);
    }

    #[test]
    fn shifting_to_a_point_and_back_recovers_the_central_tensor(
        points in cloud(),
        o in vector(3.0),
    ) {
        let o = Point3::from(o);
        let body = MassProperties::from_point_masses(&points).unwrap();
        let about_o = body.inertia_about(&o);
        let back = MassProperties::try_from_inertia_about(
            body.mass(), body.center_of_mass(), &o, &about_o,
        ).unwrap();
        // Subtracting M(|d|²𝟙 − d dᵀ) costs accuracy relative to |I_O|, not |I_cm|.
        let err = (back.inertia() - body.inertia()).norm() / about_o.norm();
        prop_assert!(err <= 1e-12, "round trip off by {:e}", err);
    }

    #[test]
    fn combining_bodies_matches_the_point_mass_sum_of_their_union(
        points in cloud(),
        split in 1usize..3,
    ) {
        // Split the cloud into consecutive groups; each group is a body, their union the cloud.
        let k = (points.len() * split / 3).clamp(1, points.len() - 1);
        let (a, b) = points.split_at(k);
        let parts = [
            MassProperties::from_point_masses(a).unwrap(),
            MassProperties::from_point_masses(b).unwrap(),
        ];
        let combined = MassProperties::combine_all(&parts).unwrap();
        let whole = MassProperties::from_point_masses(&points).unwrap();
        prop_assert!((combined.mass() - whole.mass()).abs() <= 1e-14 * whole.mass());
        prop_assert!((combined.center_of_mass() - whole.center_of_mass()).norm() <= 1e-13);
        prop_assert!(rel_err(combined.inertia(), &direct_sum(&points, &whole.center_of_mass())) <= 1e-12);
        let pairwise = parts[0].combine(&parts[1]).unwrap();
        prop_assert!(rel_err(pairwise.inertia(), combined.inertia()) <= 1e-15);
    }

    #[test]
    fn rotating_a_body_turns_its_tensor_and_centre_and_keeps_its_moments(
        points in cloud(),
        r in rotation(),
    ) {
        let body = MassProperties::from_point_masses(&points).unwrap();
        let turned: Vec<PointMass> = points
            .iter()
            .map(|p| PointMass::new(p.mass, r * p.position))
            .collect();
        let direct = MassProperties::from_point_masses(&turned).unwrap();
        let rotated = body.rotated(&r);
        prop_assert!(rel_err(rotated.inertia(), direct.inertia()) <= 1e-12);
        prop_assert!((rotated.center_of_mass() - direct.center_of_mass()).norm() <= 1e-13);
        let dm = (rotated.principal().moments - body.principal().moments).norm();
        prop_assert!(dm <= 1e-15 * body.principal().moments.norm());
        // The rotated principal axes still diagonalize the rotated tensor.
        let q = rotated.principal().axes.matrix();
        let d = q.transpose() * rotated.inertia() * q;
        let mut off = d;
        off.fill_diagonal(0.0);
        prop_assert!(off.norm() <= 1e-12 * d.norm());
    }
}

#[test]
fn parallel_axis_term_is_the_point_mass_tensor() {
    let d = Vector3::new(1.0, 2.0, 3.0);
    let expected = Matrix3::new(13.0, -2.0, -3.0, -2.0, 10.0, -6.0, -3.0, -6.0, 5.0) * 2.0;
    assert_eq!(parallel_axis_term(2.0, &d), expected);
}

#[test]
fn translating_a_body_moves_only_its_centre() {
    let body = MassProperties::solid_cylinder(2.0, 0.3, 1.0).unwrap();
    let moved = body.translated(&Vector3::new(5.0, -1.0, 2.0));
    assert_eq!(moved.inertia(), body.inertia());
    assert_eq!(moved.center_of_mass(), Point3::new(5.0, -1.0, 2.0));
}

#[test]
fn one_point_mass_is_an_idealized_body_with_no_central_inertia() {
    let p = [PointMass::new(2.0, Point3::new(1.0, 2.0, 3.0))];
    let body = MassProperties::from_point_masses(&p).unwrap();
    assert_eq!(*body.inertia(), Matrix3::zeros());
    assert!(!body.is_positive_definite());
    // A bead added to a hoop: the union is a proper rigid body again.
    let hoop = MassProperties::thin_hoop(1.0, 0.4).unwrap();
    let bead =
        MassProperties::from_point_masses(&[PointMass::new(0.2, Point3::new(0.4, 0.0, 0.0))])
            .unwrap();
    let both = hoop.combine(&bead).unwrap();
    assert!(both.is_positive_definite());
    assert!((both.center_of_mass().x - 0.4 * 0.2 / 1.2).abs() <= 1e-16);
}

#[test]
fn point_masses_reject_empty_nonpositive_and_nonfinite_input() {
    assert_eq!(
        MassProperties::from_point_masses(&[]),
        Err(InertiaError::Empty)
    );
    let bad_mass = [
        PointMass::new(1.0, Point3::origin()),
        PointMass::new(0.0, Point3::new(1.0, 0.0, 0.0)),
    ];
    assert!(matches!(
        MassProperties::from_point_masses(&bad_mass),
        Err(InertiaError::InvalidPointMass { index: 1, .. })
    ));
    let bad_position = [PointMass::new(1.0, Point3::new(f64::NAN, 0.0, 0.0))];
    assert!(matches!(
        MassProperties::from_point_masses(&bad_position),
        Err(InertiaError::InvalidPointMass { index: 0, .. })
    ));
    assert_eq!(
        MassProperties::combine_all(std::iter::empty()),
        Err(InertiaError::Empty)
    );
}
