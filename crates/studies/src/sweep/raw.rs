//! Stage 1 of reading a sweep file: the TOML text as raw tables (serde; unknown keys rejected
//! with their line).

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

pub(super) type RawNumber = Spanned<toml::Value>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSweep {
    pub(super) scene: Option<Spanned<String>>,
    pub(super) parameters: Option<BTreeMap<Spanned<String>, RawNumber>>,
    pub(super) run: Option<Spanned<RawRun>>,
    pub(super) axes: Option<Vec<Spanned<RawAxis>>>,
    pub(super) random: Option<Spanned<RawRandom>>,
    pub(super) metrics: Option<Spanned<RawMetrics>>,
    pub(super) refine: Option<Spanned<RawRefine>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRun {
    pub(super) integrator: Option<Spanned<String>>,
    pub(super) dt: Option<RawNumber>,
    pub(super) tol: Option<RawNumber>,
    pub(super) t_end: Option<RawNumber>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAxis {
    pub(super) parameter: Option<Spanned<String>>,
    pub(super) values: Option<Spanned<Vec<RawNumber>>>,
    pub(super) range: Option<Spanned<Vec<RawNumber>>>,
    pub(super) count: Option<RawNumber>,
    pub(super) spacing: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRandom {
    pub(super) samples: Option<RawNumber>,
    pub(super) seed: Option<RawNumber>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMetrics {
    pub(super) record: Option<Spanned<Vec<Spanned<String>>>>,
    pub(super) tilt_threshold: Option<RawNumber>,
    pub(super) tolerance: Option<RawNumber>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRefine {
    pub(super) levels: Option<RawNumber>,
    pub(super) metric: Option<Spanned<String>>,
    pub(super) threshold: Option<RawNumber>,
}
