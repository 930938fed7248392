//! Figure size, font size, resolution and SVG text: the options every command that writes a
//! plot takes (`--figure-size single|double|WxH`, `--font-size PT`, `--dpi N`,
//! `--svg-text font|paths`).
//!
//! A figure is laid out in *layout pixels*: its fonts, margins and line widths are fixed in
//! those units (labels at [`BASE_FONT_PX`]). Asking for a physical size and a font size in
//! points fixes the scale from layout pixels to device pixels, `s = font_pt · dpi / 72 /
//! BASE_FONT_PX`, and the figure is laid out at `size · dpi / s` layout pixels, so text keeps
//! its requested size in points whatever the width. The presets are the usual journal column
//! widths: `single` 3.4 in, `double` 7 in, at 300 dpi; the figure chooses its height for the
//! width unless it is given (`7x4`, `180x120mm`, `12x8cm`).
//!
//! Without options a figure keeps its own size in pixels (at 96 pixels per inch in SVG and
//! PDF) and its labels are 11.25 pt.

use crate::{PlotError, Result};

/// The label font of every figure, in layout pixels (axis labels, legends).
pub const BASE_FONT_PX: f64 = 15.0;

/// CSS pixels per inch: the resolution of a figure without options, in SVG and PDF.
pub const CSS_DPI: f64 = 96.0;

/// Resolution of the journal presets when `--dpi` is not given.
pub const PRESET_DPI: f64 = 300.0;

/// Label size in points with a physical size and no `--font-size`.
pub const PRESET_FONT_PT: f64 = 8.0;

/// A physical figure size: width, and height unless it follows the aspect ratio (inches).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Width in inches.
    pub width: f64,
    /// Height in inches; `None` keeps the figure's aspect ratio.
    pub height: Option<f64>,
}

impl Size {
    /// Parses `single` (3.4 in), `double` (7 in) or `WxH` in inches, or with a unit suffix
    /// `in`, `cm` or `mm` (`180x120mm`).
    ///
    /// # Errors
    /// Anything else, or a dimension that is not a positive finite number.
    pub fn parse(s: &str) -> Result<Self> {
        let t = s.trim().to_ascii_lowercase();
        match t.as_str() {
            "single" => {
                return Ok(Size {
                    width: 3.4,
                    height: None,
                });
            }
            "double" => {
                return Ok(Size {
                    width: 7.0,
                    height: None,
                });
            }
            _ => {}
        }
        let (number, per_inch) = if let Some(n) = t.strip_suffix("mm") {
            (n, 25.4)
        } else if let Some(n) = t.strip_suffix("cm") {
            (n, 2.54)
        } else {
            (t.strip_suffix("in").unwrap_or(&t), 1.0)
        };
        let Some((w, h)) = number.split_once('x') else {
            return Err(PlotError::choice(
                format!("--figure-size {s}"),
                "expected single (3.4 in), double (7 in) or WxH in inches (7x4, or 180x120mm, \
                 12x8cm)",
            ));
        };
        let dim = |v: &str, what: &str| -> Result<f64> {
            match v.trim().parse::<f64>() {
                Ok(x) if x.is_finite() && x > 0.0 => Ok(x / per_inch),
                _ => Err(PlotError::choice(
                    format!("--figure-size {s}"),
                    format!("the {what} `{v}` is not a positive number"),
                )),
            }
        };
        Ok(Size {
            width: dim(w, "width")?,
            height: Some(dim(h, "height")?),
        })
    }
}

/// How SVG text is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum SvgText {
    /// `<text>` elements in the shipped font, embedded in the file (selectable text).
    #[default]
    Font,
    /// Every glyph converted to a path (no font needed to display the file).
    Paths,
}

/// The largest raster a figure is drawn into, in device pixels: a side, and the area (a PNG is
/// drawn supersampled, 27 bytes a pixel, so 25 megapixels take about 700 MB).
pub const MAX_SIDE_PIXELS: u32 = 16_384;
/// See [`MAX_SIDE_PIXELS`].
pub const MAX_PIXELS: f64 = 25e6;

