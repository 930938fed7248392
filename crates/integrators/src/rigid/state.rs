//! States on `SO(3)` and on `SO(3) × ℝⁿ`.
//!
//! Every state stores the orientation as a plain 3×3 matrix `R` (body → space: a vector's body
//! components `v_b` map to its space components `R v_b`), not as a `Rotation3`: the methods keep
//! `R` on the group by construction, and the diagnostics measure how well they do
//! (`‖RᵀR − 𝟙‖_F`), which a type that asserts orthogonality would hide.
//!
//! - [`RigidBodyState`]: `(R, m)` with `m` the **body** angular momentum; `L = R m` is the
//!   spatial angular momentum.
//! - [`GroupState`]: `(R, y)`, `y ∈ ℝᴺ` a fixed-size vector: the state of the Lie-group
//!   Runge–Kutta methods for `Ṙ = R hat(ξ(t, R, y))`, `ẏ = f(t, R, y)`.
//! - [`CoupledState`]: `(R, Π, q, p)`: a body coupled to `N` extra coordinates `q` with their
//!   conjugate momenta `p` and the body momentum `Π = ∂L/∂Ω`; the state of the coupled
//!   variational integrator ([`crate::rigid::CoupledLgvi`]).
//!
//! All are `Copy` (on the stack) and implement [`State`]; `to_vec` flattens `R` column by column
//! and then the vector parts, in the order of the fields.

use nalgebra::{Matrix3, Rotation3, SVector, Vector3};

use crate::state::{State, compensated_add, same_time};

/// Orientation and body angular momentum of a rigid body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBodyState {
    /// `R`: body → space.
    pub rotation: Matrix3<f64>,
    /// `m`: angular momentum in the body frame.
    pub momentum: Vector3<f64>,
}

impl RigidBodyState {
    /// A state from a rotation and a body angular momentum.
    #[must_use]
    pub fn new(rotation: &Rotation3<f64>, momentum: Vector3<f64>) -> Self {
        Self {
            rotation: *rotation.matrix(),
            momentum,
        }
    }

    /// The spatial angular momentum `L = R m`.
    #[must_use]
    pub fn spatial_momentum(&self) -> Vector3<f64> {
        self.rotation * self.momentum
    }

    /// `‖RᵀR − 𝟙‖_F`.
    #[must_use]
    pub fn orthogonality_defect(&self) -> f64 {
        tumble_kinematics::so3::orthogonality_defect(&self.rotation)
    }

    /// The orientation as a `Rotation3` (no re-orthogonalization).
    #[must_use]
    pub fn rotation3(&self) -> Rotation3<f64> {
        Rotation3::from_matrix_unchecked(self.rotation)
    }
}

impl State for RigidBodyState {
    fn is_finite(&self) -> bool {
        self.rotation
            .iter()
            .chain(self.momentum.iter())
            .all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.rotation
            .iter()
            .chain(self.momentum.iter())
            .copied()
            .collect()
    }
}

/// A point of `SO(3) × ℝᴺ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroupState<const N: usize> {
    /// `R`: body → space.
    pub rotation: Matrix3<f64>,
    /// The vector-space part.
    pub vector: SVector<f64, N>,
}

impl<const N: usize> GroupState<N> {
    /// A state from a rotation and a vector.
    #[must_use]
    pub fn new(rotation: &Rotation3<f64>, vector: SVector<f64, N>) -> Self {
        Self {
            rotation: *rotation.matrix(),
            vector,
        }
    }

    /// `‖RᵀR − 𝟙‖_F`.
    #[must_use]
    pub fn orthogonality_defect(&self) -> f64 {
        tumble_kinematics::so3::orthogonality_defect(&self.rotation)
    }
}

impl From<RigidBodyState> for GroupState<3> {
    fn from(s: RigidBodyState) -> Self {
        Self {
            rotation: s.rotation,
            vector: s.momentum,
        }
    }
}

impl From<GroupState<3>> for RigidBodyState {
    fn from(s: GroupState<3>) -> Self {
        Self {
            rotation: s.rotation,
            momentum: s.vector,
        }
    }
}

impl<const N: usize> State for GroupState<N> {
    fn is_finite(&self) -> bool {
        self.rotation
            .iter()
            .chain(self.vector.iter())
            .all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.rotation
            .iter()
            .chain(self.vector.iter())
            .copied()
            .collect()
    }
}

/// A rigid body coupled to `N` extra coordinates: `(R, Π, q, p)`.
///
/// `Π = ∂L/∂Ω` is the body-frame angular momentum of the whole system (body and whatever moves
/// with `q`), `p = ∂L/∂q̇`; the spatial angular momentum about the fixed point is `R Π`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledState<const N: usize> {
    /// `R`: body → space.
    pub rotation: Matrix3<f64>,
    /// `Π = ∂L/∂Ω` (body frame).
    pub momentum: Vector3<f64>,
    /// Extra coordinates `q`.
    pub q: SVector<f64, N>,
    /// Their momenta `p = ∂L/∂q̇`.
    pub p: SVector<f64, N>,
}

