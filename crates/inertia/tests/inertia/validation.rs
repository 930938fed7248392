//! Bad meshes: each defect gives its own error, naming the face or edge, from OBJ, ASCII STL
//! and binary STL files alike.

use nalgebra::{Point3, Vector3};
use tumble_inertia::{
    LoadError, MeshError, THandle, TriangleMesh, ValidationOptions, load_mesh, shapes,
};

use crate::common::data;

fn load(name: &str) -> Result<TriangleMesh, LoadError> {
    load_mesh(data(name), &ValidationOptions::default())
}

/// The mesh error inside a load error, with the file name checked.
fn mesh_error(name: &str) -> MeshError {
    match load(name) {
        Err(LoadError::Mesh { path, source }) => {
            assert!(path.ends_with(name));
            source
        }
        other => panic!("{name}: expected a mesh error, got {other:?}"),
    }
}

/// The error and its causes, as `tumble inertia` prints them.
fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        s.push_str(": ");
        s.push_str(&cause.to_string());
        source = cause.source();
    }
    s
}

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

#[test]
fn open_mesh_names_its_boundary_edge_and_face() {
    for name in ["open.obj", "open_ascii.stl", "open_binary.stl"] {
        match mesh_error(name) {
            MeshError::OpenEdge { edge, face } => {
                // Face 0 is (v1 v3 v2) in the file; its edge v3 → v2 has no neighbour.
                assert_eq!(face, 0, "{name}");
                assert_eq!(
                    (edge.from_position, edge.to_position),
                    (p(0.0, 1.0, 0.0), p(1.0, 0.0, 0.0)),
                    "{name}"
                );
            }
            other => panic!("{name}: {other:?}"),
        }
        let message = chain(&load(name).unwrap_err());
        assert!(message.contains(name), "{message}");
        assert!(message.contains("open"), "{message}");
        assert!(message.contains("face 0"), "{message}");
        assert!(message.contains("(0, 1, 0) → (1, 0, 0)"), "{message}");
    }
}

#[test]
fn inverted_mesh_is_an_error_with_its_negative_volume() {
    for name in ["inverted.obj", "inverted_ascii.stl", "inverted_binary.stl"] {
        match mesh_error(name) {
            MeshError::Inverted { signed_volume } => {
                assert!((signed_volume + 1.0 / 6.0).abs() <= 1e-16, "{name}");
            }
            other => panic!("{name}: {other:?}"),
        }
        assert!(chain(&load(name).unwrap_err()).contains("inverted"));
    }
}

#[test]
fn degenerate_face_is_named_even_in_a_closed_consistent_mesh() {
    for name in [
        "degenerate.obj",
        "degenerate_ascii.stl",
        "degenerate_binary.stl",
    ] {
        match mesh_error(name) {
            MeshError::DegenerateFace {
                face,
                area,
                tolerance,
                ..
            } => {
                assert_eq!(face, 5, "{name}");
                assert_eq!(area, 0.0);
                // Relative tolerance 1e-12 times the squared bounding-box diagonal (√3)².
                assert!((tolerance - 3e-12).abs() <= 1e-26);
            }
            other => panic!("{name}: {other:?}"),
        }
        let message = chain(&load(name).unwrap_err());
        assert!(message.contains("degenerate face 5"), "{message}");
    }
    // Without the sliver the same surface has a hole where it was: the sliver is the only
    // defect of that file.
    let sliver_removed = {
        let mesh_faces = [[0, 2, 1], [0, 4, 3], [4, 1, 3], [0, 3, 2], [1, 2, 3]];
        let vertices = vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 0.0, 1.0),
            p(0.5, 0.0, 0.0),
        ];
        TriangleMesh::try_new(vertices, mesh_faces.to_vec())
    };
    assert!(matches!(sliver_removed, Err(MeshError::OpenEdge { .. })));
}

#[test]
fn non_manifold_edge_lists_every_face_that_uses_it() {
    for name in [
        "nonmanifold.obj",
        "nonmanifold_ascii.stl",
        "nonmanifold_binary.stl",
    ] {
        match mesh_error(name) {
            MeshError::NonManifoldEdge { edge, faces } => {
                assert_eq!(faces, vec![0, 1, 4, 5], "{name}");
                let ends = [edge.from_position, edge.to_position];
                assert!(ends.contains(&p(0.0, 0.0, 0.0)) && ends.contains(&p(1.0, 0.0, 0.0)));
            }
            other => panic!("{name}: {other:?}"),
        }
        assert!(chain(&load(name).unwrap_err()).contains("non-manifold"));
    }
}

