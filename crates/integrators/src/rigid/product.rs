//! The product group `SO(3)ᴹ × ℝᴺ`: several bodies' orientations beside a vector part (a chain
//! of rigid bodies joined by ball joints, each orientation on its own copy of `SO(3)`).
//!
//! - [`ProductState`]: `(R₁ … R_M, y)`, the state of the Lie-group Runge–Kutta methods on the
//!   product ([`crate::rigid::ProductRkmk`], [`crate::rigid::ProductCrouchGrossman`]).
//! - [`ProductVectorField`]: `Ṙₖ = Rₖ hat(ξₖ(t, R, y))`, `ẏ = f(t, R, y)`, each rotation with
//!   its own body velocity `ξₖ`.
//!
//! The group acts factor by factor, so a Lie-group method advances each `Rₖ` by the exponential
//! of its own increment, computed from the `ξₖ` alone: every rotation stays orthogonal to
//! round-off (Iserles, Munthe-Kaas, Nørsett & Zanna, *Lie-group methods*, Acta Numerica 9
//! (2000) 215–365, §2: a direct product of Lie groups is a Lie group whose algebra is the
//! product of the algebras, with the exponential and `dexp` taken factor by factor). For
//! `M = 1` this is [`crate::rigid::GroupState`] and [`crate::rigid::LieVectorField`].

use nalgebra::{Matrix3, SVector, Vector3};

use crate::state::State;

/// A point of `SO(3)ᴹ × ℝᴺ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProductState<const M: usize, const N: usize> {
    /// `R₁ … R_M`: each body → space.
    pub rotations: [Matrix3<f64>; M],
    /// The vector-space part.
    pub vector: SVector<f64, N>,
}

impl<const M: usize, const N: usize> ProductState<M, N> {
    /// The largest `‖RₖᵀRₖ − 𝟙‖_F` over the rotations.
    #[must_use]
    pub fn orthogonality_defect(&self) -> f64 {
        self.rotations
            .iter()
            .map(tumble_kinematics::so3::orthogonality_defect)
            .fold(0.0, f64::max)
    }
}

impl<const M: usize, const N: usize> State for ProductState<M, N> {
    fn is_finite(&self) -> bool {
        self.rotations
            .iter()
            .flat_map(|r| r.iter())
            .chain(self.vector.iter())
            .all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.rotations
            .iter()
            .flat_map(|r| r.iter())
            .chain(self.vector.iter())
            .copied()
            .collect()
    }
}

/// A vector field on `SO(3)ᴹ × ℝᴺ`: `Ṙₖ = Rₖ hat(ξₖ)`, `ẏ = f`, with `(ξ₁ … ξ_M, f)` functions
/// of `(t, R₁ … R_M, y)`. `eval` must not allocate (it is called at every stage).
pub trait ProductVectorField<const M: usize, const N: usize> {
    /// The body velocities `ξₖ` and `ẏ` at `(t, R, y)`.
    fn eval(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, N>,
    ) -> ([Vector3<f64>; M], SVector<f64, N>);
}

impl<const M: usize, const N: usize, F: ProductVectorField<M, N> + ?Sized> ProductVectorField<M, N>
    for &F
{
    fn eval(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, N>,
    ) -> ([Vector3<f64>; M], SVector<f64, N>) {
        (**self).eval(t, rotations, y)
    }
}
