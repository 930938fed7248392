//! The error estimate of one run: how far its written rows are from the true motion, measured
//! by running it again at a tighter setting (the *companion*) and, to judge the estimate, at a
//! coarser one (the *check*).
//!
//! # The estimate
//!
//! The companion runs the same method at half the step (a fixed-step method) or at a tolerance
//! 100 times tighter (an adaptive one): the setting of a sweep's self-check,
//! [`crate::sweep::check::tighter`]. At every compared row the difference `d` of the run from the
//! companion is measured in the work–precision norm ([`state_error`]: `max |Δᵢ| / (1 + |yᵢ|)`,
//! the quaternion up to its sign). If the run's error shrinks by a factor `R` from the run to
//! the companion, the run's error is `e ≈ d · R / (R − 1)` (Richardson extrapolation; Hairer,
//! Nørsett & Wanner, *Solving ODEs I*, §II.4). For a method of order `p` at half the step
//! `R = 2ᵖ`; for an adaptive method of order `p`, whose global error goes as `tol^{p/(p+1)}`
//! (ibid. §II.4, tolerance proportionality), `R = 100^{p/(p+1)}`. The exact flow's only error
//! is round-off: its estimate is the round-off level (below).
//!
//! # Whether to trust it
//!
//! Richardson extrapolation holds when the errors are in their asymptotic regime. The check
//! runs the method at twice the step (or a tolerance 100 times looser), and the observed
//! factor `r = d_check / d`, the largest difference over the rows the two share, is compared
//! with `R`:
//!
//! * `r ≥ √R` (at least half the expected order): **trustworthy**; `R` is taken as `min(r, R)`,
//!   so that an order observed below the nominal one enlarges the estimate.
//! * `r < √R` and `d` at the round-off level of the runs (`ROUND_OFF · ε · √steps`, with `ε`
//!   the unit round-off and `steps` the companion's; `ε` for `taylor-dd`, whose rows are its
//!   double-double state rounded once): **round-off** — both runs sit on
//!   round-off, and the estimate is that level, not a convergent error.
//! * `r < √R`, an adaptive run, and `d` below its tolerance: **within the tolerance** — the run
//!   is as good as it claims, but the check cannot confirm the order (the steps of a nearly
//!   polynomial motion, limited by the horizon or an event rather than the tolerance, barely
//!   change with it); the estimate is the difference itself.
//! * otherwise **not trustworthy**: the companion disagrees with the run by more than the run's
//!   own coarse-to-fine decrease says it should (a step or tolerance outside the asymptotic
//!   regime, a motion that the steps do not resolve, a chaotic one); the true error may be far
//!   larger than stated.
//!
//! The companion costs about twice the run (half the step; an adaptive method at a tolerance 100
//! times tighter about `100^{1/(p+1)}` times), the check about half of it: with the check
//! on, a run costs about 2–3 times more. The two run in parallel.
//!
//! # Which rows
//!
//! The written rows are kept (their time and state) while the run writes them, up to
//! [`MAX_KEPT_ROWS`]; past that every second kept row is dropped and then every second of the
//! next ones, so the rows compared are spread evenly over the run. A fixed-step companion
//! writes its rows at the same times (every `2N`-th of its steps for every `N`-th of the run's);
//! an adaptive one, or a run writing rows at chosen times, gives its rows at the run's row
//! times from its dense output. The final states are compared as they are; when a run ends at
//! a terminal event (a landing), the two events' times differ, and the difference of the
//! times (`|Δt| / (1 + |t|)`) counts with the states'.

use rayon::join;
use tumble_integrators::registry::Order;
use tumble_integrators::{Flow, ProblemKind};
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{
    DenseRows, FinalState, Recorder, RunPlan, RunSummary, Scene, SceneInfo, StepControl,
};

use crate::sweep::check::tighter;
use crate::work_precision::{state_error, state_len};

