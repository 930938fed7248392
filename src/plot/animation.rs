//! Animations: a 3D view of a body in motion, frame by frame, encoded as an animated GIF.
//!
//! A frame is a [`Shot`]: 3D polylines and dots in the lab frame (z up), a trail, and a line
//! of text. The camera looks at the origin from an azimuth and an elevation (orthographic: a
//! physicist's view, distances along the screen are true), scaled so that a sphere of the
//! scene's radius fills most of the frame. Frames are drawn at twice their size with the
//! shipped font ([`super::text::ShapedText`]), averaged down, quantized to 256 colours (NeuQuant,
//! by the `gif` crate) and written whole or not at all.

use std::path::Path;

use anyhow::{Context, Result, anyhow};
use plotters::prelude::*;

use super::{font, text};
use crate::output;

/// A 3D polyline.
#[derive(Debug, Clone)]
pub struct Line {
    /// Points in the lab frame.
    pub points: Vec<[f64; 3]>,
    /// Colour.
    pub colour: RGBColor,
    /// Width in pixels.
    pub width: u32,
}

/// One frame's content.
#[derive(Debug, Clone, Default)]
pub struct Shot {
    /// Lines, drawn in order.
    pub lines: Vec<Line>,
    /// Dots: centre, radius in pixels, colour.
    pub dots: Vec<([f64; 3], u32, RGBColor)>,
    /// The caption (time, energy error).
    pub caption: String,
}

/// The camera and the frame.
#[derive(Debug, Clone, Copy)]
pub struct View {
    /// Frame size in pixels.
    pub size: (u32, u32),
    /// Azimuth of the camera about the vertical (rad).
    pub azimuth: f64,
    /// Elevation of the camera above the horizontal (rad).
    pub elevation: f64,
    /// Radius of the scene (m): a sphere of it fills 80 % of the frame's smaller side.
    pub radius: f64,
}

impl View {
    /// Screen coordinates (pixels, at `scale` device pixels each) of lab point `p`.
    fn project(&self, p: [f64; 3], scale: f64) -> (i32, i32) {
        let (sa, ca) = self.azimuth.sin_cos();
        let (se, ce) = self.elevation.sin_cos();
        // Camera axes: right = (−sin a, cos a, 0), up = (−sin e cos a, −sin e sin a, cos e).
        let right = -sa * p[0] + ca * p[1];
        let up = -se * ca * p[0] - se * sa * p[1] + ce * p[2];
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let k = 0.4 * w.min(h) / self.radius.max(f64::MIN_POSITIVE);
        (
            ((w / 2.0 + k * right) * scale).round() as i32,
            ((h / 2.0 - k * up) * scale).round() as i32,
        )
    }
}

/// Draws one frame on `root` at `scale` device pixels per pixel.
fn draw<DB: DrawingBackend>(
    view: &View,
    shot: &Shot,
    title: &str,
    root: &DrawingArea<DB, plotters::coord::Shift>,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    // The lab axes, faint: x, y, z from the origin.
    let axes = [
        ([1.0, 0.0, 0.0], "x"),
        ([0.0, 1.0, 0.0], "y"),
        ([0.0, 0.0, 1.0], "z"),
    ];
    for (dir, name) in axes {
        let end = dir.map(|c| c * view.radius * 0.9);
        let grey = RGBColor(0xb0, 0xb0, 0xb0);
        root.draw(&PathElement::new(
            vec![view.project([0.0; 3], scale), view.project(end, scale)],
            grey.stroke_width(scale.round() as u32),
        ))?;
        root.draw(&Text::new(
            name.to_string(),
            view.project(end, scale),
            font(13.0 * scale).color(&grey),
        ))?;
    }
    for line in &shot.lines {
        let points: Vec<(i32, i32)> = line
            .points
            .iter()
            .map(|&p| view.project(p, scale))
            .collect();
        root.draw(&PathElement::new(
            points,
            line.colour
                .stroke_width(((f64::from(line.width) * scale).round() as u32).max(1)),
        ))?;
    }
    for &(p, r, colour) in &shot.dots {
        root.draw(&Circle::new(
            view.project(p, scale),
            ((f64::from(r) * scale).round() as i32).max(1),
            colour.filled(),
        ))?;
    }
    root.draw(&Text::new(
        title.to_string(),
        ((12.0 * scale) as i32, (10.0 * scale) as i32),
        font(16.0 * scale).color(&BLACK),
    ))?;
    root.draw(&Text::new(
        shot.caption.clone(),
        (
            (12.0 * scale) as i32,
            ((f64::from(view.size.1) - 28.0) * scale) as i32,
        ),
        font(14.0 * scale).color(&RGBColor(64, 64, 64)),
    ))?;
    Ok(())
}

