//! The rotation group SO(3) and its Lie algebra so(3).
//!
//! # Definitions and conventions
//!
//! * `hat: ℝ³ → so(3)`, `hat(ω) v = ω × v`, i.e.
//!   `hat(ω) = [[0, −ω₃, ω₂], [ω₃, 0, −ω₁], [−ω₂, ω₁, 0]]`; `vee` is its inverse, applied to the
//!   skew-symmetric part of its argument (so `vee(Ṙ Rᵀ)` is meaningful even when `Ṙ Rᵀ` is skew
//!   only to round-off).
//! * Rotations are **active**: `R` maps a vector's body-frame components to its space-frame
//!   components, `v_space = R v_body`.
//! * `exp: so(3) → SO(3)`, `exp(hat ω) = 𝟙 + (sin θ/θ) hat ω + ((1 − cos θ)/θ²) (hat ω)²`,
//!   `θ = |ω|` (Rodrigues). It is evaluated through the unit quaternion
//!   `q = (cos(θ/2), sin(θ/2) ω/θ)` with `(1 − cos θ)/θ² = ½ (sin(θ/2)/(θ/2))²`, so no
//!   cancellation occurs at any angle; for `θ < 0.1` the sinc and cosine are Taylor series in `θ²`
//!   (truncation below 1e-17), which also keeps derivatives finite at `ω = 0` for dual numbers.
//! * `log: SO(3) → so(3)` returns the rotation vector with `|ω| ≤ π`. It converts to a unit
//!   quaternion (Shepperd's branch on the largest of trace and diagonal), chooses `w ≥ 0`, and
//!   takes `θ = 2 atan2(|v|, w)`: well conditioned near `θ = 0` (series of `atan(x)/x`) and near
//!   `θ = π`, where the common `acos((tr R − 1)/2)` form loses half of the digits and the
//!   `vee(R − Rᵀ)/(2 sin θ)` form divides by zero. (nalgebra's `scaled_axis` is not used: it loses
//!   tiny angles and is unstable near π.)
//! * The Cayley map `cay(ω) = (𝟙 − ½ hat ω)⁻¹ (𝟙 + ½ hat ω) = 𝟙 + 4/(4 + |ω|²) (hat ω + ½ (hat ω)²)`,
//!   a rotation by `2 atan(|ω|/2)` about `ω`; its inverse `cay⁻¹(R) = 2 vee(R − Rᵀ)/(1 + tr R)`
//!   does not exist for rotations by π (an error).
//! * The **right Jacobian** `dexp(ω) = J_r(ω) = 𝟙 − ((1 − cos θ)/θ²) hat ω + ((θ − sin θ)/θ³) (hat ω)²`
//!   is the right-trivialized derivative of `exp`: `d/dt exp(ω(t)) = exp(ω) hat(J_r(ω) ω̇)`.
//!   Its inverse is `dexpinv(ω) = J_r⁻¹(ω) = 𝟙 + ½ hat ω + (1/θ² − cot(θ/2)/(2θ)) (hat ω)²`
//!   (singular only at `θ = 2π`). The left Jacobian `J_l(ω) = J_r(−ω)` gives
//!   `d/dt exp(ω) = hat(J_l(ω) ω̇) exp(ω)`; it is the `dexp` of Runge–Kutta–Munthe-Kaas methods.
//!
//! All functions are generic over `T: RealField + Copy` so that dual numbers (`num-dual`) flow
//! through them.
//!
//! # References
//! * J. Solà, J. Deray, D. Atchuthan, "A micro Lie theory for state estimation in robotics",
//!   arXiv:1812.01537 (2018) — right/left Jacobians of SO(3) and their inverses.
//! * S. W. Shepperd, "Quaternion from rotation matrix", J. Guidance and Control 1(3), 1978.
//! * E. Celledoni, H. Marthinsen, B. Owren, "An introduction to Lie group integrators — basics,
//!   new developments and applications", J. Comput. Phys. 257 (2014) — dexp, dexpinv, Cayley map.

mod jacobian;

pub use jacobian::{
    ExpCoefficients, right_jacobian_derivative, right_jacobian_derivative_transpose,
};

use nalgebra::{Matrix3, Quaternion, RealField, Rotation3, UnitQuaternion, Vector3};

use crate::{KinematicsError, real, to_f64};

/// Below this angle (radians) the closed forms are replaced by Taylor series in `θ²`.
pub const SMALL_ANGLE: f64 = 0.1;

/// `hat(ω)`: the skew-symmetric matrix with `hat(ω) v = ω × v`.
#[must_use]
#[inline]
pub fn hat<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    let z = T::zero();
    Matrix3::new(z, -w.z, w.y, w.z, z, -w.x, -w.y, w.x, z)
}

