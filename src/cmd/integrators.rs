//! `tumble integrators`: list every integrator with its name, order, family and properties.
//!
//! The table comes from `tumble_integrators::registry`; `--json` prints the same entries as a
//! JSON array.

use anyhow::Result;
use tumble_integrators::registry::{MethodInfo, methods};

/// Flags of `tumble integrators`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print a JSON array of objects (name, order, family, properties, stages, problem,
    /// summary) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs the subcommand.
///
/// # Errors
/// Only if JSON serialization fails.
pub fn run(args: &Args) -> Result<()> {
    let all = methods();
    if args.json {
        println!("{}", serde_json::to_string_pretty(all)?);
        return Ok(());
    }
    print!("{}", table(all));
    Ok(())
}

fn flags(m: &MethodInfo) -> String {
    let p = &m.properties;
    let mut out = vec![if p.explicit { "explicit" } else { "implicit" }];
    if p.symplectic {
        out.push("symplectic");
    }
    if p.symmetric {
        out.push("symmetric");
    }
    if p.adaptive {
        out.push("adaptive");
    }
    if p.dense_output {
        out.push("dense-output");
    }
    if p.lie_group {
        out.push("lie-group");
    }
    out.join(", ")
}

/// The human-readable table.
fn table(all: &[MethodInfo]) -> String {
    let rows: Vec<[String; 5]> = all
        .iter()
        .map(|m| {
            [
                m.name.to_owned(),
                m.order.to_string(),
                m.stages.to_string(),
                m.family.name().to_owned(),
                flags(m),
            ]
        })
        .collect();
    let header = ["name", "order", "stages", "family", "properties"];
    let mut widths = header.map(str::len);
    for r in &rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: [&str; 5]| {
        let mut s = String::new();
        for (i, (c, w)) in cells.iter().zip(widths).enumerate() {
            if i + 1 == cells.len() {
                s.push_str(c);
            } else {
                s.push_str(&format!("{c:<w$}  "));
            }
        }
        s.trim_end().to_owned() + "\n"
    };
    let mut out = line(header);
    for r in &rows {
        out += &line([&r[0], &r[1], &r[2], &r[3], &r[4]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_lists_every_method_with_its_order() {
        let t = table(methods());
        assert!(t.starts_with("name"));
        assert_eq!(t.lines().count(), methods().len() + 1);
        let gauss12 = t.lines().find(|l| l.starts_with("gauss12 ")).unwrap();
        assert!(gauss12.contains(" 12 ") && gauss12.contains("implicit, symplectic, symmetric"));
        let kl8 = t.lines().find(|l| l.starts_with("kahan-li8 ")).unwrap();
        assert!(kl8.contains("composition"));
    }
}
