//! The title band over a figure: the title and a smaller subtitle, each wrapped at spaces to
//! the figure's width (never clipped), measured with the shipped font.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{DEJAVU_SANS, DrawResult, font};

/// Title and subtitle sizes, their line heights and the band's margins (layout pixels).
const TITLE_PX: f64 = 22.0;
const SUBTITLE_PX: f64 = 15.0;
const TITLE_LINE: u32 = 27;
const SUBTITLE_LINE: u32 = 20;
const LEFT: u32 = 16;
const TOP: u32 = 12;
const BOTTOM: u32 = 10;

/// The width of `text` at `size` pixels per em in the shipped font (advances and kerning).
#[must_use]
pub fn width(text: &str, size: f64) -> f64 {
    let Ok(font) = FontRef::try_from_slice(DEJAVU_SANS) else {
        return 0.0;
    };
    let font = font.as_scaled(PxScale::from(size as f32));
    let mut previous = None;
    let mut pen = 0f32;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = previous {
            pen += font.kern(p, id);
        }
        pen += font.h_advance(id);
        previous = Some(id);
    }
    f64::from(pen)
}

/// `text` broken at spaces into lines at most `max` pixels wide at `size` (a single word
/// wider than `max` gets a line of its own).
#[must_use]
pub fn wrap(text: &str, size: f64, max: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && width(&candidate, size) > max {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = candidate;
        }
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// A title and subtitle laid out for a figure `width` layout pixels wide.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    title: Vec<String>,
    subtitle: Vec<String>,
}

impl Band {
    /// Lays out `title` and `subtitle` (empty: none) for a figure `width` pixels wide.
    #[must_use]
    pub fn new(title: &str, subtitle: &str, width: u32) -> Self {
        let max = f64::from(width.saturating_sub(2 * LEFT)).max(1.0);
        Band {
            title: wrap(title, TITLE_PX, max),
            subtitle: if subtitle.is_empty() {
                Vec::new()
            } else {
                wrap(subtitle, SUBTITLE_PX, max)
            },
        }
    }

    /// Height in layout pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        let n = |v: &Vec<String>| u32::try_from(v.len()).unwrap_or(u32::MAX);
        TOP + TITLE_LINE * n(&self.title) + SUBTITLE_LINE * n(&self.subtitle) + BOTTOM
    }

    /// Draws the band on `area` at `scale` device pixels per layout pixel.
    ///
    /// # Errors
    /// The backend's drawing errors.
    pub fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        scale: f64,
    ) -> DrawResult<DB> {
        let px = |v: u32| (f64::from(v) * scale).round() as i32;
        let mut y = TOP;
        for line in &self.title {
            area.draw(&Text::new(
                line.clone(),
                (px(LEFT), px(y)),
                font(TITLE_PX * scale).color(&BLACK),
            ))?;
            y += TITLE_LINE;
        }
        y += 2;
        for line in &self.subtitle {
            area.draw(&Text::new(
                line.clone(),
                (px(LEFT), px(y)),
                font(SUBTITLE_PX * scale).color(&RGBColor(64, 64, 64)),
            ))?;
            y += SUBTITLE_LINE;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_subtitles_wrap_within_the_width_and_keep_every_word() {
        let text = "M = 1, a = 1, m = 0.1, g = 9.81, θ₀ = π/2; reference: gauss12 at dt = 6.25e-5 \
                    (cross-check dop853: 3.1e-13)";
        let lines = wrap(text, SUBTITLE_PX, 300.0);
        assert!(lines.len() >= 2, "{lines:?}");
        assert!(
            lines.iter().all(|l| width(l, SUBTITLE_PX) <= 300.0),
            "{lines:?}"
        );
        assert_eq!(lines.join(" "), text);
        // Width is additive over a space-free split, and grows with the size.
        assert!(width("ab", 15.0) > width("a", 15.0));
        assert!((width("abc", 30.0) / width("abc", 15.0) - 2.0).abs() < 0.01);
        // A band with a wrapped subtitle is taller than one without.
        let one = Band::new("title", "", 400).height();
        let two = Band::new("title", text, 400).height();
        assert!(two >= one + 2 * SUBTITLE_LINE);
    }
}
