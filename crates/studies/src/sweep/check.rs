//! The self-check of a sweep: a deterministic subset of its points run again at a tighter
//! setting (half the step, or a tolerance 100 times smaller), and the largest change of each
//! metric — stated with the sweep's numbers as what it is: the largest change found.
//!
//! The errors of a map are heavy-tailed and isolated: on the hoop-tilt map the worst point's
//! trajectory lingers near an unstable relative equilibrium of the bead (a saddle), which
//! amplifies its errors about 1000 times more than its grid neighbours', and nothing in the
//! map's values singles it out (by the local differences of its metrics it ranked 681st of
//! 23,405). What singles it out is its error: so every point first runs again at a *looser*
//! setting (twice the step, or a tolerance 1000 times larger — about half the cost of the
//! sweep for a high-order method), the *screen*, and the points whose metrics change most
//! there are the ones checked. A trajectory that amplifies errors amplifies them at either
//! setting: on that map the screen ranks the worst point against a 1e-15 reference first or
//! second, and the five next worst within its first 20. The subset is
//! * the corners of a grid (every combination of the first and last value of each axis), the
//!   first and last points of random samples;
//! * the most sensitive points by the screen, half of the budget ([`most_sensitive`]);
//! * points evenly spaced in index order, the rest.
//!
//! The budget is `max(8, 1 %)` of the points by default, or as many as asked (a budget of
//! every point needs no screen). The subset depends on the definition and the sweep's values
//! alone (bit-for-bit deterministic, whatever the number of threads), so a resumed, sharded or
//! merged sweep checks the same points.

use std::collections::BTreeMap;

use rayon::prelude::*;
use tumble_scenarios::StepControl;

use super::SweepError;
use super::definition::{Sampling, SweepDefinition};
use super::engine::run_points;
use super::journal::{PointRow, Status};
use super::metrics::Metric;

/// How many points a self-check re-runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CheckSize {
    /// `max(8, 1 %)` of the points (all of them for a sweep of 8 or fewer).
    Auto,
    /// This many (at most all of them).
    Points(u64),
    /// No self-check.
    Off,
}

/// The largest change of one metric between the sweep and its self-check.
#[derive(Debug, Clone, PartialEq)]
pub struct MetricChange {
    /// The metric.
    pub metric: Metric,
    /// Largest `|tight − sweep|` over the check points where both are defined.
    pub max_change: f64,
    /// The point where it is largest.
    pub index: Option<u64>,
    /// Check points where the metric is defined in one run and not in the other (a threshold
    /// crossed in one of them only).
    pub undefined_in_one: u64,
}

/// The result of a self-check.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// The points re-run.
    pub points: Vec<u64>,
    /// The tighter setting.
    pub setting: StepControl,
    /// The screen's looser setting, when the points were chosen by a screen.
    pub screen: Option<StepControl>,
    /// Per metric.
    pub changes: Vec<MetricChange>,
    /// Check points that failed in one run and not in the other.
    pub status_changed: Vec<u64>,
}

impl CheckReport {
    /// The largest change over the metrics of the motion (0 when none could be compared);
    /// `max_energy_rel_err`, a property of the method rather than of the motion, is reported
    /// but not counted.
    #[must_use]
    pub fn largest(&self) -> f64 {
        self.physical().map(|c| c.max_change).fold(0.0, f64::max)
    }

    /// The metric of the motion whose change is largest (`None` when none could be compared).
    #[must_use]
    pub fn physical_largest(&self) -> Option<&MetricChange> {
        self.physical()
            .filter(|c| c.index.is_some())
            .max_by(|a, b| a.max_change.total_cmp(&b.max_change))
    }

    /// Whether every metric of the motion changed by at most `tolerance` and no point changed
    /// its status or had a metric defined in one run only.
    #[must_use]
    pub fn converged(&self, tolerance: f64) -> bool {
        self.status_changed.is_empty()
            && self
                .physical()
                .all(|c| c.max_change <= tolerance && c.undefined_in_one == 0)
    }

    /// The changes of the metrics of the motion (not the energy error's).
    fn physical(&self) -> impl Iterator<Item = &MetricChange> {
        self.changes
            .iter()
            .filter(|c| c.metric != Metric::MaxEnergyRelErr)
    }
}

