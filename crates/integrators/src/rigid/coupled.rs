//! A rigid body coupled to `N` vector-space coordinates (`SO(3) × ℝᴺ`): the model interface, a
//! variational integrator built from a discrete Lagrangian, and the continuous equations as a
//! [`LieVectorField`] for the Lie-group Runge–Kutta methods.
//!
//! # The model ([`CoupledLagrangian`])
//!
//! A body with a fixed point (or a free body's rotation about its centre of mass) whose
//! configuration is `(R, q) ∈ SO(3) × ℝᴺ` — a bead on a hoop (`q = α`), a mass on a spring along
//! a body axis, a rotor — with the Lagrangian
//!
//! ```text
//! L(R, Ω, q, q̇) = ½ Ωᵀ J(q) Ω + Ωᵀ B(q) q̇ + ½ q̇ᵀ M(q) q̇ − V(R, q),
//! ```
//!
//! `Ω` the body angular velocity (`Ṙ = R hat Ω`). A scene implements the two methods of
//! [`CoupledLagrangian`] once, generic over the scalar ([`Scalar`]: `f64` and the dual numbers
//! of `num-dual`); every derivative the integrators need (`∂T/∂q`, the moment
//! `M = −∂V/∂η` of `V(R exp(hat η), q)`, `∂V/∂q`, the Newton Jacobian) is then computed by
//! automatic differentiation, exactly. For a point mass `μ` at body position `r(q)` moving with
//! the body: `J = μ(|r|² 𝟙 − r rᵀ)`, `B = μ hat(r) ∂r/∂q`, `M = μ (∂r/∂q)ᵀ ∂r/∂q`.
//!
//! The momenta are `Π = ∂L/∂Ω = J Ω + B q̇` (body frame; `R Π` is the spatial angular momentum
//! about the fixed point) and `p = ∂L/∂q̇ = Bᵀ Ω + M q̇`, and the energy is
//! `H = ½ (Ω·Π + q̇·p) + V`. The state is [`CoupledState`] `(R, Π, q, p)`.
//!
//! # The variational integrator ([`CoupledLgvi`])
//!
//! Discrete Lagrangian (midpoint in the kinetic energy, trapezoid in the potential), with the
//! relative rotation `F_k = R_kᵀ R_{k+1} = cay(w)` and the discrete body velocity `ξ = w/h`:
//!
//! ```text
//! L_d = h T(ξ, q̄, v) − (h/2) (V(R_k, q_k) + V(R_{k+1}, q_{k+1})),
//! q̄ = (q_k + q_{k+1})/2,   v = (q_{k+1} − q_k)/h.
//! ```
//!
//! Perturbing `R_{k+1} → R_{k+1} exp(hat η)` moves `w` by `A_R(w) η`, perturbing
//! `R_k → R_k exp(hat η)` moves it by `−A_L(w) η`, with
//! `A_R(w) = 𝟙 + ½ hat w + ¼ w wᵀ` and `A_L(w) = A_R(w)ᵀ` (the inverse trivialized tangents of
//! the Cayley map). The discrete Legendre transforms `Π_k = −D_{R_k} L_d`,
//! `p_k = −∂L_d/∂q_k`, `Π_{k+1} = D_{R_{k+1}} L_d`, `p_{k+1} = ∂L_d/∂q_{k+1}` (left-trivialized)
//! then give the one-step map `(R_k, Π_k, q_k, p_k) ↦ (R_{k+1}, Π_{k+1}, q_{k+1}, p_{k+1})`:
//!
//! ```text
//! 0 = Π_k + (h/2) M(R_k, q_k) − A_R(w) T_ξ,
//! 0 = p_k − (h/2) V_q(R_k, q_k) + (h/2) T_q − T_v,                (solve for w, q_{k+1})
//! R_{k+1} = R_k cay(w),
//! Π_{k+1} = A_L(w) T_ξ + (h/2) M(R_{k+1}, q_{k+1}),
//! p_{k+1} = T_v + (h/2) T_q − (h/2) V_q(R_{k+1}, q_{k+1}),
//! ```
//!
//! with `T_ξ, T_q, T_v` the partial derivatives of `T` at `(ξ, q̄, v)`. The `3 + N` equations are
//! solved for `(w, d = q_{k+1} − q_k)` by a simplified Newton method in plain `f64`, from what
//! the model gives of its kinetic energy: the blocks and their first derivatives
//! ([`CoupledLagrangian::kinetic_jet`]) for the residuals, and their second derivatives
//! ([`CoupledLagrangian::kinetic_hessian`]) for the Newton matrix, which is exact at the first
//! iterate (see `StepData::jacobian`), factored once by block elimination (a 3×3 inverse and
//! the inverse of the `N×N` Schur complement, on the stack) and reused until an iteration
//! shrinks the increment less than fourfold (or lets it grow: then the step is retaken with a
//! fresh matrix). The defaults of those methods differentiate the model automatically
//! (dual and hyper-dual numbers); a model may give closed forms instead. The starting guess is
//! the explicit `w = hΩ_k`, `d = h q̇_k`. Iteration stops
//! when the increment is at round-off or stops decreasing; otherwise
//! [`Error::NoConvergence`]. The moment and `∂V/∂q` at the end of a step
//! ([`CoupledLagrangian::potential_derivatives`]) are reused at the start of the next when it
//! continues the last one. Solving for
//! the increment `d` rather than `q_{k+1}` keeps `v = d/h` free of cancellation when `q` is large
//! (an angle that winds up: with `q ≈ 40` the difference `q_{k+1} − q_k` would lose three digits,
//! enough to break the conservation of `L·e₃` at the 1e-14 level per step).
//!
//! The map is symplectic and symmetric (the discrete Lagrangian is self-adjoint), hence of order
//! 2 and composable to higher order with [`crate::Composition`]. If `V` is invariant under
//! rotations about the space axis `e` (`V(exp(θ hat e) R, q) = V(R, q)`, e.g. gravity along `e`),
//! so is `L_d`, and the discrete Noether theorem conserves `e · R_k Π_k` exactly (to round-off).
//! For `N = 0` and constant `J` it is a Cayley-based relative of the LGVI of
//! [`crate::rigid::Lgvi`] (the two discrete kinetic energies differ by `O(h³)`).
//!
//! # The continuous equations ([`CoupledVectorField`])
//!
//! `Ṙ = R hat Ω`, `Π̇ = Π × Ω + M(R, q)`, `q̇`, `ṗ = ∂T/∂q|_{Ω,q̇} − ∂V/∂q`, with `(Ω, q̇)` from
//! the momenta by the Legendre transform; as a [`LieVectorField`] on `SO(3) × ℝʸ` with
//! `y = (Π, q, p)`, `Y = 3 + 2N` (checked when the field is built), integrable by `rkmk4`, `cg3`
//! (see [`CoupledState::to_group`]) or, flattened, by any vector-space method.
//!
//! # References
//! - J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10
//!   (2001) 357–514.
//! - T. Lee, M. Leok, N. H. McClamroch, *Lie group variational integrators for the full body
//!   problem*, Comput. Methods Appl. Mech. Eng. 196 (2007) 2907–2924.
//! - N. Bou-Rabee, J. E. Marsden, *Hamilton–Pontryagin integrators on Lie groups*, Found.
//!   Comput. Math. 9 (2009) 197–219 (Cayley-map discretizations).
//! - M. Kobilarov, J. E. Marsden, *Discrete geometric optimal control on Lie groups*, IEEE
//!   Trans. Robotics 27 (2011) 641–655 (the trivialized tangents of the Cayley map).

