//! Step-size control: a PI controller as a pure function.
//!
//! After a step with scaled error `err` (accept when `err ≤ 1`) and previous accepted error
//! `err_prev`, the next step is `h_new = h · fac` with
//!
//! `fac = clamp(safety · err^(−α) · err_prev^β, fac_min, fac_max)`, `α = 1/q − 0.75 β`,
//!
//! where `q` is the order of the error estimate plus one. `β = 0` is the classical
//! (integral, "I") controller; `β = 0.04` is the PI controller Hairer recommends for DP5.
//! After a rejection the step may not grow.
//!
//! # References
//! - K. Gustafsson, *Control theoretic techniques for stepsize selection in explicit
//!   Runge–Kutta methods*, ACM TOMS 17 (1991) 533–554.
//! - E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, §IV.2; and
//!   Hairer–Nørsett–Wanner I, §II.4 (the `hinit` starting-step algorithm).

/// Parameters of the PI step-size controller.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PiController {
    /// Safety factor (< 1).
    pub safety: f64,
    /// Weight `β` of the previous error (0 for a pure I controller).
    pub beta: f64,
    /// Smallest factor by which a step may shrink.
    pub fac_min: f64,
    /// Largest factor by which a step may grow.
    pub fac_max: f64,
}

impl PiController {
    /// Hairer's defaults for DP5 (`dopri5`): PI with `β = 0.04`.
    pub const DP5: Self = Self {
        safety: 0.9,
        beta: 0.04,
        fac_min: 0.2,
        fac_max: 10.0,
    };
    /// Hairer's defaults for DOP853: I controller.
    pub const DOP853: Self = Self {
        safety: 0.9,
        beta: 0.0,
        fac_min: 0.333,
        fac_max: 6.0,
    };

    /// The controller of Verner's pairs: DOP853's (an I controller, the step shrinks at most
    /// 3× and grows at most 6×).
    pub const VERNER: Self = Self::DOP853;

    /// Factor for the next step after an *accepted* step with error `err ≤ 1`.
    #[must_use]
    pub fn accepted_factor(&self, err: f64, err_prev: f64, q: u32, after_reject: bool) -> f64 {
        let alpha = 1.0 / f64::from(q) - 0.75 * self.beta;
        let mut fac = if err <= 0.0 {
            self.fac_max
        } else {
            // x⁰ = 1 for every x: DOP853's and Verner's controllers (β = 0) skip one power.
            let memory = if self.beta == 0.0 {
                1.0
            } else {
                err_prev.powf(self.beta)
            };
            self.safety * err.powf(-alpha) * memory
        };
        fac = fac.clamp(self.fac_min, self.fac_max);
        if after_reject { fac.min(1.0) } else { fac }
    }

    /// Factor (`< 1`) for retrying a *rejected* step with error `err > 1` (or NaN).
    #[must_use]
    pub fn rejected_factor(&self, err: f64, q: u32) -> f64 {
        if !err.is_finite() {
            return self.fac_min;
        }
        let alpha = 1.0 / f64::from(q) - 0.75 * self.beta;
        (self.safety * err.powf(-alpha)).clamp(self.fac_min, 1.0)
    }
}