/// The points a self-check of `size` re-runs, increasing, chosen from the definition alone: the
/// corners and an even spread (the part of [`check_points_among`] that does not need the
/// sweep's values).
#[must_use]
pub fn check_points(def: &SweepDefinition, size: CheckSize) -> Vec<u64> {
    pick(def, size, def.points(), |k| k)
}

/// How many points a self-check of `size` re-runs among `total`.
fn budget(size: CheckSize, total: u64) -> u64 {
    match size {
        CheckSize::Off => 0,
        CheckSize::Auto => (total / 100).max(8),
        CheckSize::Points(n) => n,
    }
    .min(total)
}

/// Whether a self-check of `size` on `total` points chooses among them by a screen (it does
/// unless it checks none or every one of them).
#[must_use]
pub fn screens(size: CheckSize, total: u64) -> bool {
    let wanted = budget(size, total);
    wanted > 0 && wanted < total
}

/// The points a self-check of `size` re-runs for a sweep with these `rows` (its finished
/// points, in index order), increasing: the corners of a grid (the first and last points of
/// random samples), the most sensitive half of the budget by the `screened` rows
/// ([`most_sensitive`]; none when `screened` is empty) and an even spread over the points the
/// sweep has (all of the grid, or a refined sweep's points).
#[must_use]
pub fn check_points_among(
    def: &SweepDefinition,
    size: CheckSize,
    rows: &[PointRow],
    screened: &[PointRow],
) -> Vec<u64> {
    let wanted = budget(size, rows.len() as u64);
    if wanted == 0 || rows.is_empty() {
        return Vec::new();
    }
    let ranked = most_sensitive(def, rows, screened);
    let half = (wanted / 2) as usize;
    let rest = CheckSize::Points(wanted - half.min(ranked.len()) as u64);
    let mut points: std::collections::BTreeSet<u64> = pick(def, rest, rows.len() as u64, |k| {
        rows[usize::try_from(k).unwrap_or(usize::MAX).min(rows.len() - 1)].index
    })
    .into_iter()
    .collect();
    // The most sensitive, down the ranking until the budget is met (the spread may have
    // taken some of them already).
    for &k in &ranked {
        if points.len() as u64 >= wanted {
            break;
        }
        points.insert(k);
    }
    // Still short (fewer ranked points than the budget's half): the budget is filled with
    // points spread over the rows, halving the spacing until it is met, so that a budget as
    // large as the sweep checks every point.
    let n = rows.len();
    let mut m = 1;
    while (points.len() as u64) < wanted && m <= n {
        for i in 0..m {
            if points.len() as u64 >= wanted {
                break;
            }
            points.insert(rows[(2 * i + 1) * n / (2 * m)].index);
        }
        m *= 2;
    }
    for r in rows {
        if points.len() as u64 >= wanted {
            break;
        }
        points.insert(r.index);
    }
    points.into_iter().collect()
}

/// The points of a sweep ranked by how much their metrics changed at the screen's looser
/// setting (`screened`, rows of the same points; see the module's documentation), most
/// sensitive first; only points that changed. A point whose status changed, or one of whose
/// metrics is defined in one run only (a threshold crossed in one of them), ranks above every
/// change of value; a change of value counts relative to the metric's range over the sweep
/// (metrics of different units compare), the largest over the metrics of the motion (not
/// `max_energy_rel_err`). Ties go to the lower index, so the ranking is deterministic.
#[must_use]
pub fn most_sensitive(def: &SweepDefinition, rows: &[PointRow], screened: &[PointRow]) -> Vec<u64> {
    let metrics: Vec<usize> = def
        .metrics
        .iter()
        .enumerate()
        .filter(|(_, m)| **m != Metric::MaxEnergyRelErr)
        .map(|(k, _)| k)
        .collect();
    let finite = |row: &PointRow, k: usize| row.metrics[k].filter(|v| v.is_finite());
    // Each metric's range over the sweep (1 where it has none), to compare metrics of
    // different units.
    let ranges: Vec<f64> = metrics
        .iter()
        .map(|&k| {
            let (lo, hi) = rows
                .iter()
                .filter(|r| r.status == Status::Ok)
                .filter_map(|r| finite(r, k))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                });
            if hi > lo { hi - lo } else { 1.0 }
        })
        .collect();
    let by_index: BTreeMap<u64, &PointRow> = rows.iter().map(|r| (r.index, r)).collect();
    let mut scored: Vec<(f64, u64)> = Vec::new();
    for loose in screened {
        let Some(row) = by_index.get(&loose.index) else {
            continue;
        };
        let score = if (row.status == Status::Ok) != (loose.status == Status::Ok) {
            f64::INFINITY
        } else if row.status != Status::Ok {
            0.0
        } else {
            metrics
                .iter()
                .zip(&ranges)
                .map(|(&k, range)| match (finite(row, k), finite(loose, k)) {
                    (Some(a), Some(b)) => (a - b).abs() / range,
                    (None, None) => 0.0,
                    _ => f64::INFINITY,
                })
                .fold(0.0, f64::max)
        };
        if score > 0.0 {
            scored.push((score, row.index));
        }
    }
    scored.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    scored.into_iter().map(|(_, k)| k).collect()
}

