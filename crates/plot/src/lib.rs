//! tumble's figures (plotters): PNG, SVG and PDF figures of typed results, with text that
//! renders without system fonts. The command line (`simulate --plot`, `sweep`,
//! `work-precision`, `hard-cases`, `plot`) and the Python package (`Simulation.plot`,
//! `tumble.plot`) both draw through this crate, so the same result gives the same file.
//!
//! # The figure of each result
//!
//! | result | figure |
//! |---|---|
//! | a run | [`trajectory::RunResult::figure`] |
//! | a sweep over a grid | [`sweep::figures`]: the [`heatmap`] map and the [`slices`] |
//! | a work–precision study | [`work_precision::study_figure`] |
//! | a long run | [`work_precision::LongRecord::figure`] |
//! | a hard-case atlas | [`atlas::Atlas::of_entries`] |
//!
//! [`saved::figure`] reads any of them back from the files its command wrote and draws it.
//!
//! # Design
//!
//! * **A shipped font.** DejaVu Sans (`assets/fonts/DejaVuSans.ttf`, licence beside it) is
//!   compiled in and registered with plotters' `ab_glyph` backend as the
//!   `sans-serif` family ([`register_fonts`]), so text renders the same on a machine without
//!   fontconfig or any installed font. SVG output names the `sans-serif` family; the shipped
//!   font only measures the text there. PNG text is laid out by [`text::ShapedText`] (plotters
//!   0.3.7 misplaces glyphs), PNGs are drawn at [`SUPERSAMPLE`] times their size and averaged
//!   down (plotters draws lines aliased), and encoded with the best PNG compression.
//! * **Figures are values.** A [`Figure`] knows its size and draws itself on any plotters
//!   backend; [`save`] picks PNG, SVG or PDF from the file's extension and writes the file
//!   whole or not at all (temporary file beside it, renamed when complete).
//! * **Reusable parts.** [`xy`] has stacked panels of line or point series on linear or
//!   logarithmic axes (trajectories against time; log-log work–precision plots), [`colour`] a
//!   colour-blind-safe palette for series and the colour maps of heatmaps with a colour bar,
//!   [`legend`] legends placed where they cover no data, [`labels`] the display symbols of
//!   parameters and columns.
//! * **No printing, no command line.** Errors are returned as [`PlotError`], naming the file or
//!   option at fault and what was wrong; the option enums derive `clap::ValueEnum` only with the `clap` feature.

pub mod atlas;
pub mod colour;
mod error;
pub mod heatmap;
pub mod labels;
pub mod legend;
pub mod log_axis;
pub mod options;
pub mod saved;
pub mod slices;
pub mod sweep;
pub mod text;
pub mod title;
pub mod trajectory;
pub mod vector;
pub mod work_precision;
pub mod xy;

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

pub use error::{PlotError, Result};
pub use options::FigureOptions;
use tumble_output as output;

/// The font family every figure uses; [`register_fonts`] binds it to the shipped font.
pub const FONT: &str = "sans-serif";

/// DejaVu Sans, compiled in (licence: `assets/fonts/LICENSE-DejaVu.txt`).
static DEJAVU_SANS: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// Registers the shipped font as the [`FONT`] family (normal, bold, oblique and italic styles
/// all fall back to it). Idempotent; [`save`] calls it.
///
/// # Errors
/// If the compiled-in font cannot be parsed (a corrupt build).
pub fn register_fonts() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok =
        *REGISTERED.get_or_init(|| register_font(FONT, FontStyle::Normal, DEJAVU_SANS).is_ok());
    if ok {
        Ok(())
    } else {
        Err(PlotError::Draw(
            "the compiled-in font DejaVuSans.ttf could not be parsed".to_string(),
        ))
    }
}

/// What drawing on a backend `DB` returns.
pub type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure that can draw itself on any plotters backend.
pub trait Figure {
    /// Size in layout pixels.
    fn size(&self) -> (u32, u32);

    /// Lays the figure out at `size` layout pixels where it can; a figure whose size follows
    /// its content (the atlas's fixed cells) keeps its own, which [`Figure::size`] reports.
    fn set_size(&mut self, size: (u32, u32));

    /// Lays the figure out `width` layout pixels wide at a height of its choosing; by default
    /// its aspect ratio is kept.
    fn fit_width(&mut self, width: u32) {
        let (w, h) = self.size();
        let height = (f64::from(h) * f64::from(width) / f64::from(w.max(1))).round() as u32;
        self.set_size((width, height.max(1)));
    }

    /// Draws on `root`, which covers the whole figure at `scale` device pixels per figure
    /// pixel: every length (fonts, margins, line widths, marks) is multiplied by `scale`.
    /// [`save`] draws PNGs at scale [`SUPERSAMPLE`] and averages down, SVGs at scale 1.
    ///
    /// # Errors
    /// The backend's drawing errors.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, scale: f64)
    -> DrawResult<DB>;
}

