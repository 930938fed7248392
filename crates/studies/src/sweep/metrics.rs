//! Metrics of one sweep point, computed by a [`Recorder`] while the scene integrates: nothing
//! of the trajectory is kept but the current step.
//!
//! # Hoop metrics (scenes with a `tilt` column)
//!
//! The tilt `τ = asin|n_z|` is a property of the motion, not of where the steps fall, so its
//! extremes and threshold crossings are located between steps. The signal used is
//! `s = sin τ = |n_z|` (smooth wherever `n_z ≠ 0`, also near a horizontal hoop where `τ` itself
//! has unbounded curvature).
//!
//! * **With dense output** (explicit Runge–Kutta, Gauss–Legendre): every step `[t₀, t₁]` is
//!   seen as a function of time ([`Recorder::dense_rows`]); `s` is evaluated at the five
//!   Chebyshev–Lobatto points `θ = (1 − cos(kπ/4))/2` of the step and the quartic through
//!   them carries the step: its error is the dense output's plus `O(h⁵)` with the constant of
//!   one step. `max_tilt` is the largest value of these quartics (their interior maxima found
//!   where the derivative changes sign, by bisection to the last bit), `time_tilt_exceeds` the
//!   first root of `p(t) = sin τ_c`.
//! * **Without** (the LGVI, splittings, Lie-group methods): the polynomial through the five
//!   samples around each event (Newton divided differences on the sample times, error
//!   `O(δt⁵)`), at every sample that is a local maximum of `s` and inside the first and last
//!   interval, and for the crossing in the interval where the samples first cross.
//!
//! `final_tilt` is the tilt of the last sample (`t = t_end` exactly).
//!
//! # Other metrics
//!
//! * `max_energy_rel_err`: the run's largest `|E − E₀|/|E₀|` over every step.
//! * `flips` (`free-body`, `dzhanibekov`): the number of sign changes of `ω · e₂`, the body
//!   angular velocity's component on the intermediate principal axis — each is one flip of
//!   the body (the T-handle's half turn) — as in the scenes' flip-period test.
//!
//! A row with a non-finite value stops the run: the point fails with the time and column.

use std::fmt;

use nalgebra::Vector3;
use tumble_integrators::Flow;

use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{DenseRows, Recorder, Scene};

/// A quantity recorded for every point of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Metric {
    /// Largest tilt of the hoop over the horizon (rad), interpolated between steps.
    MaxTilt,
    /// Tilt at the end of the horizon (rad).
    FinalTilt,
    /// First time the tilt exceeds the threshold (s); empty when it never does.
    TimeTiltExceeds,
    /// Largest relative energy error over every step.
    MaxEnergyRelErr,
    /// Sign changes of the body angular velocity on the intermediate principal axis.
    Flips,
}

impl Metric {
    /// Every metric, in the order the documentation lists them.
    pub const ALL: [Metric; 5] = [
        Metric::MaxTilt,
        Metric::FinalTilt,
        Metric::TimeTiltExceeds,
        Metric::MaxEnergyRelErr,
        Metric::Flips,
    ];