/// The corners of the grid and `total` candidates (the `k`-th is point `at(k)`) evenly spread.
fn pick(def: &SweepDefinition, size: CheckSize, total: u64, at: impl Fn(u64) -> u64) -> Vec<u64> {
    let wanted = budget(size, total);
    let mut points = std::collections::BTreeSet::new();
    if wanted == 0 {
        return Vec::new();
    }
    // Corners: every combination of first and last value of each axis (grid indices have the
    // last axis fastest).
    if def.sampling == Sampling::Grid {
        let counts: Vec<u64> = def.axes.iter().map(|a| a.count().unwrap_or(1)).collect();
        for mask in 0..(1u64 << counts.len().min(16)) {
            let mut index = 0;
            for (k, &n) in counts.iter().enumerate() {
                let last = mask & (1 << k) != 0;
                index = index * n + if last { n - 1 } else { 0 };
            }
            points.insert(index);
            if points.len() as u64 >= wanted {
                break;
            }
        }
    } else {
        points.insert(at(0));
        points.insert(at(total - 1));
    }
    // Evenly spread in index order.
    let spread = wanted.saturating_sub(points.len() as u64);
    if spread > 0 {
        for k in 0..spread {
            let rank = if spread == 1 {
                total / 2
            } else {
                ((k as f64) * ((total - 1) as f64) / ((spread - 1) as f64)).round() as u64
            };
            points.insert(at(rank.min(total - 1)));
        }
    }
    // Fill up to `wanted` if rounding merged some.
    let mut next = 0;
    while (points.len() as u64) < wanted && next < total {
        points.insert(at(next));
        next += 1;
    }
    points.into_iter().collect()
}

/// The tighter setting of a self-check: half the step, or a tolerance 100 times smaller.
#[must_use]
pub fn tighter(step: StepControl) -> StepControl {
    match step {
        StepControl::Fixed(h) => StepControl::Fixed(h / 2.0),
        StepControl::Tolerance(tol) => StepControl::Tolerance(hundredth(tol)),
    }
}

/// The looser setting of a self-check's screen: twice the step (at most the horizon
/// `t_end`), or a tolerance 1000 times larger (at most 0.1).
#[must_use]
pub fn looser(step: StepControl, t_end: f64) -> StepControl {
    match step {
        StepControl::Fixed(h) => StepControl::Fixed((2.0 * h).min(t_end)),
        StepControl::Tolerance(tol) => StepControl::Tolerance(shift_decimal(tol, 3).min(0.1)),
    }
}

/// `x / 100` as the decimal number it is written as: `1e-11` gives `1e-13` exactly as
/// parsed, not `9.999999999999999e-14`.
fn hundredth(x: f64) -> f64 {
    shift_decimal(x, -2)
}

/// `x · 10^by` as a decimal number: the shortest decimal of `x` with its exponent moved by
/// `by` (`1e-13` and 3 give `1e-10` exactly as parsed).
fn shift_decimal(x: f64, by: i32) -> f64 {
    let text = format!("{x:e}");
    text.split_once('e')
        .and_then(|(mantissa, exp)| {
            let exp: i32 = exp.parse().ok()?;
            format!("{mantissa}e{}", exp + by).parse().ok()
        })
        .unwrap_or(x * 10f64.powi(by))
}

