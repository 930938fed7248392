//! Adaptive refinement of a grid sweep: start from a coarse grid and split the cells where a
//! metric changes by more than a threshold between neighbouring points, level by level.
//!
//! # The lattice
//!
//! A refined sweep's axes define its finest grid exactly as a uniform sweep's do, and every
//! point it computes is a point of that grid, with the same index and the same axis values: a
//! refined sweep's numbers at a point are those of the uniform sweep, bit for bit. With
//! `levels = L`, the coarse grid takes every `2ᴸ`-th value of each axis and its last value;
//! its cells are the boxes between neighbouring coarse values (the last one along an axis may
//! be shorter). Refining a cell bisects each of its sides that spans two or more grid steps at
//! `lo + ⌊(hi − lo)/2⌋`, giving up to `2ᵈ` children (`d` axes); after `L` levels a cell split
//! every time spans one grid step along every axis: the finest grid's own resolution.
//!
//! A cell is split when the chosen metric's values at its `2ᵈ` corners spread (largest minus
//! smallest) by more than the threshold, or when it is defined at some corners and not at
//! others (a failed point, a threshold crossed at some corners only).
//!
//! # Determinism
//!
//! Whether a cell is split depends on its own corners only, so the points under a coarse cell
//! depend on nothing outside it: a refined sweep is the union of its coarse cells' refinements.
//! Points are results of their index alone, so the set of points, each point's level and its
//! row are the same whatever the threads, interruptions and resumptions. A shard `K/N` of a
//! refined sweep refines the coarse cells numbered `c` (last axis fastest) with
//! `c mod N = K − 1`; a point on the face between two shards' cells may be computed by both,
//! with the same row, and a merge keeps it once.
//!
//! A point's level is the refinement level that first needs it: `0` for the coarse grid, and
//! for the others the largest, over the axes, of the bisection depth at which the point's grid
//! index along that axis first becomes a cell boundary — a function of the index alone.

use std::collections::{BTreeMap, BTreeSet};

use super::Shard;
use super::definition::{Sampling, SweepDefinition};
use super::file_error::{Origin, SweepFileError};
use super::journal::{PointRow, Status};
use super::metrics::Metric;
use super::value::{Num, Src};

/// Most refinement levels: `2¹⁶` grid steps to a coarse cell.
pub const MAX_LEVELS: u32 = 16;

/// How a grid sweep is refined (`[refine]` in a sweep file).
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// Levels of bisection from the coarse grid to the finest (≥ 1).
    pub levels: u32,
    /// The metric whose change splits a cell (one the sweep records).
    pub metric: Metric,
    /// A cell whose corners' values of the metric spread by more than this is split.
    pub threshold: f64,
}

/// A box of grid indices `lo[j] ≤ k ≤ hi[j]` along each axis `j`.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Cell {
    lo: Vec<u64>,
    hi: Vec<u64>,
}

/// The finest grid of a refined sweep and its coarse stride.
#[derive(Debug, Clone)]
pub(crate) struct Lattice {
    counts: Vec<u64>,
    stride: u64,
    levels: u32,
    metric: usize,
    threshold: f64,
}

impl Lattice {
    /// The lattice of `def`; `None` when it is not a refined grid sweep.
    pub(crate) fn of(def: &SweepDefinition) -> Option<Self> {
        let refine = def.refine.as_ref()?;
        if def.sampling != Sampling::Grid {
            return None;
        }
        Some(Lattice {
            counts: def.axes.iter().map(|a| a.count().unwrap_or(1)).collect(),
            stride: 1u64 << refine.levels,
            levels: refine.levels,
            metric: def.metrics.iter().position(|m| *m == refine.metric)?,
            threshold: refine.threshold,
        })
    }

    /// The point index of grid indices `k` (last axis fastest).
    fn index(&self, k: &[u64]) -> u64 {
        k.iter()
            .zip(&self.counts)
            .fold(0, |acc, (&k, &n)| acc * n + k)
    }

