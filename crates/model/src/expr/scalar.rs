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
//! | `ln a` | `a = m 2ᵏ`, `y = ln m_hi`, one Newton step `y + (m − 1 − expm1 y)/(1 + expm1 y)`, plus `k ln 2` |
//! | `sin a`, `cos a` | `a = k π/2 + r` (`π/2` in three parts), `|r| ≤ π/4`, the two series in `r`, the quadrant from `k mod 4`; NaN beyond `|a| = 10¹⁵` |
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
            Fun::Cosh => cosh(self),
            Fun::Tanh => {
                if self.hi().abs() > 40.0 {
                    // 1 − tanh|a| < 2e-35.
                    return DoubleDouble::of(self.hi().signum());
                }
                sinh(self).quotient(cosh(self))
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
        let integer = b.lo() == 0.0 && b.hi().fract() == 0.0;
        if integer && b.hi().abs() <= f64::from(i32::MAX) {
            return self.int_pow(b.hi() as i32);
        }
        if self.hi() < 0.0 && !integer {
            return nan();
        }
        DoubleDouble::of(self.hi().powf(b.hi()))
    }

    fn atan2_with(self, x: Self) -> Self {
        let y = self;
        let theta = y.hi().atan2(x.hi());
        if !(y.is_finite() && x.is_finite()) || (y.hi() == 0.0 && x.hi() == 0.0) {
            // At an infinity or at the origin the angle is a multiple of π/4 (or NaN).
            if theta.is_nan() {
                return nan();
            }
            let j = (theta / std::f64::consts::FRAC_PI_4).round();
            return ldexp(DoubleDouble::new_add(FRAC_PI_2[0], FRAC_PI_2[1]), -1) * j;
        }
        // Scaled by a power of two, so that x cos θ + y sin θ cannot overflow.
        let scale = -(x.hi().abs().max(y.hi().abs()).log2().floor() as i32);
        let (x, y) = (ldexp(x, scale), ldexp(y, scale));
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

/// `ln(f64::MAX)`: above it `eᵃ` overflows.
const EXP_MAX: f64 = 709.782_712_893_384;

/// `eᵃ`.
pub fn exp(a: DoubleDouble) -> DoubleDouble {
    if !a.hi().is_finite() {
        return DoubleDouble::of(a.hi().exp());
    }
    if a.hi() > EXP_MAX {
        return DoubleDouble::of(f64::INFINITY);
    }
    if a.hi() < -745.2 {
        return DoubleDouble::of(0.0);
    }
    let k = (a.hi() / LN2[0]).round();
    ldexp(
        expm1_reduced(reduce(a, k, &LN2)) + DoubleDouble::of(1.0),
        k as i32,
    )
}

/// `eʳ − 1` for `|r| ≤ ln 2` (relative to about `2⁻¹⁰⁴`, also near 0): the series of `r/2¹⁰`
/// (at most 12 terms), doubled ten times by `expm1(2x) = expm1(x)(expm1(x) + 2)`.
fn expm1_reduced(r: DoubleDouble) -> DoubleDouble {
    let r = ldexp(r, -10);
    let mut m = series(r, |term, n| {
        (term * r).quotient(DoubleDouble::of(f64::from(n + 1)))
    });
    for _ in 0..10 {
        m = m * (m + DoubleDouble::of(2.0));
    }
    m
}

/// `ln a`: `a = m 2ᵏ` with `m ∈ [1/√2, √2]`, `ln a = ln m + k ln 2` (`ln 2` in three parts),
/// and `ln m` by one Newton step from `y = ln m_hi` written with `expm1`:
/// `y + (m − 1 − expm1 y)/(1 + expm1 y)`, relative to about `2⁻¹⁰⁴` also near `m = 1`.
pub fn ln(a: DoubleDouble) -> DoubleDouble {
    if !(a.hi() > 0.0) || !a.hi().is_finite() {
        return DoubleDouble::of(a.hi().ln());
    }
    let k = (a.hi().log2() + 0.5).floor();
    let m = ldexp(a, -(k as i32));
    let y = m.hi().ln();
    let e = expm1_reduced(DoubleDouble::of(y));
    let one = DoubleDouble::of(1.0);
    let ln_m = DoubleDouble::of(y) + (m - one - e).quotient(one + e);
    if k == 0.0 {
        return ln_m;
    }
    DoubleDouble::new_mul(k, LN2[0])
        + DoubleDouble::new_mul(k, LN2[1])
        + DoubleDouble::of(k * LN2[2])
        + ln_m
}

/// Above this magnitude the argument reduction of [`sin_cos`] by `π/2` in three parts loses
/// double-double accuracy (its error is about `|a| · 10⁻⁴⁹`), and the angle is refused (NaN,
/// which the Taylor methods report as a non-finite coefficient).
pub const SIN_COS_MAX: f64 = 1e15;

/// `(sin a, cos a)`.
pub fn sin_cos(a: DoubleDouble) -> (DoubleDouble, DoubleDouble) {
    if !a.is_finite() || a.hi().abs() > SIN_COS_MAX {
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

/// `cosh a`, from `e^|a|`.
fn cosh(a: DoubleDouble) -> DoubleDouble {
    let e = exp(abs(a));
    (e + DoubleDouble::of(1.0).quotient(e)) * 0.5
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
