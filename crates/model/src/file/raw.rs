//! The layout of a model file as TOML: every table and key, unknown keys refused, each value
//! with its place in the text.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;
use tumble_scenarios::body_table::RawBody;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFile {
    pub(super) model: Spanned<RawHeader>,
    pub(super) parameters: Option<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    pub(super) coordinates: Option<BTreeMap<Spanned<String>, Spanned<RawCoordinate>>>,
    pub(super) definitions: Option<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    pub(super) frames: Option<BTreeMap<Spanned<String>, Spanned<RawFrame>>>,
    pub(super) rotating_frame: Option<Spanned<RawRotating>>,
    pub(super) bodies: Option<BTreeMap<Spanned<String>, Spanned<RawBodyDef>>>,
    pub(super) points: Option<BTreeMap<Spanned<String>, Spanned<RawPoint>>>,
    pub(super) lagrangian: Option<RawLagrangian>,
    pub(super) outputs: Option<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    pub(super) run: Option<Spanned<RawRun>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawHeader {
    pub(super) name: Spanned<String>,
    pub(super) summary: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCoordinate {
    pub(super) initial: Spanned<toml::Value>,
    pub(super) rate: Option<Spanned<toml::Value>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFrame {
    pub(super) orientation: Option<Spanned<String>>,
    pub(super) omega: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) euler: Option<Spanned<String>>,
    pub(super) angles: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) rotations: Option<Spanned<Vec<Spanned<RawRotation>>>>,
    pub(super) parent: Option<Spanned<String>>,
    pub(super) origin: Option<Spanned<Vec<Spanned<toml::Value>>>>,
}

/// `[axis, angle]` of a chain of rotations.
pub(super) type RawRotation = (String, Spanned<toml::Value>);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRotating {
    pub(super) omega: Spanned<Vec<Spanned<toml::Value>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBodyDef {
    pub(super) frame: Option<Spanned<String>>,
    pub(super) origin: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) mass: Option<Spanned<toml::Value>>,
    pub(super) com: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) inertia: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) geometry: Option<Spanned<RawBody>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPoint {
    pub(super) mass: Spanned<toml::Value>,
    pub(super) frame: Option<Spanned<String>>,
    pub(super) origin: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) position: Spanned<Vec<Spanned<toml::Value>>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLagrangian {
    pub(super) gravity: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    pub(super) potential: Option<Spanned<toml::Value>>,
    pub(super) kinetic: Option<Spanned<toml::Value>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRun {
    pub(super) integrator: Option<String>,
    pub(super) dt: Option<Spanned<toml::Value>>,
    pub(super) tol: Option<Spanned<toml::Value>>,
    pub(super) t_end: Option<Spanned<toml::Value>>,
}

/// Entries of a table in the order the file writes them.
pub(super) fn ordered<T>(map: Option<BTreeMap<Spanned<String>, T>>) -> Vec<(Spanned<String>, T)> {
    let mut v: Vec<_> = map.unwrap_or_default().into_iter().collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}