/// Most rows kept of a run to compare with its companion (see the module doc).
pub const MAX_KEPT_ROWS: usize = 1 << 16;

/// The round-off level of a difference, in units of `ε · √steps` (module doc).
pub const ROUND_OFF: f64 = 100.0;

/// The time and state (coordinates, rates) of a run's written rows, thinned evenly to at most
/// [`MAX_KEPT_ROWS`], and its last row.
#[derive(Debug, Clone)]
pub struct WrittenRows {
    /// Values per row: `t` and the state.
    width: usize,
    /// Kept rows, flat.
    data: Vec<f64>,
    /// A written row is kept when its index is a multiple of this.
    stride: u64,
    /// Rows written so far.
    written: u64,
    /// The last row written (`t` and the state).
    last: Vec<f64>,
}

impl WrittenRows {
    /// An empty record for the rows of `info`'s scene.
    #[must_use]
    pub fn new(info: &SceneInfo) -> Self {
        let width = 1 + state_len(info);
        WrittenRows {
            width,
            data: Vec::new(),
            stride: 1,
            written: 0,
            last: Vec::with_capacity(width),
        }
    }

    /// Keeps `row` (a scene row: `t`, state, diagnostics) when its index is due.
    pub fn push(&mut self, row: &[f64]) {
        let Some(row) = row.get(..self.width) else {
            return;
        };
        if self.written.is_multiple_of(self.stride) {
            if self.data.len() / self.width >= MAX_KEPT_ROWS {
                // Keep every second kept row (indices multiple of 2·stride).
                let width = self.width;
                let kept: Vec<f64> = self
                    .data
                    .chunks_exact(width)
                    .step_by(2)
                    .flatten()
                    .copied()
                    .collect();
                self.data = kept;
                self.stride *= 2;
            }
            if self.written.is_multiple_of(self.stride) {
                self.data.extend_from_slice(row);
            }
        }
        self.last.clear();
        self.last.extend_from_slice(row);
        self.written += 1;
    }

    /// Rows written.
    #[must_use]
    pub fn written(&self) -> u64 {
        self.written
    }

    /// The last row written: `t` and the state (empty before the first).
    #[must_use]
    pub fn last(&self) -> &[f64] {
        &self.last
    }

    /// Rows kept.
    fn kept(&self) -> usize {
        self.data.len() / self.width
    }

    /// Time of kept row `i`.
    fn time(&self, i: usize) -> f64 {
        self.data[i * self.width]
    }

    /// State of kept row `i`.
    fn state(&self, i: usize) -> &[f64] {
        &self.data[i * self.width + 1..(i + 1) * self.width]
    }
}

/// A recorder that keeps the written rows in a [`WrittenRows`] and hands every row on.
pub struct Tap<'a> {
    /// The recorder the rows go to.
    pub inner: &'a mut dyn Recorder,
    /// Where the rows are kept.
    pub rows: &'a mut WrittenRows,
}

impl Recorder for Tap<'_> {
    fn row(&mut self, values: &[f64]) -> Flow {
        self.rows.push(values);
        self.inner.row(values)
    }

    fn wants_dense_rows(&self) -> bool {
        self.inner.wants_dense_rows()
    }

    fn dense_rows(&mut self, rows: &mut dyn DenseRows) -> Flow {
        self.inner.dense_rows(rows)
    }
}

/// How far an estimate can be trusted (module doc).
#[derive(Debug, Clone, PartialEq)]
pub enum Trust {
    /// The check run confirms the asymptotic regime.
    Trustworthy,
    /// Both runs sit on round-off: the estimate is the round-off level.
    RoundOff,
    /// An adaptive run whose companion agrees with it to within the run's own tolerance,
    /// where the check could not confirm the order: the error is about the estimate, the
    /// run as good as it claims, but the figure is not a converged one.
    WithinTolerance,
    /// The companion disagrees with the run by more than the run's coarse-to-fine decrease
    /// says: the true error may be far larger.
    NotTrustworthy,
    /// No check was possible (why): the estimate is Richardson's, unconfirmed.
    Unchecked(String),
}

