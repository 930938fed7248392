//! `tumble sweep --refine`: a refined map's results hold each point's level and the uniform
//! grid's numbers at its points; shards merge into the unsharded refinement; the manifest and
//! summary state the refinement.

use tempfile::TempDir;

use crate::support::{record, stderr, succeeds, tumble_in};
use crate::sweep::write_sweep;

/// A free-hoop map over 2 s, 17 × 15 points, refined by `max_tilt` (2 levels; `--refine`
/// overrides them).
const MAP: &str = include_str!("../../crates/studies/tests/fixtures/refined-map.sweep.toml");

fn read(path: &std::path::Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn a_refined_map_states_its_levels_and_matches_the_uniform_grid_at_its_points() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "map.sweep.toml", MAP);
    let file = file.to_str().unwrap();
    succeeds(
        tmp.path(),
        &["sweep", file, "--refine", "0", "-o", "uniform"],
    );
    let out = succeeds(
        tmp.path(),
        &["sweep", file, "--refine", "2", "-o", "refined"],
    );
    let summary = stderr(&out);
    assert!(
        summary.contains("refined      2 levels where max_tilt changes by more than 0.1"),
        "{summary}"
    );
    let dir = tmp.path().join("refined");
    let results = read(&dir.join("results.csv"));
    assert!(results.starts_with("index,level,omega0,alpha0,max_tilt,final_tilt,status,reason\n"));
    let rows = results.lines().count() - 1;
    assert!(rows > 25 && rows < 255, "{rows} points");
    let m = record::<tumble_studies::sweep::record::SweepRecord>(&dir.join("manifest.json"));
    let r = &m["refinement"];
    assert_eq!(r["levels"], 2);
    assert_eq!(r["grid_points"], 255);
    let by_level: Vec<u64> = r["points_by_level"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(by_level[0], 25);
    assert_eq!(by_level.iter().sum::<u64>(), rows as u64);
    assert_eq!(m["points"], rows as u64);
    for name in [
        "tilt-map.png",
        "tilt-map.svg",
        "tilt-slices.png",
        "tilt-slices.svg",
    ] {
        assert!(dir.join(name).exists(), "{name}");
    }
    // The uniform grid's numbers at every refined point.
    let diff = succeeds(
        tmp.path(),
        &["sweep", "diff", "refined", "uniform", "--tolerance", "0"],
    );
    let table = String::from_utf8_lossy(&diff.stdout);
    assert!(table.contains(&format!("{rows} points")), "{table}");
}

#[test]
fn shards_of_a_refined_map_merge_into_the_unsharded_refinement() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "map.sweep.toml", MAP);
    let file = file.to_str().unwrap();
    succeeds(tmp.path(), &["sweep", file, "--refine", "2", "-o", "whole"]);
    for k in 1..=2 {
        let shard = format!("{k}/2");
        let part = format!("part{k}");
        succeeds(
            tmp.path(),
            &[
                "sweep", file, "--refine", "2", "--shard", &shard, "-o", &part,
            ],
        );
    }
    succeeds(
        tmp.path(),
        &["sweep", "merge", "part1", "part2", "-o", "merged"],
    );
    assert_eq!(
        read(&tmp.path().join("merged/results.csv")),
        read(&tmp.path().join("whole/results.csv"))
    );
}

#[test]
fn bad_refinements_are_refused_before_any_work() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "map.sweep.toml", MAP);
    let file = file.to_str().unwrap();
    for (args, expect) in [
        (vec!["--refine", "17"], "at most 16 levels"),
        (vec!["--refine", "-1"], "--refine"),
        (
            vec!["--refine", "2", "--set", "refine.metric=flips"],
            "refine.metric",
        ),
        (
            vec!["--refine", "2", "--set", "refine.threshold=0"],
            "positive",
        ),
        // A log axis needs a positive range.
        (
            vec![
                "--set",
                "axes.omega0.spacing=log",
                "--set",
                "axes.omega0.start=0",
            ],
            "omega0",
        ),
    ] {
        let mut all = vec!["sweep", file, "-o", "bad"];
        all.extend(&args);
        let out = tumble_in(tmp.path(), &all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(expect), "{args:?}: {}", stderr(&out));
        assert!(!tmp.path().join("bad").exists(), "{args:?}");
    }
}