use nalgebra::{Const, Matrix3, RealField, SMatrix, SVector, U1, Vector3};
use num_dual::{DualVec, HyperDualVec};

use tumble_kinematics::so3::hat;

use crate::composition::Composition;
use crate::error::{Error, check_step};
use crate::rigid::lgvi::MAX_NEWTON_ITERATIONS;
use crate::rigid::problem::LieVectorField;
use crate::rigid::state::{CoupledState, check_coupled_dimension};
use crate::stepper::Stepper;
use crate::tables::composition::{KAHAN_LI6, KAHAN_LI8, MCLACHLAN4, SOFRONIOU_SPALETTA10};

/// The scalars models are written in: `f64` and the (hyper-)dual numbers of `num-dual`.
///
/// Constants enter through `D::from(c)`; functions (`sin`, `sqrt`, …) are `RealField`'s. (The
/// name is also nalgebra's; import one of them under another name where both are needed.)
pub trait Scalar: RealField + Copy + From<f64> {}

impl<T: RealField + Copy + From<f64>> Scalar for T {}

/// The blocks of the kinetic energy `T = ½ ΩᵀJΩ + ΩᵀB q̇ + ½ q̇ᵀM q̇` at a configuration `q`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KineticBlocks<D: Scalar, const N: usize> {
    /// `J(q)`: body-frame inertia about the fixed point (symmetric positive definite).
    pub rotational: Matrix3<D>,
    /// `B(q)`: coupling of the body's rotation and the coordinates' rates (3 × N).
    pub coupling: SMatrix<D, 3, N>,
    /// `M(q)`: mass matrix of the coordinates (symmetric, N × N).
    pub internal: SMatrix<D, N, N>,
}

/// The kinetic-energy blocks at a configuration `q` and their first derivatives
/// `∂J/∂qᵢ`, `∂B/∂qᵢ`, `∂M/∂qᵢ` (`derivatives[i]`): all the integrators need of `T` besides its
/// value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KineticJet<const N: usize> {
    /// `J(q)`, `B(q)`, `M(q)`.
    pub blocks: KineticBlocks<f64, N>,
    /// `∂/∂qᵢ` of each block, `i = 0 … N − 1`.
    pub derivatives: [KineticBlocks<f64, N>; N],
}

impl<const N: usize> KineticJet<N> {
    /// `T_ξ = JΩ + Bq̇` and `T_v = BᵀΩ + Mq̇` at velocities `(Ω, q̇)`.
    #[must_use]
    pub fn momenta(
        &self,
        xi: &Vector3<f64>,
        v: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        let k = &self.blocks;
        (
            k.rotational * xi + k.coupling * v,
            k.coupling.transpose() * xi + k.internal * v,
        )
    }

    /// `∂T/∂q` at fixed velocities `(Ω, q̇)`: `½ Ωᵀ ∂ᵢJ Ω + Ωᵀ ∂ᵢB q̇ + ½ q̇ᵀ ∂ᵢM q̇`.
    #[must_use]
    pub fn configuration_gradient(
        &self,
        xi: &Vector3<f64>,
        v: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        SVector::from_fn(|i, _| {
            let d = &self.derivatives[i];
            0.5 * xi.dot(&(d.rotational * xi))
                + xi.dot(&(d.coupling * v))
                + 0.5 * v.dot(&(d.internal * v))
        })
    }
}

