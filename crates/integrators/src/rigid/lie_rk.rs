//! Lie-group Runge–Kutta methods on `SO(3) × ℝᴺ` and on the product `SO(3)ᴹ × ℝᴺ`:
//! Runge–Kutta–Munthe-Kaas and Crouch–Grossman, each a generic stepper walking a `const`
//! coefficient table. One step function serves both: `SO(3) × ℝᴺ` is the product with `M = 1`.
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
//! # On the product `SO(3)ᴹ × ℝᴺ` ([`ProductRkmk`], [`ProductCrouchGrossman`])
//!
//! A [`ProductVectorField`] gives one body velocity `ξₖ` per rotation. The exponential and
//! `dexpinv` of a direct product act factor by factor, so both methods run as above on each
//! rotation with its own `ξₖ` (RKMK: `Θₖ,ᵢ = h Σⱼ aᵢⱼ kₖ,ⱼ`, `kₖ,ᵢ = dexpinv(Θₖ,ᵢ) ξₖ,ᵢ`,
//! `Rₖ ← Rₖ exp(h Σ bᵢ kₖ,ᵢ)`), every stage evaluating the field once at all the rotations
//! together; the orders are those on one rotation, and each `Rₖ` stays on `SO(3)` to
//! round-off.
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
use crate::rigid::product::{ProductState, ProductVectorField};
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

/// Carried Kahan compensation of the updates `Rₖ ← Rₖ + ΔRₖ`, `y ← y + Δy` of a state on
/// `SO(3)ᴹ × ℝᴺ`, valid only while the state is what the stepper last produced.
#[derive(Debug, Clone, Copy)]
struct Compensation<const M: usize, const N: usize> {
    rotations: [Matrix3<f64>; M],
    vector: SVector<f64, N>,
    last: Option<(f64, [Matrix3<f64>; M], SVector<f64, N>)>,
}

impl<const M: usize, const N: usize> Compensation<M, N> {
    fn new() -> Self {
        Self {
            rotations: [Matrix3::zeros(); M],
            vector: SVector::zeros(),
            last: None,
        }
    }

    /// Resets the carries unless `(t, rotations, vector)` is the end of the last step.
    fn prepare(&mut self, t: f64, rotations: &[Matrix3<f64>; M], vector: &SVector<f64, N>) {
        let continues = self.last.as_ref().is_some_and(|(t1, r1, y1)| {
            crate::state::same_time(*t1, t) && r1 == rotations && y1 == vector
        });
        if !continues {
            *self = Self::new();
        }
    }

    fn update(
        &mut self,
        t1: f64,
        rotations: &mut [Matrix3<f64>; M],
        vector: &mut SVector<f64, N>,
        d_rotations: &[Matrix3<f64>; M],
        d_vector: &SVector<f64, N>,
    ) {
        for k in 0..M {
            compensated_add_all(&mut rotations[k], &d_rotations[k], &mut self.rotations[k]);
        }
        compensated_add_all(vector, d_vector, &mut self.vector);
        self.last = Some((t1, *rotations, *vector));
    }
}

/// The body velocities and `ẏ` of a field on `SO(3)ᴹ × ℝᴺ` at a stage.
type Velocities<const M: usize, const N: usize> = ([Vector3<f64>; M], SVector<f64, N>);

/// One RKMK step on `SO(3)ᴹ × ℝᴺ` from `(r0, y0)`: the increments `(ΔR₁ … ΔR_M, Δy)`, each
/// rotation's `ΔRₖ = Rₖ (exp(hat Θₖ) − 𝟙)` from its own local coordinate `Θₖ` (see the module
/// doc; on a direct product `exp` and `dexpinv` act factor by factor).
fn rkmk_increments<const S: usize, const M: usize, const N: usize>(
    tab: &LieRkTableau<S>,
    mut eval: impl FnMut(f64, &[Matrix3<f64>; M], &SVector<f64, N>) -> Velocities<M, N>,
    t: f64,
    r0: &[Matrix3<f64>; M],
    y0: &SVector<f64, N>,
    h: f64,
) -> ([Matrix3<f64>; M], SVector<f64, N>) {
    let mut k = [[Vector3::<f64>::zeros(); M]; S];
    let mut f = [SVector::<f64, N>::zeros(); S];
    for i in 0..S {
        let mut theta = [Vector3::zeros(); M];
        let mut y = *y0;
        for j in 0..i {
            let a = tab.a[i][j];
            if a != 0.0 {
                for m in 0..M {
                    theta[m] += k[j][m] * (h * a);
                }
                y += f[j] * (h * a);
            }
        }
        let ri = if i == 0 {
            *r0
        } else {
            std::array::from_fn(|m| times_exp(&r0[m], &theta[m]))
        };
        let (xi, fi) = eval(t + tab.c[i] * h, &ri, &y);
        for m in 0..M {
            k[i][m] = if i == 0 {
                xi[m]
            } else {
                dexpinv(&theta[m]) * xi[m]
            };
        }
        f[i] = fi;
    }
    let mut theta = [Vector3::zeros(); M];
    let mut delta = SVector::<f64, N>::zeros();
    for i in 0..S {
        for m in 0..M {
            theta[m] += k[i][m] * (h * tab.b[i]);
        }
        delta += f[i] * (h * tab.b[i]);
    }
    (
        std::array::from_fn(|m| exp_increment(&r0[m], &theta[m])),
        delta,
    )
}

