//! The Taylor method on Kepler's problem, whose coefficients are written out here by the
//! recursions of automatic differentiation, against the closed-form orbit: the error tracks
//! the tolerance, the dense output is the step's Taylor polynomial, events are located on it.

use std::cell::RefCell;
use std::f64::consts::PI;

use nalgebra::SVector;
use tumble_integrators::registry::{self, build};
use tumble_integrators::taylor::{
    Taylor, TaylorError, TaylorSystem, check_finite, jorba_zou_order, jorba_zou_step,
};
use tumble_integrators::verification::Kepler;
use tumble_integrators::{
    Action, AdaptiveStepper, DenseOutput, Direction, Driver, Event, Flow, NoObserver, Observer,
    Order, ProblemKind, Stepper, Tolerances,
};

type Y = SVector<f64, 4>;

/// Kepler's problem `q'' = −q/|q|³` as `(q₁, q₂, v₁, v₂)`, its coefficients by the series of
/// `r² = q·q`, `s = (r²)^(−3/2)` (the power recursion) and `−q s`.
struct KeplerSeries {
    /// `r²`, `s`, then `a = −q s` (two series), each of `MAX + 1` numbers.
    work: RefCell<Vec<f64>>,
}

const MAX: usize = 40;

impl KeplerSeries {
    fn new() -> Self {
        Self {
            work: RefCell::new(vec![0.0; 4 * (MAX + 1)]),
        }
    }
}

impl TaylorSystem for KeplerSeries {
    fn dim(&self) -> usize {
        4
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        c: &mut [f64],
    ) -> Result<(), TaylorError> {
        let w = &mut *self.work.borrow_mut();
        let (r2, rest) = w.split_at_mut(MAX + 1);
        let (s, _) = rest.split_at_mut(MAX + 1);
        c[..4].copy_from_slice(x0);
        for k in 0..order {
            r2[k] = (0..=k)
                .map(|j| c[j * 4] * c[(k - j) * 4] + c[j * 4 + 1] * c[(k - j) * 4 + 1])
                .sum();
            s[k] = if k == 0 {
                r2[0].powf(-1.5)
            } else {
                let mut acc = 0.0;
                for j in 0..k {
                    acc += (-1.5 * (k - j) as f64 - j as f64) * r2[k - j] * s[j];
                }
                acc / (k as f64 * r2[0])
            };
            let next = (k + 1) as f64;
            for i in 0..2 {
                let a: f64 = -(0..=k).map(|j| c[j * 4 + i] * s[k - j]).sum::<f64>();
                c[(k + 1) * 4 + i] = c[k * 4 + 2 + i] / next;
                c[(k + 1) * 4 + 2 + i] = a / next;
            }
        }
        check_finite(c, 4, order)
    }
}

const E: f64 = 0.6;

fn error_vs_exact(y: &Y, t: f64) -> f64 {
    let exact = Kepler::exact(E, t);
    (0..4).map(|i| (y[i] - exact[i]).abs()).fold(0.0, f64::max)
}

