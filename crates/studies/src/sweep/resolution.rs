//! The coarse-step check of a sweep, before any point runs: the rule `simulate` applies to
//! one run ([`StepResolution`]: a fixed step must not turn the initial state's fastest rotation
//! by more than 0.5 rad), applied to the points of the sweep where the rate is largest.
//!
//! # Which points
//!
//! A grid may hold up to [`super::definition::MAX_POINTS`] points; judging each would cost as
//! much as listing them. The rate only depends on the parameters that set it (spins, rates,
//! moments of inertia), and every scene's [`tumble_scenarios::Scene::initial_rate`] is, in
//! each parameter with the others held, largest at an end of any interval: it is built from
//! `|x|`, `x²` and `1/x` (for `x > 0`) of single parameters, added or multiplied by
//! non-negative factors of the others, and monotone functions of those (`|ω| + |α̇| + √(g/a)`,
//! `|spin| √(1 + 2ε²)`, `√Σ (mᵢ/Iᵢ)²`).
//! Then the largest rate over the box spanned by the axes is at one of its corners: from any
//! point, moving one coordinate at a time to the end of its axis where the rate is not
//! smaller never lowers the rate. So the corners of the axes — each axis at its smallest and
//! its largest value, parameters that do not set the rate included — are the points checked:
//! at most `2^d` for `d` axes, and never more than a grid's points (an axis with two distinct
//! ends has at least two values). A set of random samples smaller than its corners is checked
//! point by point instead. A parameter fixed for the whole sweep is what the point holds.

use tumble_scenarios::StepResolution;
use tumble_scenarios::error::SceneError;

use super::definition::{AxisValues, Sampling, SweepDefinition};

/// The checked point of a sweep where its fixed step is coarsest against the rate.
#[derive(Debug, Clone, PartialEq)]
pub struct CoarsestPoint {
    /// The point's axis values, in axis order.
    pub values: Vec<f64>,
    /// Its index among the sweep's points (a grid's corner or a random sample); `None` for a
    /// corner of the ranges of random samples, which is not itself a sample.
    pub index: Option<u64>,
    /// The step judged against the rate there.
    pub resolution: StepResolution,
}

impl CoarsestPoint {
    /// `omega0 = 8, alpha0 = 0.5`.
    #[must_use]
    pub fn describe(&self, def: &SweepDefinition) -> String {
        let values: Vec<String> = def
            .axes
            .iter()
            .zip(&self.values)
            .map(|(a, v)| format!("{} = {v}", a.parameter))
            .collect();
        values.join(", ")
    }
}

/// The point of `def` (module doc: the corners of its axes) where its fixed step turns the
/// fastest initial rotation by the largest angle; `None` when the rule does not apply (a
/// tolerance, the exact flow, a scene without an initial rate).
///
/// # Errors
/// A parameter the scene's rate needs is missing, or an axis value the parameter does not
/// take (neither happens for a validated definition).
pub fn coarsest_point(def: &SweepDefinition) -> Result<Option<CoarsestPoint>, SceneError> {
    if StepResolution::of(def.scene, &def.params, &def.plan)?.is_none() {
        return Ok(None);
    }
    let ends: Vec<Vec<(f64, Option<u64>)>> = def.axes.iter().map(axis_ends).collect();
    let corners = ends
        .iter()
        .try_fold(1u64, |n, e| n.checked_mul(e.len() as u64));
    let mut worst: Option<CoarsestPoint> = None;
    let mut judge = |values: Vec<f64>, index: Option<u64>| -> Result<(), SceneError> {
        let mut params = def.params.clone();
        for (axis, &v) in def.axes.iter().zip(&values) {
            params.set(axis.parameter, v)?;
        }
        if let Some(resolution) = StepResolution::of(def.scene, &params, &def.plan)? {
            // A rate that is not a number is the worst of all.
            let worse = worst
                .as_ref()
                .is_none_or(|w| !(resolution.rate <= w.resolution.rate));
            if worse {
                worst = Some(CoarsestPoint {
                    values,
                    index,
                    resolution,
                });
            }
        }
        Ok(())
    };
    match (def.sampling, corners) {
        (Sampling::Random { samples, .. }, c) if c.is_none_or(|c| c > samples) => {
            for i in 0..samples {
                judge(def.point(i), Some(i))?;
            }
        }
        (_, Some(count)) => {
            let grid = matches!(def.sampling, Sampling::Grid);
            let mut choice = vec![0usize; ends.len()];
            for _ in 0..count {
                let values = choice.iter().zip(&ends).map(|(&c, e)| e[c].0).collect();
                let index = if grid {
                    grid_index(def, &choice, &ends)
                } else {
                    None
                };
                judge(values, index)?;
                // The next corner (the last axis fastest).
                for (c, e) in choice.iter_mut().zip(&ends).rev() {
                    *c += 1;
                    if *c < e.len() {
                        break;
                    }
                    *c = 0;
                }
            }
        }
        // More corners than a u64 counts: a grid that large is refused by its definition.
        (_, None) => {}
    }
    Ok(worst)
}

