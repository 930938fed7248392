//! The record of a sweep folder: [`SweepRecord`], its `manifest.json` (and, with `--format
//! parquet`, the metadata of `results.parquet`). `tumble sweep` and `tumble sweep merge` write
//! it and whoever reads a folder's manifest reads it back as this type: one type, so the keys
//! cannot drift apart. Fields are declared in alphabetical order, the order in which the files
//! have always listed them.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use tumble_output::Provenance;
use tumble_scenarios::Params;

use super::{
    AxisValues, CheckReport, ComputeRecord, PointRow, Sampling, Shard, SweepDefinition, SweepReport,
};

/// The fixed parameters (those not swept).
fn fixed(params: &Params, swept: &[&str]) -> BTreeMap<String, f64> {
    params
        .iter()
        .filter(|(n, _)| !swept.contains(n))
        .map(|(n, v)| (n.to_string(), v))
        .collect()
}

/// One axis of a sweep, as listed or as a range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum AxisRecord {
    /// The values listed.
    List {
        /// The swept parameter.
        parameter: String,
        /// Its unit.
        unit: String,
        /// The values, in order.
        values: Vec<f64>,
    },
    /// A range of values.
    Range {
        /// Grid values, ends included (`None` for random samples).
        count: Option<u64>,
        /// The swept parameter.
        parameter: String,
        /// `[start, end]`.
        range: [f64; 2],
        /// `linear` or `log`.
        spacing: String,
        /// Its unit.
        unit: String,
    },
}

/// The run of every point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanRecord {
    /// The fixed step (s), for a fixed-step method.
    pub dt: Option<f64>,
    /// The integrator.
    pub integrator: String,
    /// The horizon (s).
    pub t_end: f64,
    /// The tolerance, for an adaptive method.
    pub tol: Option<f64>,
}

/// How the points are laid out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum SamplingRecord {
    /// Every combination of the axes' values.
    Grid,
    /// Random samples.
    Random {
        /// The generator (`splitmix64`).
        generator: String,
        /// How many.
        samples: u64,
        /// Its seed.
        seed: u64,
    },
}

/// A sweep definition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DefinitionRecord {
    /// The axes, in order.
    pub axes: Vec<AxisRecord>,
    /// The metrics recorded, by name.
    pub metrics: Vec<String>,
    /// Where the definition came from (the sweep file, or a built-in sweep).
    pub origin: String,
    /// The fixed parameters.
    pub parameters: BTreeMap<String, f64>,
    /// Points in all.
    pub points: u64,
    /// The run of every point.
    pub run: PlanRecord,
    /// How the points are laid out.
    pub sampling: SamplingRecord,
    /// The scene's name.
    pub scene: String,
    /// The tilt threshold of `time_tilt_exceeds` (rad).
    pub tilt_threshold: Option<f64>,
}

impl DefinitionRecord {
    /// The record of `def`.
    #[must_use]
    pub fn new(def: &SweepDefinition) -> Self {
        let swept: Vec<&str> = def.axes.iter().map(|a| a.parameter).collect();
        let (dt, tol) = def.plan.step.dt_tol();
        DefinitionRecord {
            axes: def
                .axes
                .iter()
                .map(|a| match &a.values {
                    AxisValues::List(v) => AxisRecord::List {
                        parameter: a.parameter.to_string(),
                        unit: a.unit.to_string(),
                        values: v.clone(),
                    },
                    AxisValues::Range {
                        start,
                        end,
                        count,
                        spacing,
                    } => AxisRecord::Range {
                        count: *count,
                        parameter: a.parameter.to_string(),
                        range: [*start, *end],
                        spacing: format!("{spacing:?}").to_lowercase(),
                        unit: a.unit.to_string(),
                    },
                })
                .collect(),
            metrics: def.metrics.iter().map(|m| m.name()).collect(),
            origin: def.origin.clone(),
            parameters: fixed(&def.params, &swept),
            points: def.points(),
            run: PlanRecord {
                dt,
                integrator: def.plan.integrator().to_string(),
                t_end: def.plan.t_end,
                tol,
            },
            sampling: match def.sampling {
                Sampling::Grid => SamplingRecord::Grid,
                Sampling::Random { samples, seed } => SamplingRecord::Random {
                    generator: "splitmix64".to_string(),
                    samples,
                    seed,
                },
            },
            scene: def.scene.info().name.to_string(),
            tilt_threshold: def.tilt_threshold,
        }
    }
}

/// A failed point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FailureRecord {
    /// The point's index.
    pub index: u64,
    /// Why it failed.
    pub reason: String,
    /// Its status, by name.
    pub status: String,
}

/// The model a sweep's points ran: the scene's reduction when it serves every metric and the
/// method integrates it ([`SweepDefinition::reduction`]), else the scene's full model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelRecord {
    /// The reduction's name, or `full`.
    pub name: String,
    /// Whether the reduction ran.
    pub reduced: bool,
    /// The rule that chose it, in words.
    pub rule: String,
    /// What the model is, in words.
    pub summary: String,
}