/// `R₀ exp(h w₁ ξ₁) ⋯ exp(h w_n ξ_n)` over the first `n` stages, for rotation `m` of each.
fn frozen_flows<const M: usize>(
    r0: &Matrix3<f64>,
    xi: &[[Vector3<f64>; M]],
    m: usize,
    weights: &[f64],
    h: f64,
) -> Matrix3<f64> {
    let mut r = *r0;
    for (x, &w) in xi.iter().zip(weights) {
        if w != 0.0 {
            r = times_exp(&r, &(x[m] * (h * w)));
        }
    }
    r
}

/// One Crouch–Grossman step on `SO(3)ᴹ × ℝᴺ` from `(r0, y0)`: the increments, each rotation
/// advanced by the frozen flows of its own body velocities (see the module doc).
fn crouch_grossman_increments<const S: usize, const M: usize, const N: usize>(
    tab: &LieRkTableau<S>,
    mut eval: impl FnMut(f64, &[Matrix3<f64>; M], &SVector<f64, N>) -> Velocities<M, N>,
    t: f64,
    r0: &[Matrix3<f64>; M],
    y0: &SVector<f64, N>,
    h: f64,
) -> ([Matrix3<f64>; M], SVector<f64, N>) {
    let mut xi = [[Vector3::<f64>::zeros(); M]; S];
    let mut f = [SVector::<f64, N>::zeros(); S];
    for i in 0..S {
        let mut y = *y0;
        for j in 0..i {
            let a = tab.a[i][j];
            if a != 0.0 {
                y += f[j] * (h * a);
            }
        }
        let ri = std::array::from_fn(|m| frozen_flows(&r0[m], &xi[..i], m, &tab.a[i][..i], h));
        let (x, fi) = eval(t + tab.c[i] * h, &ri, &y);
        xi[i] = x;
        f[i] = fi;
    }
    let mut delta = SVector::<f64, N>::zeros();
    for i in 0..S {
        delta += f[i] * (h * tab.b[i]);
    }
    (
        std::array::from_fn(|m| frozen_flows(&r0[m], &xi, m, &tab.b, h) - r0[m]),
        delta,
    )
}

/// Which way a Lie-group Runge–Kutta stepper advances the rotations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// RKMK: the local coordinates `Θₖ` ([`rkmk_increments`]).
    MuntheKaas,
    /// Crouch–Grossman: frozen flows ([`crouch_grossman_increments`]).
    CrouchGrossman,
}

/// A step of `kind` on `SO(3)ᴹ × ℝᴺ`, updating `(rotations, vector)` with compensated sums.
#[allow(clippy::too_many_arguments)]
fn step_on_product<const S: usize, const M: usize, const N: usize>(
    kind: Kind,
    table: &LieRkTableau<S>,
    compensation: &mut Compensation<M, N>,
    eval: impl FnMut(f64, &[Matrix3<f64>; M], &SVector<f64, N>) -> Velocities<M, N>,
    t: f64,
    rotations: &mut [Matrix3<f64>; M],
    vector: &mut SVector<f64, N>,
    h: f64,
) -> Result<(), Error> {
    if !h.is_finite() {
        return check_step(h);
    }
    compensation.prepare(t, rotations, vector);
    let (d_rotations, delta) = match kind {
        Kind::MuntheKaas => rkmk_increments(table, eval, t, rotations, vector, h),
        Kind::CrouchGrossman => crouch_grossman_increments(table, eval, t, rotations, vector, h),
    };
    compensation.update(t + h, rotations, vector, &d_rotations, &delta);
    Ok(())
}