impl<const N: usize> CoupledState<N> {
    /// The spatial angular momentum `R Π`.
    #[must_use]
    pub fn spatial_momentum(&self) -> Vector3<f64> {
        self.rotation * self.momentum
    }

    /// `‖RᵀR − 𝟙‖_F`.
    #[must_use]
    pub fn orthogonality_defect(&self) -> f64 {
        tumble_kinematics::so3::orthogonality_defect(&self.rotation)
    }

    /// The vector part `(Π, q, p)` flattened into a [`GroupState`] of dimension `Y = 3 + 2N`.
    ///
    /// # Errors
    /// [`crate::Error::DimensionMismatch`] unless `Y = 3 + 2N`.
    pub fn to_group<const Y: usize>(&self) -> Result<GroupState<Y>, crate::Error> {
        check_coupled_dimension(N, Y)?;
        let mut vector = SVector::<f64, Y>::zeros();
        vector.fixed_rows_mut::<3>(0).copy_from(&self.momentum);
        for i in 0..N {
            vector[3 + i] = self.q[i];
            vector[3 + N + i] = self.p[i];
        }
        Ok(GroupState {
            rotation: self.rotation,
            vector,
        })
    }

    /// The inverse of [`Self::to_group`].
    ///
    /// # Errors
    /// [`crate::Error::DimensionMismatch`] unless `Y = 3 + 2N`.
    pub fn from_group<const Y: usize>(g: &GroupState<Y>) -> Result<Self, crate::Error> {
        check_coupled_dimension(N, Y)?;
        Ok(Self {
            rotation: g.rotation,
            momentum: g.vector.fixed_rows::<3>(0).into_owned(),
            q: SVector::from_fn(|i, _| g.vector[3 + i]),
            p: SVector::from_fn(|i, _| g.vector[3 + N + i]),
        })
    }
}

/// `Y = 3 + 2N`, the flat dimension of `(Π, q, p)`.
pub(crate) fn check_coupled_dimension(n: usize, y: usize) -> Result<(), crate::Error> {
    if y == 3 + 2 * n {
        Ok(())
    } else {
        Err(crate::Error::DimensionMismatch {
            expected: 3 + 2 * n,
            found: y,
        })
    }
}

impl<const N: usize> State for CoupledState<N> {
    fn is_finite(&self) -> bool {
        self.rotation
            .iter()
            .chain(self.momentum.iter())
            .chain(self.q.iter())
            .chain(self.p.iter())
            .all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.rotation
            .iter()
            .chain(self.momentum.iter())
            .chain(self.q.iter())
            .chain(self.p.iter())
            .copied()
            .collect()
    }
}

/// `x ← x + δ` entry by entry with Kahan compensation (`carry` holds the rounding errors).
#[inline]
pub(crate) fn compensated_add_all<const R: usize, const C: usize>(
    x: &mut nalgebra::SMatrix<f64, R, C>,
    delta: &nalgebra::SMatrix<f64, R, C>,
    carry: &mut nalgebra::SMatrix<f64, R, C>,
) {
    for i in 0..R * C {
        compensated_add(&mut x[i], delta[i], &mut carry[i]);
    }
}

/// The Kahan carries of a [`RigidBodyState`] updated by increments, valid while the state is
/// what the stepper last produced (else they restart at zero).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct RigidCarry {
    rotation: Matrix3<f64>,
    momentum: Vector3<f64>,
    last: Option<(f64, RigidBodyState)>,
}

impl RigidCarry {
    /// Forgets the carries unless `(t, state)` is the last output; whether it is (the step
    /// continues the last one, so data kept from it, such as the moment at its end, apply).
    pub(crate) fn prepare(&mut self, t: f64, state: &RigidBodyState) -> bool {
        let continues = self
            .last
            .as_ref()
            .is_some_and(|(t1, s1)| same_time(*t1, t) && s1 == state);
        if !continues {
            *self = Self::default();
        }
        continues
    }

    /// `R ← R + ΔR`, then `m ← m + Δm(R)` with `Δm` computed from the updated rotation
    /// (compensated sums); remembers the result as the output at `t`.
    pub(crate) fn apply_with(
        &mut self,
        t: f64,
        state: &mut RigidBodyState,
        d_rotation: &Matrix3<f64>,
        d_momentum: impl FnOnce(&Matrix3<f64>) -> Vector3<f64>,
    ) {
        compensated_add_all(&mut state.rotation, d_rotation, &mut self.rotation);
        let dm = d_momentum(&state.rotation);
        compensated_add_all(&mut state.momentum, &dm, &mut self.momentum);
        self.last = Some((t, *state));
    }

    pub(crate) fn reset(&mut self) {
        *self = Self::default();
    }
}
