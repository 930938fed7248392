//! The hard-case battery: every built-in case parses; on each, a correct method meets the
//! case's property and a deliberately unsuitable one is recorded as a failure or a violation
//! (with its reason), never a crash or a silent number.

use tumble_studies::hard_cases::Case;
use tumble_studies::hard_cases::atlas::{self, Method, Status};

fn case(name: &str) -> Case {
    Case::built_in()
        .unwrap()
        .into_iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no built-in case {name}"))
}

/// Runs `good` and `bad` (method specs with their settings) on the case `name`.
fn good_and_bad(name: &str, good: &str, bad: &str) {
    let case = case(name);
    let refs = atlas::references(&case, 120.0).unwrap();
    let good = atlas::run_entry(&case, &refs, &Method::parse(good).unwrap(), 120.0);
    assert_eq!(good.status, Status::Ok, "{name}: {good:?}");
    assert!(good.reason.is_empty());
    assert!(good.energy.is_some_and(f64::is_finite), "{good:?}");
    let bad = atlas::run_entry(&case, &refs, &Method::parse(bad).unwrap(), 120.0);
    assert!(
        matches!(bad.status, Status::Failed | Status::Violated),
        "{name}: {bad:?}"
    );
    assert!(!bad.reason.is_empty(), "{bad:?}");
    // A violated property is stated with the numbers that violate it.
    if bad.status == Status::Violated {
        assert!(bad.reason.contains(" > "), "{bad:?}");
    }
}

/// Case files take numbers or angle expressions, as scene files do: `pi/3` is π/3 exactly as
/// a float literal would give it.
#[test]
fn case_files_take_angle_expressions_like_scene_files() {
    let text = |tilt: &str| {
        format!(
            "name = \"angles\"\nscene = \"heavy-top\"\nwhy = \"w\"\ngood = \"g\"\n\
             [parameters]\ntilt0 = {tilt}\n[run]\nt_end = 1.0\n[easy]\ntilt0 = \"pi/6\"\n\
             [property]\nerror = 1e-6\n"
        )
    };
    let expr = Case::parse(&text("\"pi/3\""), "c.toml").unwrap();
    let plain = Case::parse(
        &text(&format!("{:?}", std::f64::consts::PI / 3.0)),
        "c.toml",
    )
    .unwrap();
    assert_eq!(
        expr.params.get("tilt0").unwrap(),
        std::f64::consts::PI / 3.0
    );
    assert_eq!(expr.params, plain.params);
    assert_eq!(expr.easy.get("tilt0").unwrap(), std::f64::consts::PI / 6.0);
    let bad = Case::parse(&text("\"pi/x\""), "c.toml")
        .unwrap_err()
        .to_string();
    assert!(
        bad.contains("parameters.tilt0") && bad.contains("pi/x"),
        "{bad}"
    );
}

#[test]
fn every_built_in_case_parses_and_states_why_it_is_hard() {
    let cases = Case::built_in().unwrap();
    assert_eq!(cases.len(), 12);
    let mut names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), 12);
    for c in &cases {
        assert!(c.why.len() > 80 && c.good.len() > 40, "{}", c.name);
        assert!(c.t_end > 0.0 && c.easy_t_end > 0.0);
    }
}

#[test]
fn t_handle_separatrix() {
    good_and_bad("t-handle-separatrix", "gauss8:dt=0.01", "rk4:dt=0.05");
}

#[test]
fn t_handle_near_separatrix() {
    good_and_bad("t-handle-near-separatrix", "gauss8:dt=0.02", "rk4:dt=0.05");
}

#[test]
fn flat_body() {
    good_and_bad("flat-body", "split4:dt=0.01", "gauss12:dt=3");
}

#[test]
fn nearly_symmetric_body() {
    good_and_bad("nearly-symmetric-body", "gauss8:dt=0.1", "rk4:dt=1");
}

#[test]
fn fast_top() {
    good_and_bad("fast-top", "dop853:tol=1e-10", "split4:dt=0.027");
}

#[test]
fn sleeping_top() {
    good_and_bad("sleeping-top", "gauss8:dt=0.005", "rk4:dt=0.1");
}

