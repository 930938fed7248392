//! `tumble sweep`: run a parameter sweep (a TOML sweep file, or the built-in hoop-tilt map)
//! in parallel into an output folder; `tumble sweep merge` joins the folders of a sharded
//! sweep; `tumble sweep slurm` writes the job script that runs a sharded sweep on a Slurm
//! cluster ([`slurm`]).
//!
//! Two stages, as everywhere in the CLI: the file and the `--set` overrides become a validated
//! [`SweepDefinition`] (every error names the key and its line, or the override) and the
//! flags are checked before any point runs; then the library runs the points, appending each
//! row to the folder's journal as it finishes, while a progress bar shows the count and an
//! ETA when stderr is a terminal, and otherwise (a batch log) a line every `--progress-every`
//! seconds does.
//!
//! Output folder: `sweep.toml` (the resolved definition), `journal.csv` (the resumable
//! state) and `compute.csv` (a line per run on the folder) from the start; at the end `results.csv` (one row per point in index order),
//! the map (`tilt-map.png`/`.svg` for a tilt metric, `<metric>-map.*` otherwise; a grid of
//! two axes) and its slices (`tilt-slices.png`/`.svg`: the metric against the first axis for
//! a few values of the second; one-axis grids get this plot alone), then `manifest.json`.
//! Each is written beside its destination and renamed when complete. A shard writes its own
//! `results.csv` and manifest but no plots (its map has holes); `merge` writes them all.
//!
//! Exit status: 0 when every point is ok; 3 when the sweep finished but some points failed
//! (their rows say why); 1 for any error (nothing to run, a folder that holds another
//! sweep, an unwritable output).

mod estimate;
mod finish;
mod progress;
pub mod slurm;

use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Duration;

use finish::finish;

use anyhow::{Result, bail};
use tumble_studies::sweep::{
    self, CheckSize, Metric, Override, OverrideValue, Progress, RunConfig, Shard, SweepDefinition,
    SweepReport,
};

use tumble_output::table::Format;

use super::args::{parse_angle, parse_set};
use crate::manifest;
use crate::output;
use crate::signals;
use tumble_plot as plot;
use tumble_studies::simulation::{self, Naming};
use tumble_studies::sweep::record::SweepRecord;

/// Flags of `tumble sweep`.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    /// `merge DIR...`: join the folders of a sharded sweep; `slurm SWEEP.toml --shards N`:
    /// a Slurm job script for it.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// A sweep file (TOML); without one, the built-in hoop-tilt map on `free-hoop`.
    #[arg(value_name = "SWEEP.toml")]
    pub file: Option<PathBuf>,
    /// Override a key of the sweep: a scene parameter (`g=0`, `theta0=pi/3`), `run.dt`,
    /// `run.tol`, `run.t_end`, `metrics.tilt_threshold`, `random.samples`, `random.seed`,
    /// `axes.NAME.count`, `axes.NAME.start`, `axes.NAME.end`, `axes.NAME.spacing`,
    /// `axes.NAME.values`, `run.integrator`, `metrics.tolerance`, `refine.levels`,
    /// `refine.metric`, `refine.threshold`. Repeat for several.
    #[arg(
        long = "set",
        value_name = "KEY=VALUE",
        allow_hyphen_values = true,
        action = clap::ArgAction::Append
    )]
    pub set: Vec<String>,
    /// Refine the grid adaptively: start from every 2^LEVELS-th value of each axis and split,
    /// level by level, the cells where the sweep's `[refine]` metric changes by more than its
    /// threshold, down to the grid's own resolution (the same as `--set refine.levels=LEVELS`;
    /// 0: every point of the grid).
    #[arg(long, value_name = "LEVELS", allow_negative_numbers = true)]
    pub refine: Option<i64>,
    /// Output folder [default: out/tilt-map, or out/NAME for a file NAME.sweep.toml].
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Worker threads [default: the number of cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Continue the sweep in the output folder, skipping finished points (starts it when the
    /// folder holds none).
    #[arg(long)]
    pub resume: bool,
    /// Take over the output folder's lock even if another tumble process seems to hold it
    /// (a lock left by a dead process on this host is taken over without it).
    #[arg(long = "break-lock")]
    pub break_lock: bool,
    /// Run only the K-th of N deterministic parts (points with index mod N = K − 1), for
    /// job arrays; join the parts with `tumble sweep merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// The self-check: re-run N spread-out points (the grid's corners included) at half the
    /// step (or a tolerance 100 times tighter) and report the largest change of each metric;
    /// `auto` is max(8, 1 %) of the points, `off` skips it. A whole sweep (or a merge) runs it;
    /// a shard does not.
    #[arg(long, value_name = "N|auto|off", default_value = "auto")]
    pub check: String,
    /// Largest change of a metric under the self-check accepted as converged; above it the
    /// summary warns and the exit status is 4 [default: the sweep file's `metrics.tolerance`,
    /// else 1e-6].
    #[arg(
        long = "check-tolerance",
        value_name = "TOL",
        allow_negative_numbers = true
    )]
    pub check_tolerance: Option<f64>,
    /// When stderr is not a terminal (a batch job's log), write a progress line (points done,
    /// points per second, ETA) every this many seconds; 0 writes none. On a terminal a
    /// progress bar shows the same.
    #[arg(
        long = "progress-every",
        value_name = "SECONDS",
        default_value_t = 30.0
    )]
    pub progress_every: f64,
    /// The limits every point of the sweep runs under.
    #[command(flatten)]
    pub limits: PointLimits,
    /// Size, font size, resolution and SVG text of the folder's figures.
    #[command(flatten)]
    pub figure: super::args::FigureArgs,
    /// `parquet`: also write the results as `results.parquet` (typed columns, null where a
    /// metric is undefined, the manifest in the file's key-value metadata under `tumble`);
    /// `results.csv` is written either way.
    #[arg(long, value_name = "csv|parquet", default_value = "csv", value_parser = parse_format)]
    pub format: Format,
}

