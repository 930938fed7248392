//! Colours: a palette for series and the viridis map for heatmaps.
//!
//! * [`series`]: the Okabe–Ito palette (Okabe & Ito 2008, "Color Universal Design"), which
//!   stays distinguishable under the common colour-vision deficiencies; yellow is left out
//!   because it vanishes on white.
//! * [`viridis`]: the perceptually uniform map of matplotlib (van der Walt & Smith 2015),
//!   linear between its eleven tabulated stops, for heatmaps and their colour bars.

use plotters::style::RGBColor;

/// Okabe–Ito without yellow: blue, vermillion, bluish green, orange, reddish purple, sky
/// blue, black.
const OKABE_ITO: [RGBColor; 7] = [
    RGBColor(0x00, 0x72, 0xB2),
    RGBColor(0xD5, 0x5E, 0x00),
    RGBColor(0x00, 0x9E, 0x73),
    RGBColor(0xE6, 0x9F, 0x00),
    RGBColor(0xCC, 0x79, 0xA7),
    RGBColor(0x56, 0xB4, 0xE9),
    RGBColor(0x00, 0x00, 0x00),
];

/// Number of distinct series colours.
pub const SERIES_COLOURS: usize = OKABE_ITO.len();

/// The colour of the `i`-th series (cycling after seven).
#[must_use]
pub fn series(i: usize) -> RGBColor {
    OKABE_ITO[i % OKABE_ITO.len()]
}

/// Viridis at 0, 0.1, …, 1 (matplotlib's `viridis`, 11 stops).
const VIRIDIS: [(u8, u8, u8); 11] = [
    (0x44, 0x01, 0x54),
    (0x48, 0x24, 0x75),
    (0x41, 0x44, 0x87),
    (0x35, 0x5f, 0x8d),
    (0x2a, 0x78, 0x8e),
    (0x21, 0x91, 0x8c),
    (0x22, 0xa8, 0x84),
    (0x44, 0xbf, 0x70),
    (0x7a, 0xd1, 0x51),
    (0xbd, 0xdf, 0x26),
    (0xfd, 0xe7, 0x25),
];

/// Viridis at `x ∈ [0, 1]` (clamped; NaN gives the low end), dark purple to yellow.
#[must_use]
pub fn viridis(x: f64) -> RGBColor {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let pos = x * (VIRIDIS.len() - 1) as f64;
    let i = (pos.floor() as usize).min(VIRIDIS.len() - 2);
    let f = pos - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + f * (f64::from(q) - f64::from(p))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_hits_its_stops_and_clamps() {
        assert_eq!(viridis(0.0), RGBColor(0x44, 0x01, 0x54));
        assert_eq!(viridis(0.5), RGBColor(0x21, 0x91, 0x8c));
        assert_eq!(viridis(1.0), RGBColor(0xfd, 0xe7, 0x25));
        assert_eq!(viridis(-3.0), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        // Half-way between two stops is their mean.
        let RGBColor(r, g, b) = viridis(0.05);
        assert_eq!((r, g, b), (0x46, 0x13, 0x65));
    }

    #[test]
    fn series_colours_cycle() {
        assert_eq!(series(0), series(7));
        assert_ne!(series(0), series(1));
    }
}
