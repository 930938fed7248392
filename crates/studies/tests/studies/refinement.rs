//! Adaptive refinement of a grid sweep: its points are the uniform grid's points with the
//! uniform grid's results, and the same whatever the threads, interruptions and shards.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

use tumble_studies::sweep::{
    self, Override, OverrideValue, RunConfig, Shard, SweepDefinition, SweepError, results_csv,
};

/// A free-hoop map over 2 s: 17 spins × 15 bead angles (255 points), refined by `max_tilt`
/// from every 4th value (2 levels).
const REFINED: &str = include_str!("../fixtures/refined-map.sweep.toml");

fn refined() -> SweepDefinition {
    SweepDefinition::parse(REFINED, "refined.toml", &[]).unwrap()
}

fn set(key: &str, value: OverrideValue) -> Override {
    Override {
        key: key.into(),
        text: format!("{key}=…"),
        value,
    }
}

fn threads(n: usize) -> RunConfig<'static> {
    RunConfig {
        threads: n,
        ..RunConfig::default()
    }
}

fn run_whole(def: &SweepDefinition, dir: &std::path::Path, config: &RunConfig<'_>) -> Vec<u8> {
    let report = sweep::run(def, dir, config, &mut |_| {}).unwrap();
    assert!(report.complete());
    results_csv(def, &report.rows).unwrap()
}

#[test]
fn refined_points_are_points_of_the_uniform_grid_with_its_results_bit_for_bit() {
    let def = refined();
    let uniform = SweepDefinition::parse(
        REFINED,
        "uniform.toml",
        &[set("refine.levels", OverrideValue::Number(0.0))],
    )
    .unwrap();
    assert!(uniform.refine.is_none());
    let tmp = tempfile::tempdir().unwrap();
    let all = sweep::run(&uniform, &tmp.path().join("u"), &threads(2), &mut |_| {}).unwrap();
    let part = sweep::run(&def, &tmp.path().join("r"), &threads(2), &mut |_| {}).unwrap();
    assert!(part.complete());
    // More than the coarse grid (5 × 5), fewer than the whole grid.
    let n = part.rows.len();
    assert!(n > 25 && n < 255, "{n} points");
    for row in &part.rows {
        assert_eq!(*row, all.rows[row.index as usize], "point {}", row.index);
    }
    // Every level is there, and the coarse level is the coarse grid.
    let levels = sweep::refine::points_by_level(&def, &part.rows).unwrap();
    assert_eq!(levels[0], 25);
    assert!(levels.iter().all(|&c| c > 0), "{levels:?}");
    // A coarse edge whose ends differ by more than the threshold belongs to cells that were
    // split: its midpoint was computed.
    let have: std::collections::BTreeSet<u64> = part.rows.iter().map(|r| r.index).collect();
    let value = |i: u64| all.rows[i as usize].metrics[0].unwrap();
    for ix in (0..17).step_by(4) {
        for iy in (0..12).step_by(4) {
            let (a, b) = (ix * 15 + iy, ix * 15 + iy + 4);
            if (value(a) - value(b)).abs() > 0.1 {
                assert!(have.contains(&(a + 2)), "the edge {a}–{b} was not split");
            }
        }
    }
}

#[test]
fn sweep_diff_compares_a_refined_sweep_with_the_uniform_grid_at_the_points_it_has() {
    let def = refined();
    let uniform = SweepDefinition::parse(
        REFINED,
        "uniform.toml",
        &[set("refine.levels", OverrideValue::Number(0.0))],
    )
    .unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let all = sweep::run(&uniform, &tmp.path().join("u"), &threads(2), &mut |_| {}).unwrap();
    let part = sweep::run(&def, &tmp.path().join("r"), &threads(2), &mut |_| {}).unwrap();
    let d = sweep::diff(&def, &part.rows, &uniform, &all.rows).unwrap();
    assert_eq!(d.points, part.rows.len() as u64);
    assert_eq!(d.largest(), 0.0);
    assert!(d.status_differs.is_empty());
}

