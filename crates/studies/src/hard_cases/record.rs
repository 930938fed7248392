//! The record of a hard-case atlas: [`AtlasRecord`], the folder's `manifest.json`. `tumble
//! hard-cases` writes it and `tumble plot` reads it back (the cases and methods of the
//! figure): one type, so the keys cannot drift apart. Fields are declared in the file's key
//! order.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use tumble_output::Provenance;

use super::Case;
use super::atlas::{self, AtlasReport, Method};

/// A case as the atlas's manifest records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AtlasCaseRecord {
    /// Its name.
    pub name: String,
    /// The file it came from.
    pub origin: String,
    /// The scene's name.
    pub scene: String,
    /// Its parameters, in words ([`atlas::parameters_text`]).
    pub parameters: String,
    /// The case's property bounds the final-state error (its atlas cell is coloured by it,
    /// else by the relative energy error).
    pub bounds_error: bool,
    /// The horizon (s).
    pub t_end: f64,
    /// Why it is hard.
    pub why: String,
    /// What a good method does.
    pub good: String,
    /// How its reference was computed, or why it failed (`None`: no reference was needed).
    pub reference: Option<String>,
}

/// `manifest.json` of a hard-case atlas folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AtlasRecord {
    /// `hard-cases`.
    pub command: String,
    /// The rule that chose each method's setting, in words.
    pub rule: String,
    /// The cases, in order.
    pub cases: Vec<AtlasCaseRecord>,
    /// The atlas's rows, as given (`NAME` or `NAME:dt=H`).
    pub methods: Vec<String>,
    /// Entries of the atlas in all.
    pub entries: usize,
    /// Entries finished.
    pub finished: usize,
    /// Entries found in the journal.
    pub resumed: usize,
    /// Finished entries by outcome.
    pub counts: BTreeMap<String, usize>,
    /// Wall-clock budget of the atlas (s).
    pub budget_s: f64,
    /// Wall-clock limit of each run (s).
    pub run_seconds: f64,
    /// Wall time (s).
    pub wall_time_s: f64,
    /// The files of the folder besides the manifest.
    pub files: Vec<String>,
    /// How the atlas was made.
    pub provenance: Provenance,
}

impl AtlasRecord {
    /// The record of the atlas of `cases` × `methods` that produced `report` within
    /// `budget_s` seconds, each run limited to `run_seconds`, made by `provenance`.
    #[must_use]
    pub fn new(
        provenance: Provenance,
        cases: &[Case],
        methods: &[Method],
        report: &AtlasReport,
        budget_s: f64,
        run_seconds: f64,
    ) -> Self {
        let mut counts = BTreeMap::new();
        for e in &report.entries {
            *counts.entry(e.status.name().to_string()).or_insert(0) += 1;
        }
        AtlasRecord {
            command: "hard-cases".to_string(),
            rule: format!(
                "each method at the step (adaptive: tolerance) that gives it an error of {:e} at \
                 the horizon of the case's easy twin (the scene's default step or tolerance 1e-8 \
                 scaled by (1e-6/e)^(1/p), up to six runs; the largest setting within 3e-6 kept); \
                 the exact flow at the scene's default step; a setting given with the method \
                 replaces the rule",
                atlas::TARGET
            ),
            cases: cases
                .iter()
                .map(|c| AtlasCaseRecord {
                    name: c.name.clone(),
                    origin: c.origin.clone(),
                    scene: c.scene.info().name.to_string(),
                    parameters: atlas::parameters_text(c),
                    bounds_error: c.property.error.is_some(),
                    t_end: c.t_end,
                    why: c.why.clone(),
                    good: c.good.clone(),
                    reference: report.references.get(&c.name).cloned(),
                })
                .collect(),
            methods: methods.iter().map(Method::spec).collect(),
            entries: report.total,
            finished: report.entries.len(),
            resumed: report.resumed,
            counts,
            budget_s,
            run_seconds,
            wall_time_s: report.seconds,
            files: ["atlas.csv", "atlas.png", "atlas.svg", atlas::JOURNAL]
                .map(String::from)
                .to_vec(),
            provenance,
        }
    }
}
