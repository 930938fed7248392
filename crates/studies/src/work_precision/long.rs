//! Long runs: the relative energy error over a million steps and more, reduced to its maximum
//! over logarithmic time bins ([`EnergyHistory`]), the methods a long run compares, and the
//! matching of costs between fixed-step and adaptive methods (`tumble work-precision --long`).

use std::time::Instant;

use tumble_integrators::verification::fit_power_law;
use tumble_integrators::{Flow, registry};
use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{Observe, Recorder, RunSummary, Scene, SceneInfo, StepControl};

use super::{final_state, median, plan};

/// The relative energy error of a long run, reduced to its maximum over logarithmically
/// spaced time bins (the memory does not grow with the number of steps).
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyHistory {
    /// Upper edge of each bin (s); bin `i` covers `(edges[i-1], edges[i]]`, bin 0 `[0, edges[0]]`.
    pub edges: Vec<f64>,
    /// Largest `|E − E₀|/E_s` in each bin (`NaN` for a bin no step fell in).
    pub max_rel_err: Vec<f64>,
    column: usize,
}

impl EnergyHistory {
    /// `bins` bins spaced evenly in `log t` from `first` to `t_end`; `column` is the index of
    /// `energy_rel_err` in the scene's rows.
    #[must_use]
    pub fn new(first: f64, t_end: f64, bins: usize, column: usize) -> Self {
        let bins = bins.max(1);
        let ratio = (t_end / first).max(1.0).powf(1.0 / bins as f64);
        let edges = (1..=bins)
            .map(|i| {
                if i == bins {
                    t_end
                } else {
                    first * ratio.powi(i as i32)
                }
            })
            .collect();
        EnergyHistory {
            edges,
            max_rel_err: vec![f64::NAN; bins],
            column,
        }
    }

    /// `(t, max error)` of the bins that hold a step after the initial state.
    #[must_use]
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.edges
            .iter()
            .zip(&self.max_rel_err)
            .filter(|(_, e)| !e.is_nan())
            .map(|(t, e)| (*t, *e))
            .collect()
    }

    /// The least-squares exponent `a` of `max error ∝ tᵃ` over the bins in `[t_end/10^decades,
    /// t_end]`: about 0 for a bounded error, 1/2 for round-off growing like `√t` (Brouwer's
    /// law), 1 for a linear drift. `None` with fewer than 3 bins holding a positive error.
    #[must_use]
    pub fn growth_exponent(&self, decades: f64) -> Option<f64> {
        let t_end = *self.edges.last()?;
        power_law(
            self.points()
                .into_iter()
                .filter(|(t, e)| *t >= t_end / 10f64.powf(decades) && *e > 0.0),
        )
    }
}

impl Recorder for EnergyHistory {
    fn row(&mut self, values: &[f64]) -> Flow {
        let t = values[0];
        if t > 0.0 {
            let i = self.edges.partition_point(|&edge| edge < t);
            if let (Some(slot), Some(&e)) = (self.max_rel_err.get_mut(i), values.get(self.column)) {
                *slot = if slot.is_nan() { e } else { slot.max(e) };
            }
        }
        Flow::Continue
    }
}

/// The exponent of `y ≈ C xᵅ` through `points` by the verification harness's least-squares fit
/// ([`tumble_integrators::verification::fit_power_law`]); `None` below 3 points or when all `x`
/// are equal.
pub(super) fn power_law(points: impl Iterator<Item = (f64, f64)>) -> Option<f64> {
    let (xs, ys): (Vec<f64>, Vec<f64>) = points.unzip();
    if xs.len() < 3 {
        return None;
    }
    Some(fit_power_law(&xs, &ys)).filter(|a| a.is_finite())
}

/// One long run: its method, step control, summary and energy history.
#[derive(Debug, Clone, PartialEq)]
pub struct LongRun {
    /// Integrator.
    pub integrator: String,
    /// Step or tolerance.
    pub control: StepControl,
    /// The run's summary, or why it failed.
    pub result: Result<RunSummary, String>,
    /// Wall time (s); runs share the machine's cores, so only a rough figure.
    pub seconds: f64,
    /// Relative energy error against time.
    pub history: EnergyHistory,
}

/// The integrators a long run compares by default: the scene's symplectic, variational and
/// Lie-group methods with a fixed step (not the exact flow).
#[must_use]
pub fn long_run_methods(info: &SceneInfo) -> Vec<&'static str> {
    info.integrators()
        .into_iter()
        .filter(|name| {
            registry::find(name).is_ok_and(|m| {
                !m.properties.adaptive
                    && !m.properties.exact
                    && (m.properties.symplectic || m.properties.lie_group)
            })
        })
        .collect()
}