/// Parses `--format`.
fn parse_format(raw: &str) -> Result<Format> {
    Format::parse(raw)
        .ok_or_else(|| anyhow::anyhow!("`{raw}` is not a format: give csv or parquet"))
}

/// The Parquet copy of `results.csv` that `--format parquet` writes.
pub const RESULTS_PARQUET: &str = "results.parquet";

/// The checks on a sweep's points that `tumble sweep` and the shards of `tumble sweep slurm`
/// share.
#[derive(clap::Args, Debug)]
pub struct PointLimits {
    /// Run even when the fixed step turns the fastest initial rotation of some point by more
    /// than 0.5 rad a step (such a sweep is refused otherwise; the corners of the axes, where
    /// the rates are largest, are checked).
    #[arg(long = "allow-coarse-step")]
    pub allow_coarse_step: bool,
    /// Fail a point whose run takes longer than this many seconds of wall time (status
    /// `failed`, a time-limit reason in its row) and go on with the others. Whether a point
    /// reaches the limit depends on the machine and its load.
    #[arg(
        long = "point-seconds",
        value_name = "S",
        allow_negative_numbers = true
    )]
    pub point_seconds: Option<f64>,
}

impl PointLimits {
    /// Checks `def` against the limits (the step's resolution unless allowed, a valid time
    /// limit) and returns the time limit.
    fn check(&self, def: &SweepDefinition) -> Result<Option<f64>> {
        if !self.allow_coarse_step {
            check_resolution(def)?;
        }
        if let Some(seconds) = self.point_seconds {
            check_point_seconds(seconds)?;
        }
        Ok(self.point_seconds)
    }
}

/// The period of progress lines: `None` for 0.
fn progress_period(seconds: f64) -> Result<Option<Duration>> {
    if seconds == 0.0 {
        return Ok(None);
    }
    match Duration::try_from_secs_f64(seconds) {
        Ok(d) if d >= Duration::from_millis(10) => Ok(Some(d)),
        _ => bail!(
            "--progress-every {seconds}: expected a number of seconds, at least 0.01 (0 for no \
             progress lines)"
        ),
    }
}

/// Subcommands of `tumble sweep`.
#[derive(clap::Subcommand, Debug)]
pub enum Command {
    /// Join the output folders of the N shards of a sweep into the folder an unsharded run
    /// writes
    Merge(MergeArgs),
    /// Compare two sweeps of the same grid: the largest difference of each metric, and where
    Diff(super::sweep_diff::DiffArgs),
    /// Write a Slurm job script: a job array of N resumable shards and a merge job after
    /// all of them
    Slurm(slurm::SlurmArgs),
}

