//! Outputs that are not regular files: a device node or a FIFO is streamed to and survives, a
//! link survives while its target gets the data, a directory is refused before any work.

use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::{Command, Stdio};

use crate::support::{stderr, succeeds, tumble_in};

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

/// A null device node `name` in `dir` (root only).
fn null_node(dir: &Path, name: &str) -> std::path::PathBuf {
    let node = dir.join(name);
    let ok = Command::new("mknod")
        .arg(&node)
        .args(["c", "1", "3"])
        .status()
        .unwrap()
        .success();
    assert!(ok, "mknod failed");
    node
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn simulate_into_a_device_node_streams_and_keeps_the_node() {
    if !is_root() {
        eprintln!("skipped: making a device node needs root");
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    null_node(tmp.path(), "n");
    null_node(tmp.path(), "p.svg");
    succeeds(
        tmp.path(),
        &[
            "simulate",
            "free-body",
            "--t-end",
            "0.1",
            "-o",
            "n",
            "--plot",
            "p.svg",
        ],
    );
    for name in ["n", "p.svg"] {
        let meta = std::fs::symlink_metadata(tmp.path().join(name)).unwrap();
        assert!(meta.file_type().is_char_device(), "{name} was replaced");
    }
    assert_eq!(entries(tmp.path()), ["n", "p.svg"], "temporary files left");
}

#[test]
fn simulate_into_a_fifo_delivers_every_row_to_the_reader() {
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("pipe.csv");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let reader = Command::new("cat")
        .arg(&fifo)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    succeeds(
        tmp.path(),
        &["simulate", "free-body", "--t-end", "0.1", "-o", "pipe.csv"],
    );
    let got = reader.wait_with_output().unwrap();
    let text = String::from_utf8(got.stdout).unwrap();
    // Header and 101 rows (t = 0, 0.001, ..., 0.1 at the default step).
    let direct = succeeds(tmp.path(), &["simulate", "free-body", "--t-end", "0.1"]);
    assert_eq!(text, String::from_utf8(direct.stdout).unwrap());
    assert!(text.lines().count() > 2);
    let meta = std::fs::symlink_metadata(&fifo).unwrap();
    assert!(meta.file_type().is_fifo(), "the FIFO was replaced");
    assert_eq!(entries(tmp.path()), ["pipe.csv"]);
}

#[test]
fn simulate_through_a_link_writes_the_target_and_keeps_the_link() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::create_dir(tmp.path().join("data")).unwrap();
    std::fs::write(tmp.path().join("data/run.csv"), "old").unwrap();
    std::os::unix::fs::symlink("data/run.csv", tmp.path().join("run.csv")).unwrap();
    let direct = succeeds(tmp.path(), &["simulate", "free-body", "--t-end", "0.1"]);
    succeeds(
        tmp.path(),
        &["simulate", "free-body", "--t-end", "0.1", "-o", "run.csv"],
    );
    let link = std::fs::symlink_metadata(tmp.path().join("run.csv")).unwrap();
    assert!(link.file_type().is_symlink(), "the link was replaced");
    assert_eq!(
        std::fs::read(tmp.path().join("data/run.csv")).unwrap(),
        direct.stdout
    );
}

#[test]
fn an_output_that_is_a_directory_is_refused_before_the_run() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::create_dir(tmp.path().join("out.csv")).unwrap();
    // A horizon of 10^4 s at the default step would take a long time: the refusal comes first.
    let out = tumble_in(
        tmp.path(),
        &["simulate", "free-body", "--t-end", "10000", "-o", "out.csv"],
    );
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.contains("out.csv: is a directory"), "{err}");
    assert!(!err.contains("steps"), "the run started: {err}");
    assert_eq!(entries(tmp.path()), ["out.csv"]);
    assert!(tmp.path().join("out.csv").is_dir());
}

#[test]
fn the_csv_and_the_plot_may_not_be_one_file() {
    let tmp = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink("same.svg", tmp.path().join("alias.svg")).unwrap();
    let out = tumble_in(
        tmp.path(),
        &[
            "simulate",
            "free-body",
            "--t-end",
            "0.1",
            "-o",
            "same.svg",
            "--plot",
            "alias.svg",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("the same file as -o"),
        "{}",
        stderr(&out)
    );
    assert_eq!(entries(tmp.path()), ["alias.svg"]);
}

#[test]
fn a_sweep_whose_result_file_is_a_directory_is_refused_before_the_points() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(tmp.path().join("map/results.csv")).unwrap();
    let out = tumble_in(tmp.path(), &["sweep", "-o", "map"]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.contains("results.csv: is a directory"), "{err}");
    assert_eq!(entries(&tmp.path().join("map")), ["results.csv"]);
}

/// Every report command whose reader has gone (`tumble scenes | head -1`, the read end closed
/// before a byte is written) ends quietly with success, not with a panic.
#[test]
fn report_commands_end_quietly_when_the_reader_closes_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let commands: [&[&str]; 6] = [
        &["scenes"],
        &["scenes", "--json"],
        &["integrators"],
        &["integrators", "--json"],
        &["inertia", "--shape", "box:1,2,3", "--mass", "1"],
        &["kinematics", "--angles", "0.3,1.1,-2", "--rates", "1,0.5,4"],
    ];
    for args in commands {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
            .current_dir(dir.path())
            .args(args)
            .stdout(writer)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(out.status.success(), "{args:?}: {:?} {err}", out.status);
    }
}
