//! Methods made for rotating bodies, and the exact free-rigid-body flow that measures them.
//!
//! * [`exact`]: the exact solution of the torque-free rigid body (Jacobi elliptic functions and
//!   an elliptic integral of the third kind), used as the reference solution and as a sub-flow
//!   of splitting methods.

pub mod exact;

pub use exact::{ExactFlow, FreeRigidBody};
