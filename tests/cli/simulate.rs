//! `tumble simulate`: the CSV contract (header, full-precision rows, first row = initial
//! conditions), scene files and `--set`, plots, and bad input — each rejected with a message
//! that names what is wrong (and the line, for files), a non-zero exit code, and no output file
//! left behind.

use std::f64::consts::PI;
use std::path::Path;

use tempfile::TempDir;

use crate::support::{root, stderr, succeeds, tumble_in};
use tumble_scenarios::scene::Rows;
use tumble_scenarios::scenes::find;
use tumble_scenarios::{RunOptions, StepControl};

/// Parses CSV text: the header and the rows as numbers.
fn parse_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_string)
        .collect();
    let rows = reader
        .records()
        .map(|r| {
            r.unwrap()
                .iter()
                .map(|v| v.parse::<f64>().expect("a number"))
                .collect()
        })
        .collect();
    (header, rows)
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    parse_csv(&std::fs::read_to_string(path).expect("CSV written"))
}

/// Every entry of a directory (hidden temporary files included).
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs a failing command in a fresh directory holding only `files`; checks the exit code,
/// that stderr mentions every one of `expect`, and that nothing else was written.
pub(crate) fn fails(files: &[(&str, &str)], args: &[&str], expect: &[&str]) -> String {
    let dir = TempDir::new().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let before = entries(dir.path());
    let out = tumble_in(dir.path(), args);
    let err = stderr(&out);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    for e in expect {
        assert!(err.contains(e), "{args:?}: `{e}` missing from: {err}");
    }
    assert_eq!(
        entries(dir.path()),
        before,
        "{args:?} left files behind: {err}"
    );
    err
}

#[test]
fn driven_hoop_csv_has_the_header_rows_and_initial_conditions() {
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &["simulate", "driven-hoop", "--t-end", "1", "-o", "out.csv"],
    );
    assert!(out.stdout.is_empty(), "CSV went to stdout as well");
    let (header, rows) = read_csv(&dir.path().join("out.csv"));
    assert_eq!(
        header,
        [
            "t",
            "alpha",
            "alpha_dot",
            "energy",
            "energy_rel_err",
            "Lx",
            "Ly",
            "Lz",
            "tilt"
        ]
    );
    // dt = 0.01 over [0, 1]: the initial state and 100 steps.
    assert_eq!(rows.len(), 101);
    assert!(rows.iter().all(|r| r.len() == header.len()));
    let info = find("driven-hoop").unwrap().info();
    let defaults = info.default_params();
    let first = &rows[0];
    assert_eq!(first[0], 0.0);
    assert_eq!(first[1], defaults.get("alpha0").unwrap());
    assert_eq!(first[2], defaults.get("alpha_dot0").unwrap());
    assert_eq!(first[4], 0.0, "relative energy error at t = 0");
    assert!((rows[100][0] - 1.0).abs() < 1e-12);
    assert!(
        rows.windows(2).all(|w| w[1][0] > w[0][0]),
        "time not increasing"
    );
    // Only the CSV and its provenance are left: no temporary file.
    assert_eq!(entries(dir.path()), ["out.csv", "out.csv.json"]);
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.csv.json")).unwrap())
            .unwrap();
    assert_eq!(record["scene"], "driven-hoop");
    assert_eq!(record["rows"], 101);
    assert_eq!(
        record["provenance"]["tumble_version"],
        env!("CARGO_PKG_VERSION")
    );
    assert!(
        record["provenance"]["git_commit"]
            .as_str()
            .is_some_and(|c| !c.is_empty())
    );
    assert!(record["provenance"]["command_line"][1] == "simulate");
    assert!(
        record["max_energy_rel_err"]
            .as_f64()
            .is_some_and(|e| e < 1e-9)
    );
    // The summary names the scene, integrator and step.
    let err = stderr(&out);
    for word in [
        "driven-hoop",
        "gauss8",
        "dt = 0.01",
        "100 steps",
        "101 rows",
    ] {
        assert!(err.contains(word), "{word}: {err}");
    }
}

