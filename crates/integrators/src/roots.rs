//! Scalar root finding and maximisation on a bracket, for events and for metrics located on
//! dense output.
//!
//! - [`illinois`]: a root of `g` on `[a, b]` given a sign change, by the Illinois variant of
//!   regula falsi (Dowell & Jarratt 1971): superlinear (order ≈ 1.44), never leaves the
//!   bracket, and ends at the first representable time past the crossing.
//! - [`maximize`]: a local maximum of `f` on `[a, b]` by Brent's method — golden-section
//!   search safeguarding successive parabolic interpolation (R. P. Brent, *Algorithms for
//!   Minimization without Derivatives*, Prentice-Hall 1973, ch. 5). Near a maximum
//!   `f(t*) − f(t) ≈ ½|f''| (t − t*)²`, so locating `t*` to `√ε` gives the maximum *value* to
//!   round-off, which is what a metric needs.

/// A root of `g` on `[t0, t1]` where `g0 = g(t0)` and `g1 = g(t1)` have opposite signs (or
/// `g1 = 0`): the first time past the crossing, to a few ulps of `t`.
pub fn illinois(mut g: impl FnMut(f64) -> f64, t0: f64, g0: f64, t1: f64, g1: f64) -> f64 {
    if g1 == 0.0 {
        return t1;
    }
    let (mut a, mut ga, mut b, mut gb) = (t0, g0, t1, g1);
    let mut side = 0i8;
    for _ in 0..200 {
        if (b - a).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs()).max(1e-300) {
            break;
        }
        let mut c = (a * gb - b * ga) / (gb - ga);
        if !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        if gc == 0.0 {
            return c;
        }
        if (gc < 0.0) == (gb < 0.0) {
            // c replaces b; a is retained
            b = c;
            gb = gc;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            ga = gc;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
    }
    // `a` keeps the sign of g0 and `b` that of g1: `b` is the first time past the crossing.
    b
}

/// The largest value of `f` found on `[a, b]` by Brent's method, and where: a local maximum
/// of `f` in the interior, or an end of the interval when `f` is monotone there (both ends
/// are evaluated).
pub fn maximize(mut f: impl FnMut(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    // Brent's `localmin` on −f.
    const GOLDEN: f64 = 0.381_966_011_250_105_1; // (3 − √5)/2
    let eps = f64::EPSILON.sqrt();
    let (mut lo, mut hi) = (a.min(b), a.max(b));
    let fa = f(lo);
    let fb = f(hi);
    let mut x = lo + GOLDEN * (hi - lo);
    let (mut w, mut v) = (x, x);
    let mut fx = -f(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        let tol = eps * x.abs() + 1e-300;
        let t2 = 2.0 * tol;
        if (x - m).abs() <= t2 - 0.5 * (hi - lo) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let r = e;
            e = d;
            if p.abs() < (0.5 * q * r).abs() && p > q * (lo - x) && p < q * (hi - x) {
                d = p / q;
                let u = x + d;
                if u - lo < t2 || hi - u < t2 {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x < m { hi - x } else { lo - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else if d > 0.0 {
            x + tol
        } else {
            x - tol
        };
        let fu = -f(u);
        if fu <= fx {
            if u < x {
                hi = x;
            } else {
                lo = x;
            }
            (v, fv) = (w, fw);
            (w, fw) = (x, fx);
            (x, fx) = (u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv) = (w, fw);
                (w, fw) = (u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    let mut best = (x, -fx);
    for (t, value) in [(a.min(b), fa), (a.max(b), fb)] {
        if value > best.1 {
            best = (t, value);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn illinois_finds_the_root_of_cosine_to_the_last_bits() {
        let mut calls = 0;
        let t = illinois(
            |t| {
                calls += 1;
                t.cos()
            },
            1.0,
            1.0_f64.cos(),
            2.0,
            2.0_f64.cos(),
        );
        assert!((t - std::f64::consts::FRAC_PI_2).abs() <= 4e-16, "{t}");
        assert!(calls <= 12, "{calls} evaluations");
    }

    #[test]
    fn brent_finds_interior_maxima_to_round_off_in_value() {
        // sin has its maximum 1 at π/2; a shifted quartic bump has it at 0.3.
        let (t, v) = maximize(f64::sin, 0.5, 2.9);
        assert!((v - 1.0).abs() <= 2e-16, "{v}");
        assert!((t - std::f64::consts::FRAC_PI_2).abs() <= 1e-7, "{t}");
        let bump = |t: f64| 2.0 - (t - 0.3).powi(2) - 3.0 * (t - 0.3).powi(4);
        let (t, v) = maximize(bump, -1.0, 1.0);
        assert!(
            (v - 2.0).abs() <= 4e-16 && (t - 0.3).abs() <= 1e-7,
            "{t} {v}"
        );
    }

    #[test]
    fn brent_returns_the_larger_end_of_a_monotone_function() {
        assert_eq!(maximize(f64::exp, 0.0, 1.0), (1.0, 1.0_f64.exp()));
        assert_eq!(maximize(|t| -t, 0.0, 1.0), (0.0, 0.0));
    }
}
