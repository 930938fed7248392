//! `tumble view`: a run (a built-in scene or a scene file) as one self-contained HTML page —
//! the bodies in 3D with their axes, the angular velocity and angular momentum, a trail, play,
//! pause, speed and scrub, a camera to turn and zoom, and the run's columns plotted beside it
//! with a cursor at the time shown; or, with `--inertia`, the principal-axes explorer of a body
//! (the sources of `tumble inertia`): Euler-angle sliders turning the body while the lab-frame
//! inertia tensor is recomputed. The page needs no server and no network.

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::ArgMatches;
use tumble_scenarios::scene::Rows;
use tumble_scenarios::{Params, Scene, drawing};
use tumble_studies::simulation::{self, Naming, RunRequest, is_scene_file};

use super::inertia::BodyArgs;
use super::simulate::{SceneArgs, load_scene, number};
use crate::view::{self, App, run::Drawing};

/// Flags of `tumble view`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A built-in scene or a TOML scene file; with --inertia, the body's mesh files (OBJ or
    /// STL), if any.
    #[arg(value_name = "SCENE | FILE")]
    pub inputs: Vec<String>,
    /// The principal-axes explorer of a body given as `tumble inertia` takes it (mesh files,
    /// --shape, --point, --points, --mass, --density, --units; an --euler before any --shape
    /// sets the sliders' starting angles) instead of a run.
    #[arg(long)]
    pub inertia: bool,
    #[command(flatten)]
    pub body: BodyArgs,
    /// Set a parameter of the scene, over its default or the scene file's value; repeat for
    /// several (as `simulate --set`).
    #[arg(long = "set", value_name = "KEY=VALUE", allow_hyphen_values = true, action = clap::ArgAction::Append)]
    pub set: Vec<String>,
    /// Integrator [default: the scene file's, else the scene's].
    #[arg(long, value_name = "NAME")]
    pub integrator: Option<String>,
    /// Simulated seconds [default: the scene file's, else the scene's horizon].
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Seconds between the frames stored in the page, from the integrator's dense output; the
    /// page interpolates between them.
    #[arg(long = "output-dt", value_name = "DT", default_value_t = 1.0 / 60.0, allow_negative_numbers = true)]
    pub output_dt: f64,
    /// The HTML file to write.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "FILE.html",
        default_value = "out/view.html"
    )]
    pub output: PathBuf,
}

/// Most frames a page may hold (a frame is about 40 numbers, 200 bytes of the page).
const MAX_FRAMES: f64 = 100_000.0;

/// Runs the subcommand; `matches` orders the body flags that follow a `--shape`.
///
/// # Errors
/// Invalid flags (before any step), a scene without a 3D view, a failing run, an unwritable
/// output.
pub fn run(args: &Args, matches: Option<&ArgMatches>) -> Result<()> {
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"))
    {
        bail!(
            "-o {}: the page is HTML; give a file ending in .html",
            args.output.display()
        );
    }
    if args.inertia {
        explorer(args, matches)
    } else {
        run_view(args)
    }
}

