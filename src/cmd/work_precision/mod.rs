//! `tumble work-precision`: speed against error for every integrator that runs a scene, or
//! (`--long`) the relative energy error over a million steps and more.
//!
//! The numerics live in `tumble_studies::work_precision` (ladders, reference, error norm,
//! long runs); this module validates the flags, prints progress and a summary, and writes
//! `work-precision.csv`, `manifest.json` and the plots (`work-precision.png`/`.svg`, or
//! `long.csv`, `long.png`/`.svg`) into the output folder. `--recommend FILE` measures what
//! the scene's recommendations rest on instead ([`recommend`]).

mod recommend;

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Result, bail};
use tumble_integrators::registry;
use tumble_scenarios::{Params, Scene, StepControl};
use tumble_studies::work_precision::{
    self, Config, LONG_FACTOR, Ladder, LongRun, Rung, control_words, cost_at, fitted_slope,
    long_run_methods,
};

use super::simulate::{LoadedScene, SceneArgs, load_scene, number};
use crate::manifest;
use crate::output;
use crate::signals;
use tumble_plot as plot;
use tumble_plot::saved::SceneRecord;
use tumble_plot::work_precision::{Curve, LongManifest, LongRecord, long_label};
use tumble_plot::xy::Series;
use tumble_studies::simulation::{Naming, flag_words};
use tumble_studies::work_precision::record::StudyRecord;

/// Flags of `tumble work-precision`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene and its parameter overrides.
    #[command(flatten)]
    pub target: SceneArgs,
    /// Integrators to compare, comma-separated (default: every one the scene takes; with
    /// `--long`, its symplectic, variational and Lie-group ones).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub integrators: Vec<String>,
    /// Horizon in seconds (default: the scene's; ignored with `--long`, whose horizon is
    /// `--long-steps` steps of the scene's default step).
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Output folder (default `out/work-precision/SCENE`, or `.../SCENE-long`).
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// A ladder stops after a run that took longer than this many seconds; a run still going
    /// at twice this is cut. Each run of the reference is limited to 60 times this (a reference
    /// the limit cuts is refused before the study starts), each run of `--long` to 600 times.
    #[arg(
        long = "max-seconds",
        value_name = "S",
        default_value_t = Config::DEFAULT_MAX_RUN_SECONDS
    )]
    pub max_seconds: f64,
    /// Long-run mode: relative energy error against time over `--long-steps` steps.
    #[arg(long)]
    pub long: bool,
    /// Take over the output folder's lock even if another tumble process seems to hold it.
    #[arg(long = "break-lock")]
    pub break_lock: bool,
    /// Steps of a long run (at the scene's default step).
    #[arg(long = "long-steps", value_name = "N", default_value_t = 1 << 20)]
    pub long_steps: u64,
    /// With `--long`: compare at equal cost from the adaptive side. The adaptive methods named
    /// in `--integrators` (or the scene's adaptive method of highest order) run at this
    /// tolerance, and every fixed-step method at the step whose cost per simulated second
    /// matches the first of them (probed, then corrected), over the same horizon; a method
    /// with no step within 1.5× of that cost is left out, with the reason.
    #[arg(long = "long-tol", value_name = "TOL", requires = "long")]
    pub long_tol: Option<f64>,
    /// Measure what the scene's recommendations (`tumble scenes`) rest on, for a built-in
    /// scene at its default parameters: the time each recommended and compared method takes
    /// to each error band's finest error (its ladder, retimed in turns), and its relative
    /// energy error over `--long-steps` steps for each long horizon; then write them, with the
    /// command, version, date and machine, into FILE in place of the scene's entry (the other
    /// scenes' entries are kept). `crates/scenarios/data/recommendations.toml` is the file the
    /// binary embeds at build time.
    #[arg(
        long,
        value_name = "FILE",
        conflicts_with_all = ["long", "long_tol", "integrators", "t_end", "output"]
    )]
    pub recommend: Option<PathBuf>,
    /// Size, font size, resolution and SVG text of the figures.
    #[command(flatten)]
    pub figure: super::args::FigureArgs,
}

/// Each run of the reference is limited to this multiple of `--max-seconds`.
const REFERENCE_FACTOR: f64 = Config::REFERENCE_FACTOR;

