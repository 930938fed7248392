//! The scalars a tape's Taylor recursion runs in ([`super::taylor`]): `f64`, and double-double
//! ([`DoubleDouble`], about 32 significant digits) for the references of `taylor-dd`.
//!
//! The recursion itself needs only sums, products and quotients; its order 0 needs each
//! function's value. For `f64` these are the standard library's, so that the series of order 0
//! is the value [`super::tape::Tape::run`] computes. For double-double they are computed here to
//! about `2⁻¹⁰⁴` relative (absolute near a zero of the function), because `twofloat`'s own
//! elementary functions are polynomials of `f64` accuracy (about `1e-17`):
//!
//! | function | double-double evaluation |
//! |---|---|
//! | `√a` | `y = √a_hi`, one Newton step `y + (a − y²)/(2y)` with `y²` exact |
//! | `eᵃ` | `a = k ln 2 + r` (`ln 2` in three parts, Cody & Waite 1980), `expm1(r/2¹⁰)` by its series, doubled ten times by `expm1(2x) = expm1(x)(expm1(x) + 2)`, times `2ᵏ` |
//! | `ln a` | `y = ln a_hi`, one Newton step `y + a e⁻ʸ − 1` |
//! | `sin a`, `cos a` | `a = k π/2 + r` (`π/2` in three parts), `|r| ≤ π/4`, the two series in `r`, the quadrant from `k mod 4` |
//! | `atan2(y, x)` | `θ = atan2(y_hi, x_hi)`, one Newton step on `x sin θ − y cos θ = 0` |
//! | `atan`, `asin`, `acos` | `atan2(a, 1)`, `atan2(a, √((1 − a)(1 + a)))`, `atan2(√((1 − a)(1 + a)), a)` |
//! | `sinh`, `cosh`, `tanh` | from `eᵃ`; `sinh` by its series where `|a| < ½` |
//! | `aᵇ`, `aⁿ` | `exp(b ln a)` (`a > 0`), binary powering |
//!
//! Each Newton step doubles the number of correct digits of the `f64` start, which is correct to
//! about `2⁻⁵³`. The quotients are [`SeriesScalar::quotient`] (Hida, Li & Bailey 2001).
//!
//! # References
//! - W. J. Cody, W. Waite, *Software Manual for the Elementary Functions*, Prentice-Hall 1980
//!   (argument reduction by a constant split into parts).
//! - Y. Hida, X. S. Li, D. H. Bailey, *Algorithms for quad-double precision floating point
//!   arithmetic*, ARITH-15 (2001) 155–162.
//! - J.-M. Muller et al., *Handbook of Floating-Point Arithmetic*, 2nd ed., Birkhäuser 2018,
//!   ch. 11 (evaluation of elementary functions) and ch. 14 (double-word arithmetic).

use tumble_integrators::taylor::{DoubleDouble, SeriesScalar};

use super::Fun;

/// A scalar a tape's Taylor recursion runs in: the arithmetic of [`SeriesScalar`], order, and
/// the functions of the expression language at a point.
pub trait TapeScalar: SeriesScalar + PartialOrd {
    /// `f(self)`.
    fn fun(self, f: Fun) -> Self;
    /// `selfⁿ`. (The names differ from `f64`'s and `twofloat`'s inherent methods, which a
    /// call on a concrete type would reach first.)
    fn int_pow(self, n: i32) -> Self;
    /// `selfᵇ`.
    fn real_pow(self, b: Self) -> Self;
    /// The angle of the point `(x, self)`, in `(−π, π]`.
    fn atan2_with(self, x: Self) -> Self;
}

impl TapeScalar for f64 {
    #[inline]
    fn fun(self, f: Fun) -> Self {
        f.apply(self)
    }
    #[inline]
    fn int_pow(self, n: i32) -> Self {
        f64::powi(self, n)
    }
    #[inline]
    fn real_pow(self, b: Self) -> Self {
        f64::powf(self, b)
    }
    #[inline]
    fn atan2_with(self, x: Self) -> Self {
        f64::atan2(self, x)
    }
}

