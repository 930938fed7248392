//! `tumble plot`: redraws a saved result without recomputing it — a `simulate` CSV (with its
//! `FILE.csv.json` beside it), a sweep, work–precision, long-run or hard-case atlas folder —
//! as PNG, SVG or PDF, with the figure options of every plotting command. The figure comes
//! from [`tumble_plot::saved::figure`], which draws each kind through the code its command
//! draws with (and Python's `tumble.plot` calls too), so with the same data and options the
//! file is the same.

use std::path::PathBuf;

use anyhow::{Result, bail};
use tumble_plot::saved::{self, Choice, SweepFigure};

use super::args::FigureArgs;
use crate::output;
use tumble_plot as plot;

/// Flags of `tumble plot`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A `simulate` CSV (its `FILE.csv.json` beside it), or a sweep, work–precision, long-run
    /// (`work-precision --long`) or hard-case atlas folder.
    #[arg(value_name = "FILE.csv|DIR")]
    pub input: PathBuf,
    /// The figure to write: PNG, SVG or PDF by the extension.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "FILE.png|FILE.svg|FILE.pdf"
    )]
    pub output: PathBuf,
    /// A simulate CSV: the columns to draw (default: every coordinate, rate and diagnostic the
    /// command draws).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub columns: Vec<String>,
    /// A simulate CSV: only the rows with `T0 ≤ t ≤ T1`.
    #[arg(long = "t-range", value_name = "T0,T1")]
    pub t_range: Option<String>,
    /// A sweep: the metric to draw, by its name in `results.csv` (default: the first).
    #[arg(long, value_name = "NAME")]
    pub metric: Option<String>,
    /// A sweep over two axes: the map or its slices.
    #[arg(long, value_enum, default_value = "map")]
    pub figure: SweepFigure,
    /// A sweep: the most rows of the grid to draw as slices.
    #[arg(long, value_name = "N", default_value_t = 5)]
    pub slices: usize,
    /// A sweep map: colour by the base-10 logarithm of the metric.
    #[arg(long = "log-colour")]
    pub log_colour: bool,
    /// A sweep map: its colour map (cividis reads the same with a red–green colour-vision
    /// deficiency; grey prints in black and white).
    #[arg(long = "colour-map", value_enum, default_value = "viridis")]
    pub colour_map: tumble_plot::colour::ColourMap,
    #[command(flatten)]
    pub style: FigureArgs,
}

/// Runs the subcommand.
///
/// # Errors
/// An input that is none of the five kinds, or damaged; an unknown column or metric; bad
/// figure options; an output that cannot be written. All before anything is written.
pub fn run(args: &Args) -> Result<()> {
    plot::Format::from_path(&args.output)?;
    let opts = args.style.options()?;
    let dest = output::Destination::check(&args.output)?;
    if args.slices == 0 {
        bail!("--slices 0: draw at least one slice");
    }
    let choice = Choice {
        columns: args.columns.clone(),
        t_range: args.t_range.as_deref().map(parse_range).transpose()?,
        metric: args.metric.clone(),
        figure: args.figure,
        slices: args.slices,
        log_colour: args.log_colour,
        colour_map: args.colour_map,
    };
    let figure = saved::figure(&args.input, &choice)?;
    plot::save_to(&figure, &dest, &opts)?;
    eprintln!("plot         {}", args.output.display());
    Ok(())
}

/// `T0,T1` with `T0 < T1`.
fn parse_range(s: &str) -> Result<(f64, f64)> {
    let parsed: Option<(f64, f64)> = s
        .split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)));
    match parsed {
        Some((a, b)) if a < b => Ok((a, b)),
        _ => bail!("--t-range {s}: expected T0,T1 with T0 < T1 (seconds)"),
    }
}
