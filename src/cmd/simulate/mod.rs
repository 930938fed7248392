//! `tumble simulate`: run a built-in scene or a scene file and write its trajectory as CSV (or
//! Parquet), with an optional plot.
//!
//! Two stages, as everywhere in the CLI: the flags are turned into a validated scene, parameter
//! set and run options (scene file first, then `--set` and the run flags over it, then the
//! scene's own validation) before any output file is created or any step is taken; then the
//! scene runs, streaming rows to the CSV writer.
//!
//! Output contract (docs/design.md §5): the header is the scene's columns (`t`, coordinates, `_dot`
//! rates, diagnostics); every number is written in the shortest form that reads back to the
//! same `f64` (ryu, through the `csv` crate). `--format parquet` (or `-o FILE.parquet`) writes
//! the same columns as Parquet `DOUBLE`s, bit for bit, with the provenance record in the file's
//! key-value metadata ([`METADATA_KEY`]); the rows are kept in memory and written at the end.
//! Files (`-o`, `--plot`) are written to a temporary file beside the destination and renamed
//! when complete; a failed run leaves neither. A short summary goes to stderr.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use tumble_output::table::{Column, Format, Table, Values};
use tumble_scenarios::scene::CancelFlag;
use tumble_scenarios::{Params, RunPlan, RunSummary, Scene, SceneInfo, StepControl};
use tumble_studies::error_estimate::{self, Tap, Trust, WrittenRows};
use tumble_studies::simulation::{self, Naming, ParamOverride, RunRequest, failure_message};
pub(crate) use tumble_studies::simulation::{LoadedScene, number};

mod rows;

use rows::CsvRecorder;
use tumble_studies::record::{Estimated, RunRecord, RunSetup};

use super::args::{parse_set, refuse_repeated_keys};
use crate::manifest;
use crate::output;
use crate::signals;
use tumble_plot as plot;
use tumble_plot::trajectory::{RunResult, step_words};

/// Flags of `tumble simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene and its parameter overrides.
    #[command(flatten)]
    pub target: SceneArgs,
    /// Integrator (from `tumble integrators`) among those the scene lists as applicable.
    #[arg(long, value_name = "NAME")]
    pub integrator: Option<String>,
    /// Arithmetic of the run: `double`, or `double-double` (about 32 digits), in which the
    /// Taylor method runs (`taylor-dd`: give `--integrator taylor` or none, and a tolerance
    /// such as `--tol 1e-30`).
    #[arg(long, value_name = "double|double-double", value_parser = parse_precision)]
    pub precision: Option<Precision>,
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
    #[arg(long = "max-steps", value_name = "N", default_value_t = simulation::DEFAULT_MAX_STEPS)]
    pub max_steps: u64,
    /// Warn (on stderr and in the provenance file) when the largest relative energy error of
    /// the run exceeds this: the step does not resolve the motion.
    #[arg(
        long = "energy-warn",
        value_name = "REL",
        default_value_t = simulation::DEFAULT_ENERGY_WARN,
        allow_negative_numbers = true
    )]
    pub energy_warn: f64,
    /// Refuse a run whose CSV is estimated to be larger than this many bytes (suffixes k, M, G);
    /// an adaptive run, whose rows are not known in advance, stops with an error when its
    /// output reaches this size.
    #[arg(long = "max-output", value_name = "BYTES", default_value = "10G")]
    pub max_output: String,
    /// Run even when the fixed step turns the initial state's fastest rotation by more than
    /// 0.5 rad a step (a step that does not resolve the motion is refused otherwise).
    #[arg(long = "allow-coarse-step")]
    pub allow_coarse_step: bool,
    /// Estimate the error of the written rows by running the method again at half the step
    /// (or a tolerance 100 times tighter) and, to judge that estimate, at twice the step (or
    /// 100 times looser); the estimate goes to the summary and the provenance file. It costs
    /// about 2–3 times the run; `off` skips it.
    #[arg(
        long,
        value_name = "on|off",
        default_value = "on",
        value_parser = parse_check,
        action = clap::ArgAction::Set
    )]
    pub check: bool,
    /// Write the trajectory to FILE instead of stdout (`-` is stdout).
    #[arg(short = 'o', long = "output", value_name = "FILE.csv|FILE.parquet")]
    pub output: Option<PathBuf>,
    /// The trajectory's format: `csv`, or `parquet` (typed columns, the provenance record in
    /// the file's key-value metadata under `tumble`) [default: `parquet` when -o ends in
    /// `.parquet`, else `csv`].
    #[arg(long, value_name = "csv|parquet", value_parser = parse_format)]
    pub format: Option<Format>,
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
    /// `--max-output` in bytes.
    max_output: f64,
}

