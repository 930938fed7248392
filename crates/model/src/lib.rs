//! # tumble-model
//!
//! Models written as text: a TOML file declares parameters, generalized coordinates,
//! orientations (Euler angles of any convention, chains of rotations about fixed axes), rigid
//! bodies, point masses, a potential and gravity; the kinetic energy is assembled by the
//! article's recipe and the equations of motion follow symbolically.

pub mod drawing;
pub mod expr;
pub mod file;
pub mod group;
pub mod mechanics;
pub mod scene;
pub mod taylor;
pub mod units;

pub use file::{Model, ModelFileError};
pub use scene::{
    Evaluation, ModelProduct, ModelScene, from_text, is_model_file, is_model_text, load,
};
