//! Integration tests of `tumble-inertia`: one binary, one module per feature.
//!
//! Convergence tests print their observed rates (run with `--nocapture` to see them).

mod common;
mod euler;
mod fuzz;
mod mesh_integrals;
mod operations;
mod primitives;
mod principal;
mod t_handle;
mod torus;
mod validation;
