//! Euler–Lagrange equations from a Lagrangian, by automatic differentiation.
//!
//! # Definition
//!
//! A model is a Lagrangian `L(t, q, q̇) = T − V` in `N` generalized coordinates, written once and
//! generic over the scalar (any `nalgebra::RealField + Copy`, so that `num-dual` numbers flow
//! through it and through the kinematics crate). From it, by forward-mode automatic
//! differentiation:
//!
//! * the generalized momenta `p = ∂L/∂q̇` and the mass matrix `M = ∂²L/∂q̇²` (one evaluation with
//!   second-order dual numbers in `q̇`);
//! * the velocity-dependent terms `d/ds ∂L/∂q̇ (t + s, q + s q̇, q̇) = (∂²L/∂q̇∂q) q̇ + ∂²L/∂q̇∂t`
//!   (one evaluation with hyper-dual numbers: `q̇` against the single direction `s`);
//! * the forces `∂L/∂q` (one evaluation with first-order dual numbers in `q`);
//!
//! and the accelerations from the Euler–Lagrange equations
//! `M(q, q̇) q̈ = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t`, solved by Cholesky. The energy (the Jacobi
//! integral `h = p·q̇ − L`, conserved when `L` does not depend on `t` explicitly) and the
//! momenta come from the same derivatives. This is the article's recipe — generalized
//! coordinates, T and V, then the Lagrangian machinery — without a computer algebra system.
//!
//! # Coordinate singularities
//!
//! Euler angles make `M` singular at gimbal lock. The mass matrix's condition number
//! (`‖M‖₁ ‖M⁻¹‖₁`) is checked at every evaluation; above
//! [`DEFAULT_MAX_CONDITION`] (or a non-positive eigenvalue) the accelerations are a
//! [`ModelError::SingularMassMatrix`] carrying the time, the state and the condition number,
//! never a NaN.
//!
//! # References
//! * H. Goldstein, C. Poole, J. Safko, *Classical Mechanics*, 3rd ed., ch. 1–2.
//! * num-dual: G. Rehner, G. Bauer, "Application of generalized (hyper-) dual numbers in
//!   equation of state modeling", Front. Chem. Eng. 3 (2021).

use std::cell::RefCell;

use nalgebra::{Const, RealField, SMatrix, SVector, U1};
use num_dual::{Dual2Vec, DualVec, HyperDualVec, gradient, hessian, partial_hessian};
use tumble_integrators::Ode;

use crate::error::ModelError;

/// Hyper-dual numbers with `N` first directions (`q̇`) and one second direction (`s`).
type Hyper<const N: usize> = HyperDualVec<f64, Const<N>, U1>;

/// Default bound on the mass matrix's condition number: beyond it the coordinates are too
/// close to a singularity for the accelerations to carry more than ~6 significant digits.
pub const DEFAULT_MAX_CONDITION: f64 = 1e10;

/// A Lagrangian `L(t, q, q̇)` in `N` generalized coordinates, generic over the scalar.
pub trait Lagrangian<const N: usize> {
    /// `L = T − V` at time `t`, coordinates `q` and rates `q̇`.
    fn lagrangian<D: RealField + Copy>(&self, t: D, q: &SVector<D, N>, qd: &SVector<D, N>) -> D;
}

/// The Euler–Lagrange equations of a [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerLagrange<L, const N: usize> {
    lagrangian: L,
    max_condition: f64,
}

/// Everything the equations of motion need at one point, from three AD evaluations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives<const N: usize> {
    /// `L`.
    pub lagrangian: f64,
    /// `p = ∂L/∂q̇`.
    pub momenta: SVector<f64, N>,
    /// `M = ∂²L/∂q̇²`.
    pub mass_matrix: SMatrix<f64, N, N>,
    /// `∂L/∂q`.
    pub forces: SVector<f64, N>,
    /// `(∂²L/∂q̇∂q) q̇ + ∂²L/∂q̇∂t`.
    pub velocity_terms: SVector<f64, N>,
}

