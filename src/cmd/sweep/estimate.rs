//! The estimated time of a large sweep, printed before it starts: a few of its points, spread
//! over the grid, are computed on one thread and timed; the estimate is the points left over
//! the sampled rate times the worker threads. An 81-million-point sweep says "about 22 h"
//! before it runs for a day, on a terminal and in a batch log alike.

use std::time::{Duration, Instant};

use tumble_studies::sweep::{self, Shard, SweepDefinition};

/// Sweeps of fewer points than this start without an estimate (they take seconds).
pub const LARGE: u64 = 200;

/// The sample stops after this many points…
const SAMPLE_POINTS: u64 = 16;

/// …or once it has taken this long.
const SAMPLE_TIME: Duration = Duration::from_millis(500);

/// A sampled estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Points the run computes at most (the shard's size).
    pub points: u64,
    /// Points sampled.
    pub sampled: u64,
    /// Time the sample took.
    pub sample_seconds: f64,
    /// Estimated wall time of the whole run, in seconds.
    pub seconds: f64,
}

/// Samples `def`'s points in `shard` (evenly spread over the shard's points) and estimates the
/// run's time on `threads` workers; `None` for a sweep of fewer than [`LARGE`] points.
#[must_use]
pub fn estimate(def: &SweepDefinition, shard: Shard, threads: usize) -> Option<Estimate> {
    let total = def.points();
    let points = shard.size(total);
    if points < LARGE {
        return None;
    }
    let start = Instant::now();
    let mut sampled = 0;
    while sampled < SAMPLE_POINTS && (sampled == 0 || start.elapsed() < SAMPLE_TIME) {
        // The k-th of the shard's points, k spread evenly over them.
        let k = (sampled * points) / SAMPLE_POINTS;
        let index = (shard.index - 1) + k * shard.count;
        let _ = sweep::run_point(def, index.min(total - 1));
        sampled += 1;
    }
    let sample_seconds = start.elapsed().as_secs_f64();
    let per_point = sample_seconds / sampled as f64;
    Some(Estimate {
        points,
        sampled,
        sample_seconds,
        seconds: per_point * points as f64 / threads.max(1) as f64,
    })
}

/// `estimate     about 2 h 05 min for 81000000 points on 2 threads (16 points sampled in
/// 0.41 s; a resumed run computes only the points left)`.
#[must_use]
pub fn line(e: &Estimate, threads: usize) -> String {
    format!(
        "estimate     about {} for {} points on {threads} thread{} ({} points sampled in \
         {:.2} s; a resumed run computes only the points left)",
        super::progress::duration(e.seconds),
        e.points,
        if threads == 1 { "" } else { "s" },
        e.sampled,
        e.sample_seconds
    )
}
