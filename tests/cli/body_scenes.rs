//! `tumble simulate` with the example scenes whose body comes from a `[body]` table: they run,
//! their sidecar names the frame of the rows, and a bad body fails before any output.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scene(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
        .display()
        .to_string()
}

fn tumble(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(args)
        .output()
        .expect("cannot run the tumble binary")
}

#[test]
fn the_example_body_scenes_run_and_their_sidecar_names_the_body_frame() {
    let dir = tempfile::tempdir().unwrap();
    for (file, source) in [
        ("t-handle-flip.toml", "mesh t-handle.obj"),
        ("disk-rod-top.toml", "2 shape(s)"),
        ("dumbbell.toml", "points dumbbell.csv"),
    ] {
        let csv = dir.path().join(format!("{file}.csv"));
        let out = tumble(&[
            "simulate",
            &scene(file),
            "--t-end",
            "0.5",
            "-o",
            csv.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{file}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = std::fs::read_to_string(&csv).unwrap();
        assert!(
            text.starts_with("t,qw,qx,qy,qz,omega_x,omega_y,omega_z,energy"),
            "{file}"
        );
        let sidecar = std::fs::read_to_string(format!("{}.json", csv.display())).unwrap();
        let record: serde_json::Value = serde_json::from_str(&sidecar).unwrap();
        let frame = record["frame"].as_str().unwrap();
        assert!(
            frame.contains("[body] table's own frame"),
            "{file}: {frame}"
        );
        assert!(frame.contains(source), "{file}: {frame}");
    }
}

#[test]
fn a_built_in_scene_reports_its_own_body_frame() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("free.csv");
    let out = tumble(&[
        "simulate",
        "free-body",
        "--t-end",
        "0.1",
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let sidecar = std::fs::read_to_string(format!("{}.json", csv.display())).unwrap();
    assert!(sidecar.contains("the scene's body frame"), "{sidecar}");
}

#[test]
fn a_thin_rod_body_fails_before_any_output_naming_the_file_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("rod.toml");
    std::fs::write(
        &file,
        "scene = \"dzhanibekov\"\n\n[[body.shape]]\nshape = \"rod:0.5\"\nmass = 0.2\n",
    )
    .unwrap();
    let csv = dir.path().join("rod.csv");
    let out = tumble(&[
        "simulate",
        file.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("rod.toml:3:"), "{err}");
    assert!(err.contains("`body`"), "{err}");
    assert!(err.contains("three positive moments"), "{err}");
    assert!(!csv.exists());
}
