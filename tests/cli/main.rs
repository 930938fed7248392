//! Tests of the `tumble` binary: one module per subcommand, each running the built binary.

mod animate;
mod body_scenes;
mod hard_cases;
mod hostile;
mod inertia;
mod inertia_sources;
mod interrupts;
mod outputs_and_limits;
mod plot;
mod refine;
mod scenes;
mod simulate;
mod slurm;
mod special_files;
mod support;
mod sweep;
mod sweep_diff;
mod view;
mod work_precision;
