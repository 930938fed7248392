//! # tumble-scenarios
//!
//! Where a physical scene becomes the smallest model it needs.
//!
//! "The article" in these docs is Andy Rundquist's blog post "Rigid bodies, formulation and
//! examples" (Euler angles ZYZ, the bead on a driven, spinning and free hoop); "the lecture" is
//! Harvard Physics 151, lecture 9, "Rigid Body Motion". The repository's `docs/design.md`
//! summarizes what the code takes from them.
//!
//! ## Design choices
//!
//! * **Lagrangians by automatic differentiation.** A model is a Lagrangian `L = T − V` written
//!   once, generic over the scalar; [`lagrangian::EulerLagrange`] forms the mass matrix, forces,
//!   accelerations, momenta and energy by forward-mode AD (`num-dual`). Kinetic energies are
//!   built as the article builds them: `½ ω·(I ω)` with the inertia tensor in the body frame and
//!   `ω` from the generalized coordinates through `tumble-kinematics`.
//! * **Hand-written right-hand sides where speed matters.** Scenes that sweeps run millions of
//!   times also have an `f64` right-hand side that allocates nothing; each is tested against its
//!   AD twin.
//! * **Model only what a scene needs.** The driven hoop has one coordinate, the spinning hoop
//!   two; neither carries an orientation.
//! * **Errors, not NaN.** Coordinate singularities (an ill-conditioned mass matrix) and bad
//!   parameters are [`ModelError`]s carrying what and where. The library never prints.

mod applicability;
pub mod body_table;
pub mod dispatch;
pub mod error;
pub mod lagrangian;
pub mod params;
pub mod resolution;
pub mod scene;
pub mod scene_file;
pub mod scenes;
pub mod toml_file;

pub use error::{ModelError, SceneError};
pub use lagrangian::{EulerLagrange, Lagrangian, LagrangianOde};
pub use params::{Domain, ParamSpec, Params};
pub use resolution::StepResolution;
pub use scene::{
    DenseRows, Guide, Observe, Recorder, RunOptions, RunPlan, RunSummary, Scene, SceneInfo,
    StepControl,
};
