//! Stage 3 of reading a sweep file: the draft validated into a [`SweepDefinition`], part by
//! part (scene, sampling, axes, fixed parameters, run plan, metrics, size), each error naming
//! the key and its origin.

use super::super::definition::{Axis, AxisValues, MAX_POINTS, Sampling, Spacing, SweepDefinition};
use super::super::file_error::{Origin, SweepFileError};
use super::super::metrics::Metric;
use super::super::value::{Num, Src};
use super::{Draft, DraftAxis};
use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{RunOptions, RunPlan, Scene, StepControl};
use tumble_scenarios::toml_file::{Location, TomlFileError};

impl Draft {
    pub(in crate::sweep) fn validate(self) -> Result<SweepDefinition, SweepFileError> {
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
