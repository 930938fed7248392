//! `tumble sweep`: the same `results.csv` byte for byte whatever the threads, after a kill and
//! `--resume`, and from merged shards; failing points marked and the exit status 3; bad sweep
//! files refused before any work; the output folder's files.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use tempfile::TempDir;

use crate::support::{root, stderr, succeeds, tumble_in};
use tumble_studies::sweep::SweepDefinition;

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A small sweep of the free hoop: 4 spins × 2 bead angles over `t_end`.
pub(crate) fn small(t_end: f64, spins: usize) -> String {
    format!(
        r#"# A small test sweep.
scene = "free-hoop"

[parameters]
g = 9.81
a = 1.0

[run]
integrator = "gauss8"
dt = 0.01
t_end = {t_end:?}

[[axes]]
parameter = "omega0"
range = [1.0, 6.0]
count = {spins}

[[axes]]
parameter = "alpha0"
values = [0.5, 2.0]

[metrics]
record = ["max_tilt", "final_tilt", "time_tilt_exceeds", "max_energy_rel_err"]
tilt_threshold = 0.05
"#
    )
}

pub(crate) fn write_sweep(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn manifest(dir: &Path) -> serde_json::Value {
    crate::support::record::<tumble_studies::sweep::record::SweepRecord>(&dir.join("manifest.json"))
}

#[test]
fn one_and_two_threads_write_the_same_results_and_a_complete_folder() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.5, 4));
    let file = file.to_str().unwrap();
    succeeds(tmp.path(), &["sweep", file, "--threads", "1", "-o", "one"]);
    let out = succeeds(tmp.path(), &["sweep", file, "--threads", "2", "-o", "two"]);
    let one = read(&tmp.path().join("one/results.csv"));
    let two = read(&tmp.path().join("two/results.csv"));
    assert_eq!(one, two);
    assert_eq!(one.lines().count(), 1 + 8);
    assert!(one.starts_with(
        "index,omega0,alpha0,max_tilt,final_tilt,time_tilt_exceeds,max_energy_rel_err,status,reason\n"
    ));
    assert!(one.lines().skip(1).all(|l| l.ends_with(",ok,")), "{one}");
    // The folder: definition, journal, results, map and slices, manifest; nothing partial.
    let dir = tmp.path().join("two");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "compute.csv",
            "journal.csv",
            "manifest.json",
            "results.csv",
            "sweep.toml",
            "tilt-map.png",
            "tilt-map.svg",
            "tilt-slices.png",
            "tilt-slices.svg"
        ]
    );
    let svg = read(&dir.join("tilt-map.svg"));
    for label in [
        "ω₀ (rad/s)",
        "α₀ (rad)",
        "maximum tilt (rad)",
        "√(g/a)",
        "cos α* = g/(a ω₀²)",
    ] {
        assert!(svg.contains(label), "map without `{label}`");
    }
    let m = manifest(&dir);
    assert_eq!(m["threads"], 2);
    assert_eq!(m["points"], 8);
    assert_eq!(m["failed"], 0);
    assert_eq!(m["integrator"], "gauss8");
    assert_eq!(m["dt"], 0.01);
    assert_eq!(m["definition"]["scene"], "free-hoop");
    assert_eq!(m["definition"]["axes"][0]["parameter"], "omega0");
    assert_eq!(m["tumble_version"], env!("CARGO_PKG_VERSION"));
    assert!(m["wall_time_s"].as_f64().unwrap() > 0.0);
    assert!(m["points_per_second"].as_f64().unwrap() > 0.0);
    // The resolved definition runs the same sweep again.
    let resolved = dir.join("sweep.toml");
    succeeds(
        tmp.path(),
        &["sweep", resolved.to_str().unwrap(), "-o", "three"],
    );
    assert_eq!(read(&tmp.path().join("three/results.csv")), one);
    // No progress bar when stderr is not a terminal: only the summary.
    let err = stderr(&out);
    assert!(err.contains("8 ok, 0 failed"), "{err}");
    assert!(!err.contains("ETA"), "{err}");
}

