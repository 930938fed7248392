//! The Taylor method on models: the series of the graph's nodes against closed forms, the
//! observed order at fixed order and step, the adaptive method's accuracy and conservation, and
//! agreement with an explicit pair.

use std::f64::consts::FRAC_PI_2;

use nalgebra::SVector;
use tumble_integrators::verification::fit_power_law;
use tumble_integrators::{
    Driver, ExplicitRungeKutta, NoObserver, Taylor, TaylorSystem, Tolerances,
};
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
    let system = scene.taylor(&params);
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
            check_order::<4>((name, set, t_end), p, steps, &reference);
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

/// The SO(3) models: the rigid body in a potential, coupled to a coordinate, torque-free.
const SO3_MODELS: [&str; 3] = ["heavy-top-so3", "free-hoop-so3", "t-handle-so3"];

#[test]
fn taylor_coefficients_of_so3_models_are_the_flow_and_its_derivatives() {
    // On the first-order tape (state (q, R, q̇, ω)): x₁ = F(x₀) (the same operations as the
    // right-hand side, to round-off), x₂ = ½ dF/dt along the flow (a central difference), and
    // the order-24 polynomial at a step h against 4000 RK4 steps over it (h half a radian of
    // the fastest rate of the state).
    for name in SO3_MODELS {
        let scene = shipped(name);
        let params = scene.info().default_params();
        let x0 = scene.initial_state(&params);
        let dim = x0.len();
        let ode = scene.ode(&params);
        let f = |x: &[f64]| {
            let mut dy = vec![0.0; dim];
            ode.rhs_slice(0.0, x, &mut dy);
            dy
        };
        let order = 24;
        let mut c = vec![0.0; (order + 1) * dim];
        let system = scene.taylor(&params);
        assert_eq!(system.dim(), dim);
        system.coefficients(0.0, &x0, order, &mut c).unwrap();
        let f0 = f(&x0);
        let along = |s: f64| -> Vec<f64> { x0.iter().zip(&f0).map(|(x, d)| x + s * d).collect() };
        let d = 1e-5;
        let (fp, fm) = (f(&along(d)), f(&along(-d)));
        for i in 0..dim {
            assert!(
                (c[dim + i] - f0[i]).abs() <= 1e-14 * (1.0 + f0[i].abs()),
                "{name}: x1[{i}] = {} vs F = {}",
                c[dim + i],
                f0[i]
            );
            let x2 = (fp[i] - fm[i]) / (2.0 * d) / 2.0;
            assert!(
                (c[2 * dim + i] - x2).abs() <= 1e-7 * (1.0 + x2.abs()),
                "{name}: x2[{i}] = {} vs {x2}",
                c[2 * dim + i]
            );
        }
        let spin = f0.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let h = 0.5 / spin;
        let steps = 4000;
        let dt = h / f64::from(steps);
        let mut y = x0.clone();
        let axpy = |y: &[f64], k: &[f64], s: f64| -> Vec<f64> {
            y.iter().zip(k).map(|(a, b)| a + s * b).collect()
        };
        for _ in 0..steps {
            let k1 = f(&y);
            let k2 = f(&axpy(&y, &k1, dt / 2.0));
            let k3 = f(&axpy(&y, &k2, dt / 2.0));
            let k4 = f(&axpy(&y, &k3, dt));
            for i in 0..dim {
                y[i] += (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) * (dt / 6.0);
            }
        }
        let mut worst = 0.0f64;
        for i in 0..dim {
            let sum = (0..=order).rev().fold(0.0, |s, k| s * h + c[k * dim + i]);
            worst = worst.max((sum - y[i]).abs() / (1.0 + y[i].abs()));
        }
        println!("{name}: polynomial at h = {h:.3e} against RK4: {worst:.2e}");
        assert!(worst <= 1e-13, "{name}: {worst:e}");
    }
}

/// The largest `|RᵀR − I|` entry of the rotation at `y[at..at + 9]` (by rows).
fn off_so3(y: &[f64], at: usize) -> f64 {
    let r = |a: usize, b: usize| y[at + 3 * a + b];
    let mut worst = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| r(k, i) * r(k, j)).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((dot - want).abs());
        }
    }
    worst
}

#[test]
fn taylor_on_the_so3_heavy_top_agrees_with_the_builtin_double_double_reference() {
    // The model's rows (quaternion, body angular velocity, energy, axis) at every 0.1 s of
    // 10 s (dense output) against the built-in `heavy-top` under taylor-dd at 1e-26, its own
    // hand-written equations on ℝ¹² in double-double. The tolerance bounds each step's error
    // against the largest component of the state (the spin, 50 rad/s).
    let t_end = 10.0;
    let rows_at = |scene: &dyn Scene, method: &str, tol: f64| {
        let options = tumble_scenarios::RunOptions {
            integrator: Some(method.to_string()),
            step: Some(StepControl::Tolerance(tol)),
            t_end: Some(t_end),
            output_dt: Some(0.1),
            ..tumble_scenarios::RunOptions::default()
        };
        let mut rows = tumble_scenarios::scene::Rows::default();
        let params = scene.info().default_params();
        scene.run(&params, &options, &mut rows).unwrap();
        (scene.info().columns(), rows.0)
    };
    let builtin = tumble_scenarios::scenes::find("heavy-top").unwrap();
    let (bc, br) = rows_at(builtin, "taylor-dd", 1e-26);
    let model = shipped("heavy-top-so3");
    for tol in [1e-10, 1e-12, 1e-14] {
        let (mc, mr) = rows_at(model, "taylor", tol);
        assert_eq!(mr.len(), br.len());
        let mut worst = 0.0f64;
        let mut shared = 0;
        for name in [
            "qw", "qx", "qy", "qz", "omega_x", "omega_y", "omega_z", "energy",
        ] {
            let (m, b) = (column(&mc, &mr, name), column(&bc, &br, name));
            shared += 1;
            for (x, y) in m.iter().zip(&b) {
                worst = worst.max((x - y).abs() / (1.0 + y.abs()));
            }
        }
        let energy = column(&mc, &mr, "energy_rel_err")
            .into_iter()
            .fold(0.0, f64::max);
        println!(
            "heavy-top-so3, taylor at {tol:e}: {shared} columns against taylor-dd: {worst:.2e}; \
             energy {energy:.2e}"
        );
        assert!(
            worst <= 50.0 * tol,
            "tol {tol:e}: {worst:e} from the reference"
        );
        assert!(energy <= tol, "tol {tol:e}: energy drift {energy:e}");
    }
}