#[test]
fn csv_values_round_trip_to_the_library_run_bit_for_bit() {
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "spinning-hoop",
            "--t-end",
            "0.5",
            "--dt",
            "0.005",
            "--integrator",
            "gauss6",
        ],
    );
    let (_, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
    let scene = find("spinning-hoop").unwrap();
    let mut expected = Rows::default();
    scene
        .run(
            &scene.info().default_params(),
            &RunOptions {
                integrator: Some("gauss6".into()),
                step: Some(StepControl::Fixed(0.005)),
                t_end: Some(0.5),
                every: None,
                ..RunOptions::default()
            },
            &mut expected,
        )
        .unwrap();
    assert_eq!(rows.len(), expected.0.len());
    for (got, want) in rows.iter().zip(&expected.0) {
        for (g, w) in got.iter().zip(want) {
            assert_eq!(g.to_bits(), w.to_bits(), "{g} vs {w}");
        }
    }
}

/// The hoop scenes are separable Hamiltonians: Störmer–Verlet and the composition tables named
/// alone run them from the command line, with the scene's columns, and give rows at chosen
/// times.
#[test]
fn separable_methods_run_the_hoop_scenes_from_the_command_line() {
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "driven-hoop",
            "--integrator",
            "verlet",
            "--dt",
            "0.001",
            "-o",
            "verlet.csv",
        ],
    );
    assert!(stderr(&out).contains("verlet"), "{}", stderr(&out));
    let (header, rows) = read_csv(&dir.path().join("verlet.csv"));
    assert_eq!(header, find("driven-hoop").unwrap().info().columns());
    // The default horizon of 10 s in steps of 1 ms, and the initial state.
    assert_eq!(rows.len(), 10_001);
    let energy_err = header.iter().position(|c| c == "energy_rel_err").unwrap();
    assert!(rows.iter().all(|r| r[energy_err] < 1e-5));

    succeeds(
        dir.path(),
        &[
            "simulate",
            "spinning-hoop",
            "--integrator",
            "kahan-li8",
            "-o",
            "kl8.csv",
        ],
    );
    let (header, rows) = read_csv(&dir.path().join("kl8.csv"));
    assert_eq!(header, find("spinning-hoop").unwrap().info().columns());
    assert_eq!(rows.len(), 1_001);
    let lz = header.iter().position(|c| c == "Lz").unwrap();
    let energy_err = header.iter().position(|c| c == "energy_rel_err").unwrap();
    assert!(
        rows.iter()
            .all(|r| (r[lz] - rows[0][lz]).abs() < 1e-15 && r[energy_err] < 1e-9)
    );

    succeeds(
        dir.path(),
        &[
            "simulate",
            "spinning-hoop",
            "--integrator",
            "yoshida4",
            "--output-dt",
            "0.25",
            "-o",
            "at.csv",
        ],
    );
    let (_, rows) = read_csv(&dir.path().join("at.csv"));
    let times: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(times, (0..=40).map(|k| k as f64 * 0.25).collect::<Vec<_>>());
}

