//! Two sweeps of the same grid compared point by point (`tumble sweep diff A B`): the largest
//! difference of each metric they share, and where.
//!
//! This is how a study is checked against itself — the same grid at half the step, a tighter
//! tolerance, another method — and how two tools are compared. The sweeps must have the same
//! axes (names, and the same values at every index); their scenes' settings, integrators and
//! steps may differ, which is the point. Metrics are matched by name; a metric recorded by one
//! sweep only is listed, not compared. A point where one sweep has a value and the other none
//! (a crossing found by one method only, a failed point) is counted apart from the numbers.
//! A refined sweep holds some points of its grid: it is compared at the points both hold
//! (against the uniform sweep of its grid: every point it has).

use std::path::Path;

use super::SweepError;
use super::definition::SweepDefinition;
use super::journal::{self, DEFINITION, PointRow, RESULTS};

/// The largest difference of one metric between two sweeps.
#[derive(Debug, Clone, PartialEq)]
pub struct MetricDifference {
    /// The metric's name.
    pub metric: String,
    /// `max |a − b|` over the points where both have a value (0 when there are none).
    pub largest: f64,
    /// The largest relative to the larger magnitude there, `|a − b| / max(|a|, |b|)`.
    pub relative: f64,
    /// The point of the largest difference: its index and axis values.
    pub at: Option<(u64, Vec<f64>)>,
    /// Points where both have a value.
    pub compared: u64,
    /// Points where exactly one of the two has a value.
    pub defined_in_one: u64,
}

/// The comparison of two sweeps ([`diff`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepDiff {
    /// The axes' parameter names.
    pub axes: Vec<String>,
    /// Points compared: every point of the grid, or those both sweeps hold when one is refined.
    pub points: u64,
    /// One entry per metric both sweeps record, in the first sweep's order.
    pub metrics: Vec<MetricDifference>,
    /// Metrics recorded by only the first or only the second sweep.
    pub only_in_first: Vec<String>,
    /// See `only_in_first`.
    pub only_in_second: Vec<String>,
    /// Indices of the points whose status (ok, failed, panicked) differs.
    pub status_differs: Vec<u64>,
}

impl SweepDiff {
    /// The largest difference of any metric.
    #[must_use]
    pub fn largest(&self) -> f64 {
        self.metrics.iter().map(|m| m.largest).fold(0.0, f64::max)
    }
}

/// A sweep folder's definition and its `results.csv` rows.
///
/// # Errors
/// A folder without `sweep.toml` or `results.csv` (an unfinished sweep has no results yet),
/// an invalid definition, a damaged results file.
pub fn read_folder(dir: &Path) -> Result<(SweepDefinition, Vec<PointRow>), SweepError> {
    let read = |name: &str, what: &'static str| {
        let path = dir.join(name);
        std::fs::read_to_string(&path).map_err(|source| SweepError::Io { path, what, source })
    };
    let text = read(
        DEFINITION,
        "cannot read the sweep's definition (is this a sweep folder?)",
    )?;
    let def = SweepDefinition::parse(&text, &dir.join(DEFINITION).display().to_string(), &[])?;
    let results = read(
        RESULTS,
        "cannot read the results (a sweep writes them when all its points are done)",
    )?;
    let rows =
        journal::parse_results(&def, &results).map_err(|(line, reason)| SweepError::Journal {
            path: dir.join(RESULTS),
            line,
            reason,
        })?;
    Ok((def, rows))
}

/// Compares the sweeps in folders `a` and `b` ([`read_folder`], [`diff`]).
///
/// # Errors
/// As [`read_folder`] and [`diff`].
pub fn diff_folders(a: &Path, b: &Path) -> Result<SweepDiff, SweepError> {
    let (def_a, rows_a) = read_folder(a)?;
    let (def_b, rows_b) = read_folder(b)?;
    diff(&def_a, &rows_a, &def_b, &rows_b)
}

