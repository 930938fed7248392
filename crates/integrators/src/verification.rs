//! Verification harness: observed order, power-law fits, and test problems with exact
//! solutions. Shared by this crate's tests and by any crate that adds methods (the
//! Lie-group methods are measured with the same harness).
//!
//! # Observed order
//! [`OrderStudy`] runs a method at steps `h₀, h₀/2, h₀/4, …` (or another ratio), measures the error against an
//! exact solution, keeps the longest run of consecutive points that lie above the round-off
//! floor (default `1e-13`), below a ceiling (outside the asymptotic regime), and decrease by
//! at least a factor 1.2 from one point to the next (before stagnation), requires at least
//! three of them, and fits the slope `p` of `log err` against `log h` by least squares.
//!
//! # Long runs
//! [`fit_power_law`] fits `y ≈ C xᵅ` (least squares in log-log); Brouwer's law for the
//! round-off of a compensated long run is `α ≈ ½`.
//!
//! # Problems
//! Harmonic oscillator, Kepler (eccentricity `e`, exact solution by Kepler's equation solved
//! with Newton), pendulum (exact `q(t) = 2 asin(k sn(t | k²))`), and Hairer's rigid-body
//! test problem with its forced (non-autonomous) variant.

use crate::error::Error;
use crate::problem::{Ode, SeparableHamiltonian};
use crate::special::jacobi_sn_cn_dn;
use crate::state::VectorState;

/// Settings of an observed-order study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderStudy {
    /// Largest step.
    pub h0: f64,
    /// Number of step sizes (`h₀ / r^k`, `k = 0 … count−1`).
    pub count: usize,
    /// Ratio `r` of consecutive steps: 2 (halving) by default. A smaller ratio
    /// (`2^{1/3}`) resolves methods of order ≥ 10, whose error falls three decades per
    /// halving, when the asymptotic regime spans fewer decades above the floor.
    pub ratio: f64,
    /// When set, every step is snapped to `span / N` with `N` an integer, so a fixed-step
    /// run lands on the horizon with equal steps.
    pub span: Option<f64>,
    /// Errors at or below this are round-off dominated and not fitted.
    pub floor: f64,
    /// Errors above this are outside the asymptotic regime and not fitted.
    pub ceiling: f64,
}

impl OrderStudy {
    /// `count` halvings from `h0`, floor `1e-13`, ceiling `1e-2`.
    #[must_use]
    pub fn new(h0: f64, count: usize) -> Self {
        Self {
            h0,
            count,
            ratio: 2.0,
            span: None,
            floor: 1e-13,
            ceiling: 1e-2,
        }
    }

    /// Same study with ratio `r` between consecutive steps.
    #[must_use]
    pub fn with_ratio(mut self, ratio: f64) -> Self {
        self.ratio = ratio;
        self
    }

    /// Same study with steps snapped to `span / N`, `N` integer.
    #[must_use]
    pub fn on_span(mut self, span: f64) -> Self {
        self.span = Some(span);
        self
    }

    /// The step sizes of the study.
    #[must_use]
    pub fn steps(&self) -> Vec<f64> {
        (0..self.count)
            .map(|k| {
                let h = self.h0 / self.ratio.powi(k as i32);
                match self.span {
                    Some(span) => span / (span / h).round().max(1.0),
                    None => h,
                }
            })
            .collect()
    }

    /// Runs `error_at(h)` for every step size and fits the slope.
    ///
    /// # Errors
    /// Whatever `error_at` returns.
    pub fn run(
        &self,
        mut error_at: impl FnMut(f64) -> Result<f64, Error>,
    ) -> Result<OrderFit, Error> {
        let mut points = Vec::with_capacity(self.count);
        for h in self.steps() {
            points.push((h, error_at(h)?));
        }
        Ok(OrderFit::from_points(points, self.floor, self.ceiling))
    }
}

/// Result of an [`OrderStudy`].
#[derive(Debug, Clone, PartialEq)]
pub struct OrderFit {
    /// All `(h, error)` pairs.
    pub points: Vec<(f64, f64)>,
    /// Indices `[start, end)` of the points used in the fit.
    pub used: (usize, usize),
    /// Fitted slope (NaN with fewer than two usable points).
    pub slope: f64,
}