#[test]
fn taylor_on_the_so3_heavy_top_conserves_its_integrals_and_stays_near_so3() {
    // The raw state (R by rows, ω) after 10 s of the adaptive method: the energy, the vertical
    // angular momentum L_z = (R I ω)_z and the spin ω₃ (I₁ = I₂) are conserved by the flow;
    // R leaves SO(3) by the series' truncation error only.
    let scene = shipped("heavy-top-so3");
    let params = scene.info().default_params();
    let inertia = [5.0, 5.0, 1.0];
    let (mgl, t_end) = (20.0, 10.0);
    let integrals = |y: &[f64]| {
        let w = &y[9..12];
        let energy = 0.5 * (0..3).map(|b| inertia[b] * w[b] * w[b]).sum::<f64>() + mgl * y[8];
        let lz = (0..3).map(|b| y[6 + b] * inertia[b] * w[b]).sum::<f64>();
        [energy, lz, w[2]]
    };
    let y0 = scene.initial_state(&params);
    let start = integrals(&y0);
    let system = scene.taylor(&params);
    let mut drifts = Vec::new();
    for tol in [1e-8, 1e-12] {
        let mut y = SVector::<f64, 12>::from_column_slice(&y0);
        let mut stepper = Taylor::adaptive().stepper(&y);
        let report = Driver::new(0.0, t_end)
            .unwrap()
            .run_adaptive(
                &mut stepper,
                &system,
                &mut y,
                &Tolerances::new(tol, tol).unwrap(),
                &mut [],
                &mut NoObserver,
            )
            .unwrap();
        let end = integrals(y.as_slice());
        let rel: Vec<f64> = (0..3)
            .map(|i| (end[i] - start[i]).abs() / start[i].abs())
            .collect();
        let drift = off_so3(y.as_slice(), 0);
        println!(
            "heavy-top-so3, taylor at {tol:e}: {} steps; energy, L_z, omega_3 relative drift \
             {rel:?}; |R^T R - I| {drift:.2e}",
            report.steps
        );
        for (what, r) in ["energy", "L_z", "omega_3"].iter().zip(&rel) {
            assert!(*r <= tol, "tol {tol:e}: {what} drifts by {r:e}");
        }
        // The drift is the method's error, set by the tolerance against the state's largest
        // component (the spin, 50 rad/s): well above round-off at a loose tolerance.
        assert!(
            drift <= 10.0 * tol * 50.0,
            "tol {tol:e}: |R^T R - I| {drift:e}"
        );
        drifts.push(drift);
    }
    assert!(drifts[0] > 1e3 * drifts[1], "{drifts:?}");
}

#[test]
fn taylor_fixed_order_reaches_its_order_on_an_so3_model() {
    // The heavy top on SO(3) over 0.5 s (four turns of its spin), errors of the raw state
    // (R, ω) against vern9 at 1e-15 at three step counts, each twice the last: orders 4 and 6.
    let name = "heavy-top-so3";
    let t_end = 0.5;
    let reference = final_state_raw::<12>(name, t_end);
    for (p, steps) in [(4u32, [64u32, 128, 256]), (6, [32, 64, 128])] {
        check_order::<12>((name, &[], t_end), p, steps, &reference);
    }
}

/// The fixed-order Taylor method of order `p` on a case at three step counts, each twice the
/// last: its errors against `reference` well above the reference's own, and the order fitted
/// by least squares within ±0.3 of `p`.
fn check_order<const S: usize>(case: Case, p: u32, steps: [u32; 3], reference: &[f64]) {
    let (name, set, t_end) = case;
    let e: Vec<f64> = steps
        .iter()
        .map(|&n| max_diff(&taylor_fixed::<S>(name, set, p, n, t_end), reference))
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

/// The raw final state of a model after vern9 at 1e-15 (not the Taylor method).
fn final_state_raw<const S: usize>(name: &str, t_end: f64) -> Vec<f64> {
    let scene = shipped(name);
    let params = scene.info().default_params();
    let ode = scene.ode(&params);
    let mut y = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let mut stepper = ExplicitRungeKutta::vern9().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &ode,
            &mut y,
            &Tolerances::new(1e-15, 1e-15).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    y.as_slice().to_vec()
}
