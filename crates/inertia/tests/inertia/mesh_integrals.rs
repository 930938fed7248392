//! Mesh integrals: the exact box, the unit tetrahedron through every loader, density versus
//! total mass, and invariance under translations and rotations.

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use tumble_inertia::{
    MassProperties, MassSpec, THandle, TriangleMesh, ValidationOptions, load_mesh, shapes,
};

use crate::common::{data, rel_err, rotation, vector};

#[test]
fn twelve_triangle_box_mesh_matches_box_formula_to_1e_12() {
    for sides in [
        Vector3::new(1.0, 1.0, 1.0),
        Vector3::new(0.3, 1.7, 2.9),
        Vector3::new(1e-3, 2e-3, 5e-4),
        Vector3::new(40.0, 0.5, 7.0),
    ] {
        let mesh = shapes::box_mesh(&sides).unwrap();
        assert_eq!(mesh.faces().len(), 12);
        assert!((mesh.volume() - sides.product()).abs() <= 1e-15 * sides.product());
        let body = mesh.mass_properties(MassSpec::TotalMass(3.5)).unwrap();
        let formula = MassProperties::solid_box(3.5, &sides).unwrap();
        let err = rel_err(body.inertia(), formula.inertia());
        assert!(err <= 1e-12, "sides {sides:?}: relative error {err:e}");
        assert!(body.center_of_mass().coords.norm() <= 1e-15 * sides.norm());
    }
}

/// The unit right tetrahedron (0, e_x, e_y, e_z) at unit density: `V = 1/6`, centroid
/// `(1/4, 1/4, 1/4)`, `∫x² dV = 1/60`, `∫xy dV = 1/120`, hence about the centroid
/// `I_xx = 2 (1/60 − 1/96) = 1/80` and `I_xy = −(1/120 − 1/96) = 1/480`.
fn check_unit_tetrahedron(mesh: &TriangleMesh) {
    assert!((mesh.volume() - 1.0 / 6.0).abs() <= 1e-16);
    let body = mesh.mass_properties(MassSpec::Density(1.0)).unwrap();
    assert!((body.mass() - 1.0 / 6.0).abs() <= 1e-16);
    assert!((body.center_of_mass() - Point3::new(0.25, 0.25, 0.25)).norm() <= 1e-16);
    let (d, o) = (1.0 / 80.0, 1.0 / 480.0);
    let expected = Matrix3::new(d, o, o, o, d, o, o, o, d);
    let err = rel_err(body.inertia(), &expected);
    assert!(err <= 1e-14, "relative error {err:e}");
}

#[test]
fn unit_tetrahedron_from_obj_ascii_stl_and_binary_stl_matches_its_closed_form() {
    for file in [
        "tetra.obj",
        "tetra_ascii.stl",
        "tetra_binary.stl",
        "tetra_binary_solid_header.stl",
    ] {
        let mesh = load_mesh(data(file), &ValidationOptions::default())
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(mesh.faces().len(), 4, "{file}");
        assert_eq!(mesh.vertices().len(), 4, "{file}");
        check_unit_tetrahedron(&mesh);
    }
}

#[test]
fn quads_in_two_obj_objects_are_merged_into_one_closed_box() {
    let mesh = load_mesh(data("cube_quads.obj"), &ValidationOptions::default()).unwrap();
    assert_eq!(mesh.faces().len(), 12);
    assert_eq!(mesh.vertices().len(), 8);
    let body = mesh.mass_properties(MassSpec::Density(2.0)).unwrap();
    let sides = Vector3::new(2.0, 1.0, 3.0);
    let formula = MassProperties::solid_box(2.0 * 6.0, &sides).unwrap();
    assert!((body.mass() - 12.0).abs() <= 1e-14);
    assert!((body.center_of_mass() - Point3::new(1.0, 0.5, 1.5)).norm() <= 1e-15);
    assert!(rel_err(body.inertia(), formula.inertia()) <= 1e-14);
}

