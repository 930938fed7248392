//! Legends placed where they cover no data.
//!
//! A panel's legend is a box of one row per series (its sample — line, dashes, mark — and its
//! label). [`place`] measures, for each candidate position, how much of the drawn series the
//! box would cover — segments of the polylines and marks, in device pixels, widened by the
//! line width — and takes the first candidate that covers nothing: the four corners of the
//! plot area, then the middles of its edges. When every one covers data the legend goes
//! outside, to the right of the plot area, which the panel then narrows to make room.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{DrawResult, font};

/// An axis-aligned rectangle in device pixels: `[x0, x1] × [y0, y1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Left.
    pub x0: f64,
    /// Top.
    pub y0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y1: f64,
}

impl Rect {
    /// The rectangle grown by `d` on every side.
    #[must_use]
    pub fn grown(&self, d: f64) -> Rect {
        Rect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }

    fn contains(&self, (x, y): (f64, f64)) -> bool {
        (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y)
    }

    /// Whether the segment from `a` to `b` meets the rectangle (Liang–Barsky clipping).
    #[must_use]
    pub fn meets_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// What a panel drew, in device pixels: polylines and marks.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Drawn {
    /// Each line series' vertices.
    pub lines: Vec<Vec<(f64, f64)>>,
    /// Centres of marks.
    pub marks: Vec<(f64, f64)>,
    /// Half the line width plus the marks' radius: how far ink reaches from the geometry.
    pub reach: f64,
}

impl Drawn {
    /// How many segments and marks of the drawing `rect` covers.
    #[must_use]
    pub fn overlap(&self, rect: &Rect) -> usize {
        let r = rect.grown(self.reach);
        let segments = self
            .lines
            .iter()
            .flat_map(|l| l.windows(2))
            .filter(|w| r.meets_segment(w[0], w[1]))
            .count();
        let single = self
            .lines
            .iter()
            .filter(|l| l.len() == 1 && r.contains(l[0]))
            .count();
        segments + single + self.marks.iter().filter(|&&m| r.contains(m)).count()
    }
}

/// Where a legend goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Placement {
    /// Inside the plot area, in this rectangle.
    Inside(Rect),
    /// Outside, right of the plot area.
    Outside,
}

/// The first candidate position for a legend of `size` in `plot` (device pixels, `inset`
/// from the edges) that covers nothing `drawn`; [`Placement::Outside`] when each covers
/// something.
#[must_use]
pub fn place(plot: &Rect, size: (f64, f64), inset: f64, drawn: &Drawn) -> Placement {
    let (w, h) = size;
    let left = plot.x0 + inset;
    let right = plot.x1 - inset - w;
    let top = plot.y0 + inset;
    let bottom = plot.y1 - inset - h;
    let centre_x = 0.5 * (plot.x0 + plot.x1 - w);
    let centre_y = 0.5 * (plot.y0 + plot.y1 - h);
    if right < left || bottom < top {
        return Placement::Outside;
    }
    [
        (right, top),
        (left, top),
        (right, bottom),
        (left, bottom),
        (centre_x, top),
        (centre_x, bottom),
        (right, centre_y),
        (left, centre_y),
    ]
    .into_iter()
    .map(|(x, y)| Rect {
        x0: x,
        y0: y,
        x1: x + w,
        y1: y + h,
    })
    .find(|r| drawn.overlap(r) == 0)
    .map_or(Placement::Outside, Placement::Inside)
}

/// How a series looks in its legend sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Colour of its line and marks.
    pub colour: RGBColor,
    /// 0: circles, 1: squares, 2: triangles.
    pub marker: usize,
    /// 0: solid, 1: dashed, 2: dotted.
    pub dash: usize,
    /// Whether it has a line.
    pub line: bool,
    /// Whether it has marks.
    pub marks: bool,
}

/// Width of a sample in layout pixels.
const SAMPLE: u32 = 22;

/// The legend's text style at `scale`.
fn label_font(scale: f64) -> TextStyle<'static> {
    font(15.0 * scale)
}

/// `(row height, margin)` in device pixels at `scale`.
fn metrics(scale: f64) -> (f64, f64) {
    ((15.0 * 1.35 * scale).round(), (6.0 * scale).round())
}

/// The size of the legend of `labels` in device pixels, text measured on `area`.
#[must_use]
pub fn size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    labels: &[&str],
    scale: f64,
) -> (f64, f64) {
    let style = label_font(scale);
    let widest = labels
        .iter()
        .map(|l| area.estimate_text_size(l, &style).map_or(0, |(w, _)| w))
        .max()
        .unwrap_or(0);
    let (row, margin) = metrics(scale);
    let sample = f64::from(SAMPLE) * scale;
    (
        f64::from(widest) + sample + 3.0 * margin,
        row * labels.len() as f64 + 2.0 * margin,
    )
}

