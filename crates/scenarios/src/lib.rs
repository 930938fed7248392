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
//!
//! ## Example
//!
//! The spinning hoop run with its default integrator: while the bead moves, the hoop's spin
//! `φ̇` changes so that `L_z = (M a²/2 + m a² sin²α) φ̇` keeps its initial value (the scene's
//! defaults are `M = 1 kg`, `m = 0.2 kg`, `a = 0.4 m`, `φ̇₀ = 5 rad/s`, `α₀ = 3.1 rad`).
//!
//! ```
//! use tumble_scenarios::scene::Rows;
//! use tumble_scenarios::{RunOptions, scenes};
//!
//! let scene = scenes::find("spinning-hoop")?;
//! let params = scene.info().default_params();
//! let options = RunOptions { t_end: Some(2.0), ..RunOptions::default() };
//! let mut rows = Rows::default();
//! let summary = scene.run(&params, &options, &mut rows)?;
//!
//! let columns = scene.info().columns();
//! let at = |name: &str| columns.iter().position(|c| c == name).unwrap();
//! let (alpha, phi_dot) = (at("alpha"), at("phi_dot"));
//! let lz = |alpha: f64, phi_dot: f64| (0.5 * 0.16 + 0.2 * 0.16 * alpha.sin().powi(2)) * phi_dot;
//! let lz0 = lz(3.1, 5.0);
//! for row in &rows.0 {
//!     assert!((lz(row[alpha], row[phi_dot]) - lz0).abs() < 1e-12 * lz0);
//! }
//! assert_eq!(summary.t, 2.0);
//! assert!(summary.max_energy_rel_err < 1e-12);
//! # Ok::<(), tumble_scenarios::SceneError>(())
//! ```

mod applicability;
pub mod body_table;
pub mod dispatch;
pub mod display;
pub mod drawing;
pub mod error;
pub mod lagrangian;
pub mod params;
pub mod recommendation;
pub mod resolution;
pub mod scene;
pub mod scene_file;
pub mod scenes;
pub mod toml_file;

pub use error::{ModelError, SceneError};
pub use lagrangian::{EulerLagrange, Lagrangian, LagrangianOde};
pub use params::{Domain, ParamSpec, Params};
pub use recommendation::Measure;
pub use resolution::StepResolution;
pub use scene::{
    DenseRows, DtAndTol, Guide, Observe, Recommendation, Recorder, RunOptions, RunPlan, RunSummary,
    Scene, SceneInfo, StepControl,
};