/// Runs `points` of `def` at the `setting` (named `what` in errors) on `threads` workers.
fn rerun(
    def: &SweepDefinition,
    setting: StepControl,
    what: &str,
    points: &[u64],
    threads: usize,
) -> Result<Vec<PointRow>, SweepError> {
    let mut other = def.clone();
    other.plan = def
        .plan
        .with_step(setting)
        .map_err(|e| SweepError::SelfCheck(format!("the {what} setting: {e}")))?;
    let threads = threads.clamp(1, points.len().max(1));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| SweepError::Threads {
            threads,
            reason: e.to_string(),
        })?;
    let width = other.lanes().map_or(1, |l| l.width);
    Ok(pool.install(|| {
        points
            .par_chunks(width)
            .flat_map_iter(|chunk| run_points(&other, chunk))
            .collect()
    }))
}

/// The screen of a self-check: every point of `rows` that finished run again at the
/// [`looser`] setting on `threads` workers, for [`most_sensitive`] to rank.
///
/// # Errors
/// The looser setting is invalid for the method; the worker threads cannot be started.
pub fn screen(
    def: &SweepDefinition,
    rows: &[PointRow],
    threads: usize,
) -> Result<Vec<PointRow>, SweepError> {
    let points: Vec<u64> = rows
        .iter()
        .filter(|r| r.status == Status::Ok)
        .map(|r| r.index)
        .collect();
    rerun(
        def,
        looser(def.plan.step, def.plan.t_end),
        "screen's looser",
        &points,
        threads,
    )
}

/// The self-check of a sweep with these `rows` (its finished points, in index order): the
/// [`screen`] when it chooses ([`screens`]), the points of [`check_points_among`], and their
/// [`self_check`]; `None` when the check has no points (`size` off, no rows).
///
/// # Errors
/// As [`screen`] and [`self_check`].
pub fn check_sweep(
    def: &SweepDefinition,
    rows: &[PointRow],
    size: CheckSize,
    threads: usize,
) -> Result<Option<CheckReport>, SweepError> {
    let screened = if screens(size, rows.len() as u64) {
        screen(def, rows, threads)?
    } else {
        Vec::new()
    };
    let points = check_points_among(def, size, rows, &screened);
    if points.is_empty() {
        return Ok(None);
    }
    let mut report = self_check(def, rows, &points, threads)?;
    report.screen = (!screened.is_empty()).then(|| looser(def.plan.step, def.plan.t_end));
    Ok(Some(report))
}

/// Re-runs `points` of `def` at the tighter setting on `threads` workers and compares their
/// metrics with the sweep's `rows` (by index).
///
/// # Errors
/// The tighter setting is invalid for the method (it never is for a valid plan), or the
/// worker threads cannot be started.
pub fn self_check(
    def: &SweepDefinition,
    rows: &[PointRow],
    points: &[u64],
    threads: usize,
) -> Result<CheckReport, SweepError> {
    let setting = tighter(def.plan.step);
    let again = rerun(def, setting, "tighter", points, threads)?;
    let by_index: BTreeMap<u64, &PointRow> = rows.iter().map(|r| (r.index, r)).collect();
    let mut changes: Vec<MetricChange> = def
        .metrics
        .iter()
        .map(|metric| MetricChange {
            metric: metric.clone(),
            max_change: 0.0,
            index: None,
            undefined_in_one: 0,
        })
        .collect();
    let mut status_changed = Vec::new();
    for row in &again {
        let Some(base) = by_index.get(&row.index) else {
            continue;
        };
        if (base.status == Status::Ok) != (row.status == Status::Ok) {
            status_changed.push(row.index);
            continue;
        }
        if row.status != Status::Ok {
            continue;
        }
        for (k, change) in changes.iter_mut().enumerate() {
            match (base.metrics[k], row.metrics[k]) {
                (Some(a), Some(b)) => {
                    let d = (a - b).abs();
                    if change.index.is_none() || d > change.max_change {
                        change.max_change = d;
                        change.index = Some(row.index);
                    }
                }
                (None, None) => {}
                _ => change.undefined_in_one += 1,
            }
        }
    }
    Ok(CheckReport {
        points: points.to_vec(),
        setting,
        screen: None,
        changes,
        status_changed,
    })
}
