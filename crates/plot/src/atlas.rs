//! The hard-case atlas as a figure: methods (rows) × cases (columns), each cell coloured by the
//! decimal logarithm of the method's error on the case (the final-state error against the
//! reference where the case bounds it, else the energy error), with its outcome marked:
//! nothing for `ok`, `!` for a violated property, `×` on grey for a failure, `T` on grey for
//! a run that reached its time limit; blank where the method cannot run the case's scene.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{DrawResult, Figure, colour, font};
use tumble_scenarios::SceneInfo;
use tumble_studies::hard_cases::atlas::{Entry, Method, Status};

/// One cell of the atlas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell {
    /// The method does not run the case's scene.
    NotApplicable,
    /// An entry not computed (the budget ran out).
    Missing,
    /// An outcome and the error to colour it by.
    Entry {
        /// How it ended.
        status: Status,
        /// The error (final state, else energy).
        error: Option<f64>,
    },
}

/// The atlas figure.
#[derive(Debug, Clone)]
pub struct Atlas {
    /// Title.
    pub title: String,
    /// Under the title.
    pub subtitle: String,
    /// Column labels (case names).
    pub cases: Vec<String>,
    /// Row labels (methods).
    pub methods: Vec<String>,
    /// `cells[method][case]`.
    pub cells: Vec<Vec<Cell>>,
}

/// A case of an atlas as its figure reads it: its name, the scene it runs (which methods
/// apply), and whether its property bounds the final-state error (the cell is coloured by
/// that error, else by the relative energy error).
#[derive(Debug, Clone, Copy)]
pub struct AtlasCase<'a> {
    /// The case's name.
    pub name: &'a str,
    /// Its scene's declaration.
    pub scene: &'a SceneInfo,
    /// Its property bounds the final-state error.
    pub bounds_error: bool,
}

impl Atlas {
    /// The figure of a finished (or cut short) atlas: `methods` × `cases`, each cell the entry
    /// of that method on that case, blank where the method does not run the case's scene.
    /// `tumble hard-cases` and `tumble plot DIR` both draw through this.
    #[must_use]
    pub fn of_entries(cases: &[AtlasCase<'_>], methods: &[Method], entries: &[Entry]) -> Self {
        let cells = methods
            .iter()
            .map(|m| {
                let spec = m.spec();
                cases
                    .iter()
                    .map(|c| {
                        if c.scene.kind_for(m.info).is_none() {
                            return Cell::NotApplicable;
                        }
                        entries
                            .iter()
                            .find(|e| e.case == c.name && e.method == spec)
                            .map_or(Cell::Missing, |e| Cell::Entry {
                                status: e.status,
                                error: if c.bounds_error { e.error } else { e.energy },
                            })
                    })
                    .collect()
            })
            .collect();
        Atlas {
            title: "Hard cases: every method at an error of 1e-6 on each case's easy twin".into(),
            subtitle: "colour: final-state error against the reference where the case bounds \
                       it, else the relative energy error; log scale"
                .into(),
            cases: cases.iter().map(|c| c.name.to_string()).collect(),
            methods: methods.iter().map(Method::spec).collect(),
            cells,
        }
    }
}

/// Colour range of `log10(error)`.
const LOG_RANGE: (f64, f64) = (-16.0, 0.0);
/// The colour of an error: its place on the log scale, an error of 0 (the exact flow against
/// itself) and those below the scale at its bottom; grey for none or a non-finite one.
fn shade(error: Option<f64>) -> RGBColor {
    error
        .filter(|e| e.is_finite() && *e >= 0.0)
        .map_or(GREY, |e| {
            let log = e.max(10f64.powf(LOG_RANGE.0)).log10();
            colour::viridis((log - LOG_RANGE.0) / (LOG_RANGE.1 - LOG_RANGE.0))
        })
}

/// Grey of failed and timed-out cells.
const GREY: RGBColor = RGBColor(0xb0, 0xb0, 0xb0);

const CELL_W: u32 = 58;
const CELL_H: u32 = 22;
/// The least left margin (for row labels).
const LEFT: u32 = 120;
const TOP: u32 = 100;
const KEY_LINE: u32 = 19;

impl Atlas {
    /// The left margin: the longest method name at the labels' 13 px, its 8 px gap and 16 px
    /// of page, and never less than [`LEFT`] (`TABLE:BASE` names run long).
    fn left(&self) -> u32 {
        let longest = self
            .methods
            .iter()
            .map(|m| super::title::width(m, 13.0))
            .fold(0.0, f64::max);
        LEFT.max((longest + 24.0).ceil() as u32)
    }

