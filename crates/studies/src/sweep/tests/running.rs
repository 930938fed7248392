//! Running a sweep: determinism, resumption, shards, failures.

use super::*;

fn temp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

#[test]
fn results_are_the_same_bytes_for_one_and_two_threads() {
    let def = small();
    let dir = temp();
    let one = results(&def, &dir.path().join("one"), &threads(1));
    let two = results(&def, &dir.path().join("two"), &threads(2));
    assert_eq!(String::from_utf8_lossy(&one), String::from_utf8_lossy(&two));
    let text = String::from_utf8(one).unwrap();
    assert!(
        text.starts_with(
            "index,omega0,alpha0,max_tilt,final_tilt,time_tilt_exceeds,max_energy_rel_err,\
             status,reason\n0,1.0,0.5,"
        ),
        "{text}"
    );
    assert_eq!(text.lines().count(), 7);
}

#[test]
fn a_cancelled_sweep_resumes_to_the_same_results() {
    // 200 points: the one worker cannot finish them all before the calling thread, which
    // receives the rows, has seen two and cancelled (with 6 points it sometimes did, on a
    // loaded machine, and the run was complete).
    let def = parse(&SMALL.replace("count = 3", "count = 100")).unwrap();
    let dir = temp();
    let reference = results(&def, &dir.path().join("ref"), &threads(2));
    let cut = dir.path().join("cut");
    let cancel = AtomicBool::new(false);
    let config = RunConfig {
        threads: 1,
        cancel: Some(&cancel),
        ..RunConfig::default()
    };
    let mut seen = 0;
    let partial = run(&def, &cut, &config, &mut |p| {
        seen = p.finished;
        if p.finished >= 2 {
            cancel.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    assert!(!partial.complete(), "{} rows", partial.rows.len());
    assert!(partial.rows.len() >= 2);
    // Without --resume the folder is refused; with it, only the rest is computed.
    let e = run(&def, &cut, &threads(2), &mut |_| {}).unwrap_err();
    assert!(matches!(e, SweepError::Exists { .. }), "{e}");
    let resumed = RunConfig {
        resume: true,
        ..threads(2)
    };
    let report = run(&def, &cut, &resumed, &mut |_| {}).unwrap();
    assert_eq!(report.resumed, partial.rows.len() as u64);
    assert_eq!(report.computed, def.points() - report.resumed);
    assert_eq!(results_csv(&def, &report.rows).unwrap(), reference);
    // Resuming a complete sweep computes nothing and gives the same file.
    let again = run(&def, &cut, &resumed, &mut |_| {}).unwrap();
    assert_eq!(again.computed, 0);
    assert_eq!(results_csv(&def, &again.rows).unwrap(), reference);
}

#[test]
fn a_torn_last_journal_line_is_dropped_and_redone() {
    let def = small();
    let dir = temp();
    let reference = results(&def, &dir.path().join("ref"), &threads(1));
    let folder = dir.path().join("torn");
    results(&def, &folder, &threads(1));
    // Keep the header lines and two rows, and half of the third row: a kill mid-write.
    let journal = folder.join(JOURNAL);
    let text = std::fs::read_to_string(&journal).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let torn = format!(
        "{}\n{}",
        lines[..4].join("\n"),
        &lines[4][..lines[4].len() / 2]
    );
    std::fs::write(&journal, torn).unwrap();
    let resumed = RunConfig {
        resume: true,
        ..threads(2)
    };
    let report = run(&def, &folder, &resumed, &mut |_| {}).unwrap();
    assert_eq!((report.resumed, report.computed), (2, 4));
    assert_eq!(results_csv(&def, &report.rows).unwrap(), reference);
    // The journal is whole again: complete lines, each point once.
    let text = std::fs::read_to_string(&journal).unwrap();
    assert!(text.ends_with('\n'));
    assert_eq!(text.lines().count(), 2 + 6);
}

#[test]
fn a_damaged_journal_or_another_sweep_is_refused() {
    let def = small();
    let dir = temp();
    let folder = dir.path().join("s");
    results(&def, &folder, &threads(1));
    let resume = RunConfig {
        resume: true,
        ..threads(1)
    };
    // Another definition in the same folder.
    let other = SweepDefinition::parse(SMALL, "test.toml", &[set("M", 2.0)]).unwrap();
    let e = run(&other, &folder, &resume, &mut |_| {}).unwrap_err();
    assert!(matches!(e, SweepError::DifferentSweep { .. }), "{e}");
    assert!(e.to_string().contains("M = 2.0"), "{e}");
    // Another shard.
    let e = run(
        &def,
        &folder,
        &RunConfig {
            shard: Shard::new(1, 2).unwrap(),
            ..resume
        },
        &mut |_| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("holds shard 1/1"), "{e}");
    // A damaged row in the middle (not a torn end).
    let journal = folder.join(JOURNAL);
    let text = std::fs::read_to_string(&journal).unwrap();
    std::fs::write(&journal, text.replacen(",ok,", ",fine,", 1)).unwrap();
    let e = run(&def, &folder, &resume, &mut |_| {}).unwrap_err();
    assert!(matches!(e, SweepError::Journal { line: 3, .. }), "{e}");
    assert!(e.to_string().contains("status `fine`"), "{e}");
}

#[test]
fn three_shards_merge_into_the_unsharded_results() {
    let def = small();
    let dir = temp();
    let reference = results(&def, &dir.path().join("ref"), &threads(2));
    let shards: Vec<PathBuf> = (1..=3)
        .map(|k| dir.path().join(format!("shard{k}")))
        .collect();
    for (k, folder) in shards.iter().enumerate() {
        let config = RunConfig {
            shard: Shard::new(k as u64 + 1, 3).unwrap(),
            ..threads(1)
        };
        let report = run(&def, folder, &config, &mut |_| {}).unwrap();
        assert_eq!(report.rows.len(), 2);
    }
    let merged = dir.path().join("merged");
    let (merged_def, report) = merge(&shards, &merged).unwrap();
    assert_eq!(merged_def.to_toml(), def.to_toml());
    assert_eq!(results_csv(&merged_def, &report.rows).unwrap(), reference);
    // The merged folder is a complete unsharded sweep: resuming it computes nothing.
    let again = run(
        &def,
        &merged,
        &RunConfig {
            resume: true,
            ..threads(1)
        },
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(again.computed, 0);
    // The merged compute record holds every shard's run, and the resume adds its own.
    assert_eq!(report.compute.runs.len(), 3);
    assert_eq!(report.compute.totals().computed, 6);
    assert_eq!(report.computed, 6);
    assert_eq!(report.threads, 1);
    assert_eq!(again.compute.runs.len(), 4);
    assert_eq!(again.compute.totals().computed, 6);
    // Missing, repeated and incomplete shards are refused.
    let e = merge(&shards[..2], &dir.path().join("m2")).unwrap_err();
    assert!(
        e.to_string().contains("1 of 3 shards not finished: 3/3")
            && e.to_string()
                .contains("shard 3/3: no folder given holds it"),
        "{e}"
    );
    let e = merge(
        &[shards[0].clone(), shards[0].clone(), shards[2].clone()],
        &dir.path().join("m3"),
    )
    .unwrap_err();
    assert!(e.to_string().contains("both shard 1/3"), "{e}");
    let journal = shards[1].join(JOURNAL);
    let text = std::fs::read_to_string(&journal).unwrap();
    let cut: Vec<&str> = text.lines().collect();
    std::fs::write(&journal, cut[..cut.len() - 1].join("\n") + "\n").unwrap();
    let e = merge(&shards, &dir.path().join("m4")).unwrap_err();
    assert!(e.to_string().contains("shard 2/3: 1 of 2 points"), "{e}");
    assert!(e.to_string().contains("--shard 2/3 --resume -o"), "{e}");
    // Every unfinished shard is listed at once, a folder that never started among them.
    let never = dir.path().join("never");
    let e = merge(
        &[shards[0].clone(), shards[1].clone(), never.clone()],
        &dir.path().join("m5"),
    )
    .unwrap_err();
    let SweepError::Unfinished(u) = &e else {
        panic!("{e}")
    };
    let listed: Vec<String> = u.shards.iter().map(|s| s.shard.to_string()).collect();
    assert_eq!(listed, ["2/3", "3/3"]);
    assert_eq!(u.empty, [never]);
    assert!(!dir.path().join("m5").join(JOURNAL).exists());
}

#[test]
fn failing_points_are_recorded_and_the_sweep_goes_on() {
    // At 10^4 rad/s a step of 0.01 s is absurd: gauss8's stage iteration diverges.
    let def =
        parse(&SMALL.replace("range = [1.0, 5.0]\ncount = 3", "values = [1.0, 1e4, 3.0]")).unwrap();
    let dir = temp();
    let report = run(&def, dir.path(), &threads(2), &mut |_| {}).unwrap();
    assert!(report.complete());
    let failed: Vec<u64> = report.failures().map(|r| r.index).collect();
    assert_eq!(failed, vec![2, 3]);
    for r in report.failures() {
        assert_eq!(r.status, Status::Failed);
        assert!(r.reason.contains("did not converge"), "{}", r.reason);
        assert!(r.metrics.iter().all(Option::is_none));
    }
    let csv = String::from_utf8(results_csv(&def, &report.rows).unwrap()).unwrap();
    let line = csv.lines().nth(3).unwrap();
    assert!(line.starts_with("2,10000.0,0.5,,,,,failed,"), "{line}");
}

#[test]
fn panics_are_caught_and_recorded() {
    let row = engine::guarded(7, vec![1.0], 2, || panic!("boom at {}", 7));
    assert_eq!(row.status, Status::Panicked);
    assert_eq!(row.reason, "panic: boom at 7");
    assert_eq!(row.metrics, vec![None, None]);
    let row = engine::guarded(1, vec![1.0], 1, || std::panic::panic_any(42));
    assert_eq!(row.reason, "panic: a panic without a message");
    let row = engine::guarded(1, vec![1.0], 1, || Err("no".to_string()));
    assert_eq!((row.status, row.reason.as_str()), (Status::Failed, "no"));
}

#[test]
fn shards_partition_the_points() {
    let n = 3;
    let shards: Vec<Shard> = (1..=n).map(|k| Shard::new(k, n).unwrap()).collect();
    for points in [0u64, 1, 2, 3, 10, 11] {
        let mut total = 0;
        for i in 0..points {
            assert_eq!(shards.iter().filter(|s| s.contains(i)).count(), 1);
        }
        for s in &shards {
            let count = (0..points).filter(|&i| s.contains(i)).count() as u64;
            assert_eq!(s.size(points), count, "{s} of {points}");
            total += count;
        }
        assert_eq!(total, points);
    }
    assert_eq!(Shard::parse("2/3").unwrap(), Shard { index: 2, count: 3 });
    for bad in ["0/3", "4/3", "1/0", "x/3", "3", "1/2/3"] {
        assert!(Shard::parse(bad).is_err(), "{bad}");
    }
}
