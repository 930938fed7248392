//! Lie-group Runge–Kutta methods on `SO(3) × ℝᴺ`: Runge–Kutta–Munthe-Kaas and
//! Crouch–Grossman, each a generic stepper walking a `const` coefficient table.
//!
//! The problem is a [`LieVectorField`]: `Ṙ = R hat(ξ(t, R, y))`, `ẏ = f(t, R, y)`. On the
//! vector part both families are the underlying Runge–Kutta method (updated with compensated
//! summation); they differ in how the rotation is advanced.
//!
//! # Runge–Kutta–Munthe-Kaas ([`Rkmk`], `rkmk4`)
//!
//! Write `R(t₀ + τ) = R₀ exp(hat Θ(τ))`. With the right Jacobian `J_r` of
//! [`tumble_kinematics::so3::dexp`] (`d/dτ exp(Θ) = exp(Θ) hat(J_r(Θ) Θ̇)`) the local coordinate
//! obeys the ODE on the vector space `so(3) ≅ ℝ³`
//!
//! ```text
//! Θ̇ = J_r(Θ)⁻¹ ξ(t, R₀ exp Θ, y)       (dexpinv),      Θ(0) = 0,
//! ```
//!
//! and RKMK applies the classical Runge–Kutta method to it: stage `i` is
//! `Θᵢ = h Σⱼ aᵢⱼ kⱼ`, `Yᵢ = y₀ + h Σⱼ aᵢⱼ fⱼ`, `Rᵢ = R₀ exp(Θᵢ)`,
//! `(ξᵢ, fᵢ) = (ξ, f)(t₀ + cᵢh, Rᵢ, Yᵢ)`, `kᵢ = dexpinv(Θᵢ) ξᵢ`; then `R₁ = R₀ exp(h Σ bᵢ kᵢ)`,
//! `y₁ = y₀ + h Σ bᵢ fᵢ`. The exact `dexpinv` is used, so an RK table of order `p` gives an RKMK
//! method of order `p` (Munthe-Kaas 1999). `R` stays on `SO(3)` to round-off: it is only ever
//! multiplied by exponentials.
//!
//! # Crouch–Grossman ([`CrouchGrossman`], `cg3`)
//!
//! The flows are frozen instead of the coordinates: `Rᵢ = R₀ exp(h aᵢ₁ ξ₁) ⋯ exp(h aᵢ,ᵢ₋₁ ξᵢ₋₁)`,
//! `R₁ = R₀ exp(h b₁ ξ₁) ⋯ exp(h b_s ξ_s)` (the body-velocity form of Crouch & Grossman's
//! `yᵢ = exp(h aᵢ,ᵢ₋₁ Fᵢ₋₁) ⋯ exp(h aᵢ₁ F₁) y₀`). Order 3 needs, besides the classical
//! conditions, `Σ bᵢ² cᵢ + 2 Σ_{i<j} bᵢ cᵢ bⱼ = 1/3` (Owren & Marthinsen 1999), which
//! [`CROUCH_GROSSMAN3`] satisfies.
//!
//! # References
//! - H. Munthe-Kaas, *Runge–Kutta methods on Lie groups*, BIT 38 (1998) 92–111; *High order
//!   Runge–Kutta methods on manifolds*, Appl. Numer. Math. 29 (1999) 115–127.
//! - P. E. Crouch, R. Grossman, *Numerical integration of ordinary differential equations on
//!   manifolds*, J. Nonlinear Sci. 3 (1993) 1–33.
//! - B. Owren, A. Marthinsen, *Runge–Kutta methods adapted to manifolds and based on rigid
//!   frames*, BIT 39 (1999) 116–142.
//! - A. Iserles, H. Munthe-Kaas, S. P. Nørsett, A. Zanna, *Lie-group methods*, Acta Numerica 9
//!   (2000) 215–365.
//! - E. Celledoni, H. Marthinsen, B. Owren, *An introduction to Lie group integrators — basics,
//!   new developments and applications*, J. Comput. Phys. 257 (2014) 1040–1061.

use nalgebra::{Matrix3, SVector, Vector3};

use tumble_kinematics::so3::{dexpinv, exp_quat, hat};

use crate::error::{Error, check_step};
use crate::rigid::problem::LieVectorField;
use crate::rigid::state::GroupState;
use crate::rigid::state::compensated_add_all;
use crate::stepper::Stepper;

