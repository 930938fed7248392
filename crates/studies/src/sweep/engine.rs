//! Running a sweep's points in parallel into a folder's journal, resuming, merging shards.

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::compute::{ComputeRecord, ComputeRun};
use super::definition::SweepDefinition;
use super::journal::{self, DEFINITION, JOURNAL, PointRow, RESULTS, Status};
use super::metrics::{Metric, MetricRecorder};
use super::refine::{self, Lattice};
use super::{Shard, SweepError};
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{TiltLanes, TiltRun};

/// How to run a sweep.
#[derive(Debug, Clone, Copy)]
pub struct RunConfig<'a> {
    /// Worker threads (≥ 1).
    pub threads: usize,
    /// The part of the sweep to run.
    pub shard: Shard,
    /// Continue the sweep the folder holds (or start it if there is none).
    pub resume: bool,
    /// Set to stop starting new points; the run then returns what finished, incomplete.
    pub cancel: Option<&'a AtomicBool>,
}

impl Default for RunConfig<'_> {
    fn default() -> Self {
        RunConfig {
            threads: 1,
            shard: Shard::ALL,
            resume: false,
            cancel: None,
        }
    }
}

/// Where a sweep stands, after each finished point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Points in this shard.
    pub total: u64,
    /// Points finished (resumed from the journal included).
    pub finished: u64,
    /// Points found finished in the journal when the run started.
    pub resumed: u64,
    /// Points that failed or panicked so far.
    pub failed: u64,
}

/// What a run (or a merge) produced.
#[derive(Debug, Clone)]
pub struct SweepReport {
    /// Rows of the finished points of the shard, in index order.
    pub rows: Vec<PointRow>,
    /// The shard's points.
    pub total: u64,
    /// Points computed by this run.
    pub computed: u64,
    /// Points found finished in the journal.
    pub resumed: u64,
    /// Wall time of the computation (reading and writing the journal included).
    pub elapsed: Duration,
    /// Threads used.
    pub threads: usize,
    /// The compute record of the folder: every run on it, this one included (a merge: the
    /// runs of every shard).
    pub compute: ComputeRecord,
}

impl SweepReport {
    /// Whether every point of the shard has finished.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.rows.len() as u64 == self.total
    }

    /// The rows of points that failed or panicked.
    pub fn failures(&self) -> impl Iterator<Item = &PointRow> {
        self.rows.iter().filter(|r| r.status != Status::Ok)
    }

    /// Points computed per second of wall time by this run (`None` when it computed none).
    #[must_use]
    pub fn points_per_second(&self) -> Option<f64> {
        let s = self.elapsed.as_secs_f64();
        (self.computed > 0 && s > 0.0).then(|| self.computed as f64 / s)
    }
}

/// Computes point `index` of `def`: its row, whatever happens (failures and panics included).
#[must_use]
pub fn run_point(def: &SweepDefinition, index: u64) -> PointRow {
    let values = def.point(index);
    if let Some(lanes) = def.lanes() {
        return lane_rows(def, lanes, &[index]).remove(0);
    }
    guarded(index, values.clone(), def.metrics.len(), || {
        metrics_of(def, &values)
    })
}

/// Computes points `indices` of `def`, in order: together, several per instruction, where the
/// sweep runs the reduction's lanes ([`SweepDefinition::lanes`]), else one by one. Each row is
/// the one [`run_point`] gives for its point alone, bit for bit.
#[must_use]
pub fn run_points(def: &SweepDefinition, indices: &[u64]) -> Vec<PointRow> {
    match def.lanes() {
        Some(lanes) => indices
            .chunks(lanes.width.max(1))
            .flat_map(|chunk| lane_rows(def, lanes, chunk))
            .collect(),
        None => indices.iter().map(|&i| run_point(def, i)).collect(),
    }
}

/// The points' parameters: the sweep's with the axes at the point's values.
fn params_at(def: &SweepDefinition, values: &[f64]) -> Result<Params, String> {
    let mut params = def.params.clone();
    for (axis, &v) in def.axes.iter().zip(values) {
        params.set(axis.parameter, v).map_err(|e| e.to_string())?;
    }
    Ok(params)
}