/// Checks a figure's device size against [`MAX_SIDE_PIXELS`] and [`MAX_PIXELS`].
///
/// # Errors
/// A side or an area above the limits, with the size and what to change.
pub fn check_pixels((w, h): (u32, u32)) -> Result<()> {
    if w > MAX_SIDE_PIXELS || h > MAX_SIDE_PIXELS || f64::from(w) * f64::from(h) > MAX_PIXELS {
        return Err(PlotError::TooLarge {
            width: w,
            height: h,
        });
    }
    Ok(())
}

/// The options of one figure; the default keeps the figure as it is.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FigureOptions {
    /// Physical size; `None` keeps the figure's own size.
    pub size: Option<Size>,
    /// Label size in points.
    pub font_pt: Option<f64>,
    /// Dots per inch of a PNG (and the pixel grid of the layout).
    pub dpi: Option<f64>,
    /// SVG text as font or paths.
    pub svg_text: SvgText,
}

/// The size a figure is laid out at, in layout pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Its own size.
    Own,
    /// This width, the figure choosing its height ([`super::Figure::fit_width`]).
    Width(u32),
    /// This width and height.
    Size(u32, u32),
}

/// Where a figure's layout ends up: its layout size, the device pixels per layout pixel, and
/// the physical size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Size to lay the figure out at (layout pixels).
    pub target: Target,
    /// Device pixels per layout pixel.
    pub scale: f64,
    /// Dots per inch.
    pub dpi: f64,
}

impl Layout {
    /// The device size in pixels of a figure laid out at `layout` pixels.
    #[must_use]
    pub fn pixels(&self, layout: (u32, u32)) -> (u32, u32) {
        let f = |v: u32| ((f64::from(v) * self.scale).round() as u32).max(1);
        (f(layout.0), f(layout.1))
    }

    /// The physical size in inches of a figure laid out at `layout` pixels.
    #[must_use]
    pub fn inches(&self, layout: (u32, u32)) -> (f64, f64) {
        (
            f64::from(layout.0) * self.scale / self.dpi,
            f64::from(layout.1) * self.scale / self.dpi,
        )
    }
}

impl FigureOptions {
    /// Checks the numbers given on the command line.
    ///
    /// # Errors
    /// A font size or resolution that is not a positive finite number, or a figure whose
    /// layout would be smaller than 120 layout pixels wide (text too large for the width).
    pub fn validate(&self) -> Result<()> {
        if let Some(pt) = self.font_pt
            && !(pt.is_finite() && pt > 0.0 && pt <= 200.0)
        {
            return Err(PlotError::choice(
                format!("--font-size {pt}"),
                "expected a size in points in (0, 200]",
            ));
        }
        if let Some(dpi) = self.dpi
            && !(dpi.is_finite() && (10.0..=4800.0).contains(&dpi))
        {
            return Err(PlotError::choice(
                format!("--dpi {dpi}"),
                "expected a resolution between 10 and 4800 dots per inch",
            ));
        }
        if self.size.is_none() {
            // The figures' own sizes are at most this many layout pixels.
            check_pixels(self.layout().pixels((1000, 700)))?;
        }
        if let Some(size) = self.size {
            let (w, h) = match self.layout().target {
                Target::Own => (1000, 700),
                Target::Width(w) => (w, 700),
                Target::Size(w, h) => (w, h),
            };
            check_pixels(self.layout().pixels((w, h)))?;
            if w < 120 || h < 80 {
                return Err(PlotError::choice(
                    format!(
                        "--figure-size {}x{} in with {} pt text",
                        size.width,
                        size.height.map_or("auto".into(), |h| h.to_string()),
                        self.font_pt.unwrap_or(PRESET_FONT_PT)
                    ),
                    "leaves no room for a plot: use a larger size or a smaller --font-size",
                ));
            }
        }
        Ok(())
    }

