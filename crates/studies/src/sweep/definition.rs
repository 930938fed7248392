//! The validated sweep: scene, fixed parameters, run plan, axes, sampling and metrics, with
//! the points it runs and its canonical text.

use std::fmt;
use std::path::Path;

use super::draft::Draft;
use super::file_error::SweepFileError;
use super::metrics::Metric;
use super::overrides::Override;
use super::refine::{Lattice, Refinement};
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{Reduction, RunPlan, Scene, StepControl, TiltLanes};
use tumble_scenarios::toml_file;

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
    /// Whether the axis is drawn on a logarithmic scale: a `log`-spaced range, or listed
    /// values that are positive and spaced by equal ratios (to 1e-9).
    #[must_use]
    pub fn is_log(&self) -> bool {
        match &self.values {
            AxisValues::Range { spacing, .. } => *spacing == Spacing::Log,
            AxisValues::List(v) => {
                v.len() >= 3 && v.iter().all(|&x| x > 0.0) && v.windows(2).all(|w| w[1] > w[0]) && {
                    let ratio = v[1] / v[0];
                    ratio > 1.5
                        && v.windows(2)
                            .all(|w| ((w[1] / w[0]) / ratio - 1.0).abs() < 1e-9)
                }
            }
        }
    }

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
                    Spacing::Log => log_value(*start, *end, k, m),
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

/// The `k`-th of `m + 1` log-spaced values from `start` to `end`: `10^(a + (b − a) k/m)` with
/// `a, b` the decimal logarithms; a value whose exponent is a whole number (to round-off) is the
/// decade itself, parsed from its decimal form, so that `1e-4` is `1e-4` and not
/// `0.00010000000000000002` (the signs of `start` and `end` are equal; a negative range is the
/// mirror image).
fn log_value(start: f64, end: f64, k: f64, m: f64) -> f64 {
    let sign = start.signum();
    let (a, b) = (start.abs().log10(), end.abs().log10());
    let exponent = a + (b - a) * k / m;
    let rounded = exponent.round();
    let value = if (exponent - rounded).abs() <= 1e-12 * exponent.abs().max(1.0) {
        format!("1e{rounded}")
            .parse::<f64>()
            .unwrap_or(10f64.powf(rounded))
    } else {
        10f64.powf(exponent)
    };
    sign * value
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
    /// `metrics.tolerance`: the largest change of a metric the self-check accepts (the
    /// command line's `--check-tolerance` overrides it; 1e-6 when neither is given).
    pub check_tolerance: Option<f64>,
    /// `[refine]`: adaptive refinement of the grid (`None`: every point of the grid).
    pub refine: Option<Refinement>,
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
            .field("check_tolerance", &self.check_tolerance)
            .field("refine", &self.refine)
            .finish()
    }
}

/// Most points a sweep may have.
///
/// The engine lists the points a run still has to compute (8 bytes each), so this bounds that
/// list to 800 MB; a larger study is a set of sweeps (or shards of one) below it. A grid of
/// 10¹² points once passed validation and aborted on the allocation.
pub const MAX_POINTS: u64 = 100_000_000;

impl SweepDefinition {
    /// Reads, overrides and validates the sweep file at `path`.
    ///
    /// # Errors
    /// [`TomlFileError::Read`], or as [`SweepDefinition::parse`].
    pub fn load(path: &Path, overrides: &[Override]) -> Result<Self, SweepFileError> {
        let text = toml_file::read(path, "sweep")?;
        Self::parse(&text, &path.display().to_string(), overrides)
    }

    /// The smaller model the sweep's points run, when there is one that serves: the scene's
    /// [`Reduction`] if the plan's method integrates it (a vector-space method: the Lie-group
    /// methods need the full rotation) and every metric reads only its columns
    /// (`max_energy_rel_err` reads the energy, which every reduction has). `None`: the scene's
    /// full model runs.
    #[must_use]
    pub fn reduction(&self) -> Option<&'static Reduction> {
        let reduction = self.scene.reduction()?;
        let served = self
            .metrics
            .iter()
            .all(|m| match m.as_column(self.tilt_threshold) {
                Some((_, column)) => reduction.columns.contains(&column),
                None => *m == Metric::MaxEnergyRelErr,
            });
        (served && reduction.runs(&self.plan)).then_some(reduction)
    }

    /// The reduction's lanes when they serve this sweep: its reduction runs them
    /// ([`Self::reduction`]), they run its plan, and every metric is one of the tilt metrics
    /// they report (`max_tilt`, `final_tilt`, `time_tilt_exceeds`, `max_energy_rel_err`).
    #[must_use]
    pub fn lanes(&self) -> Option<&'static TiltLanes> {
        let lanes = self.reduction()?.lanes.as_ref()?;
        let served = self.metrics.iter().all(|m| {
            matches!(
                m,
                Metric::MaxTilt
                    | Metric::FinalTilt
                    | Metric::TimeTiltExceeds
                    | Metric::MaxEnergyRelErr
            )
        });
        (served && (lanes.runs)(&self.plan)).then_some(lanes)
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

    /// The refinement level of point `index` of a refined sweep ([`super::refine`]); `None`
    /// for a sweep that is not refined.
    #[must_use]
    pub fn level(&self, index: u64) -> Option<u32> {
        Lattice::of(self).map(|l| l.level(index))
    }

    /// The header of `results.csv`: `index`, `level` (refined sweeps), the axes, the metrics,
    /// `status`, `reason`.
    #[must_use]
    pub fn columns(&self) -> Vec<String> {
        std::iter::once("index".to_string())
            .chain(self.refine.is_some().then(|| "level".to_string()))
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
        if let Some(tol) = self.check_tolerance {
            let _ = writeln!(s, "tolerance = {}", float(tol));
        }
        if let Some(r) = &self.refine {
            let _ = writeln!(
                s,
                "\n[refine]\nlevels = {}\nmetric = {:?}\nthreshold = {}",
                r.levels,
                r.metric.name(),
                float(r.threshold)
            );
        }
        s
    }
}

/// A float as TOML: Rust's shortest round-trip form (`0.1`, `1e-10`, `9.81`, `2.0`).
fn float(x: f64) -> String {
    format!("{x:?}")
}
