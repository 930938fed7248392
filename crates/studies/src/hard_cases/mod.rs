//! Hard cases: a fixed, named battery of situations that break integrators, each a scene with
//! parameters and a horizon, why it is hard, an independent reference or an exact property, and
//! what a good method does; and the atlas of every method on every case ([`atlas`]), whose
//! folder's `manifest.json` is [`record::AtlasRecord`].
//!
//! # Case files
//!
//! ```toml
//! name = "t-handle-separatrix"      # letters, digits and dashes
//! scene = "dzhanibekov"            # a built-in scene (`tumble scenes`)
//! why = "..."                      # why it is hard
//! good = "..."                     # what a good method does
//!
//! [parameters]                     # the case (numbers or angles: `pi/3`); the rest keep the scene's defaults
//! perturbation = 1e-9
//!
//! [run]
//! t_end = 20.0                     # the horizon (s)
//! reference = true                 # compare the final state with the reference (default)
//!
//! [easy]                           # the easy twin: the same scene with these parameters
//! perturbation = 0.1               # (and horizon), on which each method's step is chosen
//! t_end = 10.0
//!
//! [property]                       # what a good method meets (at least one)
//! error = 1e-4                     # final-state error against the reference at most
//! energy = 1e-6                    # largest relative energy error at most
//! conserved = ["Lx", "Ly", "Lz"]   # columns that the motion conserves
//! drift = 1e-9                     # their largest change, relative to the largest at t = 0
//! ```
//!
//! The built-in cases are such files (`crates/studies/src/hard_cases/cases/`); a user adds a
//! case by writing one. Every key is checked before any run: unknown keys (with their line),
//! the scene, parameters and their domains (in the case and its easy twin), the horizons, the
//! property's bounds and columns.

pub mod atlas;
pub mod record;

use std::path::Path;

use serde::Deserialize;
use std::collections::BTreeMap;

use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::Scene;
use tumble_scenarios::toml_file::{self, TomlFileError};

/// The built-in cases: `(file name, text)`, in atlas order.
pub const BUILT_IN: &[(&str, &str)] = &[
    (
        "t-handle-separatrix.case.toml",
        include_str!("cases/t-handle-separatrix.case.toml"),
    ),
    (
        "t-handle-near-separatrix.case.toml",
        include_str!("cases/t-handle-near-separatrix.case.toml"),
    ),
    (
        "flat-body.case.toml",
        include_str!("cases/flat-body.case.toml"),
    ),
    (
        "nearly-symmetric-body.case.toml",
        include_str!("cases/nearly-symmetric-body.case.toml"),
    ),
    (
        "fast-top.case.toml",
        include_str!("cases/fast-top.case.toml"),
    ),
    (
        "sleeping-top.case.toml",
        include_str!("cases/sleeping-top.case.toml"),
    ),
    (
        "hoop-through-flat.case.toml",
        include_str!("cases/hoop-through-flat.case.toml"),
    ),
    (
        "bead-at-the-top.case.toml",
        include_str!("cases/bead-at-the-top.case.toml"),
    ),
    (
        "light-bead.case.toml",
        include_str!("cases/light-bead.case.toml"),
    ),
    (
        "heavy-bead.case.toml",
        include_str!("cases/heavy-bead.case.toml"),
    ),
    (
        "long-free-body.case.toml",
        include_str!("cases/long-free-body.case.toml"),
    ),
    (
        "long-free-hoop.case.toml",
        include_str!("cases/long-free-hoop.case.toml"),
    ),
];

/// What a good method meets on a case.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Property {
    /// Largest final-state error against the reference.
    pub error: Option<f64>,
    /// Largest relative energy error over the run.
    pub energy: Option<f64>,
    /// Columns the motion conserves.
    pub conserved: Vec<String>,
    /// Their largest change over the run, relative to the largest of them at `t = 0`.
    pub drift: Option<f64>,
}

/// A validated hard case.
#[derive(Clone)]
pub struct Case {
    /// Its name.
    pub name: String,
    /// The file it came from (`built-in: NAME.case.toml` for the shipped ones).
    pub origin: String,
    /// The scene.
    pub scene: &'static dyn Scene,
    /// Why it is hard.
    pub why: String,
    /// What a good method does.
    pub good: String,
    /// The case's parameters (the scene's defaults with the file's).
    pub params: Params,
    /// The horizon (s).
    pub t_end: f64,
    /// Whether the final state is compared with the reference.
    pub reference: bool,
    /// The easy twin's parameters.
    pub easy: Params,
    /// The easy twin's horizon (s).
    pub easy_t_end: f64,
    /// What a good method meets.
    pub property: Property,
}

impl std::fmt::Debug for Case {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Case")
            .field("name", &self.name)
            .field("scene", &self.scene.info().name)
            .field("params", &self.params)
            .field("t_end", &self.t_end)
            .field("easy", &self.easy)
            .field("property", &self.property)
            .finish_non_exhaustive()
    }
}