    /// The grid indices of point `index`.
    fn coords(&self, mut index: u64) -> Vec<u64> {
        let mut out = vec![0; self.counts.len()];
        for (k, &n) in self.counts.iter().enumerate().rev() {
            out[k] = index % n.max(1);
            index /= n.max(1);
        }
        out
    }

    /// The bisection depth at which grid index `c` of an axis of `n` values becomes a cell
    /// boundary (0: a coarse value).
    fn depth(&self, n: u64, c: u64) -> u32 {
        if c.is_multiple_of(self.stride) || c + 1 >= n {
            return 0;
        }
        let mut lo = c / self.stride * self.stride;
        let mut hi = (lo + self.stride).min(n - 1);
        let mut depth = 1;
        loop {
            let mid = lo + (hi - lo) / 2;
            if c == mid {
                return depth;
            }
            if c < mid {
                hi = mid;
            } else {
                lo = mid;
            }
            depth += 1;
        }
    }

    /// The refinement level of point `index`: the largest depth of its grid indices.
    pub(crate) fn level(&self, index: u64) -> u32 {
        let coords = self.coords(index);
        coords
            .iter()
            .zip(&self.counts)
            .map(|(&c, &n)| self.depth(n, c))
            .max()
            .unwrap_or(0)
    }

    /// Coarse intervals along an axis of `n` values: `[k s, min((k + 1) s, n − 1)]`.
    fn intervals(&self, n: u64) -> u64 {
        if n <= 1 {
            1
        } else {
            (n - 1).div_ceil(self.stride)
        }
    }

    /// Number of coarse cells.
    pub(crate) fn coarse_cells(&self) -> u64 {
        self.counts
            .iter()
            .map(|&n| self.intervals(n))
            .fold(1u64, u64::saturating_mul)
    }

    /// Coarse cell number `c` (last axis fastest).
    fn coarse_cell(&self, mut c: u64) -> Cell {
        let d = self.counts.len();
        let (mut lo, mut hi) = (vec![0; d], vec![0; d]);
        for (j, &n) in self.counts.iter().enumerate().rev() {
            let m = self.intervals(n);
            let k = c % m;
            c /= m;
            lo[j] = (k * self.stride).min(n.saturating_sub(1));
            hi[j] = ((k + 1) * self.stride).min(n.saturating_sub(1));
        }
        Cell { lo, hi }
    }

    /// The point indices of the corners of `cell` (each once).
    fn corners(&self, cell: &Cell, out: &mut BTreeSet<u64>) {
        let d = cell.lo.len();
        let mut k = vec![0; d];
        for mask in 0..(1u64 << d) {
            for j in 0..d {
                k[j] = if mask & (1 << j) == 0 {
                    cell.lo[j]
                } else {
                    cell.hi[j]
                };
            }
            out.insert(self.index(&k));
        }
    }

    /// Whether `cell` is split: its corners' metric spreads by more than the threshold, or
    /// is defined at some corners only. Every corner must be in `rows`.
    fn splits(&self, cell: &Cell, rows: &BTreeMap<u64, PointRow>) -> bool {
        let mut corners = BTreeSet::new();
        self.corners(cell, &mut corners);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut defined, mut undefined) = (false, false);
        for index in corners {
            match rows
                .get(&index)
                .filter(|r| r.status == Status::Ok)
                .and_then(|r| r.metrics.get(self.metric).copied().flatten())
            {
                Some(x) => {
                    defined = true;
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
                None => undefined = true,
            }
        }
        defined && (undefined || hi - lo > self.threshold)
    }

    /// The children of `cell`: each side spanning two or more grid steps bisected; none when
    /// every side spans one step or less.
    fn children(cell: &Cell, out: &mut Vec<Cell>) {
        let d = cell.lo.len();
        let halves: Vec<Vec<(u64, u64)>> = (0..d)
            .map(|j| {
                let (lo, hi) = (cell.lo[j], cell.hi[j]);
                if hi - lo >= 2 {
                    let mid = lo + (hi - lo) / 2;
                    vec![(lo, mid), (mid, hi)]
                } else {
                    vec![(lo, hi)]
                }
            })
            .collect();
        if halves.iter().all(|h| h.len() == 1) {
            return;
        }
        let total: usize = halves.iter().map(Vec::len).product();
        for mut m in 0..total {
            let (mut lo, mut hi) = (vec![0; d], vec![0; d]);
            for j in (0..d).rev() {
                let (a, b) = halves[j][m % halves[j].len()];
                m /= halves[j].len();
                lo[j] = a;
                hi[j] = b;
            }
            out.push(Cell { lo, hi });
        }
    }
}

