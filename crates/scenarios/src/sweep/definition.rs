//! Sweep files (TOML): what to run at every point, validated as a whole before any work.
//!
//! See the [module documentation](super) for the format. Parsing goes in three stages: the
//! TOML text becomes raw tables (serde, unknown keys rejected with their line); the raw values
//! become a draft in which every value remembers where it came from (a `file:line:column`,
//! or the `--set KEY=VALUE` that replaced it); the draft is validated into a
//! [`SweepDefinition`], each error naming the key and that origin.

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::metrics::Metric;
use crate::error::SceneError;
use crate::params::Params;
use crate::scene::{RunOptions, RunPlan, Scene, StepControl};
use crate::scene_file::{Location, describe, excerpt};
use crate::scenes;

/// Where a value of a sweep definition came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Origin {
    /// A key of the file (or of the built-in definition's text).
    File(Location),
    /// A command-line override, as typed (`--set run.dt=0.005`).
    Override(String),
}

impl Origin {
    /// The 1-based line in the file, when the value came from one.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self {
            Origin::File(at) => at.line(),
            Origin::Override(_) => None,
        }
    }
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::File(at) => at.fmt(f),
            Origin::Override(text) => write!(f, "--set {text}"),
        }
    }
}

/// What can be wrong with a sweep file or an override; every variant but
/// [`SweepFileError::Read`], [`SweepFileError::MissingScene`] and [`SweepFileError::NoAxes`]
/// names the key and where it is.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepFileError {
    /// The file could not be read.
    #[error("{}: cannot read the sweep file", path.display())]
    Read {
        /// The path given.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not valid TOML, an unknown key, a duplicate key or a value of the wrong type: the
    /// parser's message (naming the key) and the offending line.
    #[error("{at}: {message}{excerpt}")]
    Syntax {
        /// Where.
        at: Location,
        /// The parser's message.
        message: String,
        /// The offending line with a caret under the column (empty when unplaced).
        excerpt: String,
    },
    /// The file does not name its scene.
    #[error("{origin}: missing `scene = \"NAME\"`; built-in scenes: {known}")]
    MissingScene {
        /// The file.
        origin: String,
        /// The built-in scene names.
        known: String,
    },
    /// The scene rejected a key: unknown scene or parameter, a value outside its domain, an
    /// integrator that cannot run it, an invalid step, tolerance or horizon.
    #[error("{at}: `{key}`: {error}")]
    Scene {
        /// Where.
        at: Origin,
        /// The dotted key (`scene`, `parameters.M`, `run.dt`, `axes.omega0.range`).
        key: String,
        /// What the scene said (boxed to keep the error small).
        error: Box<SceneError>,
    },
    /// A value that must be a number (or a whole number) is something else.
    #[error("{at}: `{key}` must be {expected}, found {found}")]
    NotANumber {
        /// Where.
        at: Origin,
        /// The dotted key.
        key: String,
        /// `a number`, `a whole number >= 1`, …
        expected: &'static str,
        /// What was found, described.
        found: String,
    },
    /// A key whose value is not allowed: a bad range, count, spacing or threshold, a
    /// parameter both fixed and swept, an axis given twice, conflicting keys, an unknown
    /// override key.
    #[error("{at}: `{key}`: {reason}")]
    Invalid {
        /// Where.
        at: Origin,
        /// The dotted key.
        key: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A metric name that does not exist or does not apply to the scene.
    #[error("{at}: `metrics.record`: {reason}")]
    Metric {
        /// Where the name is.
        at: Origin,
        /// What is wrong (the metric, the scene, the known metrics).
        reason: String,
    },
    /// The file sweeps nothing.
    #[error(
        "{origin}: no [[axes]]: a sweep needs at least one axis (a parameter with `values` or \
         a `range`)"
    )]
    NoAxes {
        /// The file.
        origin: String,
    },
}

impl SweepFileError {
    /// Where the offending key is, when it has a place.
    #[must_use]
    pub fn origin(&self) -> Option<Origin> {
        match self {
            SweepFileError::Syntax { at, .. } => Some(Origin::File(at.clone())),
            SweepFileError::Scene { at, .. }
            | SweepFileError::NotANumber { at, .. }
            | SweepFileError::Invalid { at, .. }
            | SweepFileError::Metric { at, .. } => Some(at.clone()),
            SweepFileError::Read { .. }
            | SweepFileError::MissingScene { .. }
            | SweepFileError::NoAxes { .. } => None,
        }
    }

    /// The 1-based line of the offending key, when it is in a file.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        self.origin().and_then(|o| o.line())
    }
}

/// A command-line override of one key of a sweep definition (`--set KEY=VALUE`).
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The key: a scene parameter (`omega0` or `parameters.omega0`), `run.dt`, `run.tol`,
    /// `run.t_end`, `metrics.tilt_threshold`, `random.samples`, `random.seed`, or
    /// `axes.NAME.count`, `axes.NAME.start`, `axes.NAME.end`.
    pub key: String,
    /// The value.
    pub value: f64,
    /// As typed, for messages (`run.dt=5e-3`).
    pub text: String,
}

/// How the points of an axis given by a range are spread.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spacing {
    /// Equal differences (random samples: uniform).
    Linear,
    /// Equal ratios (random samples: log-uniform); the range must be positive.
    Log,
}

