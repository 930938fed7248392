//! Jacobi elliptic functions and the Legendre elliptic integrals, for exact reference solutions
//! (the pendulum, the free rigid body).
//!
//! Parameter convention: `m = k²`, amplitude `φ = am(u | m)` with
//! `u = F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ)`; `sn u = sin φ`, `cn u = cos φ`,
//! `dn u = √(1 − m sin²φ)`. The third kind is
//! `Π(n; φ | m) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − m sin²θ))`.
//!
//! * `sn, cn, dn` by Bulirsch's descending Landen (AGM) scheme, which returns `dn` and `cn`
//!   with full relative accuracy also when `cn → 0` and `m → 1` (unlike `dn = √(1 − m sn²)`).
//!   The argument is first reduced to `|r| ≤ K(m)` by `u = 2jK + r`,
//!   `sn u = (−1)ʲ sn r`, `cn u = (−1)ʲ cn r`, `dn u = dn r`.
//! * `F` and `Π` from Carlson's symmetric integrals (the `ellip` crate):
//!   `F(φ|m) = sin φ R_F(cos²φ, 1 − m sin²φ, 1)`,
//!   `Π(n; φ|m) = F(φ|m) + (n/3) sin³φ R_J(cos²φ, 1 − m sin²φ, 1, 1 − n sin²φ)` for `|φ| ≤ π/2`,
//!   and quasi-periodicity `Π(n; φ + jπ | m) = Π(n; φ | m) + 2j Π(n | m)` beyond.
//!
//! # References
//! * R. Bulirsch, "Numerical calculation of elliptic integrals and elliptic functions",
//!   Numer. Math. 7 (1965) 78–90 (the `sncndn` scheme).
//! * B. C. Carlson, "Numerical computation of real or complex elliptic integrals",
//!   Numer. Algorithms 10 (1995) 13–26; DLMF §19.25 (Legendre integrals from R_F, R_J).
//! * DLMF §22.2, §22.4 (periods and signs of the Jacobi functions).

use crate::error::Error;

/// `(sn, cn, dn)(u | m)` by Bulirsch's scheme without argument reduction (accurate for
/// `|u| ≤ K(m)`), with `m` and `m_c = 1 − m` both given to full relative precision.
fn sncndn_core(u: f64, m: f64, mc: f64) -> (f64, f64, f64) {
    if mc == 0.0 {
        let s = 1.0 / u.cosh();
        return (u.tanh(), s, s);
    }
    if m == 0.0 {
        return (u.sin(), u.cos(), 1.0);
    }
    const LEVELS: usize = 24;
    let mut em = [0.0; LEVELS];
    let mut en = [0.0; LEVELS];
    let mut a = 1.0;
    let mut emc = mc;
    let mut c = 1.0;
    let mut last = 0;
    for i in 0..LEVELS {
        last = i;
        em[i] = a;
        emc = emc.sqrt();
        en[i] = emc;
        c = 0.5 * (a + emc);
        // Quadratic convergence: once |a − b| ≤ 1e-9 a, the next mean is exact to ~1e-18.
        if (a - emc).abs() <= 1e-9 * a {
            break;
        }
        emc *= a;
        a = c;
    }
    let v = c * u;
    let mut sn = v.sin();
    let mut cn = v.cos();
    let mut dn = 1.0;
    if sn != 0.0 {
        let mut a = cn / sn;
        let mut c = c * a;
        for i in (0..=last).rev() {
            let b = em[i];
            a *= c;
            c *= dn;
            dn = (en[i] + a) / (b + a);
            a = c / b;
        }
        let a = 1.0 / (c * c + 1.0).sqrt();
        sn = if sn >= 0.0 { a } else { -a };
        cn = c * sn;
    }
    (sn, cn, dn)
}

/// Complete elliptic integral of the first kind `K(m) = R_F(0, 1 − m, 1)`, `0 ≤ m < 1`.
///
/// # Errors
/// [`Error::InvalidParameter`] for `m` outside `[0, 1)`.
pub fn ellip_k(m: f64) -> Result<f64, Error> {
    check_parameter(m, false)?;
    Ok(complete_k_mc(1.0 - m))
}

fn check_parameter(m: f64, allow_one: bool) -> Result<(), Error> {
    let ok = if allow_one {
        (0.0..=1.0).contains(&m)
    } else {
        (0.0..1.0).contains(&m)
    };
    if ok {
        Ok(())
    } else {
        Err(Error::InvalidParameter {
            name: "m",
            value: m,
            reason: if allow_one {
                "the parameter m = k² must lie in [0, 1]"
            } else {
                "the parameter m = k² must lie in [0, 1)"
            },
        })
    }
}