/// `tumble view SCENE`.
fn run_view(args: &Args) -> Result<()> {
    if args.body.any() {
        bail!(
            "--units, --mass, --density, --euler, --shape, --at, --point, --points and \
             --flip-inverted describe a body for --inertia; a scene's body comes from the scene \
             (a scene file's [body] table)"
        );
    }
    let [scene_arg] = args.inputs.as_slice() else {
        bail!(
            "give one scene (a built-in name or a .toml scene file), or --inertia and a body; \
             got {} arguments",
            args.inputs.len()
        );
    };
    if !(args.output_dt.is_finite() && args.output_dt > 0.0) {
        bail!(
            "--output-dt {}: expected a positive number of seconds",
            number(args.output_dt)
        );
    }
    let target = SceneArgs {
        scene: scene_arg.clone(),
        set: args.set.clone(),
    };
    let loaded = load_scene(&target)?;
    let info = loaded.scene.info();
    let drawing = drawing_of(Some(scene_arg), loaded.scene, &loaded.params)?;
    let request = RunRequest {
        integrator: args.integrator.clone(),
        t_end: args.t_end,
        output_dt: Some(args.output_dt),
        cancel: Some(tumble_scenarios::scene::CancelFlag(crate::signals::flag())),
        ..RunRequest::default()
    };
    let mut options = loaded.options(&request);
    // The page's frames replace the scene file's own output rows.
    options.every = None;
    let plan = options
        .resolve(info)
        .map_err(|e| anyhow::anyhow!("{}: {e}", info.name))?;
    simulation::check_resolution(loaded.scene, &loaded.params, &plan, Naming::Cli)?;
    if plan.t_end / args.output_dt > MAX_FRAMES {
        bail!(
            "--output-dt {}: {:.0} frames over t_end = {}, more than {MAX_FRAMES}; give a \
             larger --output-dt or a shorter --t-end",
            number(args.output_dt),
            plan.t_end / args.output_dt,
            number(plan.t_end)
        );
    }
    let dest = crate::output::check_all([("-o", args.output.as_path())])?;
    if is_scene_file(scene_arg) {
        crate::output::refuse_input(
            "-o",
            &dest[0],
            std::path::Path::new(scene_arg),
            "the scene file",
        )?;
    }
    let mut rows = Rows::default();
    let summary = crate::signals::simulated(
        loaded.scene.simulate(&loaded.params, &plan, &mut rows),
        &args.output,
    )?;
    let columns = info.columns();
    let mut data = drawing.data(&columns, &rows.0)?;
    let title = format!("{} — {}", info.name, plan.integrator());
    data["title"] = title.clone().into();
    data["scene"] = info.name.into();
    data["origin"] = loaded.origin.clone().into();
    data["integrator"] = plan.integrator().into();
    data["t_end"] = plan.t_end.into();
    data["max_energy_rel_err"] = summary.max_energy_rel_err.into();
    let html = view::page(App::Run, &title, &data);
    dest[0].write_all(html.as_bytes())?;
    eprintln!(
        "view         {} frames of {} over t in [0, {}] s ({}), every {} s",
        rows.0.len(),
        info.name,
        number(plan.t_end),
        plan.integrator(),
        number(args.output_dt)
    );
    eprintln!(
        "output       {} ({:.0} kB)",
        args.output.display(),
        html.len() as f64 / 1e3
    );
    Ok(())
}

/// `tumble view --inertia BODY…`.
fn explorer(args: &Args, matches: Option<&ArgMatches>) -> Result<()> {
    let scene_flags = [
        (!args.set.is_empty(), "--set"),
        (args.integrator.is_some(), "--integrator"),
        (args.t_end.is_some(), "--t-end"),
    ];
    if let Some((_, flag)) = scene_flags.iter().find(|(given, _)| *given) {
        bail!("{flag} belongs to a run; --inertia shows a body, not a run");
    }
    let files: Vec<PathBuf> = args.inputs.iter().map(PathBuf::from).collect();
    let mut flags = super::inertia::ordered(&args.body, matches).unwrap_or_else(|e| {
        clap::Error::raw(clap::error::ErrorKind::ArgumentConflict, format!("{e}\n")).exit()
    });
    // The whole body's --euler starts the sliders instead of turning the body.
    let start = flags
        .turn
        .take()
        .map(|t| super::args::parse_triple("euler", &t))
        .transpose()?
        .unwrap_or_default();
    let assembled = super::inertia::assemble(&files, &args.body, &flags)?;
    let dest = crate::output::check_all([("-o", args.output.as_path())])?;
    for file in &files {
        crate::output::refuse_input("-o", &dest[0], file, "the mesh file")?;
    }
    let mut data = view::explorer::data(
        &assembled.body,
        &assembled.parts,
        &assembled.sources,
        &start,
    );
    let title = format!("principal axes — {}", assembled.sources.join("; "));
    data["title"] = title.clone().into();
    let html = view::page(App::Explorer, &title, &data);
    dest[0].write_all(html.as_bytes())?;
    eprintln!(
        "explorer     {} (mass {} kg)",
        assembled.sources.join("; "),
        number(assembled.body.mass())
    );
    eprintln!(
        "output       {} ({:.0} kB)",
        args.output.display(),
        html.len() as f64 / 1e3
    );
    Ok(())
}

/// The drawing of a run: a scene file's `[body]` when `scene_arg` names a scene file with
/// one, else what `scene` declares ([`Drawing::of_scene`]: a model's bodies and point masses,
/// a built-in scene's bodies).
///
/// # Errors
/// A scene file that cannot be read, a scene with no 3D view.
pub fn drawing_of(
    scene_arg: Option<&str>,
    scene: &'static dyn Scene,
    params: &Params,
) -> Result<Drawing> {
    if let Some(path) = scene_arg
        .filter(|a| is_scene_file(a))
        .map(std::path::Path::new)
        .filter(|path| !tumble_model::is_model_file(path))
        && let Some(body) = drawing::of_scene_file(path)?
    {
        return Ok(Drawing::of_body(&body, params));
    }
    Drawing::of_scene(scene, params)
}
