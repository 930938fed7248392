//! The T-handle: mesh against the analytic composition of boxes, the shipped OBJ file against
//! the generator, three distinct moments.

use std::collections::HashSet;

use nalgebra::Point3;
use tumble_inertia::{MassSpec, THandle, ValidationOptions, load_mesh};

use crate::common::{rel_err, workspace_root};

#[test]
fn t_handle_mesh_matches_the_composition_of_boxes_to_1e_12() {
    let mesh = THandle::STANDARD.mesh().unwrap();
    for spec in [
        MassSpec::Density(1.0),
        MassSpec::Density(2700.0),
        MassSpec::TotalMass(0.25),
    ] {
        let meshed = mesh.mass_properties(spec).unwrap();
        let analytic = THandle::STANDARD.mass_properties(spec).unwrap();
        assert!((meshed.mass() - analytic.mass()).abs() <= 1e-12 * analytic.mass());
        let com_err = (meshed.center_of_mass() - analytic.center_of_mass()).norm();
        assert!(com_err <= 1e-12 * 0.1, "centre of mass off by {com_err:e}");
        let err = rel_err(meshed.inertia(), analytic.inertia());
        assert!(err <= 1e-12, "{spec:?}: relative error {err:e}");
    }
    assert!((mesh.volume() - THandle::STANDARD.volume()).abs() <= 1e-12 * mesh.volume());
}

#[test]
fn t_handle_analytic_values_are_the_hand_computed_ones() {
    // Density 1: bar 0.08·0.02·0.02 = 3.2e-5 m³ at z = 0.01, stem 0.02·0.02·0.06 = 2.4e-5 m³ at
    // z = −0.03: M = 5.6e-5 kg, z_c = (3.2e-5·0.01 − 2.4e-5·0.03)/5.6e-5 = −1/140 m.
    let body = THandle::STANDARD
        .mass_properties(MassSpec::Density(1.0))
        .unwrap();
    assert!((body.mass() - 5.6e-5).abs() <= 1e-18);
    assert!((body.center_of_mass() - Point3::new(0.0, 0.0, -1.0 / 140.0)).norm() <= 1e-17);
    // I_z = bar M(a² + d²)/12 + stem M(s² + d²)/12 (no shift: both centres are on z).
    let i_z = 3.2e-5 * (0.08f64.powi(2) + 0.02f64.powi(2)) / 12.0
        + 2.4e-5 * (0.02f64.powi(2) + 0.02f64.powi(2)) / 12.0;
    assert!((body.inertia()[(2, 2)] - i_z).abs() <= 1e-14 * i_z);
}

#[test]
fn t_handle_has_three_distinct_principal_moments_along_its_symmetry_axes() {
    let body = THandle::STANDARD
        .mass_properties(MassSpec::Density(1.0))
        .unwrap();
    let m = body.principal().moments;
    // Well separated (Dzhanibekov needs I1 < I2 < I3): ratio about 1 : 1.63 : 2.44.
    assert!(m[1] > 1.5 * m[0] && m[2] > 1.4 * m[1], "{m:?}");
    // By the mirror symmetries, the axes are z (smallest), x (intermediate), y (largest).
    let q = body.principal().axes.matrix();
    assert_eq!(q.column(0).into_owned(), nalgebra::Vector3::z());
    assert_eq!(q.column(1).into_owned(), nalgebra::Vector3::x());
    assert_eq!(q.column(2).into_owned(), nalgebra::Vector3::y());
}

#[test]
fn t_handle_mesh_is_one_closed_surface_without_internal_faces() {
    let mesh = THandle::STANDARD.mesh().unwrap();
    let edges: HashSet<(usize, usize)> = mesh
        .faces()
        .iter()
        .flat_map(|f| (0..3).map(move |k| (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3]))))
        .collect();
    assert_eq!(mesh.vertices().len(), 16);
    assert_eq!(mesh.faces().len(), 28);
    // Euler characteristic 2: one sphere-like surface, no internal wall between bar and stem.
    assert_eq!(mesh.vertices().len() + mesh.faces().len() - edges.len(), 2);
    // No face lies in the plane z = 0 inside the solid (where bar and stem meet): the only
    // faces in that plane are the bar's underside, outside the stem's footprint.
    for f in mesh.faces() {
        let vs = f.map(|i| mesh.vertices()[i]);
        if vs.iter().all(|v| v.z == 0.0) {
            let centroid_x = vs.iter().map(|v| v.x).sum::<f64>() / 3.0;
            assert!(centroid_x.abs() > 0.01, "internal face {f:?}");
        }
    }
}

#[test]
fn scenes_t_handle_obj_matches_the_generator() {
    // Regenerate with `TUMBLE_WRITE_SCENES=1 cargo test -p tumble-inertia t_handle`.
    let path = workspace_root().join("scenes/t-handle.obj");
    let mut generated = Vec::new();
    THandle::STANDARD.write_obj(&mut generated).unwrap();
    if std::env::var_os("TUMBLE_WRITE_SCENES").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &generated).unwrap();
    }
    let shipped = std::fs::read(&path).expect("scenes/t-handle.obj is missing");
    assert!(
        shipped == generated,
        "scenes/t-handle.obj differs from THandle::STANDARD.write_obj"
    );
    // And it loads back to the generator's mesh, bit for bit.
    let loaded = load_mesh(&path, &ValidationOptions::default()).unwrap();
    let mesh = THandle::STANDARD.mesh().unwrap();
    assert_eq!(loaded.volume(), mesh.volume());
    let a = loaded.mass_properties(MassSpec::Density(1.0)).unwrap();
    let b = mesh.mass_properties(MassSpec::Density(1.0)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn t_handle_rejects_dimensions_that_are_not_a_t() {
    let wide_stem = THandle {
        stem_width: 0.08,
        ..THandle::STANDARD
    };
    assert!(wide_stem.mesh().is_err());
    assert!(wide_stem.mass_properties(MassSpec::Density(1.0)).is_err());
    let negative = THandle {
        depth: -0.02,
        ..THandle::STANDARD
    };
    assert!(negative.mesh().is_err());
    assert!(negative.mass_properties(MassSpec::Density(1.0)).is_err());
}