/// PNGs are drawn at this many device pixels per image pixel in each direction and averaged
/// down: anti-aliased lines and marks (plotters draws them aliased).
pub const SUPERSAMPLE: u32 = 3;

/// Averages each `k × k` block of an RGB image of `(w·k) × (h·k)` pixels into one pixel.
#[must_use]
pub fn downsample(rgb: &[u8], (w, h): (u32, u32), k: u32) -> Vec<u8> {
    let (w, h, k) = (w as usize, h as usize, k as usize);
    let big_w = w * k;
    let mut out = vec![0u8; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut sum = 0u32;
                for j in 0..k {
                    let row = (y * k + j) * big_w;
                    for i in 0..k {
                        sum += u32::from(rgb[(row + x * k + i) * 3 + c]);
                    }
                }
                let n = (k * k) as u32;
                out[(y * w + x) * 3 + c] = ((sum + n / 2) / n) as u8;
            }
        }
    }
    out
}

/// Image formats, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Portable Network Graphics (`.png`), rendered with the shipped font.
    Png,
    /// Scalable Vector Graphics (`.svg`), coordinates to 0.01 px, the font embedded or the
    /// text as paths.
    Svg,
    /// Portable Document Format (`.pdf`), the font embedded.
    Pdf,
}

impl Format {
    /// The format of `path` from its extension (case-insensitive).
    ///
    /// # Errors
    /// If the extension is not `png`, `svg` or `pdf`.
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("png") => Ok(Format::Png),
            Some("svg") => Ok(Format::Svg),
            Some("pdf") => Ok(Format::Pdf),
            _ => Err(PlotError::choice(
                path.display().to_string(),
                "plots are written as .png, .svg or .pdf (chosen by the file's extension)",
            )),
        }
    }
}

/// Draws `figure` into `path` (PNG, SVG or PDF by extension) at its own size, atomically:
/// nothing is left at `path` unless the whole image was written.
///
/// # Errors
/// An unknown extension, an unwritable directory, or a drawing error.
pub fn save<F: Figure + Clone>(figure: &F, path: &Path) -> Result<()> {
    save_with(figure, path, &FigureOptions::default())
}

/// As [`save`], with a figure size, font size, resolution and SVG text mode.
///
/// # Errors
/// As [`save`].
pub fn save_with<F: Figure + Clone>(figure: &F, path: &Path, opts: &FigureOptions) -> Result<()> {
    save_to(figure, &output::Destination::check(path)?, opts)
}

/// Draws `figure` into a checked destination: atomically into a regular file, or rendered
/// aside and then streamed into a device or FIFO.
///
/// # Errors
/// As [`save`].
pub fn save_to<F: Figure + Clone>(
    figure: &F,
    dest: &output::Destination,
    opts: &FigureOptions,
) -> Result<()> {
    let path = dest.path();
    let format = Format::from_path(path)?;
    let bytes = render(figure, format, opts).map_err(|e| PlotError::Drawing {
        path: path.to_path_buf(),
        source: Box::new(e),
    })?;
    let temp = dest.scratch()?;
    std::fs::write(&temp, bytes).map_err(|source| PlotError::Write {
        path: temp.to_path_buf(),
        source,
    })?;
    dest.commit_scratch(temp)?;
    Ok(())
}

/// The bytes of the file `figure` makes in `format` with `opts`.
///
/// # Errors
/// A drawing or conversion error.
pub fn render<F: Figure + Clone>(
    figure: &F,
    format: Format,
    opts: &FigureOptions,
) -> Result<Vec<u8>> {
    register_fonts()?;
    let layout = opts.layout();
    let mut figure = figure.clone();
    match layout.target {
        options::Target::Own => {}
        options::Target::Width(w) => figure.fit_width(w),
        options::Target::Size(w, h) => figure.set_size((w, h)),
    }
    let size = figure.size();
    let pixels = layout.pixels(size);
    options::check_pixels(pixels)?;
    match format {
        Format::Png => {
            let k = SUPERSAMPLE;
            let big = (pixels.0 * k, pixels.1 * k);
            let mut rgb = vec![255u8; big.0 as usize * big.1 as usize * 3];
            {
                let root = text::ShapedText::new(BitMapBackend::with_buffer(&mut rgb, big))
                    .into_drawing_area();
                figure
                    .draw(&root, layout.scale * f64::from(k))
                    .and_then(|()| root.present())
                    .map_err(|e| PlotError::Draw(e.to_string()))?;
            }
            let small = downsample(&rgb, pixels, k);
            encode_png(&small, pixels, layout.dpi)
        }
        Format::Svg | Format::Pdf => {
            let scale = layout.scale * vector::SUBPIXEL;
            let device = (
                (f64::from(size.0) * scale).round() as u32,
                (f64::from(size.1) * scale).round() as u32,
            );
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, device).into_drawing_area();
                figure
                    .draw(&root, scale)
                    .and_then(|()| root.present())
                    .map_err(|e| PlotError::Draw(e.to_string()))?;
            }
            let extent = if opts.size.is_some() {
                let (w, h) = layout.inches(size);
                vector::Extent {
                    width: format!("{w:.4}in"),
                    height: format!("{h:.4}in"),
                }
            } else {
                let css = options::CSS_DPI / layout.dpi;
                vector::Extent {
                    width: format!("{:.2}", f64::from(pixels.0) * css),
                    height: format!("{:.2}", f64::from(pixels.1) * css),
                }
            };
            let doc = vector::document(&svg, device, &extent)?;
            if format == Format::Svg {
                Ok(vector::finish_svg(&doc, opts.svg_text)?.into_bytes())
            } else {
                vector::pdf(&doc)
            }
        }
    }
}

