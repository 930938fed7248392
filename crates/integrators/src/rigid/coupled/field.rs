//! The continuous equations of a coupled model as a vector field on `SO(3) × ℝʸ`
//! ([`CoupledVectorField`]; [`super`] module doc, "The continuous equations").

use nalgebra::{Matrix3, SVector, Vector3};

use super::model::{CoupledLagrangian, velocities_of};
use crate::error::Error;
use crate::rigid::problem::LieVectorField;
use crate::rigid::state::check_coupled_dimension;

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
