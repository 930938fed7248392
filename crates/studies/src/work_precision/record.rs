//! The records of a work–precision study: one [`Rung`] per run (the type the ladders compute
//! is the row of `work-precision.csv`, and of Python's `work_precision` frame) and the
//! [`StudyRecord`] of its `manifest.json`. `tumble work-precision` writes them, `tumble plot`
//! reads them back, and Python hands over the same rows: one type each, so names cannot drift
//! apart.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use tumble_integrators::registry::Order;
use tumble_output::Provenance;
use tumble_scenarios::{Params, StepControl};

use super::{Config, Ladder, Reference};

/// One run of a ladder, as computed and as recorded: a row of `work-precision.csv` and of
/// Python's `work_precision` rows (field order is the column order).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rung {
    /// The integrator.
    pub integrator: String,
    /// Its order, written as a number, `exact` or `variable`.
    #[serde(with = "order_words")]
    pub order: Order,
    /// The fixed step (s), for a fixed-step method.
    pub dt: Option<f64>,
    /// The tolerance, for an adaptive one.
    pub tol: Option<f64>,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations (steps for methods without a right-hand side).
    pub evaluations: u64,
    /// The error at the final time ([`super::state_error`] against the reference).
    pub error: f64,
    /// The largest relative energy error (over every step of the monitored run).
    pub max_energy_rel_err: f64,
    /// Wall time (s) of one run observing only the ends: the median over samples of the mean
    /// of back-to-back runs (each sample at least 5 ms; [`super::retime`] times it again).
    pub wall_time_s: f64,
    /// Timed runs in all.
    pub repeats: usize,
}

/// [`Rung::order`] as `work-precision.csv` writes it: the [`Order`]'s words (`4`, `exact`,
/// `variable`), where the manifest writes a number, `null` or `"variable"`.
mod order_words {
    use serde::{Deserialize, Deserializer, Serializer, de::Error};
    use tumble_integrators::registry::Order;

    pub(super) fn serialize<S: Serializer>(order: &Order, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(order)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Order, D::Error> {
        let words = String::deserialize(d)?;
        match words.as_str() {
            "exact" => Ok(Order::Exact),
            "variable" => Ok(Order::Variable),
            n => n.parse().map(Order::Finite).map_err(|_| {
                D::Error::custom(format!("order `{words}`: a number, `exact` or `variable`"))
            }),
        }
    }
}

impl Rung {
    /// The columns of `work-precision.csv`: the fields, in order.
    pub const COLUMNS: [&'static str; 10] = [
        "integrator",
        "order",
        "dt",
        "tol",
        "steps",
        "evaluations",
        "error",
        "max_energy_rel_err",
        "wall_time_s",
        "repeats",
    ];

    /// The step or tolerance the rung ran at (`None` for a row read with both or neither).
    #[must_use]
    pub fn control(&self) -> Option<StepControl> {
        StepControl::from_dt_tol(self.dt, self.tol).ok().flatten()
    }

    /// The rungs of `ladders`, ladder by ladder, rung by rung: the rows of the study.
    #[must_use]
    pub fn of(ladders: &[Ladder]) -> Vec<&Rung> {
        ladders.iter().flat_map(|l| &l.rungs).collect()
    }

    /// The row's fields as `work-precision.csv` writes them, in [`Rung::COLUMNS`] order:
    /// numbers in Rust's shortest round-trip decimal form (`0.0001`, never `1e-4`), an absent
    /// `dt` or `tol` empty.
    #[must_use]
    pub fn csv_fields(&self) -> [String; 10] {
        let optional = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
        [
            self.integrator.clone(),
            self.order.to_string(),
            optional(self.dt),
            optional(self.tol),
            self.steps.to_string(),
            self.evaluations.to_string(),
            self.error.to_string(),
            self.max_energy_rel_err.to_string(),
            self.wall_time_s.to_string(),
            self.repeats.to_string(),
        ]
    }

    /// The text of `work-precision.csv` for `rows`: the header, then a line per row.
    ///
    /// # Errors
    /// Never in practice (the CSV is written to memory); the writer's error otherwise.
    pub fn csv_text<'a>(rows: impl IntoIterator<Item = &'a Rung>) -> Result<String, csv::Error> {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(Self::COLUMNS)?;
        for row in rows {
            w.write_record(row.csv_fields())?;
        }
        let bytes = w
            .into_inner()
            .map_err(|e| csv::Error::from(e.into_error()))?;
        Ok(String::from_utf8_lossy(&bytes).into_owned())
    }
}

