//! A base-10 logarithmic axis and its labels, powers of ten written with superscripts
//! (`10⁻⁵`, `2×10⁻¹⁵`).

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

/// `10^k`, exactly as the decimal literal `1ek` reads.
fn decade(k: i32) -> f64 {
    times_decade(1, k)
}

/// `m·10^k`, exactly as the decimal literal `mek` reads.
fn times_decade(m: u32, k: i32) -> f64 {
    format!("{m}e{k}").parse::<f64>().unwrap_or(f64::NAN)
}

/// `k` in superscript digits: `⁻¹⁵`.
#[must_use]
pub fn superscript(k: i32) -> String {
    k.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

/// A positive value as a power of ten: `10⁻⁵` for a decade, `2×10⁻¹⁵` or `3.2×10⁻⁴` (two
/// significant digits) between decades; `0` and non-finite values as they print.
#[must_use]
pub fn power_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return format!("{v}");
    }
    let mut k = v.log10().floor() as i32;
    let mut m = v / decade(k);
    if (m - 10.0).abs() < 1e-6 {
        k += 1;
        m = 1.0;
    }
    let m = (m * 10.0).round() / 10.0;
    if (m - 1.0).abs() < 1e-9 {
        format!("10{}", superscript(k))
    } else if (m - m.round()).abs() < 1e-9 {
        format!("{m:.0}×10{}", superscript(k))
    } else {
        format!("{m:.1}×10{}", superscript(k))
    }
}

/// Labels of a logarithmic axis: [`power_label`].
pub fn log_label(v: &f64) -> String {
    power_label(*v)
}

/// A base-10 logarithmic axis over `[lo, hi]`, `0 < lo < hi`.
///
/// Written here rather than taken from plotters' `log_scale()`, whose tick search drops every
/// tick below `f64::EPSILON` (it takes them for the zero point) and can lose an end decade to
/// rounding: relative energy errors live at 1e-16. Bold ticks are whole decades (every k-th
/// when there are too many), light ones add 2…9 × each decade when they fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Log10Axis {
    lo: f64,
    hi: f64,
}

impl Log10Axis {
    /// The axis over `range`; `None` unless `0 < start < end` and both are finite.
    #[must_use]
    pub fn new(range: Range<f64>) -> Option<Self> {
        (range.start > 0.0 && range.end > range.start && range.end.is_finite()).then_some(
            Log10Axis {
                lo: range.start,
                hi: range.end,
            },
        )
    }
}

impl Log10Axis {
    /// `[10⁻¹⁶, 1]`: the axis of a panel with nothing to show.
    #[must_use]
    pub fn fallback() -> Self {
        Log10Axis { lo: 1e-16, hi: 1.0 }
    }
}

impl Ranged for Log10Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (a, b) = (self.lo.log10(), self.hi.log10());
        // Non-positive values map far below the axis (and are clipped by the plot area).
        let f = if *value > 0.0 {
            ((value.log10() - a) / (b - a)).clamp(-10.0, 11.0)
        } else {
            -10.0
        };
        limit.0 + (f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let max = hint.max_num_points().max(1);
        let first = (self.lo.log10() - 1e-9).ceil() as i32;
        let last = (self.hi.log10() + 1e-9).floor() as i32;
        let count = usize::try_from(last - first + 1).unwrap_or(0);
        let stride = count.div_ceil(max).max(1);
        let mut points: Vec<f64> = (first..=last).step_by(stride).map(decade).collect();
        if count < 3 && !hint.weight().allow_light_points() {
            // Two decades or fewer: 2 and 5 times each decade are labelled too.
            points.extend(
                (first - 1..=last)
                    .flat_map(|k| [times_decade(2, k), times_decade(5, k)])
                    .filter(|v| (self.lo..=self.hi).contains(v)),
            );
            points.sort_by(f64::total_cmp);
        }
        if hint.weight().allow_light_points() && stride == 1 {
            let minor: Vec<f64> = (first - 1..=last)
                .flat_map(|k| (2..=9).map(move |m| times_decade(m, k)))
                .filter(|v| (self.lo..=self.hi).contains(v))
                .collect();
            if points.len() + minor.len() <= max {
                points.extend(minor);
            }
        }
        points
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_ten_are_written_with_superscripts() {
        assert_eq!(power_label(1e-5), "10⁻⁵");
        assert_eq!(power_label(1e4), "10⁴");
        assert_eq!(power_label(1.0), "10⁰");
        assert_eq!(power_label(2e-15), "2×10⁻¹⁵");
        assert_eq!(power_label(3.2e-4), "3.2×10⁻⁴");
        assert_eq!(power_label(9.9999999e-3), "10⁻²");
        assert_eq!(superscript(-1234567890), "⁻¹²³⁴⁵⁶⁷⁸⁹⁰");
    }

    #[test]
    fn log_axis_ticks_are_decades_even_below_machine_epsilon() {
        let axis = Log10Axis::new(1e-17..1e-14).unwrap();
        assert_eq!(
            axis.key_points(plotters::coord::ranged1d::BoldPoints(10)),
            [1e-17, 1e-16, 1e-15, 1e-14]
        );
        let all = axis.key_points(100);
        assert_eq!(all.len(), 4 + 3 * 8);
        assert!(all.contains(&5e-16));
        // Too many decades for the hint: every other one.
        let wide = Log10Axis::new(1e-20..1.0).unwrap();
        assert!(wide.key_points(10).len() <= 11);
        assert_eq!(axis.map(&1e-17, (0, 300)), 0);
        assert_eq!(axis.map(&1e-14, (0, 300)), 300);
        assert_eq!(axis.map(&1e-16, (0, 300)), 100);
        assert!(Log10Axis::new(0.0..1.0).is_none());
        // Within two decades, 2× and 5× each decade are labelled too.
        let narrow = Log10Axis::new(1e-15..1e-14).unwrap();
        assert_eq!(
            narrow.key_points(plotters::coord::ranged1d::BoldPoints(10)),
            [1e-15, 2e-15, 5e-15, 1e-14]
        );
    }
}
