//! `tumble simulate`: run a built-in scene or a scene file and write its trajectory as CSV, with
//! an optional plot.
//!
//! Two stages, as everywhere in the CLI: the flags are turned into a validated scene, parameter
//! set and run options (scene file first, then `--set` and the run flags over it, then the
//! scene's own validation) before any output file is created or any step is taken; then the
//! scene runs, streaming rows to the CSV writer.
//!
//! Output contract (docs/design.md §5): the header is the scene's columns (`t`, coordinates, `_dot`
//! rates, diagnostics); every number is written in the shortest form that reads back to the
//! same `f64` (ryu, through the `csv` crate). Files (`-o`, `--plot`) are written to a temporary
//! file beside the destination and renamed when complete; a failed run leaves neither. A short
//! summary goes to stderr.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use tumble_integrators::Flow;
use tumble_scenarios::StepResolution;
use tumble_scenarios::scene::{CancelFlag, MAX_ANGLE_PER_STEP};
use tumble_scenarios::scene_file::SceneFile;
use tumble_scenarios::scenes;
use tumble_scenarios::{
    ModelError, Params, Recorder, RunOptions, RunPlan, RunSummary, Scene, SceneError, SceneInfo,
    StepControl,
};

use super::args::parse_set;
use crate::manifest;
use crate::output;
use crate::plot;
use crate::provenance::Provenance;
use crate::signals;

/// Flags of `tumble simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene and its parameter overrides.
    #[command(flatten)]
    pub target: SceneArgs,
    /// Integrator (from `tumble integrators`) among those the scene lists as applicable.
    #[arg(long, value_name = "NAME")]
    pub integrator: Option<String>,
    /// Fixed step in seconds (fixed-step integrators).
    #[arg(
        long,
        value_name = "H",
        conflicts_with = "tol",
        allow_negative_numbers = true
    )]
    pub dt: Option<f64>,
    /// Error tolerance, rtol = atol = TOL (adaptive integrators: dp5, dop853).
    #[arg(long, value_name = "TOL", allow_negative_numbers = true)]
    pub tol: Option<f64>,
    /// Horizon in seconds: integrate over [0, T].
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Write every N-th step (the first row is always the initial state, the last the final
    /// state).
    #[arg(
        long,
        value_name = "N",
        conflicts_with_all = ["at", "output_dt"],
        allow_negative_numbers = true
    )]
    pub every: Option<u64>,
    /// Write rows at exactly these times (comma-separated, increasing, in [0, T]), from the
    /// integrator's dense output, and the final state; the steps are the same as without.
    #[arg(
        long,
        value_name = "T1,T2,...",
        conflicts_with = "output_dt",
        allow_hyphen_values = true
    )]
    pub at: Option<String>,
    /// Write rows every DT seconds from 0 (from dense output), and the final state.
    #[arg(long = "output-dt", value_name = "DT", allow_negative_numbers = true)]
    pub output_dt: Option<f64>,
    /// Refuse a run estimated to take more steps than this (fixed steps: t_end/dt), and stop an
    /// adaptive one that reaches it.
    #[arg(long = "max-steps", value_name = "N", default_value_t = 1_000_000_000)]
    pub max_steps: u64,
    /// Warn (on stderr and in the provenance file) when the largest relative energy error of
    /// the run exceeds this: the step does not resolve the motion.
    #[arg(
        long = "energy-warn",
        value_name = "REL",
        default_value_t = 1e-6,
        allow_negative_numbers = true
    )]
    pub energy_warn: f64,
    /// Refuse a run whose CSV is estimated to be larger than this many bytes (suffixes k, M, G).
    #[arg(long = "max-output", value_name = "BYTES", default_value = "10G")]
    pub max_output: String,
    /// Run even when the fixed step turns the initial state's fastest rotation by more than
    /// 0.5 rad a step (a step that does not resolve the motion is refused otherwise).
    #[arg(long = "allow-coarse-step")]
    pub allow_coarse_step: bool,
    /// Write the CSV to FILE instead of stdout (`-` is stdout).
    #[arg(short = 'o', long = "output", value_name = "FILE.csv")]
    pub output: Option<PathBuf>,
    /// Also draw the coordinates, rates and relative energy error against time, as PNG, SVG
    /// or PDF by the file's extension.
    #[arg(long, value_name = "FILE.png|FILE.svg|FILE.pdf")]
    pub plot: Option<PathBuf>,
    #[command(flatten)]
    pub figure: super::args::FigureArgs,
}

