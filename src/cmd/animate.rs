//! `tumble animate`: a scene in motion as an animated GIF, or an MP4 for slides (encoded by
//! `ffmpeg` when it is installed), drawn as `tumble view` draws it — the bodies shaded in 3D
//! (the hoop as a torus with its bead, the free body as its equivalent box, the T-handle's
//! mesh, the top's axis and disk, a scene file's `[body]`), the lab and body axes, the ω and L
//! arrows and a smooth trail — with a readout of the time and the energy error. Frames are the
//! scene's rows at equal times from the integrator's dense output (`--at`); the trail passes
//! through rows at least eight times as dense (and 4000 over the run at least). The animation
//! does not depend on the steps.

use std::path::PathBuf;

use anyhow::{Result, bail};
use tumble_integrators::Flow;
use tumble_scenarios::{Recorder, RunOptions};

use super::simulate::{LoadedScene, SceneArgs, load_scene};
use crate::animation::{Captions, Container, caption, write};
use crate::view::render::{Canvas, Renderer};

/// Flags of `tumble animate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene and its parameter overrides, or a saved `simulate` CSV (`FILE.csv`, its
    /// `FILE.csv.json` beside it) to animate without recomputing.
    #[command(flatten)]
    pub target: SceneArgs,
    /// Simulated seconds [default: the scene's horizon].
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Frames per second of the animation.
    #[arg(long, value_name = "FPS", default_value_t = 25.0)]
    pub fps: f64,
    /// Playing time of the animation in seconds [default: the simulated time, at most 20 s].
    #[arg(long, value_name = "SECONDS")]
    pub duration: Option<f64>,
    /// Frame size in pixels, `WxH` [default: 640x480 for a GIF, 1280x720 for an MP4].
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Output file: `.gif`, or `.mp4` (H.264, encoded by ffmpeg, which must be installed).
    #[arg(
        short = 'o',
        long = "output",
        value_name = "FILE",
        default_value = "out/animation.gif"
    )]
    pub output: PathBuf,
}

/// Keeps every row.
#[derive(Default)]
struct Rows(Vec<Vec<f64>>);

impl Recorder for Rows {
    fn row(&mut self, values: &[f64]) -> Flow {
        self.0.push(values.to_vec());
        Flow::Continue
    }
}

/// Most frames an animation may have.
const MAX_FRAMES: u64 = 10_000;
/// Fewest rows per frame interval: the trail passes through them.
const TRAIL_ROWS: usize = 8;
/// Fewest rows over the run (a short animation of a fast body still has a smooth trail).
const TRAIL_POINTS: usize = 4000;
/// Device pixels per frame pixel while drawing (averaged down: smooth edges).
const SUPERSAMPLE: u32 = 2;