/// Runs the subcommand.
///
/// # Errors
/// Invalid flags (before any run), a failing reference, an unwritable output folder.
pub fn run(args: &Args) -> Result<()> {
    let figure_options = args.figure.options()?;
    let LoadedScene {
        scene,
        origin,
        params,
        run: file_options,
        ..
    } = load_scene(&args.target)?;
    // SIGINT and SIGTERM stop the run under way at a step boundary; nothing is written then.
    signals::flag();
    let interruptible = signals::interruptible(scene);
    let scene: &dyn Scene = &interruptible;
    let info = scene.info();
    for (k, name) in args.integrators.iter().enumerate() {
        if !info.runs(name) {
            bail!("--integrators: {}", info.unsupported(name));
        }
        if args.integrators[..k].contains(name) {
            bail!("--integrators: `{name}` twice; list each integrator once");
        }
    }
    if !(args.max_seconds.is_finite() && args.max_seconds > 0.0) {
        bail!(
            "--max-seconds {}: must be finite and positive",
            number(args.max_seconds)
        );
    }
    if let Some(file) = &args.recommend {
        return recommend::run(scene, &origin, &params, args, file);
    }
    let stem = if origin == tumble_studies::simulation::BUILT_IN {
        info.name.to_string()
    } else {
        PathBuf::from(&origin)
            .file_stem()
            .map_or_else(|| info.name.to_string(), |s| s.to_string_lossy().into())
    };
    if args.long {
        let dir = args.output.clone().unwrap_or_else(|| {
            PathBuf::from("out")
                .join("work-precision")
                .join(format!("{stem}-long"))
        });
        return long(scene, &origin, &params, args, &dir);
    }
    let t_end = args
        .t_end
        .or(file_options.t_end)
        .unwrap_or(info.default_t_end);
    let mut config = Config::new(info);
    config.t_end = t_end;
    config.max_run_seconds = args.max_seconds;
    config.max_reference_seconds = REFERENCE_FACTOR * args.max_seconds;
    tumble_scenarios::scene::check_horizon(t_end)
        .map_err(|e| anyhow::anyhow!("{}: {}", info.name, flag_words(&e, Naming::Cli)))?;
    let integrators: Vec<String> = if args.integrators.is_empty() {
        info.integrators()
            .iter()
            .map(|s| (*s).to_string())
            .collect()
    } else {
        args.integrators.clone()
    };
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join("work-precision").join(stem));
    output::check_folder(&dir, &folder_files("work-precision"))?;
    let _lock = output::lock_folder(&dir, args.break_lock)?;

    let reference = study_reference(scene, &origin, &params, &config, &dir)?;
    let mut ladders = Vec::with_capacity(integrators.len());
    for name in &integrators {
        ladders.push(study_ladder(
            scene, &params, name, &reference, &config, &dir,
        )?);
    }
    eprintln!(
        "timing          every rung again, the methods taking turns ({} rounds)",
        work_precision::RETIME_ROUNDS
    );
    let retimed = work_precision::retime(
        scene,
        &params,
        &mut ladders,
        &config,
        work_precision::RETIME_ROUNDS,
    );
    stop_if_interrupted(&dir)?;
    retimed?;

    output::write_whole(
        &dir.join("work-precision.csv"),
        Rung::csv_text(Rung::of(&ladders))?.as_bytes(),
    )?;
    let curves: Vec<Curve> = ladders
        .iter()
        .filter(|l| !l.rungs.is_empty())
        .map(|l| Curve {
            integrator: l.integrator.clone(),
            label: plot::work_precision::curve_label(&l.integrator, &l.order.to_string()),
            rungs: l
                .rungs
                .iter()
                .map(|r| (r.wall_time_s, r.evaluations as f64, r.error))
                .collect(),
        })
        .collect();
    let study = plot::work_precision::Study {
        scene: info.name,
        t_end,
        parameters: plot::labels::parameters(params.iter()),
        reference: (&reference.method, &reference.check, reference.agreement),
    };
    let figure = plot::work_precision::study_figure(&study, &curves);
    for ext in ["png", "svg"] {
        plot::save_with(
            &figure,
            &dir.join(format!("work-precision.{ext}")),
            &figure_options,
        )?;
    }
    let text = manifest::to_text(&StudyRecord::new(
        crate::provenance::now(1),
        info.name,
        &origin,
        &params,
        &config,
        &reference,
        &ladders,
        control_words,
    ))?;
    output::write_whole(&dir.join("manifest.json"), text.as_bytes())?;

    print!("{}", summary(&ladders, t_end));
    eprintln!("output          {}", dir.display());
    Ok(())
}