/// A scene with its parameters and run options, validated, ready to run.
struct Setup {
    scene: &'static dyn Scene,
    /// `builtin` or the scene file's path.
    origin: String,
    params: Params,
    plan: RunPlan,
    /// The frame a `[body]` scene's rows report, in words (`None`: the scene's own body frame).
    frame: Option<String>,
}

/// Whether SCENE names a file rather than a built-in scene.
fn is_file(arg: &str) -> bool {
    Path::new(arg)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        || Path::new(arg).is_file()
}

/// A scene and its parameter overrides, as `simulate` and `work-precision` take them.
#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    /// A built-in scene (`tumble scenes` lists them) or a TOML scene file (taken as a file if
    /// the argument ends in `.toml` or names an existing file).
    #[arg(value_name = "SCENE")]
    pub scene: String,
    /// Set a parameter of the scene, over its default or the scene file's value; repeat for
    /// several. VALUE is a number or an angle expression such as `pi/2`, `-3pi/4`, `2*pi`.
    #[arg(
        long = "set",
        value_name = "KEY=VALUE",
        allow_hyphen_values = true,
        action = clap::ArgAction::Append
    )]
    pub set: Vec<String>,
}

/// A scene as the command line names it, with its parameters and the file's run options.
pub(crate) struct LoadedScene {
    /// The scene.
    pub scene: &'static dyn Scene,
    /// Where it came from: `builtin` or the scene file's path.
    pub origin: String,
    /// Its parameters: defaults, then the file's values, then `--set`.
    pub params: Params,
    /// The scene file's `[run]` options (none for a built-in scene).
    pub run: RunOptions,
    /// The frame the rows report when the scene file has a `[body]` table.
    pub frame: Option<String>,
}

/// The scene of `target` (built-in name or TOML file) with its `--set` overrides.
pub(crate) fn load_scene(target: &SceneArgs) -> Result<LoadedScene> {
    let (arg, set) = (target.scene.as_str(), target.set.as_slice());
    let (scene, origin, mut params, options, frame) = if is_file(arg) {
        let file = SceneFile::load(Path::new(arg))?;
        (file.scene, file.origin, file.params, file.run, file.frame)
    } else {
        let scene = scenes::find(arg).map_err(|e| match e {
            SceneError::UnknownScene { name, known } => anyhow::anyhow!(
                "unknown scene `{name}` (and no file of that name); built-in scenes: {known}; \
                 a scene file must end in .toml"
            ),
            other => other.into(),
        })?;
        let params = scene.info().default_params();
        (
            scene,
            "builtin".to_string(),
            params,
            RunOptions::default(),
            None,
        )
    };
    for raw in set {
        let (key, value) = parse_set(raw, "omega0=5")?;
        params
            .set(key, value)
            .with_context(|| format!("--set {raw}"))?;
    }
    Ok(LoadedScene {
        scene,
        origin,
        params,
        run: options,
        frame,
    })
}