    fn key_rows(&self) -> u32 {
        self.cases.len().div_ceil(2) as u32
    }
}

impl Figure for Atlas {
    fn size(&self) -> (u32, u32) {
        let w = self.left() + CELL_W * self.cases.len().max(1) as u32 + 150;
        let h =
            TOP + CELL_H * self.methods.len().max(1) as u32 + 60 + KEY_LINE * self.key_rows() + 20;
        (w.max(900), h)
    }

    /// The atlas's cells have a fixed size: it keeps its own.
    fn set_size(&mut self, _size: (u32, u32)) {}

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        s: f64,
    ) -> DrawResult<DB> {
        let px = |v: u32| (f64::from(v) * s).round() as i32;
        let left = self.left();
        root.fill(&WHITE)?;
        root.draw(&Text::new(
            self.title.clone(),
            (px(16), px(12)),
            font(22.0 * s).color(&BLACK),
        ))?;
        root.draw(&Text::new(
            self.subtitle.clone(),
            (px(16), px(42)),
            font(14.0 * s).color(&RGBColor(64, 64, 64)),
        ))?;
        // Column numbers (the key below names them).
        for (j, _) in self.cases.iter().enumerate() {
            let x = left + CELL_W * j as u32 + CELL_W / 2;
            root.draw(&Text::new(
                format!("{}", j + 1),
                (px(x), px(TOP - 6)),
                font(14.0 * s)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Center, VPos::Bottom)),
            ))?;
        }
        for (i, method) in self.methods.iter().enumerate() {
            let y = TOP + CELL_H * i as u32;
            root.draw(&Text::new(
                method.clone(),
                (px(left - 8), px(y + CELL_H / 2)),
                font(13.0 * s)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Right, VPos::Center)),
            ))?;
            for (j, cell) in self.cells[i].iter().enumerate() {
                let x = left + CELL_W * j as u32;
                let (fill, mark) = match cell {
                    Cell::NotApplicable => (WHITE, ""),
                    Cell::Missing => (WHITE, "…"),
                    Cell::Entry { status, error } => {
                        let shade = shade(*error);
                        match status {
                            Status::Ok => (shade, ""),
                            Status::Violated => (shade, "!"),
                            Status::Failed => (GREY, "×"),
                            Status::TimeLimit => (GREY, "T"),
                        }
                    }
                };
                root.draw(&Rectangle::new(
                    [(px(x), px(y)), (px(x + CELL_W), px(y + CELL_H))],
                    fill.filled(),
                ))?;
                root.draw(&Rectangle::new(
                    [(px(x), px(y)), (px(x + CELL_W), px(y + CELL_H))],
                    RGBColor(0xe0, 0xe0, 0xe0).stroke_width((s.round() as u32).max(1)),
                ))?;
                if !mark.is_empty() {
                    // White marks on the dark end of the scale, black elsewhere.
                    let dark = matches!(cell, Cell::Entry { error: Some(e), status: Status::Violated }
                        if e.is_finite() && *e > 0.0 && (e.log10() - LOG_RANGE.0) / (LOG_RANGE.1 - LOG_RANGE.0) < 0.45);
                    root.draw(&Text::new(
                        mark.to_string(),
                        (px(x + CELL_W / 2), px(y + CELL_H / 2)),
                        font(15.0 * s)
                            .color(if dark { &WHITE } else { &BLACK })
                            .pos(Pos::new(HPos::Center, VPos::Center)),
                    ))?;
                }
            }
        }
        // The colour bar, right of the grid.
        let bar_x = left + CELL_W * self.cases.len() as u32 + 30;
        let bar_h = (CELL_H * self.methods.len() as u32).max(200);
        let steps = 64;
        for k in 0..steps {
            let y0 = TOP + bar_h - bar_h * (k + 1) / steps;
            let y1 = TOP + bar_h - bar_h * k / steps;
            root.draw(&Rectangle::new(
                [(px(bar_x), px(y0)), (px(bar_x + 18), px(y1))],
                colour::viridis((f64::from(k) + 0.5) / f64::from(steps)).filled(),
            ))?;
        }
        for decade in (LOG_RANGE.0 as i32..=LOG_RANGE.1 as i32).step_by(2) {
            let f = (f64::from(decade) - LOG_RANGE.0) / (LOG_RANGE.1 - LOG_RANGE.0);
            let y = TOP + bar_h - (f * f64::from(bar_h)).round() as u32;
            root.draw(&Text::new(
                format!("1e{decade}"),
                (px(bar_x + 24), px(y)),
                font(12.0 * s)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        root.draw(&Text::new(
            "error".to_string(),
            (px(bar_x), px(TOP - 6)),
            font(13.0 * s)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Bottom)),
        ))?;
        // The key: marks, then the numbered cases in two columns.
        let key_top = TOP + CELL_H * self.methods.len() as u32 + 24;
        root.draw(&Text::new(
            "ok: colour only    ! property violated    × failed (typed error)    T time limit    \
             … not run (budget)    blank: not applicable"
                .to_string(),
            (px(left), px(key_top)),
            font(13.0 * s).color(&BLACK),
        ))?;
        let half = self.key_rows() as usize;
        for (j, case) in self.cases.iter().enumerate() {
            let (col, row) = (j / half.max(1), j % half.max(1));
            root.draw(&Text::new(
                format!("{}  {case}", j + 1),
                (
                    px(left + col as u32 * 330),
                    px(key_top + 26 + KEY_LINE * row as u32),
                ),
                font(13.0 * s).color(&BLACK),
            ))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_of_zero_is_drawn_at_the_bottom_of_the_scale_not_grey() {
        assert_eq!(shade(Some(0.0)), colour::viridis(0.0));
        assert_eq!(shade(Some(1e-20)), colour::viridis(0.0));
        assert_eq!(shade(Some(1.0)), colour::viridis(1.0));
        assert_eq!(shade(None), GREY);
        assert_eq!(shade(Some(f64::NAN)), GREY);
    }

    #[test]
    fn an_atlas_renders_every_outcome_to_png_and_svg() {
        let fig = Atlas {
            title: "hard cases".into(),
            subtitle: "test".into(),
            cases: vec!["one".into(), "two".into(), "three".into()],
            methods: vec!["rk4".into(), "exact".into()],
            cells: vec![
                vec![
                    Cell::Entry {
                        status: Status::Ok,
                        error: Some(1e-8),
                    },
                    Cell::Entry {
                        status: Status::Violated,
                        error: Some(1e-2),
                    },
                    Cell::Entry {
                        status: Status::Failed,
                        error: None,
                    },
                ],
                vec![
                    Cell::NotApplicable,
                    Cell::Missing,
                    Cell::Entry {
                        status: Status::TimeLimit,
                        error: None,
                    },
                ],
            ],
        };
        let dir = tempfile::tempdir().unwrap();
        for name in ["a.png", "a.svg"] {
            let path = dir.path().join(name);
            super::super::save(&fig, &path).unwrap();
            assert!(std::fs::metadata(&path).unwrap().len() > 1000, "{name}");
        }
        let svg = std::fs::read_to_string(dir.path().join("a.svg")).unwrap();
        for text in ["three", "×", "T", "!", "1e-8"] {
            assert!(svg.contains(text), "{text}");
        }
    }
}
