//! Work–precision figures: error against wall time and against right-hand-side evaluations
//! (log–log, one curve per integrator), and the long-run relative energy error against time.

use super::xy::{Mark, Panel, Scale, Series, SeriesLook, StackedFigure};

/// One integrator's curve: `(wall time s, evaluations, error)` per rung.
pub struct Curve {
    /// The integrator's registry name: its family sets the curve's colour.
    pub integrator: String,
    /// Legend entry (integrator and order).
    pub label: String,
    /// `(seconds, evaluations, error)` from coarse to fine.
    pub rungs: Vec<(f64, f64, f64)>,
}

/// What a work–precision figure says about its study, beside the curves.
pub struct Study<'a> {
    /// Scene name.
    pub scene: &'a str,
    /// Horizon (s).
    pub t_end: f64,
    /// The parameters in words (`M = 1, a = 0.4`).
    pub parameters: String,
    /// The reference method, the method that cross-checked it, and their agreement.
    pub reference: (&'a str, &'a str, f64),
}

/// A curve's legend entry: the integrator and its order as the registry displays it (`rk4 (4)`,
/// `exact (exact)`, `taylor (variable)`).
#[must_use]
pub fn curve_label(integrator: &str, order: &str) -> String {
    format!("{integrator} ({order})")
}

/// The `work-precision` figure of `study`: [`figure`] with its title and subtitle. The
/// command and `tumble plot` both draw through this.
#[must_use]
pub fn study_figure(study: &Study<'_>, curves: &[Curve]) -> StackedFigure {
    let (method, check, agreement) = study.reference;
    figure(
        format!(
            "{}: error at t = {} s against cost",
            study.scene, study.t_end
        ),
        format!(
            "{}; reference: {method} (cross-check {check}: {agreement:.1e})",
            study.parameters
        ),
        curves,
    )
}

/// The palette index of the family of `integrator` (one colour per family; methods of a
/// family differ by mark and dash). Unknown names share the last colour.
fn family_colour(integrator: &str) -> usize {
    use tumble_integrators::registry::{Family, find};
    match find(integrator).map(|m| m.family) {
        Ok(Family::ExplicitRungeKutta) => 0,
        Ok(Family::GaussLegendre) => 1,
        Ok(Family::Splitting) => 2,
        Ok(Family::Composition) => 3,
        Ok(Family::LieGroup) => 4,
        Ok(Family::SymplecticPartitioned) => 5,
        _ => 6,
    }
}

/// Error at the final time against wall time (top) and against evaluations (bottom).
pub fn figure(title: String, subtitle: String, curves: &[Curve]) -> StackedFigure {
    let panel = |x_label: &str, pick: fn(&(f64, f64, f64)) -> f64| {
        let mut p = Panel::new(x_label, "error at the final time")
            .with_x_scale(Scale::Log)
            .with_y_scale(Scale::Log);
        let mut seen: Vec<usize> = Vec::new();
        for c in curves {
            let mut series = Series::marked(
                c.label.clone(),
                c.rungs.iter().map(|r| (pick(r), r.2)).collect(),
                if c.rungs.len() == 1 {
                    Mark::Points
                } else {
                    Mark::LineAndPoints
                },
            );
            let colour = family_colour(&c.integrator);
            series.look = Some(SeriesLook {
                colour,
                variant: seen.iter().filter(|&&f| f == colour).count(),
            });
            seen.push(colour);
            p = p.with_series(series);
        }
        p
    };
    StackedFigure {
        title,
        subtitle,
        panels: vec![
            panel("wall time per run (s)", |r| r.0),
            panel(
                "right-hand-side evaluations (steps for a method without one)",
                |r| r.1,
            ),
        ],
        width: 1000,
        panel_height: 760,
    }
}

/// The record of a long run (`work-precision --long`), written into its folder's
/// `manifest.json` and read back by `tumble plot`: what its figure's title and subtitle say.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LongRecord {
    /// The scene and its parameters.
    #[serde(flatten)]
    pub scene: crate::saved::SceneRecord,
    /// Steps of each run (at the scene's default step).
    pub steps: u64,
    /// The scene's default step (s).
    pub dt: f64,
    /// Compared at equal cost from the adaptive side (`--long-tol`).
    pub equal_cost: bool,
    /// How the adaptive method was matched to the fixed-step ones, in words (empty: none).
    pub matched: String,
}

/// `manifest.json` of a long-run folder (`work-precision --long`): its [`LongRecord`] with the
/// command, where the scene came from and the provenance. The command line writes it and
/// `tumble plot` reads it back, the one type for both.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LongManifest {
    /// The command that wrote it (`work-precision --long`).
    pub command: String,
    /// Where the scene came from (`builtin`, or the scene or model file as given).
    pub origin: String,
    /// The record the figure is drawn from.
    #[serde(flatten)]
    pub record: LongRecord,
    /// Which binary wrote it, where and when.
    pub provenance: tumble_output::Provenance,
}

impl LongRecord {
    /// The long-run figure of this record with the scene's `params` and one line per run.
    #[must_use]
    pub fn figure(&self, params: &tumble_scenarios::Params, lines: Vec<Series>) -> StackedFigure {
        long_figure(
            format!(
                "{}: relative energy error over {} steps",
                self.scene.scene, self.steps
            ),
            format!(
                "{}; {}{}",
                if self.equal_cost {
                    "equal cost".to_string()
                } else {
                    format!("dt = {} s", self.dt)
                },
                super::labels::parameters(params.iter()),
                if self.matched.is_empty() {
                    String::new()
                } else {
                    format!("; {}", self.matched)
                }
            ),
            lines,
        )
    }
}

/// The legend label of a long run: the integrator, with its tolerance when adaptive
/// (`control` as `long.csv` writes it: `dt = …` or `tol = …`).
#[must_use]
pub fn long_label(integrator: &str, control: &str) -> String {
    if control.starts_with("tol") {
        format!("{integrator} ({control})")
    } else {
        integrator.to_string()
    }
}

/// The relative energy error's maximum per logarithmic time bin, one line per method.
pub fn long_figure(title: String, subtitle: String, lines: Vec<Series>) -> StackedFigure {
    let mut panel = Panel::new(
        "time (s)",
        "relative energy error |E − E₀|/E_s (maximum per log-time bin)",
    )
    .with_x_scale(Scale::Log)
    .with_y_scale(Scale::Log);
    for s in lines {
        panel = panel.with_series(s);
    }
    StackedFigure {
        title,
        subtitle,
        panels: vec![panel],
        width: 1000,
        panel_height: 700,
    }
}
