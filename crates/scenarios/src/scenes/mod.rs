//! Built-in scenes: each documents its coordinates, parameters, conserved quantities and the
//! oracle its tests use.

pub mod hoop;