/// [`ModelRecord::rule`].
const MODEL_RULE: &str = "the scene's reduction runs when the scene has one, the method is a \
                          vector-space method and every metric reads only the reduction's \
                          columns; otherwise the full model";

impl ModelRecord {
    /// The model the points of `def` run.
    #[must_use]
    pub fn new(def: &SweepDefinition) -> Self {
        let (name, reduced, summary) = match def.reduction() {
            Some(r) => (r.name, true, r.summary),
            None => ("full", false, def.scene.info().summary),
        };
        ModelRecord {
            name: name.to_string(),
            reduced,
            rule: MODEL_RULE.to_string(),
            summary: summary.to_string(),
        }
    }
}

/// The self-check of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SelfCheckRecord {
    /// Whether every metric of the motion changed by at most [`SelfCheckRecord::tolerance`].
    pub converged: bool,
    /// The tighter fixed step (s).
    pub dt: Option<f64>,
    /// The largest change over the metrics of the motion.
    pub largest_change: f64,
    /// Each metric's largest change, by name.
    pub metrics: BTreeMap<String, MetricChangeRecord>,
    /// The points re-run.
    pub points: Vec<u64>,
    /// The screen's looser setting (`dt` or `tol`), when it chose the points.
    pub screen: Option<BTreeMap<String, f64>>,
    /// Points that failed in one run and not in the other.
    pub status_changed: Vec<u64>,
    /// The tighter tolerance.
    pub tol: Option<f64>,
    /// The largest change accepted.
    pub tolerance: f64,
}

/// One metric's largest change under the self-check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MetricChangeRecord {
    /// The point where it is largest.
    pub at_point: Option<u64>,
    /// The largest change.
    pub max_change: f64,
    /// Points where the metric is defined in one run only.
    pub undefined_in_one: u64,
}

impl SelfCheckRecord {
    /// The record of the self-check `c` judged against `tolerance`.
    #[must_use]
    pub fn new(c: &CheckReport, tolerance: f64) -> Self {
        let (dt, tol) = c.setting.dt_tol();
        SelfCheckRecord {
            converged: c.converged(tolerance),
            dt,
            largest_change: c.largest(),
            metrics: c
                .changes
                .iter()
                .map(|m| {
                    (
                        m.metric.name(),
                        MetricChangeRecord {
                            at_point: m.index,
                            max_change: m.max_change,
                            undefined_in_one: m.undefined_in_one,
                        },
                    )
                })
                .collect(),
            points: c.points.clone(),
            screen: c.screen.map(|s| {
                let (dt, tol) = s.dt_tol();
                dt.map(|v| ("dt".to_string(), v))
                    .into_iter()
                    .chain(tol.map(|v| ("tol".to_string(), v)))
                    .collect()
            }),
            status_changed: c.status_changed.clone(),
            tol,
            tolerance,
        }
    }
}

/// One run of the sweep on a folder (a shard's, for a merge).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComputeRunRecord {
    /// Whether it finished its points.
    pub complete: bool,
    /// Points it computed.
    pub computed_points: u64,
    /// Of them, failed.
    pub failed_points: u64,
    /// The host it ran on.
    pub host: String,
    /// Points per second of wall time.
    pub points_per_second: Option<f64>,
    /// Its shard (`K/N`, or `all`).
    pub shard: String,
    /// Worker threads.
    pub threads: usize,
    /// Wall time (s).
    pub wall_time_s: f64,
}

/// The totals of a compute record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComputeTotalsRecord {
    /// Points computed over every run.
    pub computed_points: u64,
    /// Of them, failed.
    pub failed_points: u64,
    /// The hosts, each once.
    pub hosts: Vec<String>,
    /// The most threads of a run.
    pub max_threads: usize,
    /// Runs.
    pub runs: usize,
    /// Wall time times threads, summed over the runs (s).
    pub thread_seconds: f64,
    /// Finished points no run recorded (computed before the compute record existed).
    pub unrecorded_points: u64,
    /// Wall time summed over the runs (s).
    pub wall_time_s: f64,
}

/// Every run that computed the sweep's points, and the totals.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComputeSection {
    /// The runs, in order.
    pub runs: Vec<ComputeRunRecord>,
    /// Their totals.
    pub totals: ComputeTotalsRecord,
}

impl ComputeSection {
    /// The section of `record`, whose sweep has `finished` points.
    #[must_use]
    pub fn new(record: &ComputeRecord, finished: u64) -> Self {
        let t = record.totals();
        ComputeSection {
            runs: record
                .runs
                .iter()
                .map(|r| {
                    let s = r.wall_time.as_secs_f64();
                    ComputeRunRecord {
                        complete: r.complete,
                        computed_points: r.computed,
                        failed_points: r.failed,
                        host: r.host.clone(),
                        points_per_second: (r.computed > 0 && s > 0.0)
                            .then(|| r.computed as f64 / s),
                        shard: r.shard.to_string(),
                        threads: r.threads,
                        wall_time_s: s,
                    }
                })
                .collect(),
            totals: ComputeTotalsRecord {
                computed_points: t.computed,
                failed_points: t.failed,
                hosts: t.hosts,
                max_threads: t.max_threads,
                runs: t.runs,
                thread_seconds: t.thread_seconds,
                unrecorded_points: record.unrecorded(finished),
                wall_time_s: t.wall_time.as_secs_f64(),
            },
        }
    }
}