impl TapeScalar for DoubleDouble {
    fn fun(self, f: Fun) -> Self {
        match f {
            Fun::Sqrt => sqrt(self),
            Fun::Sin => sin_cos(self).0,
            Fun::Cos => sin_cos(self).1,
            Fun::Tan => {
                let (s, c) = sin_cos(self);
                s.quotient(c)
            }
            Fun::Asin => {
                if self.hi().abs() > 1.0 {
                    return nan();
                }
                self.atan2_with(sqrt(one_minus_square(self)))
            }
            Fun::Acos => {
                if self.hi().abs() > 1.0 {
                    return nan();
                }
                sqrt(one_minus_square(self)).atan2_with(self)
            }
            Fun::Atan => self.atan2_with(DoubleDouble::of(1.0)),
            Fun::Sinh => sinh(self),
            Fun::Cosh => {
                let e = exp(abs(self));
                (e + DoubleDouble::of(1.0).quotient(e)) * 0.5
            }
            Fun::Tanh => {
                if self.hi().abs() > 40.0 {
                    // 1 − tanh|a| < 2e-35.
                    return DoubleDouble::of(self.hi().signum());
                }
                let e = exp(abs(self));
                sinh(self).quotient((e + DoubleDouble::of(1.0).quotient(e)) * 0.5)
            }
            Fun::Exp => exp(self),
            Fun::Log => ln(self),
            Fun::Abs => abs(self),
            Fun::Sign => {
                if self.hi() > 0.0 {
                    DoubleDouble::of(1.0)
                } else if self.hi() < 0.0 {
                    DoubleDouble::of(-1.0)
                } else {
                    self
                }
            }
        }
    }

    fn int_pow(self, n: i32) -> Self {
        let mut base = self;
        let mut e = n.unsigned_abs();
        let mut p = DoubleDouble::of(1.0);
        while e > 0 {
            if e & 1 == 1 {
                p *= base;
            }
            e >>= 1;
            if e > 0 {
                base *= base;
            }
        }
        if n < 0 {
            DoubleDouble::of(1.0).quotient(p)
        } else {
            p
        }
    }

    fn real_pow(self, b: Self) -> Self {
        if self.hi() > 0.0 && self.hi().is_finite() {
            return exp(b * ln(self));
        }
        // A base ≤ 0: an integer exponent is a power; otherwise the value of `f64::powf`
        // (0, ±∞ or NaN).
        if b.lo() == 0.0 && b.hi().fract() == 0.0 && b.hi().abs() <= f64::from(i32::MAX) {
            return self.int_pow(b.hi() as i32);
        }
        DoubleDouble::of(self.hi().powf(b.hi()))
    }

    fn atan2_with(self, x: Self) -> Self {
        let y = self;
        let theta = y.hi().atan2(x.hi());
        if !(y.is_finite() && x.is_finite()) || (y.hi() == 0.0 && x.hi() == 0.0) {
            return DoubleDouble::of(theta);
        }
        // One Newton step on g(θ) = x sin θ − y cos θ, g'(θ) = x cos θ + y sin θ > 0 near
        // the root.
        let t = DoubleDouble::of(theta);
        let (s, c) = sin_cos(t);
        t + (y * c - x * s).quotient(x * c + y * s)
    }
}

/// NaN as a double-double.
fn nan() -> DoubleDouble {
    DoubleDouble::of(f64::NAN)
}

/// `|a|`.
fn abs(a: DoubleDouble) -> DoubleDouble {
    if a.hi() < 0.0 { -a } else { a }
}

/// `1 − a²` as `(1 − a)(1 + a)`, exact near `|a| = 1` where `1 − a²` cancels.
fn one_minus_square(a: DoubleDouble) -> DoubleDouble {
    let one = DoubleDouble::of(1.0);
    (one - a) * (one + a)
}

/// `a · 2ᵏ`, exact where it neither overflows nor becomes subnormal.
fn ldexp(a: DoubleDouble, k: i32) -> DoubleDouble {
    let half = k / 2;
    let p = 2f64.powi(half);
    let q = 2f64.powi(k - half);
    DoubleDouble::new_add(a.hi() * p * q, a.lo() * p * q)
}

/// `ln 2` in three parts, `π/2` in three parts: the first two as a double-double, the third
/// for the reductions' last digits.
const LN2: [f64; 3] = [
    std::f64::consts::LN_2,
    2.319_046_813_846_299_6e-17,
    5.707_708_438_416_212e-34,
];
const FRAC_PI_2: [f64; 3] = [
    std::f64::consts::FRAC_PI_2,
    6.123_233_995_736_766e-17,
    -1.497_384_904_859_169_8e-33,
];