#[test]
fn hoop_through_flat() {
    good_and_bad("hoop-through-flat", "gauss8:dt=0.01", "rk4:dt=0.5");
}

#[test]
fn bead_at_the_top() {
    good_and_bad("bead-at-the-top", "dop853:tol=1e-10", "rk4:dt=0.3");
}

#[test]
fn light_bead() {
    good_and_bad("light-bead", "gauss8:dt=0.01", "rk4:dt=0.3");
}

#[test]
fn heavy_bead() {
    good_and_bad("heavy-bead", "gauss8:dt=0.01", "gauss12:dt=0.7");
}

#[test]
fn long_free_body() {
    good_and_bad("long-free-body", "exact:dt=1000", "rk4:dt=0.5");
}

#[test]
fn long_free_hoop() {
    good_and_bad("long-free-hoop", "gauss8:dt=0.05", "dop853:tol=1e-6");
}

#[test]
fn the_rule_sets_each_method_to_the_target_error_on_the_easy_twin() {
    // On the easy twin of the near-separatrix case, the chosen settings give errors within a
    // factor 3 of 1e-6 (the rule keeps the largest setting at most 3e-6).
    let case = case("t-handle-near-separatrix");
    let refs = atlas::references(&case, 120.0).unwrap();
    for name in ["rk4", "dop853", "gauss4", "lgvi", "split4"] {
        let method = Method::parse(name).unwrap();
        let (_, e) = atlas::calibrate(&case, method.info, &refs.easy, 120.0).unwrap();
        assert!((1e-7..=3e-6).contains(&e), "{name}: {e:e}");
    }
}

#[test]
fn bad_case_files_are_refused_with_the_file_and_key() {
    let good = include_str!("../../src/hard_cases/cases/light-bead.case.toml");
    let err = |text: &str| Case::parse(text, "mine.case.toml").unwrap_err().to_string();
    for (text, expect) in [
        (good.replace("m = 1e-6", "m = -1"), "parameters.m"),
        (
            good.replace("scene = \"free-hoop\"", "scene = \"hoop\""),
            "scene",
        ),
        (good.replace("t_end = 10.0", "t_end = -1.0"), "run.t_end"),
        (good.replace("error = 1e-5", "error = 0"), "property.error"),
        (
            good.replace(
                "energy = 1e-6",
                "energy = 1e-6\nconserved = [\"Qz\"]\ndrift = 1e-9",
            ),
            "Qz",
        ),
        (
            good.replace("name = \"light-bead\"", "name = \"light bead\""),
            "name",
        ),
        (good.replace("[easy]", "[easy]\nmass = 2"), "easy.mass"),
        (good.replace("[run]", "[run]\nsteps = 3"), "steps"),
    ] {
        let e = err(&text);
        assert!(
            e.contains("mine.case.toml") && e.contains(expect),
            "{expect}: {e}"
        );
    }
}

/// A quick case of one's own: the free hoop over 0.2 s.
pub(crate) const QUICK: &str = r#"
name = "quick-hoop"
scene = "free-hoop"
why = "w"
good = "g"

[run]
t_end = 0.2

[property]
energy = 1e-3
"#;

fn quick_atlas(dir: &std::path::Path, methods: &[Method], resume: bool) -> atlas::AtlasReport {
    let cases = [Case::parse(QUICK, "quick.case.toml").unwrap()];
    let config = atlas::AtlasConfig {
        threads: 2,
        run_seconds: 60.0,
        budget: 600.0,
        resume,
        cancel: None,
    };
    atlas::run(&cases, methods, dir, &config, &|_, _| {}).unwrap()
}

