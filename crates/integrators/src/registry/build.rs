//! The registry builds steppers: from a method's [`Stepping`] to the stepper of its family on
//! a kind of problem, handed to a receiver that runs it.
//!
//! One function per [`ProblemKind`] ([`ode`], [`taylor`], [`rigid_body`], [`free_rigid_body`],
//! [`lie_vector_field`], [`product_vector_field`], [`product_lagrangian`], [`coupled`], [`separable`], [`split`]) matches every [`Stepping`]
//! without a wildcard: a new family is a compile error here until each kind says whether it
//! runs it. A new table of an existing family (an explicit pair, a Gauss table, a composition)
//! needs nothing here — its registry row carries the table. The caller supplies a receiver
//! ([`Receive`], or [`ReceiveOde`] for first-order ODEs, where methods differ in how they step
//! and interpolate) that runs the stepper it is handed; the stepper's type stays concrete, so
//! nothing is boxed and nothing allocates per step.
//!
//! The tests, the benches and `tumble_scenarios::dispatch` all build steppers here, by name
//! through [`super::find`], so no list of names is kept anywhere else.

use std::marker::PhantomData;

use crate::composition::Composition;
use crate::explicit::ExplicitRungeKutta;
use crate::gauss::{Gauss, gauss2};
use crate::problem::{Ode, SeparableHamiltonian, SplitOde};
use crate::rigid::{
    CoupledLagrangian, CoupledLgvi, CoupledLieGauss, CoupledState, Dmv, ExactSplitting,
    ExactStepper, FreeRigidBody, GroupState, Lgvi, LieGauss, LieVectorField,
    PrincipalAxisSplitting, ProductLagrangian, ProductLgvi, ProductState, ProductVectorField,
    RigidBody, RigidBodyState, cg3, product_cg3, product_rkmk4, rkmk4,
};
use crate::state::{State, VectorState};
use crate::stepper::{AdaptiveStepper, DenseOutput, Stepper};
use crate::symplectic::{Splitting, SplittingStepper, StormerVerlet, SymplecticEuler};
use crate::tables::GaussTableau;
use crate::taylor::{DoubleDoubleTaylorStepper, Taylor, TaylorOrder, TaylorSystem};

use super::{BaseStepper, ExplicitVisitor, GaussVisitor, MethodInfo, ProblemKind, Stepping};

/// A method has no stepper for the kind of problem it was asked to integrate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("`{method}` has no stepper for a {} problem", kind.name())]
pub struct NoStepper {
    /// The method's registry name.
    pub method: &'static str,
    /// The kind of problem asked for.
    pub kind: ProblemKind,
}

/// Receives the stepper a method builds for problems `P` with states `S`, and runs it.
pub trait Receive<P: ?Sized, S: State> {
    /// What running it returns.
    type Output;
    /// Runs `stepper` (fixed steps; no interpolant of its own).
    fn receive<St: Stepper<P, State = S> + Clone>(self, stepper: St) -> Self::Output;
}

/// Receives the stepper a method builds for a first-order ODE `P` on states `Y` (an [`Ode`], or
/// a [`TaylorSystem`] for [`taylor`]), and runs it.
pub trait ReceiveOde<P: ?Sized, Y: VectorState> {
    /// What running it returns.
    type Output;
    /// An explicit pair (error estimate, step-size control and its own interpolant), or an
    /// adaptive Taylor method (its own steps, its polynomial).
    fn adaptive<St: AdaptiveStepper<P, State = Y> + DenseOutput<P>>(
        self,
        stepper: St,
    ) -> Self::Output;
    /// A fixed-step method with its own interpolant (RK4, Gauss–Legendre, a Taylor method of
    /// fixed order).
    fn interpolating<St: DenseOutput<P, State = Y>>(self, stepper: St) -> Self::Output;
    /// A fixed-step method without an interpolant (a composition of `gauss2`).
    fn plain<St: Stepper<P, State = Y> + Clone>(self, stepper: St) -> Self::Output;
}

impl NoStepper {
    fn of<T>(method: &MethodInfo, kind: ProblemKind) -> Result<T, Self> {
        Err(Self {
            method: method.name,
            kind,
        })
    }
}