/// A rigid body coupled to `N` coordinates, by its Lagrangian (see the module doc).
///
/// Both required methods must be written generically over the scalar `D` (no branching on
/// values that would break derivatives) and must not allocate. The two provided methods give
/// the derivatives the integrators and the vector field use, by automatic differentiation of
/// the required ones; a model may override them with closed forms (the free hoop does: its
/// right-hand side and its variational step then run in plain `f64`), which its tests should
/// check against these defaults.
pub trait CoupledLagrangian<const N: usize> {
    /// The kinetic-energy blocks `J(q)`, `B(q)`, `M(q)`.
    fn kinetic<D: Scalar>(&self, q: &SVector<D, N>) -> KineticBlocks<D, N>;

    /// The potential `V(R, q)`; `R` maps body to space components.
    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, N>) -> D;

    /// The blocks at `q` and their first derivatives (default: one evaluation of
    /// [`Self::kinetic`] in first-order dual numbers).
    fn kinetic_jet(&self, q: &SVector<f64, N>) -> KineticJet<N> {
        let qd = SVector::<Grad<N>, N>::from_fn(|i, _| grad_var::<N>(q[i], i));
        let b = self.kinetic(&qd);
        let part = |i: Option<usize>| {
            let pick = |x: &Grad<N>| match i {
                None => x.re,
                Some(i) => grad_of(x)[i],
            };
            KineticBlocks {
                rotational: b.rotational.map(|x| pick(&x)),
                coupling: b.coupling.map(|x| pick(&x)),
                internal: b.internal.map(|x| pick(&x)),
            }
        };
        KineticJet {
            blocks: part(None),
            derivatives: std::array::from_fn(|i| part(Some(i))),
        }
    }

    /// The second derivatives `∂²/∂qᵢ∂qⱼ` of the blocks (`[i][j]`; default: one evaluation of
    /// [`Self::kinetic`] in hyper-dual numbers). Only the Newton matrix of the variational
    /// step uses them, once a step.
    fn kinetic_hessian(&self, q: &SVector<f64, N>) -> [[KineticBlocks<f64, N>; N]; N] {
        type H<const N: usize> = HyperDualVec<f64, Const<N>, Const<N>>;
        let qd =
            SVector::<H<N>, N>::from_fn(|i, _| H::<N>::from_re(q[i]).derivative1(i).derivative2(i));
        let b = self.kinetic(&qd);
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let pick = |x: &H<N>| x.eps1eps2.unwrap_generic(Const::<N>, Const::<N>)[(i, j)];
                KineticBlocks {
                    rotational: b.rotational.map(|x| pick(&x)),
                    coupling: b.coupling.map(|x| pick(&x)),
                    internal: b.internal.map(|x| pick(&x)),
                }
            })
        })
    }

    /// The moment `M(R, q) = −∂/∂η V(R exp(hat η), q)|₀` (body frame) and `∂V/∂q` (default:
    /// [`coupled_torque`] and [`coupled_potential_gradient`], by automatic differentiation).
    fn potential_derivatives(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        (
            coupled_torque(self, rotation, q),
            coupled_potential_gradient(self, rotation, q),
        )
    }
}

/// `T`, `∂T/∂Ω`, `∂T/∂q̇` at velocities `(ξ, v)` for given blocks.
fn kinetic_terms<D: Scalar, const N: usize>(
    blocks: &KineticBlocks<D, N>,
    xi: &Vector3<D>,
    v: &SVector<D, N>,
) -> (D, Vector3<D>, SVector<D, N>) {
    let jx = blocks.rotational * xi;
    let bv = blocks.coupling * v;
    let mv = blocks.internal * v;
    let t_xi = jx + bv;
    let t_v = blocks.coupling.transpose() * xi + mv;
    let half = D::from(0.5);
    let t = half * xi.dot(&jx) + xi.dot(&bv) + half * v.dot(&mv);
    (t, t_xi, t_v)
}

/// `A_R(w) = 𝟙 + ½ hat w + ¼ w wᵀ`.
fn a_right<D: Scalar>(w: &Vector3<D>) -> Matrix3<D> {
    Matrix3::identity() + hat(w) * D::from(0.5) + w * w.transpose() * D::from(0.25)
}

type Grad<const N: usize> = DualVec<f64, Const<N>>;

fn grad_var<const N: usize>(x: f64, i: usize) -> Grad<N> {
    Grad::<N>::from_re(x).derivative(i)
}

fn grad_of<const N: usize>(x: &Grad<N>) -> SVector<f64, N> {
    x.eps.unwrap_generic(Const::<N>, U1)
}

/// The moment `M(R, q) = −∂/∂η V(R exp(hat η), q)|₀` (body frame), by automatic
/// differentiation.
#[must_use]
pub fn coupled_torque<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    rotation: &Matrix3<f64>,
    q: &SVector<f64, N>,
) -> Vector3<f64> {
    let eta = Vector3::from_fn(|i, _| grad_var::<3>(0.0, i));
    let r = rotation.map(Grad::<3>::from) * (Matrix3::identity() + hat(&eta));
    let v = model.potential(&r, &q.map(Grad::<3>::from));
    -grad_of(&v)
}