/// The rows of `indices` run in `lanes` together. A panic in a batch runs its points again
/// one at a time, so that it marks only the point it comes from (the same row as alone).
fn lane_rows(def: &SweepDefinition, lanes: &TiltLanes, indices: &[u64]) -> Vec<PointRow> {
    let values: Vec<Vec<f64>> = indices.iter().map(|&i| def.point(i)).collect();
    let params: Vec<Result<Params, String>> = values.iter().map(|v| params_at(def, v)).collect();
    let ready: Vec<Params> = params
        .iter()
        .filter_map(|p| p.as_ref().ok().cloned())
        .collect();
    if let [index] = *indices {
        let values = values.into_iter().next().unwrap_or_default();
        return vec![guarded(index, values.clone(), def.metrics.len(), || {
            let params = params_at(def, &values)?;
            let run = (lanes.run)(&[params], &def.plan, def.tilt_threshold)
                .pop()
                .ok_or_else(|| "the map's lanes returned no run".to_string())?;
            run.map(|run| tilt_metrics(&def.metrics, &run))
                .map_err(|e| e.to_string())
        })];
    }
    let runs = catch_unwind(AssertUnwindSafe(|| {
        (lanes.run)(&ready, &def.plan, def.tilt_threshold)
    }));
    let Ok(runs) = runs else {
        return indices
            .iter()
            .flat_map(|&i| lane_rows(def, lanes, &[i]))
            .collect();
    };
    let mut runs = runs.into_iter();
    indices
        .iter()
        .zip(values)
        .zip(params)
        .map(|((&index, values), params)| {
            let result = match params {
                Err(e) => Err(e),
                Ok(_) => match runs.next() {
                    Some(Ok(run)) => Ok(tilt_metrics(&def.metrics, &run)),
                    Some(Err(e)) => Err(e.to_string()),
                    None => Err("the map's lanes returned fewer runs than points".to_string()),
                },
            };
            guarded(index, values, def.metrics.len(), || result)
        })
        .collect()
}

/// The sweep's metrics of a run of the lanes, in the sweep's order.
fn tilt_metrics(metrics: &[Metric], run: &TiltRun) -> Vec<Option<f64>> {
    metrics
        .iter()
        .map(|m| match m {
            Metric::MaxTilt => Some(run.max_tilt),
            Metric::FinalTilt => Some(run.final_tilt),
            Metric::TimeTiltExceeds => run.first_exceeds,
            Metric::MaxEnergyRelErr => Some(run.max_energy_rel_err),
            Metric::Column { .. } | Metric::Flips => None,
        })
        .collect()
}

/// The row of point `index` whose metrics `compute` returns: `failed` with its error, or
/// `panicked` with the panic's message when it panics.
pub(crate) fn guarded(
    index: u64,
    values: Vec<f64>,
    metrics: usize,
    compute: impl FnOnce() -> Result<Vec<Option<f64>>, String>,
) -> PointRow {
    let (metrics, status, reason) = match catch_unwind(AssertUnwindSafe(compute)) {
        Ok(Ok(values)) => (values, Status::Ok, String::new()),
        Ok(Err(reason)) => (vec![None; metrics], Status::Failed, reason),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic without a message".to_string());
            (
                vec![None; metrics],
                Status::Panicked,
                format!("panic: {message}"),
            )
        }
    };
    PointRow {
        index,
        values,
        metrics,
        status,
        reason,
    }
}

/// Runs the scene at `values` and reduces the run to the definition's metrics.
fn metrics_of(def: &SweepDefinition, values: &[f64]) -> Result<Vec<Option<f64>>, String> {
    let params = params_at(def, values)?;
    // The scene's reduction when it serves every metric, else the scene itself.
    let reduction = def.reduction();
    let columns = reduction.map_or_else(
        || def.scene.info().columns(),
        |r| r.columns.iter().map(|c| (*c).to_string()).collect(),
    );
    let mut recorder = MetricRecorder::new(
        def.scene,
        columns,
        &params,
        &def.metrics,
        def.tilt_threshold,
    )
    .map_err(|e| e.to_string())?;
    let summary = match reduction {
        Some(r) => (r.simulate)(&params, &def.plan, &mut recorder),
        None => def.scene.simulate(&params, &def.plan, &mut recorder),
    }
    .map_err(|e| e.to_string())?;
    if let Some(failure) = recorder.failure() {
        return Err(failure.to_string());
    }
    if !(summary.t >= def.plan.t_end || summary.terminated) {
        return Err(format!(
            "the run stopped at t = {} before the horizon t_end = {}",
            summary.t, def.plan.t_end
        ));
    }
    Ok(recorder.finish(&def.metrics, summary.max_energy_rel_err))
}