/// The number of points of each refinement level among `rows` (index 0: the coarse grid);
/// `None` for a sweep that is not refined.
#[must_use]
pub fn points_by_level(def: &SweepDefinition, rows: &[PointRow]) -> Option<Vec<u64>> {
    let lattice = Lattice::of(def)?;
    let mut counts = vec![0; lattice.levels as usize + 1];
    for row in rows {
        let level = lattice.level(row.index) as usize;
        if let Some(c) = counts.get_mut(level) {
            *c += 1;
        }
    }
    Some(counts)
}

/// How far a walk of the refinement got.
#[derive(Debug, Clone, Default)]
pub(crate) struct Walk {
    /// Every point the walk needed (the refinement's points when it is complete).
    pub needed: BTreeSet<u64>,
    /// Whether every level was done (every needed point is in the rows).
    pub complete: bool,
}

/// Computes (or looks up) the points a level lacks: `(missing, points needed so far, rows)`.
pub(crate) type Fill<'a, E> =
    dyn FnMut(&[u64], u64, &mut BTreeMap<u64, PointRow>) -> Result<(), E> + 'a;

/// Walks the refinement of the coarse cells of `shard`, level by level. At each level the
/// points the cells need and `rows` lacks are handed to `fill`, which adds what it can to
/// `rows` (its second argument: every point needed so far); the walk stops, incomplete, at the
/// first level whose points `fill` leaves missing (a cancelled run, or a merge checking a
/// shard's journal with a `fill` that adds nothing).
///
/// # Errors
/// Whatever `fill` returns.
pub(crate) fn walk<E>(
    lattice: &Lattice,
    shard: Shard,
    rows: &mut BTreeMap<u64, PointRow>,
    fill: &mut Fill<'_, E>,
) -> Result<Walk, E> {
    let mut cells: Vec<Cell> = (0..lattice.coarse_cells())
        .filter(|&c| shard.contains(c))
        .map(|c| lattice.coarse_cell(c))
        .collect();
    let mut needed = BTreeSet::new();
    for level in 0..=lattice.levels {
        let mut points = BTreeSet::new();
        for cell in &cells {
            lattice.corners(cell, &mut points);
        }
        let missing: Vec<u64> = points
            .iter()
            .copied()
            .filter(|i| !rows.contains_key(i))
            .collect();
        needed.extend(points);
        if !missing.is_empty() {
            fill(&missing, needed.len() as u64, rows)?;
            if missing.iter().any(|i| !rows.contains_key(i)) {
                return Ok(Walk {
                    needed,
                    complete: false,
                });
            }
        }
        if level == lattice.levels {
            break;
        }
        let mut next = Vec::new();
        for cell in cells.iter().filter(|c| lattice.splits(c, rows)) {
            Lattice::children(cell, &mut next);
        }
        if next.is_empty() {
            break;
        }
        cells = next;
    }
    Ok(Walk {
        needed,
        complete: true,
    })
}

/// The `[refine]` table of a sweep-file draft (or `--set refine.*`/`--refine`).
#[derive(Debug, Clone)]
pub(super) struct DraftRefine {
    pub(super) at: Origin,
    pub(super) levels: Option<Src<Num>>,
    pub(super) metric: Option<Src<String>>,
    pub(super) threshold: Option<Src<Num>>,
}