/// Builds `method`'s stepper for a first-order ODE shaped like `y0` and hands it to
/// `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate first-order ODEs.
pub fn ode<P: Ode<Y>, Y: VectorState, R: ReceiveOde<P, Y>>(
    method: &MethodInfo,
    y0: &Y,
    receiver: R,
) -> Result<R::Output, NoStepper> {
    match method.stepping {
        Stepping::Explicit(m) => Ok(m.visit(ExplicitOde {
            y0,
            receiver,
            problem: PhantomData,
        })),
        Stepping::Gauss(table) => Ok(table.visit(GaussOde {
            y0,
            receiver,
            problem: PhantomData,
        })),
        Stepping::Composition { table, base } => match base.stepper {
            BaseStepper::Gauss2 => {
                Ok(receiver.plain(Composition::new(table, gauss2().stepper(y0))))
            }
            BaseStepper::StormerVerlet
            | BaseStepper::Lgvi
            | BaseStepper::PrincipalAxisSplitting
            | BaseStepper::ExactSplitting => NoStepper::of(method, ProblemKind::Ode),
        },
        Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::Ode),
    }
}

/// Builds `method`'s stepper for a first-order ODE that computes its Taylor coefficients
/// ([`ProblemKind::TaylorSeries`]; in double-double for `taylor-dd`,
/// [`ProblemKind::DoubleDoubleTaylorSeries`]), on states shaped like `y0`, and hands it to
/// `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method is not a Taylor method.
pub fn taylor<P: TaylorSystem + ?Sized, Y: VectorState, R: ReceiveOde<P, Y>>(
    method: &MethodInfo,
    y0: &Y,
    receiver: R,
) -> Result<R::Output, NoStepper> {
    match method.stepping {
        Stepping::Taylor(order) => {
            let stepper = Taylor { order }.stepper(y0);
            Ok(match order {
                TaylorOrder::FromTolerance => receiver.adaptive(stepper),
                TaylorOrder::Fixed(_) => receiver.interpolating(stepper),
            })
        }
        Stepping::TaylorDoubleDouble => Ok(receiver.adaptive(DoubleDoubleTaylorStepper::new(y0))),
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Composition { .. }
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow => NoStepper::of(method, ProblemKind::TaylorSeries),
    }
}

/// Builds `method`'s stepper for a rigid body `B` on SO(3) × ℝ³ and hands it to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate rigid bodies.
pub fn rigid_body<B: RigidBody + ?Sized, R: Receive<B, RigidBodyState>>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper> {
    match method.stepping {
        Stepping::Lgvi => Ok(receiver.receive(Lgvi::new())),
        Stepping::LieGauss(table) => Ok(table.visit(LieGaussRigid {
            receiver,
            problem: PhantomData,
        })),
        Stepping::PrincipalAxisSplitting => Ok(receiver.receive(PrincipalAxisSplitting::new())),
        Stepping::ExactSplitting => Ok(receiver.receive(ExactSplitting::new())),
        Stepping::Composition { table, base } => match base.stepper {
            BaseStepper::Lgvi => Ok(receiver.receive(Composition::new(table, Lgvi::new()))),
            BaseStepper::PrincipalAxisSplitting => {
                Ok(receiver.receive(Composition::new(table, PrincipalAxisSplitting::new())))
            }
            BaseStepper::ExactSplitting => {
                Ok(receiver.receive(Composition::new(table, ExactSplitting::new())))
            }
            BaseStepper::StormerVerlet | BaseStepper::Gauss2 => {
                NoStepper::of(method, ProblemKind::RigidBody)
            }
        },
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::RigidBody),
    }
}

/// Builds `method`'s stepper for a torque-free rigid body and hands it to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate free rigid bodies as such.
pub fn free_rigid_body<R: Receive<FreeRigidBody, RigidBodyState>>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper> {
    match method.stepping {
        Stepping::Dmv => Ok(receiver.receive(Dmv::new())),
        Stepping::ExactFlow => Ok(receiver.receive(ExactStepper::new())),
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Composition { .. }
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::FreeRigidBody),
    }
}