#[test]
fn inconsistently_oriented_faces_are_named_with_their_shared_edge() {
    for name in [
        "inconsistent.obj",
        "inconsistent_ascii.stl",
        "inconsistent_binary.stl",
    ] {
        match mesh_error(name) {
            MeshError::InconsistentOrientation { edge, faces } => {
                assert_eq!(faces, [0, 3], "{name}");
                assert_eq!(
                    (edge.from_position, edge.to_position),
                    (p(0.0, 1.0, 0.0), p(1.0, 0.0, 0.0))
                );
            }
            other => panic!("{name}: {other:?}"),
        }
        assert!(chain(&load(name).unwrap_err()).contains("inconsistently oriented"));
    }
}

#[test]
fn flat_and_empty_meshes_are_rejected() {
    assert!(matches!(
        mesh_error("flat.obj"),
        MeshError::ZeroVolume { .. }
    ));
    assert_eq!(mesh_error("empty.obj"), MeshError::Empty);
}

#[test]
fn unreadable_unknown_and_malformed_files_are_load_errors() {
    assert!(matches!(
        load("does-not-exist.obj"),
        Err(LoadError::Io { .. })
    ));
    assert!(matches!(
        load_mesh(
            data("tetra.obj").with_extension("ply"),
            &ValidationOptions::default()
        ),
        Err(LoadError::UnknownFormat { .. })
    ));
    // An OBJ file read as STL: neither valid ASCII STL ("solid ...") nor a binary one.
    let dir = std::env::temp_dir().join(format!("tumble-inertia-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fake = dir.join("not-really.stl");
    std::fs::copy(data("tetra.obj"), &fake).unwrap();
    let result = load_mesh(&fake, &ValidationOptions::default());
    std::fs::remove_dir_all(&dir).unwrap();
    // Not starting with `solid`, it is judged as binary: its size is not what its header's
    // triangle count implies.
    assert!(
        matches!(result, Err(LoadError::BinaryStlSize { .. })),
        "{result:?}"
    );
}

#[test]
fn index_and_coordinate_errors_are_named() {
    let tetra = vec![
        p(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.0),
        p(0.0, 1.0, 0.0),
        p(0.0, 0.0, 1.0),
    ];
    let faces = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 7]];
    assert_eq!(
        TriangleMesh::try_new(tetra.clone(), faces),
        Err(MeshError::VertexIndexOutOfRange {
            face: 3,
            index: 7,
            vertex_count: 4
        })
    );
    let mut bad = tetra.clone();
    bad[3].z = f64::NAN;
    let faces = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    assert!(matches!(
        TriangleMesh::try_new(bad, faces.clone()),
        Err(MeshError::NonFiniteVertex { vertex: 3, .. })
    ));
    let repeated = vec![[0, 2, 1], [0, 1, 3], [0, 3, 3], [1, 2, 3]];
    assert!(matches!(
        TriangleMesh::try_new(tetra.clone(), repeated),
        Err(MeshError::DegenerateFace { face: 2, .. })
    ));
    let options = ValidationOptions {
        relative_area_tolerance: -1.0,
        ..ValidationOptions::default()
    };
    assert!(matches!(
        TriangleMesh::try_new_with(tetra, faces, &options),
        Err(MeshError::InvalidTolerance { .. })
    ));
}

#[test]
fn degeneracy_is_judged_relative_to_the_mesh_size_not_in_absolute_units() {
    // The same meshes in kilometres and in micrometres: valid at every scale...
    for scale in [1e-9, 1e-3, 1.0, 1e3, 1e9] {
        let handle = THandle {
            bar_length: 0.08 * scale,
            bar_thickness: 0.02 * scale,
            depth: 0.02 * scale,
            stem_width: 0.02 * scale,
            stem_length: 0.06 * scale,
        };
        assert!(handle.mesh().is_ok(), "scale {scale}");
        assert!(shapes::box_mesh(&(Vector3::new(1.0, 2.0, 3.0) * scale)).is_ok());
    }
    // ...and a sliver whose area is 1e-13 of the size² is degenerate at every scale.
    for scale in [1e-6, 1.0, 1e6] {
        let eps = 1e-13;
        let vertices: Vec<Point3<f64>> = [
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 0.0, 1.0),
            p(0.5, eps, 0.0),
        ]
        .iter()
        .map(|v| v * scale)
        .collect();
        // As degenerate.obj, but the sliver's apex is lifted by 1e-13 off the edge.
        let faces = vec![
            [0, 2, 1],
            [0, 4, 3],
            [4, 1, 3],
            [0, 3, 2],
            [1, 2, 3],
            [0, 1, 4],
        ];
        let result = TriangleMesh::try_new(vertices, faces);
        assert!(
            matches!(result, Err(MeshError::DegenerateFace { face: 5, .. })),
            "scale {scale}: {result:?}"
        );
    }
}
