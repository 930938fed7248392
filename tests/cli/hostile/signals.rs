//! Signals in the middle of work, and what a killed run leaves for the next one: SIGINT,
//! SIGTERM and SIGHUP end with 130, 143 or 129 and leave no temporary file or lock, a second
//! signal too; a hangup inherited ignored (`nohup`) stays ignored; a run killed with SIGKILL
//! leaves a stale lock and temporary files that the next command into the folder clears.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use super::{listing, run_in};
use crate::support::{interrupt, no_panic, signal, start, wait_for};

/// The number of signal cases below (for the suite's count).
pub const CASES: usize = 8;

const LONG_SWEEP: &str = "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\n\
t_end = 5.0\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 6.0]\ncount = 40\n[metrics]\n\
record = [\"max_tilt\"]\n";

const LONG_SIMULATION: &[&str] = &[
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

/// The signals to stop a run with and their exit statuses: INT, TERM, and HUP unless this
/// test process runs with SIGHUP ignored (under `nohup`), which its children inherit.
fn stopping_signals() -> Vec<(&'static str, i32)> {
    let mut signals = vec![("INT", 130), ("TERM", 143)];
    let ignored = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let mask = s.lines().find_map(|l| l.strip_prefix("SigIgn:"))?;
            u64::from_str_radix(mask.trim(), 16).ok()
        })
        .is_some_and(|m| m & 1 == 1);
    if ignored {
        eprintln!("SIGHUP is ignored in this test process: its hangup case is skipped");
    } else {
        signals.push(("HUP", 129));
    }
    signals
}

fn journal_lines(dir: &Path) -> usize {
    std::fs::read_to_string(dir.join("sw/journal.csv")).map_or(0, |t| t.lines().count())
}

#[test]
fn signals_end_a_simulation_cleanly() {
    for (signal, code) in stopping_signals() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let (got, err) = interrupt(dir, LONG_SIMULATION, || !listing(dir).is_empty(), signal);
        no_panic(got, &err);
        assert_eq!(got, Some(code), "{err}");
        assert!(
            err.contains("interrupted: free-body stopped at t ="),
            "{err}"
        );
        assert!(listing(dir).is_empty(), "left behind: {:?}", listing(dir));
    }
}

#[test]
fn signals_end_a_sweep_with_its_journal_and_no_temporary_file() {
    for (signal, code) in stopping_signals() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        std::fs::write(dir.join("s.sweep.toml"), LONG_SWEEP).unwrap();
        let args = [
            "sweep",
            "s.sweep.toml",
            "-o",
            "sw",
            "--threads",
            "1",
            "--check",
            "off",
        ];
        let (got, err) = interrupt(dir, &args, || journal_lines(dir) > 4, signal);
        no_panic(got, &err);
        assert_eq!(got, Some(code), "{err}");
        assert!(err.contains("--resume"), "{err}");
        let left = listing(&dir.join("sw"));
        assert!(
            left.iter().all(|f| f.starts_with("journal.csv")
                || f.starts_with("sweep.toml")
                || f.starts_with("compute.csv")),
            "{left:?}"
        );
    }
}

#[test]
fn a_killed_sweep_leaves_nothing_the_next_run_trips_on() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("s.sweep.toml"), LONG_SWEEP).unwrap();
    let args = [
        "sweep",
        "s.sweep.toml",
        "-o",
        "sw",
        "--threads",
        "1",
        "--check",
        "off",
    ];
    let (got, _) = interrupt(dir, &args, || journal_lines(dir) > 4, "KILL");
    assert_eq!(got, None, "killed by SIGKILL");
    // What a kill while files were written leaves: the lock, and temporary files (a 0-byte
    // PNG of a plot being drawn among them). A hidden file of the user's stays.
    let sw = dir.join("sw");
    assert!(sw.join(".tumble.lock").exists());
    for name in [
        ".results.csv.a1B2c3.tmp.csv",
        ".map.png.Xy9Zw8.tmp.png",
        ".manifest.json.000000.tmp.json",
    ] {
        std::fs::write(sw.join(name), "").unwrap();
    }
    std::fs::write(sw.join(".notes.tmp"), "mine").unwrap();
    let (code, err) = run_in(
        dir,
        &[
            "sweep",
            "s.sweep.toml",
            "-o",
            "sw",
            "--resume",
            "--check",
            "off",
        ],
    );
    no_panic(code, &err);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("removed"), "{err}");
    let left = listing(&sw);
    assert!(!left.iter().any(|f| f.contains(".tmp.")), "{left:?}");
    assert!(!left.iter().any(|f| f.contains(".tumble.lock")), "{left:?}");
    assert!(left.iter().any(|f| f.starts_with(".notes.tmp")), "{left:?}");
    assert!(
        left.iter().any(|f| f.starts_with("results.csv")),
        "{left:?}"
    );
}