impl Trust {
    /// One word for files: `trustworthy`, `round-off`, `not-trustworthy`, `unchecked`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Trust::Trustworthy => "trustworthy",
            Trust::RoundOff => "round-off",
            Trust::WithinTolerance => "within-tolerance",
            Trust::NotTrustworthy => "not-trustworthy",
            Trust::Unchecked(_) => "unchecked",
        }
    }
}

/// The error estimate of a run (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorEstimate {
    /// The companion's setting.
    pub companion: StepControl,
    /// The check's setting (`None`: no check run).
    pub check: Option<StepControl>,
    /// Estimated error of the final state, in the work–precision norm.
    pub final_error: f64,
    /// Largest estimated error over the compared rows (the final state included).
    pub max_error: f64,
    /// Time of the row where it is largest.
    pub max_error_t: f64,
    /// Rows compared with the companion (the final state included).
    pub rows_compared: u64,
    /// Rows the run wrote.
    pub rows_written: u64,
    /// The factor `R / (R − 1)` applied to the differences.
    pub factor: f64,
    /// The decrease `R` expected from the run to the companion.
    pub expected_ratio: f64,
    /// The decrease observed from the check to the run against the run to the companion
    /// (`None` without a check).
    pub observed_ratio: Option<f64>,
    /// The round-off level of the differences.
    pub round_off: f64,
    /// Whether to trust it.
    pub trust: Trust,
    /// Steps of the companion and the check together.
    pub steps: u64,
    /// Right-hand-side evaluations of the companion and the check together.
    pub evaluations: u64,
}

impl ErrorEstimate {
    /// One line for a summary: why the estimate is or is not to be trusted.
    #[must_use]
    pub fn trust_words(&self) -> String {
        let ratio = |r: Option<f64>| r.map_or_else(|| "?".to_string(), |r| format!("{r:.3}"));
        match &self.trust {
            Trust::Trustworthy => format!(
                "trustworthy: the coarser check's difference is {}× the companion's ({} \
                 expected)",
                ratio(self.observed_ratio),
                ratio(Some(self.expected_ratio))
            ),
            Trust::RoundOff => format!(
                "round-off: the runs agree to the round-off level ({:.1e}); the error is about \
                 that, not a convergent estimate",
                self.round_off
            ),
            Trust::WithinTolerance => format!(
                "within the tolerance: the companion agrees with the run to within its \
                 tolerance, but the coarser check's difference is only {}× the companion's ({} \
                 expected): the error is about this, not a converged figure",
                ratio(self.observed_ratio),
                ratio(Some(self.expected_ratio))
            ),
            Trust::NotTrustworthy => format!(
                "NOT trustworthy: the coarser check's difference is only {}× the companion's \
                 ({} expected): the setting is outside the asymptotic regime and the true \
                 error may be far larger; use a smaller step or tolerance",
                ratio(self.observed_ratio),
                ratio(Some(self.expected_ratio))
            ),
            Trust::Unchecked(why) => format!("unchecked: {why}"),
        }
    }
}

/// Compares a companion's rows with the kept rows of a run, at equal times.
struct Matcher<'a> {
    info: &'a SceneInfo,
    rows: &'a WrittenRows,
    next: usize,
    /// Difference at each kept row (`NaN`: not matched).
    diffs: Vec<f64>,
    ours: FinalState,
    theirs: FinalState,
    /// The companion's last row (`t` and state).
    last: Vec<f64>,
}

impl<'a> Matcher<'a> {
    fn new(info: &'a SceneInfo, rows: &'a WrittenRows) -> Self {
        let n = rows.width - 1;
        Matcher {
            info,
            rows,
            next: 0,
            diffs: vec![f64::NAN; rows.kept()],
            ours: FinalState {
                t: 0.0,
                values: vec![0.0; n],
            },
            theirs: FinalState {
                t: 0.0,
                values: vec![0.0; n],
            },
            last: Vec::with_capacity(rows.width),
        }
    }
}