    /// The layout these options ask for.
    #[must_use]
    pub fn layout(&self) -> Layout {
        let sized = self.size.is_some();
        let dpi = self.dpi.unwrap_or(if sized { PRESET_DPI } else { CSS_DPI });
        let font_pt = self.font_pt.unwrap_or(if sized {
            PRESET_FONT_PT
        } else {
            BASE_FONT_PX * 72.0 / CSS_DPI
        });
        let scale = font_pt * dpi / 72.0 / BASE_FONT_PX;
        let to_layout = |inches: f64| ((inches * dpi / scale).round() as u32).max(1);
        let target = match self.size {
            None => Target::Own,
            Some(Size {
                width,
                height: None,
            }) => Target::Width(to_layout(width)),
            Some(Size {
                width,
                height: Some(height),
            }) => Target::Size(to_layout(width), to_layout(height)),
        };
        Layout { target, scale, dpi }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_presets_inches_and_metric_units() {
        assert_eq!(Size::parse("single").unwrap().width, 3.4);
        assert_eq!(Size::parse("Double").unwrap().width, 7.0);
        let s = Size::parse("7x4").unwrap();
        assert_eq!((s.width, s.height), (7.0, Some(4.0)));
        let s = Size::parse("254x127mm").unwrap();
        assert!((s.width - 10.0).abs() < 1e-12 && (s.height.unwrap() - 5.0).abs() < 1e-12);
        assert!((Size::parse("2.54x5.08cm").unwrap().width - 1.0).abs() < 1e-12);
        for bad in ["", "wide", "3x", "x4", "-1x2", "3x0", "nanx2"] {
            assert!(Size::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn no_options_keep_the_figure_as_it_is() {
        let l = FigureOptions::default().layout();
        assert_eq!(l.target, Target::Own);
        assert!((l.scale - 1.0).abs() < 1e-12);
        assert_eq!(l.pixels((1000, 720)), (1000, 720));
    }

    #[test]
    fn a_single_column_figure_is_3_4_inches_at_300_dpi_with_text_in_points() {
        let opts = FigureOptions {
            size: Some(Size::parse("single").unwrap()),
            ..FigureOptions::default()
        };
        let l = opts.layout();
        // 3.4 in at 300 dpi is 1020 pixels; the figure chooses its height.
        let Target::Width(w) = l.target else {
            panic!("{:?}", l.target)
        };
        let px = l.pixels((w, 500));
        assert!((i64::from(px.0) - 1020).abs() <= 2, "{px:?}");
        // A 15-pixel label is PRESET_FONT_PT points: 15 layout px · scale / dpi · 72.
        let pt = BASE_FONT_PX * l.scale / l.dpi * 72.0;
        assert!((pt - PRESET_FONT_PT).abs() < 1e-12);
        let (inches, _) = l.inches((w, 500));
        assert!((inches - 3.4).abs() < 0.01, "{inches}");
        // Both dimensions given: both kept.
        let opts = FigureOptions {
            size: Some(Size::parse("7x4").unwrap()),
            ..FigureOptions::default()
        };
        let l = opts.layout();
        let Target::Size(w, h) = l.target else {
            panic!("{:?}", l.target)
        };
        let (a, b) = l.inches((w, h));
        assert!((a - 7.0).abs() < 0.01 && (b - 4.0).abs() < 0.01, "{a} {b}");
    }

    #[test]
    fn figures_too_large_to_draw_are_refused_before_any_work() {
        // 200 x 200 in at 300 dpi would be 60000 pixels a side (a 97 GB supersampled buffer).
        let huge = FigureOptions {
            size: Some(Size::parse("200x200").unwrap()),
            ..FigureOptions::default()
        };
        let e = huge.validate().unwrap_err().to_string();
        assert!(e.contains("pixels") && e.contains("--dpi"), "{e}");
        // The figure's own size at 4800 dpi: 50 device pixels a layout pixel.
        let dense = FigureOptions {
            dpi: Some(4800.0),
            ..FigureOptions::default()
        };
        assert!(dense.validate().is_err());
        // A double-column figure at 600 dpi (4200 x 2400 pixels) is fine.
        let paper = FigureOptions {
            size: Some(Size::parse("7x4").unwrap()),
            dpi: Some(600.0),
            ..FigureOptions::default()
        };
        paper.validate().unwrap();
        assert!(check_pixels((MAX_SIDE_PIXELS, 1000)).is_ok());
        assert!(check_pixels((MAX_SIDE_PIXELS + 1, 1000)).is_err());
        assert!(check_pixels((6000, 6000)).is_err());
    }

    #[test]
    fn text_too_large_for_the_width_is_refused() {
        let opts = FigureOptions {
            size: Some(Size::parse("1x1").unwrap()),
            font_pt: Some(40.0),
            ..FigureOptions::default()
        };
        assert!(opts.validate().is_err());
        assert!(
            FigureOptions {
                dpi: Some(0.0),
                ..FigureOptions::default()
            }
            .validate()
            .is_err()
        );
    }
}