/// `vee(M)`: the axial vector of the skew-symmetric part `½ (M − Mᵀ)`; inverse of [`hat`].
#[must_use]
#[inline]
pub fn vee<T: RealField + Copy>(m: &Matrix3<T>) -> Vector3<T> {
    let half: T = real(0.5);
    Vector3::new(
        (m[(2, 1)] - m[(1, 2)]) * half,
        (m[(0, 2)] - m[(2, 0)]) * half,
        (m[(1, 0)] - m[(0, 1)]) * half,
    )
}

/// `sin(x)/x` as a function of `x²`, exact to round-off for every `x`, smooth at 0.
#[inline]
fn sinc_from_sq<T: RealField + Copy>(x2: T) -> T {
    if x2 < real(SMALL_ANGLE * SMALL_ANGLE) {
        // 1 − x²/6 + x⁴/120 − x⁶/5040 + x⁸/362880; next term x¹⁰/39916800 < 3e-19 for x < 0.1.
        let c: [T; 5] = [
            T::one(),
            real(-1.0 / 6.0),
            real(1.0 / 120.0),
            real(-1.0 / 5040.0),
            real(1.0 / 362_880.0),
        ];
        horner(&c, x2)
    } else {
        let x = x2.sqrt();
        x.sin() / x
    }
}

/// `cos(x)` as a function of `x²` (series below the small-angle threshold so that derivatives with
/// respect to `x²` stay finite at 0).
#[inline]
fn cos_from_sq<T: RealField + Copy>(x2: T) -> T {
    if x2 < real(SMALL_ANGLE * SMALL_ANGLE) {
        let c: [T; 6] = [
            T::one(),
            real(-0.5),
            real(1.0 / 24.0),
            real(-1.0 / 720.0),
            real(1.0 / 40_320.0),
            real(-1.0 / 3_628_800.0),
        ];
        horner(&c, x2)
    } else {
        x2.sqrt().cos()
    }
}

/// Evaluates `c₀ + c₁ x + c₂ x² + …` by Horner's rule.
#[inline]
fn horner<T: RealField + Copy>(c: &[T], x: T) -> T {
    c.iter().rev().fold(T::zero(), |acc, &ci| acc * x + ci)
}

/// `exp(ω)` as a unit quaternion `(cos(θ/2), sin(θ/2) ω/θ)`.
#[must_use]
pub fn exp_quat<T: RealField + Copy>(w: &Vector3<T>) -> UnitQuaternion<T> {
    let quarter: T = real(0.25);
    let half: T = real(0.5);
    let half_theta_sq = w.norm_squared() * quarter;
    let s = sinc_from_sq(half_theta_sq) * half; // sin(θ/2)/θ
    let c = cos_from_sq(half_theta_sq);
    // cos² + sin² = 1 holds only to a few ulps in floating point; renormalizing keeps the
    // rotation matrices built from this quaternion orthogonal to about one ulp.
    UnitQuaternion::new_normalize(Quaternion::new(c, w.x * s, w.y * s, w.z * s))
}

/// `exp(ω)`: the rotation by angle `|ω|` about the axis `ω/|ω|` (right-hand rule).
///
/// ```
/// use nalgebra::Vector3;
/// use tumble_kinematics::so3::{exp, log};
/// let w = Vector3::new(0.3, -1.2, 2.0);
/// assert!((log(&exp(&w)) - w).norm() < 1e-14);
/// ```
#[must_use]
pub fn exp<T: RealField + Copy>(w: &Vector3<T>) -> Rotation3<T> {
    quat_to_rotation(&exp_quat(w))
}

/// The rotation matrix of a unit quaternion, `R = 𝟙 + 2w hat(v) + 2 hat(v)²`.
///
/// Unlike `UnitQuaternion::to_rotation_matrix` this is generic over `RealField + Copy` without SIMD
/// bounds and uses the form that is exact for the quaternions [`exp_quat`] returns.
#[must_use]
pub fn quat_to_rotation<T: RealField + Copy>(q: &UnitQuaternion<T>) -> Rotation3<T> {
    let two: T = real(2.0);
    let v = q.vector().into_owned();
    let vh = hat(&v);
    Rotation3::from_matrix_unchecked(Matrix3::identity() + vh * (q.w * two) + vh * vh * two)
}

