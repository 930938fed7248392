//! Work–precision: observed orders on small ladders (the slopes of the curves `tumble
//! work-precision` draws), every scene with every applicable integrator, the references and
//! their cross-checks, the error norm, and the long-run energy history.

use tumble_integrators::registry::{self, Order};
use tumble_scenarios::scenes::{self, find};
use tumble_scenarios::{Recorder, StepControl};
use tumble_studies::work_precision::{
    self, Config, EnergyHistory, FinalState, fitted_slope, long_run_methods,
};

/// A ladder over `t_end` limited by steps, not by time, so that it does not depend on the
/// machine's speed.
fn config(t_end: f64, max_steps: u64) -> Config {
    Config {
        t_end,
        max_run_seconds: f64::INFINITY,
        max_reference_seconds: f64::INFINITY,
        max_steps,
        error_floor: 1e-13,
        max_error: 1e-1,
    }
}

/// The observed order of each (scene, integrator) on a ladder over `t_end` = 2 s: minus the
/// slope of `log error` against `log steps` over the rungs with errors in `[1e-12, 1e-4]`,
/// within 0.3 of the registry's order (docs/design.md §4). References: the exact flow (free body),
/// Gauss–Legendre s = 6 at a 16 times smaller step than the scene's default (the others).
#[test]
fn work_precision_slopes_match_the_methods_orders() {
    let cases: &[(&str, &[&str])] = &[
        (
            "free-body",
            &[
                "lgvi", "dmv", "split2", "split4", "split6", "rkmk4", "cg3", "rk4", "gauss2",
                "gauss4", "gauss6", "gauss8",
            ],
        ),
        ("free-hoop", &["lgvi", "rk4", "gauss4", "gauss6", "gauss8"]),
        (
            "heavy-top",
            &["split-exact2", "split4", "split6", "rkmk4", "cg3", "gauss4"],
        ),
        ("driven-hoop", &["rk4", "gauss4", "gauss6", "gauss8"]),
    ];
    let mut report = Vec::new();
    let mut bad = Vec::new();
    for (name, integrators) in cases {
        let scene = find(name).unwrap();
        let params = scene.info().default_params();
        let reference = work_precision::reference(scene, &params, 2.0).unwrap();
        for integrator in *integrators {
            let Order::Finite(p) = registry::find(integrator).unwrap().order else {
                panic!("{integrator} has no finite order");
            };
            let ladder = work_precision::ladder(
                scene,
                &params,
                integrator,
                &reference.state,
                &config(2.0, 20_000),
                &mut |_| {},
            )
            .unwrap();
            let slope = fitted_slope(&ladder.rungs, |r| r.steps as f64, 1e-12, 1e-4);
            report.push(format!("{name}/{integrator}: {slope:?} ({})", ladder.stop));
            match slope {
                Some(s) if (-s - f64::from(p)).abs() <= 0.3 => {}
                _ => bad.push(format!("{name}/{integrator}: order {p}, slope {slope:?}")),
            }
        }
    }
    assert!(bad.is_empty(), "{bad:?}\nall: {report:#?}");
}

/// Timing the rungs again in turns ([`work_precision::retime`]) changes their times only: the
/// runs (steps, evaluations, errors) stay, every rung gets a positive time from its rounds, and
/// the repeats count the new runs.
#[test]
fn retimed_rungs_keep_their_runs_and_count_the_interleaved_repeats() {
    let scene = find("heavy-top").unwrap();
    let params = scene.info().default_params();
    let reference = work_precision::reference(scene, &params, 1.0).unwrap();
    let cfg = config(1.0, 2_000);
    let mut ladders: Vec<_> = ["rk4", "dop853"]
        .iter()
        .map(|m| {
            work_precision::ladder(scene, &params, m, &reference.state, &cfg, &mut |_| {}).unwrap()
        })
        .collect();
    let before = ladders.clone();
    work_precision::retime(scene, &params, &mut ladders, &cfg, 3).unwrap();
    for (old, new) in before.iter().zip(&ladders) {
        assert_eq!(old.rungs.len(), new.rungs.len());
        assert!(!new.rungs.is_empty(), "{}: no rungs", new.integrator);
        for (a, b) in old.rungs.iter().zip(&new.rungs) {
            assert_eq!(
                (a.control(), a.dt, a.tol, a.steps, a.evaluations),
                (b.control(), b.dt, b.tol, b.steps, b.evaluations)
            );
            assert_eq!(a.error.to_bits(), b.error.to_bits());
            assert!(b.wall_time_s.is_finite() && b.wall_time_s > 0.0, "{b:?}");
            assert!(b.repeats >= a.repeats + 3, "{a:?} -> {b:?}");
        }
    }
}