/// `R (exp(hat θ) − 𝟙)`, with `exp(hat θ) − 𝟙 = 2w hat(v) + 2 hat(v)²` from the unit quaternion
/// `(w, v)` of `θ`. `R exp(hat θ)` is then formed as `R + R (exp(hat θ) − 𝟙)`, which rounds once
/// per entry of `R` in a pattern that changes with `R`, where the product would round the
/// diagonal `1 − O(|θ|²)` of the exponential the same way at every step of a steady rotation and
/// make `‖RᵀR − 𝟙‖` grow linearly.
pub(crate) fn exp_increment(r: &Matrix3<f64>, theta: &Vector3<f64>) -> Matrix3<f64> {
    let q = exp_quat(theta);
    let v = hat(&q.vector().into_owned());
    r * ((v * q.w + v * v) * 2.0)
}

/// `R exp(hat θ)` as `R + R (exp(hat θ) − 𝟙)` (see [`exp_increment`]).
fn times_exp(r: &Matrix3<f64>, theta: &Vector3<f64>) -> Matrix3<f64> {
    r + exp_increment(r, theta)
}

/// Coefficients `(c, A, b)` of an explicit `S`-stage method used on a Lie group.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LieRkTableau<const S: usize> {
    /// Registry name.
    pub name: &'static str,
    /// Order on the Lie group.
    pub order: u32,
    /// Nodes.
    pub c: [f64; S],
    /// Strictly lower-triangular coefficients.
    pub a: [[f64; S]; S],
    /// Weights.
    pub b: [f64; S],
}

/// The classical Runge–Kutta method (Kutta 1901) as an RKMK method of order 4.
///
/// ```text
///   0  |
///  1/2 | 1/2
///  1/2 |  0   1/2
///   1  |  0    0    1
/// -----+--------------------
///      | 1/6  1/3  1/3  1/6
/// ```
pub const RKMK4: LieRkTableau<4> = LieRkTableau {
    name: "rkmk4",
    order: 4,
    c: [0.0, 0.5, 0.5, 1.0],
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

/// Crouch & Grossman's 3-stage method of order 3 (Crouch & Grossman 1993, as tabulated by Owren
/// & Marthinsen 1999):
///
/// ```text
///    0    |
///   3/4   |   3/4
///  17/24  | 119/216  17/108
/// --------+------------------------
///         |  13/51   −2/3    24/17
/// ```
pub const CROUCH_GROSSMAN3: LieRkTableau<3> = LieRkTableau {
    name: "cg3",
    order: 3,
    c: [0.0, 3.0 / 4.0, 17.0 / 24.0],
    a: [
        [0.0; 3],
        [3.0 / 4.0, 0.0, 0.0],
        [119.0 / 216.0, 17.0 / 108.0, 0.0],
    ],
    b: [13.0 / 51.0, -2.0 / 3.0, 24.0 / 17.0],
};

/// Carried Kahan compensation of the updates `R ← R + ΔR`, `y ← y + Δy`, valid only while the
/// state is what the stepper last produced.
#[derive(Debug, Clone, Copy)]
struct Compensation<const N: usize> {
    rotation: Matrix3<f64>,
    vector: SVector<f64, N>,
    last: Option<(f64, GroupState<N>)>,
}

impl<const N: usize> Compensation<N> {
    fn new() -> Self {
        Self {
            rotation: Matrix3::zeros(),
            vector: SVector::zeros(),
            last: None,
        }
    }

    /// Resets the carries unless `(t, state)` is the end of the last step.
    fn prepare(&mut self, t: f64, state: &GroupState<N>) {
        let continues = self
            .last
            .as_ref()
            .is_some_and(|(t1, s1)| crate::state::same_time(*t1, t) && s1 == state);
        if !continues {
            *self = Self::new();
        }
    }

    fn update(
        &mut self,
        t1: f64,
        state: &mut GroupState<N>,
        d_rotation: &Matrix3<f64>,
        d_vector: &SVector<f64, N>,
    ) {
        compensated_add_all(&mut state.rotation, d_rotation, &mut self.rotation);
        compensated_add_all(&mut state.vector, d_vector, &mut self.vector);
        self.last = Some((t1, *state));
    }
}

/// Runge–Kutta–Munthe-Kaas stepper on `SO(3) × ℝᴺ` with an `S`-stage table.
#[derive(Debug, Clone, Copy)]
pub struct Rkmk<const S: usize, const N: usize> {
    table: &'static LieRkTableau<S>,
    compensation: Compensation<N>,
}

impl<const S: usize, const N: usize> Rkmk<S, N> {
    /// A stepper for the table.
    #[must_use]
    pub fn new(table: &'static LieRkTableau<S>) -> Self {
        Self {
            table,
            compensation: Compensation::new(),
        }
    }

    /// The table.
    #[must_use]
    pub fn table(&self) -> &'static LieRkTableau<S> {
        self.table
    }
}