/// An axis's smallest and largest value, each with its grid index (`None` for the ends of a
/// range of random samples); one entry when they are equal.
fn axis_ends(axis: &super::definition::Axis) -> Vec<(f64, Option<u64>)> {
    let mut ends = match &axis.values {
        AxisValues::List(v) => {
            let position = |pick: fn(f64, f64) -> bool| {
                (0..v.len()).reduce(|best, k| if pick(v[k], v[best]) { k } else { best })
            };
            let lo = position(|a, b| a < b);
            let hi = position(|a, b| a > b);
            [lo, hi]
                .into_iter()
                .flatten()
                .map(|k| (v[k], Some(k as u64)))
                .collect::<Vec<_>>()
        }
        AxisValues::Range {
            start, end, count, ..
        } => vec![
            (*start, count.map(|_| 0)),
            (*end, count.map(|n| n.saturating_sub(1))),
        ],
    };
    ends.dedup_by(|a, b| a.0 == b.0);
    ends
}

/// The index of the grid point whose axes take the chosen ends.
fn grid_index(
    def: &SweepDefinition,
    choice: &[usize],
    ends: &[Vec<(f64, Option<u64>)>],
) -> Option<u64> {
    let mut index = 0u64;
    for ((axis, &c), e) in def.axes.iter().zip(choice).zip(ends) {
        index = index.checked_mul(axis.count()?)?.checked_add(e[c].1?)?;
    }
    Some(index)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sweep(axes: &str, run: &str) -> SweepDefinition {
        let text = format!(
            "scene = \"free-hoop\"\n[run]\n{run}\nt_end = 1.0\n{axes}\n[metrics]\n\
             record = [\"max_tilt\"]\n"
        );
        SweepDefinition::parse(&text, "test", &[]).unwrap()
    }

    const AXES: &str = "[[axes]]\nparameter = \"alpha0\"\nvalues = [0.5, 0.1, 2.0]\n\
        [[axes]]\nparameter = \"omega0\"\nrange = [-30.0, 10.0]\ncount = 5\n\
        [[axes]]\nparameter = \"alpha_dot0\"\nvalues = [3.0, -1.0]\n";

    #[test]
    fn the_coarsest_corner_is_where_the_rates_are_largest_with_its_grid_index() {
        let def = sweep(AXES, "integrator = \"gauss8\"\ndt = 0.01");
        let p = coarsest_point(&def).unwrap().unwrap();
        // |omega0| + |alpha_dot0| + √(g/a) is largest at omega0 = -30, alpha_dot0 = 3; alpha0
        // does not set the rate and stays at its first corner, its smallest value.
        assert_eq!(p.values, vec![0.1, -30.0, 3.0]);
        assert_eq!(p.resolution.rate, 33.0 + 9.81f64.sqrt());
        // alpha0 = 0.1 is its value 1, omega0 = -30 value 0, alpha_dot0 = 3 value 0.
        assert_eq!(p.index, Some(5 * 2));
        assert_eq!(def.point(10), p.values);
        assert!(p.resolution.resolved());
        assert_eq!(
            p.describe(&def),
            "alpha0 = 0.1, omega0 = -30, alpha_dot0 = 3"
        );
    }

    #[test]
    fn the_largest_rate_of_a_grid_is_at_a_corner() {
        let def = sweep(AXES, "integrator = \"gauss8\"\ndt = 0.01");
        let p = coarsest_point(&def).unwrap().unwrap();
        let largest = (0..def.points())
            .map(|i| {
                let mut params = def.params.clone();
                for (a, v) in def.axes.iter().zip(def.point(i)) {
                    params.set(a.parameter, v).unwrap();
                }
                def.scene.initial_rate(&params).unwrap().unwrap()
            })
            .fold(0.0, f64::max);
        assert_eq!(p.resolution.rate, largest);
    }

    #[test]
    fn adaptive_sweeps_are_exempt() {
        let def = sweep(AXES, "integrator = \"dop853\"\ntol = 1e-9");
        assert_eq!(coarsest_point(&def).unwrap(), None);
    }

    #[test]
    fn random_samples_fewer_than_the_corners_are_checked_one_by_one() {
        let axes = "[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 100.0]\n\
            [[axes]]\nparameter = \"alpha_dot0\"\nrange = [0.0, 1.0]\n\
            [random]\nsamples = 3\nseed = 7\n";
        let def = sweep(axes, "integrator = \"gauss8\"\ndt = 0.01");
        let p = coarsest_point(&def).unwrap().unwrap();
        let i = p.index.unwrap();
        assert!(i < 3);
        assert_eq!(def.point(i), p.values);
        // Below the corner's 101 + √9.81 rad/s: a sample, not the corner.
        let corner = 101.0 + 9.81f64.sqrt();
        assert!(p.resolution.rate < corner);
        let many = axes.replace("samples = 3", "samples = 50");
        let def = sweep(&many, "integrator = \"gauss8\"\ndt = 0.01");
        let p = coarsest_point(&def).unwrap().unwrap();
        assert_eq!((p.index, p.resolution.rate), (None, corner));
        assert!(!p.resolution.resolved());
    }
}