#[test]
fn a_killed_sweep_resumes_to_the_same_results() {
    let tmp = TempDir::new().unwrap();
    // 200 points of a few ms each on one thread: long enough to be killed midway.
    let file = write_sweep(tmp.path(), "kill.sweep.toml", &small(1.0, 100));
    let file = file.to_str().unwrap();
    succeeds(
        tmp.path(),
        &["sweep", file, "--threads", "2", "-o", "reference"],
    );
    let reference = read(&tmp.path().join("reference/results.csv"));

    let mut child = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(tmp.path())
        .args(["sweep", file, "--threads", "1", "-o", "killed"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let journal = tmp.path().join("killed/journal.csv");
    let start = Instant::now();
    // Kill once the first chunk of rows is on disk (2 header lines, 16 rows).
    loop {
        let lines = std::fs::read_to_string(&journal).map_or(0, |t| t.lines().count());
        if lines >= 2 + 16 {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no journal rows after two minutes"
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the sweep ended before it could be killed"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert!(!status.success());
    let killed = tmp.path().join("killed");
    assert!(
        !killed.join("results.csv").exists() && !killed.join("manifest.json").exists(),
        "a killed sweep left results behind as if complete"
    );
    let done = read(&journal).lines().count() - 2;
    assert!(done < 200, "all {done} points finished before the kill");

    // Without --resume the folder is refused; with it, the rest is computed.
    let out = tumble_in(tmp.path(), &["sweep", file, "-o", "killed"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("pass --resume"), "{}", stderr(&out));
    succeeds(
        tmp.path(),
        &["sweep", file, "--threads", "2", "-o", "killed", "--resume"],
    );
    assert_eq!(read(&killed.join("results.csv")), reference);
    let m = manifest(&killed);
    let resumed = m["resumed_points"].as_u64().unwrap();
    assert!((16..200).contains(&resumed), "{resumed}");
    assert_eq!(m["computed_points"].as_u64().unwrap(), 200 - resumed);
}

#[test]
fn three_shards_merge_into_the_unsharded_results() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "shards.sweep.toml", &small(0.5, 5));
    let file = file.to_str().unwrap();
    succeeds(tmp.path(), &["sweep", file, "-o", "whole"]);
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let dir = format!("part{k}");
        succeeds(
            tmp.path(),
            &[
                "sweep",
                file,
                "--shard",
                &shard,
                "-o",
                &dir,
                "--threads",
                "1",
            ],
        );
        // A shard's results hold its points only, and it draws no map.
        let rows = read(&tmp.path().join(&dir).join("results.csv"))
            .lines()
            .count()
            - 1;
        assert_eq!(rows, [4, 3, 3][k - 1], "shard {shard}");
        assert!(!tmp.path().join(&dir).join("tilt-map.png").exists());
        assert_eq!(manifest(&tmp.path().join(&dir))["shard"], shard);
    }
    succeeds(
        tmp.path(),
        &["sweep", "merge", "part1", "part2", "part3", "-o", "merged"],
    );
    let merged = tmp.path().join("merged");
    assert_eq!(
        read(&merged.join("results.csv")),
        read(&tmp.path().join("whole/results.csv"))
    );
    assert_eq!(
        read(&merged.join("sweep.toml")),
        read(&tmp.path().join("whole/sweep.toml"))
    );
    assert!(merged.join("tilt-map.png").exists());
    assert_eq!(manifest(&merged)["command"], "merge");
    // An incomplete set of shards is refused.
    let out = tumble_in(
        tmp.path(),
        &["sweep", "merge", "part1", "part3", "-o", "m2"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("1 of 3 shards not finished: 2/3")
            && stderr(&out).contains("shard 2/3: no folder given holds it"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn failing_points_are_marked_and_the_exit_status_says_so() {
    let tmp = TempDir::new().unwrap();
    // At 10^4 rad/s, dt = 0.01 s is absurd: gauss8's stage iteration diverges there (such a
    // step is refused unless allowed).
    let text = small(0.5, 2).replace(
        "range = [1.0, 6.0]\ncount = 2",
        "values = [1.0, 1e4, 3.0, 2e4]",
    );
    let file = write_sweep(tmp.path(), "fail.sweep.toml", &text);
    let out = tumble_in(
        tmp.path(),
        &[
            "sweep",
            file.to_str().unwrap(),
            "-o",
            "f",
            "--allow-coarse-step",
        ],
    );
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(err.contains("4 of 8 points failed"), "{err}");
    let results = read(&tmp.path().join("f/results.csv"));
    let failed: Vec<&str> = results
        .lines()
        .skip(1)
        .filter(|l| l.contains(",failed,"))
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(failed, ["2", "3", "6", "7"]);
    for line in results.lines().skip(1) {
        let ok = line.ends_with(",ok,");
        assert!(
            ok || line.contains("did not converge"),
            "a failed row without its reason: {line}"
        );
    }
    let m = manifest(&tmp.path().join("f"));
    assert_eq!(m["failed"], 4);
    assert_eq!(m["failures"][0]["index"], 2);
    assert!(
        m["failures"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("did not converge")
    );
}

#[test]
fn bad_sweep_files_and_flags_are_refused_before_any_work() {
    let tmp = TempDir::new().unwrap();
    let good = small(0.5, 2);
    let cases: Vec<(String, &str)> = vec![
        (good.replace("[run]", "[run]\nstep = 0.1"), "bad.toml:9:1"),
        (
            good.replace("t_end = 0.5", "t_end = 0.5\nevery = 3"),
            "every",
        ),
        (good.replace("count = 2", "count = 0"), "axes.omega0.count"),
        (good.replace("[1.0, 6.0]", "[6.0, 1.0]"), "increasing"),
        (
            good.replace("\"omega0\"", "\"omega\""),
            "no parameter `omega`",
        ),
        (good.replace("a = 1.0", "a = -1.0"), "parameters.a"),
        (
            good.replace("\"max_tilt\"", "\"flips\""),
            "torque-free bodies",
        ),
        (good.replace("tilt_threshold = 0.05", ""), "tilt_threshold"),
        (good.replace("dt = 0.01", "dt = 1.0"), "run.dt"),
        (
            good.replace("values = [0.5, 2.0]", "values = [0.5, 2.0]\ncount = 3"),
            "goes with a `range`",
        ),
    ];
    for (text, needle) in &cases {
        let file = write_sweep(tmp.path(), "bad.toml", text);
        let out = tumble_in(
            tmp.path(),
            &["sweep", file.to_str().unwrap(), "-o", "never"],
        );
        assert_eq!(out.status.code(), Some(1), "{needle}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(err.contains(needle), "{needle}: {err}");
        assert!(err.contains("bad.toml:"), "no location: {err}");
        assert!(
            !tmp.path().join("never").exists(),
            "{needle}: output created"
        );
    }
    let file = write_sweep(tmp.path(), "ok.toml", &good);
    let file = file.to_str().unwrap();
    for (args, needle) in [
        (vec!["--threads", "0"], "--threads 0"),
        (vec!["--shard", "4/3"], "shard 4/3"),
        (vec!["--shard", "two"], "K/N"),
        (vec!["--set", "omega0=3"], "swept by the axis"),
        (vec!["--set", "run.dt=x"], "not a number"),
        (vec!["--set", "warp=9"], "no parameter `warp`"),
    ] {
        let mut all = vec!["sweep", file, "-o", "never"];
        all.extend(args);
        let out = tumble_in(tmp.path(), &all);
        assert_eq!(out.status.code(), Some(1), "{all:?}");
        assert!(stderr(&out).contains(needle), "{all:?}: {}", stderr(&out));
        assert!(!tmp.path().join("never").exists());
    }
    let out = tumble_in(tmp.path(), &["sweep", "missing.sweep.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("cannot read the sweep file"));
}

#[test]
fn the_built_in_map_runs_with_overrides_into_out_tilt_map() {
    let tmp = TempDir::new().unwrap();
    succeeds(
        tmp.path(),
        &[
            "sweep",
            "--set",
            "axes.omega0.count=3",
            "--set",
            "axes.alpha0.count=2",
            "--set",
            "run.t_end=0.3",
        ],
    );
    let dir = tmp.path().join("out/tilt-map");
    let results = read(&dir.join("results.csv"));
    assert_eq!(results.lines().count(), 1 + 6);
    assert!(dir.join("tilt-map.png").exists() && dir.join("tilt-slices.svg").exists());
    assert_eq!(manifest(&dir)["definition"]["origin"], "built-in tilt map");
}

#[test]
fn the_example_sweep_files_are_valid() {
    let mut found = 0;
    for entry in std::fs::read_dir(root().join("scenes")).unwrap() {
        let path = entry.unwrap().path();
        if path.to_string_lossy().ends_with(".sweep.toml") {
            SweepDefinition::load(&path, &[]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            found += 1;
        }
    }
    assert!(found >= 2, "{found} example sweep files");
}

/// `--threads` beyond the points to compute starts only as many workers as points (100,000
/// threads were once spawned for 6 points); the manifest says how many ran.
#[test]
fn threads_are_clamped_to_the_points() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.2, 3));
    let file = file.to_str().unwrap();
    succeeds(
        tmp.path(),
        &["sweep", file, "--threads", "100000", "-o", "many"],
    );
    assert_eq!(manifest(&tmp.path().join("many"))["threads"], 6);
}

/// Every whole sweep checks itself: chosen points (the grid's corners, its most sensitive
/// points by a screen and an even spread) again at half the step, the largest change found in the summary and of
/// each metric in the manifest. A setting
/// that does not resolve the metrics (Gauss–Legendre 2 at 0.05 s) exits with status 4 and says
/// so; `--check off` skips the check.
#[test]
fn a_sweep_states_how_far_its_metrics_converged() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(1.0, 4));
    let file = file.to_str().unwrap();
    let out = succeeds(tmp.path(), &["sweep", file, "-o", "good"]);
    let err = stderr(&out);
    assert!(err.contains("self-check   largest change"), "{err}");
    assert!(err.contains("within the tolerance"), "{err}");
    let check = &manifest(&tmp.path().join("good"))["self_check"];
    assert_eq!(check["converged"], true);
    assert_eq!(check["dt"], 0.005);
    // max(8, 1 %) of 8 points: all of them, corners 0, 1, 6, 7 included.
    assert_eq!(check["points"].as_array().unwrap().len(), 8);
    assert!(check["largest_change"].as_f64().unwrap() < 1e-6);

    let coarse = small(1.0, 4)
        .replace("integrator = \"gauss8\"", "integrator = \"gauss2\"")
        .replace("dt = 0.01", "dt = 0.05");
    let file = write_sweep(tmp.path(), "coarse.sweep.toml", &coarse);
    let file = file.to_str().unwrap();
    let out = tumble_in(tmp.path(), &["sweep", file, "-o", "coarse", "--check", "3"]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(err.contains("self-check   largest change"), "{err}");
    assert!(err.contains("more than the tolerance"), "{err}");
    let check = &manifest(&tmp.path().join("coarse"))["self_check"];
    assert_eq!(check["converged"], false);
    assert_eq!(check["points"].as_array().unwrap().len(), 3);
    // The results are written all the same.
    assert!(tmp.path().join("coarse/results.csv").is_file());

    let out = succeeds(
        tmp.path(),
        &["sweep", file, "-o", "unchecked", "--check", "off"],
    );
    assert!(stderr(&out).contains("self-check   off"));
    assert!(manifest(&tmp.path().join("unchecked"))["self_check"].is_null());
    let out = tumble_in(tmp.path(), &["sweep", file, "-o", "x", "--check", "many"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("--check many"));
    assert!(!tmp.path().join("x").exists());
}

/// Two writers, one folder: while a sweep runs, a second `tumble sweep … --resume` on its
/// folder is refused (exit 1, naming the holder) instead of interleaving journal writes; the
/// first finishes, the lock is gone, and a later `--resume` works. A lock left by a process
/// that no longer runs on this host is taken over.
#[test]
fn a_second_writer_on_a_busy_folder_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "slow.sweep.toml", &small(20.0, 30));
    let file = file.to_str().unwrap();
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(tmp.path())
        .args(["sweep", file, "-o", "busy", "--threads", "1"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let lock = tmp.path().join("busy/.tumble.lock");
    let start = std::time::Instant::now();
    while !lock.exists() {
        assert!(
            start.elapsed().as_secs() < 30,
            "the first sweep never locked its folder"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let second = tumble_in(tmp.path(), &["sweep", file, "-o", "busy", "--resume"]);
    let err = stderr(&second);
    let first_status = first.wait().unwrap();
    assert_eq!(second.status.code(), Some(1), "{err}");
    assert!(err.contains("busy: in use by tumble process"), "{err}");
    assert!(err.contains("--break-lock"), "{err}");
    assert!(first_status.success());
    assert!(!lock.exists(), "the lock outlived its holder");
    succeeds(tmp.path(), &["sweep", file, "-o", "busy", "--resume"]);
    // A stale lock (a dead pid on this host) is taken over.
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    std::fs::write(
        &lock,
        format!("999999999\n{}\nthen\ntumble sweep\n", host.trim()),
    )
    .unwrap();
    succeeds(tmp.path(), &["sweep", file, "-o", "busy", "--resume"]);
    assert!(!lock.exists());
}

/// An override that cannot apply is refused, not ignored: `axes.NAME.end` on an axis that
/// lists its values.
#[test]
fn an_override_of_a_values_axis_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(1.0, 4));
    let out = tumble_in(
        tmp.path(),
        &[
            "sweep",
            file.to_str().unwrap(),
            "--set",
            "axes.alpha0.end=3",
            "-o",
            "o",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("lists its `values`"),
        "{}",
        stderr(&out)
    );
    assert!(!tmp.path().join("o").exists());
}

/// Integrator studies from the command line: `run.integrator` with `run.tol` (which clears the
/// file's `run.dt`), `axes.NAME.values`, `axes.NAME.spacing`; bad values refused before any
/// point runs.
#[test]
fn integrator_studies_from_the_command_line() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(1.0, 4));
    let file = file.to_str().unwrap();
    succeeds(
        tmp.path(),
        &[
            "sweep",
            file,
            "--set",
            "run.integrator=dop853",
            "--set",
            "run.tol=1e-11",
            "--set",
            "axes.alpha0.values=[0.5, pi/2, 2.5]",
            "-o",
            "dop",
        ],
    );
    let m = manifest(&tmp.path().join("dop"));
    assert_eq!(m["integrator"], "dop853");
    assert_eq!(m["tol"], 1e-11);
    assert!(m["dt"].is_null());
    assert_eq!(m["points"], 12);
    let toml = read(&tmp.path().join("dop/sweep.toml"));
    assert!(toml.contains("integrator = \"dop853\""), "{toml}");
    succeeds(
        tmp.path(),
        &[
            "sweep",
            file,
            "--set",
            "axes.omega0.spacing=log",
            "-o",
            "log",
        ],
    );
    for (set, expect) in [
        ("run.integrator=verlet", "verlet"),
        ("run.integrator=dop853", "adaptive: give a tolerance"),
        ("axes.omega0.spacing=cubic", "spacing"),
        ("axes.omega0.values=0.5", "expected a list"),
        ("run.dt=fast", "`fast` is not a number"),
    ] {
        let out = tumble_in(tmp.path(), &["sweep", file, "--set", set, "-o", "bad"]);
        assert_eq!(out.status.code(), Some(1), "{set}: {}", stderr(&out));
        assert!(stderr(&out).contains(expect), "{set}: {}", stderr(&out));
        assert!(!tmp.path().join("bad").exists(), "{set}");
    }
}

/// A sweep too large to list is refused by its definition, with the limit (10¹² grid points or
/// random samples once aborted on an allocation).
#[test]
fn an_enormous_sweep_is_refused_by_its_definition() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(1.0, 4));
    let file = file.to_str().unwrap();
    let out = tumble_in(
        tmp.path(),
        &[
            "sweep",
            file,
            "--set",
            "axes.omega0.count=1000000000000",
            "-o",
            "huge",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("more than 100000000 points"),
        "{}",
        stderr(&out)
    );
    assert!(!tmp.path().join("huge").exists());
}

#[test]
fn a_sweep_manifest_says_how_it_was_made() {
    let tmp = tempfile::tempdir().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.2, 2));
    succeeds(tmp.path(), &["sweep", file.to_str().unwrap(), "-o", "p"]);
    let p = &manifest(&tmp.path().join("p"))["provenance"];
    assert_eq!(p["tumble_version"], env!("CARGO_PKG_VERSION"));
    assert!(p["git_commit"].as_str().is_some_and(|c| !c.is_empty()));
    assert_eq!(p["command_line"][1], "sweep");
    assert!(p["date"].as_str().is_some_and(|d| d.ends_with('Z')));
    assert!(p["host"].as_str().is_some_and(|h| !h.is_empty()));
}

#[test]
fn the_sweep_file_sets_the_self_check_tolerance_and_the_flag_overrides_it() {
    let tmp = TempDir::new().unwrap();
    let d = tmp.path();
    // gauss8 at 0.01 against 0.005: the tilt metrics move by ~1e-12, far above 1e-20.
    let strict = small(0.5, 4).replace(
        "tilt_threshold = 0.05",
        "tilt_threshold = 0.05\ntolerance = 1e-20",
    );
    let file = write_sweep(d, "strict.sweep.toml", &strict);
    let f = file.to_str().unwrap();
    let out = tumble_in(d, &["sweep", f, "-o", "a", "--check", "4"]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("more than the tolerance 1.0e-20"),
        "{}",
        stderr(&out)
    );
    assert!(read(&d.join("a/sweep.toml")).contains("tolerance = 1e-20"));
    let out = tumble_in(
        d,
        &[
            "sweep",
            f,
            "-o",
            "b",
            "--check",
            "4",
            "--check-tolerance",
            "1e-3",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let bad = small(0.5, 4).replace(
        "tilt_threshold = 0.05",
        "tilt_threshold = 0.05\ntolerance = -1",
    );
    let file = write_sweep(d, "bad.sweep.toml", &bad);
    let out = tumble_in(d, &["sweep", file.to_str().unwrap(), "-o", "c"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("metrics.tolerance"),
        "{}",
        stderr(&out)
    );
    assert!(!d.join("c").exists());
}

/// A sweep of many points says how long it will take before it starts, from a short sample:
/// a line in a batch log as on a terminal. A small one starts without.
#[test]
fn a_large_sweep_states_its_estimated_time_before_it_starts() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "big.sweep.toml", &small(0.02, 150));
    let out = succeeds(
        tmp.path(),
        &[
            "sweep",
            file.to_str().unwrap(),
            "--check",
            "off",
            "--threads",
            "2",
            "-o",
            "big",
        ],
    );
    let err = stderr(&out);
    let first = err.lines().next().unwrap_or("");
    assert!(
        first.starts_with("estimate     about ")
            && first.contains(" for 300 points on 2 threads ("),
        "{err}"
    );
    let small_file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.02, 4));
    let out = succeeds(
        tmp.path(),
        &[
            "sweep",
            small_file.to_str().unwrap(),
            "--check",
            "off",
            "-o",
            "s",
        ],
    );
    assert!(!stderr(&out).contains("estimate"), "{}", stderr(&out));
}