/// `∂V/∂q (R, q)` by automatic differentiation.
#[must_use]
pub fn coupled_potential_gradient<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    rotation: &Matrix3<f64>,
    q: &SVector<f64, N>,
) -> SVector<f64, N> {
    let qd = SVector::<Grad<N>, N>::from_fn(|i, _| grad_var::<N>(q[i], i));
    let v = model.potential(&rotation.map(Grad::<N>::from), &qd);
    grad_of(&v)
}

/// `∂T/∂q` at fixed velocities `(Ω, q̇)`: [`KineticJet::configuration_gradient`] of the model's
/// [`CoupledLagrangian::kinetic_jet`] (closed forms where the model gives them, automatic
/// differentiation otherwise).
#[must_use]
pub fn coupled_kinetic_gradient<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    omega: &Vector3<f64>,
    qdot: &SVector<f64, N>,
) -> SVector<f64, N> {
    model.kinetic_jet(q).configuration_gradient(omega, qdot)
}

/// Solves `A x = b` by Gaussian elimination with partial pivoting (fixed size, on the stack).
fn solve_small<const N: usize>(
    mut a: SMatrix<f64, N, N>,
    mut b: SVector<f64, N>,
) -> Option<SVector<f64, N>> {
    let scale = a.amax();
    for col in 0..N {
        let mut pivot = col;
        for row in col + 1..N {
            if a[(row, col)].abs() > a[(pivot, col)].abs() {
                pivot = row;
            }
        }
        let p = a[(pivot, col)];
        if !(p.abs() > 1e-14 * scale) || !p.is_finite() {
            return None;
        }
        if pivot != col {
            a.swap_rows(pivot, col);
            b.swap_rows(pivot, col);
        }
        for row in col + 1..N {
            let factor = a[(row, col)] / p;
            if factor != 0.0 {
                for k in col..N {
                    a[(row, k)] -= factor * a[(col, k)];
                }
                b[row] -= factor * b[col];
            }
        }
    }
    for col in (0..N).rev() {
        let mut s = b[col];
        for k in col + 1..N {
            s -= a[(col, k)] * b[k];
        }
        b[col] = s / a[(col, col)];
    }
    Some(b)
}

/// Solves `[A B; C D] (x, y) = (r, s)` by eliminating `x` (3 unknowns) first.
fn solve_blocks<const N: usize>(
    a: &Matrix3<f64>,
    b: &SMatrix<f64, 3, N>,
    c: &SMatrix<f64, N, 3>,
    d: &SMatrix<f64, N, N>,
    r: &Vector3<f64>,
    s: &SVector<f64, N>,
) -> Option<(Vector3<f64>, SVector<f64, N>)> {
    let a_inv = a.try_inverse()?;
    let schur = d - c * (a_inv * b);
    let y = solve_small(schur, s - c * (a_inv * r))?;
    let x = a_inv * (r - b * y);
    Some((x, y))
}

/// The velocities `(Ω, q̇)` of momenta `(Π, p)` at `q` (inverse Legendre transform).
///
/// # Errors
/// [`Error::SingularMatrix`] (with `t = NaN`, `h = NaN`) when the kinetic energy is not
/// positive definite at `q`.
pub fn coupled_velocities<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    momentum: &Vector3<f64>,
    p: &SVector<f64, N>,
) -> Result<(Vector3<f64>, SVector<f64, N>), Error> {
    velocities_of(&model.kinetic(q), q, momentum, p)
}

/// [`coupled_velocities`] for the blocks at `q`.
pub(crate) fn velocities_of<const N: usize>(
    blocks: &KineticBlocks<f64, N>,
    q: &SVector<f64, N>,
    momentum: &Vector3<f64>,
    p: &SVector<f64, N>,
) -> Result<(Vector3<f64>, SVector<f64, N>), Error> {
    solve_blocks(
        &blocks.rotational,
        &blocks.coupling,
        &blocks.coupling.transpose(),
        &blocks.internal,
        momentum,
        p,
    )
    .ok_or_else(|| Error::SingularMatrix {
        t: f64::NAN,
        h: f64::NAN,
        state: q
            .iter()
            .chain(momentum.iter())
            .chain(p.iter())
            .copied()
            .collect(),
    })
}

/// The state of velocities `(Ω, q̇)` at `(R, q)` (Legendre transform): `Π = JΩ + Bq̇`,
/// `p = BᵀΩ + Mq̇`.
#[must_use]
pub fn coupled_state_from_velocities<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    rotation: &Matrix3<f64>,
    omega: &Vector3<f64>,
    q: &SVector<f64, N>,
    qdot: &SVector<f64, N>,
) -> CoupledState<N> {
    let blocks = model.kinetic(q);
    let (_, momentum, p) = kinetic_terms(&blocks, omega, qdot);
    CoupledState {
        rotation: *rotation,
        momentum,
        q: *q,
        p,
    }
}

/// The energy `H = ½ (Ω·Π + q̇·p) + V(R, q)`.
///
/// # Errors
/// As [`coupled_velocities`].
pub fn coupled_energy<L: CoupledLagrangian<N> + ?Sized, const N: usize>(
    model: &L,
    state: &CoupledState<N>,
) -> Result<f64, Error> {
    let (omega, qdot) = coupled_velocities(model, &state.q, &state.momentum, &state.p)?;
    Ok(0.5 * (omega.dot(&state.momentum) + qdot.dot(&state.p))
        + model.potential(&state.rotation, &state.q))
}

