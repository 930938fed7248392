//! The model of a rigid body coupled to internal coordinates ([`CoupledLagrangian`]): the
//! kinetic blocks and their jet, forward-mode dual numbers for the derivatives a model does not
//! write by hand, the Legendre transform and its inverse, torques, gradients and the energy
//! ([`super`] module doc, "The model").

use nalgebra::{Const, Matrix3, RealField, SMatrix, SVector, U1, Vector3};
use num_dual::{DualVec, HyperDualVec};

use tumble_kinematics::so3::hat;

use crate::error::Error;
use crate::rigid::state::CoupledState;

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

    /// The blocks at `q` in `f64` (default: [`Self::kinetic`]): what the Legendre transform
    /// of a step ([`coupled_velocities`]) and the energy use. A model whose generic
    /// [`Self::kinetic`] is costly in `f64` (an interpreted expression allocating its
    /// workspace) gives an allocation-free evaluation here.
    fn kinetic_blocks(&self, q: &SVector<f64, N>) -> KineticBlocks<f64, N> {
        self.kinetic(q)
    }

    /// `V(R, q)` in `f64` (default: [`Self::potential`]), for the energy; overridden for the
    /// same reason as [`Self::kinetic_blocks`].
    fn potential_value(&self, rotation: &Matrix3<f64>, q: &SVector<f64, N>) -> f64 {
        self.potential(rotation, q)
    }

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
pub(super) fn kinetic_terms<D: Scalar, const N: usize>(
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
pub(super) fn a_right<D: Scalar>(w: &Vector3<D>) -> Matrix3<D> {
    Matrix3::identity() + hat(w) * D::from(0.5) + w * w.transpose() * D::from(0.25)
}

pub(super) type Grad<const N: usize> = DualVec<f64, Const<N>>;

pub(super) fn grad_var<const N: usize>(x: f64, i: usize) -> Grad<N> {
    Grad::<N>::from_re(x).derivative(i)
}

pub(super) fn grad_of<const N: usize>(x: &Grad<N>) -> SVector<f64, N> {
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
pub(super) fn solve_small<const N: usize>(
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
pub(super) fn solve_blocks<const N: usize>(
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
    velocities_of(&model.kinetic_blocks(q), q, momentum, p)
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
    let blocks = model.kinetic_blocks(q);
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
        + model.potential_value(&state.rotation, &state.q))
}