/// `tumble work-precision` runs every built-in scene with every integrator it takes: each
/// ladder has rungs with finite errors and gets at least ten times more accurate than its
/// first rung (or starts at round-off: `coriolis-drop` before landing is nearly polynomial).
#[test]
fn every_scene_runs_with_every_applicable_integrator() {
    for scene in scenes::builtin() {
        let info = scene.info();
        let params = info.default_params();
        let reference = work_precision::reference(*scene, &params, 1.0).unwrap();
        for integrator in info.integrators() {
            let ladder = work_precision::ladder(
                *scene,
                &params,
                integrator,
                &reference.state,
                &config(1.0, 4_000),
                &mut |_| {},
            )
            .unwrap();
            let name = format!("{}/{integrator}", info.name);
            assert!(!ladder.rungs.is_empty(), "{name}: no rung ({ladder:?})");
            assert!(
                ladder.rungs.iter().all(|r| r.error.is_finite()
                    && r.wall_time_s > 0.0
                    && r.evaluations > 0
                    && r.max_energy_rel_err.is_finite()),
                "{name}: {ladder:?}"
            );
            let first = ladder.rungs[0].error;
            let best = ladder
                .rungs
                .iter()
                .map(|r| r.error)
                .fold(f64::INFINITY, f64::min);
            assert!(
                best <= 1e-12 || best <= first / 10.0,
                "{name}: from {first:e} only down to {best:e} ({})",
                ladder.stop
            );
        }
    }
}

/// The references agree with their independent cross-checks: the double-double Taylor method
/// with the exact flow (free body) and with Gauss–Legendre s = 6 (heavy top) to round-off, and
/// with itself at a looser tolerance to the last bit; Gauss–Legendre s = 6 with DOP853 and
/// with itself at half the step (free hoop).
#[test]
fn references_agree_with_their_cross_checks() {
    let body = find("free-body").unwrap();
    let r = work_precision::reference(body, &body.info().default_params(), 5.0).unwrap();
    assert!(r.method.starts_with("taylor-dd"), "{r:?}");
    assert!(r.check.starts_with("exact"), "{r:?}");
    assert!(r.agreement <= 1e-15, "{r:?}");
    assert!(r.self_agreement <= 2.0 * f64::EPSILON, "{r:?}");
    let top = find("heavy-top").unwrap();
    let r = work_precision::reference(top, &top.info().default_params(), 2.0).unwrap();
    assert!(r.method.starts_with("taylor-dd"), "{r:?}");
    assert!(r.check.starts_with("gauss12"), "{r:?}");
    assert!(r.agreement <= 1e-13, "{r:?}");
    assert!(r.self_agreement <= 2.0 * f64::EPSILON, "{r:?}");
    let hoop = find("free-hoop").unwrap();
    let r = work_precision::reference(hoop, &hoop.info().default_params(), 2.0).unwrap();
    assert!(r.method.starts_with("gauss12"), "{r:?}");
    assert!(r.agreement <= 1e-11, "{r:?}");
    assert!(r.self_agreement <= 1e-13, "{r:?}");
}

/// The error norm is `max |Δᵢ| / (1 + |refᵢ|)`, blind to the sign of the quaternion, and
/// infinite for states at different times.
#[test]
fn state_error_is_the_mixed_norm_and_ignores_the_quaternion_sign() {
    let info = find("free-body").unwrap().info();
    let q = [0.5, -0.5, 0.5, 0.5];
    let reference = FinalState {
        t: 1.0,
        values: [q.as_slice(), &[1.0, -3.0, 0.5]].concat(),
    };
    let flipped = FinalState {
        t: 1.0,
        values: [q.map(|x| -x).as_slice(), &[1.0, -3.0 + 4e-9, 0.5]].concat(),
    };
    let e = work_precision::state_error(info, &flipped, &reference);
    // 4e-9 added to 3 is rounded to a multiple of ulp(3) = 4.4e-16.
    assert!((e - 1e-9).abs() <= 1e-16, "{e:e}");
    let later = FinalState {
        t: 1.5,
        ..reference.clone()
    };
    assert!(work_precision::state_error(info, &later, &reference).is_infinite());
    // A scene without a quaternion: the sign matters.
    let hoop = find("driven-hoop").unwrap().info();
    let a = FinalState {
        t: 1.0,
        values: vec![0.5, 1.0],
    };
    let b = FinalState {
        t: 1.0,
        values: vec![-0.5, -1.0],
    };
    // |0.5 + 0.5| / 1.5 and |1 + 1| / 2: the second.
    assert!((work_precision::state_error(hoop, &a, &b) - 1.0).abs() < 1e-15);
}