/// `lgvi4` on a coupled model: [`CoupledLgvi`] composed with McLachlan's 5-stage order-4
/// coefficients.
#[must_use]
pub fn coupled_lgvi4<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&MCLACHLAN4, CoupledLgvi::new())
}

/// `lgvi6` on a coupled model: [`CoupledLgvi`] composed with Kahan & Li's 9-stage order-6
/// coefficients.
#[must_use]
pub fn coupled_lgvi6<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&KAHAN_LI6, CoupledLgvi::new())
}

/// `lgvi8` on a coupled model: [`CoupledLgvi`] composed with Kahan & Li's 17-stage order-8
/// coefficients.
#[must_use]
pub fn coupled_lgvi8<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&KAHAN_LI8, CoupledLgvi::new())
}

/// `lgvi10` on a coupled model: [`CoupledLgvi`] composed with Sofroniou & Spaletta's 35-stage
/// order-10 coefficients.
#[must_use]
pub fn coupled_lgvi10<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&SOFRONIOU_SPALETTA10, CoupledLgvi::new())
}

/// The variational integrator of a [`CoupledLagrangian`] (see the module doc): order 2,
/// symplectic, symmetric.
///
/// Implements [`Stepper<L>`] on [`CoupledState<N>`]. The Newton unknowns are `w` and the
/// increment `d = q_{k+1} − q_k` (not `q_{k+1}`: `v = d/h` then carries no cancellation when
/// `q` is large, e.g. an angle that keeps winding up); `q ← q + d` and `R ← R + R G`
/// (`cay(w) = 𝟙 + G`) are summed with Kahan compensation carried between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledLgvi<const N: usize> {
    max_iterations: usize,
    carry: SVector<f64, N>,
    carry_rotation: Matrix3<f64>,
    last: Option<(f64, CoupledState<N>)>,
    /// The moment and `∂V/∂q` at the end of the last step.
    end: Option<(Vector3<f64>, SVector<f64, N>)>,
}

impl<const N: usize> Default for CoupledLgvi<N> {
    fn default() -> Self {
        Self {
            max_iterations: MAX_NEWTON_ITERATIONS,
            carry: SVector::zeros(),
            carry_rotation: Matrix3::zeros(),
            last: None,
            end: None,
        }
    }
}

impl<const N: usize> CoupledLgvi<N> {
    /// A stepper allowing [`MAX_NEWTON_ITERATIONS`] Newton iterations per step.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The same stepper allowing `n` Newton iterations per step before
    /// [`Error::NoConvergence`].
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }
}

/// The known parts of the discrete equations at step `k`.
struct StepData<const N: usize> {
    h: f64,
    q0: SVector<f64, N>,
    /// `Π_k + (h/2) M(R_k, q_k)`.
    pi: Vector3<f64>,
    /// `p_k − (h/2) V_q(R_k, q_k)`.
    p: SVector<f64, N>,
}

/// `T` and its partial derivatives at `ξ = w/h`, `q̄ = q_k + d/2`, `v = d/h`.
struct Partials<const N: usize> {
    xi: Vector3<f64>,
    v: SVector<f64, N>,
    jet: KineticJet<N>,
    t_xi: Vector3<f64>,
    t_v: SVector<f64, N>,
    t_q: SVector<f64, N>,
}

/// The Newton matrix `[A B; C D]` of the residuals `(E_R, E_q)` in `(w, d)`, factored once by
/// block elimination (`A⁻¹` and the inverse of the Schur complement `D − C A⁻¹ B`) and reused
/// by the iterations that follow (simplified Newton).
struct Factored<const N: usize> {
    a_inv: Matrix3<f64>,
    a_inv_b: SMatrix<f64, 3, N>,
    c: SMatrix<f64, N, 3>,
    schur_inv: SMatrix<f64, N, N>,
}

impl<const N: usize> Factored<N> {
    fn new(
        a: &Matrix3<f64>,
        b: &SMatrix<f64, 3, N>,
        c: &SMatrix<f64, N, 3>,
        d: &SMatrix<f64, N, N>,
    ) -> Option<Self> {
        let a_inv = a.try_inverse()?;
        let a_inv_b = a_inv * b;
        let schur = d - c * a_inv_b;
        let mut schur_inv = SMatrix::<f64, N, N>::zeros();
        for j in 0..N {
            let column = solve_small(schur, SVector::<f64, N>::from_fn(|i, _| f64::from(i == j)))?;
            schur_inv.set_column(j, &column);
        }
        Some(Self {
            a_inv,
            a_inv_b,
            c: *c,
            schur_inv,
        })
    }

    /// `(x, y)` with `[A B; C D] (x, y) = (r, s)`.
    fn solve(&self, r: &Vector3<f64>, s: &SVector<f64, N>) -> (Vector3<f64>, SVector<f64, N>) {
        let a_inv_r = self.a_inv * r;
        let y = self.schur_inv * (s - self.c * a_inv_r);
        (a_inv_r - self.a_inv_b * y, y)
    }
}

