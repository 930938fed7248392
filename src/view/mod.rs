//! `tumble view`'s pages: one self-contained HTML file (no network, opened by double-click)
//! holding three.js and its OrbitControls (vendored from npm under `assets/viewer/vendor`, their
//! licence in the page), the viewer's own script and the data of one run or one body.
//!
//! The modules are kept as inert text in the page (`<script type="text/plain">`) and loaded
//! by a short bootstrap through `blob:` URLs, with their imports rewritten to those URLs: an
//! ES module cannot otherwise import another inline module, and a `file://` page cannot fetch.

pub mod explorer;
pub mod geometry;
pub mod render;
pub mod run;

use std::fmt::Write as _;

/// The page template: `{{TITLE}}`, the three.js modules, the application module and the data.
const TEMPLATE: &str = include_str!("../../assets/viewer/page.html");
/// three.js's core and module builds (npm `three`, minified; see `assets/viewer/package.json`).
const THREE_CORE: &str = include_str!("../../assets/viewer/vendor/three.core.min.js");
const THREE_MODULE: &str = include_str!("../../assets/viewer/vendor/three.module.min.js");
/// three.js's OrbitControls addon (npm `three`, `examples/jsm/controls/OrbitControls.js`).
const ORBIT_CONTROLS: &str = include_str!("../../assets/viewer/vendor/OrbitControls.js");
/// three.js's MIT licence, shipped in every page.
const THREE_LICENSE: &str = include_str!("../../assets/viewer/vendor/three.LICENSE");
/// The shared drawing helpers and the two applications.
const COMMON: &str = include_str!("../../assets/viewer/common.js");
const RUN_APP: &str = include_str!("../../assets/viewer/run.js");
const EXPLORER_APP: &str = include_str!("../../assets/viewer/explorer.js");
/// The version of three.js embedded (from `assets/viewer/package.json`).
pub const THREE_VERSION: &str = "0.185.1";

/// Which application a page runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum App {
    /// A run played back ([`run`]).
    Run,
    /// The principal-axes explorer ([`explorer`]).
    Explorer,
}

/// HTML-escapes text for an element or an attribute.
fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// JSON for a `<script type="application/json">` element: every `<` written `\u003c` (valid
/// JSON, and no `</script>` or `<!--` can end or confuse the element).
fn script_json(value: &serde_json::Value) -> String {
    serde_json::to_string(value)
        .unwrap_or_else(|_| "null".to_string())
        .replace('<', "\\u003c")
}

/// Script text held in a `<script type="text/plain">` element: refused (by the tests of this
/// module) if it could end the element early.
fn script_text(text: &str) -> &str {
    debug_assert!(!text.to_ascii_lowercase().contains("</script"));
    text
}

/// The page of `app` with `data`, titled `title`.
#[must_use]
pub fn page(app: App, title: &str, data: &serde_json::Value) -> String {
    let app_text = match app {
        App::Run => RUN_APP,
        App::Explorer => EXPLORER_APP,
    };
    let mut out = String::with_capacity(
        TEMPLATE.len() + THREE_CORE.len() + THREE_MODULE.len() + ORBIT_CONTROLS.len() + 200_000,
    );
    // The template's placeholders, in order; each appears once.
    let mut rest = TEMPLATE;
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let Some(len) = rest[start..].find("}}") else {
            break;
        };
        let key = &rest[start + 2..start + len];
        match key {
            "TITLE" => out.push_str(&escape_html(title)),
            "THREE_VERSION" => out.push_str(THREE_VERSION),
            "THREE_LICENSE" => out.push_str(&escape_html(THREE_LICENSE)),
            "THREE_CORE" => out.push_str(script_text(THREE_CORE)),
            "THREE_MODULE" => out.push_str(script_text(THREE_MODULE)),
            "ORBIT_CONTROLS" => out.push_str(script_text(ORBIT_CONTROLS)),
            "COMMON" => out.push_str(script_text(COMMON)),
            "APP" => out.push_str(script_text(app_text)),
            "DATA" => out.push_str(&script_json(data)),
            other => {
                let _ = write!(out, "{{{{{other}}}}}");
            }
        }
        rest = &rest[start + len + 2..];
    }
    out.push_str(rest);
    out
}

/// Rounds to `digits` significant digits (for the geometry and the vectors' scale: what a
/// screen can show), keeping the JSON short.
#[must_use]
pub fn round_sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return 0.0;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// Little-endian `f32`s, base64: the compact form of a page's numeric arrays.
#[must_use]
pub fn f32_base64(values: &[f32]) -> String {
    use base64::Engine as _;
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_scripts_cannot_end_their_element() {
        for (name, text) in [
            ("three.core", THREE_CORE),
            ("three.module", THREE_MODULE),
            ("OrbitControls", ORBIT_CONTROLS),
            ("common", COMMON),
            ("run", RUN_APP),
            ("explorer", EXPLORER_APP),
        ] {
            let lower = text.to_ascii_lowercase();
            assert!(!lower.contains("</script"), "{name} contains </script");
            assert!(!lower.contains("<!--"), "{name} contains <!--");
        }
    }

    #[test]
    fn data_json_hides_markup() {
        let value = serde_json::json!({"title": "</script><!-- x"});
        let text = script_json(&value);
        assert!(!text.contains('<'));
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, value);
    }

    #[test]
    fn every_placeholder_is_filled() {
        let html = page(App::Run, "a <b>", &serde_json::json!({"x": 1}));
        assert!(!html.contains("{{"), "an unknown placeholder is left");
        assert!(html.contains("a &lt;b&gt;"));
        assert!(html.contains("Copyright © 2010-2026 three.js authors"));
    }

    #[test]
    fn the_vendored_version_is_the_locked_one() {
        let lock: serde_json::Value =
            serde_json::from_str(include_str!("../../assets/viewer/package-lock.json")).unwrap();
        assert_eq!(
            lock["packages"]["node_modules/three"]["version"],
            THREE_VERSION
        );
    }

    #[test]
    fn f32_base64_round_trips() {
        use base64::Engine as _;
        let values = [0.0f32, -1.5, 3.25e-7, f32::MAX];
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(f32_base64(&values))
            .unwrap();
        let back: Vec<f32> = bytes
            .chunks(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        assert_eq!(back, values);
    }

    #[test]
    fn rounding_keeps_significant_digits() {
        assert_eq!(round_sig(0.123456789, 4), 0.1235);
        assert_eq!(round_sig(-98765.4, 3), -98800.0);
        assert_eq!(round_sig(0.0, 3), 0.0);
    }
}
