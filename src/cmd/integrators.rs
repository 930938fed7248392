//! `tumble integrators`: list every integrator with its name, order, family, properties and
//! the built-in scenes it runs.
//!
//! The table comes from `tumble_integrators::registry`; `--json` prints the same entries as a
//! JSON array (each with its `scenes`). A composition table named alone (`kahan-li8`) composes
//! Störmer–Verlet and runs scenes with a separable model; `TABLE:BASE` (`kahan-li8:lgvi`)
//! composes the symmetric order-2 method `BASE` and runs what `BASE` runs.

use anyhow::Result;
use tumble_integrators::registry::{MethodInfo, methods};
use tumble_studies::catalog::{self, scenes_running as scenes_of};

/// Flags of `tumble integrators`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print a JSON array of objects (name, order, family, properties, stages, problem,
    /// problems, summary, scenes) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs the subcommand.
///
/// # Errors
/// Only if JSON serialization fails.
pub fn run(args: &Args) -> Result<()> {
    if args.json {
        println!("{}", serde_json::to_string_pretty(&catalog::integrators())?);
        return Ok(());
    }
    print!("{}", table(methods()));
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
    let rows: Vec<[String; 6]> = all
        .iter()
        .map(|m| {
            let scenes = scenes_of(m);
            [
                m.name.to_owned(),
                m.order.to_string(),
                m.stages.to_string(),
                m.family.name().to_owned(),
                flags(m),
                if scenes.is_empty() {
                    "(none built in)".to_owned()
                } else {
                    scenes.join(", ")
                },
            ]
        })
        .collect();
    let header = ["name", "order", "stages", "family", "properties", "scenes"];
    let mut widths = header.map(str::len);
    for r in &rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: [&str; 6]| {
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
        out += &line([&r[0], &r[1], &r[2], &r[3], &r[4], &r[5]]);
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

    #[test]
    fn scenes_column_follows_each_scenes_problem_kinds() {
        // A table named alone composes Verlet (the separable hoop models only); composed with the LGVI
        // it runs every SO(3) scene, and with the implicit midpoint every scene with an ODE.
        let scenes = |name| scenes_of(tumble_integrators::registry::find(name).unwrap());
        assert_eq!(scenes("kahan-li8"), ["driven-hoop", "spinning-hoop"]);
        assert_eq!(scenes("verlet"), scenes("kahan-li8"));
        for s in ["free-body", "dzhanibekov", "heavy-top", "free-hoop"] {
            assert!(scenes("kahan-li8:lgvi").contains(&s), "{s}");
        }
        assert!(!scenes("kahan-li8:split2").contains(&"free-hoop"));
        assert_eq!(scenes("kahan-li8:gauss2"), scenes("gauss2"));
        assert_eq!(scenes("kahan-li8:lgvi"), scenes("lgvi8"));
    }
}