impl Spacing {
    fn name(self) -> &'static str {
        match self {
            Spacing::Linear => "linear",
            Spacing::Log => "log",
        }
    }
}

/// The values one axis takes.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// Listed values, in order.
    List(Vec<f64>),
    /// A range: `count` values from `start` to `end` inclusive on a grid; random samples
    /// drawn in `[start, end)` (no count).
    Range {
        /// First value.
        start: f64,
        /// Last value (`> start`).
        end: f64,
        /// Number of values (grids; `None` for random samples).
        count: Option<u64>,
        /// Linear or logarithmic.
        spacing: Spacing,
    },
}

/// One swept parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The scene parameter.
    pub parameter: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Its values.
    pub values: AxisValues,
}

impl Axis {
    /// Number of grid values (`None` for a range of random samples).
    #[must_use]
    pub fn count(&self) -> Option<u64> {
        match &self.values {
            AxisValues::List(v) => Some(v.len() as u64),
            AxisValues::Range { count, .. } => *count,
        }
    }

    /// The `k`-th grid value (`k < count`). Linear ranges take
    /// `(start (n − 1 − k) + end k) / (n − 1)`; when `start` and `end` are short decimals
    /// (`S·10⁻ᵖ`, `E·10⁻ᵖ` with integers `S`, `E` and `p ≤ 15`) this is evaluated exactly in
    /// integers with one final division, so the result is the double nearest the exact decimal
    /// grid value (`0.1, 0.2, …, 3.0`, never `0.30000000000000004`). Logarithmic ranges take
    /// `start (end/start)^(k/(n−1))`. Both end exactly at `end`.
    #[must_use]
    pub fn grid_value(&self, k: u64) -> f64 {
        match &self.values {
            AxisValues::List(v) => v[k as usize],
            AxisValues::Range {
                start,
                end,
                count,
                spacing,
            } => {
                let n = count.unwrap_or(1);
                if n <= 1 || k == 0 {
                    return *start;
                }
                if k + 1 == n {
                    return *end;
                }
                let (k, m) = (k as f64, (n - 1) as f64);
                match spacing {
                    Spacing::Linear => match decimal_scale(*start, *end) {
                        Some((s, e, scale)) if m * scale < 2f64.powi(53) => {
                            let numerator = s * (m - k) + e * k;
                            if numerator.abs() < 2f64.powi(53) {
                                numerator / (m * scale)
                            } else {
                                (start * (m - k) + end * k) / m
                            }
                        }
                        _ => (start * (m - k) + end * k) / m,
                    },
                    Spacing::Log => start * (end / start).powf(k / m),
                }
            }
        }
    }

    /// Every grid value.
    #[must_use]
    pub fn grid_values(&self) -> Vec<f64> {
        (0..self.count().unwrap_or(0))
            .map(|k| self.grid_value(k))
            .collect()
    }

    /// The value at `u ∈ [0, 1)` of the range (random samples).
    fn sample(&self, u: f64) -> f64 {
        match &self.values {
            AxisValues::List(v) => v[((u * v.len() as f64) as usize).min(v.len() - 1)],
            AxisValues::Range {
                start,
                end,
                spacing,
                ..
            } => match spacing {
                Spacing::Linear => start + u * (end - start),
                Spacing::Log => (start.ln() + u * (end.ln() - start.ln())).exp(),
            },
        }
    }
}

/// `(S, E, 10ᵖ)` with the smallest `p ≤ 15` such that `S·10⁻ᵖ` and `E·10⁻ᵖ` (integers `S`, `E`
/// below 2⁵³) round to `start` and `end`; `None` when there is none.
fn decimal_scale(start: f64, end: f64) -> Option<(f64, f64, f64)> {
    (0..=15).find_map(|p| {
        let scale = 10f64.powi(p);
        let (s, e) = ((start * scale).round(), (end * scale).round());
        (s.abs() < 2f64.powi(53)
            && e.abs() < 2f64.powi(53)
            && s / scale == start
            && e / scale == end)
            .then_some((s, e, scale))
    })
}

/// How points are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sampling {
    /// Every combination of the axes' values; the last axis varies fastest.
    Grid,
    /// `samples` points drawn in the axes' ranges by SplitMix64 from `seed`.
    Random {
        /// Number of points.
        samples: u64,
        /// The generator's seed.
        seed: u64,
    },
}

/// SplitMix64 (Steele, Lea & Flood 2014; Vigna's `splitmix64.c`): the `n`-th output (from 0)
/// of the generator seeded with `seed`, computed directly — the state after `n + 1` steps is
/// `seed + (n + 1) γ` with `γ = 0x9E3779B97F4A7C15`, mixed by two xor-shift-multiplies.
#[must_use]
pub fn splitmix64(seed: u64, n: u64) -> u64 {
    let mut z = seed.wrapping_add(n.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A validated sweep: scene, fixed parameters, run options, axes, sampling and metrics.
#[derive(Clone)]
pub struct SweepDefinition {
    /// The file's path, or the name of a built-in definition.
    pub origin: String,
    /// The scene.
    pub scene: &'static dyn Scene,
    /// The fixed parameters (the scene's defaults with the file's and overrides' values); the
    /// swept ones are set at every point.
    pub params: Params,
    /// The validated run of every point (method, step or tolerance, horizon; every step
    /// observed, so the metrics see every step).
    pub plan: RunPlan,
    /// The axes, in file order.
    pub axes: Vec<Axis>,
    /// Grid or random samples.
    pub sampling: Sampling,
    /// The metrics, in file order.
    pub metrics: Vec<Metric>,
    /// The tilt threshold of `time_tilt_exceeds` (rad).
    pub tilt_threshold: Option<f64>,
}

impl fmt::Debug for SweepDefinition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SweepDefinition")
            .field("origin", &self.origin)
            .field("scene", &self.scene.info().name)
            .field("params", &self.params)
            .field("plan", &self.plan)
            .field("axes", &self.axes)
            .field("sampling", &self.sampling)
            .field("metrics", &self.metrics)
            .field("tilt_threshold", &self.tilt_threshold)
            .finish()
    }
}