/// Jacobi elliptic functions with the argument reduced by the half period `2K`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    /// `sn(u | m)`.
    pub sn: f64,
    /// `cn(u | m)`.
    pub cn: f64,
    /// `dn(u | m)`.
    pub dn: f64,
    /// `j` in `u = 2jK + r`.
    pub half_periods: f64,
    /// `(sn, cn, dn)(r)` with `|r| ≤ K`.
    pub reduced: (f64, f64, f64),
}

/// `sn, cn, dn` of `u` for `0 ≤ m ≤ 1` with `m_c = 1 − m`, given `K(m)` (pass
/// `f64::INFINITY` for `m = 1`).
#[must_use]
pub fn jacobi_reduced(u: f64, m: f64, mc: f64, k: f64) -> Jacobi {
    let (j, r) = if k.is_finite() {
        let j = (u / (2.0 * k)).round();
        (j, u - j * 2.0 * k)
    } else {
        (0.0, u)
    };
    let (s, c, d) = sncndn_core(r, m, mc);
    let sign = if (j as i64).rem_euclid(2) == 0 {
        1.0
    } else {
        -1.0
    };
    Jacobi {
        sn: sign * s,
        cn: sign * c,
        dn: d,
        half_periods: j,
        reduced: (s, c, d),
    }
}

/// `(sn, cn, dn)(u | m)` for any finite `u` and `0 ≤ m ≤ 1`: the argument is reduced to
/// `|r| ≤ K` first, so large arguments keep their accuracy (to the rounding of `u` itself).
///
/// # Errors
/// [`Error::InvalidParameter`] for `m ∉ [0, 1]` or a non-finite `u`.
pub fn jacobi_sn_cn_dn(u: f64, m: f64) -> Result<(f64, f64, f64), Error> {
    check_parameter(m, true)?;
    if !u.is_finite() {
        return Err(Error::InvalidParameter {
            name: "u",
            value: u,
            reason: "must be finite",
        });
    }
    let k = if m == 1.0 { f64::INFINITY } else { ellip_k(m)? };
    let j = jacobi_reduced(u, m, 1.0 - m, k);
    Ok((j.sn, j.cn, j.dn))
}

/// `Π(n; am r | m)` for `|r| ≤ K` given `(sn, cn, dn)(r)`: `n < 1`.
#[must_use]
pub fn incomplete_pi_scd(n: f64, s: f64, c: f64, d: f64) -> f64 {
    let x = c * c;
    let y = d * d;
    let rf = rf(x, y, 1.0);
    let rj = if n == 0.0 || s == 0.0 {
        0.0
    } else {
        rj(x, y, 1.0, 1.0 - n * s * s)
    };
    s * rf + n / 3.0 * s * s * s * rj
}

/// Complete `Π(n | m) = R_F(0, m_c, 1) + (n/3) R_J(0, m_c, 1, 1 − n)`, `n < 1`, given the
/// complementary parameter `m_c = 1 − m > 0`.
#[must_use]
pub fn complete_pi_mc(n: f64, mc: f64) -> f64 {
    let y = mc;
    let rf = rf(0.0, y, 1.0);
    if n == 0.0 {
        rf
    } else {
        rf + n / 3.0 * rj(0.0, y, 1.0, 1.0 - n)
    }
}

/// Carlson's `R_F(x, y, z)`; the arguments used here are non-negative with at most one zero.
pub(crate) fn rf(x: f64, y: f64, z: f64) -> f64 {
    ellip::elliprf(x, y, z).unwrap_or(f64::NAN)
}

/// Carlson's `R_J(x, y, z, p)`; here `p > 0`.
pub(crate) fn rj(x: f64, y: f64, z: f64, p: f64) -> f64 {
    ellip::elliprj(x, y, z, p).unwrap_or(f64::NAN)
}

/// `K` from the complementary parameter `m_c = 1 − m > 0` (accurate when `m` is close to 1 and
/// `m_c` is known to full relative precision).
#[must_use]
pub fn complete_k_mc(mc: f64) -> f64 {
    rf(0.0, mc, 1.0)
}

/// `F(φ | m)` for `|φ| ≤ π/2` from `sin φ`, `cos φ ≥ 0` and the complementary parameter
/// `m_c = 1 − m`: `sin φ R_F(cos²φ, cos²φ + m_c sin²φ, 1)` (no cancellation near `m = 1`).
#[must_use]
pub fn incomplete_f_mc(s: f64, c: f64, mc: f64) -> f64 {
    s * rf(c * c, c * c + mc * s * s, 1.0)
}