/// The study's reference over `[0, config.t_end]`, before any line of the study (a reference
/// the budget cannot afford makes the error the first line on stderr), with what it is and how
/// far its checks agree on stderr. `dest` is where the results go (for the message of a run
/// stopped by a signal).
pub(super) fn study_reference(
    scene: &dyn Scene,
    origin: &str,
    params: &Params,
    config: &Config,
    dest: &std::path::Path,
) -> Result<work_precision::Reference> {
    let (info, t_end) = (scene.info(), config.t_end);
    let reference =
        work_precision::reference_within(scene, params, t_end, Some(config.max_reference_seconds));
    stop_if_interrupted(dest)?;
    let reference = reference.map_err(|e| match e {
        tumble_scenarios::SceneError::Integration(tumble_integrators::Error::TimeLimit {
            t,
            seconds,
            ..
        }) => anyhow::anyhow!(
            "{}: the reference run over [0, {t_end}] s was cut after {seconds} s of wall time at \
             t = {t} s ({REFERENCE_FACTOR} × --max-seconds); shorten --t-end or raise \
             --max-seconds",
            info.name
        ),
        e => anyhow::Error::new(e).context(format!("{}: the reference run failed", info.name)),
    })?;
    eprintln!(
        "work-precision  {} ({origin}), t in [0, {t_end}] s",
        info.name
    );
    eprintln!("reference       {}", reference.method);
    eprintln!(
        "cross-check     {}: agrees to {:.1e}",
        reference.check, reference.agreement
    );
    if !reference.self_check.is_empty() {
        eprintln!(
            "self-check      {}: agrees to {:.1e}",
            reference.self_check, reference.self_agreement
        );
    }
    Ok(reference)
}

/// The ladder of `name`, each rung on stderr as it completes.
pub(super) fn study_ladder(
    scene: &dyn Scene,
    params: &Params,
    name: &str,
    reference: &work_precision::Reference,
    config: &Config,
    dest: &std::path::Path,
) -> Result<Ladder> {
    let mut on_rung = |r: &Rung| print_rung(name, r);
    let ladder =
        work_precision::ladder(scene, params, name, &reference.state, config, &mut on_rung);
    stop_if_interrupted(dest)?;
    let ladder = ladder?;
    eprintln!("  {name:<13} stopped: {}", ladder.stop);
    Ok(ladder)
}

/// A rung on stderr.
pub(super) fn print_rung(name: &str, r: &Rung) {
    eprintln!(
        "  {:<13} {:<20} error {:9.2e}  {:>10} evaluations  {}",
        name,
        r.control().map_or_else(String::new, control_words),
        r.error,
        r.evaluations,
        seconds(r.wall_time_s)
    );
}

/// [`signals::Interrupted`] when a signal stopped the work: the study writes its files only
/// once every run has finished, so nothing of it was written.
pub(super) fn stop_if_interrupted(dir: &std::path::Path) -> Result<()> {
    match signals::interrupted() {
        Some(code) => Err(signals::Interrupted {
            code,
            message: format!(
                "stopped at a step boundary before any result was written; nothing was kept in \
                 {}",
                dir.display()
            ),
        }
        .into()),
        None => Ok(()),
    }
}

/// The files written into the output folder: `STEM.csv`, its plots and `manifest.json`.
fn folder_files(stem: &str) -> Vec<String> {
    ["csv", "png", "svg"]
        .iter()
        .map(|ext| format!("{stem}.{ext}"))
        .chain(["manifest.json".to_string()])
        .collect()
}

pub(crate) fn seconds(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.1} µs", 1e6 * s)
    } else if s < 1.0 {
        format!("{:.2} ms", 1e3 * s)
    } else {
        format!("{s:.3} s")
    }
}

/// Per integrator: rungs, the observed order (minus the fitted slope of error against steps
/// over errors in [1e-11, 1e-3]; meaningless for adaptive methods), the best error, the
/// interpolated cost of reaching 1e-8, and the interpolated time to 1e-12.
fn summary(ladders: &[Ladder], t_end: f64) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<14} {:>5} {:>5} {:>14} {:>10} {:>14} {:>16} {:>14}",
        "integrator",
        "order",
        "rungs",
        "observed order",
        "best error",
        "time at 1e-8",
        "evals at 1e-8",
        "time at 1e-12"
    );
    let mut at_target: Vec<(f64, &str)> = Vec::new();
    for l in ladders {
        let slope_steps = fitted_slope(&l.rungs, |r| r.steps as f64, 1e-11, 1e-3);
        let best = l
            .rungs
            .iter()
            .map(|r| r.error)
            .fold(f64::INFINITY, f64::min);
        let time = cost_at(&l.rungs, 1e-8, |r| r.wall_time_s);
        let evals = cost_at(&l.rungs, 1e-8, |r| r.evaluations as f64);
        let time_fine = cost_at(&l.rungs, 1e-12, |r| r.wall_time_s);
        if let Some(t) = time {
            at_target.push((t, &l.integrator));
        }
        let _ = writeln!(
            out,
            "{:<14} {:>5} {:>5} {:>14} {:>10} {:>14} {:>16} {:>14}",
            l.integrator,
            l.order.to_string(),
            l.rungs.len(),
            slope_steps.map_or_else(|| "—".into(), |s| format!("{:.2}", -s)),
            if best.is_finite() {
                format!("{best:.1e}")
            } else {
                "—".into()
            },
            time.map_or_else(|| "—".into(), seconds),
            evals.map_or_else(|| "—".into(), |e| format!("{e:.0}")),
            time_fine.map_or_else(|| "—".into(), seconds),
        );
    }
    at_target.sort_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((t, name)) = at_target.first() {
        let _ = writeln!(
            out,
            "fastest to an error of 1e-8 at t = {t_end} s: {name} ({})",
            seconds(*t)
        );
        if let Some((t2, name2)) = at_target.get(1) {
            let _ = writeln!(out, "next: {name2} ({}, {:.2}x)", seconds(*t2), t2 / t);
        }
    }
    out
}

