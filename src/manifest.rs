//! The `manifest.json` of sweep folders (a work–precision folder's is
//! `tumble_studies::work_precision::record::StudyRecord`): how the results were made, as
//! `Serialize` types. Fields are declared in alphabetical order, the order in which the files
//! have always listed them.

use std::collections::BTreeMap;

use serde::Serialize;
use tumble_scenarios::Params;

use crate::provenance::Provenance;
use tumble_studies::sweep::{
    AxisValues, CheckReport, ComputeRecord, Sampling, Shard, SweepDefinition, SweepReport,
};

/// The fixed parameters (those not swept).
fn fixed(params: &Params, swept: &[&str]) -> BTreeMap<String, f64> {
    params
        .iter()
        .filter(|(n, _)| !swept.contains(n))
        .map(|(n, v)| (n.to_string(), v))
        .collect()
}

/// One axis of a sweep.
#[derive(Serialize)]
#[serde(untagged)]
enum AxisJson {
    List {
        parameter: &'static str,
        unit: &'static str,
        values: Vec<f64>,
    },
    Range {
        count: Option<u64>,
        parameter: &'static str,
        range: [f64; 2],
        spacing: String,
        unit: &'static str,
    },
}

/// The run of every point.
#[derive(Serialize)]
struct RunJson {
    dt: Option<f64>,
    integrator: &'static str,
    t_end: f64,
    tol: Option<f64>,
}

/// How the points are laid out.
#[derive(Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
enum SamplingJson {
    Grid,
    Random {
        generator: &'static str,
        samples: u64,
        seed: u64,
    },
}

/// A sweep definition.
#[derive(Serialize)]
struct DefinitionJson {
    axes: Vec<AxisJson>,
    metrics: Vec<String>,
    origin: String,
    parameters: BTreeMap<String, f64>,
    points: u64,
    run: RunJson,
    sampling: SamplingJson,
    scene: &'static str,
    tilt_threshold: Option<f64>,
}

impl DefinitionJson {
    fn new(def: &SweepDefinition) -> Self {
        let swept: Vec<&str> = def.axes.iter().map(|a| a.parameter).collect();
        let (dt, tol) = def.plan.step.dt_tol();
        DefinitionJson {
            axes: def
                .axes
                .iter()
                .map(|a| match &a.values {
                    AxisValues::List(v) => AxisJson::List {
                        parameter: a.parameter,
                        unit: a.unit,
                        values: v.clone(),
                    },
                    AxisValues::Range {
                        start,
                        end,
                        count,
                        spacing,
                    } => AxisJson::Range {
                        count: *count,
                        parameter: a.parameter,
                        range: [*start, *end],
                        spacing: format!("{spacing:?}").to_lowercase(),
                        unit: a.unit,
                    },
                })
                .collect(),
            metrics: def.metrics.iter().map(|m| m.name()).collect(),
            origin: def.origin.clone(),
            parameters: fixed(&def.params, &swept),
            points: def.points(),
            run: RunJson {
                dt,
                integrator: def.plan.integrator(),
                t_end: def.plan.t_end,
                tol,
            },
            sampling: match def.sampling {
                Sampling::Grid => SamplingJson::Grid,
                Sampling::Random { samples, seed } => SamplingJson::Random {
                    generator: "splitmix64",
                    samples,
                    seed,
                },
            },
            scene: def.scene.info().name,
            tilt_threshold: def.tilt_threshold,
        }
    }
}

/// A failed point.
#[derive(Serialize)]
struct FailureJson {
    index: u64,
    reason: String,
    status: &'static str,
}

/// The model a sweep's points ran: the scene's reduction when it serves every metric and the
/// method integrates it ([`SweepDefinition::reduction`]), else the scene's full model.
#[derive(Serialize)]
struct ModelJson {
    name: &'static str,
    reduced: bool,
    rule: &'static str,
    summary: &'static str,
}

impl ModelJson {
    fn new(def: &SweepDefinition) -> Self {
        let rule = "the scene's reduction runs when the scene has one, the method is a \
                    vector-space method and every metric reads only the reduction's columns; \
                    otherwise the full model";
        match def.reduction() {
            Some(r) => ModelJson {
                name: r.name,
                reduced: true,
                rule,
                summary: r.summary,
            },
            None => ModelJson {
                name: "full",
                reduced: false,
                rule,
                summary: def.scene.info().summary,
            },
        }
    }
}

/// The self-check of a sweep.
#[derive(Serialize)]
struct SelfCheckJson {
    converged: bool,
    dt: Option<f64>,
    largest_change: f64,
    metrics: BTreeMap<String, MetricChangeJson>,
    points: Vec<u64>,
    /// The screen's looser setting (`dt` or `tol`), when it chose the points.
    screen: Option<BTreeMap<&'static str, f64>>,
    status_changed: Vec<u64>,
    tol: Option<f64>,
    tolerance: f64,
}

/// One metric's largest change under the self-check.
#[derive(Serialize)]
struct MetricChangeJson {
    at_point: Option<u64>,
    max_change: f64,
    undefined_in_one: u64,
}