/// Seconds of wall time per simulated second of `integrator` at `control`, from the median of
/// 3 runs over `t_probe` that observe only their ends.
///
/// # Errors
/// The run's error.
pub fn cost_per_second(
    scene: &dyn Scene,
    params: &Params,
    integrator: &str,
    control: StepControl,
    t_probe: f64,
) -> Result<f64, SceneError> {
    let quiet = plan(scene.info(), integrator, control, t_probe, Observe::Ends)?;
    let mut times = Vec::with_capacity(3);
    for _ in 0..3 {
        let start = Instant::now();
        final_state(scene, params, &quiet)?;
        times.push(start.elapsed().as_secs_f64());
    }
    Ok(median(&mut times) / t_probe)
}

/// How far a cost lies from a target cost: `|ln(cost / target)|`, the same for 2× above and 2×
/// below.
#[must_use]
pub fn cost_distance(cost: f64, target: f64) -> f64 {
    (cost / target).ln().abs()
}

/// The tolerance among `1e-4 … 1e-13` (decades) at which `adaptive` costs closest (in the
/// log) to `target` seconds per simulated second, probed over `t_probe`, with its cost.
///
/// # Errors
/// A failing probe.
pub fn matching_tolerance(
    scene: &dyn Scene,
    params: &Params,
    adaptive: &str,
    target: f64,
    t_probe: f64,
) -> Result<(f64, f64), SceneError> {
    let mut best = (1e-4, f64::INFINITY, f64::INFINITY);
    for k in 4..=13 {
        let tol = 10f64.powi(-k);
        let cost = cost_per_second(
            scene,
            params,
            adaptive,
            StepControl::Tolerance(tol),
            t_probe,
        )?;
        let distance = cost_distance(cost, target);
        if distance < best.2 {
            best = (tol, cost, distance);
        }
        if cost > 4.0 * target {
            break;
        }
    }
    Ok((best.0, best.1))
}

/// The fixed step at which `integrator` costs `target` seconds per simulated second: from a
/// probe at `h`, each next step scales the last one that ran by its cost ratio (cost taken as
/// inversely proportional to the step), kept below the geometric mean of that step and the
/// shortest one that failed (a Newton solve that no longer converges, say); at most eight
/// probes, until the cost is within 10 %. The step divides `t_end` into whole steps. Returns
/// the step whose cost came closest and that cost.
///
/// # Errors
/// The probe at `h` failing.
pub fn matching_step(
    scene: &dyn Scene,
    params: &Params,
    integrator: &str,
    h: f64,
    target: f64,
    t_end: f64,
) -> Result<(f64, f64), SceneError> {
    let whole = |step: f64| t_end / (t_end / step).round().max(1.0);
    let probe = |step: f64| {
        cost_per_second(
            scene,
            params,
            integrator,
            StepControl::Fixed(step),
            (2000.0 * step).min(t_end),
        )
    };
    let mut ok = (h, probe(h)?);
    let mut best = ok;
    let mut failed = f64::INFINITY;
    for _ in 0..8 {
        if cost_distance(best.1, target) < 0.1 {
            break;
        }
        let mut step = ok.0 * ok.1 / target;
        if step > failed {
            step = (ok.0 * failed).sqrt();
        }
        let step = whole(step);
        if step == ok.0 {
            break;
        }
        match probe(step) {
            Ok(cost) => {
                ok = (step, cost);
                if cost_distance(cost, target) < cost_distance(best.1, target) {
                    best = ok;
                }
            }
            Err(_) => failed = failed.min(step),
        }
    }
    Ok(best)
}

/// Each long run (`work-precision --long`, and the long runs behind a scene's recommendations,
/// [`super::measure_recommendations`]) is limited to this multiple of
/// [`super::Config::max_run_seconds`] (`--max-seconds`): the `seconds` given to [`long_runs`].
pub const LONG_FACTOR: f64 = 600.0;

/// Runs `runs` (integrator, step or tolerance) over `[0, t_end]` in parallel, each recording
/// its relative energy error in `bins` logarithmic time bins from `first` on; each run is cut
/// after `seconds` of wall time when given (its result is then
/// [`tumble_integrators::Error::TimeLimit`]).
#[must_use]
pub fn long_runs(
    scene: &dyn Scene,
    params: &Params,
    runs: &[(String, StepControl)],
    t_end: f64,
    first: f64,
    bins: usize,
    seconds: Option<f64>,
) -> Vec<LongRun> {
    use rayon::prelude::*;
    let column = scene
        .info()
        .columns()
        .iter()
        .position(|c| c == "energy_rel_err")
        .unwrap_or(usize::MAX);
    runs.par_iter()
        .map(|(integrator, control)| {
            let mut history = EnergyHistory::new(first, t_end, bins, column);
            let start = Instant::now();
            let result = plan(
                scene.info(),
                integrator,
                *control,
                t_end,
                Observe::EveryStep,
            )
            .map(|p| match seconds.filter(|s| s.is_finite()) {
                Some(s) => p.with_deadline(s),
                None => p,
            })
            .and_then(|p| scene.simulate(params, &p, &mut history))
            .map_err(|e| e.to_string());
            LongRun {
                integrator: integrator.clone(),
                control: *control,
                result,
                seconds: start.elapsed().as_secs_f64(),
                history,
            }
        })
        .collect()
}