/// Builds `method`'s stepper for a vector field `F` on SO(3) × ℝᴺ and hands it to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate Lie-group vector fields.
pub fn lie_vector_field<F, R, const N: usize>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper>
where
    F: LieVectorField<N> + ?Sized,
    R: Receive<F, GroupState<N>>,
{
    match method.stepping {
        Stepping::Rkmk4 => Ok(receiver.receive(rkmk4::<N>())),
        Stepping::Cg3 => Ok(receiver.receive(cg3::<N>())),
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Composition { .. }
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::LieVectorField),
    }
}

/// Builds `method`'s stepper for a vector field `F` on the product `SO(3)ᴹ × ℝᴺ` and hands it to
/// `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate vector fields on the product.
pub fn product_vector_field<F, R, const M: usize, const N: usize>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper>
where
    F: ProductVectorField<M, N> + ?Sized,
    R: Receive<F, ProductState<M, N>>,
{
    match method.stepping {
        Stepping::Rkmk4 => Ok(receiver.receive(product_rkmk4::<M, N>())),
        Stepping::Cg3 => Ok(receiver.receive(product_cg3::<M, N>())),
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Composition { .. }
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::ProductVectorField),
    }
}

/// Builds `method`'s stepper for a rigid body coupled to `N` coordinates and hands it to
/// `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate coupled rigid bodies.
pub fn coupled<L, R, const N: usize>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper>
where
    L: CoupledLagrangian<N> + ?Sized,
    R: Receive<L, CoupledState<N>>,
{
    match method.stepping {
        Stepping::Lgvi => Ok(receiver.receive(CoupledLgvi::<N>::new())),
        Stepping::LieGauss(table) => Ok(table.visit(LieGaussCoupled::<L, R, N> {
            receiver,
            problem: PhantomData,
        })),
        Stepping::Composition { table, base } => match base.stepper {
            BaseStepper::Lgvi => {
                Ok(receiver.receive(Composition::new(table, CoupledLgvi::<N>::new())))
            }
            BaseStepper::StormerVerlet
            | BaseStepper::PrincipalAxisSplitting
            | BaseStepper::ExactSplitting
            | BaseStepper::Gauss2 => NoStepper::of(method, ProblemKind::CoupledRigidBody),
        },
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::CoupledRigidBody),
    }
}

/// Builds `method`'s stepper for a Lagrangian `L` on the product `SO(3)ᴹ × ℝⁿ` (`N = 2n + 3M`
/// numbers beside the rotations) and hands it to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate Lagrangians on the product.
pub fn product_lagrangian<L, R, const M: usize, const N: usize>(
    method: &MethodInfo,
    receiver: R,
) -> Result<R::Output, NoStepper>
where
    L: ProductLagrangian<M, N> + ?Sized,
    R: Receive<L, ProductState<M, N>>,
{
    match method.stepping {
        Stepping::Lgvi => Ok(receiver.receive(ProductLgvi::<M, N>::new())),
        Stepping::Composition { table, base } => match base.stepper {
            BaseStepper::Lgvi => {
                Ok(receiver.receive(Composition::new(table, ProductLgvi::<M, N>::new())))
            }
            BaseStepper::StormerVerlet
            | BaseStepper::PrincipalAxisSplitting
            | BaseStepper::ExactSplitting
            | BaseStepper::Gauss2 => NoStepper::of(method, ProblemKind::ProductLagrangian),
        },
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Strang
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::ProductLagrangian),
    }
}

/// Builds `method`'s stepper for a separable Hamiltonian `H` on states shaped like `y0` and
/// hands it to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method does not integrate separable Hamiltonians as such.
pub fn separable<H, Y, R>(method: &MethodInfo, y0: &Y, receiver: R) -> Result<R::Output, NoStepper>
where
    H: SeparableHamiltonian + ?Sized,
    Y: VectorState,
    R: Receive<H, Y>,
{
    match method.stepping {
        Stepping::SymplecticEuler => Ok(receiver.receive(SymplecticEuler::default().stepper(y0))),
        Stepping::StormerVerlet => Ok(receiver.receive(StormerVerlet::default().stepper(y0))),
        Stepping::Composition { table, base } => match base.stepper {
            BaseStepper::StormerVerlet => Ok(receiver.receive(Composition::new(
                table,
                StormerVerlet::default().stepper(y0),
            ))),
            BaseStepper::Lgvi
            | BaseStepper::PrincipalAxisSplitting
            | BaseStepper::ExactSplitting
            | BaseStepper::Gauss2 => NoStepper::of(method, ProblemKind::Separable),
        },
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::Strang
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::Separable),
    }
}