/// Computes the `count` points of `pending` on a pool of `threads` workers, `width` at a time
/// (consecutive indices of `pending`, handed to `compute` together), handing each row to
/// `sink` on the calling thread as soon as its batch is done. The indices are drawn from the
/// iterator as workers free up, never listed. Stops starting batches when `cancel` is set or
/// `sink` fails (whose error is returned).
fn execute(
    pending: impl Iterator<Item = u64> + Send,
    count: u64,
    threads: usize,
    width: usize,
    cancel: Option<&AtomicBool>,
    compute: &(dyn Fn(&[u64]) -> Vec<PointRow> + Sync),
    sink: &mut dyn FnMut(PointRow) -> Result<(), SweepError>,
) -> Result<(), SweepError> {
    let width = width.max(1);
    // No more workers than batches: `--threads 100000` on 6 points starts 6 (or 1 batch).
    let threads = clamp_threads(threads, count.div_ceil(width as u64));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("tumble-sweep-{i}"))
        .build()
        .map_err(|e| SweepError::Threads {
            threads,
            reason: e.to_string(),
        })?;
    let stop = AtomicBool::new(false);
    let stopped =
        || stop.load(Ordering::Relaxed) || cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let (tx, rx) = mpsc::channel::<PointRow>();
    let mut pending = pending;
    let batches = std::iter::from_fn(move || {
        let batch: Vec<u64> = pending.by_ref().take(width).collect();
        (!batch.is_empty()).then_some(batch)
    });
    std::thread::scope(|scope| {
        let stopped = &stopped;
        scope.spawn(move || {
            pool.install(|| {
                batches.par_bridge().for_each_with(tx, |tx, batch| {
                    if !stopped() {
                        for row in compute(&batch) {
                            // The receiver is gone only after an error; the point is dropped.
                            let _ = tx.send(row);
                        }
                    }
                });
            });
        });
        let mut result = Ok(());
        for row in rx {
            if let Err(e) = sink(row) {
                stop.store(true, Ordering::Relaxed);
                result = Err(e);
                break;
            }
        }
        result
    })
}

/// `threads` clamped to `1 ..= points`.
fn clamp_threads(threads: usize, points: u64) -> usize {
    threads.clamp(1, usize::try_from(points.max(1)).unwrap_or(usize::MAX))
}

/// Prepares `dir` for `def`: returns the journal writer and the rows already finished.
pub(crate) fn open_folder(
    def: &SweepDefinition,
    dir: &Path,
    shard: Shard,
    resume: bool,
) -> Result<(journal::Writer, BTreeMap<u64, PointRow>), SweepError> {
    std::fs::create_dir_all(dir).map_err(|source| SweepError::Io {
        path: dir.to_path_buf(),
        what: "cannot create the output folder",
        source,
    })?;
    let text = def.to_toml();
    let journal_path = dir.join(JOURNAL);
    let definition_path = dir.join(DEFINITION);
    if journal_path.exists() {
        if !resume {
            return Err(SweepError::Exists {
                dir: dir.to_path_buf(),
                found: JOURNAL,
            });
        }
        let stored =
            std::fs::read_to_string(&definition_path).map_err(|source| SweepError::Io {
                path: definition_path.clone(),
                what: "cannot read the sweep's definition",
                source,
            })?;
        if stored != text {
            return Err(SweepError::DifferentSweep {
                dir: dir.to_path_buf(),
                reason: first_difference(&stored, &text),
            });
        }
        let contents = journal::read(&journal_path, def, &text)?;
        if contents.shard != shard {
            return Err(SweepError::Shard {
                spec: shard.to_string(),
                reason: format!(
                    "{} holds shard {} of this sweep, not {shard}",
                    dir.display(),
                    contents.shard
                ),
            });
        }
        let writer = journal::Writer::append(&journal_path, contents.complete_len)?;
        return Ok((writer, contents.rows));
    }
    if dir.join(RESULTS).exists() {
        if resume {
            return Err(SweepError::NoJournal {
                dir: dir.to_path_buf(),
            });
        }
        return Err(SweepError::Exists {
            dir: dir.to_path_buf(),
            found: RESULTS,
        });
    }
    write_whole(&definition_path, text.as_bytes())?;
    // A fresh sweep starts a fresh compute record: none until its first run appends itself
    // (an old one is removed; a run stopped before it appends leaves none, not a bare header).
    match std::fs::remove_file(dir.join(super::compute::COMPUTE)) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(source) => {
            return Err(SweepError::Io {
                path: dir.join(super::compute::COMPUTE),
                what: "cannot remove the old compute record",
                source,
            });
        }
    }
    let writer = journal::Writer::create(&journal_path, def, &text, shard)?;
    Ok((writer, BTreeMap::new()))
}

