//! Animations: frames rendered by the caller (RGB, row by row), captioned here with the shipped
//! font ([`super::text::ShapedText`]) and encoded as an animated GIF (quantized to 256 colours
//! per frame by NeuQuant, the `gif` crate) or an H.264 MP4 (the full-colour frames piped to
//! `ffmpeg`), written whole or not at all.

use std::io::Write as _;
use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use plotters::prelude::*;

use crate::output;
use tumble_plot::{font, text};

/// Text over a frame: a title, a caption and labels at device positions.
pub struct Captions<'a> {
    /// Top left.
    pub title: &'a str,
    /// Bottom left (the time, the energy error).
    pub caption: &'a str,
    /// Labels: text, position (device pixels), colour.
    pub labels: &'a [(String, (i32, i32), [u8; 3])],
}

/// Writes `captions` over the RGB frame `rgb` of `size` device pixels, `scale` device pixels
/// per frame pixel.
///
/// # Errors
/// A drawing error (a font that cannot be loaded).
pub fn caption(rgb: &mut [u8], size: (u32, u32), scale: f64, captions: &Captions) -> Result<()> {
    tumble_plot::register_fonts()?;
    let root = text::ShapedText::new(BitMapBackend::with_buffer(rgb, size)).into_drawing_area();
    (|| -> Result<(), DrawingAreaErrorKind<_>> {
        for (label, at, [r, g, b]) in captions.labels {
            root.draw(&Text::new(
                label.clone(),
                *at,
                font(13.0 * scale).color(&RGBColor(*r, *g, *b)),
            ))?;
        }
        root.draw(&Text::new(
            captions.title.to_string(),
            ((12.0 * scale) as i32, (10.0 * scale) as i32),
            font(16.0 * scale).color(&BLACK),
        ))?;
        root.draw(&Text::new(
            captions.caption.to_string(),
            (
                (12.0 * scale) as i32,
                (f64::from(size.1) - 28.0 * scale) as i32,
            ),
            font(14.0 * scale).color(&RGBColor(64, 64, 64)),
        ))?;
        root.present()
    })()
    .map_err(|e| anyhow!("{e}"))
}

/// The container of an animation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Container {
    /// An animated GIF (looping).
    Gif,
    /// An MP4 (H.264, yuv420p, fast start), encoded by `ffmpeg`.
    Mp4,
}

/// Writes `count` frames of `size` pixels at `fps` frames per second to `path` as `container`,
/// whole or not at all; `frame(k, rgb)` fills frame `k` (RGB bytes, row by row). A signal (when
/// the command installed the handlers) stops between frames, and nothing is then written.
///
/// # Errors
/// An unwritable destination, a frame larger than a GIF holds, an odd MP4 size, a rendering or
/// encoding error, `ffmpeg` failing.
pub fn write(
    path: &Path,
    container: Container,
    size: (u32, u32),
    fps: f64,
    count: usize,
    frame: &mut dyn FnMut(usize, &mut [u8]) -> Result<()>,
) -> Result<()> {
    let (w, h) = size;
    let dest = output::Destination::check(path)?;
    let scratch = dest.scratch()?;
    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    let written = (|| -> Result<bool> {
        match container {
            Container::Gif => {
                let (gw, gh) = (
                    u16::try_from(w).map_err(|_| anyhow!("a GIF is at most 65535 pixels wide"))?,
                    u16::try_from(h).map_err(|_| anyhow!("a GIF is at most 65535 pixels high"))?,
                );
                let file = std::io::BufWriter::new(std::fs::File::create(&scratch)?);
                let mut encoder = gif::Encoder::new(file, gw, gh, &[])?;
                encoder.set_repeat(gif::Repeat::Infinite)?;
                // GIF delays are in hundredths of a second.
                let delay = (100.0 / fps).round().clamp(1.0, 65535.0) as u16;
                for k in 0..count {
                    if crate::signals::interrupted().is_some() {
                        return Ok(false);
                    }
                    frame(k, &mut rgb)?;
                    let mut f = gif::Frame::from_rgb_speed(gw, gh, &rgb, 10);
                    f.delay = delay;
                    encoder.write_frame(&f)?;
                }
                Ok(true)
            }
            Container::Mp4 => {
                if w % 2 != 0 || h % 2 != 0 {
                    bail!("an MP4's frame has even sides; {w}x{h} has not");
                }
                let mut child = std::process::Command::new("ffmpeg")
                    .args([
                        "-y",
                        "-loglevel",
                        "error",
                        "-f",
                        "rawvideo",
                        "-pix_fmt",
                        "rgb24",
                    ])
                    .args([
                        "-s",
                        &format!("{w}x{h}"),
                        "-r",
                        &format!("{fps}"),
                        "-i",
                        "-",
                    ])
                    .args([
                        "-c:v",
                        "libx264",
                        "-pix_fmt",
                        "yuv420p",
                        "-crf",
                        "18",
                        "-movflags",
                        "+faststart",
                        "-f",
                        "mp4",
                    ])
                    .arg(scratch.as_os_str())
                    .stdin(std::process::Stdio::piped())
                    .spawn()
                    .context("cannot start ffmpeg")?;
                let mut stdin = child.stdin.take().context("no pipe to ffmpeg")?;
                let mut complete = true;
                for k in 0..count {
                    if crate::signals::interrupted().is_some() {
                        complete = false;
                        break;
                    }
                    frame(k, &mut rgb)?;
                    if stdin.write_all(&rgb).is_err() {
                        break;
                    }
                }
                drop(stdin);
                let status = child.wait()?;
                if !complete {
                    return Ok(false);
                }
                if !status.success() {
                    bail!("ffmpeg failed ({status})");
                }
                Ok(true)
            }
        }
    })();
    // On every path but the commit, the scratch file is removed when dropped.
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