/// Builds `method`'s stepper for a system `P` split into parts with known flows and hands it
/// to `receiver`.
///
/// # Errors
/// [`NoStepper`] when the method is not a splitting of given flows.
pub fn split<P, S, R>(method: &MethodInfo, receiver: R) -> Result<R::Output, NoStepper>
where
    P: SplitOde<S> + ?Sized,
    S: State,
    R: Receive<P, S>,
{
    match method.stepping {
        Stepping::Strang => Ok(receiver.receive(SplittingStepper::new(Splitting::Strang))),
        Stepping::Explicit(_)
        | Stepping::Gauss(_)
        | Stepping::SymplecticEuler
        | Stepping::StormerVerlet
        | Stepping::Composition { .. }
        | Stepping::Lgvi
        | Stepping::LieGauss(_)
        | Stepping::Rkmk4
        | Stepping::Cg3
        | Stepping::PrincipalAxisSplitting
        | Stepping::ExactSplitting
        | Stepping::Dmv
        | Stepping::ExactFlow
        | Stepping::Taylor(_)
        | Stepping::TaylorDoubleDouble => NoStepper::of(method, ProblemKind::Split),
    }
}

/// An explicit method of any table size on an ODE: adaptive with an error estimator,
/// interpolating fixed steps without.
struct ExplicitOde<'a, P, Y, R> {
    y0: &'a Y,
    receiver: R,
    problem: PhantomData<fn(&P)>,
}

impl<P: Ode<Y>, Y: VectorState, R: ReceiveOde<P, Y>> ExplicitVisitor for ExplicitOde<'_, P, Y, R> {
    type Output = R::Output;
    fn visit<const S: usize>(self, method: ExplicitRungeKutta<S>) -> R::Output {
        let stepper = method.stepper(self.y0);
        if method.table.error == crate::tables::ErrorEstimator::None {
            self.receiver.interpolating(stepper)
        } else {
            self.receiver.adaptive(stepper)
        }
    }
}

/// Gauss–Legendre collocation of any number of stages on an ODE.
struct GaussOde<'a, P, Y, R> {
    y0: &'a Y,
    receiver: R,
    problem: PhantomData<fn(&P)>,
}

impl<P: Ode<Y>, Y: VectorState, R: ReceiveOde<P, Y>> GaussVisitor for GaussOde<'_, P, Y, R> {
    type Output = R::Output;
    fn visit<const S: usize>(self, table: &'static GaussTableau<S>) -> R::Output {
        self.receiver
            .interpolating(Gauss::new(table).stepper(self.y0))
    }
}

/// Variational Lie–Gauss of any number of stages on a rigid body.
struct LieGaussRigid<B: ?Sized, R> {
    receiver: R,
    problem: PhantomData<fn(&B)>,
}

impl<B: RigidBody + ?Sized, R: Receive<B, RigidBodyState>> GaussVisitor for LieGaussRigid<B, R> {
    type Output = R::Output;
    fn visit<const S: usize>(self, table: &'static GaussTableau<S>) -> R::Output {
        self.receiver.receive(LieGauss::new(table))
    }
}

/// Variational Lie–Gauss of any number of stages on a coupled rigid body.
struct LieGaussCoupled<L: ?Sized, R, const N: usize> {
    receiver: R,
    problem: PhantomData<fn(&L)>,
}

impl<L, R, const N: usize> GaussVisitor for LieGaussCoupled<L, R, N>
where
    L: CoupledLagrangian<N> + ?Sized,
    R: Receive<L, CoupledState<N>>,
{
    type Output = R::Output;
    fn visit<const S: usize>(self, table: &'static GaussTableau<S>) -> R::Output {
        self.receiver.receive(CoupledLieGauss::<S, N>::new(table))
    }
}
