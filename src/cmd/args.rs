//! Parsing helpers shared by the subcommands' flags.

use std::f64::consts::PI;

use anyhow::{Context, Result, bail};
use nalgebra::Vector3;

/// Parses an angle or any number: `1.5`, `1e-3`, `pi`, `-pi/2`, `2pi/3`, `3*pi/4`.
///
/// The grammar is strict: a number; or an optional sign and coefficient, an optional single
/// `*`, `pi`, and an optional `/DIVISOR` (a finite, non-zero number). An expression must give
/// a finite value, and a number that underflows to zero (`1e-999`) is refused rather than read
/// as 0; `2**pi`, `pi*2` and `2pi/0` are not angles.
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

    #[test]
    fn angle_expressions_are_strict() {
        for bad in [
            "2**pi",
            "pi*2",
            "2pi/0",
            "1e999pi",
            "1e-999",
            "3pi/1e-999",
            "2 * * pi",
        ] {
            assert_eq!(parse_angle(bad), None, "{bad}");
        }
        assert_eq!(parse_angle("0"), Some(0.0));
        assert_eq!(parse_angle("0.0e-5"), Some(0.0));
        assert!(
            parse_angle("nan").is_some_and(f64::is_nan),
            "left to the domain check"
        );
    }

    use proptest::prelude::*;

    /// `PROPTEST_CASES` cases when set, else `default_cases`.
    fn proptest_config(default_cases: u32) -> ProptestConfig {
        let cases = std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default_cases);
        ProptestConfig::with_cases(cases)
    }

    /// The valid angles of the seed corpus `fuzz/corpus/angle/angles.txt`, one a line.
    fn corpus() -> Vec<String> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/corpus/angle/angles.txt");
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect()
    }

    #[test]
    fn fuzz_corpus_angles_parse() {
        for angle in corpus() {
            assert!(parse_angle(&angle).is_some_and(f64::is_finite), "{angle}");
        }
    }

    proptest! {
        #![proptest_config(proptest_config(500))]

        #[test]
        fn fuzz_angle_arbitrary_text(text in "\\PC{0,40}") {
            if let Some(x) = parse_angle(&text) {
                // A value, or a NaN/infinity left to the parameter's domain check.
                prop_assert!(x.is_finite() || text.to_ascii_lowercase().contains("nan")
                    || text.to_ascii_lowercase().contains("inf"));
            }
        }

        #[test]
        fn fuzz_angle_expressions(
            sign in "[-+]?",
            coefficient in "[0-9.eE+-]{0,8}",
            star in "[*]{0,2}",
            pi in "(pi|PI|p|)",
            divisor in "(/[0-9.eE+-]{0,8})?",
        ) {
            let text = format!("{sign}{coefficient}{star}{pi}{divisor}");
            if let Some(x) = parse_angle(&text) {
                prop_assert!(x.is_finite() || text.to_ascii_lowercase().contains("inf")
                    || text.to_ascii_lowercase().contains("nan"), "{text} -> {x}");
            }
        }

        #[test]
        fn fuzz_angle_mutated_corpus(
            seed in any::<prop::sample::Index>(),
            insert in "\\PC{0,4}",
            at in any::<prop::sample::Index>(),
        ) {
            let seeds = corpus();
            let seed = &seeds[seed.index(seeds.len())];
            let chars: Vec<char> = seed.chars().collect();
            let k = at.index(chars.len() + 1);
            let text: String = chars[..k].iter().chain(insert.chars().collect::<Vec<_>>().iter())
                .chain(chars[k..].iter()).collect();
            let _ = parse_angle(&text);
        }
    }
}
