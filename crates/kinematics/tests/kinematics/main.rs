//! Integration tests of tumble-kinematics: one module per feature, each test named after what it
//! proves. Oracles are independent of the code under test: nalgebra's own axis-angle rotations,
//! dual-number derivatives of rotation matrices, closed forms from the lecture notes.

mod support;

mod angular_velocity;
mod automatic_differentiation;
mod euler_angles;
mod rotating_frames;
mod so3;
