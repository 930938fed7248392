//! `tumble sweep slurm`: the job script (array size, afterany, the absolute binary, the
//! resume flags), bad inputs refused before any file is written; progress lines in batch
//! logs; the compute record of manifests across `--resume` and merges. The script itself runs
//! on a real Slurm cluster in `.ci/slurm`.

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use tempfile::TempDir;

use crate::support::{stderr, succeeds, tumble_in};

/// A free-hoop sweep of `spins` spins × 2 bead angles over `t_end`.
fn sweep(spins: usize, t_end: f64) -> String {
    format!(
        r#"scene = "free-hoop"

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
record = ["max_tilt", "max_energy_rel_err"]
"#
    )
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn manifest(dir: &Path) -> serde_json::Value {
    crate::support::record::<tumble_studies::sweep::record::SweepRecord>(&dir.join("manifest.json"))
}

#[test]
fn the_job_script_runs_resumable_shards_and_a_merge_after_all_of_them() {
    let tmp = TempDir::new().unwrap();
    let file = write(tmp.path(), "hoop.sweep.toml", &sweep(5, 0.2));
    let out = succeeds(
        tmp.path(),
        &[
            "sweep",
            "slurm",
            &file,
            "--shards",
            "4",
            "--cpus-per-task",
            "3",
            "--partition",
            "short",
            "--time",
            "1:30:00",
            "-o",
            "cluster",
        ],
    );
    let dir = tmp.path().join("cluster");
    let abs = std::path::absolute(&dir).unwrap();
    let abs = abs.to_str().unwrap();
    let script = read(&dir.join("submit.sh"));
    // The binary that wrote it, by its absolute path.
    let exe = Path::new(env!("CARGO_BIN_EXE_tumble"))
        .canonicalize()
        .unwrap();
    assert!(exe.is_absolute());
    assert!(
        script.contains(&format!("'{}' sweep '{abs}/sweep.toml'", exe.display())),
        "{script}"
    );
    assert!(script.contains("tasks=${1:-1-4}"), "{script}");
    assert!(script.contains(r#"sbatch --parsable --array="$tasks""#));
    assert!(
        script.contains(r#"--dependency="afterany:$array""#),
        "{script}"
    );
    assert!(!script.contains("afterok"));
    assert!(
        script.contains(r#"--shard "$k/4" --resume --break-lock"#),
        "{script}"
    );
    assert!(script.contains(r#"--threads "${SLURM_CPUS_PER_TASK:-3}" -o "#));
    assert!(script.contains(&format!(r#"-o "{abs}/shard-$k""#)));
    for line in [
        "#SBATCH --requeue",
        "#SBATCH --cpus-per-task=3",
        "#SBATCH --partition=short",
        "#SBATCH --time=1:30:00",
        &format!("#SBATCH --output={abs}/logs/shard-%a.log"),
        &format!("#SBATCH --output={abs}/logs/merge.log"),
        "#SBATCH --open-mode=append",
    ] {
        assert!(
            script.lines().any(|l| l == line),
            "no `{line}` in\n{script}"
        );
    }
    assert!(script.contains(&format!(
        r#"sweep merge "${{shard_dirs[@]}}" -o "{abs}/merged""#
    )));
    assert!(script.contains("unfinished shards: $list"), "{script}");
    assert!(script.contains(&format!("bash {abs}/submit.sh $list")));
    // The resolved definition the shards run, the logs folder; executable; checks its syntax.
    assert!(read(&dir.join("sweep.toml")).contains("count = 5"));
    assert!(dir.join("logs").is_dir());
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(dir.join("submit.sh"))
            .unwrap()
            .permissions()
            .mode();
        assert_eq!(mode & 0o111, 0o111);
    }
    if let Ok(bash) = Command::new("bash")
        .arg("-n")
        .arg(dir.join("submit.sh"))
        .output()
    {
        assert!(
            bash.status.success(),
            "{}",
            String::from_utf8_lossy(&bash.stderr)
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains(&format!("bash {abs}/submit.sh\n")), "{text}");
    assert!(text.contains("10 points in 4 shards"), "{text}");
    // The shard command of the script, run by hand, is a shard of the sweep.
    let shard = succeeds(
        tmp.path(),
        &[
            "sweep",
            &format!("{abs}/sweep.toml"),
            "--shard",
            "2/4",
            "--resume",
            "--break-lock",
            "-o",
            &format!("{abs}/shard-2"),
        ],
    );
    assert!(stderr(&shard).contains("shard 2/4"));
    // Generating again for the same sweep and count is fine; another count is refused.
    succeeds(
        tmp.path(),
        &["sweep", "slurm", &file, "--shards", "4", "-o", "cluster"],
    );
    let again = tumble_in(
        tmp.path(),
        &["sweep", "slurm", &file, "--shards", "3", "-o", "cluster"],
    );
    assert_eq!(again.status.code(), Some(1));
    assert!(
        stderr(&again).contains("shard 2/4 of a run in 4 shards"),
        "{}",
        stderr(&again)
    );

    // --tumble names another binary, made absolute.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let other = tmp.path().join("my-tumble");
        std::fs::write(&other, "#!/bin/sh\n").unwrap();
        std::fs::set_permissions(&other, std::fs::Permissions::from_mode(0o755)).unwrap();
        succeeds(
            tmp.path(),
            &[
                "sweep",
                "slurm",
                &file,
                "--shards",
                "2",
                "-o",
                "other",
                "--tumble",
                "my-tumble",
            ],
        );
        let script = read(&tmp.path().join("other/submit.sh"));
        let other = other.canonicalize().unwrap();
        assert!(
            script.contains(&format!("'{}' sweep ", other.display())),
            "{script}"
        );
    }
}

#[test]
fn bad_inputs_are_refused_before_any_script_is_written() {
    let tmp = TempDir::new().unwrap();
    let file = write(tmp.path(), "hoop.sweep.toml", &sweep(2, 0.2));
    let broken = write(
        tmp.path(),
        "broken.sweep.toml",
        &sweep(2, 0.2).replace("count = 2", "count = 1"),
    );
    let readonly = tmp.path().join("readonly");
    std::fs::create_dir(&readonly).unwrap();
    let mut perms = std::fs::metadata(&readonly).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&readonly, perms).unwrap();
    // Root writes anywhere: the read-only case only where permissions bind.
    let bound = tempfile::NamedTempFile::new_in(&readonly).is_err();
    let not_exe = write(tmp.path(), "not-a-binary", "");
    let under_a_file = format!("{not_exe}/out");
    let mut cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![&file, "--shards", "0"], "--shards 0"),
        (
            vec![&file, "--shards", "5"],
            "the sweep has 4 points; at most 4 shards",
        ),
        (vec![&broken, "--shards", "2"], "axes.omega0.count"),
        (
            vec![&file, "--shards", "2", "--cpus-per-task", "0"],
            "--cpus-per-task 0",
        ),
        (
            vec![&file, "--shards", "2", "--time", "2h"],
            "--time \"2h\"",
        ),
        (
            vec![&file, "--shards", "2", "--partition", "a b"],
            "--partition",
        ),
        (
            vec![&file, "--shards", "2", "--tumble", &not_exe],
            "not executable",
        ),
        (
            vec![&file, "--shards", "2", "--tumble", "nowhere/tumble"],
            "cannot be used",
        ),
        (vec![&file, "--shards", "2", "--set", "g=-1"], "g"),
        (
            vec![&file, "--shards", "2", "-o", "with space"],
            "holds ' '",
        ),
        (
            vec![&file, "--shards", "2", "-o", &under_a_file],
            "cannot be written",
        ),
        (
            vec![&file, "--shards", "2", "-o", &not_exe],
            "is not a directory",
        ),
    ];
    let ro_out = readonly.join("out");
    let ro_out = ro_out.to_str().unwrap();
    if bound {
        cases.push((
            vec![&file, "--shards", "2", "-o", ro_out],
            "cannot be written",
        ));
    }
    for (k, (args, message)) in cases.iter().enumerate() {
        let dir = format!("out{k}");
        let mut full = vec!["sweep", "slurm"];
        full.extend(args);
        if !args.contains(&"-o") {
            full.extend(["-o", &dir]);
        }
        let out = tumble_in(tmp.path(), &full);
        assert_eq!(out.status.code(), Some(1), "{full:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(message), "{full:?}: {}", stderr(&out));
        assert!(!tmp.path().join(&dir).exists(), "{full:?} wrote {dir}");
        assert!(out.stdout.is_empty(), "{full:?}");
    }
    assert!(!readonly.join("out").exists());
    // A folder that holds another sweep's shards is refused.
    succeeds(
        tmp.path(),
        &["sweep", "slurm", &file, "--shards", "2", "-o", "taken"],
    );
    let other = write(tmp.path(), "other.sweep.toml", &sweep(3, 0.2));
    let out = tumble_in(
        tmp.path(),
        &["sweep", "slurm", &other, "--shards", "2", "-o", "taken"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("another sweep"), "{}", stderr(&out));
}

#[test]
fn batch_logs_get_progress_lines_and_stdout_stays_empty() {
    let tmp = TempDir::new().unwrap();
    // Long enough (about 0.15 s in a release build) for several lines at the shortest period.
    let file = write(tmp.path(), "hoop.sweep.toml", &sweep(40, 3.0));
    let out = succeeds(
        tmp.path(),
        &[
            "sweep",
            &file,
            "--threads",
            "1",
            "--progress-every",
            "0.01",
            "-o",
            "p",
        ],
    );
    let err = stderr(&out);
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("progress ")).collect();
    assert!(!lines.is_empty(), "{err}");
    for l in &lines {
        assert!(
            l.contains(" of 80 points (") && l.contains(" points/s") && l.contains("ETA "),
            "{l}"
        );
    }
    assert!(out.stdout.is_empty());
    let quiet = succeeds(
        tmp.path(),
        &[
            "sweep",
            &file,
            "--progress-every",
            "0",
            "--check",
            "off",
            "-o",
            "q",
        ],
    );
    assert!(!stderr(&quiet).contains("progress "));
    let bad = tumble_in(
        tmp.path(),
        &["sweep", &file, "--progress-every", "0.001", "-o", "r"],
    );
    assert_eq!(bad.status.code(), Some(1));
    assert!(!tmp.path().join("r").exists());
}

/// A short sweep in a batch log (stderr piped, no terminal) exits as soon as its work is done,
/// a hundred times in a row: with an hour between progress lines, a stop lost by the progress
/// thread would keep the process (and its folder lock) alive for the whole hour.
#[test]
fn a_batch_sweep_never_waits_for_its_progress_period() {
    let tmp = TempDir::new().unwrap();
    // Six points on one axis, one metric: the quickest sweep that still writes its figure.
    let six = "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\nt_end = 0.05\n\
               [[axes]]\nparameter = \"omega0\"\nrange = [1.0, 6.0]\ncount = 6\n\
               [metrics]\nrecord = [\"max_energy_rel_err\"]\n";
    let file = write(tmp.path(), "six.sweep.toml", six);
    let mut slowest = Duration::ZERO;
    for run in 0..100 {
        let out = format!("r{run}");
        let begun = Instant::now();
        succeeds(
            tmp.path(),
            &[
                "sweep",
                &file,
                "--progress-every",
                "3600",
                "--check",
                "off",
                "-o",
                &out,
            ],
        );
        slowest = slowest.max(begun.elapsed());
        assert!(tmp.path().join(&out).join("results.csv").exists());
        assert!(!tmp.path().join(&out).join(".tumble.lock").exists());
    }
    // Each run computes six points of 0.05 s; a lost stop would cost 3600 s.
    assert!(slowest < Duration::from_secs(20), "slowest run {slowest:?}");
}

#[test]
fn the_compute_record_adds_up_across_resume_and_merge() {
    let tmp = TempDir::new().unwrap();
    let file = write(tmp.path(), "hoop.sweep.toml", &sweep(5, 0.2));
    // Shard 1 in two runs: the second resumes a complete shard and computes nothing.
    for _ in 0..2 {
        succeeds(
            tmp.path(),
            &[
                "sweep",
                &file,
                "--shard",
                "1/2",
                "--resume",
                "--threads",
                "2",
                "-o",
                "s1",
            ],
        );
    }
    let m1 = manifest(&tmp.path().join("s1"));
    assert_eq!(m1["compute"]["runs"].as_array().unwrap().len(), 2);
    assert_eq!(m1["compute"]["runs"][0]["computed_points"], 5);
    assert_eq!(m1["compute"]["runs"][1]["computed_points"], 0);
    assert_eq!(m1["compute"]["totals"]["computed_points"], 5);
    assert_eq!(
        m1["computed_points"], 5,
        "a resumed manifest keeps what was computed"
    );
    assert_eq!(m1["resumed_points"], 5);
    assert_eq!(m1["threads"], 2);
    let wall = m1["wall_time_s"].as_f64().unwrap();
    let first = m1["compute"]["runs"][0]["wall_time_s"].as_f64().unwrap();
    assert!(wall >= first && first > 0.0, "{wall} {first}");
    succeeds(
        tmp.path(),
        &[
            "sweep",
            &file,
            "--shard",
            "2/2",
            "--threads",
            "1",
            "-o",
            "s2",
        ],
    );
    succeeds(tmp.path(), &["sweep", "merge", "s1", "s2", "-o", "merged"]);
    let m = manifest(&tmp.path().join("merged"));
    let runs = m["compute"]["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 3);
    assert_eq!(
        runs.iter()
            .map(|r| r["shard"].as_str().unwrap())
            .collect::<Vec<_>>(),
        ["1/2", "1/2", "2/2"]
    );
    for r in runs {
        assert!(r["host"].as_str().is_some_and(|h| !h.is_empty()));
        assert!(r["threads"].as_u64().unwrap() >= 1);
        assert_eq!(r["failed_points"], 0);
        assert_eq!(r["complete"], true);
    }
    let t = &m["compute"]["totals"];
    assert_eq!(t["runs"], 3);
    assert_eq!(t["computed_points"], 10);
    assert_eq!(t["unrecorded_points"], 0);
    assert_eq!(m["computed_points"], 10);
    assert_eq!(
        m["threads"], 2,
        "a merged manifest names the threads of its shards"
    );
    assert!(m["wall_time_s"].as_f64().unwrap() > 0.0);
    assert!(read(&tmp.path().join("merged/compute.csv")).lines().count() == 4);
}

#[test]
fn a_coarse_sweep_is_refused_for_slurm_unless_allowed_and_the_shards_pass_the_limits_on() {
    let tmp = TempDir::new().unwrap();
    // omega0 up to 100 rad/s at dt = 0.01: 1 rad a step at the corner.
    let coarse = sweep(3, 0.2).replace("range = [1.0, 6.0]", "range = [1.0, 100.0]");
    let file = write(tmp.path(), "coarse.sweep.toml", &coarse);
    let out = tumble_in(
        tmp.path(),
        &["sweep", "slurm", &file, "--shards", "2", "-o", "refused"],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("does not resolve the initial rotation at point 4"),
        "{}",
        stderr(&out)
    );
    assert!(!tmp.path().join("refused").exists());
    succeeds(
        tmp.path(),
        &[
            "sweep",
            "slurm",
            &file,
            "--shards",
            "2",
            "--allow-coarse-step",
            "--point-seconds",
            "30",
            "-o",
            "allowed",
        ],
    );
    let script = read(&tmp.path().join("allowed/submit.sh"));
    assert!(
        script.contains(
            r#"--shard "$k/2" --resume --break-lock --allow-coarse-step --point-seconds 30 "#
        ),
        "{script}"
    );
}