/// Stage one: the scene, parameters and options from the flags, validated.
fn setup(args: &Args) -> Result<Setup> {
    let LoadedScene {
        scene,
        origin,
        params,
        run: mut options,
        frame,
    } = load_scene(&args.target)?;
    if let Some(name) = &args.integrator {
        options.integrator = Some(name.clone());
    }
    match (args.dt, args.tol) {
        (Some(h), _) => options.step = Some(StepControl::Fixed(h)),
        (None, Some(tol)) => options.step = Some(StepControl::Tolerance(tol)),
        (None, None) => {}
    }
    if args.t_end.is_some() {
        options.t_end = args.t_end;
    }
    if args.every.is_some() {
        options.every = args.every;
        options.at = None;
        options.output_dt = None;
    }
    if let Some(raw) = &args.at {
        options.at = Some(parse_times(raw)?);
        options.output_dt = None;
    }
    if args.output_dt.is_some() {
        options.output_dt = args.output_dt;
        options.at = None;
    }
    options.max_steps = Some(args.max_steps);
    options.cancel = Some(CancelFlag(signals::flag()));
    let plan = options
        .resolve(scene.info())
        .map_err(|e| anyhow::anyhow!("{}: {}", scene.info().name, flag_words(&e)))?;
    check_budget(&plan, scene.info(), args)?;
    if !(args.energy_warn >= 0.0) {
        bail!(
            "--energy-warn {}: must be a relative energy error >= 0",
            number(args.energy_warn)
        );
    }
    if !args.allow_coarse_step {
        check_resolution(scene, &params, &plan)?;
    }
    Ok(Setup {
        scene,
        origin,
        params,
        plan,
        frame,
    })
}

/// Refuses a fixed step that does not resolve the initial state's fastest rotation (the rule
/// of [`StepResolution`], shared with sweeps), with the bound and a step that resolves it.
fn check_resolution(scene: &dyn Scene, params: &Params, plan: &RunPlan) -> Result<()> {
    let info = scene.info();
    let Some(r) = StepResolution::of(scene, params, plan)
        .map_err(|e| anyhow::anyhow!("{}: {e}", info.name))?
    else {
        return Ok(());
    };
    if !r.resolved() {
        bail!(
            "{}: dt = {} does not resolve the initial rotation: {}; give {} (or an adaptive \
             integrator, --integrator dop853), or pass --allow-coarse-step to run anyway",
            info.name,
            number(r.dt),
            rate_words(&r),
            r.suggested_step().map_or_else(
                || "parameters with a finite rate".to_string(),
                |h| format!("--dt {} or smaller", number(h))
            ),
        );
    }
    Ok(())
}

/// `|ω| ≈ R rad/s turns A rad a step, above the bound h·|ω| ≤ 0.5`.
pub(crate) fn rate_words(r: &StepResolution) -> String {
    format!(
        "|ω| ≈ {} rad/s turns {} rad a step, above the bound h·|ω| ≤ {MAX_ANGLE_PER_STEP}",
        significant(r.rate),
        significant(r.angle())
    )
}

/// `x` to three significant digits (in exponent form outside `[1e-3, 1e7)`).
fn significant(x: f64) -> String {
    if (1e-3..1e7).contains(&x.abs()) {
        format!("{}", format!("{x:.2e}").parse::<f64>().unwrap_or(x))
    } else {
        format!("{x:.2e}")
    }
}

/// Parses a byte count with an optional suffix: `1000`, `500k`, `20M`, `10G`.
fn parse_bytes(raw: &str) -> Result<f64> {
    let t = raw.trim();
    let (number, scale) = match t.char_indices().last() {
        Some((i, 'k' | 'K')) => (&t[..i], 1e3),
        Some((i, 'm' | 'M')) => (&t[..i], 1e6),
        Some((i, 'g' | 'G')) => (&t[..i], 1e9),
        Some((i, 't' | 'T')) => (&t[..i], 1e12),
        _ => (t, 1.0),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x * scale),
        _ => bail!("--max-output {raw}: expected a positive number of bytes, e.g. 500M or 10G"),
    }
}