impl<const N: usize> StepData<N> {
    /// `T`'s partial derivatives `(T_ξ, T_v, T_q)` at `ξ = w/h`, `q̄ = q_k + d/2`, `v = d/h`,
    /// from the model's [`KineticJet`]: what the residuals, their Jacobian and the momenta at
    /// `k + 1` need.
    fn partials<L: CoupledLagrangian<N> + ?Sized>(
        &self,
        model: &L,
        w: &Vector3<f64>,
        d: &SVector<f64, N>,
    ) -> Partials<N> {
        let inv_h = 1.0 / self.h;
        let xi = w * inv_h;
        let v = d * inv_h;
        let jet = model.kinetic_jet(&SVector::from_fn(|i, _| self.q0[i] + 0.5 * d[i]));
        let (t_xi, t_v) = jet.momenta(&xi, &v);
        let t_q = jet.configuration_gradient(&xi, &v);
        Partials {
            xi,
            v,
            jet,
            t_xi,
            t_v,
            t_q,
        }
    }

    /// The residuals `(E_R, E_q)` at `(w, d)` from their partials.
    fn residual(&self, w: &Vector3<f64>, at: &Partials<N>) -> (Vector3<f64>, SVector<f64, N>) {
        (
            self.pi - a_right(w) * at.t_xi,
            self.p + at.t_q * (0.5 * self.h) - at.t_v,
        )
    }

    /// The Newton matrix of the residuals at `(w, d)`, factored, with the model's kinetic
    /// jet and Hessian ([`CoupledLagrangian::kinetic_hessian`]) at `q̄`:
    ///
    /// ```text
    /// ∂E_R/∂w = −(−½ hat T_ξ + ¼ (w·T_ξ) 𝟙 + ¼ w T_ξᵀ) − A_R(w) J/h,
    /// ∂E_R/∂d = −A_R(w) (½ ∂_q T_ξ + B/h),         ∂_{q_j} T_ξ = ∂_j J ξ + ∂_j B v,
    /// ∂E_q/∂w = ½ ∂_ξ T_q − Bᵀ/h,                  (∂_ξ T_q)_{ij} = (∂_i J ξ + ∂_i B v)_j,
    /// ∂E_q/∂d = (h/4) ∂_q T_q + ½ ∂_v T_q − ½ ∂_q T_v − M/h,
    ///           (∂_v T_q)_{ij} = (∂_i Bᵀ ξ + ∂_i M v)_j,
    ///           (∂_q T_q)_{ij} = ½ ξᵀ ∂_{ij}J ξ + ξᵀ ∂_{ij}B v + ½ vᵀ ∂_{ij}M v.
    /// ```
    ///
    /// The term `(h/4) ∂_q T_q` is `O(h²)` against `−M/h`; without it the simplified
    /// iteration contracts only by that factor a step (3e-3 at h = 0.06 on a bead on a hoop),
    /// takes twice the iterations and stops at round-off on a biased side.
    fn jacobian<L: CoupledLagrangian<N> + ?Sized>(
        &self,
        model: &L,
        w: &Vector3<f64>,
        d: &SVector<f64, N>,
        at: &Partials<N>,
    ) -> Option<Factored<N>> {
        let inv_h = 1.0 / self.h;
        let k = &at.jet.blocks;
        let (xi, v, t) = (&at.xi, &at.v, &at.t_xi);
        let a_r = a_right(w);
        let d_ar = hat(t) * (-0.5)
            + Matrix3::from_diagonal_element(0.25 * w.dot(t))
            + w * t.transpose() * 0.25;
        let a = -(d_ar + a_r * k.rotational * inv_h);
        // ∂T_ξ/∂q_j and ∂T_v/∂q_j, column by column.
        let dtxi_dq = SMatrix::<f64, 3, N>::from_fn(|r, j| {
            let dj = &at.jet.derivatives[j];
            (dj.rotational * xi + dj.coupling * v)[r]
        });
        let dtv_dq = SMatrix::<f64, N, N>::from_fn(|r, j| {
            let dj = &at.jet.derivatives[j];
            (dj.coupling.transpose() * xi + dj.internal * v)[r]
        });
        let b = -(a_r * (dtxi_dq * 0.5 + k.coupling * inv_h));
        let c = dtxi_dq.transpose() * 0.5 - k.coupling.transpose() * inv_h;
        let hessian = model.kinetic_hessian(&SVector::from_fn(|i, _| self.q0[i] + 0.5 * d[i]));
        let t_qq = SMatrix::<f64, N, N>::from_fn(|i, j| {
            let e = &hessian[i][j];
            0.5 * xi.dot(&(e.rotational * xi))
                + xi.dot(&(e.coupling * v))
                + 0.5 * v.dot(&(e.internal * v))
        });
        let dd = t_qq * (0.25 * self.h) + (dtv_dq.transpose() - dtv_dq) * 0.5 - k.internal * inv_h;
        Factored::new(&a, &b, &c, &dd)
    }
}

impl<const N: usize, L: CoupledLagrangian<N> + ?Sized> Stepper<L> for CoupledLgvi<N> {
    type State = CoupledState<N>;