/// Writes `bytes` to `path` whole or not at all (see [`tumble_output`]).
fn write_whole(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    tumble_output::Destination::check(path)?.write_all(bytes)?;
    Ok(())
}

/// The first line where two definition texts differ, for messages.
pub(crate) fn first_difference(stored: &str, new: &str) -> String {
    let (mut a, mut b) = (stored.lines(), new.lines());
    let mut line = 1;
    loop {
        match (a.next(), b.next()) {
            (Some(x), Some(y)) if x == y => line += 1,
            (x, y) => {
                return format!(
                    "its sweep.toml line {line} is `{}`, this sweep's is `{}`",
                    x.unwrap_or("(end)"),
                    y.unwrap_or("(end)")
                );
            }
        }
    }
}

/// Runs the points of `config.shard` of `def` that `dir`'s journal does not hold, appending
/// each row as it finishes; returns the shard's rows in index order.
///
/// Without `config.resume` the folder must not hold a sweep yet (`journal.csv` or
/// `results.csv`); with it, a folder that holds one must hold this one (same `sweep.toml`,
/// same shard), and a folder that holds none starts afresh. `progress` is called on the
/// calling thread after each finished point (and once at the start).
///
/// A refined sweep ([`super::refine`]) runs level by level: the shard's coarse cells, then the
/// points of the cells its results split, and so on; its total grows as levels are added, and
/// a stopped run resumes at the level it reached.
///
/// # Errors
/// The folder or journal cannot be written, holds another sweep or shard, or its journal is
/// damaged; the worker threads cannot be started. Failing points are not errors.
pub fn run(
    def: &SweepDefinition,
    dir: &Path,
    config: &RunConfig<'_>,
    progress: &mut dyn FnMut(&Progress),
) -> Result<SweepReport, SweepError> {
    let start = Instant::now();
    let (mut writer, mut rows) = open_folder(def, dir, config.shard, config.resume)?;
    let mut state = Progress {
        total: rows.len() as u64,
        finished: rows.len() as u64,
        resumed: rows.len() as u64,
        failed: rows.values().filter(|r| r.status != Status::Ok).count() as u64,
    };
    let mut tally = Tally::default();
    // Journals a finished point and counts it. A point that failed while the run was being
    // cancelled may have been cut short by the cancellation (a plan with a cancel flag stops
    // at a step): it is not a result, so it is dropped (`None`) and a resumed run computes it
    // again.
    let record = |row: PointRow,
                  state: &mut Progress,
                  tally: &mut Tally,
                  writer: &mut journal::Writer,
                  progress: &mut dyn FnMut(&Progress)|
     -> Result<Option<PointRow>, SweepError> {
        if row.status != Status::Ok && config.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Ok(None);
        }
        writer.push(def, &row)?;
        tally.computed += 1;
        state.finished += 1;
        if row.status != Status::Ok {
            state.failed += 1;
            tally.failed += 1;
        }
        progress(state);
        Ok(Some(row))
    };
    // Points per batch: the lanes' width where they serve the sweep.
    let width = def.lanes().map_or(1, |l| l.width);
    let (result, total) = if let Some(lattice) = Lattice::of(def) {
        // Level by level: each level's points depend on the previous levels' results.
        progress(&state);
        let walked = refine::walk(
            &lattice,
            config.shard,
            &mut rows,
            &mut |missing, needed, rows| {
                state.total = needed;
                progress(&state);
                tally.threads = tally
                    .threads
                    .max(clamp_threads(config.threads, missing.len() as u64));
                execute(
                    missing.iter().copied(),
                    missing.len() as u64,
                    config.threads,
                    width,
                    config.cancel,
                    &|indices| run_points(def, indices),
                    &mut |row| {
                        if let Some(row) =
                            record(row, &mut state, &mut tally, &mut writer, &mut *progress)?
                        {
                            rows.insert(row.index, row);
                        }
                        Ok(())
                    },
                )
            },
        );
        match walked {
            Ok(w) => {
                rows.retain(|i, _| w.needed.contains(i));
                (Ok(()), w.needed.len() as u64)
            }
            Err(e) => (Err(e), 0),
        }
    } else {
        let total = config.shard.size(def.points());
        state.total = total;
        progress(&state);
        let count = total - rows.len() as u64;
        tally.threads = clamp_threads(config.threads, count);
        let shard = config.shard;
        let done = &rows;
        let pending = (shard.index - 1..def.points())
            .step_by(usize::try_from(shard.count).unwrap_or(usize::MAX))
            .filter(|i| !done.contains_key(i));
        let mut fresh = Vec::new();
        let result = execute(
            pending,
            count,
            config.threads,
            width,
            config.cancel,
            &|indices| run_points(def, indices),
            &mut |row| {
                fresh.extend(record(
                    row,
                    &mut state,
                    &mut tally,
                    &mut writer,
                    &mut *progress,
                )?);
                Ok(())
            },
        );
        rows.extend(fresh.into_iter().map(|r| (r.index, r)));
        (result, total)
    };
    let flushed = writer.flush();
    result?;
    flushed?;
    // The run adds itself to the folder's compute record, complete or stopped.
    let elapsed = start.elapsed();
    ComputeRecord::append(
        dir,
        &ComputeRun {
            shard: config.shard,
            host: tumble_output::host_name(),
            threads: tally.threads.max(1),
            wall_time: elapsed,
            computed: tally.computed,
            failed: tally.failed,
            complete: rows.len() as u64 == total,
        },
    )?;
    Ok(SweepReport {
        rows: rows.into_values().collect(),
        total,
        computed: tally.computed,
        resumed: state.resumed,
        elapsed,
        threads: tally.threads.max(1),
        compute: ComputeRecord::read(dir)?,
    })
}

