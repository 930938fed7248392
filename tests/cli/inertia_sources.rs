//! `tumble inertia` with sources besides one mesh: point masses, placed primitives, units, and
//! all of them combined, checked against closed forms and the library's own composition.

use std::path::PathBuf;
use std::process::{Command, Output};

use nalgebra::{Matrix3, Point3, Vector3};
use serde_json::Value;
use tumble_inertia::{MassProperties, MassSpec, Placement, THandle};

fn t_handle() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/t-handle.obj")
        .display()
        .to_string()
}

fn tumble(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(args)
        .output()
        .expect("cannot run the tumble binary")
}

fn json(args: &[&str]) -> Value {
    let out = tumble(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is not one JSON value")
}

fn mat3(v: &Value) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| v[i][j].as_f64().unwrap())
}

fn vec3(v: &Value) -> Vector3<f64> {
    Vector3::from_fn(|i, _| v[i].as_f64().unwrap())
}

fn fails_naming(args: &[&str], needles: &[&str]) {
    let out = tumble(args);
    assert!(!out.status.success(), "{args:?} accepted");
    assert!(out.stdout.is_empty(), "{args:?} printed results anyway");
    let err = String::from_utf8_lossy(&out.stderr);
    for needle in needles {
        assert!(
            err.contains(needle),
            "{args:?}: expected `{needle}` in: {err}"
        );
    }
}

#[test]
fn a_dumbbell_of_point_flags_has_the_closed_form_tensor() {
    // Two 1.5 kg points at x = ±0.25: I = diag(0, 2 m d², 2 m d²) about the middle.
    let v = json(&[
        "inertia",
        "--point",
        "1.5,-0.25,0,0",
        "--point",
        "1.5,0.25,0,0",
        "--json",
    ]);
    assert_eq!(v["mass"].as_f64().unwrap(), 3.0);
    let expected = Matrix3::from_diagonal(&Vector3::new(0.0, 0.1875, 0.1875));
    assert!((mat3(&v["inertia"]) - expected).norm() < 1e-16);
    assert_eq!(vec3(&v["center_of_mass"]), Vector3::zeros());
}

#[test]
fn a_point_csv_file_gives_the_same_body_as_point_flags() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("points.csv");
    std::fs::write(
        &csv,
        "# m, x, y, z\nm,x,y,z\n1,0,0,0\n2,0.3,0.1,-0.2\n0.5,0,0.4,0\n",
    )
    .unwrap();
    let from_file = json(&["inertia", "--points", csv.to_str().unwrap(), "--json"]);
    let from_flags = json(&[
        "inertia",
        "--point",
        "1,0,0,0",
        "--point",
        "2,0.3,0.1,-0.2",
        "--point",
        "0.5,0,0.4,0",
        "--json",
    ]);
    assert_eq!(from_file, from_flags);
}

#[test]
fn a_placed_box_shape_matches_the_library_composition() {
    let v = json(&[
        "inertia",
        "--shape",
        "box:2,1,0.5",
        "--mass",
        "3",
        "--at",
        "1,-2,0.5",
        "--euler",
        "0.3,-pi/5,2",
        "--json",
    ]);
    let placement = Placement {
        at: Vector3::new(1.0, -2.0, 0.5),
        euler: Vector3::new(0.3, -std::f64::consts::PI / 5.0, 2.0),
    };
    let expected =
        placement.place(&MassProperties::solid_box(3.0, &Vector3::new(2.0, 1.0, 0.5)).unwrap());
    assert!((mat3(&v["inertia"]) - expected.inertia()).norm() < 1e-14);
    assert!((vec3(&v["center_of_mass"]) - expected.center_of_mass().coords).norm() < 1e-15);
    assert_eq!(v["volume"].as_f64().unwrap(), 1.0);
}

#[test]
fn two_boxes_as_shapes_give_the_t_handle_mesh() {
    // The T-handle is a bar (80 × 20 × 20 mm, centre z = +10 mm) and a stem (20 × 20 × 60 mm,
    // centre z = −30 mm) of one density: shapes and the mesh agree to round-off.
    let mesh = json(&["inertia", &t_handle(), "--density", "2700", "--json"]);
    let shapes = json(&[
        "inertia",
        "--shape",
        "box:0.08,0.02,0.02",
        "--density",
        "2700",
        "--at",
        "0,0,0.01",
        "--shape",
        "box:0.02,0.02,0.06",
        "--density",
        "2700",
        "--at",
        "0,0,-0.03",
        "--json",
    ]);
    let scale = mat3(&mesh["inertia"]).norm();
    assert!((mat3(&mesh["inertia"]) - mat3(&shapes["inertia"])).norm() < 1e-13 * scale);
    let m = mesh["mass"].as_f64().unwrap();
    assert!((m - shapes["mass"].as_f64().unwrap()).abs() < 1e-14 * m);
    assert!((m - 2700.0 * THandle::STANDARD.volume()).abs() < 1e-13 * m);
}

