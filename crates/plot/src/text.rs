//! Text for bitmap backends, laid out and rasterized with `ab_glyph` directly.
//!
//! plotters 0.3.7's `ab_glyph` text path draws each glyph at the pen position without its left
//! side bearing (it offsets the glyph's pixels by the bounding box's top but not its left), so
//! letters with a wide bearing crowd their left neighbour and spacing looks uneven (`tim e`,
//! `dt= 0.1`). [`ShapedText`] wraps a backend, delegates every drawing call to it, and replaces
//! `draw_text` and `estimate_text_size` with a layout that positions each glyph by its outline
//! bounds: pen advance, kerning and bearing as the font defines them, baseline at the font's
//! ascent, coverage as alpha. Anchors and the quarter-turn rotations plotters asks for (the
//! vertical axis label) are honoured as plotters' default text path does.
//!
//! Only the compiled-in font is used (every figure uses the one [`super::FONT`] family).

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use plotters::prelude::DrawingBackend;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

use super::DEJAVU_SANS;

/// A backend whose text is drawn with correct glyph placement; see the module doc.
pub struct ShapedText<DB> {
    inner: DB,
    font: FontRef<'static>,
}

impl<DB> ShapedText<DB> {
    /// Wraps `inner`.
    ///
    /// # Panics
    /// Never for the compiled-in font (it is parsed by a test).
    #[must_use]
    pub fn new(inner: DB) -> Self {
        ShapedText {
            inner,
            font: FontRef::try_from_slice(DEJAVU_SANS).expect("the compiled-in font parses"),
        }
    }
}

/// One glyph's pixels: `(x, y, coverage)` relative to the text box's top-left corner.
type Pixels = Vec<(i32, i32, f32)>;

impl<DB> ShapedText<DB> {
    /// Lays `text` out at `size` pixels per em: its box `(width, height)` and, if `pixels` is
    /// given, the covered pixels.
    fn layout(&self, text: &str, size: f64, mut pixels: Option<&mut Pixels>) -> (u32, u32) {
        let scale = PxScale::from(size as f32);
        let font = self.font.as_scaled(scale);
        let ascent = font.ascent();
        let height = ascent - font.descent();
        let mut pen = 0f32;
        let mut previous = None;
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = previous {
                pen += font.kern(p, id);
            }
            previous = Some(id);
            if let Some(pixels) = pixels.as_deref_mut() {
                let glyph = id.with_scale_and_position(scale, point(pen, ascent));
                if let Some(outline) = self.font.outline_glyph(glyph) {
                    let bounds = outline.px_bounds();
                    let (x0, y0) = (bounds.min.x as i32, bounds.min.y as i32);
                    outline.draw(|x, y, coverage| {
                        if coverage > 0.0 {
                            pixels.push((x0 + x as i32, y0 + y as i32, coverage));
                        }
                    });
                }
            }
            pen += font.h_advance(id);
        }
        (pen.ceil().max(0.0) as u32, height.ceil().max(0.0) as u32)
    }
}

impl<DB: DrawingBackend> DrawingBackend for ShapedText<DB> {
    type ErrorType = DB::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vert, style)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, size, src)
    }

    fn estimate_text_size<TStyle: BackendTextStyle>(
        &self,
        text: &str,
        style: &TStyle,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        Ok(self.layout(text, style.size(), None))
    }

    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let colour = style.color();
        if colour.alpha == 0.0 {
            return Ok(());
        }
        let mut pixels = Pixels::new();
        let (width, height) = self.layout(text, style.size(), Some(&mut pixels));
        let (width, height) = (width as i32, height as i32);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Center => -width / 2,
            HPos::Right => -width,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let turn = style.transform();
        for (x, y, coverage) in pixels {
            let (x, y) = turn.transform(x + dx, y + dy);
            self.inner.draw_pixel(
                (pos.0 + x, pos.1 + y),
                BackendColor {
                    alpha: colour.alpha * f64::from(coverage.min(1.0)),
                    rgb: colour.rgb,
                },
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;

    /// The leftmost and rightmost inked columns of `text` drawn at (10, 10), and the image.
    fn ink(text: &str) -> (usize, usize) {
        let (w, h) = (400u32, 60u32);
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let root =
                ShapedText::new(BitMapBackend::with_buffer(&mut buf, (w, h))).into_drawing_area();
            root.draw(&Text::new(
                text.to_string(),
                (10, 10),
                (super::super::FONT, 30.0).into_font().color(&BLACK),
            ))
            .unwrap();
            root.present().unwrap();
        }
        let inked: Vec<usize> = (0..w as usize)
            .filter(|&x| (0..h as usize).any(|y| buf[(y * w as usize + x) * 3] < 128))
            .collect();
        (*inked.first().unwrap(), *inked.last().unwrap())
    }

    #[test]
    fn glyphs_keep_their_bearings_and_advances() {
        super::super::register_fonts().unwrap();
        // A glyph drawn after another starts one advance later: "ll" is one "l" plus the
        // advance of "l" (a glyph with a wide left bearing, the case plotters misplaces).
        let (l0, l1) = ink("l");
        let (ll0, ll1) = ink("ll");
        assert_eq!(l0, ll0);
        let font = FontRef::try_from_slice(DEJAVU_SANS).unwrap();
        let advance = font
            .as_scaled(PxScale::from(30.0))
            .h_advance(font.glyph_id('l'));
        let shift = (ll1 - l1) as f32;
        assert!((shift - advance).abs() <= 1.0, "{shift} vs {advance}");
        // The left bearing is kept: ink starts right of the anchor.
        assert!(l0 > 10, "ink starts at {l0}");
    }
}