/// Flags of `tumble sweep merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard folders (each written by `tumble sweep --shard K/N`).
    #[arg(value_name = "DIR", required = true)]
    pub dirs: Vec<PathBuf>,
    /// Output folder [default: out/merged].
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// As for `tumble sweep`.
    #[arg(long = "break-lock")]
    pub break_lock: bool,
    /// The self-check of the merged sweep (as for `tumble sweep`).
    #[arg(long, value_name = "N|auto|off", default_value = "auto")]
    pub check: String,
    /// As for `tumble sweep`.
    #[arg(
        long = "check-tolerance",
        value_name = "TOL",
        allow_negative_numbers = true
    )]
    pub check_tolerance: Option<f64>,
    /// Size, font size, resolution and SVG text of the folder's figures.
    #[command(flatten)]
    pub figure: super::args::FigureArgs,
}

/// The sweep finished but some points failed: exit status 3.
#[derive(Debug)]
pub struct PointsFailed {
    /// Failed points.
    pub failed: usize,
    /// All points.
    pub total: u64,
    /// Where the results are.
    pub results: PathBuf,
}

impl fmt::Display for PointsFailed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} of {} points failed (status and reason in {})",
            self.failed,
            self.total,
            self.results.display()
        )
    }
}

impl std::error::Error for PointsFailed {}

/// The sweep finished, but its self-check found a metric that changed by more than the
/// tolerance at the tighter setting: exit status 4.
#[derive(Debug)]
pub struct NotConverged {
    /// The largest change.
    pub largest: f64,
    /// The tolerance.
    pub tolerance: f64,
}

impl fmt::Display for NotConverged {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the self-check changed a metric by {:.2e}, more than the tolerance {:.1e} (or a \
             point's status or a metric's definedness changed): the sweep's setting does not \
             resolve its metrics; see manifest.json's self_check and use a smaller step or \
             tolerance",
            self.largest, self.tolerance
        )
    }
}

impl std::error::Error for NotConverged {}

impl NotConverged {
    /// The exit status that says the metrics did not pass the self-check.
    pub const EXIT_CODE: u8 = 4;
}

/// The self-check settings of `sweep` and `merge`.
#[derive(Debug, Clone, Copy)]
struct CheckSettings {
    size: CheckSize,
    /// `--check-tolerance`, if given.
    tolerance: Option<f64>,
    threads: usize,
}

/// The self-check's tolerance when neither `--check-tolerance` nor `metrics.tolerance` is
/// given.
const DEFAULT_CHECK_TOLERANCE: f64 = 1e-6;

impl CheckSettings {
    /// The tolerance for `def`: the flag, else the sweep file's, else the default.
    fn tolerance(&self, def: &SweepDefinition) -> f64 {
        self.tolerance
            .or(def.check_tolerance)
            .unwrap_or(DEFAULT_CHECK_TOLERANCE)
    }

    fn parse(raw: &str, tolerance: Option<f64>, threads: usize) -> Result<Self> {
        let size = match raw.trim() {
            "auto" => CheckSize::Auto,
            "off" => CheckSize::Off,
            n => match n.parse::<u64>() {
                Ok(0) => CheckSize::Off,
                Ok(n) => CheckSize::Points(n),
                Err(_) => bail!("--check {raw}: expected a number of points, `auto` or `off`"),
            },
        };
        if let Some(t) = tolerance
            && !(t.is_finite() && t > 0.0)
        {
            bail!("--check-tolerance {t}: must be finite and positive");
        }
        Ok(Self {
            size,
            tolerance,
            threads,
        })
    }
}

impl PointsFailed {
    /// The exit status that says some points failed.
    pub const EXIT_CODE: u8 = 3;
}

/// Parses one `--set KEY=VALUE`.
fn parse_override(raw: &str) -> Result<Override> {
    let Some((key, text)) = raw.split_once('=') else {
        bail!("--set {raw}: expected KEY=VALUE, e.g. --set run.dt=0.005 or --set theta0=pi/3");
    };
    let key = key.trim();
    let text = text.trim();
    let value = if Override::takes_text(key) {
        if text.is_empty() {
            bail!("--set {raw}: the value is empty");
        }
        OverrideValue::Text(text.to_string())
    } else if Override::takes_list(key) {
        let Some(inner) = text.strip_prefix('[').and_then(|t| t.strip_suffix(']')) else {
            bail!("--set {raw}: expected a list such as [0.5, 1, pi/2]");
        };
        let values = inner
            .split(',')
            .map(|v| {
                parse_angle(v)
                    .ok_or_else(|| anyhow::anyhow!("--set {raw}: `{}` is not a number", v.trim()))
            })
            .collect::<Result<Vec<f64>>>()?;
        OverrideValue::List(values)
    } else {
        let (_, x) = parse_set(raw, "run.dt=0.005")?;
        OverrideValue::Number(x)
    };
    Ok(Override {
        key: key.to_string(),
        value,
        text: raw.to_string(),
    })
}

