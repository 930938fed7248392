//! `tumble scenes`: list the built-in scenes with their coordinates, CSV columns, parameters
//! (name, default, unit, domain, description), conserved quantities, oracle, default run, the
//! methods recommended by purpose with the measurements behind them (the embedded data of
//! `tumble_scenarios::recommendation`, written by `tumble work-precision SCENE --recommend`, and
//! how they were made) and applicable integrators.
//!
//! `--json` prints the same as a JSON array of objects. The default step shown is the one a run
//! without `--dt`/`--tol` uses (the scene's options resolved), a fixed step `dt` or a
//! tolerance `tol` depending on the default integrator.

use anyhow::{Context, Result};
use tumble_scenarios::recommendation::{Band, LongRuns, Provenance};
use tumble_scenarios::scenes::builtin;
use tumble_studies::catalog::{Entry, Recommended, entry};

use super::work_precision::seconds;

/// Flags of `tumble scenes`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print a JSON array of objects (name, summary, coordinates, columns, parameters,
    /// conserved, oracle, problems, integrators, composition_bases, default_integrator,
    /// default_error, default_dt or default_tol, default_t_end, recommended: purpose,
    /// integrators, finest_error, compared_with, reason, to_error or long_run: the
    /// measurements; measured_by: command, version, date, machine; measured_against) instead
    /// of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs the subcommand.
///
/// # Errors
/// If a scene's own defaults do not validate (a bug in the scene) or JSON serialization fails.
pub fn run(args: &Args) -> Result<()> {
    let entries = builtin()
        .iter()
        .map(|s| {
            entry(*s)
                .with_context(|| format!("scene `{}`: its own defaults are invalid", s.info().name))
        })
        .collect::<Result<Vec<_>>>()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&entries)?);
    } else {
        print!("{}", text(&entries));
    }
    Ok(())
}

/// Left-aligned columns separated by two spaces; the last column is not padded.
fn table(header: &[&str], rows: &[Vec<String>], indent: &str) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: &[&str]| {
        let mut s = indent.to_string();
        for (i, (c, w)) in cells.iter().zip(&widths).enumerate() {
            if i + 1 == cells.len() {
                s.push_str(c);
            } else {
                s.push_str(&format!("{c:<w$}  "));
            }
        }
        s.trim_end().to_string() + "\n"
    };
    let mut out = line(header);
    for r in rows {
        out += &line(&r.iter().map(String::as_str).collect::<Vec<_>>());
    }
    out
}

/// The `parameters` block of a listing: a table of name, default, unit, domain, description.
pub(crate) fn parameters(e: &Entry) -> String {
    let rows: Vec<Vec<String>> = e
        .parameters
        .iter()
        .map(|p| {
            vec![
                p.name.to_string(),
                p.default.to_string(),
                p.unit.to_string(),
                p.domain.clone(),
                p.description.to_string(),
            ]
        })
        .collect();
    "  parameters\n".to_string()
        + &table(
            &["name", "default", "unit", "domain", "description"],
            &rows,
            "    ",
        )
}

/// The human-readable listing: one block per scene.
fn text(entries: &[Entry]) -> String {
    let mut out = String::new();
    for (k, e) in entries.iter().enumerate() {
        if k > 0 {
            out.push('\n');
        }
        out += &format!("{} — {}\n", e.name, e.summary);
        out += &format!("  coordinates  {}\n", e.coordinates.join(", "));
        out += &format!("  CSV columns  {}\n", e.columns.join(", "));
        out += &parameters(e);
        out += &format!("  conserved    {}\n", e.conserved.join("; "));
        out += &format!("  oracle       {}\n", e.oracle);
        let step = match (e.default_dt, e.default_tol) {
            (Some(h), _) => format!("dt = {h} s"),
            (None, Some(tol)) => format!("tol = {tol:e}"),
            (None, None) => String::new(),
        };
        out += &format!(
            "  default run  {}, {step}, t_end = {} s; error {:.1e} against the reference\n",
            e.default_integrator, e.default_t_end, e.default_error
        );
        for (i, r) in e.recommended.iter().enumerate() {
            let label = if i == 0 {
                "recommended "
            } else {
                "            "
            };
            out += &format!("  {label} {}\n", recommendation(r));
            if let Some(line) = measured(r.integrators.len(), r.to_error, r.long_run) {
                out += &format!("                 {line}\n");
            }
        }
        if let (Some(p), Some(reference)) = (e.measured_by, e.measured_against) {
            out += &format!(
                "  measured     {}; errors against {reference}\n",
                provenance(p)
            );
        }
        out += &format!("  integrators  {}\n", e.integrators.join(", "));
        if !e.composition_bases.is_empty() {
            out += &format!(
                "  compositions TABLE:BASE, BASE one of {} (`tumble integrators` lists them)\n",
                e.composition_bases.join(", ")
            );
        }
    }
    out
}

/// `purpose: method, method (reason)`.
fn recommendation(r: &Recommended) -> String {
    let mut line = format!("{}: {}", r.purpose, r.integrators.join(", "));
    if !r.reason.is_empty() {
        line += &format!(" ({})", r.reason);
    }
    line
}

/// The measurements of a recommendation whose first `own` methods are its own (the others
/// compared with them, after a `;`): each method's time to the band's finest error (or the
/// best error its ladder reached), or its largest relative energy error over the long run
/// (with the exponent of its growth, or why it failed).
pub(crate) fn measured(
    own: usize,
    to_error: Option<&Band>,
    long: Option<&LongRuns>,
) -> Option<String> {
    let joined = |items: Vec<String>| {
        let (mine, others) = items.split_at(own.min(items.len()));
        let mut s = mine.join(", ");
        if !others.is_empty() {
            s += "; ";
            s += &others.join(", ");
        }
        s
    };
    if let Some(b) = to_error {
        let items = b
            .methods
            .iter()
            .map(|m| match m.seconds {
                Some(t) => format!("{} {}", m.integrator, seconds(t)),
                None => format!("{} not reached (best {:.1e})", m.integrator, m.best_error),
            })
            .collect();
        return Some(format!("to {:.0e}: {}", b.target_error, joined(items)));
    }
    let l = long?;
    let steps = if l.steps.is_power_of_two() {
        format!("2^{}", l.steps.trailing_zeros())
    } else {
        l.steps.to_string()
    };
    let items = l
        .methods
        .iter()
        .map(|m| {
            let control = if m.control.starts_with("tol") {
                format!(" ({})", m.control)
            } else {
                String::new()
            };
            match (m.max_energy_rel_err, &m.failed) {
                (Some(e), _) => format!(
                    "{}{control} {e:.1e}{}",
                    m.integrator,
                    m.growth
                        .map_or_else(String::new, |a| format!(" (t^{a:.2})"))
                ),
                (None, failed) => format!(
                    "{}{control} failed: {}",
                    m.integrator,
                    failed.as_deref().unwrap_or("no energy recorded")
                ),
            }
        })
        .collect();
    Some(format!(
        "{steps} steps of {} s, largest relative energy error: {}",
        l.dt,
        joined(items)
    ))
}

/// How measurements were made, in a line.
fn provenance(p: &Provenance) -> String {
    let load = p
        .load_average
        .map_or_else(String::new, |l| format!(", load average {l:.2}"));
    format!(
        "by `{}` (tumble {}, {}) on {}: {}, {} cores{load}",
        p.command, p.tumble_version, p.git_commit, p.date, p.cpu, p.cores
    )
}