/// What a run computed.
#[derive(Debug, Default)]
struct Tally {
    computed: u64,
    failed: u64,
    threads: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(index: u64) -> PointRow {
        PointRow {
            index,
            values: vec![index as f64],
            metrics: vec![Some(2.0 * index as f64)],
            status: Status::Ok,
            reason: String::new(),
        }
    }

    fn rows(batch: &[u64]) -> Vec<PointRow> {
        batch.iter().map(|&i| row(i)).collect()
    }

    #[test]
    fn every_point_reaches_the_sink_once_whatever_the_threads_and_batch_width() {
        let pending: Vec<u64> = (0..50).collect();
        for threads in [1, 2, 3] {
            for width in [1, 3, 8, 64] {
                let mut seen = Vec::new();
                execute(
                    pending.iter().copied(),
                    pending.len() as u64,
                    threads,
                    width,
                    None,
                    &rows,
                    &mut |r| {
                        seen.push(r.index);
                        Ok(())
                    },
                )
                .unwrap();
                seen.sort_unstable();
                assert_eq!(seen, pending, "{threads} threads, batches of {width}");
            }
        }
    }

    #[test]
    fn a_failing_sink_stops_the_workers_and_returns_its_error() {
        let pending: Vec<u64> = (0..1000).collect();
        let mut n = 0;
        let e = execute(
            pending.iter().copied(),
            1000,
            2,
            1,
            None,
            &rows,
            &mut |_| {
                n += 1;
                if n == 3 {
                    Err(SweepError::Merge("disk full".into()))
                } else {
                    Ok(())
                }
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("disk full"));
        assert_eq!(n, 3);
    }

    #[test]
    fn cancelling_stops_new_points() {
        let pending: Vec<u64> = (0..200).collect();
        let cancel = AtomicBool::new(false);
        let mut seen = 0;
        let slow = |b: &[u64]| {
            std::thread::sleep(Duration::from_millis(2));
            rows(b)
        };
        execute(
            pending.iter().copied(),
            200,
            1,
            1,
            Some(&cancel),
            &slow,
            &mut |_| {
                seen += 1;
                if seen == 5 {
                    cancel.store(true, Ordering::Relaxed);
                }
                Ok(())
            },
        )
        .unwrap();
        assert!((5..200).contains(&seen), "{seen}");
    }

    /// The built-in map runs in lanes, and its rows are the same bits whatever the batch:
    /// points alone, in batches of the lanes' width, of 3, and in another order.
    #[test]
    fn the_maps_rows_do_not_depend_on_the_batch() {
        let def = SweepDefinition::tilt_map(&[]).unwrap();
        let lanes = def.lanes().expect("the built-in map runs in lanes");
        let indices: Vec<u64> = (0..def.points()).step_by(1171).collect();
        assert!(indices.len() > lanes.width);
        let alone: Vec<PointRow> = indices.iter().map(|&i| run_point(&def, i)).collect();
        let key = |rows: &[PointRow]| -> Vec<(u64, Vec<Option<u64>>, Status)> {
            rows.iter()
                .map(|r| {
                    let bits = r.metrics.iter().map(|m| m.map(f64::to_bits)).collect();
                    (r.index, bits, r.status)
                })
                .collect()
        };
        assert!(alone.iter().all(|r| r.status == Status::Ok));
        assert_eq!(key(&run_points(&def, &indices)), key(&alone));
        let threes: Vec<PointRow> = indices
            .chunks(3)
            .flat_map(|c| run_points(&def, c))
            .collect();
        assert_eq!(key(&threes), key(&alone));
        let reversed: Vec<u64> = indices.iter().rev().copied().collect();
        let mut back = run_points(&def, &reversed);
        back.reverse();
        assert_eq!(key(&back), key(&alone));
    }

    /// The lanes' metrics are those of the scalar run with its rows (a metric the lanes do not
    /// report, `max:alpha`, sends the same sweep down the scalar path): the final tilt and the
    /// energy error bit for bit (the same steps), the largest tilt and the first crossing to
    /// 1e-12 (located on the same polynomials, by root-finding or by the rows' quartic fits).
    #[test]
    fn the_lanes_metrics_are_the_scalar_runs() {
        let def = SweepDefinition::tilt_map(&[]).unwrap();
        let mut scalar = def.clone();
        scalar.metrics.push(Metric::parse("max:alpha").unwrap());
        assert!(def.lanes().is_some() && scalar.lanes().is_none());
        let mut crossings = 0;
        for i in (0..def.points()).step_by(997) {
            let (a, b) = (run_point(&def, i), run_point(&scalar, i));
            assert_eq!((a.status, b.status), (Status::Ok, Status::Ok), "point {i}");
            for (k, m) in def.metrics.iter().enumerate() {
                let (x, y) = (a.metrics[k], b.metrics[k]);
                match m {
                    Metric::FinalTilt | Metric::MaxEnergyRelErr => {
                        assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits), "{m:?} at {i}");
                    }
                    _ => match (x, y) {
                        (Some(x), Some(y)) => {
                            assert!((x - y).abs() <= 1e-12, "{m:?} at {i}: {x} vs {y}");
                            crossings += usize::from(*m == Metric::TimeTiltExceeds);
                        }
                        (x, y) => assert_eq!(x, y, "{m:?} at {i}"),
                    },
                }
            }
        }
        assert!(crossings >= 3, "{crossings}");
    }
}
