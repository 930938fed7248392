//! Colours: a palette for series and the colour maps of heatmaps.
//!
//! * [`series`]: the Okabe–Ito palette (Okabe & Ito 2008, "Color Universal Design"), which
//!   stays distinguishable under the common colour-vision deficiencies; yellow is left out
//!   because it vanishes on white.
//! * [`ColourMap`]: the maps of heatmaps and their colour bars, each linear between eleven
//!   stops (at 0, 0.1, …, 1) of matplotlib's tables: [`viridis`] (the default) and magma, the
//!   perceptually uniform maps of van der Walt & Smith (2015); cividis, made to read the same
//!   to readers with a red–green colour-vision deficiency (Nuñez, Anderton & Renslow 2018,
//!   PLoS ONE 13, e0199239); and grey, for print in black and white.

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

/// Stops at 0, 0.1, …, 1 of a colour map.
type Stops = [(u8, u8, u8); 11];

/// Viridis (matplotlib's `viridis`).
const VIRIDIS: Stops = [
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

/// Cividis (matplotlib's `cividis`).
const CIVIDIS: Stops = [
    (0x00, 0x22, 0x4e),
    (0x08, 0x33, 0x70),
    (0x35, 0x45, 0x6c),
    (0x4f, 0x57, 0x6c),
    (0x66, 0x69, 0x70),
    (0x7d, 0x7c, 0x78),
    (0x94, 0x8e, 0x77),
    (0xae, 0xa3, 0x71),
    (0xc8, 0xb8, 0x66),
    (0xe5, 0xcf, 0x52),
    (0xfe, 0xe8, 0x38),
];

/// Magma (matplotlib's `magma`).
const MAGMA: Stops = [
    (0x00, 0x00, 0x04),
    (0x14, 0x0e, 0x36),
    (0x3b, 0x0f, 0x70),
    (0x64, 0x1a, 0x80),
    (0x8c, 0x29, 0x81),
    (0xb7, 0x37, 0x79),
    (0xde, 0x49, 0x68),
    (0xf7, 0x70, 0x5c),
    (0xfe, 0x9f, 0x6d),
    (0xfe, 0xcf, 0x92),
    (0xfc, 0xfd, 0xbf),
];

/// Grey from black to a light grey (0xe6, so that the top of the scale stays apart from the
/// white of the page and of missing cells) in equal steps.
const GREY: Stops = {
    let mut stops = [(0, 0, 0); 11];
    let mut i = 0;
    while i < 11 {
        let v = (i * 0xe6 / 10) as u8;
        stops[i] = (v, v, v);
        i += 1;
    }
    stops
};

/// The colour map of a heatmap and its colour bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum ColourMap {
    /// Dark purple to yellow, perceptually uniform.
    #[default]
    Viridis,
    /// Dark blue to yellow, for readers with a red–green colour-vision deficiency.
    Cividis,
    /// Black through purple and orange to pale yellow, perceptually uniform.
    Magma,
    /// Black to light grey, for print in black and white.
    Grey,
}

impl ColourMap {
    /// Every colour map, in the order of their documentation.
    pub const ALL: [ColourMap; 4] = [
        ColourMap::Viridis,
        ColourMap::Cividis,
        ColourMap::Magma,
        ColourMap::Grey,
    ];

    /// The map of a name as the command line writes it (`viridis`, `cividis`, `magma`,
    /// `grey`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "viridis" => Some(ColourMap::Viridis),
            "cividis" => Some(ColourMap::Cividis),
            "magma" => Some(ColourMap::Magma),
            "grey" => Some(ColourMap::Grey),
            _ => None,
        }
    }

    /// The colour at `x ∈ [0, 1]` (clamped; NaN gives the low end).
    #[must_use]
    pub fn at(self, x: f64) -> RGBColor {
        let stops = match self {
            ColourMap::Viridis => &VIRIDIS,
            ColourMap::Cividis => &CIVIDIS,
            ColourMap::Magma => &MAGMA,
            ColourMap::Grey => &GREY,
        };
        interpolate(stops, x)
    }
}

/// Viridis at `x ∈ [0, 1]` (clamped; NaN gives the low end), dark purple to yellow.
#[must_use]
pub fn viridis(x: f64) -> RGBColor {
    ColourMap::Viridis.at(x)
}

/// `stops` at `x ∈ [0, 1]`, linear between neighbouring stops (clamped; NaN gives the low end).
fn interpolate(stops: &Stops, x: f64) -> RGBColor {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let pos = x * (stops.len() - 1) as f64;
    let i = (pos.floor() as usize).min(stops.len() - 2);
    let f = pos - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
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

    /// Each map runs from dark to light: its relative luminance (Rec. 709 weights on the
    /// sRGB values, enough to order them) increases from stop to stop, so that larger values
    /// read as lighter in any map and in greyscale print.
    #[test]
    fn every_colour_map_grows_lighter_with_the_value() {
        for map in &ColourMap::ALL {
            let luminance = |x: f64| {
                let RGBColor(r, g, b) = map.at(x);
                0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
            };
            for k in 0..10 {
                let (lo, hi) = (f64::from(k) / 10.0, f64::from(k + 1) / 10.0);
                assert!(luminance(hi) > luminance(lo), "{map:?} at {lo} and {hi}");
            }
            assert_eq!(map.at(f64::NAN), map.at(0.0));
            assert_eq!(map.at(2.0), map.at(1.0));
        }
        assert_eq!(ColourMap::Grey.at(0.5), RGBColor(0x73, 0x73, 0x73));
        for (name, map) in ["viridis", "cividis", "magma", "grey"]
            .iter()
            .zip(ColourMap::ALL)
        {
            assert_eq!(ColourMap::from_name(name), Some(map));
        }
        assert_eq!(ColourMap::Cividis.at(0.0), RGBColor(0x00, 0x22, 0x4e));
    }

    #[test]
    fn series_colours_cycle() {
        assert_eq!(series(0), series(7));
        assert_ne!(series(0), series(1));
    }
}
