//! Signals in the middle of work, and what a killed run leaves for the next one: SIGINT and
//! SIGTERM end with 130 or 143 and leave no temporary file or lock; a run killed with SIGKILL
//! leaves a stale lock and temporary files that the next command into the folder clears.

use std::path::Path;

use super::{listing, run_in};
use crate::support::{interrupt, no_panic};

/// The number of signal cases below (for the suite's count).
pub const CASES: usize = 6;

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

fn journal_lines(dir: &Path) -> usize {
    std::fs::read_to_string(dir.join("sw/journal.csv")).map_or(0, |t| t.lines().count())
}

#[test]
fn signals_end_a_simulation_cleanly() {
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
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
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
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
