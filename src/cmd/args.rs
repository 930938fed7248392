//! Parsing helpers shared by the subcommands' flags.

use std::f64::consts::PI;

use anyhow::{Context, Result, bail};
use nalgebra::Vector3;

/// Parses an angle or any number: `1.5`, `pi`, `-pi/2`, `2pi/3`, `3*pi/4`.
pub fn parse_angle(s: &str) -> Option<f64> {
    let t = s.trim().to_ascii_lowercase().replace(' ', "");
    if let Ok(x) = t.parse::<f64>() {
        return Some(x);
    }
    let (num, den) = match t.split_once('/') {
        Some((n, d)) => (n.to_string(), d.parse::<f64>().ok()?),
        None => (t.clone(), 1.0),
    };
    let coeff = num.strip_suffix("pi")?.trim_end_matches('*');
    let c = match coeff {
        "" | "+" => 1.0,
        "-" => -1.0,
        other => other.parse::<f64>().ok()?,
    };
    Some(c * PI / den)
}

/// Parses one `--set KEY=VALUE` (the value a number or an angle expression) into the trimmed
/// key and the value; `example` completes the message of a malformed one (`omega0=5`).
pub fn parse_set<'a>(raw: &'a str, example: &str) -> Result<(&'a str, f64)> {
    let Some((key, value)) = raw.split_once('=') else {
        bail!("--set {raw}: expected KEY=VALUE, e.g. --set {example} or --set alpha0=pi/2");
    };
    let key = key.trim();
    if key.is_empty() {
        bail!("--set {raw}: the key is empty");
    }
    let Some(x) = parse_angle(value) else {
        bail!(
            "--set {raw}: `{}` is not a number (numbers and angle expressions such as 2.5, \
             1e-3, pi/2, -3pi/4 are accepted)",
            value.trim()
        );
    };
    Ok((key, x))
}

/// Parses three comma-separated numbers (angle expressions allowed) for the flag `--{flag}`;
/// every value must be finite.
pub fn parse_triple(flag: &str, s: &str) -> Result<Vector3<f64>> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        bail!(
            "--{flag} expects three comma-separated values, got {} in `{s}`",
            parts.len()
        );
    }
    let mut v = Vector3::zeros();
    for (i, p) in parts.iter().enumerate() {
        let x = parse_angle(p)
            .with_context(|| format!("--{flag}: value {} (`{p}`) is not a number", i + 1))?;
        if !x.is_finite() {
            bail!("--{flag}: value {} (`{p}`) is not finite", i + 1);
        }
        v[i] = x;
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_expressions_parse() {
        assert_eq!(parse_angle("1.5"), Some(1.5));
        assert_eq!(parse_angle("pi"), Some(PI));
        assert_eq!(parse_angle("-pi/2"), Some(-PI / 2.0));
        assert_eq!(parse_angle("2pi/3"), Some(2.0 * PI / 3.0));
        assert_eq!(parse_angle("3*pi/4"), Some(3.0 * PI / 4.0));
        assert_eq!(parse_angle("pie"), None);
        assert_eq!(parse_angle("x"), None);
    }
}
