//! Whether a fixed step resolves the motion it integrates: the one rule `simulate` and sweeps
//! apply before any step.
//!
//! A fixed step `h` that turns the initial state's fastest rotation ([`Scene::initial_rate`])
//! by more than [`MAX_ANGLE_PER_STEP`] a step (`h · |ω| > 0.5`, fewer than about 12 steps a
//! turn) does not resolve the motion: such runs returned energy errors of several percent with
//! nothing to say so. Adaptive runs choose their own steps and the exact flow has no step
//! error, so the rule does not apply to them.

use crate::error::SceneError;
use crate::params::Params;
use crate::scene::{MAX_ANGLE_PER_STEP, RunPlan, Scene, StepControl};

/// A fixed step judged against the fastest rate of an initial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResolution {
    /// The fixed step (s).
    pub dt: f64,
    /// The fastest angular rate of the initial state (rad/s; an upper estimate).
    pub rate: f64,
}

impl StepResolution {
    /// The fixed step of `plan` judged against `scene`'s initial rate at `params`; `None` when
    /// the rule does not apply: an adaptive plan, the exact flow (its step only spaces the
    /// rows), or a scene without an initial rate.
    ///
    /// # Errors
    /// A parameter the scene's rate needs is missing.
    pub fn of(
        scene: &dyn Scene,
        params: &Params,
        plan: &RunPlan,
    ) -> Result<Option<Self>, SceneError> {
        let StepControl::Fixed(dt) = plan.step else {
            return Ok(None);
        };
        if plan.method.properties.exact {
            return Ok(None);
        }
        match scene.initial_rate(params) {
            None => Ok(None),
            Some(rate) => Ok(Some(Self { dt, rate: rate? })),
        }
    }

    /// The angle (rad) the step turns at the rate.
    #[must_use]
    pub fn angle(&self) -> f64 {
        self.dt * self.rate
    }

    /// Whether the step resolves the rate: `h · |ω| ≤` [`MAX_ANGLE_PER_STEP`] (a rate that is
    /// not finite is never resolved).
    #[must_use]
    pub fn resolved(&self) -> bool {
        self.angle() <= MAX_ANGLE_PER_STEP
    }

    /// A step that resolves the rate with a margin of two (`h · |ω| ≤ 0.25`), rounded down to
    /// one significant digit; `None` when the rate is not finite or the step would underflow.
    #[must_use]
    pub fn suggested_step(&self) -> Option<f64> {
        let x = 0.5 * MAX_ANGLE_PER_STEP / self.rate;
        if !(x.is_finite() && x > 0.0) {
            return None;
        }
        let scale = 10f64.powf(x.log10().floor());
        let r = (x / scale).floor() * scale;
        Some(if r > 0.0 && r.is_finite() { r } else { x })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_is_resolved_up_to_half_a_radian_and_the_suggestion_resolves_it_twice_over() {
        let r = StepResolution {
            dt: 0.01,
            rate: 50.0,
        };
        assert!(r.resolved());
        let r = StepResolution {
            dt: 0.01,
            rate: 50.1,
        };
        assert!(!r.resolved());
        let h = r.suggested_step().unwrap();
        assert_eq!(h, 0.004);
        assert!(h * r.rate <= 0.5 * MAX_ANGLE_PER_STEP);
    }

    #[test]
    fn an_infinite_rate_is_never_resolved_and_has_no_suggested_step() {
        let r = StepResolution {
            dt: 0.01,
            rate: f64::INFINITY,
        };
        assert!(!r.resolved());
        assert_eq!(r.suggested_step(), None);
        let nan = StepResolution {
            dt: 0.01,
            rate: f64::NAN,
        };
        assert!(!nan.resolved());
        assert_eq!(nan.suggested_step(), None);
    }
}