impl SelfCheckJson {
    fn new(c: &CheckReport, tolerance: f64) -> Self {
        let (dt, tol) = c.setting.dt_tol();
        SelfCheckJson {
            converged: c.converged(tolerance),
            dt,
            largest_change: c.largest(),
            metrics: c
                .changes
                .iter()
                .map(|m| {
                    (
                        m.metric.name(),
                        MetricChangeJson {
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
                dt.map(|v| ("dt", v))
                    .into_iter()
                    .chain(tol.map(|v| ("tol", v)))
                    .collect()
            }),
            status_changed: c.status_changed.clone(),
            tol,
            tolerance,
        }
    }
}

/// One run of the sweep on a folder (a shard's, for a merge).
#[derive(Serialize)]
struct ComputeRunJson {
    complete: bool,
    computed_points: u64,
    failed_points: u64,
    host: String,
    points_per_second: Option<f64>,
    shard: String,
    threads: usize,
    wall_time_s: f64,
}

/// The totals of a compute record.
#[derive(Serialize)]
struct ComputeTotalsJson {
    computed_points: u64,
    failed_points: u64,
    hosts: Vec<String>,
    max_threads: usize,
    runs: usize,
    thread_seconds: f64,
    unrecorded_points: u64,
    wall_time_s: f64,
}

/// Every run that computed the sweep's points, and the totals.
#[derive(Serialize)]
struct ComputeJson {
    runs: Vec<ComputeRunJson>,
    totals: ComputeTotalsJson,
}

impl ComputeJson {
    fn new(record: &ComputeRecord, finished: u64) -> Self {
        let t = record.totals();
        ComputeJson {
            runs: record
                .runs
                .iter()
                .map(|r| {
                    let s = r.wall_time.as_secs_f64();
                    ComputeRunJson {
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
            totals: ComputeTotalsJson {
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

/// `manifest.json` of a sweep folder.
#[derive(Serialize)]
pub struct SweepManifest {
    command: String,
    compute: ComputeJson,
    computed_points: u64,
    definition: DefinitionJson,
    definition_toml: String,
    dt: Option<f64>,
    failed: usize,
    failures: Vec<FailureJson>,
    files: Vec<String>,
    integrator: &'static str,
    model: ModelJson,
    ok: usize,
    points: u64,
    points_per_second: Option<f64>,
    provenance: Provenance,
    refinement: Option<RefinementJson>,
    resumed_points: u64,
    self_check: Option<SelfCheckJson>,
    shard: String,
    t_end: f64,
    threads: usize,
    tol: Option<f64>,
    tumble_version: &'static str,
    wall_time_s: f64,
}

impl SweepManifest {
    /// The manifest of `def` run (or merged, by `command`) into `report`, with the plot files
    /// written.
    ///
    /// `computed_points`, `wall_time_s`, `points_per_second` and `threads` are those of the
    /// whole compute record — every run on the folder, or on every shard of a merge — (the
    /// most threads of a run); `compute` lists the runs; `resumed_points` are the points this
    /// command found finished.
    #[must_use]
    pub fn new(
        def: &SweepDefinition,
        report: &SweepReport,
        shard: Shard,
        command: &str,
        plots: &[String],
        self_check: Option<(&CheckReport, f64)>,
    ) -> Self {
        let failures: Vec<FailureJson> = report
            .failures()
            .map(|r| FailureJson {
                index: r.index,
                reason: r.reason.clone(),
                status: r.status.name(),
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
        SweepManifest {
            command: command.to_string(),
            compute: ComputeJson::new(&report.compute, report.rows.len() as u64),
            computed_points: totals.computed,
            definition: DefinitionJson::new(def),
            definition_toml: def.to_toml(),
            dt,
            failed: failures.len(),
            ok: report.rows.len() - failures.len(),
            failures,
            files,
            integrator: def.plan.integrator(),
            model: ModelJson::new(def),
            points: report.total,
            points_per_second: (totals.computed > 0 && wall > 0.0)
                .then(|| totals.computed as f64 / wall),
            provenance: crate::provenance::now(report.threads),
            refinement: RefinementJson::new(def, &report.rows),
            resumed_points: report.resumed,
            self_check: self_check.map(|(c, tol)| SelfCheckJson::new(c, tol)),
            shard: shard.to_string(),
            t_end: def.plan.t_end,
            threads: totals.max_threads,
            tol,
            tumble_version: env!("CARGO_PKG_VERSION"),
            wall_time_s: wall,
        }
    }
}

/// A refined sweep's refinement: its settings, the uniform grid's size and its points per
/// level.
#[derive(Serialize)]
struct RefinementJson {
    grid_points: u64,
    levels: u32,
    metric: String,
    points_by_level: Vec<u64>,
    threshold: f64,
}

impl RefinementJson {
    fn new(def: &SweepDefinition, rows: &[tumble_studies::sweep::PointRow]) -> Option<Self> {
        let r = def.refine.as_ref()?;
        Some(RefinementJson {
            grid_points: def.points(),
            levels: r.levels,
            metric: r.metric.name(),
            points_by_level: tumble_studies::sweep::refine::points_by_level(def, rows)?,
            threshold: r.threshold,
        })
    }
}

/// Serializes a manifest as pretty JSON with a final newline.
///
/// # Errors
/// If serialization fails.
pub fn to_text(manifest: &impl Serialize) -> serde_json::Result<String> {
    let mut text = serde_json::to_string_pretty(manifest)?;
    text.push('\n');
    Ok(text)
}
