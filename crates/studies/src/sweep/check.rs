//! The self-check of a sweep: a deterministic, spread-out subset of its points run again at a
//! tighter setting (half the step, or a tolerance 100 times smaller), and the largest change of
//! each metric — how far the sweep's numbers can be trusted, stated with them.
//!
//! The subset is the corners of the grid (every combination of the first and last value of
//! each axis; the first and last point of random samples) and points evenly spaced in index
//! order, `max(8, 1 %)` by default or as many as asked. It depends only on the definition, so
//! a resumed, sharded or merged sweep checks the same points.

use std::collections::BTreeMap;

use rayon::prelude::*;
use tumble_scenarios::StepControl;

use super::SweepError;
use super::definition::{Sampling, SweepDefinition};
use super::engine::run_point;
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

/// The points a self-check of `size` re-runs, increasing (a grid or random sweep: see
/// [`check_points_among`] for a refined one).
#[must_use]
pub fn check_points(def: &SweepDefinition, size: CheckSize) -> Vec<u64> {
    pick(def, size, def.points(), |k| k)
}

/// The points a self-check of `size` re-runs among a sweep's `rows` (in index order): for a
/// refined sweep, whose points are not every point of its grid, the grid's corners (always
/// points of its coarse level) and a spread in index order over the points it has; for others,
/// [`check_points`]. A refined sweep's points depend on its definition alone, so this does too.
#[must_use]
pub fn check_points_among(def: &SweepDefinition, size: CheckSize, rows: &[PointRow]) -> Vec<u64> {
    if def.refine.is_none() {
        return check_points(def, size);
    }
    pick(def, size, rows.len() as u64, |k| {
        rows[usize::try_from(k).unwrap_or(usize::MAX).min(rows.len() - 1)].index
    })
}

/// The corners of the grid and `total` candidates (the `k`-th is point `at(k)`) evenly spread.
fn pick(def: &SweepDefinition, size: CheckSize, total: u64, at: impl Fn(u64) -> u64) -> Vec<u64> {
    let wanted = match size {
        CheckSize::Off => return Vec::new(),
        CheckSize::Auto => (total / 100).max(8),
        CheckSize::Points(n) => n,
    }
    .min(total);
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

/// `x / 100` as the decimal number it is written as: `1e-11` gives `1e-13` exactly as
/// parsed, not `9.999999999999999e-14` (the shortest decimal of `x` with its exponent
/// lowered by two).
fn hundredth(x: f64) -> f64 {
    let text = format!("{x:e}");
    text.split_once('e')
        .and_then(|(mantissa, exp)| {
            let exp: i32 = exp.parse().ok()?;
            format!("{mantissa}e{}", exp - 2).parse().ok()
        })
        .unwrap_or(x / 100.0)
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
    let mut tight = def.clone();
    tight.plan = def
        .plan
        .with_step(setting)
        .map_err(|e| SweepError::SelfCheck(format!("the tighter setting: {e}")))?;
    let threads = threads.clamp(1, points.len().max(1));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| SweepError::Threads {
            threads,
            reason: e.to_string(),
        })?;
    let again: Vec<PointRow> =
        pool.install(|| points.par_iter().map(|&i| run_point(&tight, i)).collect());
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
        changes,
        status_changed,
    })
}