/// The default output folder of a sweep.
fn default_output(file: Option<&Path>) -> PathBuf {
    let name = file
        .and_then(|f| f.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .map(|n| {
            n.trim_end_matches(".toml")
                .trim_end_matches(".sweep")
                .to_string()
        })
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| "tilt-map".to_string());
    Path::new("out").join(name)
}

/// Runs the subcommand.
///
/// # Errors
/// An invalid file, override or flag (before any point runs), a folder that holds another
/// sweep, an unwritable output; [`PointsFailed`] when the sweep finished with failed points.
pub fn run(args: &Args) -> Result<()> {
    match &args.command {
        Some(Command::Merge(m)) => return merge(m),
        Some(Command::Diff(d)) => return super::sweep_diff::run(d),
        Some(Command::Slurm(s)) => return slurm::run(s),
        None => {}
    }
    let figure_options = args.figure.options()?;
    // Stage one: everything validated.
    let mut overrides = args
        .set
        .iter()
        .map(|s| parse_override(s))
        .collect::<Result<Vec<_>>>()?;
    super::args::refuse_repeated_keys(
        overrides
            .iter()
            .zip(&args.set)
            .map(|(o, raw)| (o.key.as_str(), raw.as_str())),
    )?;
    if let Some(levels) = args.refine {
        if levels < 0 {
            bail!("--refine {levels}: expected a whole number of levels, 0 (none) or more");
        }
        overrides.push(Override {
            key: "refine.levels".into(),
            value: OverrideValue::Number(levels as f64),
            text: format!("refine.levels={levels} (--refine {levels})"),
        });
    }
    let mut def = match &args.file {
        Some(path) => SweepDefinition::load(path, &overrides)?,
        None => SweepDefinition::tilt_map(&overrides)?,
    };
    if let Some(seconds) = args.limits.check(&def)? {
        // Every run of a point (the self-check's included) gets the limit; it is not part of
        // the definition, so a folder resumes whatever the limit.
        def.plan = def.plan.with_deadline(seconds);
    }
    let threads = match args.threads {
        Some(0) => bail!("--threads 0: at least one worker thread is needed"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    let shard = match &args.shard {
        Some(spec) => Shard::parse(spec)?,
        None => Shard::ALL,
    };
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| default_output(args.file.as_deref()));

    let every = progress_period(args.progress_every)?;
    output::check_folder(&dir, &folder_files(&def))?;
    let check = CheckSettings::parse(&args.check, args.check_tolerance, threads)?;
    let _lock = output::lock_folder(&dir, args.break_lock)?;

    // Stage two: the points (a large sweep first says how long it will take).
    let mut interruptible = def.clone();
    interruptible.plan.cancel = Some(tumble_scenarios::scene::CancelFlag(signals::flag()));
    if let Some(e) = estimate::estimate(&interruptible, shard, threads) {
        eprintln!("{}", estimate::line(&e, threads));
    }
    let reporter = progress::Reporter::new(every);
    let mut on_progress = |p: &Progress| reporter.update(p);
    let config = RunConfig {
        threads,
        shard,
        resume: args.resume,
        cancel: Some(signals::flag()),
    };
    // A signal also stops the points under way at their next step; the engine journals none
    // of the points it cut, so --resume computes them again.
    let report = quiet_point_panics(|| sweep::run(&interruptible, &dir, &config, &mut on_progress));
    reporter.finish();
    let report = report?;
    if let Some(code) = signals::interrupted() {
        return Err(signals::Interrupted {
            code,
            message: format!(
                "{} of {} points are in {}; run the same command with --resume to finish",
                report.rows.len(),
                report.total,
                dir.join("journal.csv").display()
            ),
        }
        .into());
    }
    finish(
        &def,
        &dir,
        &report,
        shard,
        ("sweep", args.format),
        check,
        &figure_options,
    )
}

/// Refuses a sweep whose fixed step does not resolve the fastest initial rotation at one of
/// its points ([`simulation::check_sweep_resolution`]).
pub(super) fn check_resolution(def: &SweepDefinition) -> Result<()> {
    Ok(simulation::check_sweep_resolution(def, Naming::Cli)?)
}

/// Refuses a `--point-seconds` that is not a finite, positive number of seconds.
fn check_point_seconds(seconds: f64) -> Result<()> {
    if seconds.is_finite() && seconds > 0.0 {
        Ok(())
    } else {
        bail!("--point-seconds {seconds}: must be a finite, positive number of seconds")
    }
}

/// `tumble sweep merge`.
fn merge(args: &MergeArgs) -> Result<()> {
    let figure_options = args.figure.options()?;
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| Path::new("out").join("merged"));
    output::check_folder(
        &out,
        &[
            "results.csv".to_string(),
            "manifest.json".to_string(),
            sweep::COMPUTE.to_string(),
        ],
    )?;
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    let check = CheckSettings::parse(&args.check, args.check_tolerance, threads)?;
    let _lock = output::lock_folder(&out, args.break_lock)?;
    let (def, report) = sweep::merge(&args.dirs, &out)?;
    finish(
        &def,
        &out,
        &report,
        Shard::ALL,
        ("merge", Format::Csv),
        check,
        &figure_options,
    )
}

