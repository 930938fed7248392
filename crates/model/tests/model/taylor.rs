//! The Taylor method on models: the series of the graph's nodes against closed forms, the
//! observed order at fixed order and step, the adaptive method's accuracy and conservation, and
//! agreement with an explicit pair.

use std::f64::consts::FRAC_PI_2;

use nalgebra::SVector;
use tumble_integrators::verification::fit_power_law;
use tumble_integrators::{Driver, NoObserver, Taylor};
use tumble_model::expr::tape::Tape;
use tumble_model::expr::taylor::{TaylorPlan, TaylorWork};
use tumble_model::expr::{Fun, Graph, Id};
use tumble_scenarios::{Scene, StepControl};

use crate::support::{column, run, shipped};

const ORDER: usize = 18;

/// Coefficients `0 ..= ORDER` of each output of `build(g, t)` along the series `t₀ + h`.
fn series(t0: f64, build: impl Fn(&mut Graph, Id) -> Vec<Id>) -> Vec<Vec<f64>> {
    let mut g = Graph::default();
    let t = g.input(0);
    let outputs = build(&mut g, t);
    let tape = Tape::new(&g, &outputs);
    let plan = TaylorPlan::new(&tape, 1);
    let mut work = TaylorWork::new(&tape, &plan, &[], ORDER);
    for k in 0..=ORDER {
        let tk = match k {
            0 => t0,
            1 => 1.0,
            _ => 0.0,
        };
        work.set_input(0, k, tk);
        work.run_order(&tape, &plan, k);
    }
    (0..outputs.len())
        .map(|i| (0..=ORDER).map(|k| work.output(&tape, i, k)).collect())
        .collect()
}

fn factorial(k: usize) -> f64 {
    (1..=k).map(|i| i as f64).product()
}

/// `|got − want| ≤ 4 (k + 1) ε · scale` for every coefficient `k` — the round-off of a
/// recursion summing `k` terms — `scale` the magnitude of the terms.
fn assert_close(
    name: &str,
    got: &[f64],
    want: impl Fn(usize) -> f64,
    scale: impl Fn(usize) -> f64,
) {
    for (k, g) in got.iter().enumerate() {
        let w = want(k);
        let tol = 4.0 * (k + 1) as f64 * f64::EPSILON * scale(k).max(w.abs());
        assert!(
            (g - w).abs() <= tol,
            "{name}: order {k}: {g:e} vs {w:e} (tolerance {tol:e})"
        );
    }
}

#[test]
fn series_of_elementary_functions_match_their_closed_forms() {
    let t0 = 0.3f64;
    let s = series(t0, |g, t| {
        let one = g.constant(1.0);
        let d = g.sub(one, t);
        let log_arg = g.add(one, t);
        vec![
            g.call(Fun::Sin, t),
            g.call(Fun::Cos, t),
            g.call(Fun::Exp, t),
            g.div(one, d),
            g.call(Fun::Log, log_arg),
            g.call(Fun::Sqrt, log_arg),
            g.call(Fun::Atan, t),
            g.powi(log_arg, 5),
            g.powi(log_arg, -3),
            g.call(Fun::Sinh, t),
            g.call(Fun::Cosh, t),
        ]
    });
    let inv = |k: usize| 1.0 / factorial(k);
    let phase = |k: usize, f: fn(f64) -> f64| f(t0 + k as f64 * FRAC_PI_2) / factorial(k);
    assert_close("sin", &s[0], |k| phase(k, f64::sin), inv);
    assert_close("cos", &s[1], |k| phase(k, f64::cos), inv);
    assert_close(
        "exp",
        &s[2],
        |k| t0.exp() / factorial(k),
        |k| t0.exp() * inv(k),
    );
    // 1/(1 − t) = Σ hᵏ/(1 − t₀)^(k+1).
    let geometric = |k: usize| (1.0 - t0).powi(-(k as i32) - 1);
    assert_close("1/(1-t)", &s[3], geometric, geometric);
    // ln(1 + t): (−1)^(k+1) / (k (1 + t₀)^k).
    let a = 1.0 + t0;
    let log_k = |k: usize| {
        if k == 0 {
            a.ln()
        } else {
            (-1f64).powi(k as i32 + 1) / (k as f64 * a.powi(k as i32))
        }
    };
    assert_close("log", &s[4], log_k, |k| 4.0 * a.powi(-(k as i32)));
    // (1 + t)^r: binomial coefficients C(r, k) a^(r − k).
    let binomial = |r: f64, k: usize| {
        let c: f64 = (0..k).map(|j| (r - j as f64) / (j + 1) as f64).product();
        c * a.powf(r - k as f64)
    };
    let binomial_scale = |r: f64, k: usize| {
        4.0 * binomial(r.abs() + k as f64, k)
            .abs()
            .max(binomial(r, k).abs())
    };
    assert_close(
        "sqrt",
        &s[5],
        |k| binomial(0.5, k),
        |k| binomial_scale(0.5, k),
    );
    // atan: u₀ = atan t₀, uₖ = (−1)^(k−1) sin(kθ) / (k rᵏ), θ = atan2(1, t₀), r = √(1 + t₀²).
    let (theta, r) = (1f64.atan2(t0), (1.0 + t0 * t0).sqrt());
    let atan_k = |k: usize| {
        if k == 0 {
            t0.atan()
        } else {
            (-1f64).powi(k as i32 - 1) * (k as f64 * theta).sin() / (k as f64 * r.powi(k as i32))
        }
    };
    assert_close("atan", &s[6], atan_k, |k| 8.0 * r.powi(-(k as i32)));
    assert_close(
        "powi 5",
        &s[7],
        |k| binomial(5.0, k),
        |k| binomial_scale(5.0, k),
    );
    assert_close(
        "powi -3",
        &s[8],
        |k| binomial(-3.0, k),
        |k| binomial_scale(-3.0, k),
    );
    let sinh = |k: usize| if k.is_multiple_of(2) { t0.sinh() } else { t0.cosh() } / factorial(k);
    let cosh = |k: usize| if k.is_multiple_of(2) { t0.cosh() } else { t0.sinh() } / factorial(k);
    assert_close("sinh", &s[9], sinh, |k| 2.0 * inv(k));
    assert_close("cosh", &s[10], cosh, |k| 2.0 * inv(k));
}

