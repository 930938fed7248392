//! The measurements behind a scene's recommendations (`tumble work-precision SCENE
//! --recommend FILE`): for each error band, every method's wall time to the band's finest error
//! from its work–precision ladder (the ladders retimed in turns); for each long horizon, every
//! method's relative energy error over a long run at the scene's default step.

use tumble_integrators::registry;
use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::recommendation::{
    Band, LONG_RUN_TOLERANCE, LongRun, LongRuns, Measure, Recommendation, TimeToError,
};
use tumble_scenarios::scene::{Scene, StepControl};

use super::{Config, FinalState, Ladder, RETIME_ROUNDS, Rung, control_words, ladder, retime};

/// The cost at which a ladder reaches `target`, interpolated log–log between the last rung
/// above it and the first rung at or below it (the first rung's cost when that is already
/// below; `None` if the ladder never gets there).
pub fn cost_at(rungs: &[Rung], target: f64, cost: impl Fn(&Rung) -> f64) -> Option<f64> {
    let i = rungs.iter().position(|r| r.error <= target)?;
    if i == 0 {
        return Some(cost(&rungs[0]));
    }
    let (a, b) = (&rungs[i - 1], &rungs[i]);
    let (ea, eb) = (a.error.log10(), b.error.log10());
    let (ca, cb) = (cost(a).log10(), cost(b).log10());
    if !(ea > eb) {
        return Some(cost(b));
    }
    let s = (ea - target.log10()) / (ea - eb);
    Some(10f64.powf(ca + s * (cb - ca)))
}

/// Measures `recommendations` on `scene` at `params` (module doc): the ladders of every method
/// an error band names run against `reference` with `config` (`progress` sees each rung with
/// its method) and are retimed in [`RETIME_ROUNDS`] rounds; the long runs take `long_steps`
/// steps of the scene's default step (an adaptive method at [`LONG_RUN_TOLERANCE`]), each cut
/// after `long_seconds` of wall time when given (its failure is then recorded).
///
/// # Errors
/// A method the scene does not take, or a rung that fails on retiming although it ran in its
/// ladder.
pub fn measure_recommendations(
    scene: &dyn Scene,
    params: &Params,
    recommendations: &[Recommendation],
    reference: &FinalState,
    config: &Config,
    long_steps: u64,
    long_seconds: Option<f64>,
    progress: &mut dyn FnMut(&str, &Rung),
) -> Result<(Vec<Band>, Vec<LongRuns>), SceneError> {
    let mut names: Vec<&str> = Vec::new();
    for r in recommendations {
        if let Measure::ToError(_) = r.measure {
            for name in r.measured_methods() {
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
    }
    let mut ladders: Vec<Ladder> = Vec::with_capacity(names.len());
    for name in &names {
        let mut on_rung = |rung: &Rung| progress(name, rung);
        ladders.push(ladder(
            scene,
            params,
            name,
            reference,
            config,
            &mut on_rung,
        )?);
    }
    retime(scene, params, &mut ladders, config, RETIME_ROUNDS)?;
    let bands = recommendations
        .iter()
        .filter_map(|r| match r.measure {
            Measure::ToError(target) => Some(Band {
                purpose: r.purpose.to_string(),
                target_error: target,
                methods: r
                    .measured_methods()
                    .filter_map(|name| ladders.iter().find(|l| l.integrator == name))
                    .map(|l| TimeToError {
                        integrator: l.integrator.clone(),
                        seconds: cost_at(&l.rungs, target, |r| r.wall_time_s),
                        evaluations: cost_at(&l.rungs, target, |r| r.evaluations as f64),
                        best_error: l
                            .rungs
                            .iter()
                            .map(|r| r.error)
                            .fold(f64::INFINITY, f64::min),
                    })
                    .collect(),
            }),
            Measure::LongRun | Measure::Nothing => None,
        })
        .collect();
    let h = scene.info().default_step;
    let mut long = Vec::new();
    for r in recommendations
        .iter()
        .filter(|r| r.measure == Measure::LongRun)
    {
        let runs = r
            .measured_methods()
            .map(|name| {
                let adaptive = registry::find(name)?.properties.adaptive;
                let control = if adaptive {
                    StepControl::Tolerance(LONG_RUN_TOLERANCE)
                } else {
                    StepControl::Fixed(h)
                };
                Ok((name.to_string(), control))
            })
            .collect::<Result<Vec<_>, tumble_integrators::Error>>()?;
        let runs = super::long_runs(
            scene,
            params,
            &runs,
            h * long_steps as f64,
            h,
            240,
            long_seconds,
        );
        long.push(LongRuns {
            purpose: r.purpose.to_string(),
            steps: long_steps,
            dt: h,
            methods: runs
                .into_iter()
                .map(|run| {
                    let failed = run.result.as_ref().err().cloned();
                    let max = run.history.points().iter().map(|p| p.1).fold(0.0, f64::max);
                    LongRun {
                        integrator: run.integrator.clone(),
                        control: control_words(run.control),
                        max_energy_rel_err: failed.is_none().then_some(max),
                        growth: failed
                            .is_none()
                            .then(|| run.history.growth_exponent(2.0))
                            .flatten(),
                        seconds: run.seconds,
                        failed,
                    }
                })
                .collect(),
        });
    }
    Ok((bands, long))
}
