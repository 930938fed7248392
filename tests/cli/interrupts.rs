//! Clean interrupts: SIGINT and SIGTERM stop the work at a step boundary, leave no temporary
//! file, keep what is complete and exit 130 or 143.

use std::path::Path;

use crate::support::{interrupt, no_panic, stderr, succeeds};

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn an_interrupted_simulation_leaves_nothing_and_exits_130() {
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "simulate",
        "free-body",
        "--dt",
        "1e-6",
        "--t-end",
        "1000",
        "--every",
        "1000000",
        "--max-steps",
        "10000000000",
        "-o",
        "big.csv",
    ];
    // The temporary CSV appears once the run has started.
    let (code, err) = interrupt(tmp.path(), &args, || !entries(tmp.path()).is_empty(), "INT");
    no_panic(code, &err);
    assert_eq!(code, Some(130), "{err}");
    assert!(
        err.contains("interrupted: free-body stopped at t ="),
        "{err}"
    );
    assert!(err.contains("nothing was written"), "{err}");
    assert!(
        entries(tmp.path()).is_empty(),
        "left behind: {:?}",
        entries(tmp.path())
    );
}

#[test]
fn an_interrupted_animation_leaves_nothing_and_exits_130() {
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "animate",
        "free-hoop",
        "--t-end",
        "100",
        "--fps",
        "100",
        "--duration",
        "99",
        "-o",
        "long.gif",
    ];
    // The scratch GIF appears once the frames are being drawn.
    let (code, err) = interrupt(tmp.path(), &args, || !entries(tmp.path()).is_empty(), "INT");
    no_panic(code, &err);
    assert_eq!(code, Some(130), "{err}");
    assert!(
        err.contains("interrupted: long.gif was not written"),
        "{err}"
    );
    assert!(
        entries(tmp.path()).is_empty(),
        "left behind: {:?}",
        entries(tmp.path())
    );
}

#[test]
fn a_terminated_sweep_keeps_its_journal_and_resumes_to_the_same_results() {
    let tmp = tempfile::tempdir().unwrap();
    let sweep = r#"
scene = "free-hoop"
[run]
integrator = "gauss8"
dt = 0.01
t_end = 5.0
[[axes]]
parameter = "omega0"
range = [1.0, 6.0]
count = 40
[[axes]]
parameter = "alpha0"
values = [0.5, 2.0]
[metrics]
record = ["max_tilt", "final_tilt"]
"#;
    std::fs::write(tmp.path().join("s.sweep.toml"), sweep).unwrap();
    let journal = tmp.path().join("cut/journal.csv");
    // Some points done.
    let (code, err) = interrupt(
        tmp.path(),
        &["sweep", "s.sweep.toml", "-o", "cut", "--threads", "1"],
        || std::fs::read_to_string(&journal).is_ok_and(|t| t.lines().count() > 8),
        "TERM",
    );
    no_panic(code, &err);
    assert_eq!(code, Some(143), "{err}");
    assert!(err.contains("run the same command with --resume"), "{err}");
    let left = entries(&tmp.path().join("cut"));
    assert!(!left.iter().any(|f| f == "results.csv"), "{left:?}");
    assert!(!left.iter().any(|f| f.contains(".tmp")), "{left:?}");
    assert!(!left.iter().any(|f| f == ".tumble.lock"), "{left:?}");
    let resumed = succeeds(
        tmp.path(),
        &[
            "sweep",
            "s.sweep.toml",
            "-o",
            "cut",
            "--resume",
            "--check",
            "off",
        ],
    );
    assert!(stderr(&resumed).contains("resumed"));
    succeeds(
        tmp.path(),
        &["sweep", "s.sweep.toml", "-o", "whole", "--check", "off"],
    );
    assert_eq!(
        std::fs::read(tmp.path().join("cut/results.csv")).unwrap(),
        std::fs::read(tmp.path().join("whole/results.csv")).unwrap()
    );
}

/// A work–precision study whose reference takes minutes (gauss12 over 2000 s of the free
/// hoop at a sixteenth of its step).
const LONG_WORK_PRECISION: &[&str] = &[
    "work-precision",
    "free-hoop",
    "--t-end",
    "2000",
    "--integrators",
    "rk4",
    "--max-seconds",
    "100",
    "-o",
    "wp",
];

#[test]
fn signals_stop_a_work_precision_study_at_once_and_leave_nothing() {
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let lock = dir.join("wp/.tumble.lock");
        let start = std::time::Instant::now();
        // The lock is taken just before the reference run starts.
        let (got, err) = interrupt(dir, LONG_WORK_PRECISION, || lock.exists(), signal);
        no_panic(got, &err);
        assert_eq!(got, Some(code), "{err}");
        assert!(
            err.contains("interrupted: stopped at a step boundary before any result was written"),
            "{err}"
        );
        // Stopped within the run, not after the reference's minutes.
        assert!(
            start.elapsed() < std::time::Duration::from_secs(30),
            "took {:?}",
            start.elapsed()
        );
        // The folder it created is gone again: no result, no temporary file, no lock.
        assert!(entries(dir).is_empty(), "left behind: {:?}", entries(dir));
    }
}

#[test]
fn a_signal_in_a_long_work_precision_run_leaves_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::create_dir(dir.join("wp")).unwrap();
    std::fs::write(dir.join("wp/notes.txt"), "mine").unwrap();
    let lock = dir.join("wp/.tumble.lock");
    let args = [
        "work-precision",
        "free-hoop",
        "--long",
        "--long-steps",
        "100000000",
        "--integrators",
        "gauss4",
        "-o",
        "wp",
    ];
    let (code, err) = interrupt(dir, &args, || lock.exists(), "INT");
    no_panic(code, &err);
    assert_eq!(code, Some(130), "{err}");
    assert!(err.contains("nothing was kept in wp"), "{err}");
    // The user's file stays; nothing of the study is there.
    assert_eq!(entries(&dir.join("wp")), ["notes.txt"]);
}