impl OrderFit {
    /// Selects the fitted range and fits the slope.
    #[must_use]
    pub fn from_points(points: Vec<(f64, f64)>, floor: f64, ceiling: f64) -> Self {
        let ok = |e: f64| e.is_finite() && e > floor && e <= ceiling;
        let mut best = (0, 0);
        let mut start = None;
        for i in 0..points.len() {
            let e = points[i].1;
            let continues = match start {
                Some(_) => ok(e) && points[i - 1].1 >= 1.2 * e,
                None => false,
            };
            if !continues {
                start = ok(e).then_some(i);
            }
            if let Some(s) = start
                && i + 1 - s > best.1 - best.0
            {
                best = (s, i + 1);
            }
        }
        let slope = if best.1 - best.0 >= 2 {
            let xs: Vec<f64> = points[best.0..best.1].iter().map(|p| p.0).collect();
            let ys: Vec<f64> = points[best.0..best.1].iter().map(|p| p.1).collect();
            fit_power_law(&xs, &ys)
        } else {
            f64::NAN
        };
        Self {
            points,
            used: best,
            slope,
        }
    }

    /// Number of points in the fit.
    #[must_use]
    pub fn used_points(&self) -> usize {
        self.used.1 - self.used.0
    }

    /// `Ok` when at least 3 points were fitted and `|slope − nominal| ≤ tolerance`;
    /// otherwise a message with the data.
    ///
    /// # Errors
    /// A description of the failure (the points and the fit).
    pub fn check(&self, nominal: f64, tolerance: f64) -> Result<(), String> {
        if self.used_points() < 3 {
            return Err(format!(
                "only {} usable points (need 3): {:?}",
                self.used_points(),
                self.points
            ));
        }
        if (self.slope - nominal).abs() > tolerance {
            return Err(format!(
                "observed order {:.3}, nominal {nominal}: points {:?}, used {:?}",
                self.slope, self.points, self.used
            ));
        }
        Ok(())
    }
}

/// Least-squares exponent `α` of `y ≈ C xᵅ`.
#[must_use]
pub fn fit_power_law(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len().min(ys.len()) as f64;
    let lx: Vec<f64> = xs.iter().map(|x| x.ln()).collect();
    let ly: Vec<f64> = ys.iter().map(|y| y.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let mut sxy = 0.0;
    let mut sxx = 0.0;
    for (x, y) in lx.iter().zip(&ly) {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
    }
    sxy / sxx
}

/// Largest absolute componentwise difference.
#[must_use]
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Harmonic oscillator `H = p²/2 + q²/2`.
#[derive(Debug, Clone, Copy, Default)]
pub struct HarmonicOscillator;

impl HarmonicOscillator {
    /// Exact solution from `(q₀, p₀)` at time `t`.
    #[must_use]
    pub fn exact(q0: f64, p0: f64, t: f64) -> [f64; 2] {
        let (s, c) = t.sin_cos();
        [q0 * c + p0 * s, -q0 * s + p0 * c]
    }
}

impl SeparableHamiltonian for HarmonicOscillator {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        0.5 * p[0] * p[0]
    }
    fn potential(&self, q: &[f64]) -> f64 {
        0.5 * q[0] * q[0]
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
    }
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        out[0] = q[0];
    }
}

/// Kepler problem `H = |p|²/2 − 1/|q|` in the plane (`μ = 1`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Kepler;

impl Kepler {
    /// Initial state at pericentre for eccentricity `e` (semi-major axis 1, period 2π):
    /// `q = (1 − e, 0)`, `p = (0, √((1 + e)/(1 − e)))`.
    #[must_use]
    pub fn initial(e: f64) -> [f64; 4] {
        [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()]
    }

    /// Exact state at time `t` from [`Kepler::initial`]: solve Kepler's equation
    /// `E − e sin E = t` by Newton, then `q = (cos E − e, √(1−e²) sin E)`,
    /// `p = (−sin E, √(1−e²) cos E)/(1 − e cos E)`.
    #[must_use]
    pub fn exact(e: f64, t: f64) -> [f64; 4] {
        let mean = t.rem_euclid(2.0 * std::f64::consts::PI);
        let mut ecc = if e > 0.8 { std::f64::consts::PI } else { mean };
        for _ in 0..60 {
            let f = ecc - e * ecc.sin() - mean;
            let d = f / (1.0 - e * ecc.cos());
            ecc -= d;
            if d.abs() <= 1e-16 * ecc.abs().max(1.0) {
                break;
            }
        }
        let (s, c) = ecc.sin_cos();
        let r = (1.0 - e * e).sqrt();
        let den = 1.0 - e * c;
        [c - e, r * s, -s / den, r * c / den]
    }

    /// Angular momentum `q₁p₂ − q₂p₁` (a quadratic invariant).
    #[must_use]
    pub fn angular_momentum(y: &[f64]) -> f64 {
        y[0] * y[3] - y[1] * y[2]
    }
}

impl SeparableHamiltonian for Kepler {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        0.5 * (p[0] * p[0] + p[1] * p[1])
    }
    fn potential(&self, q: &[f64]) -> f64 {
        -1.0 / (q[0] * q[0] + q[1] * q[1]).sqrt()
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
        out[1] = p[1];
    }
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let r3 = r2 * r2.sqrt();
        out[0] = q[0] / r3;
        out[1] = q[1] / r3;
    }
}