/// The run's work and output estimated from its plan, refused above the budgets before any
/// step: fixed-step runs take `⌈t_end/dt⌉` steps; the CSV holds a row per written step (or per
/// output time) of about 22 bytes a column.
fn check_budget(plan: &RunPlan, info: &SceneInfo, args: &Args) -> Result<()> {
    let max_output = parse_bytes(&args.max_output)?;
    let steps = match plan.step {
        StepControl::Fixed(h) => Some((plan.t_end / h).ceil()),
        StepControl::Tolerance(_) => None,
    };
    if let Some(n) = steps
        && n > args.max_steps as f64
    {
        bail!(
            "{}: about {n:.3e} steps (t_end / dt = {} / {}), more than --max-steps {}; give a \
             larger step, a shorter horizon, or a larger --max-steps",
            info.name,
            number(plan.t_end),
            number(match plan.step {
                StepControl::Fixed(h) => h,
                StepControl::Tolerance(t) => t,
            }),
            args.max_steps
        );
    }
    let rows = match (&plan.times, steps) {
        (Some(times), _) => Some(times.len() as f64 + 1.0),
        (None, Some(n)) => Some((n / plan.every as f64).ceil() + 2.0),
        (None, None) => None,
    };
    if let Some(rows) = rows {
        let bytes = rows * info.columns().len() as f64 * 22.0;
        if bytes > max_output {
            bail!(
                "{}: the CSV would be about {:.2e} bytes ({rows:.3e} rows), more than \
                 --max-output {}; write fewer rows (--every N, --output-dt DT) or raise \
                 --max-output",
                info.name,
                bytes,
                args.max_output
            );
        }
    }
    Ok(())
}

/// Parses `--at T1,T2,...`: plain numbers (their order and range are checked with the plan).
fn parse_times(raw: &str) -> Result<Vec<f64>> {
    raw.split(',')
        .map(|p| {
            let p = p.trim();
            p.parse::<f64>().map_err(|_| {
                anyhow::anyhow!(
                    "--at {raw}: `{p}` is not a number (give times in seconds, comma-separated, \
                     e.g. --at 0.5,1,2.5)"
                )
            })
        })
        .collect()
}

/// A run-option error in the words of the command line (`--dt` for `dt`, `--t-end` for
/// `t_end`).
pub(crate) fn flag_words(e: &SceneError) -> String {
    match e {
        SceneError::InvalidOption {
            option,
            value,
            reason,
        } => {
            let flag = match *option {
                "t_end" => "--t-end",
                "dt" => "--dt",
                "tol" => "--tol",
                "every" => "--every",
                "at" => "--at",
                "output_dt" => "--output-dt",
                _ => return e.to_string(),
            };
            if value.is_nan() && matches!(*option, "at" | "output_dt") {
                format!("{flag}: {reason}")
            } else {
                format!("{flag} {}: {reason}", number(*value))
            }
        }
        SceneError::UnsupportedIntegrator { .. } => format!("--integrator: {e}"),
        _ => e.to_string(),
    }
}

/// A number as a person would type it: plain, or in exponent form when very small or large.
pub(crate) fn number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The state a failure carries, if any.
fn failure_state(e: &SceneError) -> Option<&[f64]> {
    use tumble_integrators::Error as I;
    match e {
        SceneError::Model(
            ModelError::SingularMassMatrix { state, .. } | ModelError::NonFinite { state, .. },
        )
        | SceneError::Integration(
            I::NonFinite { state, .. }
            | I::NoConvergence { state, .. }
            | I::SingularMatrix { state, .. }
            | I::StepSizeUnderflow { state, .. }
            | I::TooManySteps { state, .. }
            | I::TimeLimit { state, .. },
        ) => Some(state),
        _ => None,
    }
}