/// Runs the registry's `taylor` adaptively over `[0, t_end]` at `tol` with `events`.
fn run_adaptive<O: Observer<Y>>(
    tol: f64,
    t_end: f64,
    events: &mut [Event<'_, Y>],
    observer: &mut O,
    outputs: &[f64],
) -> (Y, tumble_integrators::Report<Y>) {
    let problem = KeplerSeries::new();
    let mut y = Y::from(Kepler::initial(E));
    let method = registry::find("taylor").unwrap();
    let mut stepper = Taylor::adaptive().stepper(&y);
    assert!(matches!(method.stepping, registry::Stepping::Taylor(_)));
    let driver = Driver::new(0.0, t_end).unwrap().output_at(outputs).unwrap();
    let tolerances = Tolerances::new(tol, tol).unwrap();
    let report = driver
        .run_adaptive(
            &mut stepper,
            &problem,
            &mut y,
            &tolerances,
            events,
            observer,
        )
        .unwrap();
    (y, report)
}

#[test]
fn taylor_is_registered_with_a_variable_order_for_taylor_series_problems() {
    let m = registry::find("taylor").unwrap();
    assert_eq!(m.order, Order::Variable);
    assert_eq!(m.problems, &[ProblemKind::TaylorSeries]);
    assert!(m.properties.adaptive && m.properties.dense_output);
    for (name, p) in [("taylor8", 8), ("taylor16", 16)] {
        let m = registry::find(name).unwrap();
        assert_eq!(m.order, Order::Finite(p));
        assert!(!m.properties.adaptive && m.properties.dense_output);
    }
    // No other builder runs a Taylor method.
    let y = Y::zeros();
    assert!(
        build::ode::<tumble_integrators::FnOde<fn(f64, &Y, &mut Y)>, Y, _>(m, &y, Unused).is_err()
    );
}

/// A receiver that is never handed a stepper.
struct Unused;

impl<P: ?Sized> build::ReceiveOde<P, Y> for Unused {
    type Output = ();
    fn adaptive<St: AdaptiveStepper<P, State = Y> + DenseOutput<P>>(self, _: St) {}
    fn interpolating<St: DenseOutput<P, State = Y>>(self, _: St) {}
    fn plain<St: Stepper<P, State = Y> + Clone>(self, _: St) {}
}

#[test]
fn jorba_zou_order_is_half_the_log_of_the_tolerance_plus_one() {
    // ⌈−½ ln ε + 1⌉.
    assert_eq!(jorba_zou_order(1e-8), 11);
    assert_eq!(jorba_zou_order(1e-14), 18);
    assert_eq!(jorba_zou_order(1e-16), 20);
    // The step of a geometric series Σ (h/ρ)^k: ρ/e² times the safety factor.
    let (rho, p) = (0.5f64, 12u32);
    let h = jorba_zou_step(rho.powi(-11), rho.powi(-12), p, 1.0);
    let expected = rho * (-2.0f64).exp() * (-0.7 / 11.0f64).exp();
    assert!(
        (h - expected).abs() <= 1e-15 * expected,
        "{h} vs {expected}"
    );
}

#[test]
fn taylor_fixed_order_observed_order_on_kepler() {
    // Half an orbit at e = 0.6 (through the pericentre at t = 0), against the closed form.
    for p in [6u32, 10] {
        let study = tumble_integrators::verification::OrderStudy::new(PI / 16.0, 6)
            .with_ratio(if p > 8 { 2f64.powf(0.5) } else { 2.0 })
            .on_span(PI);
        let fit = study
            .run(|h| {
                let problem = KeplerSeries::new();
                let mut y = Y::from(Kepler::initial(E));
                let mut stepper = Taylor::fixed(p).stepper(&y);
                Driver::new(0.0, PI)?.run_fixed(
                    &mut stepper,
                    &problem,
                    &mut y,
                    h,
                    &mut NoObserver,
                )?;
                Ok(error_vs_exact(&y, PI))
            })
            .unwrap();
        fit.check(f64::from(p), 0.3)
            .unwrap_or_else(|e| panic!("p = {p}: {e}"));
    }
}

#[test]
fn taylor_adaptive_error_tracks_the_tolerance_on_kepler() {
    // One orbit at e = 0.6: final error within a small factor of the tolerance, 1e-8 … 1e-14.
    let mut last = f64::INFINITY;
    for tol in [1e-8, 1e-10, 1e-12, 1e-14] {
        let (y, report) = run_adaptive(tol, 2.0 * PI, &mut [], &mut NoObserver, &[]);
        let err = error_vs_exact(&y, 2.0 * PI);
        assert!(err <= 20.0 * tol, "tol {tol}: error {err:e}");
        assert!(err < last, "tol {tol}: error {err:e} not below {last:e}");
        assert_eq!(report.rejected, 0, "the step is chosen, never rejected");
        last = err;
    }
}

/// Records the state at the start of every step and every output.
#[derive(Default)]
struct Record {
    steps: Vec<(f64, Y)>,
    outputs: Vec<(f64, Y)>,
}

impl Observer<Y> for Record {
    fn observe(&mut self, t: f64, y: &Y) -> Flow {
        self.steps.push((t, *y));
        Flow::Continue
    }
    fn output(&mut self, t: f64, y: &Y) -> Flow {
        self.outputs.push((t, *y));
        Flow::Continue
    }
}

#[test]
fn taylor_dense_output_is_the_steps_polynomial() {
    // Each output equals a fresh step of the same order from the start of its step to the
    // output time, to round-off; and the orbit to the tolerance.
    let tol = 1e-12;
    let times: Vec<f64> = (1..40).map(|i| f64::from(i) * 0.15).collect();
    let mut record = Record::default();
    run_adaptive(tol, 6.0, &mut [], &mut record, &times);
    assert_eq!(record.outputs.len(), times.len());
    let p = jorba_zou_order(tol);
    let problem = KeplerSeries::new();
    for (t, y) in &record.outputs {
        let (t0, y0) = record.steps.iter().rev().find(|(s, _)| s <= t).unwrap();
        let mut fresh = *y0;
        Taylor::fixed(p)
            .stepper(&fresh)
            .step(&problem, *t0, &mut fresh, t - t0)
            .unwrap();
        let diff = (0..4).map(|i| (fresh[i] - y[i]).abs()).fold(0.0, f64::max);
        assert!(diff <= 4.0 * f64::EPSILON, "t = {t}: {diff:e}");
        assert!(error_vs_exact(y, *t) <= 20.0 * tol, "t = {t}");
    }
}

#[test]
fn taylor_locates_apocentre_and_pericentre_passages_to_round_off() {
    // q₂ = 0 falling at the apocentre (t = π), rising at the pericentre (t = 2π).
    let mut events = [
        Event::new(|_t, y: &Y| y[1], Direction::Falling, Action::Continue),
        Event::new(|_t, y: &Y| y[1], Direction::Rising, Action::Continue),
    ];
    let (_, report) = run_adaptive(1e-15, 7.0, &mut events, &mut NoObserver, &[]);
    let times: Vec<(usize, f64)> = report.events.iter().map(|e| (e.index, e.t)).collect();
    assert_eq!(times.len(), 2, "{times:?}");
    for ((index, t), (expected_index, expected)) in times.iter().zip([(0, PI), (1, 2.0 * PI)]) {
        assert_eq!(*index, expected_index);
        assert!(
            (t - expected).abs() <= 1e-14,
            "event at {t}, expected {expected}: {:e}",
            t - expected
        );
    }
}

/// The harmonic oscillator `x' = v, v' = −x`: its coefficients `xₖ₊₁ = vₖ/(k+1)`,
/// `vₖ₊₁ = −xₖ/(k+1)`.
struct Oscillator;

impl TaylorSystem for Oscillator {
    fn dim(&self) -> usize {
        2
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        c: &mut [f64],
    ) -> Result<(), TaylorError> {
        c[..2].copy_from_slice(x0);
        for k in 0..order {
            let next = (k + 1) as f64;
            c[(k + 1) * 2] = c[k * 2 + 1] / next;
            c[(k + 1) * 2 + 1] = -c[k * 2] / next;
        }
        check_finite(c, 2, order)
    }
}

/// 10⁵ steps of the order-20 method (truncation far below round-off) on the oscillator: the
/// state is the sum of its increments with compensation, so its error against the closed
/// form `(cos t, −sin t)` stays at a few ulps, where the same polynomials summed plainly
/// (`x₀ + …` by Horner, each step rounded) drift as a random walk of half an ulp per step.
#[test]
fn compensated_steps_keep_round_off_from_accumulating() {
    type Y2 = SVector<f64, 2>;
    let (h, steps) = (1e-3, 100_000);
    let problem = Oscillator;
    let mut y = Y2::new(1.0, 0.0);
    let mut plain = y;
    let mut stepper = Taylor::fixed(20).stepper(&y);
    let mut t = 0.0f64;
    let mut c = vec![0.0; 21 * 2];
    for _ in 0..steps {
        // The plain sum over the clock's step, from the plain state's own coefficients.
        let step = (t + h) - t;
        problem
            .coefficients(t, plain.as_slice(), 20, &mut c)
            .unwrap();
        for i in 0..2 {
            plain[i] = (0..=20).rev().fold(0.0, |s, k| s * step + c[k * 2 + i]);
        }
        stepper.step(&problem, t, &mut y, h).unwrap();
        t += h;
    }
    let exact = Y2::new(t.cos(), -t.sin());
    let compensated = (y - exact).amax();
    let drift = (plain - exact).amax();
    eprintln!("t = {t}: compensated {compensated:.1e}, plain {drift:.1e}");
    assert!(compensated <= 4.0 * f64::EPSILON, "{compensated:e}");
    assert!(drift >= 10.0 * compensated, "plain {drift:e}");
}

/// The carried rounding error belongs to the state the stepper wrote: a state changed
/// between steps (an event's action, a restart) is stepped exactly as a fresh stepper steps
/// it.
#[test]
fn a_changed_state_drops_the_carried_rounding_error() {
    type Y2 = SVector<f64, 2>;
    let problem = Oscillator;
    let mut y = Y2::new(1.0, 0.0);
    let mut stepper = Taylor::fixed(12).stepper(&y);
    let mut t = 0.0;
    for _ in 0..100 {
        stepper.step(&problem, t, &mut y, 0.01).unwrap();
        t += 0.01;
    }
    y *= 0.5;
    let mut fresh_y = y;
    stepper.step(&problem, t, &mut y, 0.01).unwrap();
    let mut fresh = Taylor::fixed(12).stepper(&fresh_y);
    fresh.step(&problem, t, &mut fresh_y, 0.01).unwrap();
    assert_eq!(y, fresh_y);
}
