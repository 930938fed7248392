//! The record of a run: how its rows were made, and what it measured. `tumble simulate -o
//! FILE.csv` writes it beside the CSV as `FILE.csv.json` (and into a Parquet file's metadata),
//! `tumble plot` and `tumble animate` read it back, and Python's `Simulation` holds the same
//! fields: one type, so the names and defaults of the three cannot drift apart.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use tumble_output::Provenance;
use tumble_scenarios::{DtAndTol, Params, RunPlan, RunSummary, SceneInfo, StepControl};

use crate::error_estimate::{self, ErrorEstimate};

/// `FILE.csv.json`: how a run's rows were made (field order is the file's key order).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// The program and invocation that made the run.
    pub provenance: Provenance,
    /// The scene's name.
    pub scene: String,
    /// `builtin`, or the scene or model file the scene came from.
    pub origin: String,
    /// The frame of the orientation and angular-velocity columns, in words
    /// ([`crate::simulation::BODY_FRAME`] unless the scene file names one).
    pub frame: String,
    /// Every parameter of the scene, by name.
    pub parameters: BTreeMap<String, f64>,
    /// The integrator's name.
    pub integrator: String,
    /// The fixed step (s), for a fixed-step run.
    pub dt: Option<f64>,
    /// The tolerance, for an adaptive run.
    pub tol: Option<f64>,
    /// The horizon (s).
    pub t_end: f64,
    /// Rows were written every `every`-th step.
    pub every: u64,
    /// The output times, when rows were written at chosen times.
    pub at: Option<Vec<f64>>,
    /// The trajectory file (empty: standard output, or none).
    pub csv: String,
    /// The columns of the rows, in order.
    pub columns: Vec<String>,
    /// Rows written.
    pub rows: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub evaluations: u64,
    /// The time the run reached (s).
    pub reached_t: f64,
    /// The largest relative energy error over every step.
    pub max_energy_rel_err: f64,
    /// `max_energy_rel_err` exceeded the warning threshold (`--energy-warn`,
    /// [`crate::simulation::DEFAULT_ENERGY_WARN`] unless given).
    pub energy_warning: bool,
    /// The error estimate, or why there is none.
    pub error_estimate: EstimateRecord,
    /// Wall time of the run (s), the error estimate not included.
    pub wall_time_s: f64,
}

/// What a run is, as [`RunRecord::new`] takes it.
#[derive(Debug, Clone, Copy)]
pub struct RunSetup<'a> {
    /// The scene's declaration.
    pub info: &'a SceneInfo,
    /// `builtin` or the scene file.
    pub origin: &'a str,
    /// The frame of the rows, in words (`None`: [`crate::simulation::BODY_FRAME`]).
    pub frame: Option<&'a str>,
    /// The parameters it ran at.
    pub params: &'a Params,
    /// How it ran.
    pub plan: &'a RunPlan,
}

impl RunRecord {
    /// The record of the run `setup` that ended with `summary` in `wall_time_s` seconds,
    /// written to `csv` (empty: none), its energy error judged against `energy_warn`.
    #[must_use]
    pub fn new(
        provenance: Provenance,
        setup: &RunSetup<'_>,
        summary: &RunSummary,
        estimate: &Estimated,
        energy_warn: f64,
        csv: String,
        wall_time_s: f64,
    ) -> Self {
        let plan = setup.plan;
        let (dt, tol) = plan.step.dt_tol();
        RunRecord {
            provenance,
            scene: setup.info.name.to_string(),
            origin: setup.origin.to_string(),
            frame: setup
                .frame
                .unwrap_or(crate::simulation::BODY_FRAME)
                .to_string(),
            parameters: setup
                .params
                .iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
            integrator: plan.integrator().to_string(),
            dt,
            tol,
            t_end: plan.t_end,
            every: plan.every,
            at: plan.times.clone(),
            csv,
            columns: setup.info.columns(),
            rows: summary.rows,
            steps: summary.steps,
            evaluations: summary.evaluations,
            reached_t: summary.t,
            max_energy_rel_err: summary.max_energy_rel_err,
            energy_warning: !(summary.max_energy_rel_err <= energy_warn),
            error_estimate: EstimateRecord::of(estimate),
            wall_time_s,
        }
    }