/// A step of `kind` on `SO(3) × ℝᴺ`: the product with one factor.
fn step_on_group<const S: usize, const N: usize, F: LieVectorField<N> + ?Sized>(
    kind: Kind,
    table: &LieRkTableau<S>,
    compensation: &mut Compensation<1, N>,
    problem: &F,
    t: f64,
    state: &mut GroupState<N>,
    h: f64,
) -> Result<(), Error> {
    let eval = |t: f64, r: &[Matrix3<f64>; 1], y: &SVector<f64, N>| {
        let (xi, f) = problem.eval(t, &r[0], y);
        ([xi], f)
    };
    let mut rotations = [state.rotation];
    let result = step_on_product(
        kind,
        table,
        compensation,
        eval,
        t,
        &mut rotations,
        &mut state.vector,
        h,
    );
    state.rotation = rotations[0];
    result
}

/// Defines a stepper type of one [`Kind`] with its constructor and table accessor.
macro_rules! lie_rk_stepper {
    ($(#[$doc:meta])* $name:ident <$($c:ident),*>, $m:tt) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $name<$(const $c: usize),*> {
            table: &'static LieRkTableau<S>,
            compensation: Compensation<$m, N>,
        }

        impl<$(const $c: usize),*> $name<$($c),*> {
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
    };
}

lie_rk_stepper!(
    /// Runge–Kutta–Munthe-Kaas stepper on `SO(3) × ℝᴺ` with an `S`-stage table.
    Rkmk<S, N>, 1
);
lie_rk_stepper!(
    /// Crouch–Grossman stepper on `SO(3) × ℝᴺ` with an `S`-stage table.
    CrouchGrossman<S, N>, 1
);
lie_rk_stepper!(
    /// Runge–Kutta–Munthe-Kaas stepper on the product `SO(3)ᴹ × ℝᴺ` with an `S`-stage table:
    /// each rotation advanced by the exponential of its own local coordinate.
    ProductRkmk<S, M, N>, M
);
lie_rk_stepper!(
    /// Crouch–Grossman stepper on the product `SO(3)ᴹ × ℝᴺ` with an `S`-stage table: each
    /// rotation advanced by the frozen flows of its own body velocities.
    ProductCrouchGrossman<S, M, N>, M
);

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

/// `rkmk4` on `SO(3)ᴹ × ℝᴺ`.
#[must_use]
pub fn product_rkmk4<const M: usize, const N: usize>() -> ProductRkmk<4, M, N> {
    ProductRkmk::new(&RKMK4)
}

/// `cg3` on `SO(3)ᴹ × ℝᴺ`.
#[must_use]
pub fn product_cg3<const M: usize, const N: usize>() -> ProductCrouchGrossman<3, M, N> {
    ProductCrouchGrossman::new(&CROUCH_GROSSMAN3)
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
        let (table, compensation) = (self.table, &mut self.compensation);
        step_on_group(Kind::MuntheKaas, table, compensation, problem, t, state, h)
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
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
        let (table, compensation) = (self.table, &mut self.compensation);
        step_on_group(
            Kind::CrouchGrossman,
            table,
            compensation,
            problem,
            t,
            state,
            h,
        )
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
}

impl<const S: usize, const M: usize, const N: usize, F: ProductVectorField<M, N> + ?Sized>
    Stepper<F> for ProductRkmk<S, M, N>
{
    type State = ProductState<M, N>;

    fn step(
        &mut self,
        problem: &F,
        t: f64,
        state: &mut ProductState<M, N>,
        h: f64,
    ) -> Result<(), Error> {
        let eval = |t: f64, r: &[Matrix3<f64>; M], y: &SVector<f64, N>| problem.eval(t, r, y);
        step_on_product(
            Kind::MuntheKaas,
            self.table,
            &mut self.compensation,
            eval,
            t,
            &mut state.rotations,
            &mut state.vector,
            h,
        )
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
}

impl<const S: usize, const M: usize, const N: usize, F: ProductVectorField<M, N> + ?Sized>
    Stepper<F> for ProductCrouchGrossman<S, M, N>
{
    type State = ProductState<M, N>;

    fn step(
        &mut self,
        problem: &F,
        t: f64,
        state: &mut ProductState<M, N>,
        h: f64,
    ) -> Result<(), Error> {
        let eval = |t: f64, r: &[Matrix3<f64>; M], y: &SVector<f64, N>| problem.eval(t, r, y);
        step_on_product(
            Kind::CrouchGrossman,
            self.table,
            &mut self.compensation,
            eval,
            t,
            &mut state.rotations,
            &mut state.vector,
            h,
        )
    }

    fn reset(&mut self) {
        self.compensation = Compensation::new();
    }
}