/// Most points a sweep may have.
pub const MAX_POINTS: u64 = 1 << 40;

impl SweepDefinition {
    /// Reads, overrides and validates the sweep file at `path`.
    ///
    /// # Errors
    /// [`SweepFileError::Read`], or as [`SweepDefinition::parse`].
    pub fn load(path: &Path, overrides: &[Override]) -> Result<Self, SweepFileError> {
        let text = std::fs::read_to_string(path).map_err(|source| SweepFileError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, &path.display().to_string(), overrides)
    }

    /// The built-in hoop-tilt map ([`super::TILT_MAP`]) with `overrides`.
    ///
    /// # Errors
    /// An invalid override.
    pub fn tilt_map(overrides: &[Override]) -> Result<Self, SweepFileError> {
        Self::parse(super::TILT_MAP, "built-in tilt map", overrides)
    }

    /// Parses sweep-file text (`origin` names it in messages), applies `overrides` and
    /// validates the whole.
    ///
    /// # Errors
    /// A [`SweepFileError`] naming the key and its line (or override).
    pub fn parse(text: &str, origin: &str, overrides: &[Override]) -> Result<Self, SweepFileError> {
        let mut draft = Draft::from_text(text, origin)?;
        for o in overrides {
            draft.apply(o)?;
        }
        draft.validate()
    }

    /// Number of points.
    #[must_use]
    pub fn points(&self) -> u64 {
        match self.sampling {
            Sampling::Grid => self.axes.iter().map(|a| a.count().unwrap_or(0)).product(),
            Sampling::Random { samples, .. } => samples,
        }
    }

    /// Per-axis grid indices of point `index` (last axis fastest); `None` for random samples.
    #[must_use]
    pub fn grid_indices(&self, index: u64) -> Option<Vec<u64>> {
        if !matches!(self.sampling, Sampling::Grid) {
            return None;
        }
        let mut rest = index;
        let mut out = vec![0; self.axes.len()];
        for (k, axis) in self.axes.iter().enumerate().rev() {
            let n = axis.count().unwrap_or(1).max(1);
            out[k] = rest % n;
            rest /= n;
        }
        Some(out)
    }

    /// The axis values of point `index` (`index < points()`): grid values, or for random
    /// samples, axis `j` of sample `i` at `u = 2⁻⁵³ ⌊x / 2¹¹⌋` with `x` the `(i d + j)`-th
    /// output of [`splitmix64`] from the seed (`d` axes). A point's values depend on its index
    /// alone, never on threads or shards.
    #[must_use]
    pub fn point(&self, index: u64) -> Vec<f64> {
        match self.sampling {
            Sampling::Grid => {
                let ks = self.grid_indices(index).unwrap_or_default();
                self.axes
                    .iter()
                    .zip(ks)
                    .map(|(a, k)| a.grid_value(k))
                    .collect()
            }
            Sampling::Random { seed, .. } => {
                let d = self.axes.len() as u64;
                self.axes
                    .iter()
                    .enumerate()
                    .map(|(j, a)| {
                        let x = splitmix64(seed, index.wrapping_mul(d).wrapping_add(j as u64));
                        a.sample((x >> 11) as f64 * (1.0 / (1u64 << 53) as f64))
                    })
                    .collect()
            }
        }
    }

    /// The header of `results.csv`: `index`, the axes, the metrics, `status`, `reason`.
    #[must_use]
    pub fn columns(&self) -> Vec<String> {
        std::iter::once("index".to_string())
            .chain(self.axes.iter().map(|a| a.parameter.to_string()))
            .chain(self.metrics.iter().map(|m| m.name().to_string()))
            .chain(["status".to_string(), "reason".to_string()])
            .collect()
    }

