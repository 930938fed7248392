//! One module per subcommand: each has its clap `Args` and a `run` returning `anyhow::Result`.

pub mod animate;
pub mod args;
pub mod hard_cases;
pub mod inertia;
pub mod integrators;
pub mod kinematics;
pub mod models;
pub mod plot;
pub mod scenes;
pub mod simulate;
pub mod sweep;
pub mod sweep_diff;
pub mod view;
pub mod work_precision;