impl DraftRefine {
    /// Validates the table against the sweep's sampling and metrics; `None` for `levels = 0`
    /// (no refinement: a uniform grid).
    pub(super) fn validate(
        &self,
        sampling: Sampling,
        metrics: &[Metric],
    ) -> Result<Option<Refinement>, SweepFileError> {
        let invalid = |at: &Origin, key: &str, reason: String| SweepFileError::Invalid {
            at: at.clone(),
            key: key.into(),
            reason,
        };
        let levels = match &self.levels {
            None => {
                return Err(invalid(
                    &self.at,
                    "refine.levels",
                    "missing: how many levels to refine (0 for none)".into(),
                ));
            }
            Some(v) => v.whole("refine.levels", 0, "a whole number >= 0")?,
        };
        if levels > u64::from(MAX_LEVELS) {
            let at = self.levels.as_ref().map_or(&self.at, |v| &v.at);
            return Err(invalid(
                at,
                "refine.levels",
                format!("{levels}: at most {MAX_LEVELS} levels"),
            ));
        }
        let metric = match &self.metric {
            None => metrics.first().cloned().ok_or_else(|| {
                invalid(&self.at, "refine.metric", "no metric to refine by".into())
            })?,
            Some(name) => {
                let m = Metric::parse(&name.value)
                    .map_err(|reason| invalid(&name.at, "refine.metric", reason))?;
                if !metrics.contains(&m) {
                    let names: Vec<String> = metrics.iter().map(Metric::name).collect();
                    return Err(invalid(
                        &name.at,
                        "refine.metric",
                        format!(
                            "`{}` is not recorded by this sweep; metrics.record lists: {}",
                            name.value,
                            names.join(", ")
                        ),
                    ));
                }
                m
            }
        };
        let threshold = match &self.threshold {
            None => {
                return Err(invalid(
                    &self.at,
                    "refine.threshold",
                    format!(
                        "missing: the change of `{metric}` between neighbouring points above \
                         which a cell is split"
                    ),
                ));
            }
            Some(v) => {
                let x = v.float("refine.threshold")?;
                if !(x.is_finite() && x > 0.0) {
                    return Err(invalid(
                        &v.at,
                        "refine.threshold",
                        format!("{x}: the threshold must be finite and positive"),
                    ));
                }
                x
            }
        };
        if levels == 0 {
            return Ok(None);
        }
        if sampling != Sampling::Grid {
            return Err(invalid(
                &self.at,
                "refine",
                "refinement splits the cells of a grid; a sweep of random samples has none".into(),
            ));
        }
        Ok(Some(Refinement {
            levels: u32::try_from(levels).unwrap_or(MAX_LEVELS),
            metric,
            threshold,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(counts: &[u64], levels: u32) -> Lattice {
        Lattice {
            counts: counts.to_vec(),
            stride: 1 << levels,
            levels,
            metric: 0,
            threshold: 0.5,
        }
    }

    fn row(index: u64, value: f64) -> PointRow {
        PointRow {
            index,
            values: Vec::new(),
            metrics: vec![Some(value)],
            status: Status::Ok,
            reason: String::new(),
        }
    }

    /// Walks with rows from `f` of the grid indices.
    fn walk_with(l: &Lattice, shard: Shard, f: &dyn Fn(&[u64]) -> f64) -> BTreeSet<u64> {
        let mut rows = BTreeMap::new();
        let w = walk::<()>(l, shard, &mut rows, &mut |missing, _, rows| {
            for &i in missing {
                rows.insert(i, row(i, f(&l.coords(i))));
            }
            Ok(())
        })
        .unwrap();
        assert!(w.complete);
        assert_eq!(w.needed, rows.keys().copied().collect());
        w.needed
    }

    #[test]
    fn depths_bisect_each_coarse_interval_down_to_one_step() {
        // 11 values, stride 4: coarse 0, 4, 8, 10; depth 1 at 2, 6, 9; depth 2 at 1, 3, 5, 7.
        let l = lattice(&[11], 2);
        let depths: Vec<u32> = (0..11).map(|c| l.depth(11, c)).collect();
        assert_eq!(depths, [0, 2, 1, 2, 0, 2, 1, 2, 0, 1, 0]);
    }

    #[test]
    fn a_metric_that_never_changes_keeps_the_coarse_grid_and_a_jump_everywhere_reaches_every_point()
    {
        let l = lattice(&[11, 7], 2);
        let flat = walk_with(&l, Shard::ALL, &|_| 1.0);
        // Coarse values: 0, 4, 8, 10 and 0, 4, 6.
        assert_eq!(flat.len(), 4 * 3);
        assert!(flat.iter().all(|&i| l.level(i) == 0));
        let wild = walk_with(&l, Shard::ALL, &|k| (k[0] * 7 + k[1]) as f64);
        assert_eq!(wild.len(), 11 * 7);
    }

    #[test]
    fn a_step_is_refined_to_the_finest_grid_along_its_edge_only() {
        // A jump across x = 5.5 on a 33 x 33 grid with 3 levels: the finest resolution along
        // the jump, coarse elsewhere.
        let l = lattice(&[33, 33], 3);
        let points = walk_with(&l, Shard::ALL, &|k| if k[0] <= 5 { 0.0 } else { 1.0 });
        // Every point of the two finest columns either side of the jump.
        for y in 0..33 {
            assert!(points.contains(&l.index(&[5, y])), "(5, {y})");
            assert!(points.contains(&l.index(&[6, y])), "(6, {y})");
        }
        // Far from it, only the coarse grid.
        assert!(points.iter().all(|&i| {
            let k = l.coords(i);
            k[0] <= 8 || l.level(i) == 0
        }));
        assert!(points.len() < 33 * 33 / 3, "{}", points.len());
    }

    #[test]
    fn a_point_s_level_is_the_level_whose_walk_first_needs_it() {
        let l = lattice(&[19, 12], 3);
        let f = |k: &[u64]| ((k[0] as f64 * 0.7).sin() + (k[1] as f64 * 0.3).cos()) * 2.0;
        let mut rows = BTreeMap::new();
        let mut first_need = BTreeMap::new();
        let mut level = 0;
        walk::<()>(&l, Shard::ALL, &mut rows, &mut |missing, _, rows| {
            for &i in missing {
                rows.insert(i, row(i, f(&l.coords(i))));
                first_need.insert(i, level);
            }
            level += 1;
            Ok(())
        })
        .unwrap();
        assert!(first_need.len() > 4 * 3);
        for (i, needed_at) in first_need {
            assert_eq!(l.level(i), needed_at, "point {i} at {:?}", l.coords(i));
        }
    }

    #[test]
    fn shards_refine_disjoint_coarse_cells_whose_union_is_the_whole_refinement() {
        let l = lattice(&[23, 17], 2);
        let f = |k: &[u64]| {
            if k[0] * k[0] + 2 * k[1] * k[1] < 300 {
                0.0
            } else {
                1.0
            }
        };
        let all = walk_with(&l, Shard::ALL, &f);
        for n in [2, 3, 5] {
            let mut union = BTreeSet::new();
            for k in 1..=n {
                union.extend(walk_with(&l, Shard::new(k, n).unwrap(), &f));
            }
            assert_eq!(union, all, "{n} shards");
        }
    }

    #[test]
    fn a_fill_that_adds_nothing_stops_the_walk_incomplete() {
        let l = lattice(&[9, 9], 2);
        let mut rows = BTreeMap::new();
        let w = walk::<()>(&l, Shard::ALL, &mut rows, &mut |_, _, _| Ok(())).unwrap();
        assert!(!w.complete);
        assert_eq!(w.needed.len(), 9);
    }

    #[test]
    fn failed_corners_next_to_defined_ones_split_their_cells() {
        let l = lattice(&[9], 2);
        let mut rows = BTreeMap::new();
        let w = walk::<()>(&l, Shard::ALL, &mut rows, &mut |missing, _, rows| {
            for &i in missing {
                let mut r = row(i, 0.0);
                if i == 8 {
                    r.status = Status::Failed;
                    r.metrics = vec![None];
                }
                rows.insert(i, r);
            }
            Ok(())
        })
        .unwrap();
        // Cell [4, 8] splits down to [7, 8]; cell [0, 4] stays.
        assert_eq!(w.needed.into_iter().collect::<Vec<_>>(), [0, 4, 6, 7, 8]);
    }
}