#[test]
fn a_mesh_in_millimetres_with_units_mm_is_the_metre_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let mm = dir.path().join("t-handle-mm.obj");
    let mesh = THandle::STANDARD.mesh().unwrap().scaled(1e3).unwrap();
    mesh.write_obj(
        std::fs::File::create(&mm).unwrap(),
        "T-handle in millimetres",
    )
    .unwrap();
    let mm = mm.to_str().unwrap();
    let metres = json(&["inertia", &t_handle(), "--density", "2700", "--json"]);
    let read_mm = json(&[
        "inertia",
        mm,
        "--units",
        "mm",
        "--density",
        "2700",
        "--json",
    ]);
    let raw = json(&["inertia", mm, "--density", "2700", "--json"]);
    let rel = |a: f64, b: f64| ((a - b) / b).abs();
    let (m, v) = (
        metres["mass"].as_f64().unwrap(),
        metres["volume"].as_f64().unwrap(),
    );
    assert!(rel(read_mm["mass"].as_f64().unwrap(), m) < 1e-14);
    assert!(rel(raw["volume"].as_f64().unwrap(), 1e9 * v) < 1e-14);
    let i = mat3(&metres["inertia"]);
    assert!((mat3(&read_mm["inertia"]) - i).norm() < 1e-13 * i.norm());
    // Read as metres, the same density gives a tensor 1e15 times larger (mass 1e9, length² 1e6).
    assert!((mat3(&raw["inertia"]) / 1e15 - i).norm() < 1e-13 * i.norm());
    assert!((vec3(&raw["center_of_mass"]) / 1e3 - vec3(&metres["center_of_mass"])).norm() < 1e-15);
    fails_naming(
        &["inertia", mm, "--units", "inch"],
        &["--units", "inch", "mm, cm, m"],
    );
}

#[test]
fn a_mesh_a_shape_and_points_combine_into_one_body() {
    let v = json(&[
        "inertia",
        &t_handle(),
        "--mass",
        "0.05",
        "--point",
        "0.01,0,0,-0.1",
        "--shape",
        "sphere:0.01",
        "--mass",
        "0.02",
        "--at",
        "0.04,0,0.01",
        "--json",
    ]);
    let handle = THandle::STANDARD
        .mass_properties(MassSpec::TotalMass(0.05))
        .unwrap();
    let point = MassProperties::from_point_masses(&[tumble_inertia::PointMass::new(
        0.01,
        Point3::new(0.0, 0.0, -0.1),
    )])
    .unwrap();
    let ball = MassProperties::solid_sphere(0.02, 0.01)
        .unwrap()
        .translated(&Vector3::new(0.04, 0.0, 0.01));
    let expected = MassProperties::combine_all([&handle, &point, &ball]).unwrap();
    assert!((v["mass"].as_f64().unwrap() - 0.08).abs() < 1e-16);
    assert!((mat3(&v["inertia"]) - expected.inertia()).norm() < 1e-12 * expected.inertia().norm());
}

#[test]
fn bad_bodies_fail_before_any_output_naming_the_flag() {
    fails_naming(
        &["inertia", "--point", "-1,0,0,0"],
        &["--point -1,0,0,0", "mass -1"],
    );
    fails_naming(
        &["inertia", "--point", "1,0,0"],
        &["--point 1,0,0", "four values"],
    );
    fails_naming(&["inertia"], &["no body given"]);
    fails_naming(
        &["inertia", "--shape", "box:1,1,1"],
        &["--shape box:1,1,1", "--mass"],
    );
    fails_naming(
        &["inertia", "--shape", "rod:1", "--density", "3"],
        &["rod", "no volume"],
    );
    fails_naming(
        &["inertia", "--shape", "cube:1", "--mass", "1"],
        &["cube", "box:a,b,c"],
    );
    fails_naming(
        &["inertia", "--shape", "box:1,-1,1", "--mass", "1"],
        &["box side y"],
    );
    fails_naming(
        &[
            "inertia", "--at", "1,0,0", "--shape", "sphere:1", "--mass", "1",
        ],
        &["--at"],
    );
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.csv");
    std::fs::write(&empty, "# nothing here\n").unwrap();
    fails_naming(
        &["inertia", "--points", empty.to_str().unwrap()],
        &["empty.csv", "no point masses"],
    );
    let bad = dir.path().join("bad.csv");
    std::fs::write(&bad, "1,0,0,0\n2,0,0,nan\n").unwrap();
    fails_naming(
        &["inertia", "--points", bad.to_str().unwrap()],
        &["bad.csv", "line 2", "finite"],
    );
}