/// A run failure with the state it carries, named by the scene's coordinates and rates when
/// the state has one value for each.
fn failure_message(info: &SceneInfo, e: &SceneError) -> String {
    let mut msg = format!("{}: {e}", info.name);
    if let Some(state) = failure_state(e) {
        let names: Vec<String> = info
            .coordinates
            .iter()
            .map(|c| (*c).to_string())
            .chain(plot::trajectory::rate_columns(info))
            .collect();
        if names.len() == state.len() {
            let parts: Vec<String> = names
                .iter()
                .zip(state)
                .map(|(n, v)| format!("{n} = {}", number(*v)))
                .collect();
            msg += &format!("\n  state: {}", parts.join(", "));
        } else {
            let values: Vec<String> = state.iter().map(|v| number(*v)).collect();
            msg += &format!("\n  state: [{}]", values.join(", "));
        }
    }
    msg
}

/// Writes rows as CSV and keeps them, column by column, when a plot needs them.
struct CsvRecorder<W: Write> {
    csv: csv::Writer<W>,
    keep: Option<Vec<Vec<f64>>>,
    error: Option<csv::Error>,
    /// Stdout was closed by the reader (`| head`): stop quietly.
    closed: bool,
}

impl<W: Write> CsvRecorder<W> {
    fn new(out: W, columns: &[String], keep: bool) -> Result<Self> {
        let mut csv = csv::Writer::from_writer(out);
        csv.write_record(columns)?;
        Ok(CsvRecorder {
            csv,
            keep: keep.then(|| vec![Vec::new(); columns.len()]),
            error: None,
            closed: false,
        })
    }

    fn fail(&mut self, e: csv::Error) -> Flow {
        if matches!(e.kind(), csv::ErrorKind::Io(io) if io.kind() == io::ErrorKind::BrokenPipe) {
            self.closed = true;
        } else {
            self.error = Some(e);
        }
        Flow::Stop
    }

    /// Flushes; the kept columns and whether the reader closed the output early, or the first
    /// write error.
    fn finish(mut self) -> Result<(Option<Vec<Vec<f64>>>, bool)> {
        if let Some(e) = self.error.take() {
            return Err(e.into());
        }
        if !self.closed
            && let Err(e) = self.csv.flush()
        {
            if e.kind() == io::ErrorKind::BrokenPipe {
                self.closed = true;
            } else {
                return Err(e.into());
            }
        }
        Ok((self.keep, self.closed))
    }
}

impl<W: Write> Recorder for CsvRecorder<W> {
    fn row(&mut self, values: &[f64]) -> Flow {
        if let Err(e) = self.csv.serialize(values) {
            return self.fail(e);
        }
        if let Some(keep) = &mut self.keep {
            for (column, &v) in keep.iter_mut().zip(values) {
                column.push(v);
            }
        }
        Flow::Continue
    }
}

pub(crate) fn step_words(step: StepControl) -> String {
    match step {
        StepControl::Fixed(h) => format!("fixed step dt = {h} s"),
        StepControl::Tolerance(tol) => format!("tolerance {}", number(tol)),
    }
}

/// `FILE.csv.json`: how a simulation's CSV was made.
#[derive(serde::Serialize)]
struct SimulationRecord<'a> {
    provenance: Provenance,
    scene: &'static str,
    origin: &'a str,
    /// The frame of the orientation and angular-velocity columns.
    frame: String,
    parameters: std::collections::BTreeMap<&'static str, f64>,
    integrator: &'static str,
    dt: Option<f64>,
    tol: Option<f64>,
    t_end: f64,
    every: u64,
    at: Option<&'a [f64]>,
    csv: String,
    columns: Vec<String>,
    rows: u64,
    steps: u64,
    evaluations: u64,
    reached_t: f64,
    max_energy_rel_err: f64,
    energy_warning: bool,
    wall_time_s: f64,
}