/// A refined sweep's refinement: its settings, the uniform grid's size and its points per
/// level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RefinementRecord {
    /// Points of the uniform grid.
    pub grid_points: u64,
    /// Refinement levels.
    pub levels: u32,
    /// The metric refined on.
    pub metric: String,
    /// Points computed at each level.
    pub points_by_level: Vec<u64>,
    /// The spread above which a cell is split.
    pub threshold: f64,
}

impl RefinementRecord {
    /// The refinement of `def` over `rows` (`None` for a sweep that is not refined).
    #[must_use]
    pub fn new(def: &SweepDefinition, rows: &[PointRow]) -> Option<Self> {
        let r = def.refine.as_ref()?;
        Some(RefinementRecord {
            grid_points: def.points(),
            levels: r.levels,
            metric: r.metric.name(),
            points_by_level: super::refine::points_by_level(def, rows)?,
            threshold: r.threshold,
        })
    }
}

/// `manifest.json` of a sweep folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepRecord {
    /// `sweep` or `merge`.
    pub command: String,
    /// Every run that computed the points.
    pub compute: ComputeSection,
    /// Points computed over every run.
    pub computed_points: u64,
    /// The definition.
    pub definition: DefinitionRecord,
    /// The definition as resolved TOML.
    pub definition_toml: String,
    /// The fixed step (s), for a fixed-step method.
    pub dt: Option<f64>,
    /// Points that failed.
    pub failed: usize,
    /// Each failed point.
    pub failures: Vec<FailureRecord>,
    /// The files of the folder.
    pub files: Vec<String>,
    /// The integrator.
    pub integrator: String,
    /// The model the points ran.
    pub model: ModelRecord,
    /// Points that finished.
    pub ok: usize,
    /// Points in all.
    pub points: u64,
    /// Points per second of wall time over every run.
    pub points_per_second: Option<f64>,
    /// How the manifest was made.
    pub provenance: Provenance,
    /// The refinement, for a refined sweep.
    pub refinement: Option<RefinementRecord>,
    /// Points this command found finished.
    pub resumed_points: u64,
    /// The self-check, when one ran.
    pub self_check: Option<SelfCheckRecord>,
    /// The shard (`K/N`, or `all`).
    pub shard: String,
    /// The horizon (s).
    pub t_end: f64,
    /// The most threads of a run.
    pub threads: usize,
    /// The tolerance, for an adaptive method.
    pub tol: Option<f64>,
    /// `tumble` version.
    pub tumble_version: String,
    /// Wall time over every run (s).
    pub wall_time_s: f64,
}

impl SweepRecord {
    /// The manifest of `def` run (or merged, by `command`) into `report`, with the plot files
    /// written, made by `provenance`.
    ///
    /// `computed_points`, `wall_time_s`, `points_per_second` and `threads` are those of the
    /// whole compute record — every run on the folder, or on every shard of a merge — (the
    /// most threads of a run); `compute` lists the runs; `resumed_points` are the points this
    /// command found finished.
    #[must_use]
    pub fn new(
        provenance: Provenance,
        def: &SweepDefinition,
        report: &SweepReport,
        shard: Shard,
        command: &str,
        plots: &[String],
        self_check: Option<(&CheckReport, f64)>,
    ) -> Self {
        let failures: Vec<FailureRecord> = report
            .failures()
            .map(|r| FailureRecord {
                index: r.index,
                reason: r.reason.clone(),
                status: r.status.name().to_string(),
            })
            .collect();
        let (dt, tol) = def.plan.step.dt_tol();
        let mut files = vec![
            "sweep.toml".to_string(),
            "journal.csv".to_string(),
            "compute.csv".to_string(),
            "results.csv".to_string(),
        ];
        files.extend(plots.iter().cloned());
        let totals = report.compute.totals();
        let wall = totals.wall_time.as_secs_f64();
        SweepRecord {
            command: command.to_string(),
            compute: ComputeSection::new(&report.compute, report.rows.len() as u64),
            computed_points: totals.computed,
            definition: DefinitionRecord::new(def),
            definition_toml: def.to_toml(),
            dt,
            failed: failures.len(),
            ok: report.rows.len() - failures.len(),
            failures,
            files,
            integrator: def.plan.integrator().to_string(),
            model: ModelRecord::new(def),
            points: report.total,
            points_per_second: (totals.computed > 0 && wall > 0.0)
                .then(|| totals.computed as f64 / wall),
            tumble_version: provenance.tumble_version.clone(),
            provenance,
            refinement: RefinementRecord::new(def, &report.rows),
            resumed_points: report.resumed,
            self_check: self_check.map(|(c, tol)| SelfCheckRecord::new(c, tol)),
            shard: shard.to_string(),
            t_end: def.plan.t_end,
            threads: totals.max_threads,
            tol,
            wall_time_s: wall,
        }
    }
}