/// A scene and its parameter overrides, as `simulate` and `work-precision` take them.
#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    /// A built-in scene (`tumble scenes` lists them), a TOML scene file, or a model file (a
    /// TOML file with a `[model]` table: `tumble models` lists the shipped ones); taken as a
    /// file if the argument ends in `.toml` or names an existing file.
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

/// The scene of `target` (built-in name or TOML file) with its `--set` overrides.
pub(crate) fn load_scene(target: &SceneArgs) -> Result<LoadedScene> {
    let overrides = target
        .set
        .iter()
        .map(|raw| {
            let (key, value) = parse_set(raw, "omega0=5")?;
            Ok(ParamOverride {
                label: format!("--set {raw}"),
                key: key.to_string(),
                value,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    refuse_repeated_keys(
        overrides
            .iter()
            .zip(&target.set)
            .map(|(o, raw)| (o.key.as_str(), raw.as_str())),
    )?;
    Ok(simulation::load_scene(&target.scene, &overrides)?)
}

/// Stage one: the scene, parameters and options from the flags, validated.
fn setup(args: &Args) -> Result<Setup> {
    let loaded = load_scene(&args.target)?;
    let at = args.at.as_deref().map(parse_times).transpose()?;
    let request = RunRequest {
        integrator: integrator_at(args.integrator.as_deref(), args.precision)?,
        // clap refuses --dt with --tol.
        step: StepControl::from_dt_tol(args.dt, args.tol)?,
        t_end: args.t_end,
        every: args.every,
        at,
        output_dt: args.output_dt,
        max_steps: Some(args.max_steps),
        allow_coarse_step: true,
        cancel: Some(CancelFlag(signals::flag())),
    };
    let plan = loaded.plan(&request, Naming::Cli)?;
    check_budget(&plan, loaded.scene.info(), args)?;
    if !(args.energy_warn >= 0.0) {
        bail!(
            "--energy-warn {}: must be a relative energy error >= 0",
            number(args.energy_warn)
        );
    }
    if !args.allow_coarse_step {
        simulation::check_resolution(loaded.scene, &loaded.params, &plan, Naming::Cli)?;
    }
    Ok(Setup {
        scene: loaded.scene,
        origin: loaded.origin,
        params: loaded.params,
        plan,
        frame: loaded.frame,
        max_output: parse_bytes(&args.max_output)?,
    })
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

/// The key of a Parquet trajectory's key-value metadata that holds its provenance record (the
/// JSON written beside a CSV).
pub const METADATA_KEY: &str = "tumble";

/// Parses `--check`.
fn parse_check(raw: &str) -> Result<bool> {
    match raw {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => bail!("`{raw}` is not a check setting: give on or off"),
    }
}

/// The arithmetic a run asks for (`--precision`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// IEEE double.
    Double,
    /// Double-double (an unevaluated sum of two doubles, about 32 digits).
    DoubleDouble,
}

/// Parses `--precision`.
fn parse_precision(raw: &str) -> Result<Precision> {
    match raw {
        "double" => Ok(Precision::Double),
        "double-double" => Ok(Precision::DoubleDouble),
        _ => bail!("`{raw}` is not a precision: give double or double-double"),
    }
}

/// The integrator `--integrator` names in the arithmetic `--precision` asks for: in
/// double-double the Taylor method (`taylor-dd`), the only method that runs in it.
fn integrator_at(integrator: Option<&str>, precision: Option<Precision>) -> Result<Option<String>> {
    const DD: &str = "taylor-dd";
    match (precision, integrator) {
        (None, name) => Ok(name.map(str::to_string)),
        (Some(Precision::DoubleDouble), None | Some("taylor" | DD)) => Ok(Some(DD.into())),
        (Some(Precision::DoubleDouble), Some(name)) => bail!(
            "--precision double-double --integrator {name}: `{name}` runs in double; the \
             method that runs in double-double is the Taylor method ({DD}): give --integrator \
             taylor, or leave --integrator out"
        ),
        (Some(Precision::Double), Some(DD)) => bail!(
            "--precision double --integrator {DD}: `{DD}` runs in double-double; give \
             --integrator taylor for the Taylor method in double, or --precision double-double"
        ),
        (Some(Precision::Double), name) => Ok(name.map(str::to_string)),
    }
}

/// Parses `--format`.
fn parse_format(raw: &str) -> Result<Format> {
    Format::parse(raw)
        .ok_or_else(|| anyhow::anyhow!("`{raw}` is not a format: give csv or parquet"))
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

/// What a run produced.
struct Outcome {
    summary: RunSummary,
    /// The rows, column by column, when a plot needs them.
    kept: Option<Vec<Vec<f64>>>,
    /// The reader closed the output before the end (`| head`).
    closed: bool,
    /// The written rows' times and states (`--check on`).
    written: Option<WrittenRows>,
}

/// Runs the scene into `out` (CSV), or only keeps the rows when `out` is `None`; with
/// `check`, keeps the written rows' states for the error estimate too.
fn run_into<W: Write>(setup: &Setup, out: Option<W>, keep: bool, check: bool) -> Result<Outcome> {
    let info = setup.scene.info();
    let mut recorder = CsvRecorder::new(out, &info.columns(), keep, setup.max_output)?;
    let mut written = check.then(|| WrittenRows::new(info));
    let result = match &mut written {
        Some(rows) => setup.scene.simulate(
            &setup.params,
            &setup.plan,
            &mut Tap {
                inner: &mut recorder,
                rows,
            },
        ),
        None => setup
            .scene
            .simulate(&setup.params, &setup.plan, &mut recorder),
    };
    let summary = result.map_err(|e| anyhow::anyhow!(failure_message(info, &e)))?;
    if let Some(t) = recorder.over_at {
        bail!(
            "{}: the output reached --max-output ({} bytes) at t = {t} s, before t_end = {} s, \
             and the run stopped there: write fewer rows (--every N, --output-dt DT, --at) or \
             raise --max-output",
            info.name,
            setup.max_output,
            setup.plan.t_end,
        );
    }
    let (kept, closed) = recorder.finish().context("cannot write the CSV")?;
    Ok(Outcome {
        summary,
        kept,
        closed,
        written,
    })
}

/// The error estimate of a finished run (module doc of `tumble_studies::error_estimate`).
fn estimate_error(setup: &Setup, outcome: &Outcome) -> Estimated {
    let Some(rows) = &outcome.written else {
        return Estimated::Off;
    };
    let summary = &outcome.summary;
    if outcome.closed || !(summary.t >= setup.plan.t_end || summary.terminated) {
        return Estimated::Failed(format!(
            "the run stopped at t = {} before its end",
            number(summary.t)
        ));
    }
    match error_estimate::estimate(setup.scene, &setup.params, &setup.plan, summary, rows) {
        Ok(e) => Estimated::Done(e),
        Err(reason) => Estimated::Failed(reason),
    }
}

/// The summary's lines on the error estimate.
fn print_estimate(estimated: &Estimated) {
    match estimated {
        Estimated::Off => eprintln!("error        not estimated (--check off)"),
        Estimated::Failed(reason) => eprintln!("error        not estimated: {reason}"),
        Estimated::Done(e) => {
            eprintln!(
                "error        estimated {:.1e} at the final state, at most {:.1e} (t = {}) over \
                 {} of {} rows (work–precision norm; companion {}{})",
                e.final_error,
                e.max_error,
                format!("{:.4e}", e.max_error_t)
                    .parse::<f64>()
                    .map_or_else(|_| number(e.max_error_t), number),
                e.rows_compared,
                e.rows_written,
                error_estimate::words(e.companion),
                e.check.map_or_else(String::new, |c| format!(
                    ", check {}",
                    error_estimate::words(c)
                ))
            );
            let label = if e.trust == Trust::NotTrustworthy {
                "warning"
            } else {
                ""
            };
            eprintln!("{label:13}{}", e.trust_words());
        }
    }
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
    let format = args
        .format
        .unwrap_or_else(|| args.output.as_deref().map_or(Format::Csv, Format::of_path));
    // A regular file gets its provenance beside it: FILE.csv.json (output::provenance_path).
    let sidecar = match csv_dest.as_ref().map(output::Destination::mode) {
        Some(output::Mode::Atomic { target }) => {
            let path = output::provenance_path(target, format);
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
    if setup.origin != simulation::BUILT_IN {
        let scene_file = Path::new(&setup.origin);
        let outputs = [
            ("-o", &csv_dest),
            ("--plot", &plot_dest),
            ("-o (provenance)", &sidecar),
        ];
        for (role, dest) in outputs {
            if let Some(dest) = dest {
                output::refuse_input(role, dest, scene_file, "the scene file")?;
            }
        }
    }
    // Files that exist now are replaced; the summary says which.
    let sidecar_name = args
        .output
        .as_deref()
        .map(|o| output::provenance_path(o, format));
    let replaced: Vec<String> = [
        (&csv_dest, args.output.as_deref()),
        (&plot_dest, args.plot.as_deref()),
        (&sidecar, sidecar_name.as_deref()),
    ]
    .into_iter()
    .filter_map(|(d, name)| Some((d.as_ref()?, name?)))
    .filter(|(d, _)| output::replaces(d))
    .map(|(_, name)| name.display().to_string())
    .collect();
    let parquet = format == Format::Parquet;
    let keep = args.plot.is_some() || parquet;
    let start = Instant::now();
    let (outcome, written) = match &csv_dest {
        // A Parquet file is written whole after the run, from the kept columns.
        _ if parquet => (run_into::<io::Sink>(&setup, None, true, args.check)?, None),
        Some(dest) if *dest.mode() != output::Mode::Stdout => {
            let mut out = dest.create().context("-o")?;
            let outcome = run_into(&setup, Some(&mut out), keep, args.check)?;
            (outcome, Some(out))
        }
        _ => (
            run_into(&setup, Some(io::stdout().lock()), keep, args.check)?,
            None,
        ),
    };
    let elapsed = start.elapsed();
    let check_start = Instant::now();
    let estimated = if signals::interrupted().is_some() {
        Estimated::Off
    } else {
        estimate_error(&setup, &outcome)
    };
    let check_seconds = check_start.elapsed().as_secs_f64();
    let Outcome {
        summary,
        kept,
        closed,
        ..
    } = outcome;
    if let Some(code) = signals::interrupted() {
        // Dropping the unfinished output removes its temporary file: nothing is left behind.
        drop(written);
        let kept = match csv_dest.as_ref().map(output::Destination::mode) {
            None | Some(output::Mode::Stdout | output::Mode::Stream) if !parquet => format!(
                "the rows up to t = {} went to {}",
                number(summary.t),
                args.output
                    .as_ref()
                    .map_or_else(|| "stdout".to_string(), |p| p.display().to_string())
            ),
            _ => "nothing was written".to_string(),
        };
        return Err(signals::Interrupted {
            code,
            message: format!(
                "{} stopped at t = {} of {} s{}; {kept}",
                info.name,
                number(summary.t),
                number(setup.plan.t_end),
                if summary.t >= setup.plan.t_end || summary.terminated {
                    " (while estimating its error)"
                } else {
                    ""
                }
            ),
        }
        .into());
    }

    let kept = match (&plot_dest, kept) {
        (Some(dest), Some(values)) => {
            let run = RunResult::of_scene(
                info,
                setup.plan.integrator(),
                setup.plan.step,
                &setup.params,
                info.columns(),
                values,
            );
            plot::save_to(&run.figure(), dest, &figure_options)?;
            Some(run.values)
        }
        (_, kept) => kept,
    };
    let record = manifest::to_text(&RunRecord::new(
        crate::provenance::now(1),
        &RunSetup {
            info,
            origin: &setup.origin,
            frame: setup.frame.as_deref(),
            params: &setup.params,
            plan: &setup.plan,
        },
        &summary,
        &estimated,
        args.energy_warn,
        args.output
            .as_deref()
            .map_or_else(String::new, |p| p.display().to_string()),
        elapsed.as_secs_f64(),
    ))?;
    let trajectory = if parquet {
        let columns = info.columns().into_iter().zip(kept.unwrap_or_default());
        let table = Table {
            columns: columns
                .map(|(name, v)| Column {
                    name,
                    values: Values::F64(v),
                })
                .collect(),
            metadata: vec![(METADATA_KEY.to_string(), record.clone())],
        };
        let dest = match csv_dest {
            Some(dest) => dest,
            None => output::Destination::check(Path::new("-"))?,
        };
        table
            .to_parquet()
            .map_err(anyhow::Error::from)
            .and_then(|bytes| Ok(dest.write_all(&bytes)?))
    } else if let Some(out) = written {
        out.finish().map_err(anyhow::Error::from)
    } else {
        Ok(())
    };
    if let Err(e) = trajectory {
        if let Some(dest) = &plot_dest
            && let output::Mode::Atomic { target } = dest.mode()
        {
            // Do not leave the plot of a run whose trajectory could not be written.
            let _ = std::fs::remove_file(target);
        }
        return Err(e);
    }
    if let Some(dest) = &sidecar {
        dest.write_all(record.as_bytes())?;
    }

    let r = &setup.plan;
    let source = if setup.origin == simulation::BUILT_IN {
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
    print_estimate(&estimated);
    if let Some(p) = &args.plot {
        eprintln!("plot         {}", p.display());
    }
    if !replaced.is_empty() {
        eprintln!("replaced     {} (they existed)", replaced.join(", "));
    }
    let time = |seconds: f64| {
        if seconds < 1.0 {
            format!("{:.1} ms", 1e3 * seconds)
        } else {
            format!("{seconds:.3} s")
        }
    };
    let check_time = match estimated {
        Estimated::Off => String::new(),
        _ => format!(", and {} for the error estimate", time(check_seconds)),
    };
    eprintln!("wall time    {}{check_time}", time(elapsed.as_secs_f64()));
    Ok(())
}
