//! Parsing helpers shared by the subcommands' flags.

use anyhow::{Context, Result, bail};
use nalgebra::Vector3;

use tumble_kinematics::angle::ACCEPTED;
pub use tumble_kinematics::angle::parse_angle;

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
            "--set {raw}: `{}` is not a number ({ACCEPTED})",
            value.trim()
        );
    };
    Ok((key, x))
}

/// Refuses a key given twice among `--set` flags (`(key, the flag's text)` in command-line
/// order): the second would silently replace the first.
///
/// # Errors
/// The second flag that repeats a key, naming the first.
pub fn refuse_repeated_keys<'a>(sets: impl IntoIterator<Item = (&'a str, &'a str)>) -> Result<()> {
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for (key, raw) in sets {
        if let Some((_, first)) = seen.iter().find(|(k, _)| *k == key) {
            bail!("--set {raw}: `{key}` is already set by --set {first}; give each key once");
        }
        seen.push((key, raw));
    }
    Ok(())
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

/// The figure options of every command that draws: size, font size, resolution, SVG text.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FigureArgs {
    /// Figure size: `single` (a 3.4 in journal column) or `double` (7 in), at 300 dpi, the
    /// figure choosing its height for the width; or WxH in inches, cm or mm (`7x4`,
    /// `180x120mm`). Default: the figure's own size in pixels. At most 16384 pixels a side and
    /// 25 megapixels at the chosen --dpi.
    #[arg(long = "figure-size", value_name = "single|double|WxH")]
    pub figure_size: Option<String>,
    /// Size of axis labels and legends in points (default 8 pt with --figure-size).
    #[arg(long = "font-size", value_name = "PT")]
    pub font_size: Option<f64>,
    /// Resolution of PNGs in dots per inch (default 300 with --figure-size, else 96).
    #[arg(long, value_name = "N")]
    pub dpi: Option<f64>,
    /// SVG text: `font` keeps selectable text in the embedded shipped font, `paths` converts
    /// every glyph to a path.
    #[arg(long = "svg-text", value_enum, default_value_t)]
    pub svg_text: tumble_plot::options::SvgText,
}

impl FigureArgs {
    /// The options, checked.
    ///
    /// # Errors
    /// A malformed size, or a font size or resolution out of range.
    pub fn options(&self) -> Result<tumble_plot::FigureOptions> {
        let opts = tumble_plot::FigureOptions {
            size: self
                .figure_size
                .as_deref()
                .map(tumble_plot::options::Size::parse)
                .transpose()?,
            font_pt: self.font_size,
            dpi: self.dpi,
            svg_text: self.svg_text,
        };
        opts.validate()?;
        Ok(opts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

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