    /// The definition as a sweep file with every value explicit (the scene's defaults
    /// included): parsing it gives the same definition. Floats are written in their shortest
    /// round-trip form. This text identifies a sweep: `--resume` and `merge` require it to be
    /// identical.
    #[must_use]
    pub fn to_toml(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let info = self.scene.info();
        let _ = writeln!(
            s,
            "# The resolved definition of the sweep in this folder (tumble sweep); every value\n\
             # explicit. `tumble sweep THIS_FILE` runs it again; `--resume` and `merge` check\n\
             # that it is unchanged.\n"
        );
        let _ = writeln!(s, "scene = {:?}\n", info.name);
        let _ = writeln!(s, "[parameters]");
        for (name, value) in self.params.iter() {
            if !self.axes.iter().any(|a| a.parameter == name) {
                let _ = writeln!(s, "{name} = {}", float(value));
            }
        }
        let _ = writeln!(s, "\n[run]");
        let _ = writeln!(s, "integrator = {:?}", self.plan.integrator());
        match self.plan.step {
            StepControl::Fixed(h) => {
                let _ = writeln!(s, "dt = {}", float(h));
            }
            StepControl::Tolerance(tol) => {
                let _ = writeln!(s, "tol = {}", float(tol));
            }
        }
        let _ = writeln!(s, "t_end = {}", float(self.plan.t_end));
        for axis in &self.axes {
            let _ = writeln!(s, "\n[[axes]]");
            let _ = writeln!(s, "parameter = {:?}", axis.parameter);
            match &axis.values {
                AxisValues::List(v) => {
                    let items: Vec<String> = v.iter().map(|x| float(*x)).collect();
                    let _ = writeln!(s, "values = [{}]", items.join(", "));
                }
                AxisValues::Range {
                    start,
                    end,
                    count,
                    spacing,
                } => {
                    let _ = writeln!(s, "range = [{}, {}]", float(*start), float(*end));
                    if let Some(n) = count {
                        let _ = writeln!(s, "count = {n}");
                    }
                    let _ = writeln!(s, "spacing = {:?}", spacing.name());
                }
            }
        }
        if let Sampling::Random { samples, seed } = self.sampling {
            let _ = writeln!(s, "\n[random]\nsamples = {samples}\nseed = {seed}");
        }
        let _ = writeln!(s, "\n[metrics]");
        let names: Vec<String> = self
            .metrics
            .iter()
            .map(|m| format!("{:?}", m.name()))
            .collect();
        let _ = writeln!(s, "record = [{}]", names.join(", "));
        if let Some(thr) = self.tilt_threshold {
            let _ = writeln!(s, "tilt_threshold = {}", float(thr));
        }
        s
    }
}

/// A float as TOML: Rust's shortest round-trip form (`0.1`, `1e-10`, `9.81`, `2.0`).
fn float(x: f64) -> String {
    format!("{x:?}")
}

// ---------------------------------------------------------------------------------------
// Stage 1: raw TOML.