impl<'a> SimulationRecord<'a> {
    fn new(
        setup: &'a Setup,
        summary: &RunSummary,
        wall: f64,
        csv: Option<&Path>,
        energy_warn: f64,
    ) -> Self {
        let plan = &setup.plan;
        let (dt, tol) = match plan.step {
            StepControl::Fixed(h) => (Some(h), None),
            StepControl::Tolerance(t) => (None, Some(t)),
        };
        SimulationRecord {
            provenance: Provenance::now(1),
            scene: setup.scene.info().name,
            origin: &setup.origin,
            frame: setup.frame.clone().unwrap_or_else(|| {
                "the scene's body frame (docs/design.md, section 3)".to_string()
            }),
            parameters: setup.params.iter().collect(),
            integrator: plan.integrator(),
            dt,
            tol,
            t_end: plan.t_end,
            every: plan.every,
            at: plan.times.as_deref(),
            csv: csv.map_or_else(String::new, |p| p.display().to_string()),
            columns: setup.scene.info().columns(),
            rows: summary.rows,
            steps: summary.steps,
            evaluations: summary.evaluations,
            reached_t: summary.t,
            max_energy_rel_err: summary.max_energy_rel_err,
            energy_warning: !(summary.max_energy_rel_err <= energy_warn),
            wall_time_s: wall,
        }
    }
}

/// What a run produced.
struct Outcome {
    summary: RunSummary,
    /// The rows, column by column, when a plot needs them.
    kept: Option<Vec<Vec<f64>>>,
    /// The reader closed the output before the end (`| head`).
    closed: bool,
}

/// Runs the scene into `out`.
fn run_into<W: Write>(setup: &Setup, out: W, keep: bool) -> Result<Outcome> {
    let info = setup.scene.info();
    let mut recorder = CsvRecorder::new(out, &info.columns(), keep)?;
    let result = setup
        .scene
        .simulate(&setup.params, &setup.plan, &mut recorder);
    let summary = result.map_err(|e| anyhow::anyhow!(failure_message(info, &e)))?;
    let (kept, closed) = recorder.finish().context("cannot write the CSV")?;
    Ok(Outcome {
        summary,
        kept,
        closed,
    })
}

