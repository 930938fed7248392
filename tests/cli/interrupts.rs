//! Clean interrupts: SIGINT and SIGTERM stop the work at a step boundary, leave no temporary
//! file, keep what is complete and exit 130 or 143.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{stderr, succeeds};

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn signal(pid: u32, name: &str) {
    let ok = Command::new("kill")
        .args([format!("-{name}"), pid.to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{name} failed");
}

/// Waits until `ready()` or 60 s.
fn wait_for(ready: impl Fn() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(start.elapsed() < Duration::from_secs(60), "timed out");
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
fn an_interrupted_simulation_leaves_nothing_and_exits_130() {
    let tmp = tempfile::tempdir().unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(tmp.path())
        .args([
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
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The temporary CSV appears once the run has started.
    wait_for(|| !entries(tmp.path()).is_empty());
    signal(child.id(), "INT");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
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
    let child = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(tmp.path())
        .args(["sweep", "s.sweep.toml", "-o", "cut", "--threads", "1"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let journal = tmp.path().join("cut/journal.csv");
    // Some points done.
    wait_for(|| std::fs::read_to_string(&journal).is_ok_and(|t| t.lines().count() > 8));
    signal(child.id(), "TERM");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(143), "{err}");
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
