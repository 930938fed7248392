//! `tumble inertia`: output contract (JSON keys, units), flags, and bad files.

use std::path::PathBuf;
use std::process::{Command, Output};

use nalgebra::{Matrix3, Vector3};
use serde_json::Value;
use tumble_inertia::{MassSpec, THandle};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn mesh_data(name: &str) -> String {
    root()
        .join("crates/inertia/tests/data")
        .join(name)
        .display()
        .to_string()
}

fn t_handle() -> String {
    root().join("scenes/t-handle.obj").display().to_string()
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

fn vec3(v: &Value) -> Vector3<f64> {
    let a = v.as_array().expect("array of 3");
    assert_eq!(a.len(), 3);
    Vector3::from_fn(|i, _| a[i].as_f64().unwrap())
}

/// A row-major nested 3×3 array.
fn mat3(v: &Value) -> Matrix3<f64> {
    let rows = v.as_array().expect("array of 3 rows");
    assert_eq!(rows.len(), 3);
    let mut m = Matrix3::zeros();
    for (i, row) in rows.iter().enumerate() {
        m.set_row(i, &vec3(row).transpose());
    }
    m
}

fn off_diagonal(m: &Matrix3<f64>) -> f64 {
    let mut off = *m;
    off.fill_diagonal(0.0);
    off.norm()
}

#[test]
fn json_output_has_exactly_the_documented_keys_and_the_t_handle_values() {
    let v = json(&["inertia", &t_handle(), "--json"]);
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "center_of_mass",
            "inertia",
            "mass",
            "principal_axes",
            "principal_euler_zyz",
            "principal_moments",
            "volume"
        ]
    );
    // Default density 1 kg/m³: mass equals volume.
    let analytic = THandle::STANDARD
        .mass_properties(MassSpec::Density(1.0))
        .unwrap();
    let mass = v["mass"].as_f64().unwrap();
    assert!((mass - analytic.mass()).abs() <= 1e-12 * analytic.mass());
    assert_eq!(v["volume"].as_f64().unwrap(), mass);
    let com = vec3(&v["center_of_mass"]);
    assert!((com - analytic.center_of_mass().coords).norm() <= 1e-14);
    let inertia = mat3(&v["inertia"]);
    assert!((inertia - analytic.inertia()).norm() <= 1e-12 * analytic.inertia().norm());
    let moments = vec3(&v["principal_moments"]);
    assert!(moments[0] < moments[1] && moments[1] < moments[2]);
    // Columns of principal_axes are the axes: Qᵀ I Q = diag(moments), det Q = +1.
    let q = mat3(&v["principal_axes"]);
    assert!((q.determinant() - 1.0).abs() <= 1e-14);
    let d = q.transpose() * inertia * q;
    assert!(off_diagonal(&d) <= 1e-12 * inertia.norm());
    assert!((d.diagonal() - moments).norm() <= 1e-12 * moments.norm());
    assert_eq!(vec3(&v["principal_euler_zyz"]).len(), 3);
}

#[test]
fn euler_flag_turns_the_tensor_and_the_principal_angles_make_it_diagonal() {
    let plain = json(&["inertia", &t_handle(), "--json"]);
    let inertia = mat3(&plain["inertia"]);
    // An arbitrary turn: R I Rᵀ with R = Rz(φ) Ry(θ) Rz(ψ).
    let (phi, theta, psi) = (0.3, -1.2, 2.0);
    let turned = json(&["inertia", &t_handle(), "--json", "--euler", "0.3,-1.2,2"]);
    let r = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), phi)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::y_axis(), theta)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
    let expected = r.matrix() * inertia * r.matrix().transpose();
    assert!((mat3(&turned["inertia"]) - expected).norm() <= 1e-12 * inertia.norm());
    assert!(off_diagonal(&expected) > 1e-3 * inertia.norm());
    // The turned body's principal angles, fed back as --euler, give a diagonal tensor.
    let angles = vec3(&plain["principal_euler_zyz"]);
    let arg = format!("{},{},{}", angles.x, angles.y, angles.z);
    let aligned = json(&["inertia", &t_handle(), "--json", "--euler", &arg]);
    let diagonalized = mat3(&aligned["inertia"]);
    assert!(off_diagonal(&diagonalized) <= 1e-12 * inertia.norm());
    let moments = vec3(&plain["principal_moments"]);
    assert!((diagonalized.diagonal() - moments).norm() <= 1e-12 * moments.norm());
}