/// Whether two row times are the same (round-off apart).
fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(1.0)
}

impl Recorder for Matcher<'_> {
    fn row(&mut self, values: &[f64]) -> Flow {
        let Some(row) = values.get(..self.rows.width) else {
            return Flow::Continue;
        };
        let t = row[0];
        let kept = self.rows.kept();
        while self.next < kept
            && self.rows.time(self.next) < t
            && !same_time(self.rows.time(self.next), t)
        {
            self.next += 1;
        }
        if self.next < kept && same_time(self.rows.time(self.next), t) {
            self.ours.t = t;
            self.ours.values.copy_from_slice(self.rows.state(self.next));
            self.theirs.t = t;
            self.theirs.values.copy_from_slice(&row[1..]);
            self.diffs[self.next] = state_error(self.info, &self.ours, &self.theirs);
            self.next += 1;
        }
        self.last.clear();
        self.last.extend_from_slice(row);
        Flow::Continue
    }
}

/// What one comparison run gave: its differences per kept row, at the final state, and work.
struct Compared {
    diffs: Vec<f64>,
    final_diff: f64,
    summary: RunSummary,
}

/// The difference of two final states in the work–precision norm ([`state_error`], `theirs`
/// the reference); when both runs ended at a terminal event (`events`), at different times,
/// the states are compared as the event's and the relative difference of the times,
/// `|Δt| / (1 + |t|)`, counts too. Otherwise states at different times differ by `∞`.
#[must_use]
pub fn final_difference(
    info: &SceneInfo,
    ours: &FinalState,
    theirs: &FinalState,
    events: bool,
) -> f64 {
    if !events || same_time(ours.t, theirs.t) {
        return state_error(info, ours, theirs);
    }
    let aligned = FinalState {
        t: theirs.t,
        values: ours.values.clone(),
    };
    let dt = (ours.t - theirs.t).abs() / (1.0 + theirs.t.abs());
    state_error(info, &aligned, theirs).max(dt)
}

/// A row (`t` and state) as a [`FinalState`].
fn as_state(row: &[f64]) -> FinalState {
    FinalState {
        t: row.first().copied().unwrap_or(f64::NAN),
        values: row.get(1..).map(<[f64]>::to_vec).unwrap_or_default(),
    }
}

/// Runs `plan` of `scene` and compares its rows with `rows`.
fn compare(
    scene: &dyn Scene,
    params: &Params,
    plan: &RunPlan,
    rows: &WrittenRows,
    events: bool,
) -> Result<Compared, String> {
    let info = scene.info();
    let mut matcher = Matcher::new(info, rows);
    let summary = scene
        .simulate(params, plan, &mut matcher)
        .map_err(|e| e.to_string())?;
    if summary.t < plan.t_end && !summary.terminated {
        return Err(format!("it stopped at t = {}", summary.t));
    }
    let final_diff = final_difference(
        info,
        &as_state(&rows.last),
        &as_state(&matcher.last),
        events && summary.terminated,
    );
    Ok(Compared {
        diffs: matcher.diffs,
        final_diff,
        summary,
    })
}

/// The plan of a comparison run at `step` whose rows fall at the kept rows' times: every
/// `every` steps (`times_mode` false), or at the kept times from dense output.
fn comparison_plan(
    plan: &RunPlan,
    step: StepControl,
    rows: &WrittenRows,
    every: Option<u64>,
    max_steps: u64,
) -> Result<RunPlan, String> {
    let mut p = plan.with_step(step).map_err(|e| e.to_string())?;
    p.max_steps = max_steps;
    match every {
        Some(n) => {
            p.every = n.max(1);
            p.times = None;
        }
        None => {
            let mut times: Vec<f64> = Vec::with_capacity(rows.kept());
            for i in 0..rows.kept() {
                let t = rows.time(i);
                if t <= plan.t_end && times.last().is_none_or(|&last| t > last) {
                    times.push(t);
                }
            }
            p.times = Some(times);
        }
    }
    Ok(p)
}