/// Runs the subcommand.
///
/// # Errors
/// Invalid flags (before any step), a scene without a 3D view, a failing run, an unwritable
/// output.
pub fn run(args: &Args) -> Result<()> {
    // SIGINT and SIGTERM stop the simulation at a step and the drawing between frames; the
    // output is then not written.
    crate::signals::flag();
    let csv = args.target.scene.to_ascii_lowercase().ends_with(".csv");
    let ext = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let container = match ext.as_deref() {
        Some("gif") => Container::Gif,
        Some("mp4") => Container::Mp4,
        _ => bail!(
            "{}: expected a .gif file (or .mp4 with ffmpeg installed)",
            args.output.display()
        ),
    };
    let (w, h) = match (&args.size, container) {
        (Some(text), _) => parse_size(text)?,
        (None, Container::Gif) => (640, 480),
        (None, Container::Mp4) => (1280, 720),
    };
    if container == Container::Mp4 && (w % 2 != 0 || h % 2 != 0) {
        bail!("--size {w}x{h}: an MP4's sides are even numbers of pixels, e.g. 1280x720");
    }
    if container == Container::Mp4 {
        ffmpeg_present(&args.output)?;
    }
    if !(args.fps.is_finite() && args.fps > 0.0 && args.fps <= 100.0) {
        bail!(
            "--fps {}: expected a number of frames per second in (0, 100]",
            args.fps
        );
    }
    let (scene, params, saved, drawing) = if csv {
        if !args.target.set.is_empty() {
            bail!("--set changes a simulation's parameters; a saved CSV keeps its own");
        }
        if args.t_end.is_some() {
            bail!("--t-end: a saved CSV is shown over all its rows");
        }
        let path = std::path::Path::new(&args.target.scene);
        let (record_path, record) = tumble_plot::saved::run_record(path)?;
        let (scene, params) = tumble_plot::saved::recorded_scene(
            &record.scene,
            &record.origin,
            &record.parameters,
            &record_path,
        )?;
        let drawing = super::view::drawing_of(None, scene, &params)?;
        let saved = tumble_plot::saved::read_columns(path)?;
        (scene, params, Some((saved, record)), drawing)
    } else {
        let LoadedScene { scene, params, .. } = load_scene(&args.target)?;
        let drawing = super::view::drawing_of(Some(&args.target.scene), scene, &params)?;
        (scene, params, None, drawing)
    };
    let info = scene.info();
    let t_end = match &saved {
        Some(((_, values), _)) => match values.first().map(Vec::as_slice) {
            Some([first, .., last]) if last > first => last - first,
            _ => bail!("{}: fewer than two rows to animate", args.target.scene),
        },
        None => args.t_end.unwrap_or(info.default_t_end),
    };
    if !(t_end.is_finite() && t_end > 0.0) {
        bail!("--t-end {t_end}: expected a positive number of seconds");
    }
    let duration = args.duration.unwrap_or(t_end.min(20.0));
    if !(duration.is_finite() && duration > 0.0) {
        bail!("--duration {duration}: expected a positive number of seconds");
    }
    let frames = (duration * args.fps).round() as u64 + 1;
    if frames > MAX_FRAMES {
        bail!(
            "--duration {duration} at --fps {}: {frames} frames, more than {MAX_FRAMES}",
            args.fps
        );
    }
    crate::output::check_all([("-o", args.output.as_path())])?;

    // Rows at the frames' times and `per_frame - 1` times between each two: at least
    // TRAIL_ROWS, and at least TRAIL_POINTS over the run.
    let frames = frames as usize;
    let intervals = (frames - 1).max(1);
    let per_frame = TRAIL_ROWS.max(TRAIL_POINTS.div_ceil(intervals));
    let dense = per_frame * intervals;
    let times: Vec<f64> = (0..=dense)
        .map(|k| t_end * k as f64 / dense as f64)
        .collect();
    let (rows, columns, integrator) = match saved {
        Some(((columns, values), record)) => {
            let integrator = record.integrator.clone();
            (saved_rows(&values, &times), columns, integrator)
        }
        None => {
            let mut plan = RunOptions {
                t_end: Some(t_end),
                at: Some(times),
                ..RunOptions::default()
            }
            .resolve(info)?;
            plan.cancel = Some(tumble_scenarios::scene::CancelFlag(crate::signals::flag()));
            let mut rows = Rows::default();
            crate::signals::simulated(scene.simulate(&params, &plan, &mut rows), &args.output)?;
            (rows.0, info.columns(), plan.integrator().to_string())
        }
    };
    let poses = drawing.frames(&columns, &rows)?;
    let energy = columns.iter().position(|c| c == "energy_rel_err");
    let title = format!("{}: {integrator}", info.name);
    let big = (w * SUPERSAMPLE, h * SUPERSAMPLE);
    let renderer = Renderer::new(&drawing, big, f64::from(SUPERSAMPLE));
    let mut canvas = Canvas::new(big);
    // Frame k is row k·per_frame (the last row, when one frame only).
    let row_of = |k: usize| (k * per_frame).min(rows.len() - 1);
    write(
        &args.output,
        container,
        (w, h),
        args.fps,
        frames,
        &mut |k, rgb| {
            let r = row_of(k);
            let labels = renderer.draw(&mut canvas, &poses, r, &poses.trail[..=r]);
            let row = &rows[r];
            let text = format!(
                "t = {:.2} s{}",
                row[0],
                energy.map_or(String::new(), |e| format!(
                    "    relative energy error {:.1e}",
                    row[e]
                ))
            );
            caption(
                &mut canvas.rgb,
                big,
                f64::from(SUPERSAMPLE),
                &Captions {
                    title: &title,
                    caption: &text,
                    labels: &labels,
                },
            )?;
            rgb.copy_from_slice(&tumble_plot::downsample(&canvas.rgb, (w, h), SUPERSAMPLE));
            Ok(())
        },
    )?;
    eprintln!(
        "animation    {frames} frames of {} over t in [0, {t_end}] s, {duration:.1} s at {} fps, \
         {w}x{h}",
        info.name, args.fps
    );
    eprintln!("output       {}", args.output.display());
    Ok(())
}

/// The rows of a saved CSV (`values` column by column, `t` first) nearest the frame times
/// `times` (measured from its first row): rows at equal times when the CSV has them
/// (`simulate --output-dt`).
fn saved_rows(values: &[Vec<f64>], times: &[f64]) -> Vec<Vec<f64>> {
    let t = values.first().map_or(&[][..], Vec::as_slice);
    let t0 = t.first().copied().unwrap_or(0.0);
    times
        .iter()
        .map(|&s| {
            let target = t0 + s;
            let i = t.partition_point(|&x| x < target).min(t.len() - 1);
            let k = if i > 0 && (target - t[i - 1]) <= (t[i] - target) {
                i - 1
            } else {
                i
            };
            values.iter().map(|column| column[k]).collect()
        })
        .collect()
}

/// Checks that `ffmpeg` runs, for writing `output` as MP4.
fn ffmpeg_present(output: &std::path::Path) -> Result<()> {
    let runs = std::process::Command::new("ffmpeg")
        .arg("-version")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !runs {
        bail!(
            "{}: an MP4 is encoded by ffmpeg, which is not installed (not found on PATH); \
             install it (Debian: apt-get install ffmpeg) or write a .gif",
            output.display()
        );
    }
    Ok(())
}

/// `WxH` in pixels, each 64…4096.
fn parse_size(text: &str) -> Result<(u32, u32)> {
    let parsed = text
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)));
    match parsed {
        Some((w, h)) if (64..=4096).contains(&w) && (64..=4096).contains(&h) => Ok((w, h)),
        _ => bail!("--size {text}: expected WxH in pixels, each 64 to 4096, e.g. 640x480"),
    }
}
