//! Kinematics of a rigid body: SO(3), Euler angles, angular velocity, rotating frames.
#![allow(missing_docs)]
pub mod so3;