/// Compares two sweeps' rows point by point.
///
/// # Errors
/// [`SweepError::Compare`] when the grids differ (axes, point count, or the values of a point)
/// or a sweep lacks a point.
pub fn diff(
    def_a: &SweepDefinition,
    rows_a: &[PointRow],
    def_b: &SweepDefinition,
    rows_b: &[PointRow],
) -> Result<SweepDiff, SweepError> {
    let names = |def: &SweepDefinition| -> Vec<String> {
        def.axes.iter().map(|a| a.parameter.to_string()).collect()
    };
    let axes = names(def_a);
    if axes != names(def_b) {
        return Err(SweepError::Compare(format!(
            "the sweeps have different axes: [{}] and [{}]",
            axes.join(", "),
            names(def_b).join(", ")
        )));
    }
    if def_a.points() != def_b.points() {
        return Err(SweepError::Compare(format!(
            "the sweeps have {} and {} points",
            def_a.points(),
            def_b.points()
        )));
    }
    for (def, rows, which) in [(def_a, rows_a, "first"), (def_b, rows_b, "second")] {
        // A refined sweep holds some points of its grid, each once, in index order.
        let holds = if def.refine.is_some() {
            rows.windows(2).all(|w| w[0].index < w[1].index)
                && rows.last().is_none_or(|r| r.index < def.points())
        } else {
            rows.len() as u64 == def.points()
                && rows.iter().enumerate().all(|(i, r)| r.index == i as u64)
        };
        if !holds {
            return Err(SweepError::Compare(format!(
                "the {which} sweep's results do not hold its points once each, in order"
            )));
        }
    }
    // The points both sweeps have (every point when neither is refined).
    let pairs = shared_points(rows_a, rows_b);
    if let Some((ra, rb)) = pairs.iter().find(|(ra, rb)| {
        ra.values
            .iter()
            .zip(&rb.values)
            .any(|(x, y)| x.to_bits() != y.to_bits())
    }) {
        return Err(SweepError::Compare(format!(
            "point {} is ({}) in the first sweep and ({}) in the second: not the same grid",
            ra.index,
            format_point(&axes, &ra.values),
            format_point(&axes, &rb.values)
        )));
    }
    let metric_names = |def: &SweepDefinition| -> Vec<String> {
        def.metrics.iter().map(super::Metric::name).collect()
    };
    let (ma, mb) = (metric_names(def_a), metric_names(def_b));
    let mut metrics = Vec::new();
    for (ia, name) in ma.iter().enumerate() {
        let Some(ib) = mb.iter().position(|n| n == name) else {
            continue;
        };
        let mut d = MetricDifference {
            metric: name.clone(),
            largest: 0.0,
            relative: 0.0,
            at: None,
            compared: 0,
            defined_in_one: 0,
        };
        for (ra, rb) in &pairs {
            match (ra.metrics[ia], rb.metrics[ib]) {
                (Some(x), Some(y)) => {
                    d.compared += 1;
                    let diff = (x - y).abs();
                    if diff > d.largest || (d.at.is_none() && diff.is_nan()) {
                        d.largest = diff;
                        let scale = x.abs().max(y.abs());
                        d.relative = if scale > 0.0 { diff / scale } else { 0.0 };
                        d.at = Some((ra.index, ra.values.clone()));
                    }
                }
                (None, None) => {}
                _ => d.defined_in_one += 1,
            }
        }
        metrics.push(d);
    }
    let only = |x: &[String], y: &[String]| -> Vec<String> {
        x.iter().filter(|n| !y.contains(n)).cloned().collect()
    };
    let status_differs = pairs
        .iter()
        .filter(|(ra, rb)| ra.status != rb.status)
        .map(|(ra, _)| ra.index)
        .collect();
    Ok(SweepDiff {
        axes,
        points: pairs.len() as u64,
        metrics,
        only_in_first: only(&ma, &mb),
        only_in_second: only(&mb, &ma),
        status_differs,
    })
}

/// The rows of the points both `a` and `b` hold (each in index order), paired.
fn shared_points<'a>(a: &'a [PointRow], b: &'a [PointRow]) -> Vec<(&'a PointRow, &'a PointRow)> {
    let (mut i, mut j) = (0, 0);
    let mut out = Vec::with_capacity(a.len().min(b.len()));
    while i < a.len() && j < b.len() {
        match a[i].index.cmp(&b[j].index) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                out.push((&a[i], &b[j]));
                i += 1;
                j += 1;
            }
        }
    }
    out
}

/// `name = value` pairs of a point, for messages.
#[must_use]
pub fn format_point(axes: &[String], values: &[f64]) -> String {
    axes.iter()
        .zip(values)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}