/// The reference of a study, as its manifest records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRecord {
    /// How far the cross-check agrees with the reference.
    pub agreement: f64,
    /// What cross-checked it.
    pub cross_check: String,
    /// What computed it.
    pub method: String,
    /// How far the reference agrees with itself at half the step.
    pub self_agreement: f64,
    /// What it was compared with (empty for the exact flow).
    pub self_check: String,
}

/// A rung that failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FailedRungRecord {
    /// Its step or tolerance, in words.
    pub control: String,
    /// Why.
    pub reason: String,
}

/// One integrator's ladder, as the manifest records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LadderRecord {
    /// The rungs that failed.
    pub failures: Vec<FailedRungRecord>,
    /// The integrator.
    pub name: String,
    /// A number, `null` for the exact flow, `"variable"` for a Taylor method.
    pub order: Order,
    /// Rungs kept.
    pub rungs: usize,
    /// Why the ladder stopped.
    pub stopped: String,
}

/// `manifest.json` of a work–precision folder (fields in the file's key order, alphabetical).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyRecord {
    /// `work-precision`.
    pub command: String,
    /// The error norm, in words.
    pub error: String,
    /// Each integrator's ladder.
    pub integrators: Vec<LadderRecord>,
    /// [`Config::max_run_seconds`].
    pub max_run_seconds: f64,
    /// `builtin` or the scene file.
    pub origin: String,
    /// The scene's parameters.
    pub parameters: BTreeMap<String, f64>,
    /// The program and invocation.
    pub provenance: Provenance,
    /// The reference solution.
    pub reference: ReferenceRecord,
    /// The scene's name.
    pub scene: String,
    /// The horizon (s).
    pub t_end: f64,
    /// `tumble` version.
    pub tumble_version: String,
    /// How `wall_time_s` was measured, in words.
    pub wall_time: String,
}

/// What the study's error is, in words ([`super::state_error`]).
pub const ERROR_WORDS: &str = "max_i |y_i - y_ref_i| / (1 + |y_ref_i|) over the final coordinates \
                               and rates (quaternion up to sign)";

/// How a rung's wall time is measured, in words ([`super::retime`]).
pub const WALL_TIME_WORDS: &str = "seconds per run observing only the initial and final states: \
                                   median of 5 samples (3 for runs over 0.1 s), each the mean of \
                                   back-to-back runs lasting at least 5 ms";

impl StudyRecord {
    /// The record of the ladders of `scene` (from `origin`) at `params` over `[0, t_end]`,
    /// made by `provenance`; `control_words` describes a step or tolerance.
    #[must_use]
    pub fn new(
        provenance: Provenance,
        scene: &str,
        origin: &str,
        params: &Params,
        config: &Config,
        reference: &Reference,
        ladders: &[Ladder],
        control_words: impl Fn(StepControl) -> String,
    ) -> Self {
        StudyRecord {
            command: "work-precision".to_string(),
            error: ERROR_WORDS.to_string(),
            integrators: ladders
                .iter()
                .map(|l| LadderRecord {
                    failures: l
                        .failures
                        .iter()
                        .map(|f| FailedRungRecord {
                            control: control_words(f.control),
                            reason: f.reason.clone(),
                        })
                        .collect(),
                    name: l.integrator.clone(),
                    order: l.order,
                    rungs: l.rungs.len(),
                    stopped: l.stop.clone(),
                })
                .collect(),
            max_run_seconds: config.max_run_seconds,
            origin: origin.to_string(),
            parameters: params.iter().map(|(k, v)| (k.to_string(), v)).collect(),
            tumble_version: provenance.tumble_version.clone(),
            provenance,
            reference: ReferenceRecord {
                agreement: reference.agreement,
                cross_check: reference.check.clone(),
                method: reference.method.clone(),
                self_agreement: reference.self_agreement,
                self_check: reference.self_check.clone(),
            },
            scene: scene.to_string(),
            t_end: config.t_end,
            wall_time: WALL_TIME_WORDS.to_string(),
        }
    }
}