/// `a − k (c₀ + c₁ + c₂)`, the products `k c₀` and `k c₁` exact.
fn reduce(a: DoubleDouble, k: f64, c: &[f64; 3]) -> DoubleDouble {
    a - DoubleDouble::new_mul(k, c[0]) - DoubleDouble::new_mul(k, c[1]) - DoubleDouble::of(k * c[2])
}

/// Sums a series whose terms `termₙ` follow from `termₙ₋₁` by `next`, until a term no longer
/// changes the sum in double-double (at most 60 terms).
fn series(
    first: DoubleDouble,
    mut next: impl FnMut(DoubleDouble, u32) -> DoubleDouble,
) -> DoubleDouble {
    let mut term = first;
    let mut sum = first;
    for n in 1..60 {
        term = next(term, n);
        sum += term;
        if term.hi().abs() <= sum.hi().abs() * 1e-34 {
            break;
        }
    }
    sum
}

/// `√a`.
pub fn sqrt(a: DoubleDouble) -> DoubleDouble {
    if a.hi() < 0.0 {
        return nan();
    }
    if a.hi() == 0.0 || !a.hi().is_finite() {
        return DoubleDouble::of(a.hi().sqrt());
    }
    let y = a.hi().sqrt();
    DoubleDouble::of(y) + (a - DoubleDouble::new_mul(y, y)).quotient(DoubleDouble::of(2.0 * y))
}

/// `eᵃ`.
pub fn exp(a: DoubleDouble) -> DoubleDouble {
    if !a.hi().is_finite() {
        return DoubleDouble::of(a.hi().exp());
    }
    if a.hi() > 709.78 {
        return DoubleDouble::of(f64::INFINITY);
    }
    if a.hi() < -745.2 {
        return DoubleDouble::of(0.0);
    }
    let k = (a.hi() / LN2[0]).round();
    let r = ldexp(reduce(a, k, &LN2), -10);
    // expm1(r), |r| ≤ 3.4e-4: 12 terms at most.
    let mut m = series(r, |term, n| {
        (term * r).quotient(DoubleDouble::of(f64::from(n + 1)))
    });
    for _ in 0..10 {
        m = m * (m + DoubleDouble::of(2.0));
    }
    ldexp(m + DoubleDouble::of(1.0), k as i32)
}

/// `ln a`.
pub fn ln(a: DoubleDouble) -> DoubleDouble {
    if !(a.hi() > 0.0) || !a.hi().is_finite() {
        return DoubleDouble::of(a.hi().ln());
    }
    let y = DoubleDouble::of(a.hi().ln());
    y + a * exp(-y) - DoubleDouble::of(1.0)
}

/// `(sin a, cos a)`.
pub fn sin_cos(a: DoubleDouble) -> (DoubleDouble, DoubleDouble) {
    if !a.is_finite() {
        return (nan(), nan());
    }
    let k = (a.hi() / FRAC_PI_2[0]).round();
    let r = reduce(a, k, &FRAC_PI_2);
    let r2 = r * r;
    // sin r = Σ (−1)ⁿ r²ⁿ⁺¹/(2n+1)!, cos r = Σ (−1)ⁿ r²ⁿ/(2n)!: 14 terms at |r| = π/4.
    let s = series(r, |term, n| {
        -(term * r2).quotient(DoubleDouble::of(f64::from((2 * n) * (2 * n + 1))))
    });
    let c = series(DoubleDouble::of(1.0), |term, n| {
        -(term * r2).quotient(DoubleDouble::of(f64::from((2 * n - 1) * (2 * n))))
    });
    match (k.rem_euclid(4.0)) as u8 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `sinh a`.
fn sinh(a: DoubleDouble) -> DoubleDouble {
    if a.hi().abs() < 0.5 {
        let a2 = a * a;
        return series(a, |term, n| {
            (term * a2).quotient(DoubleDouble::of(f64::from((2 * n) * (2 * n + 1))))
        });
    }
    let e = exp(abs(a));
    let s = (e - DoubleDouble::of(1.0).quotient(e)) * 0.5;
    if a.hi() < 0.0 { -s } else { s }
}
