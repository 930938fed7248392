//! `tumble sweep diff A B`: the largest difference of each metric between two sweeps of the
//! same grid (a step-halving check, another method, another tool's results written as a sweep
//! folder), and where it is.
//!
//! Exit status: 0; with `--tolerance TOL`, 4 when a metric differs by more than `TOL`, or a
//! point's status or a metric's definedness differs (the self-check's code); 1 for folders
//! that cannot be compared.

use std::fmt;
use std::path::PathBuf;

use anyhow::Result;
use tumble_studies::sweep::{self, SweepDiff, compare::format_point};

/// Flags of `tumble sweep diff`.
#[derive(clap::Args, Debug)]
pub struct DiffArgs {
    /// The first sweep folder (with `sweep.toml` and `results.csv`).
    #[arg(value_name = "A")]
    pub a: PathBuf,
    /// The second sweep folder, a sweep of the same grid.
    #[arg(value_name = "B")]
    pub b: PathBuf,
    /// Exit with status 4 when a metric differs by more than TOL (or a status or a metric's
    /// definedness differs).
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// Print the comparison as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Two sweeps differ by more than the tolerance: exit status 4.
#[derive(Debug)]
pub struct Differ {
    /// The largest difference.
    pub largest: f64,
    /// The tolerance.
    pub tolerance: f64,
    /// Points whose status differs, metrics defined in one sweep only.
    pub mismatches: u64,
}

impl fmt::Display for Differ {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the sweeps differ by {:.2e}, more than the tolerance {:.1e}",
            self.largest, self.tolerance
        )?;
        if self.mismatches > 0 {
            write!(
                f,
                " ({} points with a different status or a metric defined in one only)",
                self.mismatches
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for Differ {}

impl Differ {
    /// The exit status (the self-check's).
    pub const EXIT_CODE: u8 = 4;
}

/// Runs `tumble sweep diff`.
///
/// # Errors
/// Folders that cannot be read or compared; [`Differ`] above the tolerance.
pub fn run(args: &DiffArgs) -> Result<()> {
    if let Some(t) = args.tolerance
        && !(t.is_finite() && t >= 0.0)
    {
        anyhow::bail!("--tolerance {t}: give a finite, non-negative difference");
    }
    let d = sweep::diff_folders(&args.a, &args.b)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&json(&d))?);
    } else {
        print!("{}", table(&d, &args.a, &args.b));
    }
    let mismatches =
        d.status_differs.len() as u64 + d.metrics.iter().map(|m| m.defined_in_one).sum::<u64>();
    match args.tolerance {
        Some(tolerance) if d.largest() > tolerance || d.largest().is_nan() || mismatches > 0 => {
            Err(Differ {
                largest: d.largest(),
                tolerance,
                mismatches,
            }
            .into())
        }
        _ => Ok(()),
    }
}

/// The comparison as a table.
fn table(d: &SweepDiff, a: &std::path::Path, b: &std::path::Path) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} and {}: {} points over {}",
        a.display(),
        b.display(),
        d.points,
        d.axes.join(" x ")
    );
    let width = d
        .metrics
        .iter()
        .map(|m| m.metric.len())
        .max()
        .unwrap_or(6)
        .max(6);
    let _ = writeln!(
        s,
        "{:width$}  {:>10}  {:>10}  {:>8}  {:>9}  where",
        "metric", "largest", "relative", "compared", "one-sided"
    );
    for m in &d.metrics {
        let at = m.at.as_ref().map_or_else(String::new, |(i, values)| {
            format!("point {i} ({})", format_point(&d.axes, values))
        });
        let _ = writeln!(
            s,
            "{:width$}  {:>10.3e}  {:>10.3e}  {:>8}  {:>9}  {at}",
            m.metric, m.largest, m.relative, m.compared, m.defined_in_one
        );
    }
    if !d.status_differs.is_empty() {
        let shown: Vec<String> = d
            .status_differs
            .iter()
            .take(20)
            .map(ToString::to_string)
            .collect();
        let _ = writeln!(
            s,
            "status differs at {} points: {}{}",
            d.status_differs.len(),
            shown.join(", "),
            if d.status_differs.len() > 20 {
                ", …"
            } else {
                ""
            }
        );
    }
    for (list, which) in [(&d.only_in_first, a), (&d.only_in_second, b)] {
        if !list.is_empty() {
            let _ = writeln!(
                s,
                "recorded only by {}: {}",
                which.display(),
                list.join(", ")
            );
        }
    }
    s
}

fn json(d: &SweepDiff) -> serde_json::Value {
    serde_json::json!({
        "axes": d.axes,
        "points": d.points,
        "largest": d.largest(),
        "metrics": d.metrics.iter().map(|m| serde_json::json!({
            "metric": m.metric,
            "largest": m.largest,
            "relative": m.relative,
            "at_point": m.at.as_ref().map(|(i, _)| i),
            "at_values": m.at.as_ref().map(|(_, v)| v),
            "compared": m.compared,
            "defined_in_one": m.defined_in_one,
        })).collect::<Vec<_>>(),
        "status_differs": d.status_differs,
        "only_in_first": d.only_in_first,
        "only_in_second": d.only_in_second,
    })
}
