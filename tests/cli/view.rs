//! `tumble view`: the pages are self-contained and small, hold the run they were made from
//! (checked against physics: conserved `L_z`, the bead on its hoop, the T-handle's flip seen
//! in both its pose and its rows), and bad requests are refused before anything is written.
//! The pages' behaviour in a browser is tested by `.ci/browser`.

use std::path::Path;

use base64::Engine as _;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use serde_json::Value;
use tempfile::TempDir;
use tumble_kinematics::EulerConvention;

use crate::support::{root, stderr, succeeds, tumble_in};

/// The data a page holds.
fn page_data(path: &Path) -> Value {
    let html = std::fs::read_to_string(path).unwrap();
    let start = html
        .find(r#"<script type="application/json" id="tumble-data">"#)
        .unwrap();
    let rest = &html[start..];
    let open = rest.find('>').unwrap() + 1;
    let close = rest.find("</script>").unwrap();
    serde_json::from_str(&rest[open..close]).unwrap()
}

/// A named array of a run page: `width` floats a frame.
fn array(data: &Value, name: &str) -> Vec<Vec<f64>> {
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(data["data"].as_str().unwrap())
        .unwrap();
    let floats: Vec<f64> = bytes
        .chunks(4)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect();
    let frames = data["frames"].as_u64().unwrap() as usize;
    let entry = data["layout"]
        .as_array()
        .unwrap()
        .iter()
        .find(|a| a["name"] == name)
        .unwrap_or_else(|| panic!("no array {name}"));
    let (w, at) = (
        entry["width"].as_u64().unwrap() as usize,
        entry["offset"].as_u64().unwrap() as usize,
    );
    floats[at..at + w * frames]
        .chunks(w)
        .map(<[f64]>::to_vec)
        .collect()
}

fn column(data: &Value, name: &str) -> Vec<f64> {
    array(data, &format!("col:{name}"))
        .into_iter()
        .map(|v| v[0])
        .collect()
}

#[test]
fn a_ten_second_free_hoop_page_is_self_contained_and_under_two_megabytes() {
    let tmp = TempDir::new().unwrap();
    let out = succeeds(
        tmp.path(),
        &["view", "free-hoop", "--t-end", "10", "-o", "hoop.html"],
    );
    let size = std::fs::metadata(tmp.path().join("hoop.html"))
        .unwrap()
        .len();
    assert!(size < 2_000_000, "{size} bytes");
    let html = std::fs::read_to_string(tmp.path().join("hoop.html")).unwrap();
    // Nothing is loaded from elsewhere: no script or style by address.
    for outside in [
        "<script src",
        "<link",
        "@import",
        "import(\"http",
        "from \"http",
        "from 'http",
    ] {
        assert!(!html.contains(outside), "{outside}");
    }
    assert!(
        html.contains("Copyright © 2010-2026 three.js authors"),
        "three.js's licence is shipped"
    );
    assert!(
        stderr(&out).contains("601 frames of free-hoop"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_free_hoop_page_holds_the_run_its_bead_on_the_hoop_and_lz_conserved() {
    let tmp = TempDir::new().unwrap();
    succeeds(
        tmp.path(),
        &["view", "free-hoop", "--t-end", "4", "-o", "hoop.html"],
    );
    let data = page_data(&tmp.path().join("hoop.html"));
    let t = column(&data, "t");
    assert_eq!(t.len(), 241);
    for (k, &tk) in t.iter().enumerate() {
        assert!((tk - k as f64 / 60.0).abs() < 1e-6, "frame {k} at t = {tk}");
    }
    // The hoop (object 0) turns with the rows' quaternion; the bead (object 1) lies on it:
    // at distance a = 1 from the centre, in the plane normal to R e_z.
    let (hoop, bead) = (array(&data, "0.q"), array(&data, "1.p"));
    let alpha = column(&data, "alpha");
    for k in 0..t.len() {
        let q = UnitQuaternion::from_quaternion(Quaternion::new(
            hoop[k][3], hoop[k][0], hoop[k][1], hoop[k][2],
        ));
        let b = Vector3::new(bead[k][0], bead[k][1], bead[k][2]);
        assert!(
            (b.norm() - 1.0).abs() < 1e-5,
            "frame {k}: |bead| = {}",
            b.norm()
        );
        assert!(
            (q * Vector3::z()).dot(&b).abs() < 1e-5,
            "frame {k}: bead off the hoop's plane"
        );
        let expected = q * Vector3::new(alpha[k].cos(), alpha[k].sin(), 0.0);
        assert!((expected - b).norm() < 1e-5, "frame {k}");
    }
    // L_z is conserved (gravity has no moment about the vertical), to f32 rounding.
    let l = array(&data, "L");
    for v in &l {
        assert!(
            (v[2] - l[0][2]).abs() < 1e-6 * l[0][2].abs(),
            "Lz {} vs {}",
            v[2],
            l[0][2]
        );
    }
    // ω and L are not parallel while the bead moves (the hoop's tensor is not isotropic).
    let w = array(&data, "omega");
    let angle = |a: &[f64], b: &[f64]| {
        let (a, b) = (
            Vector3::new(a[0], a[1], a[2]),
            Vector3::new(b[0], b[1], b[2]),
        );
        (a.dot(&b) / (a.norm() * b.norm())).clamp(-1.0, 1.0).acos()
    };
    let widest = (0..t.len())
        .map(|k| angle(&w[k], &l[k]))
        .fold(0.0, f64::max);
    assert!(widest > 0.05, "ω and L at most {widest} rad apart");
}

#[test]
fn a_model_page_places_its_bodies_and_masses_by_the_models_own_geometry() {
    // The hoop with two beads (models/hoop-two-beads.toml): the hoop turns about the vertical
    // by phi, each bead at a (sin α cos φ, sin α sin φ, −cos α) — on the hoop: at distance a
    // from its centre, in its plane.
    let tmp = TempDir::new().unwrap();
    let model = root().join("models/hoop-two-beads.toml");
    succeeds(
        tmp.path(),
        &[
            "view",
            model.to_str().unwrap(),
            "--t-end",
            "2",
            "-o",
            "beads.html",
        ],
    );
    let data = page_data(&tmp.path().join("beads.html"));
    let objects = data["objects"].as_array().unwrap();
    let names: Vec<&str> = objects
        .iter()
        .map(|o| o["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["body", "point", "point", "pivot"]);
    // The hoop, known by its inertia (a ring: I₃ = M a²), is drawn as a torus of radius a.
    let hoop = &objects[0]["parts"][0];
    assert_eq!(hoop["kind"], "torus");
    let a = hoop["dims"][0].as_f64().unwrap();
    let turn = array(&data, "0.q");
    for bead in ["1.p", "2.p"] {
        for (k, p) in array(&data, bead).iter().enumerate() {
            let q = UnitQuaternion::from_quaternion(Quaternion::new(
                turn[k][3], turn[k][0], turn[k][1], turn[k][2],
            ));
            let torus_turn = {
                let t = &hoop["quaternion"];
                UnitQuaternion::from_quaternion(Quaternion::new(
                    t[3].as_f64().unwrap(),
                    t[0].as_f64().unwrap(),
                    t[1].as_f64().unwrap(),
                    t[2].as_f64().unwrap(),
                ))
            };
            let normal = q * (torus_turn * Vector3::z());
            let b = Vector3::new(p[0], p[1], p[2]);
            assert!(
                (b.norm() - a).abs() < 1e-5 * a,
                "{bead} frame {k}: |r| = {}",
                b.norm()
            );
            assert!(
                normal.dot(&b).abs() < 1e-5 * a,
                "{bead} frame {k}: off the hoop's plane"
            );
        }
    }
}

#[test]
fn the_t_handle_page_flips_as_its_rows_do() {
    // For the handle in its own (principal) frame, the crossbar's direction in the lab dotted
    // with L is the body component L_x = I_xx ω_x: the trail (on the crossbar) and the ω_x
    // column must agree at every frame, and ω_x changes sign at each flip.
    let tmp = TempDir::new().unwrap();
    let scene = root().join("scenes/t-handle-flip.toml");
    succeeds(
        tmp.path(),
        &["view", scene.to_str().unwrap(), "-o", "flip.html"],
    );
    let data = page_data(&tmp.path().join("flip.html"));
    let mesh = root().join("scenes/t-handle.obj");
    let report = succeeds(
        tmp.path(),
        &[
            "inertia",
            mesh.to_str().unwrap(),
            "--mass",
            "0.05",
            "--json",
        ],
    );
    let report: Value = serde_json::from_slice(&report.stdout).unwrap();
    let ixx = report["inertia"][0][0].as_f64().unwrap();
    let (trail, l, wx) = (
        array(&data, "trail"),
        array(&data, "L"),
        column(&data, "omega_x"),
    );
    let mut flips = 0;
    for k in 0..wx.len() {
        let tip = Vector3::new(trail[k][0], trail[k][1], trail[k][2]).normalize();
        let lk = Vector3::new(l[k][0], l[k][1], l[k][2]);
        let lx = tip.dot(&lk).abs();
        assert!(
            (lx - ixx * wx[k].abs()).abs() < 1e-4 * ixx * 20.0,
            "frame {k}: |crossbar · L| = {lx}, I_xx |ω_x| = {}",
            ixx * wx[k].abs()
        );
        if k > 0 && wx[k].signum() != wx[k - 1].signum() {
            flips += 1;
        }
    }
    assert!(flips >= 4, "{flips} flips in 10 s");
}

#[test]
fn the_explorer_holds_the_body_of_tumble_inertia_and_its_principal_frame_in_every_convention() {
    let tmp = TempDir::new().unwrap();
    let mesh = root().join("scenes/t-handle.obj");
    let mesh = mesh.to_str().unwrap();
    succeeds(
        tmp.path(),
        &["view", "--inertia", mesh, "--mass", "0.05", "-o", "x.html"],
    );
    let data = page_data(&tmp.path().join("x.html"));
    let report = succeeds(tmp.path(), &["inertia", mesh, "--mass", "0.05", "--json"]);
    let report: Value = serde_json::from_slice(&report.stdout).unwrap();
    for key in [
        "inertia",
        "principal_moments",
        "principal_axes",
        "center_of_mass",
    ] {
        assert_eq!(data[key], report[key], "{key}");
    }
    let i = Matrix3::from_fn(|r, c| data["inertia"][r][c].as_f64().unwrap());
    let snaps = data["principal_euler"].as_object().unwrap();
    assert_eq!(snaps.len(), 24);
    for (key, snap) in snaps {
        let convention: EulerConvention = key.parse().unwrap();
        let a = Vector3::from_fn(|k, _| snap["angles"][k].as_f64().unwrap());
        let r = convention.to_rotation(&a);
        let turned = r.matrix() * i * r.matrix().transpose();
        for (row, col) in [(0, 1), (0, 2), (1, 2)] {
            assert!(
                turned[(row, col)].abs() < 1e-12 * i.amax(),
                "{key}: {turned}"
            );
        }
        for k in 0..3 {
            let moment = report["principal_moments"][k].as_f64().unwrap();
            assert!(
                (turned[(k, k)] - moment).abs() < 1e-12 * moment,
                "{key}: {turned}"
            );
        }
    }
}

#[test]
fn bad_requests_are_refused_before_anything_is_written() {
    let tmp = TempDir::new().unwrap();
    let mesh = root().join("scenes/t-handle.obj");
    let mesh = mesh.to_str().unwrap();
    for (args, says) in [
        (vec!["view", "free-hoop", "-o", "a.png"], "ending in .html"),
        (
            vec!["view", "coriolis-drop", "-o", "a.html"],
            "has no 3D view",
        ),
        (
            vec!["view", "free-hoop", "--shape", "box:1,1,1", "-o", "a.html"],
            "for --inertia",
        ),
        (
            vec!["view", "free-hoop", "free-body", "-o", "a.html"],
            "give one scene",
        ),
        (
            vec!["view", "free-hoop", "--output-dt", "0", "-o", "a.html"],
            "--output-dt 0",
        ),
        (
            vec!["view", "no-such-scene", "-o", "a.html"],
            "unknown scene",
        ),
        (
            vec!["view", "--inertia", mesh, "--set", "a=1", "-o", "a.html"],
            "--set belongs to a run",
        ),
        (vec!["view", "--inertia", "-o", "a.html"], "no body given"),
        (
            vec!["view", "--inertia", "missing.obj", "-o", "a.html"],
            "missing.obj",
        ),
    ] {
        let out = tumble_in(tmp.path(), &args);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr(&out).contains(says), "{args:?}: {}", stderr(&out));
        assert!(!tmp.path().join("a.html").exists(), "{args:?} wrote a file");
    }
}
