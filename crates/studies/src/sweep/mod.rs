//! Parameter sweeps: one scene run at many points of its parameter space, in parallel, each
//! point reduced to a few metrics while it integrates.
//!
//! # Sweep files
//!
//! ```toml
//! scene = "free-hoop"            # a built-in scene (`tumble scenes`)
//!
//! [parameters]                   # fixed values; any left out keeps the scene's default
//! g = 9.81
//! a = 1.0
//!
//! [run]                          # integrator, step (or tol for dp5/dop853), horizon;
//! integrator = "gauss8"          # each defaults to the scene's own
//! dt = 0.01
//! t_end = 10.0
//!
//! [[axes]]                       # one table per swept parameter, in this order
//! parameter = "omega0"
//! range = [0.5, 8.0]             # start < end, both valid values of the parameter
//! count = 76                     # grid values, ends included (>= 2)
//! spacing = "linear"             # or "log" (equal ratios; positive range); default linear
//!
//! [[axes]]
//! parameter = "alpha0"
//! values = [0.25, 0.5, 1.0]      # or list the values
//!
//! # [random]                     # instead of a grid: draw `samples` points in the ranges
//! # samples = 1000               # (no `count`, no `values`; "log" draws log-uniformly)
//! # seed = 42
//!
//! [metrics]
//! record = ["max_tilt", "final_tilt", "time_tilt_exceeds", "max_energy_rel_err"]
//! tilt_threshold = 0.5           # rad; needed by (and only by) time_tilt_exceeds
//!
//! # [refine]                     # adaptive refinement of a grid (see `refine`)
//! # levels = 3                   # start from every 8th value; 0: the whole grid
//! # metric = "max_tilt"          # one of the recorded metrics (default: the first)
//! # threshold = 0.04             # split a cell whose corners spread by more than this
//! ```
//!
//! Metrics ([`Metric`]): `max_tilt`, `final_tilt`, `time_tilt_exceeds` (hoop scenes, which
//! have a `tilt` column), `max_energy_rel_err` (every scene), `flips` (`free-body`,
//! `dzhanibekov`). Without `record`, every applicable metric but `time_tilt_exceeds`.
//!
//! Everything is checked before the first point runs: TOML syntax, unknown keys, the scene,
//! unknown parameters and values outside their domain (every axis value, and both ends of
//! every range), a parameter both fixed and swept, an axis given twice, ranges that do not
//! increase, counts below 2, log spacing of a non-positive range, the run options against the
//! scene and integrator, unknown or inapplicable metrics, a missing or useless threshold.
//! Each error is a [`SweepFileError`] naming the key and its `file:line:column`, or the
//! `--set` override ([`Override`]) that set it.
//!
//! # Points
//!
//! A grid's points are every combination of the axes' values, numbered with the **last axis
//! varying fastest**. Random samples draw axis `j` of point `i` from the `(i d + j)`-th output
//! of SplitMix64 ([`definition::splitmix64`]) — a point's values depend on its index alone.
//! A point is the scene run once with the fixed parameters and its axis values, from `t = 0`
//! to `t_end` with the given integrator and step; it is deterministic, so results do not
//! depend on threads, shards or resumption.
//!
//! # Running
//!
//! [`run`] computes the points of a [`Shard`] (`K/N`: the indices `i` with
//! `i mod N = K − 1`) that a folder's journal does not hold yet, on a rayon pool of the
//! requested size; each finished point's row is appended to the journal (flushed every 16
//! rows or 2 s), so an interrupted sweep resumes without redoing finished points. A point that
//! fails — a typed error, a non-finite state, a panic (caught with `catch_unwind`) — has its
//! status and reason in its row, and the sweep goes on. [`results_csv`] gives `results.csv`:
//! one row per point in index order (`index`, axis values, metrics, `status`, `reason`),
//! identical byte for byte whatever the threads, interruptions or shards. [`merge`] joins the
//! folders of the `N` shards of a sweep into the folder an unsharded run writes.
//! Each run on a folder appends a line to its compute record ([`compute`]: host, threads,
//! wall time, points computed and failed) when it ends, completed or stopped; a merge
//! gathers the records of its shards. The folder's `manifest.json` is one type,
//! [`record::SweepRecord`], written by `tumble sweep` and read back as the same type.
//!
//! The library never prints: progress goes to a callback, cancellation comes in through an
//! `AtomicBool`.

pub mod check;
mod column;
pub mod compare;
pub mod compute;
pub mod definition;
mod draft;
mod engine;
pub mod file_error;
pub mod journal;
pub mod merge;
pub mod metrics;
mod overrides;
mod raw;
pub mod record;
pub mod refine;
pub mod resolution;
mod value;

use std::fmt;
use std::path::PathBuf;

pub use check::{
    CheckReport, CheckSize, MetricChange, check_points, check_points_among, check_sweep, looser,
    most_sensitive, screen, screens, self_check,
};
pub use compare::{MetricDifference, SweepDiff, diff, diff_folders, read_folder};
pub use compute::{COMPUTE, ComputeRecord, ComputeRun, ComputeTotals};
pub use definition::{Axis, AxisValues, Sampling, Spacing, SweepDefinition};
pub use engine::{Progress, RunConfig, SweepReport, run, run_point};
pub use file_error::{Origin, SweepFileError};
pub use journal::{DEFINITION, JOURNAL, PointRow, RESULTS, Status, results_csv, results_table};
pub use merge::{Unfinished, UnfinishedShard, merge};
pub use metrics::{ColumnOp, Metric};
pub use overrides::{Override, OverrideValue};
pub use refine::Refinement;
pub use resolution::{CoarsestPoint, coarsest_point};