/// What can be wrong with a case file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CaseError {
    /// Not readable, not TOML, an unknown key, a value of the wrong type.
    #[error(transparent)]
    File(#[from] TomlFileError),
    /// A key with an invalid value.
    #[error("{origin}: `{key}`: {reason}")]
    Invalid {
        /// The file.
        origin: String,
        /// The dotted key.
        key: String,
        /// What is wrong.
        reason: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    name: String,
    scene: String,
    why: String,
    good: String,
    parameters: Option<BTreeMap<String, toml::Value>>,
    run: RawRun,
    easy: Option<BTreeMap<String, toml::Value>>,
    property: RawProperty,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    t_end: f64,
    reference: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProperty {
    error: Option<f64>,
    energy: Option<f64>,
    conserved: Option<Vec<String>>,
    drift: Option<f64>,
}

impl Case {
    /// A fingerprint of everything that defines the case's runs (scene, parameters, horizons,
    /// reference, easy twin, property), as hex.
    #[must_use]
    pub fn key(&self) -> String {
        let text = format!(
            "{} {:?} {:?} {} {} {:?} {} {:?}",
            self.scene.info().name,
            self.params,
            self.t_end,
            self.reference,
            self.easy_t_end,
            self.easy,
            self.name,
            self.property
        );
        format!("{:016x}", crate::sweep::journal::fnv1a64(text.as_bytes()))
    }

    /// Reads and validates the case file at `path`.
    ///
    /// # Errors
    /// As [`Case::parse`], or the file cannot be read.
    pub fn load(path: &Path) -> Result<Self, CaseError> {
        let text = toml_file::read(path, "hard-case")?;
        Self::parse(&text, &path.display().to_string())
    }

    /// The built-in cases.
    ///
    /// # Errors
    /// Never for the shipped files (a test parses them all).
    pub fn built_in() -> Result<Vec<Self>, CaseError> {
        BUILT_IN
            .iter()
            .map(|(file, text)| Self::parse(text, &format!("built-in: {file}")))
            .collect()
    }

    /// Parses and validates case-file text (`origin` names it in messages).
    ///
    /// # Errors
    /// A [`CaseError`] naming the file and key.
    pub fn parse(text: &str, origin: &str) -> Result<Self, CaseError> {
        let raw: RawCase = toml_file::parse(text, origin)?;
        let invalid = |key: &str, reason: String| CaseError::Invalid {
            origin: origin.to_string(),
            key: key.to_string(),
            reason,
        };
        if raw.name.is_empty()
            || !raw
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-')
        {
            return Err(invalid(
                "name",
                format!("`{}`: use letters, digits and dashes", raw.name),
            ));
        }
        let scene = crate::models::find_scene(&raw.scene, origin)
            .map_err(|e| invalid("scene", e.to_string()))?;
        let info = scene.info();
        // Numbers or angle expressions (`pi/3`, `60 deg`), as in scene files.
        let number = |table: &str, name: &str, value: &toml::Value| {
            toml_file::number_or_angle(value)
                .map_err(|found| invalid(&format!("{table}.{name}"), format!("found {found}")))
        };
        let set = |table: &str, values: &BTreeMap<String, toml::Value>, params: &mut Params| {
            for (name, value) in values {
                if table == "easy" && name == "t_end" {
                    continue;
                }
                let value = number(table, name, value)?;
                params
                    .set(name, value)
                    .map_err(|e: SceneError| invalid(&format!("{table}.{name}"), e.to_string()))?;
            }
            Ok::<(), CaseError>(())
        };
        let mut params = info.default_params();
        set(
            "parameters",
            &raw.parameters.unwrap_or_default(),
            &mut params,
        )?;
        let easy_table = raw.easy.unwrap_or_default();
        let mut easy = params.clone();
        set("easy", &easy_table, &mut easy)?;
        let horizon = |key: &str, t: f64| {
            tumble_scenarios::scene::check_horizon(t)
                .map(|()| t)
                .map_err(|e| invalid(key, e.to_string()))
        };
        let t_end = horizon("run.t_end", raw.run.t_end)?;
        let easy_t_end = match easy_table.get("t_end") {
            Some(t) => horizon("easy.t_end", number("easy", "t_end", t)?)?,
            None => t_end,
        };
        let bound = |key: &str, v: Option<f64>| match v {
            Some(x) if !(x.is_finite() && x > 0.0) => Err(invalid(
                key,
                format!("{x}: a bound must be finite and positive"),
            )),
            _ => Ok(v),
        };
        let columns = info.columns();
        let conserved = raw.property.conserved.unwrap_or_default();
        for c in &conserved {
            if !columns.contains(c) || c == "t" {
                return Err(invalid(
                    "property.conserved",
                    format!(
                        "`{c}` is not a column of `{}`; its columns are {}",
                        info.name,
                        columns.join(", ")
                    ),
                ));
            }
        }
        let property = Property {
            error: bound("property.error", raw.property.error)?,
            energy: bound("property.energy", raw.property.energy)?,
            drift: bound("property.drift", raw.property.drift)?,
            conserved,
        };
        let reference = raw.run.reference.unwrap_or(true);
        if property.error.is_some() && !reference {
            return Err(invalid(
                "property.error",
                "an error bound needs the reference (`run.reference = true`)".into(),
            ));
        }
        if property.drift.is_some() == property.conserved.is_empty() {
            return Err(invalid(
                "property.drift",
                "`drift` and `conserved` go together: the columns and their bound".into(),
            ));
        }
        if property.error.is_none() && property.energy.is_none() && property.drift.is_none() {
            return Err(invalid(
                "property",
                "empty: give at least one of error, energy, drift".into(),
            ));
        }
        Ok(Case {
            name: raw.name,
            origin: origin.to_string(),
            scene,
            why: raw.why,
            good: raw.good,
            params,
            t_end,
            reference,
            easy,
            easy_t_end,
            property,
        })
    }
}
