//! `tumble hard-cases`: the atlas folder (CSV, figure, manifest), a user's case file, bad flags
//! refused before any run, and a budget that runs out resumed to the same atlas.

use tempfile::TempDir;

use crate::support::{record, stderr, succeeds, tumble_in};

fn read(path: &std::path::Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

const ARGS: &[&str] = &[
    "hard-cases",
    "--cases",
    "sleeping-top,nearly-symmetric-body",
    "--integrators",
    "gauss8,rk4:dt=0.1",
];

#[test]
fn an_atlas_writes_its_csv_figure_and_manifest_and_records_failures_as_results() {
    let tmp = TempDir::new().unwrap();
    let mut args = ARGS.to_vec();
    args.extend(["-o", "atlas"]);
    let out = succeeds(tmp.path(), &args);
    let summary = stderr(&out);
    assert!(summary.contains("4 entries"), "{summary}");
    let dir = tmp.path().join("atlas");
    for f in ["atlas.csv", "atlas.png", "atlas.svg", "manifest.json"] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let csv = read(&dir.join("atlas.csv"));
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 1 + 4, "{csv}");
    assert!(rows[0].starts_with("case,case_key,method,dt,tol,chosen_by,easy_error,status,reason"));
    // gauss8 by the rule meets both properties; rk4 at h·|ω| = 5 on the top does not.
    let line = |case: &str, method: &str| {
        rows.iter()
            .find(|r| r.starts_with(&format!("{case},")) && r.contains(&format!(",{method},")))
            .unwrap_or_else(|| panic!("{case} {method}: {csv}"))
            .to_string()
    };
    assert!(line("sleeping-top", "gauss8").contains(",rule,"));
    assert!(line("sleeping-top", "gauss8").contains(",ok,"));
    let bad = line("sleeping-top", "rk4:dt=0.1");
    assert!(
        bad.contains(",given,") && (bad.contains(",violated,") || bad.contains(",failed,")),
        "{bad}"
    );
    let m = record::<tumble_studies::hard_cases::record::AtlasRecord>(&dir.join("manifest.json"));
    assert_eq!(m["entries"], 4);
    assert_eq!(m["finished"], 4);
    assert!(m["rule"].as_str().unwrap().contains("easy twin"));
    assert_eq!(m["cases"][0]["name"], "sleeping-top");
    // The threads the atlas ran on (without --threads: the cores), not 0.
    assert!(
        m["provenance"]["threads"].as_u64().is_some_and(|n| n >= 1),
        "{}",
        m["provenance"]
    );
    // A complete atlas resumed computes nothing and writes the same CSV.
    let mut again = ARGS.to_vec();
    again.extend(["-o", "atlas", "--resume"]);
    succeeds(tmp.path(), &again);
    assert_eq!(read(&dir.join("atlas.csv")), csv);
}

#[test]
fn a_budget_that_runs_out_exits_3_and_resume_finishes_the_same_atlas() {
    let tmp = TempDir::new().unwrap();
    let mut whole = ARGS.to_vec();
    whole.extend(["-o", "whole"]);
    succeeds(tmp.path(), &whole);
    let mut cut = ARGS.to_vec();
    cut.extend(["-o", "cut", "--budget", "1e-6"]);
    let out = tumble_in(tmp.path(), &cut);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(stderr(&out).contains("--resume"), "{}", stderr(&out));
    let mut resumed = ARGS.to_vec();
    resumed.extend(["-o", "cut", "--resume"]);
    succeeds(tmp.path(), &resumed);
    // Same outcomes and numbers but the wall times.
    let strip = |text: String| -> Vec<String> {
        text.lines()
            .map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string())
            .collect()
    };
    assert_eq!(
        strip(read(&tmp.path().join("cut/atlas.csv"))),
        strip(read(&tmp.path().join("whole/atlas.csv")))
    );
}

#[test]
fn a_case_file_of_ones_own_runs_and_bad_flags_are_refused_before_any_run() {
    let tmp = TempDir::new().unwrap();
    let mine = tmp.path().join("mine.case.toml");
    std::fs::write(
        &mine,
        r#"
name = "slow-drop"
scene = "coriolis-drop"
why = "A drop from 10 m lasts 1.4 s: not hard, but a case of one's own, run by the atlas like the built-in ones."
good = "Lands where the reference lands."

[parameters]
h = 10.0

[run]
t_end = 1.0

[easy]
h = 100.0

[property]
error = 1e-5
"#,
    )
    .unwrap();
    succeeds(
        tmp.path(),
        &[
            "hard-cases",
            "--case-file",
            "mine.case.toml",
            "--integrators",
            "dop853",
            "-o",
            "mine",
        ],
    );
    assert!(read(&tmp.path().join("mine/atlas.csv")).contains("slow-drop,"));
    for (args, expect) in [
        (vec!["--cases", "no-such-case"], "no built-in case"),
        (vec!["--integrators", "verlet2"], "verlet2"),
        (vec!["--integrators", "rk4:dt=-1"], "positive"),
        (vec!["--integrators", "rk4:h=0.1"], "neither dt nor tol"),
        (vec!["--budget", "0"], "--budget"),
        (vec!["--run-seconds", "nan"], "--run-seconds"),
        (vec!["--case-file", "missing.toml"], "missing.toml"),
        (
            vec![
                "--cases",
                "sleeping-top",
                "--integrators",
                "split-exact2:dt=0.1,exact",
            ],
            "exact",
        ),
        (
            vec!["--cases", "fast-top,sleeping-top,fast-top"],
            "`fast-top` twice",
        ),
        (
            vec!["--cases", "fast-top", "--integrators", "rk4,dop853,rk4"],
            "`rk4` twice",
        ),
    ] {
        let mut all = vec!["hard-cases", "-o", "bad"];
        all.extend(&args);
        let out = tumble_in(tmp.path(), &all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(expect), "{args:?}: {}", stderr(&out));
        assert!(!tmp.path().join("bad").exists(), "{args:?}");
    }
    let list = succeeds(tmp.path(), &["hard-cases", "--list"]);
    let text = String::from_utf8_lossy(&list.stdout);
    assert!(
        text.contains("t-handle-separatrix") && text.contains("long-free-hoop"),
        "{text}"
    );
}
