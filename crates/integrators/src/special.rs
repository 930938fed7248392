//! Jacobi elliptic functions and the complete elliptic integral of the first kind, for
//! exact reference solutions (pendulum, free rigid body).
//!
//! With parameter `m = k²` and amplitude `φ` defined by `u = ∫₀^φ dθ / √(1 − m sin²θ)`:
//! `sn(u|m) = sin φ`, `cn(u|m) = cos φ`, `dn(u|m) = √(1 − m sin²φ)`, and
//! `K(m) = ∫₀^{π/2} dθ / √(1 − m sin²θ) = π / (2 AGM(1, √(1 − m)))`.
//!
//! `sn, cn, dn` are computed by the descending Landen (AGM) scheme of Abramowitz–Stegun
//! 16.4: `a₀ = 1, b₀ = √(1−m), c₀ = √m`, `a_{n+1} = (aₙ + bₙ)/2, b_{n+1} = √(aₙbₙ),
//! c_{n+1} = (aₙ − bₙ)/2` until `c_N` is negligible; `φ_N = 2^N a_N u`, then
//! `φ_{n−1} = (φₙ + asin(cₙ/aₙ sin φₙ))/2`. Valid for `0 ≤ m ≤ 1` (`m = 1` gives
//! `sn = tanh`, `cn = dn = sech`).
//!
//! # References
//! - M. Abramowitz, I. A. Stegun, *Handbook of Mathematical Functions*, §16.4 and §17.6.

use crate::error::Error;

/// `(sn, cn, dn)(u | m)` for `0 ≤ m ≤ 1`.
///
/// # Errors
/// [`Error::InvalidParameter`] for `m` outside `[0, 1]` or non-finite arguments.
pub fn jacobi_sn_cn_dn(u: f64, m: f64) -> Result<(f64, f64, f64), Error> {
    if !u.is_finite() {
        return Err(Error::InvalidParameter {
            name: "u",
            value: u,
            reason: "must be finite",
        });
    }
    if !(0.0..=1.0).contains(&m) {
        return Err(Error::InvalidParameter {
            name: "m",
            value: m,
            reason: "the parameter m = k² must lie in [0, 1]",
        });
    }
    if m == 0.0 {
        return Ok((u.sin(), u.cos(), 1.0));
    }
    if m == 1.0 {
        let s = 1.0 / u.cosh();
        return Ok((u.tanh(), s, s));
    }
    const LEVELS: usize = 16;
    let mut a = [0.0_f64; LEVELS + 1];
    let mut c = [0.0_f64; LEVELS + 1];
    a[0] = 1.0;
    let mut b = (1.0 - m).sqrt();
    c[0] = m.sqrt();
    let mut n = 0;
    while n < LEVELS && c[n].abs() > f64::EPSILON * a[n] {
        let an = a[n];
        a[n + 1] = 0.5 * (an + b);
        c[n + 1] = 0.5 * (an - b);
        b = (an * b).sqrt();
        n += 1;
    }
    let mut phi = (1u64 << n) as f64 * a[n] * u;
    let mut phi_prev = phi;
    for j in (1..=n).rev() {
        phi_prev = phi;
        phi = 0.5 * (phi + (c[j] / a[j] * phi.sin()).asin());
    }
    let sn = phi.sin();
    let cn = phi.cos();
    let dn = if n == 0 {
        (1.0 - m * sn * sn).sqrt()
    } else {
        cn / (phi_prev - phi).cos()
    };
    Ok((sn, cn, dn))
}

/// Complete elliptic integral of the first kind `K(m)`, `0 ≤ m < 1`, by the AGM.
///
/// # Errors
/// [`Error::InvalidParameter`] for `m` outside `[0, 1)`.
pub fn ellip_k(m: f64) -> Result<f64, Error> {
    if !(0.0..1.0).contains(&m) {
        return Err(Error::InvalidParameter {
            name: "m",
            value: m,
            reason: "K(m) needs 0 ≤ m < 1",
        });
    }
    let mut a = 1.0_f64;
    let mut b = (1.0 - m).sqrt();
    for _ in 0..64 {
        if (a - b).abs() <= f64::EPSILON * a {
            break;
        }
        let an = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = an;
    }
    Ok(std::f64::consts::PI / (a + b))
}