#[test]
fn stale_temporary_files_are_cleared_by_merge_and_work_precision() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("s.sweep.toml"), super::journals::SWEEP).unwrap();
    let (code, err) = run_in(
        dir,
        &["sweep", "s.sweep.toml", "-o", "sw", "--check", "off"],
    );
    assert_eq!(code, Some(0), "{err}");
    for out in ["merged", "wp"] {
        std::fs::create_dir(dir.join(out)).unwrap();
        std::fs::write(dir.join(out).join(".results.csv.q1w2e3.tmp.csv"), "").unwrap();
        std::fs::write(dir.join(out).join(".work-precision.png.q1w2e3.tmp.png"), "").unwrap();
    }
    let (code, err) = run_in(
        dir,
        &["sweep", "merge", "sw", "-o", "merged", "--check", "off"],
    );
    no_panic(code, &err);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run_in(
        dir,
        &[
            "work-precision",
            "free-body",
            "--t-end",
            "0.5",
            "--integrators",
            "rk4",
            "-o",
            "wp",
            "--max-seconds",
            "0.02",
        ],
    );
    no_panic(code, &err);
    assert_eq!(code, Some(0), "{err}");
    for out in ["merged", "wp"] {
        let left = listing(&dir.join(out));
        assert!(!left.iter().any(|f| f.contains(".tmp.")), "{left:?}");
    }
}

/// A second signal, sent while the first is being handled, ends the run at once; whichever
/// way it ends, the sweep's lock and temporary files are gone and its journal stays.
#[test]
fn a_second_signal_leaves_no_lock_and_no_temporary_file() {
    for second in ["INT", "TERM"] {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        std::fs::write(dir.join("s.sweep.toml"), LONG_SWEEP).unwrap();
        let child = start(
            dir,
            &[
                "sweep",
                "s.sweep.toml",
                "-o",
                "sw",
                "--threads",
                "1",
                "--check",
                "off",
            ],
        );
        wait_for("the sweep to start", || journal_lines(dir) > 4);
        signal(child.id(), "INT");
        signal(child.id(), second);
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        no_panic(out.status.code(), &err);
        assert!(
            [Some(130), Some(143)].contains(&out.status.code()),
            "{:?}: {err}",
            out.status
        );
        let left = listing(&dir.join("sw"));
        assert!(!left.iter().any(|f| f.contains(".tumble.lock")), "{left:?}");
        assert!(!left.iter().any(|f| f.contains(".tmp")), "{left:?}");
        assert!(
            left.iter().any(|f| f.starts_with("journal.csv")),
            "{left:?}"
        );
    }
}

/// A process started with SIGHUP ignored (as `nohup` starts it) keeps ignoring it: the run
/// goes on after a hangup, and stops cleanly on SIGTERM.
#[test]
fn a_hangup_inherited_ignored_stays_ignored() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // `trap '' HUP` ignores the signal and `exec` keeps the disposition, as nohup does.
    let child = Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg(format!(
            "trap '' HUP; exec {} \"$@\"",
            env!("CARGO_BIN_EXE_tumble")
        ))
        .arg("sh")
        .args(LONG_SIMULATION)
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot run sh");
    let mut child = child;
    wait_for("the run to start", || !listing(dir).is_empty());
    signal(child.id(), "HUP");
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "a hangup ended a run started with SIGHUP ignored"
    );
    signal(child.id(), "TERM");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    no_panic(out.status.code(), &err);
    assert_eq!(out.status.code(), Some(143), "{err}");
    assert!(listing(dir).is_empty(), "left behind: {:?}", listing(dir));
}