#[test]
fn series_of_inverse_functions_and_identities_are_exact_to_round_off() {
    // asin(sin t), acos(cos t), atan2(sin t, cos t), exp(log(t)), (t^2.5)^(1/2.5) are t;
    // sin² + cos² is 1; tan t cos t is sin t; tanh t cosh t is sinh t; products and
    // quotients of series: ((1 + t) sin t)/(1 + t) is sin t.
    let t0 = 0.7f64;
    let s = series(t0, |g, t| {
        let (sin, cos) = (g.call(Fun::Sin, t), g.call(Fun::Cos, t));
        let asin = g.call(Fun::Asin, sin);
        let acos = g.call(Fun::Acos, cos);
        let atan2 = g.atan2(sin, cos);
        let log = g.call(Fun::Log, t);
        let exp_log = g.call(Fun::Exp, log);
        let p = g.constant(2.5);
        let q = g.constant(1.0 / 2.5);
        let pw = g.pow(t, p);
        let root = g.pow(pw, q);
        let s2 = g.powi(sin, 2);
        let c2 = g.powi(cos, 2);
        let unity = g.add(s2, c2);
        let tan = g.call(Fun::Tan, t);
        let tan_cos = g.mul(tan, cos);
        let tanh = g.call(Fun::Tanh, t);
        let cosh = g.call(Fun::Cosh, t);
        let tanh_cosh = g.mul(tanh, cosh);
        let sinh = g.call(Fun::Sinh, t);
        let one = g.constant(1.0);
        let b = g.add(one, t);
        let ts = g.mul(b, sin);
        let back = g.div(ts, b);
        let abs = g.call(Fun::Abs, sin);
        let neg = g.neg(sin);
        let abs_neg = g.call(Fun::Abs, neg);
        vec![
            asin, acos, atan2, exp_log, root, unity, tan_cos, sin, tanh_cosh, sinh, back, abs,
            abs_neg,
        ]
    });
    let identity = |k: usize| match k {
        0 => t0,
        1 => 1.0,
        _ => 0.0,
    };
    let unit = |_: usize| 1.0;
    for (name, i) in [
        ("asin(sin)", 0),
        ("acos(cos)", 1),
        ("atan2", 2),
        ("exp(log)", 3),
        ("pow", 4),
    ] {
        assert_close(name, &s[i], identity, unit);
    }
    assert_close(
        "sin^2 + cos^2",
        &s[5],
        |k| if k == 0 { 1.0 } else { 0.0 },
        unit,
    );
    let sin = s[7].clone();
    assert_close("tan cos", &s[6], |k| sin[k], unit);
    let sinh = s[9].clone();
    assert_close("tanh cosh", &s[8], |k| sinh[k], unit);
    assert_close("((1 + t) sin t)/(1 + t)", &s[10], |k| sin[k], unit);
    // |sin t| = sin t and |−sin t| = sin t where sin t₀ > 0.
    assert_close("abs", &s[11], |k| sin[k], unit);
    assert_close("abs of negative", &s[12], |k| sin[k], unit);
}