type RawNumber = Spanned<toml::Value>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    scene: Option<Spanned<String>>,
    parameters: Option<BTreeMap<Spanned<String>, RawNumber>>,
    run: Option<Spanned<RawRun>>,
    axes: Option<Vec<Spanned<RawAxis>>>,
    random: Option<Spanned<RawRandom>>,
    metrics: Option<Spanned<RawMetrics>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    integrator: Option<Spanned<String>>,
    dt: Option<RawNumber>,
    tol: Option<RawNumber>,
    t_end: Option<RawNumber>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    parameter: Option<Spanned<String>>,
    values: Option<Spanned<Vec<RawNumber>>>,
    range: Option<Spanned<Vec<RawNumber>>>,
    count: Option<RawNumber>,
    spacing: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRandom {
    samples: Option<RawNumber>,
    seed: Option<RawNumber>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMetrics {
    record: Option<Spanned<Vec<Spanned<String>>>>,
    tilt_threshold: Option<RawNumber>,
}

// ---------------------------------------------------------------------------------------
// Stage 2: a draft whose values know their origin.

/// A value and where it came from.
#[derive(Debug, Clone)]
struct Src<T> {
    value: T,
    at: Origin,
}

/// A number as written: a float, an integer, or a value of another type (an error when a
/// number is needed).
#[derive(Debug, Clone)]
enum Num {
    Float(f64),
    Int(i64),
    Other(String),
}

impl Num {
    fn from_toml(value: &toml::Value) -> Self {
        match value {
            toml::Value::Float(x) => Num::Float(*x),
            toml::Value::Integer(i) => Num::Int(*i),
            other => Num::Other(describe(other)),
        }
    }
}

impl Src<Num> {
    /// As a float (integers exactly representable as one).
    fn float(&self, key: &str) -> Result<f64, SweepFileError> {
        match &self.value {
            Num::Float(x) => Ok(*x),
            Num::Int(i) if (*i as f64) as i64 == *i => Ok(*i as f64),
            Num::Int(i) => Err(self.not_a(
                key,
                "a number",
                format!("the integer {i}, which a float cannot hold exactly"),
            )),
            Num::Other(found) => Err(self.not_a(key, "a number", found.clone())),
        }
    }

    /// As a whole number `≥ min` (overrides give floats: they must be whole).
    fn whole(&self, key: &str, min: u64, expected: &'static str) -> Result<u64, SweepFileError> {
        let n = match &self.value {
            Num::Int(i) => u64::try_from(*i).ok(),
            Num::Float(x) if x.fract() == 0.0 && *x >= 0.0 && *x < 2f64.powi(64) => Some(*x as u64),
            _ => None,
        };
        match n {
            Some(n) if n >= min => Ok(n),
            _ => Err(self.not_a(
                key,
                expected,
                match &self.value {
                    Num::Float(x) => format!("{x}"),
                    Num::Int(i) => format!("{i}"),
                    Num::Other(found) => found.clone(),
                },
            )),
        }
    }

    fn not_a(&self, key: &str, expected: &'static str, found: String) -> SweepFileError {
        SweepFileError::NotANumber {
            at: self.at.clone(),
            key: key.to_string(),
            expected,
            found,
        }
    }
}

#[derive(Debug, Clone)]
struct DraftAxis {
    at: Origin,
    parameter: Option<Src<String>>,
    values: Option<Src<Vec<Src<Num>>>>,
    start: Option<Src<Num>>,
    end: Option<Src<Num>>,
    /// The `range` key itself, when given.
    range: Option<Origin>,
    count: Option<Src<Num>>,
    spacing: Option<Src<String>>,
}

/// The `[random]` table: where it is, `samples`, `seed`.
type DraftRandom = (Origin, Option<Src<Num>>, Option<Src<Num>>);

#[derive(Debug, Clone)]
struct Draft {
    origin: String,
    scene: Option<Src<String>>,
    parameters: Vec<(Src<String>, Src<Num>)>,
    run_at: Option<Origin>,
    integrator: Option<Src<String>>,
    dt: Option<Src<Num>>,
    tol: Option<Src<Num>>,
    t_end: Option<Src<Num>>,
    axes: Vec<DraftAxis>,
    random: Option<DraftRandom>,
    record: Option<Src<Vec<Src<String>>>>,
    tilt_threshold: Option<Src<Num>>,
}

impl Draft {
    fn from_text(text: &str, origin: &str) -> Result<Self, SweepFileError> {
        let at = |span: Range<usize>| Origin::File(Location::at(origin, text, span.start));
        let raw: RawSweep = toml::from_str(text).map_err(|e| {
            let at = match e.span() {
                Some(span) => Location::at(origin, text, span.start),
                None => Location {
                    origin: origin.to_string(),
                    position: None,
                },
            };
            SweepFileError::Syntax {
                excerpt: excerpt(text, &at),
                at,
                message: e.message().trim_end().to_string(),
            }
        })?;
        let num = |v: &RawNumber| Src {
            value: Num::from_toml(v.get_ref()),
            at: at(v.span()),
        };
        let string = |v: &Spanned<String>| Src {
            value: v.get_ref().clone(),
            at: at(v.span()),
        };
        let mut parameters: Vec<_> = raw
            .parameters
            .unwrap_or_default()
            .iter()
            .map(|(k, v)| (string(k), num(v)))
            .collect();
        parameters.sort_by_key(|(k, _)| k.at.line());
        let (run_at, run) = match raw.run {
            Some(r) => (Some(at(r.span())), Some(r.into_inner())),
            None => (None, None),
        };
        let run = run.unwrap_or(RawRun {
            integrator: None,
            dt: None,
            tol: None,
            t_end: None,
        });
        let mut axes = Vec::new();
        for axis in raw.axes.unwrap_or_default() {
            let axis_at = at(axis.span());
            let axis = axis.into_inner();
            let (range, start, end) = match &axis.range {
                Some(r) => {
                    let items = r.get_ref();
                    if items.len() != 2 {
                        return Err(SweepFileError::Invalid {
                            at: at(r.span()),
                            key: "axes.range".into(),
                            reason: format!(
                                "a range is two numbers `[start, end]`, found {} values",
                                items.len()
                            ),
                        });
                    }
                    (
                        Some(at(r.span())),
                        Some(num(&items[0])),
                        Some(num(&items[1])),
                    )
                }
                None => (None, None, None),
            };
            axes.push(DraftAxis {
                at: axis_at,
                parameter: axis.parameter.as_ref().map(string),
                values: axis.values.as_ref().map(|v| Src {
                    value: v.get_ref().iter().map(num).collect(),
                    at: at(v.span()),
                }),
                start,
                end,
                range,
                count: axis.count.as_ref().map(num),
                spacing: axis.spacing.as_ref().map(string),
            });
        }
        let random = raw.random.map(|r| {
            let span = r.span();
            let r = r.into_inner();
            (
                at(span),
                r.samples.as_ref().map(num),
                r.seed.as_ref().map(num),
            )
        });
        let (record, tilt_threshold) = match raw.metrics {
            Some(m) => {
                let m = m.into_inner();
                (
                    m.record.map(|r| Src {
                        value: r.get_ref().iter().map(string).collect(),
                        at: at(r.span()),
                    }),
                    m.tilt_threshold.as_ref().map(num),
                )
            }
            None => (None, None),
        };
        Ok(Draft {
            origin: origin.to_string(),
            scene: raw.scene.as_ref().map(string),
            parameters,
            run_at,
            integrator: run.integrator.as_ref().map(string),
            dt: run.dt.as_ref().map(num),
            tol: run.tol.as_ref().map(num),
            t_end: run.t_end.as_ref().map(num),
            axes,
            random,
            record,
            tilt_threshold,
        })
    }

    /// Replaces (or adds) the key an override names.
    fn apply(&mut self, o: &Override) -> Result<(), SweepFileError> {
        let at = Origin::Override(o.text.clone());
        let value = Src {
            value: Num::Float(o.value),
            at: at.clone(),
        };
        let invalid = |reason: String| SweepFileError::Invalid {
            at: at.clone(),
            key: o.key.clone(),
            reason,
        };
        let parts: Vec<&str> = o.key.split('.').collect();
        match parts.as_slice() {
            [name] | ["parameters", name] => {
                let name = Src {
                    value: (*name).to_string(),
                    at: at.clone(),
                };
                match self
                    .parameters
                    .iter_mut()
                    .find(|(k, _)| k.value == name.value)
                {
                    Some(entry) => *entry = (name, value),
                    None => self.parameters.push((name, value)),
                }
            }
            ["run", "dt"] => self.dt = Some(value),
            ["run", "tol"] => self.tol = Some(value),
            ["run", "t_end"] => self.t_end = Some(value),
            ["metrics", "tilt_threshold"] => self.tilt_threshold = Some(value),
            ["random", which @ ("samples" | "seed")] => {
                let Some(random) = &mut self.random else {
                    return Err(invalid(
                        "this sweep is a grid; `random.*` applies to sweeps with a [random] table"
                            .into(),
                    ));
                };
                if *which == "samples" {
                    random.1 = Some(value);
                } else {
                    random.2 = Some(value);
                }
            }
            ["axes", name, field @ ("count" | "start" | "end")] => {
                let Some(axis) = self
                    .axes
                    .iter_mut()
                    .find(|a| a.parameter.as_ref().is_some_and(|p| p.value == *name))
                else {
                    let swept: Vec<&str> = self
                        .axes
                        .iter()
                        .filter_map(|a| a.parameter.as_ref().map(|p| p.value.as_str()))
                        .collect();
                    return Err(invalid(format!(
                        "no axis sweeps `{name}`; the axes are: {}",
                        swept.join(", ")
                    )));
                };
                match *field {
                    "count" => axis.count = Some(value),
                    "start" => axis.start = Some(value),
                    _ => axis.end = Some(value),
                }
            }
            _ => {
                return Err(invalid(
                    "unknown key; --set takes a scene parameter (NAME or parameters.NAME), \
                     run.dt, run.tol, run.t_end, metrics.tilt_threshold, random.samples, \
                     random.seed, or axes.NAME.count, axes.NAME.start, axes.NAME.end"
                        .into(),
                ));
            }
        }
        Ok(())
    }

    // -----------------------------------------------------------------------------------
    // Stage 3: validation.

    fn validate(self) -> Result<SweepDefinition, SweepFileError> {
        let known = || {
            scenes::builtin()
                .iter()
                .map(|s| s.info().name)
                .collect::<Vec<_>>()
                .join(", ")
        };
        let Some(scene_name) = &self.scene else {
            return Err(SweepFileError::MissingScene {
                origin: self.origin.clone(),
                known: known(),
            });
        };
        let scene_error = |at: &Origin, key: &str, error: SceneError| SweepFileError::Scene {
            at: at.clone(),
            key: key.to_string(),
            error: Box::new(error),
        };
        let scene =
            scenes::find(&scene_name.value).map_err(|e| scene_error(&scene_name.at, "scene", e))?;
        let info = scene.info();
        let file_at = Origin::File(Location {
            origin: self.origin.clone(),
            position: None,
        });

        // Axes first: a parameter may not be both fixed and swept.
        if self.axes.is_empty() {
            return Err(SweepFileError::NoAxes {
                origin: self.origin.clone(),
            });
        }
        let random = match &self.random {
            None => None,
            Some((at, samples, seed)) => {
                let samples = samples.as_ref().ok_or_else(|| SweepFileError::Invalid {
                    at: at.clone(),
                    key: "random.samples".into(),
                    reason: "missing: how many random points to draw".into(),
                })?;
                let seed = seed.as_ref().ok_or_else(|| SweepFileError::Invalid {
                    at: at.clone(),
                    key: "random.seed".into(),
                    reason: "missing: the seed of the generator (any whole number), so that the \
                             points can be drawn again"
                        .into(),
                })?;
                let samples = samples.whole("random.samples", 1, "a whole number >= 1")?;
                let seed = seed.whole("random.seed", 0, "a whole number >= 0")?;
                Some((samples, seed))
            }
        };
        let defaults = info.default_params();
        let mut axes: Vec<Axis> = Vec::new();
        let mut axis_origins: Vec<Origin> = Vec::new();
        for draft in &self.axes {
            let axis = self.axis(draft, &defaults, random.is_some())?;
            let at = draft
                .parameter
                .as_ref()
                .map_or(draft.at.clone(), |p| p.at.clone());
            if let Some(k) = axes.iter().position(|a| a.parameter == axis.parameter) {
                return Err(SweepFileError::Invalid {
                    at,
                    key: format!("axes.{}", axis.parameter),
                    reason: format!(
                        "`{}` is already swept by the axis at {}",
                        axis.parameter, axis_origins[k]
                    ),
                });
            }
            axes.push(axis);
            axis_origins.push(at);
        }

        // Fixed parameters.
        let mut params = defaults;
        for (name, value) in &self.parameters {
            let key = format!("parameters.{}", name.value);
            if let Some(k) = axes.iter().position(|a| a.parameter == name.value) {
                return Err(SweepFileError::Invalid {
                    at: name.at.clone(),
                    key,
                    reason: format!(
                        "`{}` is swept by the axis at {}; a parameter is either fixed or swept",
                        name.value, axis_origins[k]
                    ),
                });
            }
            let x = value.float(&key)?;
            params
                .set(&name.value, x)
                .map_err(|e| scene_error(&name.at, &key, e))?;
        }

        // Run options, validated as a whole by the scene.
        let number = |v: &Option<Src<Num>>, key: &str| {
            v.as_ref()
                .map(|s| s.float(key).map(|x| (x, s.at.clone())))
                .transpose()
        };
        let dt = number(&self.dt, "run.dt")?;
        let tol = number(&self.tol, "run.tol")?;
        let t_end = number(&self.t_end, "run.t_end")?;
        let run_at = self.run_at.clone().unwrap_or_else(|| file_at.clone());
        let step = match (&dt, &tol) {
            (Some((_, a)), Some((_, b))) => {
                return Err(SweepFileError::Invalid {
                    at: b.clone(),
                    key: "run.tol".into(),
                    reason: format!(
                        "`run.dt` ({a}) and `run.tol` are both given; a run has a fixed step or \
                         a tolerance, not both"
                    ),
                });
            }
            (Some((h, _)), None) => Some(StepControl::Fixed(*h)),
            (None, Some((tol, _))) => Some(StepControl::Tolerance(*tol)),
            (None, None) => None,
        };
        let options = RunOptions {
            integrator: self.integrator.as_ref().map(|s| s.value.clone()),
            step,
            t_end: t_end.as_ref().map(|(x, _)| *x),
            every: Some(1),
            observe: crate::scene::Observe::EveryStep,
        };
        let plan = options.resolve(info).map_err(|error| {
            let (key, at) = match &error {
                SceneError::UnsupportedIntegrator { .. } => (
                    "run.integrator",
                    self.integrator.as_ref().map(|s| s.at.clone()),
                ),
                SceneError::InvalidOption { option, .. } => match *option {
                    "dt" => ("run.dt", dt.as_ref().map(|d| d.1.clone())),
                    "tol" => ("run.tol", tol.as_ref().map(|d| d.1.clone())),
                    "t_end" => ("run.t_end", t_end.as_ref().map(|d| d.1.clone())),
                    _ => ("run", None),
                },
                _ => ("run", None),
            };
            scene_error(&at.unwrap_or_else(|| run_at.clone()), key, error)
        })?;

        // Metrics.
        let metrics = match &self.record {
            None => Metric::ALL
                .into_iter()
                .filter(|m| *m != Metric::TimeTiltExceeds && m.not_applicable(info).is_none())
                .collect(),
            Some(record) => {
                if record.value.is_empty() {
                    return Err(SweepFileError::Metric {
                        at: record.at.clone(),
                        reason: "empty: name at least one metric".into(),
                    });
                }
                let mut metrics: Vec<Metric> = Vec::new();
                for name in &record.value {
                    let Some(m) = Metric::from_name(&name.value) else {
                        return Err(SweepFileError::Metric {
                            at: name.at.clone(),
                            reason: format!(
                                "unknown metric `{}`; metrics: {}",
                                name.value,
                                Metric::ALL.map(Metric::name).join(", ")
                            ),
                        });
                    };
                    if let Some(why) = m.not_applicable(info) {
                        return Err(SweepFileError::Metric {
                            at: name.at.clone(),
                            reason: why,
                        });
                    }
                    if metrics.contains(&m) {
                        return Err(SweepFileError::Metric {
                            at: name.at.clone(),
                            reason: format!("`{m}` is listed twice"),
                        });
                    }
                    metrics.push(m);
                }
                metrics
            }
        };
        let wants_threshold = metrics.contains(&Metric::TimeTiltExceeds);
        let tilt_threshold = match (&self.tilt_threshold, wants_threshold) {
            (Some(v), true) => {
                let x = v.float("metrics.tilt_threshold")?;
                if !(x > 0.0 && x < std::f64::consts::FRAC_PI_2) {
                    return Err(SweepFileError::Invalid {
                        at: v.at.clone(),
                        key: "metrics.tilt_threshold".into(),
                        reason: format!(
                            "{x} rad: the threshold must lie strictly between 0 and pi/2 \
                             (a tilt is asin|n_z|, in [0, pi/2])"
                        ),
                    });
                }
                Some(x)
            }
            (Some(v), false) => {
                return Err(SweepFileError::Invalid {
                    at: v.at.clone(),
                    key: "metrics.tilt_threshold".into(),
                    reason: "only `time_tilt_exceeds` uses a threshold, and `metrics.record` \
                             does not list it"
                        .into(),
                });
            }
            (None, true) => {
                return Err(SweepFileError::Invalid {
                    at: self
                        .record
                        .as_ref()
                        .map_or(file_at.clone(), |r| r.at.clone()),
                    key: "metrics.tilt_threshold".into(),
                    reason: "missing: `time_tilt_exceeds` needs `tilt_threshold = ANGLE` (rad) \
                             in [metrics]"
                        .into(),
                });
            }
            (None, false) => None,
        };

        let definition = SweepDefinition {
            origin: self.origin.clone(),
            scene,
            params,
            plan,
            axes,
            sampling: match random {
                Some((samples, seed)) => Sampling::Random { samples, seed },
                None => Sampling::Grid,
            },
            metrics,
            tilt_threshold,
        };
        // The product of the counts, without overflow.
        let mut total: u64 = 1;
        if definition.sampling == Sampling::Grid {
            for (axis, at) in definition.axes.iter().zip(&axis_origins) {
                total = total
                    .checked_mul(axis.count().unwrap_or(0))
                    .filter(|&n| n <= MAX_POINTS)
                    .ok_or_else(|| SweepFileError::Invalid {
                        at: at.clone(),
                        key: format!("axes.{}.count", axis.parameter),
                        reason: format!("the grid has more than {MAX_POINTS} points"),
                    })?;
            }
        } else if definition.points() > MAX_POINTS {
            let at = self.random.as_ref().map_or(file_at, |r| r.0.clone());
            return Err(SweepFileError::Invalid {
                at,
                key: "random.samples".into(),
                reason: format!("more than {MAX_POINTS} points"),
            });
        }
        Ok(definition)
    }

    /// Validates one axis against the scene's parameters.
    fn axis(
        &self,
        draft: &DraftAxis,
        defaults: &Params,
        random: bool,
    ) -> Result<Axis, SweepFileError> {
        let Some(parameter) = &draft.parameter else {
            return Err(SweepFileError::Invalid {
                at: draft.at.clone(),
                key: "axes.parameter".into(),
                reason: "missing: the scene parameter this axis sweeps".into(),
            });
        };
        let name = parameter.value.as_str();
        let key = |field: &str| format!("axes.{name}.{field}");
        // An unknown name: the scene's own error, which lists its parameters.
        if let Err(error) = defaults.get(name) {
            return Err(SweepFileError::Scene {
                at: parameter.at.clone(),
                key: "axes.parameter".into(),
                error: Box::new(error),
            });
        }
        let spec = defaults
            .specs()
            .iter()
            .find(|s| s.name == name)
            .ok_or_else(|| SweepFileError::Invalid {
                at: parameter.at.clone(),
                key: "axes.parameter".into(),
                reason: format!("`{name}` has no specification"),
            })?;
        // Every value must be a valid value of the parameter.
        let check = |x: f64, at: &Origin, field: &str| -> Result<(), SweepFileError> {
            let mut p = defaults.clone();
            p.set(name, x).map_err(|e| SweepFileError::Scene {
                at: at.clone(),
                key: key(field),
                error: Box::new(e),
            })
        };
        let spacing = match &draft.spacing {
            None => Spacing::Linear,
            Some(s) => match s.value.as_str() {
                "linear" => Spacing::Linear,
                "log" => Spacing::Log,
                other => {
                    return Err(SweepFileError::Invalid {
                        at: s.at.clone(),
                        key: key("spacing"),
                        reason: format!("`{other}`: spacing is \"linear\" or \"log\""),
                    });
                }
            },
        };
        let values = match (&draft.values, &draft.start) {
            (Some(v), None) => {
                for (field, given) in [("count", draft.count.as_ref().map(|c| &c.at))]
                    .into_iter()
                    .chain([("spacing", draft.spacing.as_ref().map(|s| &s.at))])
                {
                    if let Some(at) = given {
                        return Err(SweepFileError::Invalid {
                            at: at.clone(),
                            key: key(field),
                            reason: format!("`{field}` goes with a `range`, not with `values`"),
                        });
                    }
                }
                if random {
                    return Err(SweepFileError::Invalid {
                        at: v.at.clone(),
                        key: key("values"),
                        reason: "random samples are drawn in a `range`; `values` lists grid \
                                 values"
                            .into(),
                    });
                }
                if v.value.is_empty() {
                    return Err(SweepFileError::Invalid {
                        at: v.at.clone(),
                        key: key("values"),
                        reason: "empty: list at least one value".into(),
                    });
                }
                let mut list = Vec::with_capacity(v.value.len());
                for item in &v.value {
                    let x = item.float(&key("values"))?;
                    check(x, &item.at, "values")?;
                    list.push(x);
                }
                AxisValues::List(list)
            }
            (None, Some(start_src)) => {
                let end_src = draft.end.as_ref().unwrap_or(start_src);
                let start = start_src.float(&key("range"))?;
                let end = end_src.float(&key("range"))?;
                check(start, &start_src.at, "range")?;
                check(end, &end_src.at, "range")?;
                let range_at = draft.range.clone().unwrap_or_else(|| start_src.at.clone());
                if !(end > start) {
                    return Err(SweepFileError::Invalid {
                        at: range_at,
                        key: key("range"),
                        reason: format!(
                            "[{start}, {end}]: the range must be increasing (start < end)"
                        ),
                    });
                }
                if spacing == Spacing::Log && !(start > 0.0) {
                    return Err(SweepFileError::Invalid {
                        at: range_at,
                        key: key("range"),
                        reason: format!(
                            "[{start}, {end}]: a \"log\" spacing needs a positive range"
                        ),
                    });
                }
                let count = match (&draft.count, random) {
                    (Some(c), false) => Some(c.whole(&key("count"), 2, "a whole number >= 2")?),
                    (None, false) => {
                        return Err(SweepFileError::Invalid {
                            at: range_at,
                            key: key("count"),
                            reason: "missing: how many grid values the range holds (>= 2)".into(),
                        });
                    }
                    (Some(c), true) => {
                        return Err(SweepFileError::Invalid {
                            at: c.at.clone(),
                            key: key("count"),
                            reason: "random sweeps draw `random.samples` points; an axis of \
                                     one has no count"
                                .into(),
                        });
                    }
                    (None, true) => None,
                };
                AxisValues::Range {
                    start,
                    end,
                    count,
                    spacing,
                }
            }
            (Some(_), Some(start)) => {
                return Err(SweepFileError::Invalid {
                    at: draft.range.clone().unwrap_or_else(|| start.at.clone()),
                    key: key("range"),
                    reason: "give either `values` or a `range`, not both".into(),
                });
            }
            (None, None) => {
                return Err(SweepFileError::Invalid {
                    at: draft.at.clone(),
                    key: key("range"),
                    reason: "missing: an axis takes `values = [..]` or `range = [start, end]`"
                        .into(),
                });
            }
        };
        Ok(Axis {
            parameter: spec.name,
            unit: spec.unit,
            values,
        })
    }
}
