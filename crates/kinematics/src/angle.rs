//! Angle expressions: the numbers a user may write wherever an angle or any other parameter is
//! expected (`--set`, scene files, sweep files), so that `pi/2` means the same everywhere.

use std::f64::consts::PI;

/// What [`parse_angle`] accepts, for error messages (the same words wherever a value is read).
pub const ACCEPTED: &str =
    "numbers and angle expressions such as 2.5, 1e-3, pi/2, -3pi/4 are accepted";

/// Parses an angle or any number: `1.5`, `1e-3`, `pi`, `-pi/2`, `2pi/3`, `3*pi/4`.
///
/// The grammar is strict: a number; or an optional sign and coefficient, an optional single
/// `*`, `pi`, and an optional `/DIVISOR` (a finite, non-zero number). An expression must give
/// a finite value, and a number that underflows to zero (`1e-999`) is refused rather than read
/// as 0; `2**pi`, `pi*2` and `2pi/0` are not angles.
#[must_use]
pub fn parse_angle(s: &str) -> Option<f64> {
    let t = s.trim().to_ascii_lowercase().replace(' ', "");
    let number = |text: &str| -> Option<f64> {
        let x = text.parse::<f64>().ok()?;
        let nonzero_digits = text
            .split(['e', 'E'])
            .next()
            .is_some_and(|m| m.chars().any(|c| ('1'..='9').contains(&c)));
        (x.is_finite() && !(x == 0.0 && nonzero_digits)).then_some(x)
    };
    if let Ok(x) = t.parse::<f64>() {
        // `inf` and `nan` go on to the parameter's own check, which names the domain; an
        // underflow to zero is refused here.
        return if x.is_finite() { number(&t) } else { Some(x) };
    }
    let (num, den) = match t.split_once('/') {
        Some((n, d)) => (n, number(d).filter(|d| *d != 0.0)?),
        None => (t.as_str(), 1.0),
    };
    let coeff = num.strip_suffix("pi")?;
    let coeff = coeff.strip_suffix('*').unwrap_or(coeff);
    if coeff.ends_with('*') {
        return None;
    }
    let c = match coeff {
        "" | "+" => 1.0,
        "-" => -1.0,
        other => number(other)?,
    };
    let x = c * PI / den;
    (x.is_finite()).then_some(x)
}