/// `rkmk4`: RKMK with the classical RK4 coefficients.
#[must_use]
pub fn rkmk4<const N: usize>() -> Rkmk<4, N> {
    Rkmk::new(&RKMK4)
}

/// `cg3`: Crouch–Grossman of order 3.
#[must_use]
pub fn cg3<const N: usize>() -> CrouchGrossman<3, N> {
    CrouchGrossman::new(&CROUCH_GROSSMAN3)
}

impl<const S: usize, const N: usize, F: LieVectorField<N> + ?Sized> Stepper<F> for Rkmk<S, N> {
    type State = GroupState<N>;

    fn step(
        &mut self,
        problem: &F,
        t: f64,
        state: &mut GroupState<N>,
        h: f64,
    ) -> Result<(), Error> {
        if !h.is_finite() {
            return check_step(h);
        }
        self.compensation.prepare(t, state);
        let tab = self.table;
        let r0 = state.rotation;
        let y0 = state.vector;
        let mut k = [Vector3::<f64>::zeros(); S];
        let mut f = [SVector::<f64, N>::zeros(); S];
        for i in 0..S {
            let mut theta = Vector3::zeros();
            let mut y = y0;
            for j in 0..i {
                let a = tab.a[i][j];
                if a != 0.0 {
                    theta += k[j] * (h * a);
                    y += f[j] * (h * a);
                }
            }
            let (ri, corrected) = if i == 0 {
                (r0, None)
            } else {
                (times_exp(&r0, &theta), Some(theta))
            };
            let (xi, fi) = problem.eval(t + tab.c[i] * h, &ri, &y);
            k[i] = match corrected {
                Some(theta) => dexpinv(&theta) * xi,
                None => xi,
            };
            f[i] = fi;
        }
        let mut theta = Vector3::zeros();
        let mut delta = SVector::<f64, N>::zeros();
        for i in 0..S {
            theta += k[i] * (h * tab.b[i]);
            delta += f[i] * (h * tab.b[i]);
        }
        let d_rotation = exp_increment(&r0, &theta);
        self.compensation.update(t + h, state, &d_rotation, &delta);
        Ok(())
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
}

/// Crouch–Grossman stepper on `SO(3) × ℝᴺ` with an `S`-stage table.
#[derive(Debug, Clone, Copy)]
pub struct CrouchGrossman<const S: usize, const N: usize> {
    table: &'static LieRkTableau<S>,
    compensation: Compensation<N>,
}

impl<const S: usize, const N: usize> CrouchGrossman<S, N> {
    /// A stepper for the table.
    #[must_use]
    pub fn new(table: &'static LieRkTableau<S>) -> Self {
        Self {
            table,
            compensation: Compensation::new(),
        }
    }

    /// The table.
    #[must_use]
    pub fn table(&self) -> &'static LieRkTableau<S> {
        self.table
    }
}

/// `R₀ exp(h w₁ ξ₁) ⋯ exp(h w_n ξ_n)` over the first `n` stages.
fn frozen_flows(r0: &Matrix3<f64>, xi: &[Vector3<f64>], weights: &[f64], h: f64) -> Matrix3<f64> {
    let mut r = *r0;
    for (x, &w) in xi.iter().zip(weights) {
        if w != 0.0 {
            r = times_exp(&r, &(x * (h * w)));
        }
    }
    r
}

impl<const S: usize, const N: usize, F: LieVectorField<N> + ?Sized> Stepper<F>
    for CrouchGrossman<S, N>
{
    type State = GroupState<N>;

    fn step(
        &mut self,
        problem: &F,
        t: f64,
        state: &mut GroupState<N>,
        h: f64,
    ) -> Result<(), Error> {
        if !h.is_finite() {
            return check_step(h);
        }
        self.compensation.prepare(t, state);
        let tab = self.table;
        let r0 = state.rotation;
        let y0 = state.vector;
        let mut xi = [Vector3::<f64>::zeros(); S];
        let mut f = [SVector::<f64, N>::zeros(); S];
        for i in 0..S {
            let mut y = y0;
            for j in 0..i {
                let a = tab.a[i][j];
                if a != 0.0 {
                    y += f[j] * (h * a);
                }
            }
            let ri = frozen_flows(&r0, &xi[..i], &tab.a[i][..i], h);
            let (x, fi) = problem.eval(t + tab.c[i] * h, &ri, &y);
            xi[i] = x;
            f[i] = fi;
        }
        let mut delta = SVector::<f64, N>::zeros();
        for i in 0..S {
            delta += f[i] * (h * tab.b[i]);
        }
        let d_rotation = frozen_flows(&r0, &xi, &tab.b, h) - r0;
        self.compensation.update(t + h, state, &d_rotation, &delta);
        Ok(())
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
}
