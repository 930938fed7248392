//! Rows at chosen times, the final state always written, budgets refused before any step, an
//! unresolved motion reported (a sweep's coarse step refused, a runaway point cut at its time
//! limit), and validation holes closed.

use tempfile::TempDir;

use crate::simulate::fails;
use crate::support::{stderr, succeeds};

#[test]
fn rows_at_chosen_times_and_every_interval_end_with_the_final_state() {
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "coriolis-drop",
            "--output-dt",
            "1",
            "--integrator",
            "gauss8",
            "--dt",
            "0.01",
        ],
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    let times: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    // Rows at 0, 1, 2, 3, 4 s and the landing (the terminal event) at about 4.515 s.
    assert_eq!(&times[..5], &[0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(times.len(), 6);
    assert!((times[5] - 4.5152).abs() < 1e-3, "{times:?}");
    assert!(stderr(&out).contains("at 61 chosen times from dense output"));
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "free-body",
            "--dt",
            "0.001",
            "--t-end",
            "1",
            "--every",
            "300",
        ],
    );
    let last = String::from_utf8(out.stdout).unwrap();
    assert!(last.lines().last().unwrap().starts_with("1.0,"), "{last}");
}

/// The rows of a CSV on stdout, as numbers.
fn stdout_rows(out: &std::process::Output) -> Vec<Vec<f64>> {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn a_method_without_an_interpolant_of_its_own_gives_rows_at_chosen_times() {
    // The LGVI (order 2, dt = 1e-3) interpolates by a partial step of itself: its rows at the
    // chosen times are within its own error (a few 1e-6 on this run) of gauss8's, and each
    // quaternion has unit norm.
    let dir = TempDir::new().unwrap();
    let at = ["--at", "0.25,0.5,1.7,3"];
    let lgvi = stdout_rows(&succeeds(
        dir.path(),
        &[
            &[
                "simulate",
                "free-hoop",
                "--t-end",
                "3",
                "--integrator",
                "lgvi",
                "--dt",
                "0.001",
            ][..],
            &at,
        ]
        .concat(),
    ));
    let gauss = stdout_rows(&succeeds(
        dir.path(),
        &[&["simulate", "free-hoop", "--t-end", "3"][..], &at].concat(),
    ));
    let times: Vec<f64> = lgvi.iter().map(|r| r[0]).collect();
    assert_eq!(times, [0.25, 0.5, 1.7, 3.0]);
    for (a, b) in lgvi.iter().zip(&gauss) {
        assert_eq!(a[0], b[0]);
        let norm = a[1..5].iter().map(|q| q * q).sum::<f64>().sqrt();
        assert!((norm - 1.0).abs() < 1e-14, "t = {}: |q| = {norm}", a[0]);
        let worst = (1..5).map(|j| (a[j] - b[j]).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-4, "t = {}: lgvi {worst:e} from gauss8", a[0]);
    }
}

#[test]
fn bad_output_times_are_refused_before_running() {
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--integrator",
            "dop853",
            "--at",
            "1,x",
            "-o",
            "x.csv",
        ],
        &["--at 1,x: `x` is not a number"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--integrator",
            "dop853",
            "--at",
            "2,1",
            "-o",
            "x.csv",
        ],
        &["--at 1: comes after 2: times must increase"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--integrator",
            "dop853",
            "--at",
            "1,1",
            "-o",
            "x.csv",
        ],
        &["--at 1: given twice"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--integrator",
            "dop853",
            "--at",
            "0.5,20",
            "-o",
            "x.csv",
        ],
        &["--at 20: outside [0, t_end = 10]"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--integrator",
            "dop853",
            "--output-dt",
            "-1",
            "-o",
            "x.csv",
        ],
        &["--output-dt -1: must be positive"],
    );
}

#[test]
fn runaway_runs_are_refused_before_any_step() {
    // 10^14 steps (the run once wrote 78 GB before it was stopped).
    fails(
        &[],
        &[
            "simulate",
            "free-body",
            "--dt",
            "1e-9",
            "--t-end",
            "1e5",
            "-o",
            "x.csv",
        ],
        &["about 1.000e14 steps", "--max-steps 1000000000"],
    );
    // 10^9 rows of CSV.
    fails(
        &[],
        &[
            "simulate",
            "free-body",
            "--dt",
            "1e-6",
            "--t-end",
            "1e3",
            "-o",
            "x.csv",
        ],
        &["the CSV would be about", "--max-output 10G", "--every N"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-body",
            "--max-output",
            "lots",
            "-o",
            "x.csv",
        ],
        &["--max-output lots"],
    );
    // The same run with fewer rows or a raised budget is fine (it is not run here: a smaller
    // horizon shows the budget follows the plan).
    let dir = TempDir::new().unwrap();
    succeeds(
        dir.path(),
        &[
            "simulate",
            "free-body",
            "--dt",
            "1e-6",
            "--t-end",
            "1e-2",
            "--max-steps",
            "20000",
        ],
    );
}

#[test]
fn an_unresolved_motion_is_reported_not_hidden() {
    // The T-handle spun at 10^6 rad/s with split4 at 1 ms: the energy drifts by tens of per
    // cent. Such a step is refused unless --allow-coarse-step; with it, the run completes and
    // says so on stderr and in its provenance file.
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "--allow-coarse-step",
            "dzhanibekov",
            "--set",
            "spin=1e6",
            "--integrator",
            "split4",
            "--t-end",
            "0.1",
            "-o",
            "fast.csv",
        ],
    );
    assert!(
        stderr(&out).contains("more than --energy-warn"),
        "{}",
        stderr(&out)
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("fast.csv.json")).unwrap())
            .unwrap();
    assert_eq!(record["energy_warning"], true);
    // The default (the exact flow) resolves it.
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "dzhanibekov",
            "--set",
            "spin=1e6",
            "--t-end",
            "0.1",
            "-o",
            "ok.csv",
        ],
    );
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