/// Encodes an RGB image as PNG with the best compression (plotters' encoder uses the
/// fastest, which makes README plots several times larger) and its resolution in a `pHYs`
/// chunk.
fn encode_png(rgb: &[u8], (w, h): (u32, u32), dpi: f64) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Best);
        encoder.set_filter(png::FilterType::Paeth);
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let per_metre = (dpi / 0.0254).round() as u32;
        encoder.set_pixel_dims(Some(png::PixelDimensions {
            xppu: per_metre,
            yppu: per_metre,
            unit: png::Unit::Meter,
        }));
        let encoding = |e: png::EncodingError| PlotError::Draw(format!("PNG encoding: {e}"));
        let mut writer = encoder.write_header().map_err(encoding)?;
        writer.write_image_data(rgb).map_err(encoding)?;
        writer.finish().map_err(encoding)?;
    }
    Ok(out)
}

/// A text style of the shipped font at `size` pixels.
#[must_use]
pub fn font(size: f64) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A figure with text in every position plotters puts it (title, rotated axis label,
    /// legend), to prove the font path works without system fonts.
    fn figure() -> xy::StackedFigure {
        let t: Vec<f64> = (0..200).map(|i| f64::from(i) * 0.05).collect();
        xy::StackedFigure {
            title: "test — α(t)".into(),
            subtitle: "M = 1, a = 0.4".into(),
            width: 640,
            panel_height: 240,
            panels: vec![
                xy::Panel::new("time (s)", "angle (rad)").with_series(xy::Series::line(
                    "alpha",
                    t.iter().map(|&t| (t, t.sin())).collect(),
                )),
                xy::Panel::new("time (s)", "relative energy error")
                    .with_y_scale(xy::Scale::Log)
                    .with_series(xy::Series::line(
                        "|E − E₀|/E_s",
                        t.iter().map(|&t| (t, 1e-15 * (1.0 + t))).collect(),
                    )),
            ],
        }
    }

    #[test]
    fn png_and_svg_are_written_with_the_shipped_font() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("plot.png");
        let svg = dir.path().join("plot.svg");
        save(&figure(), &png).unwrap();
        save(&figure(), &svg).unwrap();
        let bytes = std::fs::read(&png).unwrap();
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
        assert!(bytes.len() > 1000);
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg"), "no SVG root");
        assert!(text.contains("angle (rad)"));
        // Only the two plots: no temporary file is left beside them.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn a_single_column_png_is_1020_pixels_wide_at_300_dpi() {
        let opts = FigureOptions {
            size: Some(options::Size::parse("single").unwrap()),
            ..FigureOptions::default()
        };
        let bytes = render(&figure(), Format::Png, &opts).unwrap();
        let reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let info = reader.info();
        // 3.4 in at 300 dpi, to the rounding of the layout to whole pixels.
        assert!((i64::from(info.width) - 1020).abs() <= 3, "{}", info.width);
        let dims = info.pixel_dims.unwrap();
        assert_eq!(dims.unit, png::Unit::Meter);
        // 300 dots per inch is 11811 per metre.
        assert_eq!(dims.xppu, 11811);
    }

    #[test]
    fn downsampling_averages_blocks() {
        // 2 × 1 image at k = 2: a black block and a half-white block.
        let mut big = vec![0u8; 4 * 2 * 3];
        for (i, px) in big.chunks_mut(3).enumerate() {
            let (x, y) = (i % 4, i / 4);
            let v = if x >= 2 && y == 0 { 255 } else { 0 };
            px.copy_from_slice(&[v, v, v]);
        }
        assert_eq!(downsample(&big, (2, 1), 2), vec![0, 0, 0, 128, 128, 128]);
    }

    #[test]
    fn unknown_extensions_are_refused_before_anything_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let err = save(&figure(), &dir.path().join("plot.jpg")).unwrap_err();
        assert!(err.to_string().contains(".png, .svg or .pdf"), "{err}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
