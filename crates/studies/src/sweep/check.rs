//! The self-check of a sweep: a deterministic subset of its points run again at a tighter
//! setting (half the step, or a tolerance 100 times smaller), and the largest change of each
//! metric — stated with the sweep's numbers as what it is: the largest change found.
//!
//! The errors of a map are not spread evenly: they are largest where the metric is most
//! sensitive to the point's parameters (on the hoop-tilt map, along its streaks, where a tilt
//! 50 times larger than the median one's error was measured). So on a grid the subset is
//! * the corners (every combination of the first and last value of each axis);
//! * the *steepest* points, half of the budget: every point is scored by its metrics' local
//!   variation on the grid — per axis, the central difference (one-sided at an edge) plus the
//!   second difference, each metric relative to its range over the sweep — and the highest
//!   scores are taken, one per neighbourhood (a point next to one already taken is skipped, so
//!   that the picks spread over every steep region rather than pile up on one);
//! * points evenly spaced in index order, the other half.
//!
//! The budget is `max(8, 1 %)` of the points by default, or as many as asked. Random samples
//! have no grid neighbours: their check is the first and last point and an even spread. The
//! subset depends on the definition and the sweep's values alone (bit-for-bit deterministic),
//! so a resumed, sharded or merged sweep checks the same points.

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

/// The points a self-check of `size` re-runs for a sweep with these `rows` (its finished
/// points, in index order), increasing: on a grid, the corners, the steepest half of the
/// budget ([`steepest_points`]) and an even spread over the points the sweep has (all of the
/// grid, or a refined sweep's points); for random samples, the first and last points and an
/// even spread.
#[must_use]
pub fn check_points_among(def: &SweepDefinition, size: CheckSize, rows: &[PointRow]) -> Vec<u64> {
    let wanted = budget(size, rows.len() as u64);
    if wanted == 0 || rows.is_empty() {
        return Vec::new();
    }
    let steep = if def.sampling == Sampling::Grid {
        steepest_points(def, rows, (wanted / 2) as usize)
    } else {
        Vec::new()
    };
    let rest = CheckSize::Points(wanted - steep.len() as u64);
    let mut points: std::collections::BTreeSet<u64> = pick(def, rest, rows.len() as u64, |k| {
        rows[usize::try_from(k).unwrap_or(usize::MAX).min(rows.len() - 1)].index
    })
    .into_iter()
    .collect();
    points.extend(steep);
    // Top up from the next steepest if the spread hit a steep point.
    if (points.len() as u64) < wanted {
        for k in steepest_points(def, rows, wanted as usize) {
            if points.len() as u64 >= wanted {
                break;
            }
            points.insert(k);
        }
    }
    // Still short (steep points of one neighbourhood are taken once): the budget is filled
    // with points spread over the rows, halving the spacing until it is met, so that a budget
    // as large as the sweep checks every point.
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

/// The `n` points of a grid sweep where its metrics vary most (see the module's
/// documentation), steepest first; fewer when fewer points have a neighbour on the grid.
/// Only points that finished (`ok`) and metrics of the motion (not `max_energy_rel_err`)
/// count; a neighbour missing from `rows` (a refined sweep's) is skipped.
#[must_use]
pub fn steepest_points(def: &SweepDefinition, rows: &[PointRow], n: usize) -> Vec<u64> {
    if def.sampling != Sampling::Grid || n == 0 {
        return Vec::new();
    }
    let counts: Vec<u64> = def.axes.iter().map(|a| a.count().unwrap_or(1)).collect();
    // Index strides: the last axis is the fastest.
    let strides: Vec<u64> = (0..counts.len())
        .map(|j| counts[j + 1..].iter().product())
        .collect();
    let metrics: Vec<usize> = def
        .metrics
        .iter()
        .enumerate()
        .filter(|(_, m)| **m != Metric::MaxEnergyRelErr)
        .map(|(k, _)| k)
        .collect();
    let value = |index: u64, k: usize| -> Option<f64> {
        let i = rows.binary_search_by_key(&index, |r| r.index).ok()?;
        let row = &rows[i];
        (row.status == Status::Ok)
            .then_some(row.metrics[k])
            .flatten()
            .filter(|v| v.is_finite())
    };
    // Each metric's range over the sweep, to compare metrics of different units.
    let ranges: Vec<f64> = metrics
        .iter()
        .map(|&k| {
            let (lo, hi) = rows
                .iter()
                .filter_map(|r| value(r.index, k))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                });
            hi - lo
        })
        .collect();
    let mut scored: Vec<(f64, u64)> = Vec::new();
    for row in rows {
        let mut score = 0.0_f64;
        for (&k, &range) in metrics.iter().zip(&ranges) {
            let Some(f) = value(row.index, k) else {
                continue;
            };
            if !(range > 0.0) {
                continue;
            }
            for (j, &stride) in strides.iter().enumerate() {
                let at = (row.index / stride) % counts[j];
                let below = (at > 0).then(|| value(row.index - stride, k)).flatten();
                let above = (at + 1 < counts[j])
                    .then(|| value(row.index + stride, k))
                    .flatten();
                let local = match (below, above) {
                    (Some(b), Some(a)) => 0.5 * (a - b).abs() + (a - 2.0 * f + b).abs(),
                    (Some(x), None) | (None, Some(x)) => (x - f).abs(),
                    (None, None) => 0.0,
                };
                score = score.max(local / range);
            }
        }
        if score > 0.0 {
            scored.push((score, row.index));
        }
    }
    // Steepest first; ties by index, so the choice is deterministic.
    scored.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut taken = std::collections::BTreeSet::new();
    let mut chosen = Vec::with_capacity(n);
    for &(_, index) in &scored {
        if chosen.len() == n {
            break;
        }
        let next_to_taken = strides.iter().enumerate().any(|(j, &stride)| {
            let at = (index / stride) % counts[j];
            (at > 0 && taken.contains(&(index - stride)))
                || (at + 1 < counts[j] && taken.contains(&(index + stride)))
        });
        if !next_to_taken {
            taken.insert(index);
            chosen.push(index);
        }
    }
    chosen
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