/// `--long`: the energy error of the long-run methods and of the adaptive method of highest
/// order at a matching cost.
fn long(
    scene: &dyn Scene,
    origin: &str,
    params: &Params,
    args: &Args,
    dir: &std::path::Path,
) -> Result<()> {
    let info = scene.info();
    if args.long_steps < 1000 {
        bail!("--long-steps {}: at least 1000 steps", args.long_steps);
    }
    let methods: Vec<String> = if args.integrators.is_empty() {
        long_run_methods(info)
            .into_iter()
            .map(str::to_string)
            .collect()
    } else {
        args.integrators
            .iter()
            .filter(|n| {
                registry::find(n).is_ok_and(|m| !m.properties.adaptive && !m.properties.exact)
            })
            .cloned()
            .collect()
    };
    if methods.is_empty() {
        bail!(
            "{}: no fixed-step symplectic, variational or Lie-group method to run (the scene \
             takes {})",
            info.name,
            info.integrators().join(", ")
        );
    }
    if let Some(tol) = args.long_tol
        && !(tol > 0.0 && tol < 1.0)
    {
        bail!("--long-tol {tol}: a tolerance between 0 and 1");
    }
    let named_adaptive: Vec<String> = args
        .integrators
        .iter()
        .filter(|n| registry::find(n).is_ok_and(|m| m.properties.adaptive))
        .cloned()
        .collect();
    let h = info.default_step;
    let t_end = h * args.long_steps as f64;
    output::check_folder(dir, &folder_files("long"))?;
    let _lock = output::lock_folder(dir, args.break_lock)?;
    eprintln!(
        "long run        {} ({origin}): {} steps of dt = {h} s, t in [0, {t_end}] s",
        info.name, args.long_steps
    );
    let mut runs: Vec<(String, StepControl)> = methods
        .iter()
        .map(|m| (m.clone(), StepControl::Fixed(h)))
        .collect();
    let adaptive = work_precision::highest_order(info, |m| m.properties.adaptive).map(|m| m.name);
    let mut matched = String::new();
    let probe = (2000.0 * h).min(t_end);
    if let Some(tol) = args.long_tol {
        // Equal cost from the adaptive side: each fixed-step method at the step that costs
        // what the first adaptive method costs at `tol`.
        let adaptive: Vec<String> = if named_adaptive.is_empty() {
            adaptive.map(str::to_string).into_iter().collect()
        } else {
            named_adaptive
        };
        let Some(first) = adaptive.first() else {
            bail!("{}: --long-tol needs an adaptive method", info.name);
        };
        let target = work_precision::cost_per_second(
            scene,
            params,
            first,
            StepControl::Tolerance(tol),
            probe,
        );
        stop_if_interrupted(dir)?;
        let target = target?;
        eprintln!(
            "matching cost   {first} at tol = {tol:e} costs {} per simulated second",
            seconds(target)
        );
        let mut kept = Vec::with_capacity(runs.len());
        for (name, _) in runs {
            let step = work_precision::matching_step(scene, params, &name, h, target, t_end);
            stop_if_interrupted(dir)?;
            match step {
                Ok((step, cost)) if work_precision::cost_distance(cost, target) > 1.5f64.ln() => {
                    eprintln!(
                        "                {name}: left out, no step at that cost (closest that \
                     ran: dt = {step:.4e} s at {:.2}× the cost; its longer steps failed or \
                     cost more)",
                        cost / target
                    )
                }
                Ok((step, cost)) => {
                    eprintln!(
                        "                {name} at dt = {step:.4e} s costs {} ({:.2}×)",
                        seconds(cost),
                        cost / target
                    );
                    kept.push((name, StepControl::Fixed(step)));
                }
                // A step as long as the budget allows can be beyond the method (a Newton
                // solve that no longer converges): said, and the method left out.
                Err(e) => eprintln!("                {name}: left out, no run at that cost: {e}"),
            }
        }
        runs = kept;
        matched = format!("fixed steps at the cost of {first} at tol = {tol:e}");
        runs.extend(
            adaptive
                .into_iter()
                .map(|a| (a, StepControl::Tolerance(tol))),
        );
    } else if let Some(a) = adaptive {
        // The adaptive method of highest order at the cost of the scene's default method (or
        // the first one), probed on 2000 steps.
        let base = if methods.iter().any(|m| m == info.default_integrator) {
            info.default_integrator.to_string()
        } else {
            methods[0].clone()
        };
        let target =
            work_precision::cost_per_second(scene, params, &base, StepControl::Fixed(h), probe);
        stop_if_interrupted(dir)?;
        let target = target?;
        let matching = work_precision::matching_tolerance(scene, params, a, target, probe);
        stop_if_interrupted(dir)?;
        let (tol, cost) = matching?;
        eprintln!(
            "matching cost   {a} at tol = {tol:e} costs {} per simulated second, {base} at \
             dt = {h} s {} (tolerances 1e-4 … 1e-13 tried)",
            seconds(cost),
            seconds(target)
        );
        matched = format!(
            "{a} tol = {tol:e} at {:.2}× the cost of {base}",
            cost / target
        );
        runs.push((a.to_string(), StepControl::Tolerance(tol)));
    }
    let first = runs
        .iter()
        .filter_map(|r| match r.1 {
            StepControl::Fixed(step) => Some(step),
            StepControl::Tolerance(_) => None,
        })
        .fold(h, f64::min);
    let results = work_precision::long_runs(
        scene,
        params,
        &runs,
        t_end,
        first,
        240,
        Some(LONG_FACTOR * args.max_seconds),
    );
    stop_if_interrupted(dir)?;
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(["integrator", "control", "t", "max_energy_rel_err"])?;
    let mut lines = Vec::new();
    let mut table = String::new();
    let _ = writeln!(
        table,
        "{:<14} {:<18} {:>10} {:>12} {:>12} {:>10}",
        "integrator", "step", "steps", "max rel err", "growth t^a", "wall time"
    );
    for r in &results {
        report_long(r, &mut csv, &mut lines, &mut table)?;
    }
    output::write_whole(&dir.join("long.csv"), &csv.into_inner()?)?;
    let record = LongRecord {
        scene: SceneRecord {
            scene: info.name.to_string(),
            parameters: params.iter().map(|(k, v)| (k.to_string(), v)).collect(),
        },
        steps: args.long_steps,
        dt: h,
        equal_cost: args.long_tol.is_some(),
        matched,
    };
    let figure = record.figure(params, lines);
    output::write_whole(
        &dir.join("manifest.json"),
        manifest::to_text(&LongManifest {
            command: "work-precision --long".into(),
            origin: origin.to_string(),
            record,
            provenance: crate::provenance::now(1),
        })?
        .as_bytes(),
    )?;
    for ext in ["png", "svg"] {
        plot::save_with(
            &figure,
            &dir.join(format!("long.{ext}")),
            &args.figure.options()?,
        )?;
    }
    print!("{table}");
    eprintln!("output          {}", dir.display());
    Ok(())
}

fn report_long(
    r: &LongRun,
    csv: &mut csv::Writer<Vec<u8>>,
    lines: &mut Vec<Series>,
    table: &mut String,
) -> Result<()> {
    let control = control_words(r.control);
    let points = r.history.points();
    for (t, e) in &points {
        csv.write_record([
            r.integrator.clone(),
            control.clone(),
            t.to_string(),
            e.to_string(),
        ])?;
    }
    let max = points.iter().map(|p| p.1).fold(0.0f64, f64::max);
    match &r.result {
        Ok(summary) => {
            let _ = writeln!(
                table,
                "{:<14} {:<18} {:>10} {:>12.2e} {:>12} {:>10}",
                r.integrator,
                control,
                summary.steps,
                max,
                r.history
                    .growth_exponent(2.0)
                    .map_or_else(|| "—".into(), |a| format!("{a:.2}")),
                seconds(r.seconds)
            );
        }
        Err(reason) => {
            let _ = writeln!(
                table,
                "{:<14} {:<18} failed: {reason}",
                r.integrator, control
            );
        }
    }
    lines.push(Series::line(long_label(&r.integrator, &control), points));
    Ok(())
}