    /// The run's step control.
    ///
    /// # Errors
    /// [`StepRecordError`] for a record with both `dt` and `tol`, or neither.
    pub fn step(&self) -> Result<StepControl, StepRecordError> {
        match StepControl::from_dt_tol(self.dt, self.tol) {
            Ok(Some(step)) => Ok(step),
            Ok(None) => Err(StepRecordError::Neither),
            Err(DtAndTol) => Err(StepRecordError::Both),
        }
    }
}

/// A record whose step control is not one of `dt` and `tol`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum StepRecordError {
    /// Neither `dt` nor `tol`.
    #[error("neither `dt` nor `tol`: a run has a fixed step or a tolerance")]
    Neither,
    /// Both.
    #[error("both `dt` and `tol`: a run has a fixed step or a tolerance, not both")]
    Both,
}

/// The error estimate of a run, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub enum Estimated {
    /// Not asked for (`--check off`, `check=False`), or the run was interrupted.
    Off,
    /// The companion could not run, or the run did not finish (why).
    Failed(String),
    /// The estimate.
    Done(ErrorEstimate),
}

/// Whether a run's error was estimated, as its record says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EstimateStatus {
    /// The estimate's figures follow.
    Estimated,
    /// Not asked for.
    Off,
    /// The companion or the run failed (the reason follows).
    Failed,
}

/// The error estimate as a run's record holds it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EstimateRecord {
    /// `estimated`, `off` or `failed`.
    pub status: EstimateStatus,
    /// Why there is no estimate (`failed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The figures (`estimated`).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub estimate: Option<EstimateFigures>,
}

/// The figures of an error estimate ([`crate::error_estimate`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EstimateFigures {
    /// Estimated error of the final state (work–precision norm).
    #[serde(rename = "final")]
    pub final_error: f64,
    /// Largest estimated error over the compared rows.
    pub max: f64,
    /// Time of that row.
    pub max_t: f64,
    /// Rows compared with the companion.
    pub rows_compared: u64,
    /// `trustworthy`, `round-off`, `within-tolerance`, `not-trustworthy` or `unchecked`.
    pub trust: String,
    /// Why, in words.
    pub trust_reason: String,
    /// The companion's setting, in words.
    pub companion: String,
    /// The check's setting, in words (`None`: no check ran).
    pub check: Option<String>,
    /// The decrease expected from the run to the companion.
    pub expected_ratio: f64,
    /// The decrease observed (`None` without a check).
    pub observed_ratio: Option<f64>,
    /// The factor applied to the differences.
    pub factor: f64,
    /// The round-off level of the differences.
    pub round_off: f64,
    /// Steps of the companion and the check together.
    pub companion_steps: u64,
    /// Right-hand-side evaluations of the companion and the check together.
    pub companion_evaluations: u64,
}

impl EstimateRecord {
    /// The record of `estimate`.
    #[must_use]
    pub fn of(estimate: &Estimated) -> Self {
        match estimate {
            Estimated::Off => EstimateRecord {
                status: EstimateStatus::Off,
                reason: None,
                estimate: None,
            },
            Estimated::Failed(reason) => EstimateRecord {
                status: EstimateStatus::Failed,
                reason: Some(reason.clone()),
                estimate: None,
            },
            Estimated::Done(e) => EstimateRecord {
                status: EstimateStatus::Estimated,
                reason: None,
                estimate: Some(EstimateFigures {
                    final_error: e.final_error,
                    max: e.max_error,
                    max_t: e.max_error_t,
                    rows_compared: e.rows_compared,
                    trust: e.trust.key().to_string(),
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