#[test]
fn a_refined_sweep_is_the_same_on_one_or_two_threads_after_a_cancel_and_a_torn_journal() {
    let def = refined();
    let tmp = tempfile::tempdir().unwrap();
    let reference = run_whole(&def, &tmp.path().join("one"), &threads(1));
    assert_eq!(
        run_whole(&def, &tmp.path().join("two"), &threads(2)),
        reference
    );

    // Cancelled in the first refined level (after the 25 coarse points and 3 more).
    let cut = tmp.path().join("cut");
    let cancel = AtomicBool::new(false);
    let config = RunConfig {
        threads: 1,
        cancel: Some(&cancel),
        ..RunConfig::default()
    };
    let partial = sweep::run(&def, &cut, &config, &mut |p| {
        if p.finished >= 28 {
            cancel.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    assert!(!partial.complete(), "{} rows", partial.rows.len());
    assert!(partial.rows.len() >= 28);
    // A kill in the middle of a write leaves a torn last line; resuming drops it.
    let mut journal = std::fs::OpenOptions::new()
        .append(true)
        .open(cut.join(sweep::JOURNAL))
        .unwrap();
    journal.write_all(b"77,1,3.1,0.9").unwrap();
    drop(journal);
    let resumed = RunConfig {
        resume: true,
        ..threads(2)
    };
    let report = sweep::run(&def, &cut, &resumed, &mut |_| {}).unwrap();
    assert_eq!(report.resumed, partial.rows.len() as u64);
    assert_eq!(results_csv(&def, &report.rows).unwrap(), reference);
    // Resuming the finished refinement computes nothing.
    let again = sweep::run(&def, &cut, &resumed, &mut |_| {}).unwrap();
    assert_eq!(again.computed, 0);
    assert_eq!(results_csv(&def, &again.rows).unwrap(), reference);
}

#[test]
fn merged_shards_of_a_refined_sweep_give_the_unsharded_results() {
    let def = refined();
    let tmp = tempfile::tempdir().unwrap();
    let reference = run_whole(&def, &tmp.path().join("whole"), &threads(2));
    let n = 3;
    let dirs: Vec<_> = (1..=n).map(|k| tmp.path().join(format!("s{k}"))).collect();
    // Shard 3 first stops unfinished: the merge lists it.
    for (k, dir) in (1..=n).zip(&dirs).take(2) {
        let config = RunConfig {
            shard: Shard::new(k, n).unwrap(),
            ..threads(1)
        };
        assert!(
            sweep::run(&def, dir, &config, &mut |_| {})
                .unwrap()
                .complete()
        );
    }
    let e = sweep::merge(&dirs, &tmp.path().join("early")).unwrap_err();
    match e {
        SweepError::Unfinished(u) => {
            assert_eq!(u.shards.len(), 1);
            assert_eq!(u.shards[0].shard, Shard::new(3, 3).unwrap());
        }
        other => panic!("{other}"),
    }
    let config = RunConfig {
        shard: Shard::new(3, n).unwrap(),
        ..threads(2)
    };
    assert!(
        sweep::run(&def, &dirs[2], &config, &mut |_| {})
            .unwrap()
            .complete()
    );
    let (_, merged) = sweep::merge(&dirs, &tmp.path().join("merged")).unwrap();
    assert_eq!(results_csv(&def, &merged.rows).unwrap(), reference);
}

#[test]
fn refinement_keys_are_checked_with_their_origin() {
    let err = |text: &str, overrides: &[Override]| {
        SweepDefinition::parse(text, "r.toml", overrides)
            .unwrap_err()
            .to_string()
    };
    let e = err(
        &REFINED.replace("metric = \"max_tilt\"", "metric = \"flips\""),
        &[],
    );
    assert!(e.contains("refine.metric") && e.contains("r.toml:"), "{e}");
    let e = err(
        &REFINED.replace("metric = \"max_tilt\"", "metric = \"max_energy_rel_err\""),
        &[],
    );
    assert!(e.contains("not recorded by this sweep"), "{e}");
    let e = err(&REFINED.replace("threshold = 0.1", "threshold = -1"), &[]);
    assert!(
        e.contains("refine.threshold") && e.contains("positive"),
        "{e}"
    );
    let e = err(&REFINED.replace("threshold = 0.1", ""), &[]);
    assert!(
        e.contains("refine.threshold") && e.contains("missing"),
        "{e}"
    );
    let e = err(
        REFINED,
        &[set("refine.levels", OverrideValue::Number(40.0))],
    );
    assert!(
        e.contains("at most 16 levels") && e.contains("--set"),
        "{e}"
    );
    let e = err(REFINED, &[set("refine.levels", OverrideValue::Number(1.5))]);
    assert!(e.contains("refine.levels"), "{e}");
    let random = REFINED.replace("count = 17", "").replace("count = 15", "")
        + "\n[random]\nsamples = 10\nseed = 1\n";
    let e = err(&random, &[]);
    assert!(e.contains("random samples"), "{e}");
    let e = err(&REFINED.replace("levels = 2", "level = 2"), &[]);
    assert!(e.contains("level"), "{e}");
    // An override sets the table's keys, or adds the table.
    let def = SweepDefinition::parse(
        &REFINED.replace(
            "[refine]\nlevels = 2\nmetric = \"max_tilt\"\nthreshold = 0.1\n",
            "",
        ),
        "r.toml",
        &[
            set("refine.levels", OverrideValue::Number(3.0)),
            set("refine.metric", OverrideValue::Text("final_tilt".into())),
            set("refine.threshold", OverrideValue::Number(0.5)),
        ],
    )
    .unwrap();
    let r = def.refine.as_ref().unwrap();
    assert_eq!(
        (r.levels, r.metric.name(), r.threshold),
        (3, "final_tilt".into(), 0.5)
    );
    // The resolved definition names the refinement, and reads back to the same.
    let again = SweepDefinition::parse(&def.to_toml(), "again.toml", &[]).unwrap();
    assert_eq!(again.refine, def.refine);
    assert_eq!(
        again.columns()[..2],
        ["index".to_string(), "level".to_string()]
    );
}

#[test]
fn a_journal_row_with_a_wrong_level_is_refused() {
    let def = refined();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("r");
    run_whole(&def, &dir, &threads(2));
    let path = dir.join(sweep::JOURNAL);
    let text = std::fs::read_to_string(&path).unwrap();
    // The coarse point 0 is level 0; claim level 2.
    let line = text
        .lines()
        .find(|l| l.starts_with("0,0,"))
        .unwrap()
        .to_string();
    std::fs::write(
        &path,
        text.replace(&line, &line.replacen("0,0,", "0,2,", 1)),
    )
    .unwrap();
    let resumed = RunConfig {
        resume: true,
        ..threads(1)
    };
    let e = sweep::run(&def, &dir, &resumed, &mut |_| {}).unwrap_err();
    assert!(e.to_string().contains("the refinement gives 0"), "{e}");
}

/// A plan that carries the cancel flag stops the point under way at its next step; that cut
/// point is not journalled as a failure, and resuming computes it to the uninterrupted result.
#[test]
fn a_point_cut_by_a_cancel_is_not_journalled_and_the_resumed_sweep_is_whole() {
    use tumble_scenarios::scene::CancelFlag;
    let text = r#"
scene = "free-hoop"
[run]
integrator = "gauss8"
dt = 1e-3
t_end = 10.0
[[axes]]
parameter = "omega0"
values = [1.0, 2.0, 3.0, 4.0]
[metrics]
record = ["max_tilt"]
"#;
    let def = SweepDefinition::parse(text, "cut.toml", &[]).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let reference = run_whole(&def, &tmp.path().join("whole"), &threads(1));
    let flag: &'static AtomicBool = Box::leak(Box::new(AtomicBool::new(false)));
    let mut cancellable = def.clone();
    cancellable.plan.cancel = Some(CancelFlag(flag));
    let config = RunConfig {
        threads: 1,
        cancel: Some(flag),
        ..RunConfig::default()
    };
    let dir = tmp.path().join("cut");
    // Cancel as soon as the first point is in: the worker is then inside the second.
    let partial = sweep::run(&cancellable, &dir, &config, &mut |p| {
        if p.finished >= 1 {
            flag.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    assert!(!partial.complete());
    assert!(
        partial.rows.iter().all(|r| r.status == sweep::Status::Ok),
        "a cut point was kept: {:?}",
        partial.rows
    );
    let journal = std::fs::read_to_string(dir.join(sweep::JOURNAL)).unwrap();
    assert!(!journal.contains("failed"), "{journal}");
    flag.store(false, Ordering::Relaxed);
    let resumed = RunConfig {
        resume: true,
        ..threads(1)
    };
    let report = sweep::run(&def, &dir, &resumed, &mut |_| {}).unwrap();
    assert_eq!(results_csv(&def, &report.rows).unwrap(), reference);
}