#[test]
fn validation_holes_are_closed() {
    // Angle expressions are strict: `2**pi` was read as 2π, `1e-999` as 0.
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--set",
            "alpha0=2**pi",
            "-o",
            "x.csv",
        ],
        &["`2**pi` is not a number"],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-hoop",
            "--set",
            "alpha0=1e-999",
            "-o",
            "x.csv",
        ],
        &["`1e-999` is not a number"],
    );
    // A documented domain that the scene runs: a massless bead has no dynamics on the free
    // hoop (every integrator failed at t = 0).
    fails(
        &[],
        &["simulate", "free-hoop", "--set", "m=0", "-o", "x.csv"],
        &["`m`", "positive"],
    );
    // A horizon that no step count can reach is refused by the plan, not by every step.
    fails(
        &[],
        &["simulate", "free-body", "--t-end", "1e308", "-o", "x.csv"],
        &["--dt 0.01", "more than 10^15"],
    );
    // A scene file with a 200 kB line: the excerpt shows a window around the error.
    let long = format!(
        "scene = \"free-body\"\n[parameters]\nI1 = \"{}\"\n",
        "x".repeat(200_000)
    );
    let err = fails(
        &[("long.toml", &long)],
        &["simulate", "long.toml", "-o", "x.csv"],
        &["long.toml:3"],
    );
    assert!(err.len() < 2_000, "{} bytes of error", err.len());
}

/// A free-hoop sweep at a fixed step of 0.01 s whose corner `omega0 = 100` turns the hoop by
/// about 1 rad a step.
const COARSE_SWEEP: &str = "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\n\
t_end = 0.2\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 100.0]\ncount = 3\n[[axes]]\n\
parameter = \"alpha0\"\nvalues = [2.0, 0.5]\n[metrics]\nrecord = [\"max_tilt\"]\n";

#[test]
fn a_sweep_whose_step_does_not_resolve_a_corner_is_refused_unless_allowed() {
    let dir = TempDir::new().unwrap();
    std::fs::write(dir.path().join("c.sweep.toml"), COARSE_SWEEP).unwrap();
    let out = crate::support::tumble_in(
        dir.path(),
        &["sweep", "c.sweep.toml", "-o", "refused", "--check", "off"],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("run.dt = 0.01 does not resolve the initial rotation at point 5 (omega0 = 100, alpha0 = 0.5)"),
        "{err}"
    );
    // 100 rad/s of spin and the bead's pendulum frequency √(g/a) = 3.13 rad/s.
    assert!(
        err.contains("|ω| ≈ 103 rad/s turns 1.03 rad a step"),
        "{err}"
    );
    // Refused before the folder was made.
    assert!(!dir.path().join("refused").exists());
    // The suggested step is accepted, and so is the coarse one when allowed.
    succeeds(
        dir.path(),
        &[
            "sweep",
            "c.sweep.toml",
            "-o",
            "fine",
            "--check",
            "off",
            "--set",
            "run.dt=0.002",
        ],
    );
    let out = crate::support::tumble_in(
        dir.path(),
        &[
            "sweep",
            "c.sweep.toml",
            "-o",
            "coarse",
            "--check",
            "off",
            "--allow-coarse-step",
        ],
    );
    assert!(matches!(out.status.code(), Some(0 | 3)), "{}", stderr(&out));
    assert!(dir.path().join("coarse/results.csv").is_file());
}

#[test]
fn a_runaway_sweep_point_fails_at_its_time_limit_and_the_sweep_goes_on() {
    // omega0 = 3000 at a tolerance of 1e-12 over 200 s takes minutes; omega0 = 1 a tenth of
    // a second.
    let dir = TempDir::new().unwrap();
    let sweep = "scene = \"free-hoop\"\n[run]\nintegrator = \"dop853\"\ntol = 1e-12\n\
        t_end = 200.0\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0, 3000.0]\n[metrics]\n\
        record = [\"max_tilt\"]\n";
    std::fs::write(dir.path().join("r.sweep.toml"), sweep).unwrap();
    let start = std::time::Instant::now();
    let out = crate::support::tumble_in(
        dir.path(),
        &[
            "sweep",
            "r.sweep.toml",
            "-o",
            "r",
            "--check",
            "off",
            "--point-seconds",
            "3",
        ],
    );
    assert!(
        start.elapsed() < std::time::Duration::from_secs(60),
        "{:?}",
        start.elapsed()
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(err.contains("1 of 2 points failed"), "{err}");
    let results = std::fs::read_to_string(dir.path().join("r/results.csv")).unwrap();
    let rows: Vec<&str> = results.lines().collect();
    assert!(
        rows[1].starts_with("0,1.0,") && rows[1].ends_with(",ok,"),
        "{results}"
    );
    assert!(
        rows[2]
            .starts_with("1,3000.0,,failed,integration failed: time limit of 3 s reached at t ="),
        "{results}"
    );
}

#[test]
fn a_tiny_hoop_is_refused_for_its_step_not_failed_at_the_first_one() {
    // a = 1e-9 m: the bead swings at √(g/a) ≈ 10^5 rad/s, which dt = 0.01 s cannot follow
    // (every integrator failed at t = 0: "stage iteration did not converge").
    let dir = TempDir::new().unwrap();
    for scene in ["driven-hoop", "spinning-hoop", "free-hoop"] {
        let out = crate::support::tumble_in(dir.path(), &["simulate", scene, "--set", "a=1e-9"]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{scene}: {err}");
        assert!(
            err.contains("does not resolve the initial rotation") && err.contains("--dt 2e-6"),
            "{scene}: {err}"
        );
    }
}
