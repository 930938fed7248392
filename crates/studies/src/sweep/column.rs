//! Metrics of one column of a scene's rows, located on the method's dense output.
//!
//! Every step `[t₀, t₁]` is seen as a function of time ([`DenseRows`]). The column is
//! evaluated at the five Chebyshev–Lobatto points `θ = (1 − cos(kπ/4))/2` of the step; the
//! quartic through them only *guides*: where its derivative changes sign inside the step, an
//! extremum is there, and it is then located on the dense output itself by Brent's method
//! ([`tumble_integrators::roots::maximize`]), so that its value is the dense output's to
//! round-off (near an extremum the value is quadratic in the time error). Crossings of a
//! value are bracketed by the nodes (or by a refined extremum that crosses when the nodes do
//! not) and solved on the dense output by the Illinois method. The time average integrates
//! each step by Clenshaw–Curtis quadrature on the same five nodes (exact for quintics),
//! halving the step on the dense output where Simpson's rule on three of the nodes disagrees
//! (a kink, a long step) — see [`integrate`].
//!
//! The hoop's `tilt = asin|n_z|` has unbounded curvature where the hoop stands flat
//! (`|n_z| → 1`); its metrics are computed on `sin(tilt) = |n_z|`, which is smooth there, and
//! mapped back (`asin` is increasing, so extremes and crossings are the same).

use tumble_integrators::roots::{illinois, maximize};
use tumble_scenarios::scene::DenseRows;

/// What is computed from a column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColumnOp {
    /// Largest value over the run.
    Max,
    /// Smallest value over the run.
    Min,
    /// Value at the end of the run.
    Final,
    /// Time average over the run.
    Mean,
    /// First time the column exceeds (`above`) or falls below `value`; none when it never does.
    FirstTime {
        /// `>` (exceeds) or `<` (falls below).
        above: bool,
        /// The value crossed.
        value: f64,
    },
}

/// The five Chebyshev–Lobatto nodes of a step, `θ_k = (1 − cos(kπ/4))/2`.
pub(crate) fn lobatto_nodes(t0: f64, t1: f64) -> [f64; 5] {
    std::array::from_fn(|k| match k {
        0 => t0,
        4 => t1,
        _ => t0 + 0.5 * (1.0 - (std::f64::consts::FRAC_PI_4 * k as f64).cos()) * (t1 - t0),
    })
}

/// Clenshaw–Curtis weights of the five nodes on `[0, 1]`.
const CLENSHAW_CURTIS: [f64; 5] = [1.0 / 30.0, 4.0 / 15.0, 2.0 / 5.0, 4.0 / 15.0, 1.0 / 30.0];

/// Halvings of a step allowed to the adaptive quadrature of a time average (a kink, such as
/// the tilt's where `n_z` changes sign, is resolved to `2⁻³⁰` of the step).
const MAX_HALVINGS: u32 = 30;