/// The unit quaternion of a rotation matrix by Shepperd's method: the largest of
/// `1 + tr R`, `1 + 2R₁₁ − tr R`, … is taken under the square root, so no component is obtained by
/// dividing by a small number. The result has `w ≥ 0`.
#[must_use]
pub fn rotation_to_quat<T: RealField + Copy>(r: &Rotation3<T>) -> UnitQuaternion<T> {
    let m = r.matrix();
    let one = T::one();
    let quarter: T = real(0.25);
    let tr = m[(0, 0)] + m[(1, 1)] + m[(2, 2)];
    let cands = [
        tr,
        m[(0, 0)] + m[(0, 0)] - tr,
        m[(1, 1)] + m[(1, 1)] - tr,
        m[(2, 2)] + m[(2, 2)] - tr,
    ];
    let mut best = 0;
    for i in 1..4 {
        if cands[i] > cands[best] {
            best = i;
        }
    }
    // 4 qᵦ² = 1 + cands[best]; the other components come from sums/differences of off-diagonals.
    let d = (one + cands[best]).sqrt(); // = 2 |qᵦ|
    let f = quarter / (d * real(0.5)); // = 1 / (4 |qᵦ|)
    let h = d * real(0.5);
    let (w, x, y, z) = match best {
        0 => (
            h,
            (m[(2, 1)] - m[(1, 2)]) * f,
            (m[(0, 2)] - m[(2, 0)]) * f,
            (m[(1, 0)] - m[(0, 1)]) * f,
        ),
        1 => (
            (m[(2, 1)] - m[(1, 2)]) * f,
            h,
            (m[(0, 1)] + m[(1, 0)]) * f,
            (m[(0, 2)] + m[(2, 0)]) * f,
        ),
        2 => (
            (m[(0, 2)] - m[(2, 0)]) * f,
            (m[(0, 1)] + m[(1, 0)]) * f,
            h,
            (m[(1, 2)] + m[(2, 1)]) * f,
        ),
        _ => (
            (m[(1, 0)] - m[(0, 1)]) * f,
            (m[(0, 2)] + m[(2, 0)]) * f,
            (m[(1, 2)] + m[(2, 1)]) * f,
            h,
        ),
    };
    let q = Quaternion::new(w, x, y, z);
    let q = if w < T::zero() { -q } else { q };
    // Renormalize: for an orthogonal input this changes the quaternion by round-off only.
    UnitQuaternion::new_normalize(q)
}

/// `log(q)`: the rotation vector `ω` with `|ω| ≤ π` and `exp_quat(ω) = ±q`.
#[must_use]
pub fn log_quat<T: RealField + Copy>(q: &UnitQuaternion<T>) -> Vector3<T> {
    let (w, v) = if q.w < T::zero() {
        (-q.w, -q.vector().into_owned())
    } else {
        (q.w, q.vector().into_owned())
    };
    let n2 = v.norm_squared();
    // Small |v| relative to w: θ/|v| = (2/w) atan(x)/x with x = |v|/w; series in x².
    // |v| < sin(0.05) and w > cos(0.05) imply x² < 0.0026: truncation after x⁸ is below 1e-22.
    let small: T = real(0.05f64.sin().powi(2));
    let factor = if n2 < small {
        let x2 = n2 / (w * w);
        let c: [T; 6] = [
            T::one(),
            real(-1.0 / 3.0),
            real(1.0 / 5.0),
            real(-1.0 / 7.0),
            real(1.0 / 9.0),
            real(-1.0 / 11.0),
        ];
        horner(&c, x2) * real::<T>(2.0) / w
    } else {
        let n = n2.sqrt();
        T::atan2(n, w) * real::<T>(2.0) / n
    };
    v * factor
}

/// `log(R)`: the rotation vector `ω`, `|ω| ≤ π`, with `exp(ω) = R` (see the module doc for the
/// method). At exactly `θ = π` both `±ω` are valid; one of them is returned.
#[must_use]
pub fn log<T: RealField + Copy>(r: &Rotation3<T>) -> Vector3<T> {
    log_quat(&rotation_to_quat(r))
}

/// The Cayley map `cay(ω) = 𝟙 + 4/(4 + |ω|²) (hat ω + ½ (hat ω)²)`, a rotation by `2 atan(|ω|/2)`.
#[must_use]
pub fn cayley<T: RealField + Copy>(w: &Vector3<T>) -> Rotation3<T> {
    let four: T = real(4.0);
    let k = four / (four + w.norm_squared());
    let wh = hat(w);
    Rotation3::from_matrix_unchecked(Matrix3::identity() + (wh + wh * wh * real::<T>(0.5)) * k)
}

