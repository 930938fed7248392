//! The lanes against the scalar Taylor method, their independence of the batch, and the
//! metrics on the polynomial against dense rows.

use super::*;
use crate::scene::{Rows, RunOptions};
use crate::scenes::free_hoop::FREE_HOOP;

/// The map's points: spin `omega0` about the vertical, the bead released at rest at
/// `alpha0` (the built-in map's hoop: 1 kg, bead 0.1 kg, standing).
fn point(omega0: f64, alpha0: f64) -> Params {
    let mut p = FREE_HOOP.default_params();
    for (name, value) in [
        ("m", 0.1),
        ("omega0", omega0),
        ("alpha0", alpha0),
        ("alpha_dot0", 0.0),
        ("theta0", std::f64::consts::FRAC_PI_2),
    ] {
        p.set(name, value).unwrap();
    }
    p
}

/// Points across the map, its hardest one (ω₀ = 7.25, α₀ = 2.38) among them, and points
/// whose tilt exceeds 0.5 rad.
fn points() -> Vec<Params> {
    [
        (0.5, 0.04),
        (3.2, 1.5),
        (4.35, 1.88),
        (5.9, 2.2),
        (7.25, 2.38),
        (8.0, 3.12),
        (1.1, 1.2),
        (6.55, 1.34),
        (2.0, 2.9),
        (4.45, 3.04),
        (3.13, 0.7),
        (1.0, 1.64),
        (2.5, 2.4),
        (4.7, 2.8),
    ]
    .into_iter()
    .map(|(w, a)| point(w, a))
    .collect()
}

fn plan(tol: f64, at: Option<Vec<f64>>) -> RunPlan {
    RunOptions {
        integrator: Some("taylor".into()),
        step: Some(StepControl::Tolerance(tol)),
        t_end: Some(10.0),
        at,
        ..Default::default()
    }
    .resolve(&FREE_HOOP)
    .unwrap()
}

fn bits(r: &TiltRun) -> [u64; 5] {
    [
        r.max_tilt.to_bits(),
        r.final_tilt.to_bits(),
        r.first_exceeds.map_or(u64::MAX, f64::to_bits),
        r.max_energy_rel_err.to_bits(),
        r.steps,
    ]
}

/// Each lane is the scalar Taylor method of the reduction, bit for bit: the same number
/// of steps, the same final tilt and the same largest energy error as
/// [`super::super::simulate`] gives for the point alone.
#[test]
fn lanes_take_the_scalar_methods_steps_bit_for_bit() {
    let plan = plan(1e-12, None);
    assert!(runs(&plan));
    let params = points();
    let runs = tilt_runs(&params, &plan, Some(0.5));
    for (p, run) in params.iter().zip(&runs) {
        let run = run.as_ref().unwrap();
        let mut rows = Rows::default();
        let summary = super::super::simulate(p, &plan, &mut rows).unwrap();
        let last = rows.0.last().unwrap();
        assert_eq!(last[0], 10.0);
        assert_eq!(summary.steps, run.steps);
        assert_eq!(last[9].to_bits(), run.final_tilt.to_bits(), "{p:?}");
        assert_eq!(
            summary.max_energy_rel_err.to_bits(),
            run.max_energy_rel_err.to_bits()
        );
    }
}

/// A run's numbers do not depend on the runs beside it: each point alone, the points in
/// one call (two batches, the second part empty) and in reverse order give the same bits.
#[test]
fn a_runs_numbers_do_not_depend_on_its_batch() {
    let plan = plan(1e-12, None);
    let params = points();
    let together: Vec<[u64; 5]> = tilt_runs(&params, &plan, Some(0.5))
        .iter()
        .map(|r| bits(r.as_ref().unwrap()))
        .collect();
    let mut reversed: Vec<[u64; 5]> = tilt_runs(
        &params.iter().rev().cloned().collect::<Vec<_>>(),
        &plan,
        Some(0.5),
    )
    .iter()
    .map(|r| bits(r.as_ref().unwrap()))
    .collect();
    reversed.reverse();
    assert_eq!(together, reversed);
    for (p, expected) in params.iter().zip(&together) {
        let alone = tilt_runs(std::slice::from_ref(p), &plan, Some(0.5));
        assert_eq!(&bits(alone[0].as_ref().unwrap()), expected);
    }
}

/// The largest tilt found on the polynomials is at least the largest of 20,001 rows of the
/// same run (its dense output), and above it by no more than the tilt can rise between
/// two rows (`½ |tilt''| Δt²` with `|tilt''| < 40 rad/s²` here, Δt = 5e-4 s); the first
/// crossing of 0.5 rad lies between the last row at or below it and the first above.
#[test]
fn maxima_and_crossings_on_the_polynomial_agree_with_dense_rows() {
    let times: Vec<f64> = (0..=20_000).map(|i| f64::from(i) * 5e-4).collect();
    let dense = plan(1e-12, Some(times));
    let params = points();
    let runs = tilt_runs(&params, &plan(1e-12, None), Some(0.5));
    let mut crossed = 0;
    for (p, run) in params.iter().zip(&runs) {
        let run = run.as_ref().unwrap();
        let mut rows = Rows::default();
        super::super::simulate(p, &dense, &mut rows).unwrap();
        let sampled = rows
            .0
            .iter()
            .map(|r| r[9])
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            run.max_tilt >= sampled - 1e-15,
            "{p:?}: {} < {sampled}",
            run.max_tilt
        );
        assert!(run.max_tilt - sampled <= 0.5 * 40.0 * 5e-4 * 5e-4, "{p:?}");
        match rows.0.iter().position(|r| r[9] > 0.5) {
            Some(0) => assert_eq!(run.first_exceeds, Some(0.0)),
            Some(i) => {
                let t = run.first_exceeds.unwrap();
                assert!(rows.0[i - 1][0] <= t && t <= rows.0[i][0], "{p:?}: {t}");
                crossed += 1;
            }
            // A crossing between two rows that falls back below is allowed.
            None => assert!(run.first_exceeds.is_none() || run.max_tilt > 0.5),
        }
    }
    assert!(crossed >= 4, "only {crossed} points cross 0.5 rad");
}

/// A lane that fails does so alone, with its own typed error: a step budget too small for
/// the fastest spin stops that point and not the slow one beside it, as alone.
#[test]
fn a_failing_lane_fails_alone_with_its_error() {
    let mut plan = plan(1e-12, None);
    let slow = point(0.5, 0.04);
    let fast = point(8.0, 3.12);
    let alone = tilt_runs(std::slice::from_ref(&slow), &plan, None);
    let steps = alone[0].as_ref().unwrap().steps;
    plan.max_steps = steps;
    let runs = tilt_runs(&[fast, slow], &plan, None);
    assert!(
        matches!(
            runs[0],
            Err(SceneError::Integration(IntegrationError::TooManySteps { max_steps, .. }))
                if max_steps == steps
        ),
        "{:?}",
        runs[0]
    );
    assert_eq!(
        bits(runs[1].as_ref().unwrap()),
        bits(alone[0].as_ref().unwrap())
    );
}

#[test]
fn only_the_adaptive_taylor_method_runs_in_lanes() {
    assert!(runs(&plan(1e-10, None)));
    assert!(!runs(&plan(1e-10, Some(vec![1.0]))));
    let vern9 = RunOptions {
        integrator: Some("vern9".into()),
        ..Default::default()
    }
    .resolve(&FREE_HOOP)
    .unwrap();
    assert!(!runs(&vern9));
}