/// The coarser setting of the check: twice the step, or a tolerance 100 times looser (at most
/// `1e-2`); `None` when the step would exceed the horizon.
fn coarser(step: StepControl, t_end: f64) -> Option<StepControl> {
    match step {
        StepControl::Fixed(h) => (2.0 * h <= t_end).then_some(StepControl::Fixed(2.0 * h)),
        StepControl::Tolerance(tol) => {
            (tol * 100.0 <= 1e-2).then_some(StepControl::Tolerance(tol * 100.0))
        }
    }
}

/// The largest of `values` over the indices where `mask` holds and the value is a number,
/// with its index.
fn largest(values: &[f64], mask: impl Fn(usize) -> bool) -> Option<(usize, f64)> {
    values
        .iter()
        .enumerate()
        .filter(|(i, v)| !v.is_nan() && mask(*i))
        .fold(None, |best: Option<(usize, f64)>, (i, &v)| match best {
            Some((_, b)) if b >= v => best,
            _ => Some((i, v)),
        })
}

/// Estimates the error of a run of `plan` on `scene` that wrote `rows` and ended with `run`
/// (module doc): the companion and the check run in parallel.
///
/// # Errors
/// The companion failed (why): no estimate.
pub fn estimate(
    scene: &dyn Scene,
    params: &Params,
    plan: &RunPlan,
    run: &RunSummary,
    rows: &WrittenRows,
) -> Result<ErrorEstimate, String> {
    if rows.written == 0 {
        return Err("the run wrote no row".into());
    }
    let method = plan.method;
    let adaptive = method.properties.adaptive;
    let fixed_rows = !adaptive && plan.times.is_none();
    let events = run.terminated;
    let companion = tighter(plan.step);
    let budget = run.steps.saturating_mul(16).saturating_add(1000);
    let block = plan.every.saturating_mul(rows.stride);
    let companion_plan = comparison_plan(
        plan,
        companion,
        rows,
        fixed_rows.then_some(block.saturating_mul(2)),
        budget,
    )?;
    let expected_ratio = match (method.order, adaptive) {
        (Order::Exact, _) => f64::INFINITY,
        (Order::Finite(p), false) => 2f64.powi(p as i32),
        (Order::Finite(p), true) => 100f64.powf(f64::from(p) / f64::from(p + 1)),
        // The order grows with the tolerance: the ratio of the limit p → ∞.
        (Order::Variable, _) => 100.0,
    };
    let exact = method.order == Order::Exact;
    let check = if exact {
        None
    } else {
        coarser(plan.step, plan.t_end)
    };
    let check_plan = check.map(|c| {
        comparison_plan(
            plan,
            c,
            rows,
            fixed_rows.then_some(if block.is_multiple_of(2) {
                block / 2
            } else {
                block
            }),
            budget,
        )
    });
    let (fine, coarse) = join(
        || compare(scene, params, &companion_plan, rows, events),
        || check_plan.map(|p| p.and_then(|p| compare(scene, params, &p, rows, events))),
    );
    let fine = fine.map_err(|e| format!("the companion run ({}) failed: {e}", words(companion)))?;
    // A method that carries its state in double-double rounds it to `f64` only in the rows.
    let round_off = if method.problems == [ProblemKind::DoubleDoubleTaylorSeries] {
        f64::EPSILON
    } else {
        ROUND_OFF * f64::EPSILON * (fine.summary.steps.max(1) as f64).sqrt()
    };
    let all_fine = largest(&fine.diffs, |_| true).map_or(0.0, |(_, v)| v);
    let d_fine = all_fine.max(fine.final_diff);
    let mut steps = fine.summary.steps;
    let mut evaluations = fine.summary.evaluations;
    let (observed_ratio, trust) = match (exact, coarse) {
        (true, _) => (
            None,
            if d_fine <= round_off {
                Trust::RoundOff
            } else {
                Trust::Unchecked("the exact flow's runs differ by more than round-off".into())
            },
        ),
        (false, None) => (
            None,
            Trust::Unchecked(format!(
                "no coarser check: {} would exceed the horizon or 1e-2",
                match plan.step {
                    StepControl::Fixed(_) => "twice the step",
                    StepControl::Tolerance(_) => "a tolerance 100 times looser",
                }
            )),
        ),
        (false, Some(Err(e))) => (
            None,
            Trust::Unchecked(format!(
                "the coarser check ({}) failed: {e}",
                check.map_or_else(String::new, words)
            )),
        ),
        (false, Some(Ok(c))) => {
            steps += c.summary.steps;
            evaluations += c.summary.evaluations;
            // The largest differences over the rows both compared, and the final states.
            let shared = |i: usize| !c.diffs[i].is_nan();
            let f = largest(&fine.diffs, shared)
                .map_or(0.0, |(_, v)| v)
                .max(fine.final_diff);
            let k = largest(&c.diffs, |_| true)
                .map_or(0.0, |(_, v)| v)
                .max(c.final_diff);
            let r = if f > 0.0 { k / f } else { f64::INFINITY };
            let trust = if d_fine == 0.0 || (r < expected_ratio.sqrt() && d_fine <= round_off) {
                Trust::RoundOff
            } else if r >= expected_ratio.sqrt() {
                Trust::Trustworthy
            } else {
                match plan.step {
                    StepControl::Tolerance(tol) if d_fine <= tol => Trust::WithinTolerance,
                    _ => Trust::NotTrustworthy,
                }
            };
            (Some(r), trust)
        }
    };
    let ratio = match (&trust, observed_ratio) {
        (Trust::Trustworthy, Some(r)) => r.min(expected_ratio),
        _ => expected_ratio,
    };
    let factor = if matches!(trust, Trust::RoundOff | Trust::WithinTolerance) || ratio.is_infinite()
    {
        1.0
    } else {
        ratio / (ratio - 1.0)
    };
    let (max_i, max_row) = largest(&fine.diffs, |_| true).unwrap_or((0, 0.0));
    let (max_error, max_error_t) = if fine.final_diff >= max_row || rows.kept() == 0 {
        (fine.final_diff, rows.last[0])
    } else {
        (max_row, rows.time(max_i))
    };
    // Round-off: the estimate is the round-off level (or the difference, when larger).
    let (final_error, max_error) = if matches!(trust, Trust::RoundOff) {
        (fine.final_diff.max(round_off), max_error.max(round_off))
    } else {
        (factor * fine.final_diff, factor * max_error)
    };
    let matched = fine.diffs.iter().filter(|d| !d.is_nan()).count() as u64;
    let final_is_kept = rows.kept() > 0
        && same_time(rows.time(rows.kept() - 1), rows.last[0])
        && !fine.diffs[rows.kept() - 1].is_nan();
    Ok(ErrorEstimate {
        companion,
        check,
        final_error,
        max_error,
        max_error_t,
        rows_compared: matched + u64::from(!final_is_kept),
        rows_written: rows.written,
        factor,
        expected_ratio,
        observed_ratio,
        round_off,
        trust,
        steps,
        evaluations,
    })
}

/// `dt = 5e-4` or `tol = 1e-14`.
#[must_use]
pub fn words(step: StepControl) -> String {
    match step {
        StepControl::Fixed(h) => format!("dt = {}", crate::simulation::number(h)),
        // A tolerance scaled by 100 for the check (1e-30 · 100) shows as the round number.
        StepControl::Tolerance(t) => format!(
            "tol = {}",
            crate::simulation::number(format!("{t:.12e}").parse().unwrap_or(t))
        ),
    }
}