/// The inverse Cayley map `cay⁻¹(R) = 2 vee(R − Rᵀ)/(1 + tr R)`.
///
/// # Errors
/// [`KinematicsError::CayleySingular`] when `1 + tr R ≤ 1e-12` (a rotation by π, or within about
/// 1e-6 rad of one): no finite Cayley vector exists there.
pub fn try_cayley_inv<T: RealField + Copy>(
    r: &Rotation3<T>,
) -> Result<Vector3<T>, KinematicsError> {
    let m = r.matrix();
    let denom = T::one() + m[(0, 0)] + m[(1, 1)] + m[(2, 2)];
    // Written so that a NaN trace is rejected too.
    let regular = denom > real(1e-12);
    if !regular {
        return Err(KinematicsError::CayleySingular {
            one_plus_trace: to_f64(denom),
        });
    }
    let two: T = real(2.0);
    // vee(R − Rᵀ) = 2 vee(R) since vee takes the skew part.
    Ok(vee(m) * (two * two / denom))
}

/// Coefficients `(a, b)` of `𝟙 + a hat ω + b (hat ω)²` for the right Jacobian:
/// `a = −(1 − cos θ)/θ²`, `b = (θ − sin θ)/θ³`.
fn right_jacobian_coefficients<T: RealField + Copy>(theta2: T) -> (T, T) {
    // (1 − cos θ)/θ² = ½ sinc²(θ/2): no cancellation.
    let s = sinc_from_sq(theta2 * real(0.25));
    let a = -(s * s * real(0.5));
    let b = if theta2 < real(SMALL_ANGLE * SMALL_ANGLE) {
        // (θ − sin θ)/θ³ = 1/6 − θ²/120 + θ⁴/5040 − θ⁶/362880 + θ⁸/39916800
        let c: [T; 5] = [
            real(1.0 / 6.0),
            real(-1.0 / 120.0),
            real(1.0 / 5040.0),
            real(-1.0 / 362_880.0),
            real(1.0 / 39_916_800.0),
        ];
        horner(&c, theta2)
    } else {
        let t = theta2.sqrt();
        (t - t.sin()) / (theta2 * t)
    };
    (a, b)
}

/// The coefficient `1/θ² − cot(θ/2)/(2θ)` of `(hat ω)²` in the inverse right Jacobian.
fn inverse_jacobian_coefficient<T: RealField + Copy>(theta2: T) -> T {
    if theta2 < real(SMALL_ANGLE * SMALL_ANGLE) {
        // 1/12 + θ²/720 + θ⁴/30240 + θ⁶/1209600 + θ⁸/47900160
        let c: [T; 5] = [
            real(1.0 / 12.0),
            real(1.0 / 720.0),
            real(1.0 / 30_240.0),
            real(1.0 / 1_209_600.0),
            real(1.0 / 47_900_160.0),
        ];
        horner(&c, theta2)
    } else {
        let t = theta2.sqrt();
        let half: T = real(0.5);
        let cot_half = (t * half).cos() / (t * half).sin();
        T::one() / theta2 - cot_half / (t + t)
    }
}

/// The right Jacobian `dexp(ω) = J_r(ω)`: `d/dt exp(ω) = exp(ω) hat(J_r(ω) ω̇)`.
#[must_use]
pub fn dexp<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    let (a, b) = right_jacobian_coefficients(w.norm_squared());
    let wh = hat(w);
    Matrix3::identity() + wh * a + wh * wh * b
}

/// The inverse right Jacobian `dexpinv(ω) = J_r(ω)⁻¹` (exists for `|ω| < 2π`).
#[must_use]
pub fn dexpinv<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    let c = inverse_jacobian_coefficient(w.norm_squared());
    let wh = hat(w);
    Matrix3::identity() + wh * real::<T>(0.5) + wh * wh * c
}

/// The left Jacobian `J_l(ω) = J_r(−ω)`: `d/dt exp(ω) = hat(J_l(ω) ω̇) exp(ω)`.
#[must_use]
pub fn left_jacobian<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    dexp(&(-w))
}

/// The inverse left Jacobian `J_l(ω)⁻¹ = J_r(−ω)⁻¹`.
#[must_use]
pub fn left_jacobian_inv<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    dexpinv(&(-w))
}

/// The rotation angle of `R` in `[0, π]`, computed as `2 atan2(|v|, |w|)` of its quaternion.
#[must_use]
pub fn angle<T: RealField + Copy>(r: &Rotation3<T>) -> T {
    let q = rotation_to_quat(r);
    T::atan2(q.vector().norm(), q.w.abs()) * real::<T>(2.0)
}

/// The orthogonality defect `‖RᵀR − 𝟙‖_F` of a matrix meant to be a rotation.
#[must_use]
pub fn orthogonality_defect(m: &Matrix3<f64>) -> f64 {
    (m.transpose() * m - Matrix3::identity()).norm()
}
