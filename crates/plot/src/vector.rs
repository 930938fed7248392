//! Vector output: SVG with the shipped font embedded or its text as paths, and PDF.
//!
//! plotters' SVG backend writes whole-pixel coordinates. A figure is therefore drawn at
//! [`SUBPIXEL`] device units per pixel and the document's `viewBox` maps those units back
//! onto its size, so every coordinate is kept to 0.01 px: curves do not step when a paper
//! scales the figure.
//!
//! * **Text.** `--svg-text font` (the default) keeps `<text>` elements and embeds the shipped
//!   DejaVu Sans in the file (`@font-face` with the TrueType data); `--svg-text paths`
//!   converts every glyph to a path (usvg's text layout with the same font), for viewers
//!   that ignore embedded fonts.
//! * **PDF.** The SVG is parsed by usvg (text laid out with the shipped font) and converted
//!   by svg2pdf, which embeds the font as a subset: the format LaTeX includes directly.
//!   Physical size: 96 SVG pixels per inch, as CSS defines it.

use std::sync::{Arc, OnceLock};

use crate::{PlotError, Result};
use base64::Engine as _;

use super::options::{CSS_DPI, SvgText};
use super::{DEJAVU_SANS, FONT};

/// Device units per figure pixel in vector output.
pub const SUBPIXEL: f64 = 100.0;

/// The family name inside the shipped font file.
pub const FAMILY: &str = "DejaVu Sans";

/// The size attributes of the document's root: `(width, height)`, in inches when the figure
/// has a physical size (`3.4in`), else in pixels.
pub struct Extent {
    /// `width` attribute.
    pub width: String,
    /// `height` attribute.
    pub height: String,
}

/// Turns plotters' SVG of `device` units into the document: the root's size set to
/// `extent` (its `viewBox` keeps the device units) and the text in the shipped family.
///
/// # Errors
/// If the input has no root element of the expected form (a plotters change).
pub fn document(svg: &str, device: (u32, u32), extent: &Extent) -> Result<String> {
    let old = format!(r#"<svg width="{}" height="{}""#, device.0, device.1);
    let new = format!(
        r#"<svg width="{}" height="{}""#,
        extent.width, extent.height
    );
    if !svg.contains(&old) {
        return Err(PlotError::Draw(
            "unexpected SVG root element from the plot backend".to_string(),
        ));
    }
    Ok(svg.replacen(&old, &new, 1).replace(
        &format!(r#"font-family="{FONT}""#),
        &format!(r#"font-family="{FAMILY}""#),
    ))
}

/// The finished SVG file for `doc` (from [`document`]) with text written as `text` says.
///
/// # Errors
/// If usvg cannot read the document (converting text to paths).
pub fn finish_svg(doc: &str, text: SvgText) -> Result<String> {
    match text {
        SvgText::Font => Ok(with_embedded_font(doc)),
        SvgText::Paths => {
            let tree = parse(doc)?;
            let options = usvg::WriteOptions {
                coordinates_precision: 2,
                transforms_precision: 6,
                ..usvg::WriteOptions::default()
            };
            Ok(tree.to_string(&options))
        }
    }
}

/// `doc` with the shipped font embedded as an `@font-face` rule after the root's opening tag.
fn with_embedded_font(doc: &str) -> String {
    static FACE: OnceLock<String> = OnceLock::new();
    let face = FACE.get_or_init(|| {
        format!(
            "<defs><style>@font-face{{font-family:'{FAMILY}';src:url(data:font/ttf;base64,{})\
             format('truetype');}}</style></defs>\n",
            base64::engine::general_purpose::STANDARD.encode(DEJAVU_SANS)
        )
    });
    match doc
        .find("<svg")
        .and_then(|i| doc[i..].find('>').map(|j| i + j + 1))
    {
        Some(end) => {
            let mut out = String::with_capacity(doc.len() + face.len() + 1);
            out.push_str(&doc[..end]);
            out.push('\n');
            out.push_str(face);
            out.push_str(doc[end..].trim_start_matches('\n'));
            out
        }
        None => doc.to_string(),
    }
}

/// The PDF of `doc` (from [`document`]), the shipped font embedded as a subset.
///
/// # Errors
/// If usvg cannot read the document or svg2pdf cannot convert it.
pub fn pdf(doc: &str) -> Result<Vec<u8>> {
    let tree = parse(doc)?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions {
            dpi: CSS_DPI as f32,
        },
    )
    .map_err(|e| PlotError::Draw(format!("PDF conversion failed: {e}")))
}

/// usvg's options with the shipped font as the only font (and the `sans-serif` family).
fn usvg_options() -> &'static usvg::Options<'static> {
    static OPTIONS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(DEJAVU_SANS.to_vec());
        db.set_sans_serif_family(FAMILY);
        usvg::Options {
            fontdb: Arc::new(db),
            font_family: FAMILY.to_string(),
            dpi: CSS_DPI as f32,
            ..usvg::Options::default()
        }
    })
}

/// Parses an SVG document with the shipped font.
///
/// # Errors
/// usvg's parse error.
pub fn parse(doc: &str) -> Result<usvg::Tree> {
    usvg::Tree::from_str(doc, usvg_options())
        .map_err(|e| PlotError::Draw(format!("the SVG cannot be read back: {e}")))
}