/// The final `(q, q̇)` of a model run with `method` and `step` over `[0, t_end]`.
fn final_state(
    scene: &dyn Scene,
    set: &[(&str, f64)],
    method: &str,
    step: StepControl,
    t_end: f64,
) -> Vec<f64> {
    let (_, rows) = run(scene, set, method, step, t_end);
    let n = scene.info().coordinates.len();
    rows.last().unwrap()[1..=2 * n].to_vec()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The final state of the fixed-order Taylor method of order `p` with `steps` equal steps on
/// a model, run through the library (any order; the registry lists `taylor8` and `taylor16`).
fn taylor_fixed<const S: usize>(
    name: &str,
    set: &[(&str, f64)],
    p: u32,
    steps: u32,
    t_end: f64,
) -> Vec<f64> {
    let scene = shipped(name);
    let mut params = scene.info().default_params();
    for (k, v) in set {
        params.set(k, *v).unwrap();
    }
    let system = scene
        .taylor(&params)
        .expect("a model without orientations on SO(3)");
    let mut y = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let mut stepper = Taylor::fixed(p).stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(
            &mut stepper,
            &system,
            &mut y,
            t_end / f64::from(steps),
            &mut NoObserver,
        )
        .unwrap();
    y.as_slice().to_vec()
}

/// A model, the parameters set, and the horizon.
type Case<'a> = (&'a str, &'a [(&'a str, f64)], f64);

#[test]
fn taylor_fixed_order_reaches_its_order_on_two_models() {
    // Errors against vern9 at 1e-15 (which agrees with the adaptive Taylor method at 1e-15 to
    // 4e-14) at three step counts, each twice the last, the order fitted by least squares:
    // orders 4 and 6 on the spherical pendulum (off its conical orbit) and the double pendulum
    // at large amplitude.
    let sph = [("theta_dot0", 1.5)];
    let cases: [Case; 2] = [
        ("spherical-pendulum", &sph, 2.0),
        ("double-pendulum", &[], 1.0),
    ];
    for (name, set, t_end) in cases {
        let steps = if name == "double-pendulum" {
            [64u32, 128, 256]
        } else {
            [128, 256, 512]
        };
        let reference = final_state(
            shipped(name),
            set,
            "vern9",
            StepControl::Tolerance(1e-15),
            t_end,
        );
        for p in [4u32, 6] {
            let e: Vec<f64> = steps
                .iter()
                .map(|&n| max_diff(&taylor_fixed::<4>(name, set, p, n, t_end), &reference))
                .collect();
            let h: Vec<f64> = steps.iter().map(|&n| t_end / f64::from(n)).collect();
            let observed = fit_power_law(&h, &e);
            println!("{name}, p = {p}: errors {e:?}: observed order {observed:.2}");
            assert!(
                e[2] > 1e-12,
                "{name}: error {:e} too close to the reference's",
                e[2]
            );
            assert!(
                (observed - f64::from(p)).abs() <= 0.3,
                "{name}, p = {p}: observed {observed}"
            );
        }
    }
}

#[test]
fn taylor_adaptive_tracks_the_tolerance_and_conserves_energy_on_a_model() {
    // The double pendulum at large amplitude against vern9 at 1e-15; the energy function
    // (conserved) to the tolerance.
    let scene = shipped("double-pendulum");
    let t_end = 3.0;
    let reference = final_state(scene, &[], "vern9", StepControl::Tolerance(1e-15), t_end);
    for tol in [1e-8, 1e-10, 1e-12, 1e-14] {
        let (c, rows) = run(scene, &[], "taylor", StepControl::Tolerance(tol), t_end);
        let y = &rows.last().unwrap()[1..=4];
        let err = max_diff(y, &reference);
        let drift = column(&c, &rows, "energy_rel_err")
            .into_iter()
            .fold(0.0, f64::max);
        println!(
            "taylor at {tol:e}: {} steps, final error {err:.2e}, energy drift {drift:.2e}",
            rows.len() - 1
        );
        assert!(err <= 100.0 * tol.max(1e-13), "tol {tol}: error {err:e}");
        assert!(
            drift <= 10.0 * tol.max(1e-14),
            "tol {tol}: energy drift {drift:e}"
        );
    }
}

#[test]
fn taylor_agrees_with_vern9_on_the_spherical_pendulum_trajectory() {
    // Every row of both runs at the same output times (dense output), at 1e-12.
    let scene = shipped("spherical-pendulum");
    let mut params = scene.info().default_params();
    params.set("theta_dot0", 1.5).unwrap();
    let rows_at = |method: &str| {
        let options = tumble_scenarios::RunOptions {
            integrator: Some(method.to_string()),
            step: Some(StepControl::Tolerance(1e-12)),
            t_end: Some(5.0),
            output_dt: Some(0.1),
            ..tumble_scenarios::RunOptions::default()
        };
        let mut rows = tumble_scenarios::scene::Rows::default();
        scene.run(&params, &options, &mut rows).unwrap();
        rows.0
    };
    let (a, b) = (rows_at("taylor"), rows_at("vern9"));
    assert_eq!(a.len(), b.len());
    assert_eq!(a.len(), 51);
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| {
            assert_eq!(x[0], y[0]);
            max_diff(&x[1..5], &y[1..5])
        })
        .fold(0.0, f64::max);
    println!("taylor vs vern9 at 1e-12 over 51 rows: max difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
}