/// Draws the legend of `entries` with its top-left corner at `at` (device pixels relative to
/// `area`).
///
/// # Errors
/// The backend's drawing errors.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    at: (i32, i32),
    entries: &[(&str, Sample)],
    scale: f64,
) -> DrawResult<DB> {
    let labels: Vec<&str> = entries.iter().map(|e| e.0).collect();
    let (w, h) = size(area, &labels, scale);
    let (row, margin) = metrics(scale);
    let corner = (at.0 + w.round() as i32, at.1 + h.round() as i32);
    area.draw(&Rectangle::new([at, corner], WHITE.mix(0.85).filled()))?;
    let border = (scale.round() as u32).max(1);
    area.draw(&Rectangle::new(
        [at, corner],
        RGBColor(160, 160, 160).stroke_width(border),
    ))?;
    let d = |v: f64| v.round() as i32;
    for (k, (label, sample)) in entries.iter().enumerate() {
        let y = at.1 + d(margin + row * (k as f64 + 0.5));
        let x = at.0 + d(margin);
        draw_sample(area, (x, y), sample, scale)?;
        area.draw(&Text::new(
            (*label).to_string(),
            (x + d(f64::from(SAMPLE) * scale + margin), y),
            label_font(scale)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    Ok(())
}

/// A series' sample: its line (solid, dashed or dotted) across [`SAMPLE`] pixels from `at`
/// and its mark in the middle.
fn draw_sample<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    sample: &Sample,
    scale: f64,
) -> DrawResult<DB> {
    let d = |v: f64| (v * scale).round() as i32;
    let line = sample.colour.stroke_width(d(2.0).max(1) as u32);
    if sample.line {
        let pieces: &[(f64, f64)] = match sample.dash {
            0 => &[(0.0, 22.0)],
            1 => &[(0.0, 7.0), (15.0, 22.0)],
            _ => &[(0.0, 2.0), (5.0, 7.0), (15.0, 17.0), (20.0, 22.0)],
        };
        for &(a, b) in pieces {
            area.draw(&PathElement::new(vec![(x + d(a), y), (x + d(b), y)], line))?;
        }
    }
    if sample.marks {
        let r = d(3.0);
        let c = (x + d(11.0), y);
        let fill = sample.colour.filled();
        match sample.marker {
            0 => area.draw(&Circle::new(c, r, fill))?,
            1 => area.draw(&Rectangle::new(
                [(c.0 - r, c.1 - r), (c.0 + r, c.1 + r)],
                fill,
            ))?,
            _ => area.draw(&TriangleMarker::new(c, r + d(1.0), fill))?,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_meet_a_rectangle_only_when_they_cross_it() {
        let r = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 10.0,
            y1: 10.0,
        };
        assert!(r.meets_segment((-5.0, 5.0), (15.0, 5.0)), "through");
        assert!(r.meets_segment((2.0, 2.0), (3.0, 3.0)), "inside");
        assert!(!r.meets_segment((-5.0, -1.0), (15.0, -1.0)), "above");
        // A diagonal passing the corner outside it.
        assert!(!r.meets_segment((11.0, 0.0), (20.0, 9.0)));
        assert!(
            r.meets_segment((5.0, -5.0), (5.0, 0.0)),
            "touching the edge"
        );
    }

    #[test]
    fn the_legend_avoids_the_data_or_goes_outside() {
        let plot = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 400.0,
            y1: 300.0,
        };
        // A line along the top edge: the upper corners are taken, the lower right is free.
        let drawn = Drawn {
            lines: vec![vec![(0.0, 20.0), (400.0, 20.0)]],
            marks: Vec::new(),
            reach: 1.0,
        };
        match place(&plot, (100.0, 60.0), 5.0, &drawn) {
            Placement::Inside(r) => {
                assert_eq!((r.x0, r.y0), (295.0, 235.0));
                assert_eq!(drawn.overlap(&r), 0);
            }
            Placement::Outside => panic!("a free corner was missed"),
        }
        // Lines through every candidate: outside.
        let full = Drawn {
            lines: (0..=30)
                .map(|k| vec![(0.0, f64::from(k) * 10.0), (400.0, f64::from(k) * 10.0)])
                .collect(),
            marks: Vec::new(),
            reach: 1.0,
        };
        assert_eq!(place(&plot, (100.0, 60.0), 5.0, &full), Placement::Outside);
    }
}