    fn step(
        &mut self,
        model: &L,
        t: f64,
        state: &mut CoupledState<N>,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let continues = self
            .last
            .as_ref()
            .is_some_and(|(t1, s1)| crate::state::same_time(*t1, t) && s1 == state);
        if !continues {
            self.carry = SVector::zeros();
            self.carry_rotation = Matrix3::zeros();
        }
        let failure =
            |iterations: usize, increment: f64, state: &CoupledState<N>| Error::NoConvergence {
                t,
                h,
                iterations,
                increment,
                state: crate::state::State::to_vec(state),
            };
        let r0 = state.rotation;
        let q0 = state.q;
        // The moment and ∂V/∂q at the end of the last step are those at the start of this one
        // when it continues (the same configuration, bit for bit).
        let (torque0, grad0) = match self.end {
            Some(end) if continues => end,
            _ => model.potential_derivatives(&r0, &q0),
        };
        let data = StepData {
            h,
            q0,
            pi: state.momentum + torque0 * (0.5 * h),
            p: state.p - grad0 * (0.5 * h),
        };
        // The explicit guess w = hΩ_k, d = h q̇_k, within O(h²) of the solution. (A guess
        // within O(h³), w = h (Ω + (h/2) Ω̇) from the continuous rates, saves half an iteration
        // a step but lets the energy of lgvi6 on the free hoop drift, 6.0e-11 with growth t^0.58
        // over 2²⁰ steps against 7.4e-12 bounded: the solve then stops on a side of the root
        // that depends on the guess, and the map is no longer symmetric to round-off.)
        let (omega, qdot) = coupled_velocities(model, &q0, &state.momentum, &state.p)
            .map_err(|_| failure(0, f64::NAN, state))?;
        let mut w = omega * h;
        let mut d = qdot * h;
        // Each block is measured relative to its own size (w ~ hΩ and d ~ hq̇ may differ by
        // orders of magnitude), with the explicit guess as a floor for components near zero.
        let floor_w = w.amax().max(f64::MIN_POSITIVE);
        let floor_d = d.amax().max(f64::MIN_POSITIVE);
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        // Newton's matrix is formed at the first iterate and again only when an iteration
        // fails to shrink the increment fourfold (simplified Newton: the explicit guess is
        // within O(h²) of the solution, so the reused matrix contracts fast). Every iteration
        // evaluates the model's kinetic jet once, at the current iterate; the matrix is built
        // from the same jet.
        let mut at = data.partials(model, &w, &d);
        let mut jacobian: Option<Factored<N>> = None;
        while iterations < self.max_iterations {
            iterations += 1;
            let fresh = jacobian.is_none();
            let matrix = match jacobian.take() {
                Some(m) => m,
                None => data
                    .jacobian(model, &w, &d, &at)
                    .ok_or_else(|| Error::SingularMatrix {
                        t,
                        h,
                        state: crate::state::State::to_vec(state),
                    })?,
            };
            let (er, eq) = data.residual(&w, &at);
            let (dw, dd) = matrix.solve(&(-er), &(-eq));
            jacobian = Some(matrix);
            let size = (dw.amax() / w.amax().max(floor_w)).max(dd.amax() / d.amax().max(floor_d));
            if !size.is_finite() {
                return Err(failure(iterations, size, state));
            }
            if size >= previous {
                converged = previous <= 1e-8;
                if !fresh && !converged {
                    // A reused matrix that no longer contracts far from the root (a large
                    // step): form it at the current iterate and take a Newton step from there.
                    jacobian = None;
                    continue;
                }
                // Stagnation: the previous iterate was as good as round-off allows (`at` is
                // still its jet).
                break;
            }
            w += dw;
            d += dd;
            at = data.partials(model, &w, &d);
            // (A stop on the contraction estimate θ/(1 − θ) |δ| below round-off, as the rigid
            // LGVI has, saves an iteration here but lets e · R Π wander 15 times further over
            // 10⁵ steps: the simplified iteration runs to round-off.)
            if size <= 4.0 * f64::EPSILON {
                converged = true;
                break;
            }
            if size > 0.25 * previous {
                jacobian = None;
            }
            previous = size;
        }
        if !converged {
            return Err(failure(iterations, previous, state));
        }
        // q₁ = q₀ + d with Kahan compensation.
        let mut q1 = q0;
        for i in 0..N {
            crate::state::compensated_add(&mut q1[i], d[i], &mut self.carry[i]);
        }
        // R₁ = R₀ cay(w) = R₀ + R₀ G with G = 4 (hat w + ½ hat w²)/(4 + |w|²): applied as a
        // compensated increment so that its rounding does not repeat identically from step to
        // step.
        let wh = hat(&w);
        let g = (wh + wh * wh * 0.5) * (4.0 / (4.0 + w.norm_squared()));
        let mut r1 = r0;
        crate::rigid::state::compensated_add_all(&mut r1, &(r0 * g), &mut self.carry_rotation);
        // Momenta at k + 1: T's partial derivatives at the solution.
        let (torque1, grad1) = model.potential_derivatives(&r1, &q1);
        state.momentum = a_right(&w).transpose() * at.t_xi + torque1 * (0.5 * h);
        state.p = at.t_v + at.t_q * (0.5 * h) - grad1 * (0.5 * h);
        self.end = Some((torque1, grad1));
        state.rotation = r1;
        state.q = q1;
        self.last = Some((t + h, *state));
        Ok(())
    }

    fn reset(&mut self) {
        *self = Self {
            max_iterations: self.max_iterations,
            ..Self::default()
        };
    }
}

/// The continuous equations of a [`CoupledLagrangian`] on `SO(3) × ℝʸ`, `y = (Π, q, p)`,
/// `Y = 3 + 2N` (see the module doc).
#[derive(Debug, Clone, Copy)]
pub struct CoupledVectorField<L, const N: usize, const Y: usize> {
    model: L,
}