    /// Its name in sweep files and CSV headers.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Metric::MaxTilt => "max_tilt",
            Metric::FinalTilt => "final_tilt",
            Metric::TimeTiltExceeds => "time_tilt_exceeds",
            Metric::MaxEnergyRelErr => "max_energy_rel_err",
            Metric::Flips => "flips",
        }
    }

    /// Its SI unit (empty when dimensionless).
    #[must_use]
    pub fn unit(self) -> &'static str {
        match self {
            Metric::MaxTilt | Metric::FinalTilt => "rad",
            Metric::TimeTiltExceeds => "s",
            Metric::MaxEnergyRelErr | Metric::Flips => "",
        }
    }

    /// What it is, in a few words (plot labels).
    #[must_use]
    pub fn description(self) -> &'static str {
        match self {
            Metric::MaxTilt => "maximum tilt",
            Metric::FinalTilt => "final tilt",
            Metric::TimeTiltExceeds => "time the tilt first exceeds the threshold",
            Metric::MaxEnergyRelErr => "maximum relative energy error",
            Metric::Flips => "number of flips",
        }
    }

    /// The metric called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Metric> {
        Metric::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether its values are whole numbers (written without a decimal point).
    #[must_use]
    pub fn is_count(self) -> bool {
        matches!(self, Metric::Flips)
    }

    /// Whether it needs the hoop's `tilt` column.
    #[must_use]
    pub fn needs_tilt(self) -> bool {
        matches!(
            self,
            Metric::MaxTilt | Metric::FinalTilt | Metric::TimeTiltExceeds
        )
    }

    /// Why the metric does not apply to `scene`, or `None` when it does.
    #[must_use]
    pub fn not_applicable(self, scene: &dyn Scene) -> Option<String> {
        let info = scene.info();
        let columns = info.columns();
        if self.needs_tilt() && !columns.iter().any(|c| c == "tilt") {
            return Some(format!(
                "`{}` needs a hoop scene (a `tilt` column); scene `{}` has none",
                self.name(),
                info.name
            ));
        }
        if self == Metric::Flips && scene.intermediate_axis(&info.default_params()).is_none() {
            let bodies: Vec<&str> = tumble_scenarios::scenes::builtin()
                .iter()
                .filter(|s| s.intermediate_axis(&s.info().default_params()).is_some())
                .map(|s| s.info().name)
                .collect();
            return Some(format!(
                "`flips` applies to the torque-free bodies ({}), not to scene `{}`",
                bodies.join(", "),
                info.name
            ));
        }
        None
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The polynomial through up to five points `(t_j, y_j)` in Newton form, in the variable
/// `u = (t − t_0)/scale` for conditioning.
struct Interpolant {
    n: usize,
    u: [f64; 5],
    c: [f64; 5],
    t0: f64,
    scale: f64,
}

impl Interpolant {
    /// Through `points` (1 to 5, distinct increasing times).
    fn new(points: &[(f64, f64)]) -> Self {
        let n = points.len().min(5);
        let t0 = points[0].0;
        let scale = (points[n - 1].0 - t0).max(f64::MIN_POSITIVE);
        let mut u = [0.0; 5];
        let mut c = [0.0; 5];
        for j in 0..n {
            u[j] = (points[j].0 - t0) / scale;
            c[j] = points[j].1;
        }
        // Divided differences, in place: c[j] = y[u_0 … u_j].
        for level in 1..n {
            for j in (level..n).rev() {
                c[j] = (c[j] - c[j - 1]) / (u[j] - u[j - level]);
            }
        }
        Interpolant { n, u, c, t0, scale }
    }

    /// `(p(t), dp/du)`.
    fn eval(&self, t: f64) -> (f64, f64) {
        let x = (t - self.t0) / self.scale;
        let mut p = self.c[self.n - 1];
        let mut dp = 0.0;
        for j in (0..self.n - 1).rev() {
            dp = dp * (x - self.u[j]) + p;
            p = p * (x - self.u[j]) + self.c[j];
        }
        (p, dp)
    }

    /// The root of `f` in `[a, b]` by bisection, given `f(a) ≤ 0 < f(b)` or `f(a) ≥ 0 > f(b)`
    /// (signs as `rising` says), to the last bit of `t`.
    fn bisect(a: f64, b: f64, rising: bool, f: impl Fn(f64) -> f64) -> f64 {
        let (mut lo, mut hi) = (a, b);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let below = f(mid) <= 0.0;
            if below == rising {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The largest value of the polynomial on `[a, b]` found at its endpoints and at the
    /// interior maxima (derivative from `+` to `−`) of the sub-intervals `[a, m]`, `[m, b]`.
    fn max_on(&self, a: f64, m: f64, b: f64) -> f64 {
        let mut best = self.eval(a).0.max(self.eval(m).0).max(self.eval(b).0);
        for (lo, hi) in [(a, m), (m, b)] {
            if !(hi > lo) {
                continue;
            }
            let (d_lo, d_hi) = (self.eval(lo).1, self.eval(hi).1);
            if d_lo > 0.0 && d_hi < 0.0 {
                let t = Self::bisect(lo, hi, false, |t| self.eval(t).1);
                best = best.max(self.eval(t).0);
            }
        }
        best
    }
}

/// The tilt metrics: window of the last five samples of `s = sin τ`, the largest value found,
/// the first threshold crossing.
struct TiltTracker {
    /// Sample `(t, s)` in arrival order, at most five.
    window: Vec<(f64, f64)>,
    /// Samples seen.
    count: u64,
    /// Largest `s` so far (samples and interpolated maxima).
    max_s: f64,
    /// Last tilt sample.
    last_tilt: f64,
    /// `sin τ_c`, when the crossing time is recorded.
    threshold: Option<f64>,
    /// First crossing time, once found.
    crossing: Option<f64>,
    /// Window position `k` of the sample after which the samples first crossed the threshold
    /// (the crossing in `[t_k, t_{k+1}]` is solved once samples up to `k + 3` have arrived, or
    /// at the end).
    pending: Option<usize>,
    /// The method's dense output gives every step's tilt as a function of time: maxima and
    /// crossings come from it, not from the samples.
    dense: bool,
}

impl TiltTracker {
    fn new(threshold: Option<f64>) -> Self {
        TiltTracker {
            window: Vec::with_capacity(6),
            count: 0,
            max_s: f64::NEG_INFINITY,
            last_tilt: f64::NAN,
            threshold: threshold.map(f64::sin),
            crossing: None,
            pending: None,
            dense: false,
        }
    }

    /// One step `[t₀, t₁]` from dense output: `s = sin τ` at the Chebyshev–Lobatto nodes
    /// `θ = (1 − cos(kπ/4))/2`, `k = 0…4`, and the quartic through them, whose error is that of
    /// the dense output plus `O(h⁵)` with the small constant of one step; its maximum on the
    /// step (where its derivative changes sign), and the threshold's first crossing.
    fn step(&mut self, nodes: &[(f64, f64); 5]) {
        self.dense = true;
        let p = Interpolant::new(nodes);
        let (t0, t_mid, t1) = (nodes[0].0, nodes[2].0, nodes[4].0);
        let best = p.max_on(t0, t_mid, t1);
        if best.is_finite() {
            self.max_s = self.max_s.max(best);
        }
        if let Some(c) = self.threshold
            && self.crossing.is_none()
            && let Some(k) = (1..5).find(|&k| nodes[k].1 > c)
            && nodes[k - 1].1 <= c
        {
            let t = Interpolant::bisect(nodes[k - 1].0, nodes[k].0, true, |t| p.eval(t).0 - c);
            self.crossing = Some(t);
        }
    }

    fn push(&mut self, t: f64, tilt: f64) {
        if let Some(&(last_t, _)) = self.window.last()
            && !(t > last_t)
        {
            // A repeated sample (the driver's end-of-run call at the same time): nothing new.
            return;
        }
        let s = tilt.sin();
        self.last_tilt = tilt;
        self.max_s = self.max_s.max(s);
        if self.dense {
            self.window.clear();
            self.window.push((t, s));
            self.count += 1;
            return;
        }
        if self.window.len() == 5 {
            self.window.remove(0);
            if let Some(k) = self.pending.as_mut() {
                *k -= 1;
            }
        }
        self.window.push((t, s));
        self.count += 1;
        let n = self.window.len();

        // Threshold: the first interval where the samples cross it.
        if let Some(c) = self.threshold
            && self.crossing.is_none()
            && self.pending.is_none()
        {
            if self.count == 1 && s > c {
                self.crossing = Some(t);
            } else if n >= 2 && self.window[n - 2].1 <= c && s > c {
                self.pending = Some(n - 2);
            }
        }
        if let Some(k) = self.pending
            && n > k + 3
        {
            self.resolve_crossing(k);
        }

        // A local maximum at the sample two back (its centred five-point stencil is now
        // complete, or as complete as the start of the run allows).
        if n >= 3 {
            self.refine_max(n - 3);
        }
        // A maximum inside the first interval shows in no sample: look for it once five
        // samples are there.
        if self.count == 5 {
            self.edge_max(0);
        }
    }

    /// A maximum strictly inside the interval from window sample `k` to `k + 1` (the first or
    /// the last interval of the run, where no sample beyond can reveal it), found where the
    /// interpolant through the window turns from rising to falling.
    fn edge_max(&mut self, k: usize) {
        if k + 1 >= self.window.len() {
            return;
        }
        let p = Interpolant::new(&self.window);
        let (a, b) = (self.window[k].0, self.window[k + 1].0);
        let best = p.max_on(a, a, b);
        if best.is_finite() {
            self.max_s = self.max_s.max(best);
        }
    }

    /// Refines a local maximum of the samples at window position `c` (`0 < c < len − 1`).
    fn refine_max(&mut self, c: usize) {
        if c == 0 || c + 1 >= self.window.len() {
            return;
        }
        let (prev, mid, next) = (self.window[c - 1].1, self.window[c].1, self.window[c + 1].1);
        if !(prev <= mid && mid >= next && (prev < mid || mid > next)) {
            return;
        }
        let lo = c.saturating_sub(2);
        let hi = (c + 2).min(self.window.len() - 1);
        let p = Interpolant::new(&self.window[lo..=hi]);
        let best = p.max_on(self.window[c - 1].0, self.window[c].0, self.window[c + 1].0);
        if best.is_finite() {
            self.max_s = self.max_s.max(best);
        }
    }

    /// Solves `p(t) = sin τ_c` between window samples `k` and `k + 1`, with `p` through the
    /// whole window (samples `k − 1 … k + 3`, or what the ends of the run leave).
    fn resolve_crossing(&mut self, k: usize) {
        let Some(c) = self.threshold else { return };
        let p = Interpolant::new(&self.window);
        let (a, b) = (self.window[k].0, self.window[k + 1].0);
        let t = Interpolant::bisect(a, b, true, |t| p.eval(t).0 - c);
        self.crossing = Some(t);
        self.pending = None;
    }

    /// At the end of the run: the stencils that the last samples leave open.
    fn finish(&mut self) {
        if self.dense {
            return;
        }
        let n = self.window.len();
        if n >= 3 {
            self.refine_max(n - 2);
        }
        if n >= 2 {
            if self.count < 5 {
                self.edge_max(0);
            }
            self.edge_max(n - 2);
        }
        if let Some(k) = self.pending {
            self.resolve_crossing(k);
        }
    }

    fn max_tilt(&self) -> f64 {
        self.max_s.clamp(0.0, 1.0).asin()
    }
}

/// Counts sign changes of `ω · e₂`.
struct FlipCounter {
    axis: Vector3<f64>,
    omega_column: usize,
    sign: Option<f64>,
    flips: u64,
}

impl FlipCounter {
    fn push(&mut self, row: &[f64]) {
        let w = Vector3::new(
            row[self.omega_column],
            row[self.omega_column + 1],
            row[self.omega_column + 2],
        );
        let d = w.dot(&self.axis);
        if d != 0.0 {
            let sign = d.signum();
            if self.sign.is_some_and(|s| s != sign) {
                self.flips += 1;
            }
            self.sign = Some(sign);
        }
    }
}

/// Computes a point's metrics from the rows of its run.
pub(crate) struct MetricRecorder {
    columns: Vec<String>,
    tilt_column: Option<usize>,
    tilt: Option<TiltTracker>,
    flips: Option<FlipCounter>,
    /// Why the run was stopped (a non-finite value).
    failure: Option<String>,
}

impl MetricRecorder {
    /// A recorder for `metrics` of `scene` run with `params`.
    ///
    /// # Errors
    /// The parameters of a torque-free body without a defined intermediate axis (`flips`).
    pub(crate) fn new(
        scene: &dyn Scene,
        params: &Params,
        metrics: &[Metric],
        tilt_threshold: Option<f64>,
    ) -> Result<Self, SceneError> {
        let info = scene.info();
        let columns = info.columns();
        let find = |name: &str| columns.iter().position(|c| c == name);
        let tilt_column = find("tilt");
        let tilt = metrics
            .iter()
            .any(|m| m.needs_tilt())
            .then(|| TiltTracker::new(tilt_threshold));
        let flips = if metrics.contains(&Metric::Flips) {
            Some(FlipCounter {
                axis: scene.intermediate_axis(params).ok_or_else(|| {
                    SceneError::InvalidOption {
                        option: "flips",
                        value: f64::NAN,
                        reason: format!("scene `{}` has no intermediate axis", info.name),
                    }
                })??,
                omega_column: find("omega_x").ok_or_else(|| SceneError::InvalidOption {
                    option: "flips",
                    value: f64::NAN,
                    reason: format!("scene `{}` has no omega_x column", info.name),
                })?,
                sign: None,
                flips: 0,
            })
        } else {
            None
        };
        Ok(MetricRecorder {
            columns,
            tilt_column,
            tilt,
            flips,
            failure: None,
        })
    }

    /// Why the run stopped early, if it did.
    pub(crate) fn failure(&self) -> Option<&str> {
        self.failure.as_deref()
    }

    /// The value of `metric` after the run (`None`: not defined, e.g. a threshold never
    /// crossed). `max_energy_rel_err` is the run summary's.
    pub(crate) fn finish(
        &mut self,
        metrics: &[Metric],
        max_energy_rel_err: f64,
    ) -> Vec<Option<f64>> {
        if let Some(tilt) = &mut self.tilt {
            tilt.finish();
        }
        metrics
            .iter()
            .map(|m| match m {
                Metric::MaxTilt => self.tilt.as_ref().map(TiltTracker::max_tilt),
                Metric::FinalTilt => self.tilt.as_ref().map(|t| t.last_tilt),
                Metric::TimeTiltExceeds => self.tilt.as_ref().and_then(|t| t.crossing),
                Metric::MaxEnergyRelErr => Some(max_energy_rel_err),
                Metric::Flips => self.flips.as_ref().map(|f| f.flips as f64),
            })
            .collect()
    }
}

impl Recorder for MetricRecorder {
    fn wants_dense_rows(&self) -> bool {
        self.tilt.is_some() && self.tilt_column.is_some()
    }

    fn dense_rows(&mut self, rows: &mut dyn DenseRows) -> Flow {
        let (Some(tilt), Some(j)) = (&mut self.tilt, self.tilt_column) else {
            return Flow::Continue;
        };
        let (t0, t1) = rows.span();
        let mut nodes = [(0.0, 0.0); 5];
        for (k, node) in nodes.iter_mut().enumerate() {
            let theta = 0.5 * (1.0 - (std::f64::consts::FRAC_PI_4 * k as f64).cos());
            let t = match k {
                0 => t0,
                4 => t1,
                _ => t0 + theta * (t1 - t0),
            };
            let value = rows.row_at(t)[j];
            if !value.is_finite() {
                // The row at the step's end reports it with its time and column.
                return Flow::Continue;
            }
            *node = (t, value.sin());
        }
        tilt.step(&nodes);
        Flow::Continue
    }

    fn row(&mut self, values: &[f64]) -> Flow {
        if let Some(j) = values.iter().position(|v| !v.is_finite()) {
            self.failure = Some(format!(
                "non-finite state at t = {}: {} = {}",
                values[0],
                self.columns.get(j).map_or("?", String::as_str),
                values[j]
            ));
            return Flow::Stop;
        }
        if let (Some(tilt), Some(j)) = (&mut self.tilt, self.tilt_column) {
            tilt.push(values[0], values[j]);
        }
        if let Some(flips) = &mut self.flips {
            flips.push(values);
        }
        Flow::Continue
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds `tilt(t)` sampled at `t = k h` over `[0, t_end]`.
    fn track(h: f64, t_end: f64, threshold: Option<f64>, tilt: impl Fn(f64) -> f64) -> TiltTracker {
        let mut tracker = TiltTracker::new(threshold);
        let n = (t_end / h).round() as u64;
        for k in 0..=n {
            let t = if k == n { t_end } else { k as f64 * h };
            tracker.push(t, tilt(t));
        }
        tracker.finish();
        tracker
    }

    #[test]
    fn interpolants_reproduce_quartics_and_their_derivatives() {
        let f = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t - 0.25 * t.powi(3) + 0.125 * t.powi(4);
        let df = |t: f64| -2.0 + t - 0.75 * t * t + 0.5 * t.powi(3);
        let pts: Vec<(f64, f64)> = [0.1, 0.3, 0.35, 0.8, 1.0]
            .iter()
            .map(|&t| (t, f(t)))
            .collect();
        let p = Interpolant::new(&pts);
        for t in [0.0, 0.2, 0.5, 0.9, 1.3] {
            let (v, dv) = p.eval(t);
            assert!((v - f(t)).abs() < 1e-14, "{t}: {v} vs {}", f(t));
            assert!((dv / p.scale - df(t)).abs() < 1e-12, "{t}: {dv}");
        }
    }

    #[test]
    fn the_maximum_between_samples_is_found_to_the_fifth_order() {
        // s = sin τ with τ(t) = 0.4 sin(3t) + 0.1: maximum τ = 0.5 at 3t = π/2.
        let tilt = |t: f64| 0.4 * (3.0 * t).sin() + 0.1;
        let coarse = track(0.01, 2.0, None, tilt).max_tilt();
        let fine = track(0.005, 2.0, None, tilt).max_tilt();
        assert!((coarse - 0.5).abs() < 1e-9, "{coarse}");
        assert!((fine - 0.5).abs() < 1e-10, "{fine}");
        // The largest sample alone is off by about ½ τ'' δt².
        let samples = (0..=200)
            .map(|k| tilt(k as f64 * 0.01))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(0.5 - samples > 1e-6, "{samples}");
    }

    #[test]
    fn a_maximum_inside_the_first_or_last_interval_is_found() {
        // Peak at t = 0.996, inside the last interval [0.99, 1] of a step of 0.01: no sample
        // is a local maximum there.
        let peak = |t0: f64| move |t: f64| 0.5 - 3.0 * (t - t0) * (t - t0);
        let end = track(0.01, 1.0, None, peak(0.996));
        assert!((end.max_tilt() - 0.5).abs() < 1e-9, "{}", end.max_tilt());
        assert!(end.last_tilt < 0.5 - 1e-6);
        let start = track(0.01, 1.0, None, peak(0.004));
        assert!(
            (start.max_tilt() - 0.5).abs() < 1e-9,
            "{}",
            start.max_tilt()
        );
    }

    #[test]
    fn maxima_at_the_ends_are_the_end_samples() {
        let rising = track(0.01, 1.0, None, |t| 0.3 * t);
        assert!((rising.max_tilt() - 0.3).abs() < 1e-15);
        assert!((rising.last_tilt - 0.3).abs() < 1e-15);
        let falling = track(0.01, 1.0, None, |t| 0.3 * (1.0 - t));
        assert!((falling.max_tilt() - 0.3).abs() < 1e-15);
    }

    #[test]
    fn the_first_crossing_time_is_interpolated() {
        // τ = 0.6 t²: crosses 0.15 at t = 0.5 and keeps rising.
        let coarse = track(0.03, 1.0, Some(0.15), |t| 0.6 * t * t)
            .crossing
            .unwrap();
        let fine = track(0.015, 1.0, Some(0.15), |t| 0.6 * t * t)
            .crossing
            .unwrap();
        assert!((coarse - 0.5).abs() < 1e-8, "{coarse}");
        // Fourth order at least: halving the step divides the error by 16 or more.
        assert!((fine - 0.5).abs() < (coarse - 0.5).abs() / 16.0, "{fine}");
        // Above the threshold from the start: time 0; never: none.
        assert_eq!(track(0.03, 1.0, Some(0.1), |_| 0.2).crossing, Some(0.0));
        assert_eq!(track(0.03, 1.0, Some(0.3), |_| 0.2).crossing, None);
        // Crossing in the last interval, resolved at the end.
        let t = track(0.1, 1.0, Some(0.5), |t| 0.55 * t).crossing.unwrap();
        assert!((t - 0.5 / 0.55).abs() < 1e-7, "{t}");
        // Only the first of several crossings counts.
        let t = track(0.01, 4.0, Some(0.2), |t| 0.3 * (2.0 * t).sin().abs())
            .crossing
            .unwrap();
        let exact = (0.2f64 / 0.3).asin() / 2.0;
        assert!((t - exact).abs() < 1e-8, "{t} vs {exact}");
    }

    #[test]
    fn repeated_samples_are_ignored() {
        let mut tracker = TiltTracker::new(None);
        for (t, tau) in [(0.0, 0.1), (0.1, 0.2), (0.2, 0.15), (0.2, 0.15), (0.3, 0.1)] {
            tracker.push(t, tau);
        }
        tracker.finish();
        assert!(tracker.max_tilt() >= 0.2 && tracker.max_tilt().is_finite());
    }

    #[test]
    fn metric_names_round_trip() {
        for m in Metric::ALL {
            assert_eq!(Metric::from_name(m.name()), Some(m));
        }
        assert_eq!(Metric::from_name("tilt"), None);
    }
}