#[test]
fn set_accepts_angle_expressions_and_every_thins_the_rows() {
    let dir = TempDir::new().unwrap();
    let out = succeeds(
        dir.path(),
        &[
            "simulate",
            "driven-hoop",
            "--set",
            "alpha0=pi/3",
            "--set",
            "alpha_dot0=-0.25",
            "--t-end",
            "1",
            "--every",
            "10",
        ],
    );
    let (_, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
    assert_eq!(rows[0][1], PI / 3.0);
    assert_eq!(rows[0][2], -0.25);
    assert!((11..=12).contains(&rows.len()), "{} rows", rows.len());
    assert!((rows[1][0] - 0.1).abs() < 1e-12);
}

const WORKED_EXAMPLE: &str = "\
scene = \"spinning-hoop\"

[parameters]
M = 1
a = 0.4
m = 0.2
omega0 = 5.0
alpha0 = 3.0

[run]
dt = 0.002
t_end = 0.2
";

#[test]
fn a_scene_file_sets_parameters_and_run_options_and_set_overrides_them() {
    let dir = TempDir::new().unwrap();
    std::fs::write(dir.path().join("spin.toml"), WORKED_EXAMPLE).unwrap();
    let out = succeeds(dir.path(), &["simulate", "spin.toml", "-o", "a.csv"]);
    let (header, rows) = read_csv(&dir.path().join("a.csv"));
    assert_eq!(header[1..5], ["phi", "alpha", "phi_dot", "alpha_dot"]);
    assert_eq!(rows[0][2], 3.0);
    assert_eq!(rows[0][3], 5.0);
    assert_eq!(rows.len(), 101, "dt = 0.002 over [0, 0.2]");
    assert!(stderr(&out).contains("spin.toml"));
    // L_z = (M a²/2 + m a² sin²α) φ̇ is conserved.
    let lz = |r: &Vec<f64>| (0.08 + 0.032 * r[2].sin().powi(2)) * r[3];
    let last = rows.last().unwrap();
    assert!((lz(last) - lz(&rows[0])).abs() < 1e-12);

    succeeds(
        dir.path(),
        &[
            "simulate",
            "spin.toml",
            "--set",
            "omega0=2",
            "--t-end",
            "0.1",
            "-o",
            "b.csv",
        ],
    );
    let (_, rows) = read_csv(&dir.path().join("b.csv"));
    assert_eq!(rows[0][3], 2.0, "--set overrides the file");
    assert_eq!(rows[0][2], 3.0, "the file's other values stay");
    assert_eq!(rows.len(), 51, "--t-end overrides the file, its dt stays");
}

#[test]
fn the_shipped_scene_files_run() {
    for file in [
        "driven-hoop.toml",
        "spinning-hoop-worked-example.toml",
        "free-hoop.toml",
    ] {
        let path = root().join("scenes").join(file);
        let dir = TempDir::new().unwrap();
        let out = succeeds(
            dir.path(),
            &["simulate", path.to_str().unwrap(), "--t-end", "0.1"],
        );
        let (_, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
        assert!(rows.len() > 1, "{file}");
    }
}

#[test]
fn plots_are_written_as_png_and_svg() {
    let dir = TempDir::new().unwrap();
    succeeds(
        dir.path(),
        &[
            "simulate",
            "spinning-hoop",
            "--t-end",
            "1",
            "-o",
            "run.csv",
            "--plot",
            "run.png",
        ],
    );
    let png = std::fs::read(dir.path().join("run.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    assert!(png.len() > 10_000, "suspiciously small PNG");
    succeeds(
        dir.path(),
        &[
            "simulate",
            "driven-hoop",
            "--t-end",
            "1",
            "-o",
            "run2.csv",
            "--plot",
            "run.svg",
        ],
    );
    let svg = std::fs::read_to_string(dir.path().join("run.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
    for label in [
        "time t (s)",
        "angle (rad)",
        "angle rate (rad/s)",
        "driven-hoop",
    ] {
        assert!(svg.contains(label), "{label} missing from the SVG");
    }
    assert_eq!(
        entries(dir.path()),
        [
            "run.csv",
            "run.csv.json",
            "run.png",
            "run.svg",
            "run2.csv",
            "run2.csv.json"
        ]
    );
}

#[test]
fn unknown_scenes_and_parameters_are_named() {
    fails(
        &[],
        &["simulate", "warp-drive", "-o", "x.csv"],
        &["unknown scene `warp-drive`", "driven-hoop"],
    );
    fails(
        &[],
        &["simulate", "driven-hoop", "--set", "nope=1", "-o", "x.csv"],
        &["--set nope=1", "no parameter `nope`", "omega"],
    );
    fails(
        &[],
        &[
            "simulate",
            "driven-hoop",
            "--set",
            "omega=fast",
            "-o",
            "x.csv",
        ],
        &["`fast` is not a number"],
    );
    fails(
        &[],
        &["simulate", "driven-hoop", "--set", "omega", "-o", "x.csv"],
        &["KEY=VALUE"],
    );
}

#[test]
fn non_physical_and_non_finite_parameters_are_rejected() {
    fails(
        &[],
        &["simulate", "driven-hoop", "--set", "M=-1", "-o", "x.csv"],
        &["--set M=-1", "`M` = -1", "positive"],
    );
    fails(
        &[],
        &["simulate", "driven-hoop", "--set", "g=nan", "-o", "x.csv"],
        &["--set g=nan", "`g` = NaN", "finite"],
    );
    fails(
        &[],
        &["simulate", "driven-hoop", "--set", "a=inf", "-o", "x.csv"],
        &["`a` = inf", "finite"],
    );
    // Inertia that no body can have: a non-positive moment, and the triangle inequality.
    fails(
        &[],
        &["simulate", "free-body", "--set", "I2=0", "-o", "x.csv"],
        &["`I2` = 0", "positive"],
    );
    fails(
        &[],
        &["simulate", "heavy-top", "--set", "I3=20", "-o", "x.csv"],
        &["`I1, I2, I3` = 20", "I1 + I2 >= I3"],
    );
}

#[test]
fn bad_steps_horizons_and_integrators_are_rejected() {
    let cases: &[(&[&str], &[&str])] = &[
        (&["--dt", "0"], &["--dt 0", "positive"]),
        (&["--dt", "-0.01"], &["--dt -0.01", "positive"]),
        (&["--dt", "nan"], &["--dt NaN"]),
        (
            &["--dt", "2", "--t-end", "1"],
            &["--dt 2", "larger than the horizon"],
        ),
        (&["--t-end", "-1"], &["--t-end -1", "positive"]),
        (&["--every", "0"], &["--every 0", "at least 1"]),
        (
            &["--integrator", "lgvi"],
            &["`lgvi` cannot run scene `driven-hoop`", "gauss8"],
        ),
        (&["--integrator", "nope"], &["`nope`", "applicable"]),
        (
            &["--integrator", "dp5", "--dt", "0.01"],
            &["adaptive", "tolerance"],
        ),
        (&["--tol", "1e-9"], &["--tol 1e-9", "fixed step"]),
        (
            &["--integrator", "dop853", "--tol", "0"],
            &["--tol 0", "strictly between 0 and 1"],
        ),
        // A tolerance of 1 or more bounds nothing (1e308 gave alpha ≈ -6e81 with exit 0).
        (
            &["--integrator", "dop853", "--tol", "2"],
            &["--tol 2", "strictly between 0 and 1"],
        ),
        (
            &["--integrator", "dop853", "--tol", "1e308"],
            &["--tol 1e308", "strictly between 0 and 1"],
        ),
    ];
    for (flags, expect) in cases {
        let mut args = vec!["simulate", "driven-hoop", "-o", "x.csv"];
        args.extend_from_slice(flags);
        fails(&[], &args, expect);
    }
}

#[test]
fn bad_output_paths_are_rejected_before_running() {
    fails(
        &[],
        &["simulate", "driven-hoop", "-o", "x.csv", "--plot", "x.jpg"],
        &[".png, .svg or .pdf"],
    );
    fails(
        &[],
        &["simulate", "driven-hoop", "-o", "missing/x.csv"],
        &["missing/x.csv", "does not exist"],
    );
    fails(
        &[],
        &[
            "simulate",
            "driven-hoop",
            "-o",
            "x.csv",
            "--plot",
            "no/x.png",
        ],
        &["no/x.png", "does not exist"],
    );
}

#[test]
fn a_run_that_fails_midway_reports_time_and_state_and_leaves_no_file() {
    // ω = 1e150: the initial row is finite (ω² = 1e300), the first step of 0.5 s (far too
    // coarse for such a rate: allowed here to reach the failure) throws the bead to α ~ 1e298,
    // whose energy overflows: the run stops at that row, which is not written.
    let err = fails(
        &[],
        &[
            "simulate",
            "--allow-coarse-step",
            "driven-hoop",
            "--set",
            "omega=1e150",
            "--integrator",
            "rk4",
            "--dt",
            "0.5",
            "-o",
            "x.csv",
            "--plot",
            "x.png",
        ],
        &["driven-hoop", "non-finite", "t = 0.5", "energy = inf"],
    );
    assert!(err.contains("row: t = 0.5, alpha = "), "{err}");
    assert!(err.contains("alpha_dot = "), "{err}");
    // ω = 1e200 makes ω² overflow in the initial state's energy: refused at t = 0, before a
    // step.
    let err = fails(
        &[],
        &[
            "simulate",
            "--allow-coarse-step",
            "driven-hoop",
            "--set",
            "omega=1e200",
            "-o",
            "x.csv",
        ],
        &["non-finite output at t = 0:", "energy = -inf"],
    );
    assert!(err.contains("row: t = 0, alpha = 0.5"), "{err}");
}

#[test]
fn malformed_scene_files_are_rejected_with_their_line() {
    let cases: &[(&str, &[&str])] = &[
        (
            "scene = \"driven-hoop\"\n[parameters]\nM = = 1\n",
            &["bad.toml:3:"],
        ),
        (
            "scene = \"driven-hoop\"\nspeed = 2\n",
            &["bad.toml:2:", "speed"],
        ),
        (
            "[parameters]\nM = 1\n",
            &["bad.toml", "missing `scene", "driven-hoop"],
        ),
        (
            "\nscene = \"warp-drive\"\n",
            &["bad.toml:2:", "unknown scene `warp-drive`"],
        ),
        (
            "scene = \"driven-hoop\"\n[parameters]\nmass = 2\n",
            &["bad.toml:3:", "parameters.mass", "no parameter `mass`"],
        ),
        (
            "scene = \"driven-hoop\"\n[parameters]\nm = 0.1\nM = -1\n",
            &["bad.toml:4:", "parameters.M", "positive"],
        ),
        (
            "scene = \"driven-hoop\"\n[parameters]\ng = nan\n",
            &["bad.toml:3:", "parameters.g", "finite"],
        ),
        (
            "scene = \"driven-hoop\"\n[parameters]\nM = \"heavy\"\n",
            &["bad.toml:3:", "parameters.M", "must be a number"],
        ),
        (
            "scene = \"driven-hoop\"\n[run]\ndt = 0.0\n",
            &["bad.toml:3:", "run.dt", "positive"],
        ),
        (
            "scene = \"driven-hoop\"\n[run]\nt_end = 1\ndt = 5\n",
            &["bad.toml:4:", "run.dt", "larger than the horizon"],
        ),
        (
            "scene = \"driven-hoop\"\n[run]\nintegrator = \"lgvi\"\n",
            &["bad.toml:3:", "run.integrator", "cannot run"],
        ),
        (
            "scene = \"driven-hoop\"\n[body]\nmesh = \"t-handle.obj\"\n",
            &["bad.toml:2:", "does not take its body from a scene file"],
        ),
    ];
    for (text, expect) in cases {
        fails(
            &[("bad.toml", text)],
            &["simulate", "bad.toml", "-o", "x.csv"],
            expect,
        );
    }
    fails(
        &[],
        &["simulate", "absent.toml", "-o", "x.csv"],
        &["absent.toml", "cannot read"],
    );
}

#[test]
fn set_overrides_on_a_scene_file_are_validated_too() {
    fails(
        &[("spin.toml", WORKED_EXAMPLE)],
        &["simulate", "spin.toml", "--set", "m=-0.2", "-o", "x.csv"],
        &["--set m=-0.2", "`m` = -0.2"],
    );
}

/// The largest relative energy error a run's summary states.
fn stated_energy_error(err: &str) -> f64 {
    err.lines()
        .find_map(|l| l.strip_prefix("energy       max relative error "))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no energy line in {err}"))
}

/// Where the energy is zero while its terms are not, the relative energy error is measured
/// against the energy scale (the kinetic energy plus the potential's amplitude), so that
/// round-off reads as round-off: a bead released level with the hoop's centre (E₀ = −6e-17 in
/// floating point), a top released horizontally with no spin (E₀ = 0), a mass dropped from
/// 1e-300 m (E₀ = 1e-299). Over `|E₀|` they read 1.7, 2.8e2 and 1e277.
#[test]
fn zero_energy_runs_report_round_off_not_drift() {
    let tmp = TempDir::new().unwrap();
    for (args, bound) in [
        (
            &[
                "simulate",
                "driven-hoop",
                "--set",
                "alpha0=pi/2",
                "--set",
                "omega=0",
                "--t-end",
                "0.03",
            ][..],
            1e-15,
        ),
        (
            &[
                "simulate",
                "driven-hoop",
                "--set",
                "alpha0=pi/2",
                "--set",
                "omega=0",
                "--t-end",
                "0.03",
                "--dt",
                "1e-4",
            ][..],
            1e-15,
        ),
        (
            &[
                "simulate",
                "coriolis-drop",
                "--set",
                "omega_earth=0",
                "--set",
                "h=1e-300",
            ][..],
            1e-15,
        ),
        // vern9 at its default tolerance 1e-12 over 10 s: the method's own error, far below
        // the 1e-6 warning.
        (
            &[
                "simulate",
                "heavy-top",
                "--set",
                "tilt0=pi/2",
                "--set",
                "spin0=0",
            ][..],
            1e-12,
        ),
    ] {
        let out = succeeds(tmp.path(), args);
        let err = stderr(&out);
        let e = stated_energy_error(&err);
        assert!(e < bound, "{args:?}: {e:e}\n{err}");
        assert!(!err.contains("warning"), "{args:?}: {err}");
    }
}

/// `-o results` (no extension) keeps the format's extension in its record's name
/// (`results.csv.json`): a user's own `results.json` is never touched. Replacing files that
/// existed is said in the summary.
#[test]
fn an_output_without_extension_gets_an_unambiguous_record_and_replacing_is_said() {
    let tmp = TempDir::new().unwrap();
    std::fs::write(tmp.path().join("results.json"), "mine").unwrap();
    let args = ["simulate", "free-body", "--t-end", "0.1", "-o", "results"];
    let first = succeeds(tmp.path(), &args);
    assert!(!stderr(&first).contains("replaced"), "{}", stderr(&first));
    assert_eq!(
        std::fs::read_to_string(tmp.path().join("results.json")).unwrap(),
        "mine"
    );
    let record = std::fs::read_to_string(tmp.path().join("results.csv.json")).unwrap();
    assert!(record.contains("\"scene\": \"free-body\""), "{record}");
    // `tumble plot` finds the record by the same rule.
    succeeds(tmp.path(), &["plot", "results", "-o", "results.png"]);
    let again = succeeds(tmp.path(), &args);
    let err = stderr(&again);
    assert!(
        err.contains("replaced     results, results.csv.json (they existed)"),
        "{err}"
    );
}

/// The error of a run's final row against the scene's reference (`work_precision::reference`)
/// in the work–precision norm, with the run's provenance record.
fn run_error_and_record(dir: &Path, args: &[&str]) -> (f64, serde_json::Value, String) {
    use tumble_studies::work_precision::{reference, state_error};
    let out = succeeds(dir, args);
    let csv = args[args.iter().position(|a| *a == "-o").unwrap() + 1];
    let (_, rows) = read_csv(&dir.join(csv));
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{csv}.json"))).unwrap())
            .unwrap();
    let scene = find(args[1]).unwrap();
    let info = scene.info();
    let last = rows.last().unwrap();
    let rates = if info.rate_names.is_empty() {
        info.coordinates.len()
    } else {
        info.rate_names.len()
    };
    let n = info.coordinates.len() + rates;
    let ours = tumble_scenarios::scene::FinalState {
        t: last[0],
        values: last[1..=n].to_vec(),
    };
    let r = reference(scene, &info.default_params(), ours.t).unwrap();
    (state_error(info, &ours, &r.state), record, stderr(&out))
}

// `simulate` states the error of what it wrote: the heavy top's LGVI at dt = 1e-3 ends 8e-2 from
// the scene's reference at t = 10 (energy conserved to 5e-10 all the same), and the estimate in
// the summary and the provenance file is within a factor 10 of that and trustworthy; the default
// run states its error at its true level, 1e-12; `--check off` states none.
#[test]
fn simulate_states_an_error_estimate_within_10x_of_the_error_against_the_reference() {
    let dir = TempDir::new().unwrap();
    let (truth, record, err) = run_error_and_record(
        dir.path(),
        &[
            "simulate",
            "heavy-top",
            "--integrator",
            "lgvi",
            "--dt",
            "1e-3",
            "--allow-coarse-step",
            "-o",
            "lgvi.csv",
        ],
    );
    let e = &record["error_estimate"];
    let estimated = e["final"].as_f64().unwrap();
    eprintln!("heavy-top lgvi dt = 1e-3: estimated {estimated:e}, true {truth:e}");
    assert!(truth > 1e-2, "{truth:e}");
    assert!(estimated >= truth / 10.0 && estimated <= 10.0 * truth);
    assert_eq!(e["trust"], "trustworthy");
    assert!(e["max"].as_f64().unwrap() >= estimated);
    assert_eq!(e["rows_compared"], 10001);
    assert!(err.contains("error        estimated"), "{err}");

    let (truth, record, err) =
        run_error_and_record(dir.path(), &["simulate", "heavy-top", "-o", "default.csv"]);
    let estimated = record["error_estimate"]["final"].as_f64().unwrap();
    eprintln!("heavy-top default: estimated {estimated:e}, true {truth:e}");
    assert!(
        truth <= 1e-11 && estimated <= 1e-11,
        "{estimated:e} {truth:e}"
    );
    assert!(estimated >= truth / 10.0 && estimated <= 10.0 * truth);
    assert!(err.contains("trustworthy"), "{err}");

    let (_, record, err) = run_error_and_record(
        dir.path(),
        &["simulate", "heavy-top", "--check", "off", "-o", "off.csv"],
    );
    assert_eq!(record["error_estimate"]["status"], "off");
    assert!(err.contains("not estimated (--check off)"), "{err}");
}

/// `--precision double-double` runs the Taylor method in double-double (`taylor-dd`): the
/// same rows as `--integrator taylor-dd`, with `--integrator taylor` or none, and on the free
/// body within 1e-14 of the exact flow (the exact flow here in double). A method that runs in
/// double, `taylor-dd` under `--precision double`, and an unknown precision are refused before
/// any work, with what to give instead.
#[test]
fn precision_double_double_runs_the_taylor_method_in_double_double() {
    let dir = TempDir::new().unwrap();
    let common = [
        "simulate",
        "free-body",
        "--tol",
        "1e-30",
        "--t-end",
        "2",
        "--check",
        "off",
    ];
    let mut csvs = Vec::new();
    for (i, extra) in [
        &["--precision", "double-double"][..],
        &["--precision", "double-double", "--integrator", "taylor"],
        &["--integrator", "taylor-dd"],
    ]
    .iter()
    .enumerate()
    {
        let file = format!("run{i}.csv");
        let mut args: Vec<&str> = common.to_vec();
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", &file]);
        succeeds(dir.path(), &args);
        csvs.push(read_csv(&dir.path().join(&file)));
    }
    assert_eq!(csvs[0], csvs[2]);
    assert_eq!(csvs[1], csvs[2]);
    let (columns, rows) = &csvs[0];
    let scene = find("free-body").unwrap();
    let mut exact = Rows::default();
    scene
        .run(
            &scene.info().default_params(),
            &RunOptions {
                integrator: Some("exact".into()),
                step: Some(StepControl::Fixed(2.0)),
                t_end: Some(2.0),
                ..RunOptions::default()
            },
            &mut exact,
        )
        .unwrap();
    assert_eq!(columns, &scene.info().columns());
    let (last, reference) = (rows.last().unwrap(), exact.0.last().unwrap());
    assert_eq!(last[0], 2.0);
    let worst = last
        .iter()
        .zip(reference)
        .zip(columns)
        .filter(|(_, name)| name.as_str() != "energy_rel_err")
        .map(|((a, b), _)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-14, "{worst:e}");
    fails(
        &[],
        &[
            "simulate",
            "free-body",
            "--precision",
            "double-double",
            "--integrator",
            "vern9",
        ],
        &[
            "--integrator vern9",
            "runs in double",
            "give --integrator taylor",
        ],
    );
    fails(
        &[],
        &[
            "simulate",
            "free-body",
            "--precision",
            "double",
            "--integrator",
            "taylor-dd",
        ],
        &[
            "`taylor-dd` runs in double-double",
            "--precision double-double",
        ],
    );
    let out = tumble_in(
        dir.path(),
        &["simulate", "free-body", "--precision", "quad"],
    );
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("`quad` is not a precision: give double or double-double"),
        "{}",
        stderr(&out)
    );
}