impl<L, const N: usize> EulerLagrange<L, N> {
    /// The equations of `lagrangian`, with the default conditioning bound.
    pub fn new(lagrangian: L) -> Self {
        EulerLagrange {
            lagrangian,
            max_condition: DEFAULT_MAX_CONDITION,
        }
    }

    /// Changes the bound on the mass matrix's condition number.
    #[must_use]
    pub fn with_max_condition(mut self, max_condition: f64) -> Self {
        self.max_condition = max_condition;
        self
    }

    /// The Lagrangian.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }
}

fn constant_vec<D: RealField + Copy, const N: usize>(v: &SVector<f64, N>) -> SVector<D, N> {
    v.map(|x| nalgebra::convert::<f64, D>(x))
}

impl<L, const N: usize> EulerLagrange<L, N>
where
    L: Lagrangian<N>,
{
    /// `L(t, q, q̇)`.
    pub fn value(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> f64 {
        self.lagrangian.lagrangian(t, q, qd)
    }

    /// Momenta, mass matrix, forces and velocity terms at `(t, q, q̇)`.
    pub fn derivatives(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> Derivatives<N> {
        // M and p: second-order duals in q̇.
        let (value, momenta, mass_matrix) = hessian(
            |v: SVector<Dual2Vec<f64, Const<N>>, N>| {
                self.lagrangian
                    .lagrangian(Dual2Vec::from_re(t), &constant_vec(q), &v)
            },
            qd,
        );
        // ∂L/∂q: first-order duals in q.
        let (_, forces) = gradient(
            |v: SVector<DualVec<f64, Const<N>>, N>| {
                self.lagrangian
                    .lagrangian(DualVec::from_re(t), &v, &constant_vec(qd))
            },
            q,
        );
        // d/ds ∂L/∂q̇ along (t + s, q + s q̇): hyper-duals, q̇ against s.
        let (_, _, _, mixed) = partial_hessian(
            |(v, s): (SVector<Hyper<N>, N>, SVector<Hyper<N>, 1>)| {
                let s = s[0];
                let qs: SVector<Hyper<N>, N> =
                    SVector::from_fn(|i, _| HyperDualVec::from_re(q[i]) + s * qd[i]);
                self.lagrangian
                    .lagrangian(HyperDualVec::from_re(t) + s, &qs, &v)
            },
            (qd, &SVector::<f64, 1>::zeros()),
        );
        Derivatives {
            lagrangian: value,
            momenta,
            mass_matrix,
            forces,
            velocity_terms: mixed.column(0).into_owned(),
        }
    }

    /// Generalized momenta `p = ∂L/∂q̇`.
    pub fn momenta(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> SVector<f64, N> {
        self.derivatives(t, q, qd).momenta
    }

    /// The mass matrix `M = ∂²L/∂q̇²`.
    pub fn mass_matrix(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N> {
        self.derivatives(t, q, qd).mass_matrix
    }

    /// The energy (Jacobi integral) `h = p·q̇ − L`.
    pub fn energy(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> f64 {
        let d = self.derivatives(t, q, qd);
        d.momenta.dot(qd) - d.lagrangian
    }

    /// The 1-norm condition number of the mass matrix (∞ if it is not positive definite).
    pub fn condition(&self, t: f64, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> f64 {
        condition_number(&self.mass_matrix(t, q, qd))
    }

    /// The accelerations `q̈` from `M q̈ = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t`.
    ///
    /// # Errors
    /// [`ModelError::SingularMassMatrix`] when the mass matrix is not positive definite or its
    /// condition number exceeds the bound; [`ModelError::NonFinite`] for a non-finite result.
    pub fn accelerations(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> Result<SVector<f64, N>, ModelError> {
        let d = self.derivatives(t, q, qd);
        let state = || q.iter().chain(qd.iter()).copied().collect::<Vec<f64>>();
        let condition = condition_number(&d.mass_matrix);
        if !(condition <= self.max_condition) {
            return Err(ModelError::SingularMassMatrix {
                t,
                condition,
                max_condition: self.max_condition,
                state: state(),
            });
        }
        let rhs = d.forces - d.velocity_terms;
        let chol = d
            .mass_matrix
            .cholesky()
            .ok_or_else(|| ModelError::SingularMassMatrix {
                t,
                condition,
                max_condition: self.max_condition,
                state: state(),
            })?;
        let qdd = chol.solve(&rhs);
        if qdd.iter().all(|x| x.is_finite()) {
            Ok(qdd)
        } else {
            Err(ModelError::NonFinite { t, state: state() })
        }
    }
}

/// The 1-norm condition number `‖M‖₁ ‖M⁻¹‖₁` of a symmetric matrix, through its Cholesky
/// factor; ∞ unless it is positive definite.
#[must_use]
pub fn condition_number<const N: usize>(m: &SMatrix<f64, N, N>) -> f64 {
    if m.iter().any(|x| !x.is_finite()) {
        return f64::INFINITY;
    }
    let norm1 = |a: &SMatrix<f64, N, N>| {
        a.column_iter()
            .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
            .fold(0.0f64, f64::max)
    };
    match m.cholesky() {
        Some(ch) => {
            let c = norm1(m) * norm1(&ch.inverse());
            if c.is_finite() { c } else { f64::INFINITY }
        }
        None => f64::INFINITY,
    }
}

/// First-order form `y = (q, q̇)`, `y' = (q̇, q̈)` of [`EulerLagrange`] for the integrators:
/// `S = 2N` components.
///
/// The integrators' right-hand sides cannot fail, so a model error (a singular mass matrix)
/// is recorded here, the derivative is filled with NaN, and the driver stops with a
/// non-finite-state error; [`LagrangianOde::take_error`] then gives the model's own reason.
#[derive(Debug)]
pub struct LagrangianOde<L, const N: usize, const S: usize> {
    equations: EulerLagrange<L, N>,
    error: RefCell<Option<ModelError>>,
}

impl<L: Lagrangian<N>, const N: usize, const S: usize> LagrangianOde<L, N, S> {
    /// The first-order system of `equations`.
    ///
    /// # Errors
    /// [`ModelError::Dimension`] unless `S = 2N`.
    pub fn new(equations: EulerLagrange<L, N>) -> Result<Self, ModelError> {
        if S != 2 * N {
            return Err(ModelError::Dimension {
                expected: 2 * N,
                found: S,
            });
        }
        Ok(LagrangianOde {
            equations,
            error: RefCell::new(None),
        })
    }

    /// The equations.
    pub fn equations(&self) -> &EulerLagrange<L, N> {
        &self.equations
    }

    /// Splits a state into coordinates and rates.
    pub fn split(y: &SVector<f64, S>) -> (SVector<f64, N>, SVector<f64, N>) {
        (
            SVector::from_fn(|i, _| y[i]),
            SVector::from_fn(|i, _| y[N + i]),
        )
    }

    /// The first model error met by the right-hand side, if any (and clears it).
    pub fn take_error(&self) -> Option<ModelError> {
        self.error.borrow_mut().take()
    }
}

impl<L: Lagrangian<N>, const N: usize, const S: usize> Ode<SVector<f64, S>>
    for LagrangianOde<L, N, S>
{
    fn rhs(&self, t: f64, y: &SVector<f64, S>, dy: &mut SVector<f64, S>) {
        let (q, qd) = Self::split(y);
        match self.equations.accelerations(t, &q, &qd) {
            Ok(qdd) => {
                for i in 0..N {
                    dy[i] = qd[i];
                    dy[N + i] = qdd[i];
                }
            }
            Err(e) => {
                let mut slot = self.error.borrow_mut();
                if slot.is_none() {
                    *slot = Some(e);
                }
                dy.fill(f64::NAN);
            }
        }
    }
}