/// Runs the subcommand.
///
/// # Errors
/// Invalid scene, parameters or options (before anything is written); a model or integration
/// failure (with its time and state); an output that cannot be written.
pub fn run(args: &Args) -> Result<()> {
    let setup = setup(args)?;
    let info = setup.scene.info();
    if let Some(path) = &args.plot {
        plot::Format::from_path(path)?;
    }
    let figure_options = args.figure.options()?;
    // Every output is classified before the first step: a directory or a socket is refused
    // now, a device or FIFO is streamed to, and -o and --plot may not name one file.
    let outputs: Vec<(&str, &Path)> = [
        ("-o", args.output.as_deref()),
        ("--plot", args.plot.as_deref()),
    ]
    .into_iter()
    .filter_map(|(role, p)| p.map(|p| (role, p)))
    .collect();
    let mut destinations = output::check_all(outputs)?.into_iter();
    let csv_dest = match &args.output {
        Some(_) => destinations.next(),
        None => None,
    };
    let plot_dest = destinations.next();
    // A regular CSV file gets its provenance beside it: FILE.csv.json.
    let sidecar = match csv_dest.as_ref().map(output::Destination::mode) {
        Some(output::Mode::Atomic { target }) => {
            let mut name = target.as_os_str().to_owned();
            name.push(".json");
            let path = std::path::PathBuf::from(name);
            let dest = output::Destination::check(&path)
                .with_context(|| "the provenance file beside -o".to_string())?;
            if plot_dest.as_ref().is_some_and(|p| p.file() == dest.file()) {
                bail!(
                    "--plot {}: the same file as the provenance written beside -o",
                    path.display()
                );
            }
            Some(dest)
        }
        _ => None,
    };
    let start = Instant::now();
    let (outcome, written) = match &csv_dest {
        Some(dest) if *dest.mode() != output::Mode::Stdout => {
            let mut out = dest.create().context("-o")?;
            let outcome = run_into(&setup, &mut out, args.plot.is_some())?;
            (outcome, Some(out))
        }
        _ => (
            run_into(&setup, io::stdout().lock(), args.plot.is_some())?,
            None,
        ),
    };
    let Outcome {
        summary,
        kept,
        closed,
    } = outcome;
    let elapsed = start.elapsed();
    if let Some(code) = signals::interrupted() {
        // Dropping the unfinished output removes its temporary file: nothing is left behind.
        drop(written);
        let kept = match csv_dest.as_ref().map(output::Destination::mode) {
            None | Some(output::Mode::Stdout | output::Mode::Stream) => format!(
                "the rows up to t = {} went to {}",
                number(summary.t),
                args.output
                    .as_ref()
                    .map_or_else(|| "stdout".to_string(), |p| p.display().to_string())
            ),
            Some(output::Mode::Atomic { .. }) => "nothing was written".to_string(),
        };
        return Err(signals::Interrupted {
            code,
            message: format!(
                "{} stopped at t = {} of {} s; {kept}",
                info.name,
                number(summary.t),
                number(setup.plan.t_end)
            ),
        }
        .into());
    }

    if let (Some(dest), Some(values)) = (&plot_dest, &kept) {
        let figure = plot::trajectory::simulation(
            info,
            setup.plan.integrator(),
            &step_words(setup.plan.step),
            setup.params.iter(),
            &info.columns(),
            values,
        );
        plot::save_to(&figure, dest, &figure_options)?;
    }
    if let Some(dest) = &sidecar {
        let text = manifest::to_text(&SimulationRecord::new(
            &setup,
            &summary,
            elapsed.as_secs_f64(),
            args.output.as_deref(),
            args.energy_warn,
        ))?;
        dest.write_all(text.as_bytes())?;
    }
    if let Some(out) = written
        && let Err(e) = out.finish()
    {
        if let Some(dest) = &sidecar {
            let _ = std::fs::remove_file(dest.file());
        }
        if let Some(dest) = &plot_dest
            && let output::Mode::Atomic { target } = dest.mode()
        {
            // Do not leave the plot of a run whose CSV could not be written.
            let _ = std::fs::remove_file(target);
        }
        return Err(e.into());
    }

    let r = &setup.plan;
    let source = if setup.origin == "builtin" {
        String::new()
    } else {
        format!(" (from {})", setup.origin)
    };
    let destination = match &args.output {
        Some(p) if p.as_os_str() != "-" => p.display().to_string(),
        _ => "stdout".to_string(),
    };
    eprintln!("scene        {}{source}", info.name);
    eprintln!(
        "integrator   {}, {}, t in [0, {}] s",
        r.integrator(),
        step_words(r.step),
        r.t_end
    );
    eprintln!(
        "work         {} steps, {} evaluations, reached t = {}",
        summary.steps, summary.evaluations, summary.t
    );
    eprintln!(
        "energy       max relative error {:.3e}",
        summary.max_energy_rel_err
    );
    if !(summary.max_energy_rel_err <= args.energy_warn) {
        eprintln!(
            "warning      the energy drifted by {:.2e} (relative), more than --energy-warn {:.1e}: \
             the step or tolerance does not resolve this motion; use a smaller one",
            summary.max_energy_rel_err, args.energy_warn
        );
    }
    let cadence = match &r.times {
        Some(times) => format!(
            "at {} chosen time{} from dense output, and the final state",
            times.len(),
            if times.len() == 1 { "" } else { "s" }
        ),
        None => format!(
            "every {} step{}, and the final state",
            r.every,
            if r.every == 1 { "" } else { "s" }
        ),
    };
    eprintln!(
        "output       {} rows ({cadence}) to {destination}{}",
        summary.rows,
        if closed {
            ", closed early by the reader"
        } else {
            ""
        }
    );
    if let Some(p) = &args.plot {
        eprintln!("plot         {}", p.display());
    }
    let seconds = elapsed.as_secs_f64();
    if seconds < 1.0 {
        eprintln!("wall time    {:.1} ms", 1e3 * seconds);
    } else {
        eprintln!("wall time    {seconds:.3} s");
    }
    Ok(())
}
