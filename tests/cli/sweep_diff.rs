//! `tumble sweep diff A B`: the largest difference of each metric between two sweeps of one
//! grid, where it is, exit status 4 above `--tolerance`, and grids that differ refused.

use tempfile::TempDir;

use crate::support::{stderr, succeeds, tumble_in};
use crate::sweep::{small, write_sweep};

#[test]
fn a_step_halving_check_from_the_command_line() {
    let dir = TempDir::new().unwrap();
    let d = dir.path();
    let file = write_sweep(d, "s.sweep.toml", &small(2.0, 4));
    let f = file.to_str().unwrap();
    succeeds(d, &["sweep", f, "-o", "a", "--check", "off"]);
    succeeds(
        d,
        &[
            "sweep",
            f,
            "-o",
            "b",
            "--check",
            "off",
            "--set",
            "run.dt=0.005",
        ],
    );
    let out = succeeds(d, &["sweep", "diff", "a", "b"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("8 points over omega0 x alpha0"), "{text}");
    // gauss8 at 0.01 and 0.005 s: the tilt metrics agree far below 1e-9.
    for metric in ["max_tilt", "final_tilt", "time_tilt_exceeds"] {
        let line = text
            .lines()
            .find(|l| l.starts_with(metric))
            .unwrap_or_else(|| panic!("{metric} missing: {text}"));
        let largest: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
        assert!(largest < 1e-9, "{line}");
        assert!(line.contains("point "), "{line}");
    }
    let json = succeeds(d, &["sweep", "diff", "a", "b", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(v["points"], 8);
    assert_eq!(v["metrics"].as_array().unwrap().len(), 4);
    // A tolerance below the energy errors' difference: exit status 4, with the figure.
    let strict = tumble_in(d, &["sweep", "diff", "a", "b", "--tolerance", "0"]);
    assert_eq!(strict.status.code(), Some(4), "{}", stderr(&strict));
    assert!(stderr(&strict).contains("more than the tolerance"));
    succeeds(d, &["sweep", "diff", "a", "b", "--tolerance", "1e-6"]);
}

#[test]
fn sweeps_that_cannot_be_compared_are_refused() {
    let dir = TempDir::new().unwrap();
    let d = dir.path();
    let four = write_sweep(d, "four.sweep.toml", &small(0.5, 4));
    let five = write_sweep(d, "five.sweep.toml", &small(0.5, 5));
    succeeds(
        d,
        &["sweep", four.to_str().unwrap(), "-o", "a", "--check", "off"],
    );
    succeeds(
        d,
        &["sweep", five.to_str().unwrap(), "-o", "b", "--check", "off"],
    );
    let out = tumble_in(d, &["sweep", "diff", "a", "b"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("8 and 10 points"), "{}", stderr(&out));
    let out = tumble_in(d, &["sweep", "diff", "a", "nowhere"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("nowhere/sweep.toml"),
        "{}",
        stderr(&out)
    );
    let out = tumble_in(d, &["sweep", "diff", "a", "a", "--tolerance", "-1"]);
    assert_eq!(out.status.code(), Some(1));
}