#[test]
fn mass_and_density_flags_set_the_mass() {
    let by_mass = json(&["inertia", &t_handle(), "--json", "--mass", "0.25"]);
    assert_eq!(by_mass["mass"].as_f64().unwrap(), 0.25);
    let by_density = json(&["inertia", &t_handle(), "--json", "--density", "2700"]);
    let expected = 2700.0 * THandle::STANDARD.volume();
    assert!((by_density["mass"].as_f64().unwrap() - expected).abs() <= 1e-12 * expected);
    let out = tumble(&["inertia", &t_handle(), "--mass", "1", "--density", "2"]);
    assert!(!out.status.success(), "--mass and --density must conflict");
    for bad in [["--density", "0"], ["--mass", "-1"], ["--density", "nan"]] {
        let out = tumble(&["inertia", &t_handle(), bad[0], bad[1]]);
        assert!(!out.status.success(), "{bad:?} accepted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(bad[0].trim_start_matches("--")),
            "{bad:?}: {err}"
        );
    }
}

#[test]
fn human_output_states_si_units_and_the_default_density() {
    let out = tumble(&["inertia", &t_handle()]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "16 vertices, 28 triangles",
        "kg (default density 1 kg/m³)",
        "m³",
        "centre of mass",
        "kg·m²",
        "principal moments",
        "principal axes",
        "ZYZ Euler angles",
    ] {
        assert!(text.contains(needle), "missing `{needle}` in:\n{text}");
    }
    let help = tumble(&["inertia", "--help"]);
    let help = String::from_utf8(help.stdout).unwrap();
    assert!(help.contains("density is 1"), "{help}");
}

#[test]
fn bad_meshes_exit_non_zero_with_a_message_naming_the_problem() {
    let cases = [
        ("open.obj", "mesh is open"),
        ("open_binary.stl", "face 0 only"),
        ("inverted.obj", "inverted"),
        ("inverted_ascii.stl", "inverted"),
        ("degenerate.obj", "degenerate face 5"),
        ("degenerate_binary.stl", "degenerate face 5"),
        ("nonmanifold.obj", "non-manifold"),
        ("nonmanifold_ascii.stl", "shared by 4 faces"),
        ("inconsistent.obj", "faces 0 and 3"),
        ("inconsistent_binary.stl", "inconsistently oriented"),
        ("flat.obj", "encloses no volume"),
        ("empty.obj", "no faces"),
    ];
    for (file, problem) in cases {
        let out = tumble(&["inertia", &mesh_data(file)]);
        assert!(!out.status.success(), "{file} accepted");
        assert!(out.stdout.is_empty(), "{file}: printed results anyway");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(file),
            "{file}: message does not name the file: {err}"
        );
        assert!(
            err.contains(problem),
            "{file}: expected `{problem}` in: {err}"
        );
    }
}

#[test]
fn flip_inverted_flag_accepts_an_inverted_mesh_with_a_note() {
    let out = tumble(&[
        "inertia",
        &mesh_data("inverted.obj"),
        "--flip-inverted",
        "--json",
    ]);
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((v["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() <= 1e-16);
    assert!(String::from_utf8_lossy(&out.stderr).contains("faces were reversed"));
}

#[test]
fn missing_files_unknown_formats_and_bad_angles_fail_cleanly() {
    let out = tumble(&["inertia", "no/such/mesh.stl"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/mesh.stl"));
    let out = tumble(&["inertia", "Cargo.toml"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown mesh format"));
    for euler in ["1,2", "1,nan,2", "a,b,c"] {
        let out = tumble(&["inertia", &t_handle(), "--euler", euler]);
        assert!(!out.status.success(), "--euler {euler} accepted");
        assert!(out.stdout.is_empty());
    }
}