#[test]
fn density_and_total_mass_describe_the_same_body() {
    let mesh = THandle::STANDARD.mesh().unwrap();
    let by_density = mesh.mass_properties(MassSpec::Density(7800.0)).unwrap();
    let by_mass = mesh
        .mass_properties(MassSpec::TotalMass(7800.0 * mesh.volume()))
        .unwrap();
    assert!((by_density.mass() - by_mass.mass()).abs() <= 1e-15 * by_mass.mass());
    assert_eq!(by_density.center_of_mass(), by_mass.center_of_mass());
    assert!(rel_err(by_density.inertia(), by_mass.inertia()) <= 1e-15);
    assert!(mesh.mass_properties(MassSpec::Density(0.0)).is_err());
    assert!(mesh.mass_properties(MassSpec::TotalMass(-1.0)).is_err());
    assert!(mesh.mass_properties(MassSpec::Density(f64::NAN)).is_err());
}

#[test]
fn inverted_mesh_is_flipped_only_on_request() {
    let options = ValidationOptions {
        flip_inverted: true,
        ..ValidationOptions::default()
    };
    let flipped = load_mesh(data("inverted.obj"), &options).unwrap();
    assert!(flipped.was_flipped());
    check_unit_tetrahedron(&flipped);
    let upright = load_mesh(data("tetra.obj"), &options).unwrap();
    assert!(!upright.was_flipped());
}

/// A torus mesh coarse enough to be irregular, and the T-handle: two test solids.
fn solids() -> Vec<TriangleMesh> {
    vec![
        THandle::STANDARD.mesh().unwrap(),
        shapes::torus_mesh(1.0, 0.3, 11, 7).unwrap(),
    ]
}

proptest! {
    #![proptest_config(crate::common::proptest_config(64))]

    /// Offsets up to 100 body sizes. (Further away, the translated coordinates themselves
    /// carry less than 1e-12 relative accuracy: their rounding error is ε |offset|.)
    #[test]
    fn translating_a_mesh_moves_the_center_of_mass_and_keeps_the_tensor(
        direction in vector(100.0),
    ) {
        for mesh in solids() {
            let size = {
                let (lo, hi) = mesh.bounding_box();
                (hi - lo).norm()
            };
            let offset = direction * size;
            let body = mesh.mass_properties(MassSpec::Density(1.0)).unwrap();
            let moved = mesh
                .transformed(&Isometry3::translation(offset.x, offset.y, offset.z))
                .unwrap()
                .mass_properties(MassSpec::Density(1.0))
                .unwrap();
            prop_assert!((moved.mass() - body.mass()).abs() <= 1e-12 * body.mass());
            let com_err = (moved.center_of_mass() - (body.center_of_mass() + offset)).norm();
            prop_assert!(com_err <= 1e-12 * size, "centre of mass off by {:e}", com_err);
            let err = rel_err(moved.inertia(), body.inertia());
            prop_assert!(err <= 1e-12, "tensor changed by {:e}", err);
        }
    }

    #[test]
    fn rotating_a_mesh_by_r_gives_r_i_rt(r in rotation(), offset in vector(1.0)) {
        for mesh in solids() {
            let body = mesh.mass_properties(MassSpec::Density(1.0)).unwrap();
            let turned = mesh
                .transformed(&Isometry3::from_parts(
                    Translation3::from(offset),
                    UnitQuaternion::from_rotation_matrix(&r),
                ))
                .unwrap()
                .mass_properties(MassSpec::Density(1.0))
                .unwrap();
            let expected = r.matrix() * body.inertia() * r.matrix().transpose();
            let err = rel_err(turned.inertia(), &expected);
            prop_assert!(err <= 1e-12, "R I Rᵀ off by {:e}", err);
            let com = r * body.center_of_mass() + offset;
            prop_assert!((turned.center_of_mass() - com).norm() <= 1e-12);
            // The body-level rotation agrees with the mesh-level one.
            let rotated = body.rotated(&r);
            prop_assert!(rel_err(rotated.inertia(), &expected) <= 1e-15);
        }
    }
}