/// The built-in hoop-tilt map (`tumble sweep` without a file): how far the free hoop tilts
/// against its initial spin and the bead's starting angle. See the file for the choices.
pub const TILT_MAP: &str = include_str!("tilt-map.sweep.toml");

/// One of `count` deterministic parts of a sweep: the points `i` with
/// `i mod count = index − 1` (`1 ≤ index ≤ count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Shard {
    /// 1-based part number `K`.
    pub index: u64,
    /// Number of parts `N`.
    pub count: u64,
}

impl Shard {
    /// The whole sweep, `1/1`.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Part `index` of `count`.
    ///
    /// # Errors
    /// [`SweepError::Shard`] unless `1 ≤ index ≤ count`.
    pub fn new(index: u64, count: u64) -> Result<Self, SweepError> {
        if count >= 1 && (1..=count).contains(&index) {
            Ok(Shard { index, count })
        } else {
            Err(SweepError::Shard {
                spec: format!("{index}/{count}"),
                reason: "K/N needs 1 <= K <= N".into(),
            })
        }
    }

    /// Parses `K/N`.
    ///
    /// # Errors
    /// [`SweepError::Shard`] for anything but two whole numbers with `1 ≤ K ≤ N`.
    pub fn parse(spec: &str) -> Result<Self, SweepError> {
        let bad = |reason: &str| SweepError::Shard {
            spec: spec.to_string(),
            reason: reason.to_string(),
        };
        let (k, n) = spec
            .split_once('/')
            .ok_or_else(|| bad("expected K/N, e.g. 2/8"))?;
        let k = k
            .trim()
            .parse()
            .map_err(|_| bad("K is not a whole number"))?;
        let n = n
            .trim()
            .parse()
            .map_err(|_| bad("N is not a whole number"))?;
        Shard::new(k, n)
    }

    /// Whether point `index` belongs to this shard.
    #[must_use]
    pub fn contains(self, index: u64) -> bool {
        index % self.count == self.index - 1
    }

    /// Number of this shard's points among `points`.
    #[must_use]
    pub fn size(self, points: u64) -> u64 {
        let k = self.index - 1;
        if points > k {
            (points - k).div_ceil(self.count)
        } else {
            0
        }
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What can go wrong when a sweep runs or shards are merged (a point's own failure is not an
/// error: it is recorded in its row).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// The definition is invalid.
    #[error(transparent)]
    Definition(#[from] SweepFileError),
    /// A file of the sweep folder could not be read or written.
    #[error("{}: {what}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was being done.
        what: &'static str,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file of the sweep folder is not a file that can be written.
    #[error(transparent)]
    Output(#[from] tumble_output::OutputError),
    /// The folder already holds a sweep and `--resume` was not asked for.
    #[error(
        "{}: the folder already holds a sweep ({}); pass --resume to continue it, or choose \
         another output folder",
        dir.display(),
        found
    )]
    Exists {
        /// The folder.
        dir: PathBuf,
        /// The file found.
        found: &'static str,
    },
    /// `--resume` of a folder whose results are there but whose journal is gone.
    #[error(
        "{}: cannot resume: the folder holds results.csv but no journal.csv to resume from; \
         choose another output folder",
        dir.display()
    )]
    NoJournal {
        /// The folder.
        dir: PathBuf,
    },
    /// The folder's sweep is not this one.
    #[error("{}: the folder holds a different sweep: {reason}", dir.display())]
    DifferentSweep {
        /// The folder.
        dir: PathBuf,
        /// What differs.
        reason: String,
    },
    /// The journal is damaged beyond a torn last line.
    #[error("{}:{line}: damaged journal: {reason}", path.display())]
    Journal {
        /// The journal.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// The compute record is damaged beyond a torn last line.
    #[error("{}:{line}: damaged compute record: {reason}", path.display())]
    Compute {
        /// The record.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// An invalid `--shard K/N`, or a folder written for another shard.
    #[error("shard {spec}: {reason}")]
    Shard {
        /// As given.
        spec: String,
        /// What is wrong.
        reason: String,
    },
    /// The self-check could not run.
    #[error("self-check: {0}")]
    SelfCheck(String),
    /// Shard folders that do not make one sweep.
    #[error("merge: {0}")]
    Merge(String),
    /// Two sweeps that cannot be compared point by point.
    #[error("diff: {0}")]
    Compare(String),
    /// Shards of the sweep are missing or incomplete.
    #[error("merge: {0}")]
    Unfinished(Unfinished),
    /// The CSV writer failed (in memory; not expected).
    #[error("CSV: {0}")]
    Csv(String),
    /// The worker threads could not be started.
    #[error("cannot start {threads} worker threads: {reason}")]
    Threads {
        /// Requested.
        threads: usize,
        /// Why not.
        reason: String,
    },
}

#[cfg(test)]
mod tests;
