//! Stages 2 and 3 of reading a sweep file: a draft whose every value remembers where it came
//! from (a `file:line:column`, or the `--set KEY=VALUE` that replaced it), overrides applied to
//! it, and its validation into a [`SweepDefinition`], part by part (scene, sampling, axes,
//! fixed parameters, run plan, metrics, size), each error naming the key and that origin.

use std::ops::Range;

use toml::Spanned;

use super::definition::{Axis, AxisValues, MAX_POINTS, Sampling, Spacing, SweepDefinition};
use super::file_error::{Origin, SweepFileError};
use super::metrics::Metric;
use super::overrides::{Override, OverrideValue};
use super::raw::{RawNumber, RawRun, RawSweep};
use super::refine::DraftRefine;
use super::value::{Num, Src};
use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{RunOptions, RunPlan, Scene, StepControl};
use tumble_scenarios::toml_file::{self, Location, TomlFileError};

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
pub(super) struct Draft {
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
    check_tolerance: Option<Src<Num>>,
    refine: Option<DraftRefine>,
}

impl Draft {
    pub(super) fn from_text(text: &str, origin: &str) -> Result<Self, SweepFileError> {
        let at = |span: Range<usize>| Origin::File(Location::at(origin, text, span.start));
        let raw: RawSweep = toml_file::parse(text, origin)?;
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
        let (record, tilt_threshold, check_tolerance) = match raw.metrics {
            Some(m) => {
                let m = m.into_inner();
                (
                    m.record.map(|r| Src {
                        value: r.get_ref().iter().map(string).collect(),
                        at: at(r.span()),
                    }),
                    m.tilt_threshold.as_ref().map(num),
                    m.tolerance.as_ref().map(num),
                )
            }
            None => (None, None, None),
        };
        let refine = raw.refine.map(|r| {
            let span = r.span();
            let r = r.into_inner();
            DraftRefine {
                at: at(span),
                levels: r.levels.as_ref().map(num),
                metric: r.metric.as_ref().map(string),
                threshold: r.threshold.as_ref().map(num),
            }
        });
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
            check_tolerance,
            refine,
        })
    }

    /// Replaces (or adds) the key an override names.
    pub(super) fn apply(&mut self, o: &Override) -> Result<(), SweepFileError> {
        let at = Origin::Override(o.text.clone());
        let invalid = |reason: String| SweepFileError::Invalid {
            at: at.clone(),
            key: o.key.clone(),
            reason,
        };
        let wants = if Override::takes_text(&o.key) {
            "a name"
        } else if Override::takes_list(&o.key) {
            "a list of numbers such as [0.5, 1, pi/2]"
        } else {
            "a number"
        };
        let mismatch = || invalid(format!("expects {wants}"));
        let number = match &o.value {
            OverrideValue::Number(x) => Some(*x),
            _ => None,
        };
        let value = Src {
            value: Num::Float(number.unwrap_or(f64::NAN)),
            at: at.clone(),
        };
        match (
            &o.value,
            Override::takes_text(&o.key),
            Override::takes_list(&o.key),
        ) {
            (OverrideValue::Text(_), true, _)
            | (OverrideValue::List(_), _, true)
            | (OverrideValue::Number(_), false, false) => {}
            _ => return Err(mismatch()),
        }
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
            ["run", "integrator"] => {
                if let OverrideValue::Text(name) = &o.value {
                    self.integrator = Some(Src {
                        value: name.clone(),
                        at: at.clone(),
                    });
                }
            }
            // A run has a step or a tolerance: setting one clears the other.
            ["run", "dt"] => {
                self.dt = Some(value);
                self.tol = None;
            }
            ["run", "tol"] => {
                self.tol = Some(value);
                self.dt = None;
            }
            ["run", "t_end"] => self.t_end = Some(value),
            ["metrics", "tilt_threshold"] => self.tilt_threshold = Some(value),
            ["metrics", "tolerance"] => self.check_tolerance = Some(value),
            ["refine", field @ ("levels" | "metric" | "threshold")] => {
                let refine = self.refine.get_or_insert_with(|| DraftRefine {
                    at: at.clone(),
                    levels: None,
                    metric: None,
                    threshold: None,
                });
                match *field {
                    "levels" => refine.levels = Some(value),
                    "threshold" => refine.threshold = Some(value),
                    _ => {
                        if let OverrideValue::Text(name) = &o.value {
                            refine.metric = Some(Src {
                                value: name.clone(),
                                at: at.clone(),
                            });
                        }
                    }
                }
            }
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
            [
                "axes",
                name,
                field @ ("count" | "start" | "end" | "spacing" | "values"),
            ] => {
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
                if *field == "values" {
                    // The axis becomes a list: its range keys no longer apply.
                    if let OverrideValue::List(list) = &o.value {
                        axis.values = Some(Src {
                            value: list
                                .iter()
                                .map(|&x| Src {
                                    value: Num::Float(x),
                                    at: at.clone(),
                                })
                                .collect(),
                            at: at.clone(),
                        });
                        axis.start = None;
                        axis.end = None;
                        axis.range = None;
                        axis.count = None;
                        axis.spacing = None;
                    }
                    return Ok(());
                }
                if axis.values.is_some() {
                    return Err(invalid(format!(
                        "the axis of `{name}` lists its `values`; it has no {field} to \
                         override (a `range` axis does)"
                    )));
                }
                match *field {
                    "count" => axis.count = Some(value),
                    "start" => axis.start = Some(value),
                    "spacing" => {
                        if let OverrideValue::Text(spacing) = &o.value {
                            axis.spacing = Some(Src {
                                value: spacing.clone(),
                                at: at.clone(),
                            });
                        }
                    }
                    _ => axis.end = Some(value),
                }
            }
            _ => {
                return Err(invalid(
                    "unknown key; --set takes a scene parameter (NAME or parameters.NAME), \
                     run.integrator, run.dt, run.tol, run.t_end, metrics.tilt_threshold, metrics.tolerance, \
                     random.samples, random.seed, axes.NAME.count, axes.NAME.start, \
                     axes.NAME.end, axes.NAME.spacing, axes.NAME.values, refine.levels, \
                     refine.metric or refine.threshold"
                        .into(),
                ));
            }
        }
        Ok(())
    }

    // -----------------------------------------------------------------------------------
    // Stage 3: validation.
    pub(super) fn validate(self) -> Result<SweepDefinition, SweepFileError> {
        let Some(scene_name) = &self.scene else {
            return Err(TomlFileError::missing_scene(&self.origin).into());
        };
        let scene = crate::models::find_scene(&scene_name.value, &self.origin)
            .map_err(|e| scene_error(&scene_name.at, "scene", e))?;
        let file_at = Origin::File(Location {
            origin: self.origin.clone(),
            position: None,
        });
        if self.axes.is_empty() {
            return Err(SweepFileError::NoAxes {
                origin: self.origin.clone(),
            });
        }
        // Axes first: a parameter may not be both fixed and swept.
        let random = self.sampling()?;
        let (axes, axis_origins) = self.swept_axes(scene, random.is_some())?;
        let params = self.fixed_parameters(scene, &axes, &axis_origins)?;
        let plan = self.run_plan(scene, &file_at)?;
        let metrics = self.metrics(scene)?;
        let tilt_threshold = self.tilt_threshold(&metrics, &file_at)?;
        let check_tolerance = match &self.check_tolerance {
            None => None,
            Some(v) => {
                let x = v.float("metrics.tolerance")?;
                if !(x.is_finite() && x > 0.0) {
                    return Err(SweepFileError::Invalid {
                        at: v.at.clone(),
                        key: "metrics.tolerance".into(),
                        reason: format!(
                            "{x}: the self-check's tolerance must be finite and positive"
                        ),
                    });
                }
                Some(x)
            }
        };
        let sampling = match random {
            Some((samples, seed)) => Sampling::Random { samples, seed },
            None => Sampling::Grid,
        };
        let refine = match &self.refine {
            Some(r) => r.validate(sampling, &metrics)?,
            None => None,
        };
        let definition = SweepDefinition {
            origin: self.origin.clone(),
            scene,
            params,
            plan,
            axes,
            sampling,
            metrics,
            tilt_threshold,
            check_tolerance,
            refine,
        };
        self.check_size(&definition, &axis_origins, file_at)?;
        Ok(definition)
    }

    /// `[random]`: `(samples, seed)`, or `None` for a grid.
    fn sampling(&self) -> Result<Option<(u64, u64)>, SweepFileError> {
        Ok(match &self.random {
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
        })
    }

    /// The axes, each validated against the scene's parameters, with where each is defined.
    fn swept_axes(
        &self,
        scene: &dyn Scene,
        random: bool,
    ) -> Result<(Vec<Axis>, Vec<Origin>), SweepFileError> {
        let defaults = scene.info().default_params();
        let mut axes: Vec<Axis> = Vec::new();
        let mut axis_origins: Vec<Origin> = Vec::new();
        for draft in &self.axes {
            let axis = self.axis(draft, &defaults, random)?;
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
        Ok((axes, axis_origins))
    }

    /// The fixed parameters: the scene's defaults with `[parameters]` set; a parameter may not
    /// be both fixed and swept.
    fn fixed_parameters(
        &self,
        scene: &dyn Scene,
        axes: &[Axis],
        axis_origins: &[Origin],
    ) -> Result<Params, SweepFileError> {
        let defaults = scene.info().default_params();
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
        Ok(params)
    }

    /// `[run]`, validated as a whole by the scene into the plan every point runs.
    fn run_plan(&self, scene: &dyn Scene, file_at: &Origin) -> Result<RunPlan, SweepFileError> {
        let info = scene.info();
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
            at: None,
            output_dt: None,
            max_steps: None,
            cancel: None,
            observe: tumble_scenarios::scene::Observe::EveryStep,
        };
        options.resolve(info).map_err(|error| {
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
        })
    }

    /// `metrics.record`, or every metric that applies to the scene (but `time_tilt_exceeds`,
    /// which needs a threshold).
    fn metrics(&self, scene: &dyn Scene) -> Result<Vec<Metric>, SweepFileError> {
        Ok(match &self.record {
            None => Metric::ALL
                .into_iter()
                .filter(|m| *m != Metric::TimeTiltExceeds && m.not_applicable(scene).is_none())
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
                    let m =
                        Metric::parse(&name.value).map_err(|reason| SweepFileError::Metric {
                            at: name.at.clone(),
                            reason,
                        })?;
                    if let Some(why) = m.not_applicable(scene) {
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
        })
    }

    /// `metrics.tilt_threshold`: required by `time_tilt_exceeds`, refused without it.
    fn tilt_threshold(
        &self,
        metrics: &[Metric],
        file_at: &Origin,
    ) -> Result<Option<f64>, SweepFileError> {
        let wants_threshold = metrics.contains(&Metric::TimeTiltExceeds);
        Ok(match (&self.tilt_threshold, wants_threshold) {
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
        })
    }

    /// At most [`MAX_POINTS`] points (the product of the counts, without overflow).
    fn check_size(
        &self,
        definition: &SweepDefinition,
        axis_origins: &[Origin],
        file_at: Origin,
    ) -> Result<(), SweepFileError> {
        let mut total: u64 = 1;
        if definition.sampling == Sampling::Grid {
            for (axis, at) in definition.axes.iter().zip(axis_origins) {
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
        Ok(())
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
                for (k, item) in v.value.iter().enumerate() {
                    let x = item.float(&key("values"))?;
                    check(x, &item.at, "values")?;
                    // A repeated value would compute the same points twice under two indices.
                    if let Some(first) = list.iter().position(|&y| y == x) {
                        return Err(SweepFileError::Invalid {
                            at: item.at.clone(),
                            key: key("values"),
                            reason: format!(
                                "{x} is listed twice (values {} and {}); list each value once",
                                first + 1,
                                k + 1
                            ),
                        });
                    }
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

/// The error for a key the scene rejected.
fn scene_error(at: &Origin, key: &str, error: SceneError) -> SweepFileError {
    SweepFileError::Scene {
        at: at.clone(),
        key: key.to_string(),
        error: Box::new(error),
    }
}