/// Mathematical pendulum `H = p²/2 − cos q`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Pendulum;

impl Pendulum {
    /// Initial state `(0, 2k)`: the swing of amplitude `2 asin k`.
    #[must_use]
    pub fn initial(k: f64) -> [f64; 2] {
        [0.0, 2.0 * k]
    }

    /// Exact state from [`Pendulum::initial`]: `q = 2 asin(k sn(t | k²))`,
    /// `p = 2k cn(t | k²)`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `k` outside `[0, 1]`.
    pub fn exact(k: f64, t: f64) -> Result<[f64; 2], Error> {
        let (sn, cn, _) = jacobi_sn_cn_dn(t, k * k)?;
        Ok([2.0 * (k * sn).asin(), 2.0 * k * cn])
    }
}

impl SeparableHamiltonian for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        0.5 * p[0] * p[0]
    }
    fn potential(&self, q: &[f64]) -> f64 {
        -q[0].cos()
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
    }
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        out[0] = q[0].sin();
    }
}

/// Hairer's rigid-body test problem (Euler's equations, `I = (0.5, 2, 3)`):
/// `y' = (−2 y₂y₃, 1.25 y₁y₃, −0.5 y₁y₂)`, `y(0) = (1, 0, 0.9)`, `t ∈ [0, 20]`; with
/// `forced`, the third component gets `+ 0.25 sin² t` (`t ∈ [0, 10]`), a non-autonomous
/// problem that catches wrong stage times.
#[derive(Debug, Clone, Copy, Default)]
pub struct RigidBodyEuler {
    /// Add the forcing `0.25 sin² t` to the third equation.
    pub forced: bool,
}

impl RigidBodyEuler {
    /// `y(0) = (1, 0, 0.9)`.
    pub const INITIAL: [f64; 3] = [1.0, 0.0, 0.9];
}

impl<Y: VectorState> Ode<Y> for RigidBodyEuler {
    fn rhs(&self, t: f64, y: &Y, dy: &mut Y) {
        let y = y.as_slice();
        let d = dy.as_mut_slice();
        d[0] = -2.0 * y[1] * y[2];
        d[1] = 1.25 * y[0] * y[2];
        d[2] = -0.5 * y[0] * y[1];
        if self.forced {
            let s = t.sin();
            d[2] += 0.25 * s * s;
        }
    }

    fn jacobian(&self, _t: f64, y: &Y, jac: &mut [f64]) -> bool {
        let y = y.as_slice();
        jac.copy_from_slice(&[
            0.0,
            -2.0 * y[2],
            -2.0 * y[1],
            1.25 * y[2],
            0.0,
            1.25 * y[0],
            -0.5 * y[1],
            -0.5 * y[0],
            0.0,
        ]);
        true
    }
}

/// Hairer's rigid-body problem as a split system for splitting and composition methods:
/// with `L = I y`, `I = diag(0.5, 2, 3)`, `H = Σᵢ Lᵢ²/(2Iᵢ)`, and the flow of each term is
/// an exact rotation of `L` about body axis `i` by the angle `−h Lᵢ/Iᵢ`
/// (`L̇ = L × (Lᵢ/Iᵢ) eᵢ`). Part `i` acts on the state `y = ω = I⁻¹L` in place.
#[derive(Debug, Clone, Copy, Default)]
pub struct RigidBodySplit;

impl RigidBodySplit {
    /// Principal moments of Hairer's problem.
    pub const INERTIA: [f64; 3] = [0.5, 2.0, 3.0];
}

impl<Y: VectorState> crate::problem::SplitOde<Y> for RigidBodySplit {
    fn parts(&self) -> usize {
        3
    }
    fn flow(&self, part: usize, _t: f64, h: f64, y: &mut Y) {
        let inertia = Self::INERTIA;
        let w = y.as_mut_slice();
        let mut l = [inertia[0] * w[0], inertia[1] * w[1], inertia[2] * w[2]];
        let (j, k) = match part {
            0 => (1, 2),
            1 => (2, 0),
            _ => (0, 1),
        };
        // L̇_j = ω_i L_k, L̇_k = −ω_i L_j with ω_i = L_i / I_i constant.
        let angle = h * l[part] / inertia[part];
        let (s, c) = angle.sin_cos();
        let (lj, lk) = (l[j], l[k]);
        l[j] = c * lj + s * lk;
        l[k] = -s * lj + c * lk;
        for i in 0..3 {
            w[i] = l[i] / inertia[i];
        }
    }
}
