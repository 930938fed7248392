//! `FILE.csv.json`: the record of how a simulation's rows were made (written beside the CSV,
//! and into a Parquet file's metadata), with the error estimate of the run.

use std::path::Path;

use tumble_scenarios::{RunSummary, StepControl};
use tumble_studies::error_estimate::{self, ErrorEstimate};

use super::Setup;
use crate::provenance::Provenance;

/// `FILE.csv.json`: how a simulation's CSV was made.
#[derive(serde::Serialize)]
pub(super) struct SimulationRecord<'a> {
    provenance: Provenance,
    scene: &'static str,
    origin: &'a str,
    /// The frame of the orientation and angular-velocity columns.
    frame: String,
    parameters: std::collections::BTreeMap<&'static str, f64>,
    integrator: &'static str,
    dt: Option<f64>,
    tol: Option<f64>,
    t_end: f64,
    every: u64,
    at: Option<&'a [f64]>,
    csv: String,
    columns: Vec<String>,
    rows: u64,
    steps: u64,
    evaluations: u64,
    reached_t: f64,
    max_energy_rel_err: f64,
    energy_warning: bool,
    /// The error estimate (`--check on`), or why there is none.
    error_estimate: EstimateRecord,
    wall_time_s: f64,
}

/// The error estimate as the provenance file records it.
#[derive(serde::Serialize)]
struct EstimateRecord {
    /// `estimated`, `off` (`--check off`) or `failed`.
    status: &'static str,
    /// Why there is no estimate (`failed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<String>,
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    estimate: Option<EstimateFigures>,
}

/// The figures of an error estimate (tumble_studies::error_estimate).
#[derive(serde::Serialize)]
struct EstimateFigures {
    /// Estimated error of the final state (work–precision norm).
    #[serde(rename = "final")]
    final_error: f64,
    /// Largest estimated error over the compared rows.
    max: f64,
    /// Time of that row.
    max_t: f64,
    rows_compared: u64,
    /// `trustworthy`, `round-off`, `not-trustworthy` or `unchecked`.
    trust: &'static str,
    /// Why, in words.
    trust_reason: String,
    companion: String,
    check: Option<String>,
    expected_ratio: f64,
    observed_ratio: Option<f64>,
    factor: f64,
    round_off: f64,
    companion_steps: u64,
    companion_evaluations: u64,
}

impl EstimateRecord {
    fn of(estimate: &Estimated) -> Self {
        match estimate {
            Estimated::Off => EstimateRecord {
                status: "off",
                reason: None,
                estimate: None,
            },
            Estimated::Failed(reason) => EstimateRecord {
                status: "failed",
                reason: Some(reason.clone()),
                estimate: None,
            },
            Estimated::Done(e) => EstimateRecord {
                status: "estimated",
                reason: None,
                estimate: Some(EstimateFigures {
                    final_error: e.final_error,
                    max: e.max_error,
                    max_t: e.max_error_t,
                    rows_compared: e.rows_compared,
                    trust: e.trust.key(),
                    trust_reason: e.trust_words(),
                    companion: error_estimate::words(e.companion),
                    check: e.check.map(error_estimate::words),
                    expected_ratio: e.expected_ratio,
                    observed_ratio: e.observed_ratio,
                    factor: e.factor,
                    round_off: e.round_off,
                    companion_steps: e.steps,
                    companion_evaluations: e.evaluations,
                }),
            },
        }
    }
}

/// The error estimate of a run, or why there is none.
pub(super) enum Estimated {
    /// `--check off`.
    Off,
    /// The companion could not run, or the run did not finish (why).
    Failed(String),
    /// The estimate.
    Done(ErrorEstimate),
}

impl<'a> SimulationRecord<'a> {
    pub(super) fn new(
        setup: &'a Setup,
        summary: &RunSummary,
        wall: f64,
        csv: Option<&Path>,
        energy_warn: f64,
        estimate: &Estimated,
    ) -> Self {
        let plan = &setup.plan;
        let (dt, tol) = match plan.step {
            StepControl::Fixed(h) => (Some(h), None),
            StepControl::Tolerance(t) => (None, Some(t)),
        };
        SimulationRecord {
            provenance: Provenance::now(1),
            scene: setup.scene.info().name,
            origin: &setup.origin,
            frame: setup
                .frame
                .clone()
                .unwrap_or_else(|| tumble_studies::simulation::BODY_FRAME.to_string()),
            parameters: setup.params.iter().collect(),
            integrator: plan.integrator(),
            dt,
            tol,
            t_end: plan.t_end,
            every: plan.every,
            at: plan.times.as_deref(),
            csv: csv.map_or_else(String::new, |p| p.display().to_string()),
            columns: setup.scene.info().columns(),
            rows: summary.rows,
            steps: summary.steps,
            evaluations: summary.evaluations,
            reached_t: summary.t,
            max_energy_rel_err: summary.max_energy_rel_err,
            energy_warning: !(summary.max_energy_rel_err <= energy_warn),
            error_estimate: EstimateRecord::of(estimate),
            wall_time_s: wall,
        }
    }
}
