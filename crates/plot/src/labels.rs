//! Numbers and parameters as figures write them: symbols from
//! [`tumble_scenarios::display::symbol`], values rounded to what a reader needs (`θ₀ = π/2`,
//! `ω_earth = 7.29211×10⁻⁵`).

use std::f64::consts::PI;

use tumble_scenarios::display::symbol;

use super::log_axis::superscript;

/// `v` for a label: a simple multiple of π as such (`π/2`, `−3π/4`, `2π`, denominators up
/// to 12), else at most six significant digits — plainly for `10⁻³ ≤ |v| < 10⁶`, else as
/// `m×10ᵏ`.
#[must_use]
pub fn value(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".to_string();
    }
    if let Some(s) = pi_multiple(v) {
        return s;
    }
    let sign = if v < 0.0 { "−" } else { "" };
    let a = v.abs();
    // Six significant digits, read back so the shortest form of the rounded value prints.
    let rounded: f64 = format!("{a:.5e}").parse().unwrap_or(a);
    if (1e-3..1e6).contains(&rounded) {
        return format!("{sign}{rounded}");
    }
    let k = rounded.log10().floor() as i32;
    let m: f64 = format!("{:.5}", rounded / 10f64.powi(k))
        .parse()
        .unwrap_or(1.0);
    if m == 1.0 {
        format!("{sign}10{}", superscript(k))
    } else {
        format!("{sign}{m}×10{}", superscript(k))
    }
}

/// `p π / q` with `q ≤ 12` and `|p| ≤ 4q` when `v` is that to 1e-12 relative.
fn pi_multiple(v: f64) -> Option<String> {
    (1..=12i64).find_map(|q| {
        let p = (v * q as f64 / PI).round();
        if p == 0.0 || p.abs() > 4.0 * q as f64 {
            return None;
        }
        let p = p as i64;
        if gcd(p.unsigned_abs(), q.unsigned_abs()) != 1 {
            return None;
        }
        let exact = p as f64 * PI / q as f64;
        ((v - exact).abs() <= 1e-12 * v.abs()).then(|| {
            let sign = if p < 0 { "−" } else { "" };
            let n = p.unsigned_abs();
            let numerator = if n == 1 {
                "π".to_string()
            } else {
                format!("{n}π")
            };
            if q == 1 {
                format!("{sign}{numerator}")
            } else {
                format!("{sign}{numerator}/{q}")
            }
        })
    })
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// `name = value` pairs in symbols, comma-separated: `M = 1, a = 0.4, ω₀ = 5, α₀ = 3.1`.
#[must_use]
pub fn parameters<'a>(params: impl Iterator<Item = (&'a str, f64)>) -> String {
    params
        .map(|(k, v)| format!("{} = {}", symbol(k), value(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// An axis label: the symbol of `name` and its unit in parentheses (`ω₀ (rad/s)`).
#[must_use]
pub fn axis(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        symbol(name)
    } else {
        format!("{} ({unit})", symbol(name))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_rounded_and_pi_is_recognised() {
        assert_eq!(value(PI / 2.0), "π/2");
        // The value as a CSV or manifest writes it.
        let written: f64 = "1.5707963267948966".parse().unwrap();
        assert_eq!(value(written), "π/2");
        assert_eq!(value(-3.0 * PI / 4.0), "−3π/4");
        assert_eq!(value(2.0 * PI), "2π");
        assert_eq!(value(PI), "π");
        assert_eq!(value(PI / 12.0), "π/12");
        // Close to, but not, a multiple of π.
        assert_eq!(value(3.1), "3.1");
        let near: f64 = "1.5708".parse().unwrap();
        assert_eq!(value(near), "1.5708");
        // 7.292115e-5 is 7.29211499…e-5 in binary: six digits round down.
        assert_eq!(value(0.00007292115), "7.29211×10⁻⁵");
        assert_eq!(value(9.81), "9.81");
        assert_eq!(value(1.0), "1");
        assert_eq!(value(-0.4), "−0.4");
        assert_eq!(value(123456789.0), "1.23457×10⁸");
        assert_eq!(value(1e-7), "10⁻⁷");
        assert_eq!(value(0.0), "0");
    }

    #[test]
    fn parameters_are_written_in_symbols() {
        let p = [
            ("theta0", PI / 2.0),
            ("omega_earth", 7.292115e-5),
            ("M", 1.0),
        ];
        assert_eq!(
            parameters(p.into_iter()),
            "θ₀ = π/2, ω_earth = 7.29211×10⁻⁵, M = 1"
        );
        assert_eq!(axis("omega0", "rad/s"), "ω₀ (rad/s)");
        assert_eq!(axis("h", ""), "h");
    }
}