impl<L: CoupledLagrangian<N>, const N: usize, const Y: usize> CoupledVectorField<L, N, Y> {
    /// Wraps a model.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `Y = 3 + 2N`.
    pub fn new(model: L) -> Result<Self, Error> {
        check_coupled_dimension(N, Y)?;
        Ok(Self { model })
    }

    /// The model.
    pub fn model(&self) -> &L {
        &self.model
    }
}

impl<L: CoupledLagrangian<N>, const N: usize, const Y: usize> LieVectorField<Y>
    for CoupledVectorField<L, N, Y>
{
    fn eval(
        &self,
        _t: f64,
        rotation: &Matrix3<f64>,
        y: &SVector<f64, Y>,
    ) -> (Vector3<f64>, SVector<f64, Y>) {
        let momentum = Vector3::new(y[0], y[1], y[2]);
        let q = SVector::<f64, N>::from_fn(|i, _| y[3 + i]);
        let p = SVector::<f64, N>::from_fn(|i, _| y[3 + N + i]);
        let jet = self.model.kinetic_jet(&q);
        let Ok((omega, qdot)) = velocities_of(&jet.blocks, &q, &momentum, &p) else {
            // A singular kinetic energy: the driver reports the non-finite state.
            return (Vector3::repeat(f64::NAN), SVector::repeat(f64::NAN));
        };
        let (torque, grad) = self.model.potential_derivatives(rotation, &q);
        let dpi = momentum.cross(&omega) + torque;
        let dp = jet.configuration_gradient(&omega, &qdot) - grad;
        let mut dy = SVector::<f64, Y>::zeros();
        dy.fixed_rows_mut::<3>(0).copy_from(&dpi);
        for i in 0..N {
            dy[3 + i] = qdot[i];
            dy[3 + N + i] = dp[i];
        }
        (omega, dy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bead on a tilted hoop with a spring along it: `J`, `B` and `M` all depend on `q`.
    struct Bead;

    impl CoupledLagrangian<1> for Bead {
        fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
            let (s, c) = (q[0].sin(), q[0].cos());
            let a = D::from(0.7) + D::from(0.2) * s;
            let r = Vector3::new(a * c, a * s, D::from(0.3) * c);
            let dr = Vector3::new(-(a * s), a * c, -(D::from(0.3) * s))
                + Vector3::new(c, s, D::from(0.0)) * (D::from(0.2) * c);
            let m = D::from(0.4);
            let body =
                Matrix3::from_diagonal(&Vector3::new(D::from(1.0), D::from(1.5), D::from(2.0)));
            KineticBlocks {
                rotational: body + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m,
                coupling: SMatrix::<D, 3, 1>::from_column_slice((r.cross(&dr) * m).as_slice()),
                internal: SMatrix::<D, 1, 1>::new(m * dr.norm_squared()),
            }
        }

        fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
            let r = Vector3::new(q[0].cos(), q[0].sin(), D::from(0.3));
            (rotation * r).z * D::from(3.0) + q[0] * q[0] * D::from(0.5)
        }
    }

    #[test]
    fn newton_matrix_matches_central_differences_of_the_residuals() {
        // The matrix solved by the simplified Newton iteration against central differences of
        // the residuals (E_R, E_q) in (w, d): equal to the differences' accuracy.
        let h = 0.05;
        let q0 = SVector::<f64, 1>::new(0.4);
        let data = StepData {
            h,
            q0,
            pi: Vector3::new(0.3, -0.2, 0.9),
            p: SVector::<f64, 1>::new(0.25),
        };
        let w = Vector3::new(0.02, -0.03, 0.05);
        let d = SVector::<f64, 1>::new(0.015);
        let at = data.partials(&Bead, &w, &d);
        let f = data.jacobian(&Bead, &w, &d, &at).unwrap();
        // Rebuild the matrix from its factors' action on unit vectors.
        let mut x = nalgebra::SMatrix::<f64, 4, 4>::zeros();
        for j in 0..4 {
            let (r, s) = (
                Vector3::from_fn(|i, _| f64::from(i == j)),
                SVector::<f64, 1>::new(f64::from(j == 3)),
            );
            let (a, b) = f.solve(&r, &s);
            x.set_column(j, &nalgebra::Vector4::new(a[0], a[1], a[2], b[0]));
        }
        let matrix = x.try_inverse().unwrap();
        let residual = |w: &Vector3<f64>, d: &SVector<f64, 1>| {
            let (r, s) = data.residual(w, &data.partials(&Bead, w, d));
            nalgebra::Vector4::new(r[0], r[1], r[2], s[0])
        };
        let eps = 1e-6;
        for j in 0..4 {
            let mut wp = w;
            let mut dp = d;
            let mut wm = w;
            let mut dm = d;
            if j < 3 {
                wp[j] += eps;
                wm[j] -= eps;
            } else {
                dp[0] += eps;
                dm[0] -= eps;
            }
            let column = (residual(&wp, &dp) - residual(&wm, &dm)) / (2.0 * eps);
            for i in 0..4 {
                let scale = 1.0 / h;
                let diff = (matrix[(i, j)] - column[i]).abs();
                assert!(
                    diff < 1e-7 * scale,
                    "({i}, {j}): {} vs {}",
                    matrix[(i, j)],
                    column[i]
                );
            }
        }
    }
}