/// `∫ f` over `[t0, t1]` from `f`'s values at the five [`lobatto_nodes`]: Clenshaw–Curtis
/// (exact for quintics), accepted when Simpson's rule on three of the nodes agrees with it
/// to `1e-13` relative to the step (then the five-node value is good to far below that);
/// otherwise each half is integrated alike. A smooth column over a short step is accepted at
/// once; a kink or a long step is resolved by halving.
fn integrate(
    f: &mut dyn FnMut(f64) -> f64,
    t0: f64,
    t1: f64,
    values: &[f64; 5],
    halvings: u32,
) -> f64 {
    let h = t1 - t0;
    let cc = h * values
        .iter()
        .zip(CLENSHAW_CURTIS)
        .map(|(v, w)| w * v)
        .sum::<f64>();
    let simpson = h / 6.0 * (values[0] + 4.0 * values[2] + values[4]);
    let scale = h.abs() * (1.0 + values.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
    if halvings == 0 || (cc - simpson).abs() <= 1e-13 * scale || !cc.is_finite() {
        return cc;
    }
    let mid = times_mid(t0, t1);
    let left = lobatto_nodes(t0, mid);
    let right = lobatto_nodes(mid, t1);
    let lv = [values[0], f(left[1]), f(left[2]), f(left[3]), values[2]];
    let rv = [values[2], f(right[1]), f(right[2]), f(right[3]), values[4]];
    integrate(f, t0, mid, &lv, halvings - 1) + integrate(f, mid, t1, &rv, halvings - 1)
}

/// The middle node of a step (node 2 of [`lobatto_nodes`]).
fn times_mid(t0: f64, t1: f64) -> f64 {
    lobatto_nodes(t0, t1)[2]
}

/// One column's metric, accumulated step by step.
pub(crate) struct ColumnTracker {
    column: usize,
    op: ColumnOp,
    /// Work on `sin(value)` (the hoop's tilt).
    sine: bool,
    /// Max/Min: largest `±signal` so far.
    best: f64,
    /// FirstTime: the time found.
    crossing: Option<f64>,
    /// Mean: integral so far and the span integrated.
    integral: f64,
    span: Option<(f64, f64)>,
    /// Last row's value.
    last: f64,
    rows: u64,
}

impl ColumnTracker {
    pub(crate) fn new(column: usize, op: ColumnOp, sine: bool) -> Self {
        ColumnTracker {
            column,
            op,
            sine,
            best: f64::NEG_INFINITY,
            crossing: None,
            integral: 0.0,
            span: None,
            last: f64::NAN,
            rows: 0,
        }
    }

    /// The column of the tracked value.
    pub(crate) fn column(&self) -> usize {
        self.column
    }

    fn signal(&self, value: f64) -> f64 {
        if self.sine { value.sin() } else { value }
    }

    fn unsignal(&self, s: f64) -> f64 {
        if self.sine {
            s.clamp(-1.0, 1.0).asin()
        } else {
            s
        }
    }

    /// The sign that turns the metric into a maximum (of `±signal`, or of `±(signal − c)`).
    fn sign(&self) -> f64 {
        match self.op {
            ColumnOp::Min | ColumnOp::FirstTime { above: false, .. } => -1.0,
            _ => 1.0,
        }
    }

    /// The function maximised: `±signal` for extremes, `±(signal − c)` for crossings.
    fn objective(&self, value: f64) -> f64 {
        let c = match self.op {
            ColumnOp::FirstTime { value, .. } => self.signal(value),
            _ => 0.0,
        };
        self.sign() * (self.signal(value) - c)
    }

    /// A row of the run (every step's end, and the start).
    pub(crate) fn row(&mut self, values: &[f64]) {
        let v = values[self.column];
        self.last = v;
        self.rows += 1;
        match self.op {
            ColumnOp::Max | ColumnOp::Min => self.best = self.best.max(self.objective(v)),
            ColumnOp::FirstTime { .. } if self.rows == 1 && self.objective(v) > 0.0 => {
                self.crossing.get_or_insert(values[0]);
            }
            _ => {}
        }
    }

    /// One step, its column values `raw` at [`lobatto_nodes`] `times`, and its dense rows
    /// for refinement.
    pub(crate) fn step(&mut self, times: &[f64; 5], raw: &[f64; 5], rows: &mut dyn DenseRows) {
        if raw.iter().any(|v| !v.is_finite()) {
            // The row at the step's end reports it with its time and column.
            return;
        }
        let column = self.column;
        let mut on_dense = |tracker: &Self, t: f64| tracker.objective(rows.row_at(t)[column]);
        match self.op {
            ColumnOp::Final => {}
            ColumnOp::Mean => {
                self.integral += integrate(
                    &mut |t| rows.row_at(t)[column],
                    times[0],
                    times[4],
                    raw,
                    MAX_HALVINGS,
                );
                let start = self.span.map_or(times[0], |(a, _)| a);
                self.span = Some((start, times[4]));
            }
            ColumnOp::Max | ColumnOp::Min => {
                let g: [f64; 5] = std::array::from_fn(|k| self.objective(raw[k]));
                let mut best = g.iter().copied().fold(self.best, f64::max);
                for (lo, hi) in interior_maxima(times, &g) {
                    let (_, v) = maximize(|t| on_dense(self, t), lo, hi);
                    best = best.max(v);
                }
                self.best = best;
            }
            ColumnOp::FirstTime { .. } => {
                if self.crossing.is_some() {
                    return;
                }
                let g: [f64; 5] = std::array::from_fn(|k| self.objective(raw[k]));
                if let Some(k) = (1..5).find(|&k| g[k] > 0.0 && g[k - 1] <= 0.0) {
                    let t = illinois(
                        |t| on_dense(self, t),
                        times[k - 1],
                        g[k - 1],
                        times[k],
                        g[k],
                    );
                    self.crossing = Some(t);
                    return;
                }
                // Up and back down between two nodes: the refined maximum crosses.
                for (lo, hi) in interior_maxima(times, &g) {
                    let (tm, vm) = maximize(|t| on_dense(self, t), lo, hi);
                    if vm > 0.0 {
                        let g_lo = on_dense(self, lo);
                        let t = illinois(|t| on_dense(self, t), lo, g_lo, tm, vm);
                        self.crossing = Some(t);
                        return;
                    }
                }
            }
        }
    }

    /// The metric after the run (`None`: undefined, e.g. a value never crossed).
    pub(crate) fn finish(&self) -> Option<f64> {
        match self.op {
            ColumnOp::Max | ColumnOp::Min => self
                .best
                .is_finite()
                .then(|| self.unsignal(self.sign() * self.best)),
            ColumnOp::Final => self.last.is_finite().then_some(self.last),
            ColumnOp::Mean => match self.span {
                Some((a, b)) if b > a => Some(self.integral / (b - a)),
                _ => self.last.is_finite().then_some(self.last),
            },
            ColumnOp::FirstTime { .. } => self.crossing,
        }
    }
}

/// The sub-intervals `[t₀, t₂]`, `[t₂, t₄]` of a step where the quartic through the five
/// nodes has an interior maximum (its derivative goes from `+` to `−`).
fn interior_maxima(times: &[f64; 5], g: &[f64; 5]) -> impl Iterator<Item = (f64, f64)> {
    let p = Quartic::new(times, g);
    [(times[0], times[2]), (times[2], times[4])]
        .into_iter()
        .filter(move |&(lo, hi)| hi > lo && p.slope(lo) > 0.0 && p.slope(hi) < 0.0)
}

/// The polynomial through five points in Newton form, in `u = (t − t₀)/(t₄ − t₀)`.
struct Quartic {
    u: [f64; 5],
    c: [f64; 5],
    t0: f64,
    scale: f64,
}

impl Quartic {
    fn new(times: &[f64; 5], values: &[f64; 5]) -> Self {
        let t0 = times[0];
        let scale = (times[4] - t0).max(f64::MIN_POSITIVE);
        let u: [f64; 5] = std::array::from_fn(|j| (times[j] - t0) / scale);
        let mut c = *values;
        // Divided differences, in place: c[j] = y[u_0 … u_j].
        for level in 1..5 {
            for j in (level..5).rev() {
                c[j] = (c[j] - c[j - 1]) / (u[j] - u[j - level]);
            }
        }
        Quartic { u, c, t0, scale }
    }

    /// `(p(t), dp/du)`.
    fn eval(&self, t: f64) -> (f64, f64) {
        let x = (t - self.t0) / self.scale;
        let mut p = self.c[4];
        let mut dp = 0.0;
        for j in (0..4).rev() {
            dp = dp * (x - self.u[j]) + p;
            p = p * (x - self.u[j]) + self.c[j];
        }
        (p, dp)
    }

    fn slope(&self, t: f64) -> f64 {
        self.eval(t).1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense rows `(t, f(t))` of an analytic function.
    struct Analytic<F> {
        f: F,
        span: (f64, f64),
        row: [f64; 2],
    }

    impl<F: Fn(f64) -> f64> DenseRows for Analytic<F> {
        fn span(&self) -> (f64, f64) {
            self.span
        }
        fn row_at(&mut self, t: f64) -> &[f64] {
            self.row = [t, (self.f)(t)];
            &self.row
        }
    }

    /// Runs a tracker over `[0, t_end]` in steps of `h` on `f`.
    fn track(op: ColumnOp, sine: bool, h: f64, t_end: f64, f: impl Fn(f64) -> f64) -> Option<f64> {
        let mut tracker = ColumnTracker::new(1, op, sine);
        let n = (t_end / h).round() as u64;
        tracker.row(&[0.0, f(0.0)]);
        let mut rows = Analytic {
            f: &f,
            span: (0.0, 0.0),
            row: [0.0; 2],
        };
        for k in 0..n {
            let t0 = k as f64 * h;
            let t1 = if k + 1 == n { t_end } else { t0 + h };
            rows.span = (t0, t1);
            let times = lobatto_nodes(t0, t1);
            let raw = times.map(&f);
            tracker.step(&times, &raw, &mut rows);
            tracker.row(&[t1, f(t1)]);
        }
        tracker.finish()
    }

    #[test]
    fn quartics_are_reproduced_with_their_derivatives() {
        let f = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t - 0.25 * t.powi(3) + 0.125 * t.powi(4);
        let df = |t: f64| -2.0 + t - 0.75 * t * t + 0.5 * t.powi(3);
        let times = [0.1, 0.3, 0.35, 0.8, 1.0];
        let p = Quartic::new(&times, &times.map(f));
        for t in [0.0, 0.2, 0.5, 0.9, 1.3] {
            let (v, dv) = p.eval(t);
            assert!((v - f(t)).abs() < 1e-14, "{t}: {v} vs {}", f(t));
            assert!((dv / p.scale - df(t)).abs() < 1e-12, "{t}: {dv}");
        }
    }

    #[test]
    fn extrema_are_located_on_the_function_to_round_off_even_with_long_steps() {
        // Steps of 0.37 s against a period of 2.1 s: the quartic through the nodes is off by
        // about 1e-4 here; the maximum is found on the function itself.
        let f = |t: f64| 0.4 * (3.0 * t).sin() + 0.1;
        let max = track(ColumnOp::Max, false, 0.37, 2.0, f).unwrap();
        assert!((max - 0.5).abs() <= 2e-16, "{max}");
        let min = track(ColumnOp::Min, false, 0.37, 2.0, f).unwrap();
        assert!((min + 0.3).abs() <= 2e-16, "{min}");
        // Through sin: the tilt's maximum at a flat hoop, τ = π/2 − (t − 1)².
        let tilt = |t: f64| std::f64::consts::FRAC_PI_2 - (t - 1.0) * (t - 1.0);
        let max = track(ColumnOp::Max, true, 0.3, 2.0, tilt).unwrap();
        assert!((max - std::f64::consts::FRAC_PI_2).abs() <= 1e-7, "{max}");
    }

    #[test]
    fn extrema_at_the_ends_are_the_end_values() {
        let rising = |t: f64| 0.3 * t;
        assert_eq!(track(ColumnOp::Max, false, 0.1, 1.0, rising), Some(0.3));
        assert_eq!(track(ColumnOp::Min, false, 0.1, 1.0, rising), Some(0.0));
        assert_eq!(track(ColumnOp::Final, false, 0.1, 1.0, rising), Some(0.3));
    }

    #[test]
    fn first_crossings_are_solved_on_the_function() {
        // τ = 0.6 t²: crosses 0.15 at t = 0.5.
        let t = track(
            ColumnOp::FirstTime {
                above: true,
                value: 0.15,
            },
            false,
            0.3,
            1.0,
            |t| 0.6 * t * t,
        )
        .unwrap();
        assert!((t - 0.5).abs() <= 1e-15, "{t}");
        // Below: 1 − t falls below 0.25 at 0.75.
        let t = track(
            ColumnOp::FirstTime {
                above: false,
                value: 0.25,
            },
            false,
            0.3,
            1.0,
            |t| 1.0 - t,
        )
        .unwrap();
        assert!((t - 0.75).abs() <= 1e-15, "{t}");
        // Above from the start: time 0; never: none.
        let above = |value| ColumnOp::FirstTime { above: true, value };
        assert_eq!(track(above(0.1), false, 0.3, 1.0, |_| 0.2), Some(0.0));
        assert_eq!(track(above(0.3), false, 0.3, 1.0, |_| 0.2), None);
        // Up and back down between two nodes: a narrow bump of height 1 at t = 0.45.
        let bump = |t: f64| (-(t - 0.45f64).powi(2) / 1e-4).exp();
        let t = track(above(0.5), false, 0.3, 1.0, bump).unwrap();
        let exact = 0.45 - (0.5f64.ln() * -1e-4).sqrt();
        assert!((t - exact).abs() <= 1e-12, "{t} vs {exact}");
        // Only the first of several crossings counts.
        let t = track(above(0.2), false, 0.01, 4.0, |t| {
            0.3 * (2.0 * t).sin().abs()
        })
        .unwrap();
        let exact = (0.2f64 / 0.3).asin() / 2.0;
        assert!((t - exact).abs() < 1e-14, "{t} vs {exact}");
    }

    #[test]
    fn time_averages_are_resolved_across_long_steps_and_kinks() {
        // Mean of cos over [0, 3] is sin(3)/3, with steps of 0.5 s.
        let exact = 3.0_f64.sin() / 3.0;
        let got = track(ColumnOp::Mean, false, 0.5, 3.0, f64::cos).unwrap();
        assert!((got - exact).abs() <= 1e-14, "{:e}", got - exact);
        // |sin 2t| has a kink at t = π/2, inside a step of 0.37 s: ∫₀^{π/2} |sin 2t| = 1 and
        // ∫_{π/2}^3 (−sin 2t) = (cos 6 + 1)/2.
        let f = |t: f64| (2.0 * t).sin().abs();
        let exact = (1.0 + (6.0_f64.cos() + 1.0) / 2.0) / 3.0;
        let got = track(ColumnOp::Mean, false, 0.37, 3.0, f).unwrap();
        assert!((got - exact).abs() <= 1e-13, "{:e}", got - exact);
    }
}
