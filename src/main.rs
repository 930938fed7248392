//! The `tumble` command line: parses flags, builds validated objects from them, calls the
//! library crates and maps errors to a message on stderr and a non-zero exit code.

mod animation;
mod cmd;
mod manifest;
mod output;
mod provenance;
mod signals;
mod view;

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

/// The version and the git commit the binary was built from.
const VERSION: &str = concat!(
    env!("CARGO_PKG_VERSION"),
    " (commit ",
    env!("TUMBLE_GIT_COMMIT"),
    ")"
);

/// tumble: high-accuracy rigid-body dynamics.
#[derive(Parser, Debug)]
#[command(name = "tumble", version = VERSION, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// A scene in motion as an animated GIF (or MP4 with ffmpeg): a 3D view of the body with a trail
    Animate(cmd::animate::Args),
    /// The atlas of every integrator on a battery of cases that break integrators
    HardCases(cmd::hard_cases::Args),
    /// Mass properties of a body: mesh files (OBJ or STL), point masses and primitives
    Inertia(cmd::inertia::Args),
    /// List every integrator: name, order, family, properties
    Integrators(cmd::integrators::Args),
    /// Angular velocity from Euler angles and rates, in the space and body frames
    Kinematics(cmd::kinematics::Args),
    /// Redraw a saved result (a simulate CSV, a sweep or work–precision folder) as PNG, SVG or
    /// PDF without recomputing it
    Plot(cmd::plot::Args),
    /// List the model files of a directory (models/ by default): coordinates, parameters,
    /// defaults, integrators
    Models(cmd::models::Args),
    /// List the built-in scenes: coordinates, parameters, defaults, integrators
    Scenes(cmd::scenes::Args),
    /// Run a scene (built-in, scene file or model file) and write its trajectory as CSV,
    /// optionally a plot
    Simulate(cmd::simulate::Args),
    /// Run a parameter sweep in parallel (a TOML sweep file, or the built-in hoop-tilt map)
    Sweep(cmd::sweep::Args),
    /// A run, or with --inertia a body's principal axes, as a self-contained interactive 3D
    /// page (HTML, no network needed)
    View(cmd::view::Args),
    /// Speed against error: every integrator's error at the final time against wall time and
    /// evaluations (or, with --long, its energy error over a million steps)
    WorkPrecision(cmd::work_precision::Args),
}

/// Ends the process quietly when standard output was closed by its reader (`tumble scenes |
/// head`): the reader took what it wanted, which is not an error. Report commands print with
/// `println!`, which panics on a failed write; every other panic keeps the default report.
fn quiet_on_closed_stdout() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("os error 32") {
            std::process::exit(0);
        }
        default(info);
    }));
}

fn main() -> ExitCode {
    quiet_on_closed_stdout();
    // The matches are kept for `inertia` and `view --inertia`, whose placement flags belong to the `--shape` they
    // follow.
    let matches = Cli::command().get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = match cli.command {
        Command::Animate(args) => cmd::animate::run(&args),
        Command::HardCases(args) => cmd::hard_cases::run(&args),
        Command::Inertia(args) => cmd::inertia::run(&args, matches.subcommand_matches("inertia")),
        Command::Integrators(args) => cmd::integrators::run(&args),
        Command::Kinematics(args) => cmd::kinematics::run(&args),
        Command::Plot(args) => cmd::plot::run(&args),
        Command::Models(args) => cmd::models::run(&args),
        Command::Scenes(args) => cmd::scenes::run(&args),
        Command::Simulate(args) => cmd::simulate::run(&args),
        Command::Sweep(args) => cmd::sweep::run(&args),
        Command::View(args) => cmd::view::run(&args, matches.subcommand_matches("view")),
        Command::WorkPrecision(args) => cmd::work_precision::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if let Some(i) = e.downcast_ref::<signals::Interrupted>() {
                ExitCode::from(i.code)
            } else if e.is::<cmd::sweep::PointsFailed>() {
                ExitCode::from(cmd::sweep::PointsFailed::EXIT_CODE)
            } else if e.is::<cmd::hard_cases::Unfinished>() {
                ExitCode::from(cmd::hard_cases::Unfinished::EXIT_CODE)
            } else if e.is::<cmd::sweep::NotConverged>() {
                ExitCode::from(cmd::sweep::NotConverged::EXIT_CODE)
            } else if e.is::<cmd::sweep_diff::Differ>() {
                ExitCode::from(cmd::sweep_diff::Differ::EXIT_CODE)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