/// Energy history: the maximum per logarithmic bin, and the growth exponent of a linear
/// drift (1), a √t growth (1/2) and a bounded error (0).
#[test]
fn energy_history_bins_by_log_time_and_measures_growth() {
    for (law, exponent) in [(1.0, 1.0), (0.5, 0.5), (0.0, 0.0)] {
        let mut h = EnergyHistory::new(0.01, 1e4, 120, 1);
        for k in 0..=1_000_000u32 {
            let t = f64::from(k) * 0.01;
            h.row(&[t, 1e-12 * t.max(0.01).powf(law)]);
        }
        let a = h.growth_exponent(3.0).unwrap();
        assert!((a - exponent).abs() < 0.01, "law {law}: {a}");
        // Every bin wider than the step (0.01 s) holds steps, and its maximum is its right
        // end's value.
        let pts = h.points();
        let wide = h.edges.windows(2).filter(|w| w[1] - w[0] >= 0.01).count();
        assert!(wide > 100 && pts.len() >= wide, "{} of {wide}", pts.len());
        let (t, e) = pts[60];
        assert!((e / (1e-12 * t.powf(law)) - 1.0).abs() < 1e-2, "{t} {e:e}");
    }
}

/// The long-run methods of a scene are its fixed-step symplectic, variational and Lie-group
/// ones.
#[test]
fn long_runs_compare_the_geometric_methods() {
    let body = find("free-body").unwrap().info();
    let m = long_run_methods(body);
    for name in ["lgvi", "split2", "split8", "dmv", "rkmk4", "gauss4"] {
        assert!(m.contains(&name), "{name} missing from {m:?}");
    }
    for name in ["rk4", "dp5", "dop853", "exact"] {
        assert!(!m.contains(&name), "{name} in {m:?}");
    }
    let runs = work_precision::long_runs(
        find("free-body").unwrap(),
        &body.default_params(),
        &[
            ("split2".into(), StepControl::Fixed(0.01)),
            ("dop853".into(), StepControl::Tolerance(1e-6)),
        ],
        200.0,
        0.01,
        40,
        None,
    );
    let split = &runs[0];
    let summary = split.result.as_ref().unwrap();
    assert_eq!(summary.steps, 20_000);
    // Splitting into exact rotations: bounded energy error, no drift.
    let a = split.history.growth_exponent(2.0).unwrap();
    assert!(a.abs() < 0.2, "split2 exponent {a}");
    assert!(runs[1].result.is_ok());
}

/// The error norm compares each quaternion up to its own sign: a state with two orientations
/// (`upper_qw …`, `lower_qw …`, as a model with several shows them) whose lower quaternion
/// ends negated is the same state (error 0), while negating only part of a quaternion, or a
/// quaternion whose names do not share a prefix, is an error of `2|q|/(1 + |q|)`.
#[test]
fn each_prefixed_quaternion_is_compared_up_to_its_own_sign() {
    let base = find("free-body").unwrap().info();
    let info = tumble_scenarios::SceneInfo {
        coordinates: &[
            "upper_qw", "upper_qx", "upper_qy", "upper_qz", "lower_qw", "lower_qx", "lower_qy",
            "lower_qz", "theta",
        ],
        ..*base
    };
    let q = [0.5, -0.5, 0.5, 0.5];
    let reference = FinalState {
        t: 1.0,
        values: [0.6, 0.0, 0.8, 0.0]
            .into_iter()
            .chain(q)
            .chain([0.3])
            .collect(),
    };
    let mut y = reference.clone();
    for v in &mut y.values[4..8] {
        *v = -*v;
    }
    assert_eq!(work_precision::state_error(&info, &y, &reference), 0.0);
    // Both negated, each alone: still the same rotations.
    for v in &mut y.values[0..4] {
        *v = -*v;
    }
    assert_eq!(work_precision::state_error(&info, &y, &reference), 0.0);
    // Part of a quaternion negated is a different rotation.
    let mut part = reference.clone();
    part.values[5] = -part.values[5];
    let e = work_precision::state_error(&info, &part, &reference);
    assert!((e - 1.0 / 1.5).abs() < 1e-15, "{e}");
    // Names that do not share a prefix are not a quaternion: negated, they count.
    let mixed = tumble_scenarios::SceneInfo {
        coordinates: &[
            "upper_qw", "upper_qx", "upper_qy", "upper_qz", "lower_qw", "lower_qx", "other_qy",
            "lower_qz", "theta",
        ],
        ..*base
    };
    let e = work_precision::state_error(&mixed, &y, &reference);
    assert!((e - 1.0 / 1.5).abs() < 1e-15, "{e}");
}
