//! Stages 2 and 3 of reading a sweep file: a draft whose every value remembers where it came
//! from (a `file:line:column`, or the `--set KEY=VALUE` that replaced it), overrides applied to
//! it, and its validation into a [`SweepDefinition`], part by part (scene, sampling, axes,
//! fixed parameters, run plan, metrics, size), each error naming the key and that origin.

mod validate;

use std::ops::Range;

use toml::Spanned;

use super::file_error::{Origin, SweepFileError};
use super::overrides::{Override, OverrideValue};
use super::raw::{RawNumber, RawRun, RawSweep};
use super::refine::DraftRefine;
use super::value::{Num, Src};
use tumble_scenarios::toml_file::{self, Location};

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
}