/// Device pixels per frame pixel while drawing (averaged down: smooth lines).
const SUPERSAMPLE: u32 = 2;

/// Writes `shots` as an animated GIF at `fps` frames per second (looping) to `path`, whole or
/// not at all.
///
/// # Errors
/// An unwritable destination, a frame larger than a GIF holds, a drawing or encoding error.
pub fn write_gif(path: &Path, view: &View, title: &str, shots: &[Shot], fps: f64) -> Result<()> {
    super::register_fonts()?;
    let (w, h) = view.size;
    let (gw, gh) = (
        u16::try_from(w).map_err(|_| anyhow!("a GIF is at most 65535 pixels wide"))?,
        u16::try_from(h).map_err(|_| anyhow!("a GIF is at most 65535 pixels high"))?,
    );
    let dest = output::Destination::check(path)?;
    let scratch = dest.scratch()?;
    // Whether every frame was written: a signal (when the command installed the handlers)
    // stops between frames, and the scratch file is then removed unwritten.
    let written = (|| -> Result<bool> {
        let file = std::io::BufWriter::new(std::fs::File::create(&scratch)?);
        let mut encoder = gif::Encoder::new(file, gw, gh, &[])?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        // GIF delays are in hundredths of a second.
        let delay = (100.0 / fps).round().clamp(1.0, 65535.0) as u16;
        let big = (w * SUPERSAMPLE, h * SUPERSAMPLE);
        let mut rgb = vec![255u8; big.0 as usize * big.1 as usize * 3];
        for shot in shots {
            if crate::signals::interrupted().is_some() {
                return Ok(false);
            }
            {
                let root = text::ShapedText::new(BitMapBackend::with_buffer(&mut rgb, big))
                    .into_drawing_area();
                draw(view, shot, title, &root, f64::from(SUPERSAMPLE))
                    .and_then(|()| root.present())
                    .map_err(|e| anyhow!("{e}"))?;
            }
            let small = super::downsample(&rgb, (w, h), SUPERSAMPLE);
            let mut frame = gif::Frame::from_rgb_speed(gw, gh, &small, 10);
            frame.delay = delay;
            encoder.write_frame(&frame)?;
        }
        Ok(true)
    })();
    if !written.with_context(|| format!("cannot write {}", path.display()))? {
        let code = crate::signals::interrupted().unwrap_or(130);
        return Err(crate::signals::Interrupted {
            code,
            message: format!("{} was not written", path.display()),
        }
        .into());
    }
    dest.commit_scratch(scratch)?;
    Ok(())
}

/// A circle of `radius` in the plane spanned by `u` and `v` about `centre`, as `n` segments.
#[must_use]
pub fn circle(centre: [f64; 3], u: [f64; 3], v: [f64; 3], radius: f64, n: usize) -> Vec<[f64; 3]> {
    (0..=n)
        .map(|k| {
            let s = std::f64::consts::TAU * k as f64 / n as f64;
            let (sn, cs) = s.sin_cos();
            [0, 1, 2].map(|i| centre[i] + radius * (cs * u[i] + sn * v[i]))
        })
        .collect()
}
