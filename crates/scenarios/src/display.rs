//! Display symbols: how a parameter or CSV column is written in figures (`ω₀` for `omega0`,
//! `φ̇` for `phi_dot`, `ω_x` for `omega_x`, `L_z` for `Lz`). CSV headers, JSON and the command
//! line keep the ASCII names; only figures use the symbols.
//!
//! Every name gets one by the same rules, so a new parameter or column needs no table entry
//! unless its symbol is not derived from its name:
//!
//! * a Greek letter's name is the letter (`theta` → θ, `Omega` → Ω);
//! * trailing digits are subscripts (`omega0` → ω₀, `m2` → m₂), after a `_dot` too
//!   (`alpha_dot0` → α̇₀);
//! * `_dot` puts a dot over the symbol (`phi_dot` → φ̇);
//! * another `_suffix` is a subscript written `_suffix` (`omega_x` → ω_x, `omega_earth` →
//!   ω_earth), as are the components of `Lx`, `qw`, … (`L_x`, `q_w`);
//! * the diagnostics have their own: `energy` → E, `energy_rel_err` → |E − E₀|/E_s (`E_s` the
//!   energy scale: the largest of |E₀| and T plus the potential's amplitude so far).

/// Greek letters by name, lower case then upper case.
const GREEK: [(&str, char, char); 24] = [
    ("alpha", 'α', 'Α'),
    ("beta", 'β', 'Β'),
    ("gamma", 'γ', 'Γ'),
    ("delta", 'δ', 'Δ'),
    ("epsilon", 'ε', 'Ε'),
    ("zeta", 'ζ', 'Ζ'),
    ("eta", 'η', 'Η'),
    ("theta", 'θ', 'Θ'),
    ("iota", 'ι', 'Ι'),
    ("kappa", 'κ', 'Κ'),
    ("lambda", 'λ', 'Λ'),
    ("mu", 'μ', 'Μ'),
    ("nu", 'ν', 'Ν'),
    ("xi", 'ξ', 'Ξ'),
    ("omicron", 'ο', 'Ο'),
    ("pi", 'π', 'Π'),
    ("rho", 'ρ', 'Ρ'),
    ("sigma", 'σ', 'Σ'),
    ("tau", 'τ', 'Τ'),
    ("upsilon", 'υ', 'Υ'),
    ("phi", 'φ', 'Φ'),
    ("chi", 'χ', 'Χ'),
    ("psi", 'ψ', 'Ψ'),
    ("omega", 'ω', 'Ω'),
];

/// Names whose symbol is not derived from the name.
const SPECIAL: [(&str, &str); 5] = [
    ("energy", "E"),
    ("energy_rel_err", "|E − E₀|/E_s"),
    ("exact_err", "max(max|ΔR|, |Δm|/|m|)"),
    ("t", "t"),
    ("colatitude", "ϑ"),
];

/// The letter a whole word stands for: a Greek name, or the word itself.
fn letter(word: &str) -> String {
    for (name, lower, upper) in GREEK {
        if word == name {
            return lower.to_string();
        }
        if word.len() == name.len()
            && word.starts_with(|c: char| c.is_ascii_uppercase())
            && word.eq_ignore_ascii_case(name)
        {
            return upper.to_string();
        }
    }
    word.to_string()
}

/// `digits` as subscript digits.
fn subscript(digits: &str) -> String {
    digits
        .chars()
        .map(|c| {
            c.to_digit(10)
                .and_then(|d| char::from_u32(0x2080 + d))
                .unwrap_or(c)
        })
        .collect()
}

/// The display symbol of a parameter or column named `name` (see the module doc).
#[must_use]
pub fn symbol(name: &str) -> String {
    if let Some((_, s)) = SPECIAL.iter().find(|(n, _)| *n == name) {
        return (*s).to_string();
    }
    let digits_at = name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    let (stem, digits) = name.split_at(digits_at);
    let (stem, dot) = match stem.strip_suffix("_dot") {
        Some(s) => (s, true),
        None => (stem, false),
    };
    let (base, index) = match stem.split_once('_') {
        Some((b, i)) if !b.is_empty() && !i.is_empty() => (b, Some(i.to_string())),
        _ => match stem.as_bytes() {
            // A component: one capital or `q` followed by one axis letter (`Lx`, `qw`).
            [b'A'..=b'Z' | b'q', b'w' | b'x' | b'y' | b'z'] => (&stem[..1], Some(stem[1..].into())),
            _ => (stem, None),
        },
    };
    let mut out = letter(base);
    if dot {
        out.push('\u{307}');
    }
    out.push_str(&subscript(digits));
    if let Some(index) = index {
        out.push('_');
        out.push_str(&index);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_the_symbols_physicists_write() {
        assert_eq!(symbol("omega0"), "ω₀");
        assert_eq!(symbol("alpha0"), "α₀");
        assert_eq!(symbol("theta0"), "θ₀");
        assert_eq!(symbol("phi_dot"), "φ\u{307}");
        assert_eq!(symbol("alpha_dot0"), "α\u{307}₀");
        assert_eq!(symbol("omega_x"), "ω_x");
        assert_eq!(symbol("omega_earth"), "ω_earth");
        assert_eq!(symbol("Lz"), "L_z");
        assert_eq!(symbol("qw"), "q_w");
        assert_eq!(symbol("Omega"), "Ω");
        assert_eq!(symbol("m12"), "m₁₂");
        assert_eq!(symbol("energy_rel_err"), "|E − E₀|/E_s");
        // Names that are no symbol stay as they are.
        for plain in ["M", "a", "g", "h", "x", "tilt", "I1x"] {
            assert!(symbol(plain).starts_with(&plain[..1]), "{plain}");
        }
        assert_eq!(symbol("x_dot"), "x\u{307}");
    }

    #[test]
    fn every_scene_parameter_and_column_has_a_symbol() {
        for scene in crate::scenes::builtin() {
            let info = scene.info();
            let names = info
                .parameters
                .iter()
                .map(|p| p.name.to_string())
                .chain(info.columns());
            for name in names {
                let s = symbol(&name);
                assert!(!s.is_empty() && !s.contains("__"), "{name} → {s}");
                // No word of a symbol is still a Greek letter's ASCII name.
                for word in s.split(|c: char| !c.is_ascii_alphabetic()) {
                    assert!(
                        !GREEK.iter().any(|(g, _, _)| word.eq_ignore_ascii_case(g)),
                        "{name} → {s}"
                    );
                }
            }
        }
    }
}
