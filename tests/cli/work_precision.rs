//! `tumble work-precision`: the output folder (CSV, plots, manifest), the summary table, long
//! runs, and bad flags rejected before any run.

use std::path::PathBuf;

use tempfile::TempDir;

use crate::support::tumble_in;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn work_precision_writes_csv_plots_and_manifest_with_a_ladder_per_integrator() {
    let tmp = TempDir::new().unwrap();
    let out = tumble_in(
        tmp.path(),
        &[
            "work-precision",
            "free-body",
            "--t-end",
            "1",
            "--max-seconds",
            "0.02",
            "--integrators",
            "split2,rk4,dop853",
            "-o",
            "wp",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let dir: PathBuf = tmp.path().join("wp");
    for f in [
        "work-precision.csv",
        "work-precision.png",
        "work-precision.svg",
        "manifest.json",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(dir.join("work-precision.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        header,
        [
            "integrator",
            "order",
            "dt",
            "tol",
            "steps",
            "evaluations",
            "error",
            "max_energy_rel_err",
            "wall_time_s",
            "repeats"
        ]
    );
    let rows: Vec<csv::StringRecord> = csv::Reader::from_reader(csv.as_bytes())
        .records()
        .map(Result::unwrap)
        .collect();
    for name in ["split2", "rk4", "dop853"] {
        let errors: Vec<f64> = rows
            .iter()
            .filter(|r| &r[0] == name)
            .map(|r| r[6].parse().unwrap())
            .collect();
        assert!(errors.len() >= 3, "{name}: {errors:?}");
        assert!(
            errors.last().unwrap() < &(errors[0] / 100.0),
            "{name}: {errors:?}"
        );
    }
    let manifest = crate::support::record::<tumble_studies::work_precision::record::StudyRecord>(
        &dir.join("manifest.json"),
    );
    assert_eq!(manifest["scene"], "free-body");
    // The double-double Taylor method, checked by the exact flow.
    assert!(
        manifest["reference"]["method"]
            .as_str()
            .unwrap()
            .starts_with("taylor-dd")
    );
    assert!(
        manifest["reference"]["cross_check"]
            .as_str()
            .unwrap()
            .starts_with("exact")
    );
    assert!(manifest["reference"]["agreement"].as_f64().unwrap() < 1e-11);
    let svg = std::fs::read_to_string(dir.join("work-precision.svg")).unwrap();
    for label in [
        "split2 (2)",
        "rk4 (4)",
        "dop853 (8)",
        "wall time",
        "error at the final time",
    ] {
        assert!(svg.contains(label), "{label} not in the plot");
    }
    let stdout = text(&out.stdout);
    assert!(stdout.contains("observed order"), "{stdout}");
    assert!(stdout.contains("fastest to an error of 1e-8"), "{stdout}");
}

#[test]
fn long_mode_plots_the_energy_error_of_geometric_methods_and_a_matched_adaptive_method() {
    let tmp = TempDir::new().unwrap();
    let out = tumble_in(
        tmp.path(),
        &[
            "work-precision",
            "free-body",
            "--long",
            "--long-steps",
            "4000",
            "--integrators",
            "split2,lgvi",
            "-o",
            "long",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let dir = tmp.path().join("long");
    for f in ["long.csv", "long.png", "long.svg"] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(dir.join("long.csv")).unwrap();
    // The matched method is the scene's adaptive method of highest order.
    let scene = tumble_scenarios::scenes::find("free-body").unwrap();
    let adaptive =
        tumble_studies::work_precision::highest_order(scene.info(), |m| m.properties.adaptive)
            .unwrap()
            .name;
    for name in ["split2", "lgvi", adaptive] {
        assert!(
            csv.lines().any(|l| l.starts_with(&format!("{name},"))),
            "{name} missing"
        );
    }
    assert!(text(&out.stderr).contains("matching cost"));
    // The manifest is its one record type, every key held, read back as written.
    let manifest = crate::support::record::<tumble_plot::work_precision::LongManifest>(
        &dir.join("manifest.json"),
    );
    assert_eq!(manifest["command"], "work-precision --long");
    assert_eq!(manifest["scene"], "free-body");
    assert_eq!(manifest["steps"], 4000);
}

#[test]
fn long_tol_runs_fixed_step_methods_at_the_cost_of_the_adaptive_one() {
    let tmp = TempDir::new().unwrap();
    let out = tumble_in(
        tmp.path(),
        &[
            "work-precision",
            "heavy-top",
            "--long",
            "--long-steps",
            "2000",
            "--long-tol",
            "1e-6",
            "--integrators",
            "dop853,split-exact4",
            "-o",
            "long",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(err.contains("dop853 at tol = 1e-6 costs"), "{err}");
    assert!(err.contains("split-exact4 at dt = "), "{err}");
    let csv = std::fs::read_to_string(tmp.path().join("long/long.csv")).unwrap();
    for row in ["split-exact4,dt = ", "dop853,tol = 1.0e-6,"] {
        assert!(csv.lines().any(|l| l.starts_with(row)), "{row} missing");
    }
    // The matched step is not the scene's default one (1e-3 s).
    assert!(!csv.contains("split-exact4,dt = 1.000e-3,"), "{csv}");
}

#[test]
fn bad_flags_are_rejected_before_any_run() {
    let tmp = TempDir::new().unwrap();
    for (args, needle) in [
        (
            vec!["work-precision", "free-hoop", "--integrators", "split2"],
            "`split2` cannot run scene `free-hoop`",
        ),
        (
            vec!["work-precision", "free-body", "--max-seconds", "0"],
            "--max-seconds 0",
        ),
        (
            vec!["work-precision", "free-body", "--t-end", "-1"],
            "--t-end -1",
        ),
        (vec!["work-precision", "no-such-scene"], "unknown scene"),
        (
            vec![
                "work-precision",
                "free-body",
                "--long",
                "--long-steps",
                "10",
            ],
            "--long-steps 10",
        ),
        (
            vec!["work-precision", "free-body", "--long", "--long-tol", "2"],
            "--long-tol 2",
        ),
        (
            vec!["work-precision", "free-body", "--long-tol", "1e-8"],
            "--long",
        ),
    ] {
        let out = tumble_in(tmp.path(), &args);
        assert!(!out.status.success(), "{args:?} succeeded");
        let err = text(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!tmp.path().join("out").exists(), "{args:?} left output");
    }
}

#[test]
fn max_seconds_bounds_every_run_even_of_a_long_horizon() {
    // A horizon of 10^7 s: the reference's cross-check alone would run for hours. Each of its
    // runs is limited to 60 × --max-seconds (1.2 s here), and the folder is left as it was.
    let tmp = TempDir::new().unwrap();
    let start = std::time::Instant::now();
    let out = tumble_in(
        tmp.path(),
        &[
            "work-precision",
            "free-body",
            "--t-end",
            "1e7",
            "--max-seconds",
            "0.02",
            "--integrators",
            "rk4",
            "-o",
            "wp",
        ],
    );
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("was cut after 1.2 s of wall time") && err.contains("--max-seconds"),
        "{err}"
    );
    // The error is the first line: no header of a study that never starts.
    assert!(
        err.starts_with("error: free-body: the reference run"),
        "{err}"
    );
    assert!(
        start.elapsed().as_secs_f64() < 20.0,
        "{:?}",
        start.elapsed()
    );
    assert!(!tmp.path().join("wp").exists());
}

/// `--max-seconds`'s help states the limits of the reference's runs and of the long runs as
/// the library declares them.
#[test]
fn the_max_seconds_help_states_the_librarys_reference_and_long_run_factors() {
    use tumble_studies::work_precision::{Config, LONG_FACTOR};
    let tmp = TempDir::new().unwrap();
    let out = tumble_in(tmp.path(), &["work-precision", "--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    for stated in [
        format!("limited to {} times this", Config::REFERENCE_FACTOR),
        format!("each run of `--long` to {LONG_FACTOR} times"),
    ] {
        assert!(help.contains(&stated), "no `{stated}` in: {help}");
    }
}