fn seconds(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s < 1.0 {
        format!("{:.1} ms", 1e3 * s)
    } else {
        format!("{s:.3} s")
    }
}

/// Runs `f` with panics of the sweep's worker threads kept off stderr (the library records
/// each in its point's row); other threads' panics are reported as usual.
fn quiet_point_panics<T>(f: impl FnOnce() -> T) -> T {
    let previous = std::sync::Arc::new(std::panic::take_hook());
    let hook = std::sync::Arc::clone(&previous);
    std::panic::set_hook(Box::new(move |info| {
        let worker = std::thread::current()
            .name()
            .is_some_and(|n| n.starts_with("tumble-sweep-"));
        if !worker {
            hook(info);
        }
    }));
    let out = f();
    let _ = std::panic::take_hook();
    if let Ok(previous) = std::sync::Arc::try_unwrap(previous) {
        std::panic::set_hook(previous);
    }
    out
}

/// The files a sweep writes into its folder (besides its journal), checked before it runs.
fn folder_files(def: &SweepDefinition) -> Vec<String> {
    let mut names = vec![
        "results.csv".to_string(),
        "manifest.json".to_string(),
        RESULTS_PARQUET.to_string(),
        sweep::COMPUTE.to_string(),
    ];
    if let Some(metric) = def.metrics.first() {
        let stem = plot::sweep::plot_stem(metric);
        for kind in ["map", "slices"] {
            for ext in ["png", "svg"] {
                names.push(format!("{stem}-{kind}.{ext}"));
            }
        }
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_parse_angles_and_reject_junk() {
        let o = parse_override("theta0=pi/3").unwrap();
        assert_eq!(o.key, "theta0");
        assert_eq!(o.value, OverrideValue::Number(std::f64::consts::PI / 3.0));
        assert_eq!(
            parse_override("run.integrator=dop853").unwrap().value,
            OverrideValue::Text("dop853".into())
        );
        assert_eq!(
            parse_override("axes.alpha0.values=[0.5, pi/2]")
                .unwrap()
                .value,
            OverrideValue::List(vec![0.5, std::f64::consts::FRAC_PI_2])
        );
        assert!(parse_override("axes.alpha0.values=0.5").is_err());
        assert!(parse_override("axes.alpha0.values=[0.5, x]").is_err());
        assert!(parse_override("run.dt").is_err());
        assert!(parse_override("=1").is_err());
        assert!(parse_override("g=heavy").is_err());
    }

    #[test]
    fn default_folders_are_named_after_the_file() {
        assert_eq!(default_output(None), Path::new("out/tilt-map"));
        assert_eq!(
            default_output(Some(Path::new("scenes/flips.sweep.toml"))),
            Path::new("out/flips")
        );
        assert_eq!(
            default_output(Some(Path::new("a/b.toml"))),
            Path::new("out/b")
        );
    }
}