#[test]
fn an_atlas_journal_whose_last_line_was_torn_by_a_kill_resumes() {
    let tmp = tempfile::tempdir().unwrap();
    let methods = [
        Method::parse("rk4:dt=0.01").unwrap(),
        Method::parse("dop853:tol=1e-8").unwrap(),
    ];
    let whole = quick_atlas(tmp.path(), &methods, false);
    assert!(whole.complete());
    // A kill in the middle of writing the second entry: half of its line, no newline.
    let path = tmp.path().join(atlas::JOURNAL);
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "{text}");
    let torn = format!(
        "{}\n{}\n{}",
        lines[0],
        lines[1],
        &lines[2][..lines[2].len() / 2]
    );
    std::fs::write(&path, torn).unwrap();
    let resumed = quick_atlas(tmp.path(), &methods, true);
    assert!(resumed.complete());
    assert_eq!(resumed.resumed, 1);
    // The journal holds the header and each entry once, on lines of their own.
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().count(), 3, "{text}");
    assert!(text.ends_with('\n'));
    let strip = |e: &atlas::Entry| atlas::Entry {
        seconds: None,
        ..e.clone()
    };
    assert_eq!(
        resumed.entries.iter().map(strip).collect::<Vec<_>>(),
        whole.entries.iter().map(strip).collect::<Vec<_>>()
    );
}

#[test]
fn a_method_given_twice_is_run_journalled_and_counted_once() {
    let tmp = tempfile::tempdir().unwrap();
    let rk4 = Method::parse("rk4:dt=0.01").unwrap();
    let report = quick_atlas(tmp.path(), &[rk4.clone(), rk4], false);
    assert_eq!(report.total, 1);
    assert_eq!(report.entries.len(), 1);
    let text = std::fs::read_to_string(tmp.path().join(atlas::JOURNAL)).unwrap();
    assert_eq!(text.lines().count(), 2, "{text}");
}

#[test]
fn calibration_stops_at_a_run_that_reaches_the_time_limit_instead_of_shrinking_the_step() {
    // A smaller step (tighter tolerance) only takes longer: the rule gives up at the first run
    // cut by the limit, the starting setting, rather than trying ever smaller ones.
    let case = Case::parse(QUICK, "quick.case.toml").unwrap();
    let refs = atlas::references(&case, 60.0).unwrap();
    let default = case.scene.info().default_step.min(case.easy_t_end / 4.0);
    for (name, start) in [
        ("rk4", format!("dt = {default:.3e} s")),
        ("dop853", "tol = 1.0e-8".to_string()),
    ] {
        let method = Method::parse(name).unwrap();
        let e = atlas::calibrate(&case, method.info, &refs.easy, 1e-12).unwrap_err();
        assert!(e.contains("time limit"), "{name}: {e}");
        assert!(e.contains(&format!("at {start})")), "{name}: {e}");
    }
}

#[test]
fn an_atlas_out_of_budget_computes_no_reference_and_journals_nothing() {
    let cases = vec![case("light-bead")];
    let methods = vec![Method::parse("gauss8").unwrap()];
    let tmp = tempfile::tempdir().unwrap();
    let config = atlas::AtlasConfig {
        threads: 1,
        run_seconds: 10.0,
        budget: 1e-9,
        resume: false,
        cancel: None,
    };
    let report = atlas::run(&cases, &methods, tmp.path(), &config, &|_, _| {}).unwrap();
    assert_eq!((report.total, report.entries.len()), (1, 0));
    assert!(report.references.is_empty(), "{:?}", report.references);
    let journal = std::fs::read_to_string(tmp.path().join(atlas::JOURNAL)).unwrap_or_default();
    assert!(journal.lines().count() <= 1, "{journal}");
}

#[test]
fn settings_a_method_cannot_take_are_refused_when_parsed() {
    for (spec, words) in [
        ("dp5:dt=0.01", "is adaptive"),
        ("rk4:tol=1e-3", "fixed step"),
        ("dp5:tol=5", "strictly between 0 and 1"),
        ("dp5:tol=0", "finite and positive"),
        ("rk4:dt=-1", "finite and positive"),
        ("rk4:h=0.1", "neither dt nor tol"),
    ] {
        let e = Method::parse(spec).map(|m| m.spec()).unwrap_err();
        assert!(e.contains(words), "{spec}: {e}");
    }
    assert_eq!(
        Method::parse("dp5:tol=1e-6").unwrap().spec(),
        "dp5:tol=0.000001"
    );
    assert_eq!(Method::parse("rk4:dt=0.01").unwrap().spec(), "rk4:dt=0.01");
}
