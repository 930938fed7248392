//! # tumble-studies
//!
//! Studies built on tumble's scenes: what a researcher runs *many* simulations for.
//!
//! * [`sweep`] — a scene run at every point of a grid (or random samples) of its parameters, in
//!   parallel (rayon), each point reduced to metrics while it integrates (nothing stored per
//!   step), written to a resumable journal, shardable across machines and merged back into the
//!   same `results.csv` as one run.
//! * [`hard_cases`] — a named battery of situations that break integrators and the atlas of
//!   every method on each, at settings chosen by one stated rule.
//! * [`work_precision`] — the error at the final time against the cost of getting it: ladders
//!   of steps or tolerances per integrator, a reference solution with its cross-check, fitted
//!   orders, and long runs for energy drift.
//!
//! ## Design choices
//!
//! * **Plans, not options.** A sweep definition holds the [`tumble_scenarios::RunPlan`] that
//!   [`tumble_scenarios::RunOptions::resolve`] validated once; every point runs it through
//!   [`tumble_scenarios::Scene::simulate`]. A work–precision ladder validates its integrator's
//!   plan once and derives each rung's step from it ([`tumble_scenarios::RunPlan::with_step`]).
//! * **Scene knowledge stays in the scenes.** A metric that needs a body's intermediate axis
//!   asks the scene ([`tumble_scenarios::Scene::intermediate_axis`]); the guides drawn over a
//!   map (critical spins, relative equilibria) are the scene's
//!   ([`tumble_scenarios::Scene::map_guides`]). No scene is named here.
//! * **Files appear whole.** Everything written to a study's folder goes through
//!   [`tumble_output::Destination`]; the journal is append-only and checked on resume.
//! * **The library never prints**: progress is a callback, failures are typed errors
//!   ([`sweep::SweepError`], [`tumble_scenarios::SceneError`]).
//!
//! ## Example
//!
//! A sweep defined by the same TOML as a sweep file, validated whole before anything runs;
//! one point computed without a folder. Every point is a pure function of its index.
//!
//! ```
//! use tumble_studies::sweep::{Status, SweepDefinition, run_point};
//!
//! let sweep = SweepDefinition::parse(
//!     r#"
//!     scene = "free-hoop"
//!     [run]
//!     t_end = 2.0
//!     [[axes]]
//!     parameter = "omega0"
//!     range = [1.0, 6.0]
//!     count = 3
//!     [metrics]
//!     record = ["max_tilt", "max_energy_rel_err"]
//!     "#,
//!     "example",
//!     &[],
//! )?;
//! assert_eq!(sweep.points(), 3);
//! let row = run_point(&sweep, 1);
//! assert_eq!(row.status, Status::Ok);
//! assert_eq!(row.values, vec![3.5]);
//! let energy_error = row.metrics[1].unwrap();
//! assert!(energy_error < 1e-9);
//! assert_eq!(run_point(&sweep, 1), row); // deterministic to the bit
//!
//! // A misspelt key is refused with its line.
//! let bad = SweepDefinition::parse("scene = \"free-hoop\"\n[run]\nt_edn = 2.0\n", "bad.toml", &[]);
//! assert!(bad.unwrap_err().to_string().contains("t_edn"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod catalog;
pub mod error_estimate;
pub mod hard_cases;
pub mod models;
pub mod record;
pub mod simulation;
pub mod sweep;
pub mod work_precision;
