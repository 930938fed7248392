//! `tumble animate`: a scene in motion as an animated GIF (or an MP4, encoded by `ffmpeg` when
//! it is installed) — the hoop as a ring with its bead, the free body as its equivalent box,
//! the T-handle as the outline of its mesh, the top as its axis and disk — with a trail and a
//! readout of the time and the energy error. Frames are the scene's rows at equal times, from
//! the integrator's dense output (`--at`), so the animation does not depend on the steps.

use std::path::PathBuf;

use anyhow::{Result, bail};
use plotters::style::RGBColor;
use tumble_integrators::Flow;
use tumble_scenarios::{Params, Recorder, RunOptions, Scene};

use super::simulate::{LoadedScene, SceneArgs, load_scene};
use crate::plot::animation::{Line, Shot, View, circle, write_gif};

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
    /// Frame size in pixels, `WxH`.
    #[arg(long, value_name = "WxH", default_value = "640x480")]
    pub size: String,
    /// Output file: `.gif`, or `.mp4` (encoded by ffmpeg, which must be installed).
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
    let (scene, params, saved) = if csv {
        if !args.target.set.is_empty() {
            bail!("--set changes a simulation's parameters; a saved CSV keeps its own");
        }
        if args.t_end.is_some() {
            bail!("--t-end: a saved CSV is shown over all its rows");
        }
        let path = std::path::Path::new(&args.target.scene);
        let (record_path, record) = super::plot::simulation_record(path)?;
        let (scene, params) = super::plot::scene_and_parameters(&record, &record_path)?;
        let saved = super::plot::read_columns(path)?;
        (scene, params, Some((saved, record)))
    } else {
        let LoadedScene { scene, params, .. } = load_scene(&args.target)?;
        (scene, params, None)
    };
    let info = scene.info();
    let ext = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let mp4 = match ext.as_deref() {
        Some("gif") => false,
        Some("mp4") => {
            ffmpeg_present(&args.output)?;
            true
        }
        _ => bail!(
            "{}: expected a .gif file (or .mp4 with ffmpeg installed)",
            args.output.display()
        ),
    };
    let (w, h) = parse_size(&args.size)?;
    if !(args.fps.is_finite() && args.fps > 0.0 && args.fps <= 100.0) {
        bail!(
            "--fps {}: expected a number of frames per second in (0, 100]",
            args.fps
        );
    }
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
    let painter = Painter::of(scene, &params)?;
    crate::output::check_all([("-o", args.output.as_path())])?;

    let times: Vec<f64> = (0..frames)
        .map(|k| t_end * k as f64 / (frames - 1).max(1) as f64)
        .collect();
    let (rows, columns, integrator) = match saved {
        Some(((columns, values), record)) => {
            let integrator = record["integrator"].as_str().unwrap_or("?").to_string();
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
    let col = |name: &str| columns.iter().position(|c| c == name);
    let energy = col("energy_rel_err");
    let mut trail: Vec<[f64; 3]> = Vec::new();
    let shots: Vec<Shot> = rows
        .iter()
        .map(|row| {
            let mut shot = painter.shot(row, &col);
            if let Some(&tip) = shot.dots.first().map(|(p, _, _)| p) {
                trail.push(tip);
                let keep = trail.len().saturating_sub(3 * args.fps as usize);
                shot.lines.insert(
                    0,
                    Line {
                        points: trail[keep..].to_vec(),
                        colour: RGBColor(0xE6, 0x9F, 0x00),
                        width: 1,
                    },
                );
            }
            shot.caption = format!(
                "t = {:.2} s{}",
                row[0],
                energy.map_or(String::new(), |k| format!(
                    "    relative energy error {:.1e}",
                    row[k]
                ))
            );
            shot
        })
        .collect();
    let view = View {
        size: (w, h),
        azimuth: 0.6,
        elevation: 0.35,
        radius: painter.radius,
    };
    let title = format!("{}: {integrator}", info.name);
    if mp4 {
        // The GIF's frames (a temporary file), encoded by ffmpeg (even dimensions, yuv420p:
        // what players take) into a file beside the output, renamed over it when complete.
        let gif = tempfile::Builder::new().suffix(".gif").tempfile()?;
        write_gif(gif.path(), &view, &title, &shots, args.fps)?;
        let dest = crate::output::Destination::check(&args.output)?;
        let scratch = dest.scratch()?;
        let status = std::process::Command::new("ffmpeg")
            .args(["-y", "-loglevel", "error", "-i"])
            .arg(gif.path())
            .args([
                "-vf",
                "scale=trunc(iw/2)*2:trunc(ih/2)*2",
                "-pix_fmt",
                "yuv420p",
                "-movflags",
                "+faststart",
                "-f",
                "mp4",
            ])
            .arg(scratch.as_os_str())
            .status()?;
        if let Some(code) = crate::signals::interrupted() {
            return Err(crate::signals::Interrupted {
                code,
                message: format!("{} was not written", args.output.display()),
            }
            .into());
        }
        if !status.success() {
            bail!("{}: ffmpeg failed ({status})", args.output.display());
        }
        dest.commit_scratch(scratch)?;
    } else {
        write_gif(&args.output, &view, &title, &shots, args.fps)?;
    }
    eprintln!(
        "animation    {} frames of {} over t in [0, {t_end}] s, {:.1} s at {} fps",
        shots.len(),
        info.name,
        duration,
        args.fps
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

/// The `dzhanibekov` scene's T-handle: the outline of its mesh (front cap, corners 0–7, and
/// back cap, 8–15, as [`tumble_inertia::THandle::mesh`] orders them) about its centre of mass,
/// in the frame its orientation rotates; the trail follows the intermediate principal axis,
/// the one it flips about.
fn t_handle() -> Result<Painter> {
    use tumble_inertia::{MassSpec, THandle};
    let mesh = THandle::STANDARD.mesh()?;
    let props = THandle::STANDARD.mass_properties(MassSpec::TotalMass(1.0))?;
    let c = props.center_of_mass();
    let v: Vec<[f64; 3]> = mesh
        .vertices()
        .iter()
        .map(|p| [p.x - c.x, p.y - c.y, p.z - c.z])
        .collect();
    if v.len() != 16 {
        bail!("the T-handle mesh has {} vertices, not 16", v.len());
    }
    let reach = v
        .iter()
        .map(|p| p.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let closed = |k: std::ops::Range<usize>| {
        let mut l = v[k.clone()].to_vec();
        l.push(v[k.start]);
        l
    };
    let axis = props.principal().axes.matrix().column(1).into_owned() * 1.1 * reach;
    Ok(Painter {
        look: Look::Prism {
            front: closed(0..8),
            back: closed(8..16),
            tip: [axis.x, axis.y, axis.z],
        },
        radius: 1.3 * reach,
    })
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

/// What a scene's body looks like.
enum Look {
    /// A ring of radius `a` in the body x-y plane, the bead at angle `alpha` on it.
    FreeHoop { a: f64 },
    /// A vertical ring turned by `phi` about the vertical (or driven at `omega`).
    VerticalHoop { a: f64, omega: Option<f64> },
    /// A box with half-extents along the body axes.
    Box { half: [f64; 3] },
    /// A symmetric top: its axis along body z from the pivot and a disk at its end.
    Top,
    /// A prism (the T-handle): its front and back outlines and the point the trail follows,
    /// in the body frame about the centre of mass.
    Prism {
        front: Vec<[f64; 3]>,
        back: Vec<[f64; 3]>,
        tip: [f64; 3],
    },
}

/// Draws a scene's rows.
struct Painter {
    look: Look,
    radius: f64,
}

impl Painter {
    fn of(scene: &dyn Scene, params: &Params) -> Result<Self> {
        let name = scene.info().name;
        let get = |p: &str| params.get(p);
        Ok(match name {
            "free-hoop" => {
                let a = get("a")?;
                Painter {
                    look: Look::FreeHoop { a },
                    radius: 1.2 * a,
                }
            }
            "spinning-hoop" | "driven-hoop" => {
                let a = get("a")?;
                Painter {
                    look: Look::VerticalHoop {
                        a,
                        omega: (name == "driven-hoop").then(|| get("omega")).transpose()?,
                    },
                    radius: 1.2 * a,
                }
            }
            "free-body" => {
                let half =
                    crate::view::geometry::equivalent_box([get("I1")?, get("I2")?, get("I3")?]);
                Painter {
                    look: Look::Box { half },
                    radius: 1.6,
                }
            }
            "heavy-top" => Painter {
                look: Look::Top,
                radius: 1.5,
            },
            "dzhanibekov" => t_handle()?,
            other => bail!(
                "animate draws free-hoop, spinning-hoop, driven-hoop, free-body, dzhanibekov and \
                 heavy-top; `{other}` has no 3D view"
            ),
        })
    }

    /// The frame of one row; its first dot is the point the trail follows.
    fn shot(&self, row: &[f64], col: &dyn Fn(&str) -> Option<usize>) -> Shot {
        let value = |name: &str| col(name).map_or(0.0, |k| row[k]);
        let blue = RGBColor(0x00, 0x72, 0xB2);
        let red = RGBColor(0xD5, 0x5E, 0x00);
        let rotate = |v: [f64; 3]| -> [f64; 3] {
            let (w, x, y, z) = (value("qw"), value("qx"), value("qy"), value("qz"));
            let q =
                nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            let r = q * nalgebra::Vector3::new(v[0], v[1], v[2]);
            [r.x, r.y, r.z]
        };
        let mut shot = Shot::default();
        match self.look {
            Look::FreeHoop { a } => {
                let alpha = value("alpha");
                let (u, v, n) = (
                    rotate([1.0, 0.0, 0.0]),
                    rotate([0.0, 1.0, 0.0]),
                    rotate([0.0, 0.0, 1.0]),
                );
                let bead = rotate([a * alpha.cos(), a * alpha.sin(), 0.0]);
                shot.dots.push((bead, 6, red));
                shot.lines.push(Line {
                    points: circle([0.0; 3], u, v, a, 96),
                    colour: blue,
                    width: 3,
                });
                shot.lines.push(Line {
                    points: vec![[0.0; 3], n.map(|c| c * 0.5 * a)],
                    colour: RGBColor(0x00, 0x9E, 0x73),
                    width: 2,
                });
            }
            Look::VerticalHoop { a, omega } => {
                let phi = omega.map_or_else(|| value("phi"), |w| w * row[0]);
                let alpha = value("alpha");
                let (s, c) = phi.sin_cos();
                let u = [c, s, 0.0];
                let bead = [a * alpha.sin() * c, a * alpha.sin() * s, -a * alpha.cos()];
                shot.dots.push((bead, 6, red));
                shot.lines.push(Line {
                    points: circle([0.0; 3], u, [0.0, 0.0, 1.0], a, 96),
                    colour: blue,
                    width: 3,
                });
            }
            Look::Box { half } => {
                let corner =
                    |sx: f64, sy: f64, sz: f64| rotate([sx * half[0], sy * half[1], sz * half[2]]);
                // The twelve edges as four closed loops and four struts.
                for sz in [-1.0, 1.0] {
                    shot.lines.push(Line {
                        points: vec![
                            corner(-1.0, -1.0, sz),
                            corner(1.0, -1.0, sz),
                            corner(1.0, 1.0, sz),
                            corner(-1.0, 1.0, sz),
                            corner(-1.0, -1.0, sz),
                        ],
                        colour: blue,
                        width: 2,
                    });
                }
                for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    shot.lines.push(Line {
                        points: vec![corner(sx, sy, -1.0), corner(sx, sy, 1.0)],
                        colour: blue,
                        width: 2,
                    });
                }
                // The trail follows the end of the intermediate axis (the Dzhanibekov flip).
                shot.dots
                    .insert(0, (rotate([0.0, 1.2 * half[1].max(0.3), 0.0]), 5, red));
            }
            Look::Prism {
                ref front,
                ref back,
                tip,
            } => {
                shot.dots.push((rotate(tip), 5, red));
                for outline in [front, back] {
                    shot.lines.push(Line {
                        points: outline.iter().map(|&p| rotate(p)).collect(),
                        colour: blue,
                        width: 2,
                    });
                }
                for (&a, &b) in front.iter().zip(back).take(front.len() - 1) {
                    shot.lines.push(Line {
                        points: vec![rotate(a), rotate(b)],
                        colour: blue,
                        width: 2,
                    });
                }
            }
            Look::Top => {
                let tip = rotate([0.0, 0.0, 1.0]);
                shot.dots.push((tip, 4, red));
                shot.lines.push(Line {
                    points: vec![[0.0; 3], tip],
                    colour: RGBColor(0x00, 0x9E, 0x73),
                    width: 3,
                });
                shot.lines.push(Line {
                    points: circle(
                        tip,
                        rotate([1.0, 0.0, 0.0]),
                        rotate([0.0, 1.0, 0.0]),
                        0.4,
                        64,
                    ),
                    colour: blue,
                    width: 3,
                });
            }
        }
        shot
    }
}
