//! Euler angles: the twelve axis sequences, intrinsic and extrinsic.
//!
//! # Conventions
//!
//! * Rotations are **active** and map body-frame components to space-frame components
//!   (`v_space = R v_body`). `R_x(a)`, `R_y(a)`, `R_z(a)` are right-handed rotations by `a` about
//!   the coordinate axes, e.g. `R_z(a) = [[cos a, −sin a, 0], [sin a, cos a, 0], [0, 0, 1]]`.
//! * An **intrinsic** sequence `(e₁, e₂, e₃)` with angles `(a₁, a₂, a₃)` rotates about `e₁`, then
//!   about the *rotated* `e₂`, then about the twice-rotated `e₃`:
//!   `R = R_{e₁}(a₁) R_{e₂}(a₂) R_{e₃}(a₃)`.
//! * An **extrinsic** sequence `(e₁, e₂, e₃)` with angles `(a₁, a₂, a₃)` rotates about the
//!   *fixed* axes `e₁`, then `e₂`, then `e₃`: `R = R_{e₃}(a₃) R_{e₂}(a₂) R_{e₁}(a₁)`. It equals the
//!   intrinsic sequence `(e₃, e₂, e₁)` with angles `(a₃, a₂, a₁)`.
//! * **Proper** Euler sequences repeat the first axis (ZYZ, ZXZ, XYX, XZX, YXY, YZY); their middle
//!   angle lies in `[0, π]` and gimbal lock is at 0 and π. **Tait–Bryan** sequences use three
//!   distinct axes (XYZ, XZY, YXZ, YZX, ZXY, ZYX); their middle angle lies in `[−π/2, π/2]` and
//!   gimbal lock is at `±π/2`. First and third angles are returned in `(−π, π]`.
//! * The article's convention ([`EulerConvention::ARTICLE`]) is intrinsic ZYZ,
//!   `R = R_z(φ) R_y(θ) R_z(ψ)`, whose space-frame angular velocity is
//!   `ω = φ̇ ẑ + θ̇ (−sin φ, cos φ, 0) + ψ̇ (sin θ cos φ, sin θ sin φ, cos θ)`.
//!   Goldstein's convention (Physics 151, lecture 9: the passive matrix `A = B C D`) is intrinsic
//!   ZXZ ([`EulerConvention::GOLDSTEIN`]): the active rotation is `Aᵀ = R_z(φ) R_x(θ) R_z(ψ)`, and the
//!   body-frame angular velocity is
//!   `ω' = (φ̇ sin θ sin ψ + θ̇ cos ψ, φ̇ sin θ cos ψ − θ̇ sin ψ, φ̇ cos θ + ψ̇)`.
//!
//! # Angular velocity
//!
//! For the intrinsic form `R = R₁(a₁) R₂(a₂) R₃(a₃)` the space-frame angular velocity
//! `ω = vee(Ṙ Rᵀ)` and the body-frame one `ω' = vee(Rᵀ Ṙ) = Rᵀ ω` are linear in the rates:
//! `ω = E(a) ȧ` with columns `e₁, R₁ e₂, R₁ R₂ e₃`, and `ω' = E'(a) ȧ` with columns
//! `(R₂ R₃)ᵀ e₁, R₃ᵀ e₂, e₃`. `det E = det E' = −sin a₂` for proper and `ε cos a₂` for Tait–Bryan
//! sequences (`ε = ±1` the parity of the axis permutation); the inverse map from `ω` to rates is
//! therefore singular exactly at gimbal lock and is reported as an error there.
//!
//! # Extraction
//!
//! Angles are extracted from the unit quaternion with `atan2` and `hypot` only, following the
//! direct method of Bernardes & Viollet: for a proper intrinsic sequence `(i, j, i)` with `k` the
//! remaining axis, `a = w, b = q_i, c = q_j, d = ε q_k` give
//! `a₂ = 2 atan2(hypot(c, d), hypot(a, b))`, `θ₊ = atan2(b, a)`, `θ₋ = atan2(d, c)`,
//! `a₁ = θ₊ + θ₋`, `a₃ = θ₊ − θ₋`. A Tait–Bryan sequence `(i, j, k)` is reduced to the proper
//! sequence `(i, j, i)` by `R_k(γ) = P R_i(−εγ) Pᵀ` with `P = R_j(π/2)`. No step divides, so no
//! NaN can arise; at exact gimbal lock (`hypot(c, d)` or `hypot(a, b)` exactly zero) the third
//! intrinsic angle is set to 0 and the first carries the whole rotation about the locked axis.
//!
//! # References
//! * E. Bernardes, S. Viollet, "Quaternion to Euler angles conversion: A direct, general and
//!   computationally efficient method", PLOS ONE 17(11): e0276302 (2022).
//! * H. Goldstein, C. Poole, J. Safko, *Classical Mechanics*, 3rd ed., §4.4 and §4.9.
//! * M. D. Shuster, F. L. Markley, "General formula for extracting the Euler angles", J. Guidance,
//!   Control, and Dynamics 29(1), 2006.

use std::fmt;
use std::str::FromStr;

use nalgebra::{Matrix3, Quaternion, RealField, Rotation3, UnitQuaternion, Vector3};

use crate::so3::quat_to_rotation;
use crate::so3::rotation_to_quat;
use crate::{KinematicsError, real, to_f64};

/// Default angular distance (rad) from gimbal lock below which [`EulerDecomposition::gimbal_lock`]
/// is set: there the first and third angles lose more than half of their digits individually
/// (their error grows like `ε / sin(distance)`), although together they still reproduce the
/// rotation to round-off.
pub const GIMBAL_LOCK_TOLERANCE: f64 = 1e-8;

/// Default lower bound on `|det E|` (`|sin θ|` or `|cos θ|`) for [`EulerConvention::try_rates_from_omega_space`]
/// and its body-frame twin: rates are never amplified by more than `1/tolerance = 10⁶`.
pub const RATE_SINGULARITY_TOLERANCE: f64 = 1e-6;

/// A coordinate axis of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

impl Axis {
    /// 0, 1, 2 for x, y, z.
    #[must_use]
    pub const fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// The unit vector along the axis.
    #[must_use]
    pub fn unit<T: RealField + Copy>(self) -> Vector3<T> {
        let mut v = Vector3::zeros();
        v[self.index()] = T::one();
        v
    }

    /// The active right-handed rotation by `angle` about this axis.
    #[must_use]
    pub fn rotation<T: RealField + Copy>(self, angle: T) -> Rotation3<T> {
        let (s, c) = angle.sin_cos();
        let (o, z) = (T::one(), T::zero());
        let m = match self {
            Axis::X => Matrix3::new(o, z, z, z, c, -s, z, s, c),
            Axis::Y => Matrix3::new(c, z, s, z, o, z, -s, z, c),
            Axis::Z => Matrix3::new(c, -s, z, s, c, z, z, z, o),
        };
        Rotation3::from_matrix_unchecked(m)
    }

    /// The unit quaternion `(cos(a/2), sin(a/2) e)` of the rotation by `angle` about this axis.
    #[must_use]
    pub fn quaternion<T: RealField + Copy>(self, angle: T) -> UnitQuaternion<T> {
        let (s, c) = (angle * real::<T>(0.5)).sin_cos();
        let mut v = Vector3::zeros();
        v[self.index()] = s;
        UnitQuaternion::new_unchecked(Quaternion::from_parts(c, v))
    }

    const fn from_index(i: usize) -> Axis {
        match i {
            0 => Axis::X,
            1 => Axis::Y,
            _ => Axis::Z,
        }
    }

    fn letter(self) -> char {
        match self {
            Axis::X => 'X',
            Axis::Y => 'Y',
            Axis::Z => 'Z',
        }
    }
}

/// The twelve axis sequences: six Tait–Bryan (three distinct axes) and six proper Euler (first
/// and third axes equal). Whether the axes are fixed or moving is given separately by
/// [`RotationKind`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(clippy::upper_case_acronyms)]
pub enum EulerSequence {
    /// Tait–Bryan x-y-z.
    XYZ,
    /// Tait–Bryan x-z-y.
    XZY,
    /// Tait–Bryan y-x-z.
    YXZ,
    /// Tait–Bryan y-z-x.
    YZX,
    /// Tait–Bryan z-x-y.
    ZXY,
    /// Tait–Bryan z-y-x (yaw, pitch, roll when intrinsic).
    ZYX,
    /// Proper x-y-x.
    XYX,
    /// Proper x-z-x.
    XZX,
    /// Proper y-x-y.
    YXY,
    /// Proper y-z-y.
    YZY,
    /// Proper z-x-z (Goldstein's, when intrinsic).
    ZXZ,
    /// Proper z-y-z (the article's, when intrinsic).
    ZYZ,
}

impl EulerSequence {
    /// All twelve sequences, Tait–Bryan first.
    pub const ALL: [EulerSequence; 12] = [
        EulerSequence::XYZ,
        EulerSequence::XZY,
        EulerSequence::YXZ,
        EulerSequence::YZX,
        EulerSequence::ZXY,
        EulerSequence::ZYX,
        EulerSequence::XYX,
        EulerSequence::XZX,
        EulerSequence::YXY,
        EulerSequence::YZY,
        EulerSequence::ZXZ,
        EulerSequence::ZYZ,
    ];

    /// The three axes in the order they are named.
    #[must_use]
    pub const fn axes(self) -> [Axis; 3] {
        use Axis::{X, Y, Z};
        match self {
            EulerSequence::XYZ => [X, Y, Z],
            EulerSequence::XZY => [X, Z, Y],
            EulerSequence::YXZ => [Y, X, Z],
            EulerSequence::YZX => [Y, Z, X],
            EulerSequence::ZXY => [Z, X, Y],
            EulerSequence::ZYX => [Z, Y, X],
            EulerSequence::XYX => [X, Y, X],
            EulerSequence::XZX => [X, Z, X],
            EulerSequence::YXY => [Y, X, Y],
            EulerSequence::YZY => [Y, Z, Y],
            EulerSequence::ZXZ => [Z, X, Z],
            EulerSequence::ZYZ => [Z, Y, Z],
        }
    }

    /// The sequence with the given axes, if it is one of the twelve.
    #[must_use]
    pub fn from_axes(axes: [Axis; 3]) -> Option<EulerSequence> {
        EulerSequence::ALL.into_iter().find(|s| s.axes() == axes)
    }

    /// Proper Euler sequence (first axis repeated) rather than Tait–Bryan.
    #[must_use]
    pub const fn is_proper(self) -> bool {
        let a = self.axes();
        a[0].index() == a[2].index()
    }

    /// The sequence read backwards (`ZYX` for `XYZ`; proper sequences are their own reverse).
    #[must_use]
    pub fn reversed(self) -> EulerSequence {
        let [a, b, c] = self.axes();
        // Reversing one of the twelve sequences gives one of the twelve.
        EulerSequence::from_axes([c, b, a]).unwrap_or(self)
    }
}

impl fmt::Display for EulerSequence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.axes();
        write!(f, "{}{}{}", a[0].letter(), a[1].letter(), a[2].letter())
    }
}

impl FromStr for EulerSequence {
    type Err = KinematicsError;

    /// Parses `"zyz"`, `"ZXZ"`, `"z-y-x"`, … (case-insensitive; dashes ignored).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let letters: Vec<char> = s
            .chars()
            .filter(|c| *c != '-')
            .map(|c| c.to_ascii_lowercase())
            .collect();
        let axis = |c: char| match c {
            'x' => Some(Axis::X),
            'y' => Some(Axis::Y),
            'z' => Some(Axis::Z),
            _ => None,
        };
        if letters.len() == 3
            && let (Some(a), Some(b), Some(c)) =
                (axis(letters[0]), axis(letters[1]), axis(letters[2]))
            && let Some(seq) = EulerSequence::from_axes([a, b, c])
        {
            return Ok(seq);
        }
        Err(KinematicsError::UnknownSequence(s.to_string()))
    }
}

/// Whether the rotations of a sequence are about the moving (body) axes or the fixed (space) axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RotationKind {
    /// About the moving axes: `R = R_{e₁}(a₁) R_{e₂}(a₂) R_{e₃}(a₃)`.
    Intrinsic,
    /// About the fixed axes: `R = R_{e₃}(a₃) R_{e₂}(a₂) R_{e₁}(a₁)`.
    Extrinsic,
}

/// An Euler-angle convention: an axis sequence and whether it is intrinsic or extrinsic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EulerConvention {
    /// The axis sequence.
    pub sequence: EulerSequence,
    /// Intrinsic (moving axes) or extrinsic (fixed axes).
    pub kind: RotationKind,
}

/// Euler angles extracted from a rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerDecomposition<T: RealField + Copy> {
    /// The three angles in the order the convention names them (radians).
    pub angles: Vector3<T>,
    /// The middle angle is within [`GIMBAL_LOCK_TOLERANCE`] of gimbal lock: the first and third
    /// angles are then not individually determined (only their sum or difference is), although
    /// the returned triple still reproduces the rotation.
    pub gimbal_lock: bool,
}

impl fmt::Display for EulerConvention {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.kind {
            RotationKind::Intrinsic => "intrinsic",
            RotationKind::Extrinsic => "extrinsic",
        };
        write!(f, "{kind} {}", self.sequence)
    }
}

impl FromStr for EulerConvention {
    type Err = KinematicsError;

    /// Parses `"zyz"` (intrinsic), `"intrinsic-zyz"`, `"extrinsic-xyz"`, `"zyz-extrinsic"`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.to_ascii_lowercase();
        let (kind, rest) = if let Some(r) = lower.strip_prefix("extrinsic") {
            (RotationKind::Extrinsic, r)
        } else if let Some(r) = lower.strip_suffix("extrinsic") {
            (RotationKind::Extrinsic, r)
        } else if let Some(r) = lower.strip_prefix("intrinsic") {
            (RotationKind::Intrinsic, r)
        } else if let Some(r) = lower.strip_suffix("intrinsic") {
            (RotationKind::Intrinsic, r)
        } else {
            (RotationKind::Intrinsic, lower.as_str())
        };
        let rest = rest.trim_matches(|c: char| c == '-' || c == '_' || c == ' ');
        let sequence = rest
            .parse::<EulerSequence>()
            .map_err(|_| KinematicsError::UnknownSequence(s.to_string()))?;
        Ok(EulerConvention { sequence, kind })
    }
}

/// Wraps an angle into `(−π, π]`.
fn wrap<T: RealField + Copy>(a: T) -> T {
    let pi = T::pi();
    let two_pi = T::two_pi();
    if a > pi {
        a - two_pi
    } else if a <= -pi {
        a + two_pi
    } else {
        a
    }
}

/// Levi-Civita symbol of three distinct indices (0, 1, 2 in some order).
fn parity(i: usize, j: usize, k: usize) -> f64 {
    if (i + 1) % 3 == j && (j + 1) % 3 == k {
        1.0
    } else {
        -1.0
    }
}

impl EulerConvention {
    /// The article's convention: intrinsic ZYZ, `R = R_z(φ) R_y(θ) R_z(ψ)`.
    pub const ARTICLE: EulerConvention = EulerConvention::intrinsic(EulerSequence::ZYZ);
    /// Goldstein's convention (Physics 151 lecture 9): intrinsic ZXZ, `R = R_z(φ) R_x(θ) R_z(ψ)`
    /// (the transpose of the passive `A = B C D`).
    pub const GOLDSTEIN: EulerConvention = EulerConvention::intrinsic(EulerSequence::ZXZ);

    /// An intrinsic (moving-axes) convention.
    #[must_use]
    pub const fn intrinsic(sequence: EulerSequence) -> EulerConvention {
        EulerConvention {
            sequence,
            kind: RotationKind::Intrinsic,
        }
    }

    /// An extrinsic (fixed-axes) convention.
    #[must_use]
    pub const fn extrinsic(sequence: EulerSequence) -> EulerConvention {
        EulerConvention {
            sequence,
            kind: RotationKind::Extrinsic,
        }
    }

    /// All 24 conventions: the twelve sequences, intrinsic then extrinsic.
    pub fn all() -> impl Iterator<Item = EulerConvention> {
        EulerSequence::ALL
            .into_iter()
            .map(EulerConvention::intrinsic)
            .chain(
                EulerSequence::ALL
                    .into_iter()
                    .map(EulerConvention::extrinsic),
            )
    }

    /// The axes of the equivalent intrinsic product `R = R_{e₁}(·) R_{e₂}(·) R_{e₃}(·)`.
    fn product_axes(&self) -> [Axis; 3] {
        let a = self.sequence.axes();
        match self.kind {
            RotationKind::Intrinsic => a,
            RotationKind::Extrinsic => [a[2], a[1], a[0]],
        }
    }

    /// Angles reordered to match [`Self::product_axes`] (an involution).
    fn product_order<T: RealField + Copy>(&self, v: &Vector3<T>) -> Vector3<T> {
        match self.kind {
            RotationKind::Intrinsic => *v,
            RotationKind::Extrinsic => Vector3::new(v.z, v.y, v.x),
        }
    }

    /// Where the middle angle makes the convention singular, in words.
    #[must_use]
    pub fn singular_at(&self) -> &'static str {
        if self.sequence.is_proper() {
            "middle angle 0 or π"
        } else {
            "middle angle ±π/2"
        }
    }

    /// The rotation matrix for the given angles (in the order the convention names them).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tumble_kinematics::{EulerConvention, EulerSequence};
    /// let conv = EulerConvention::extrinsic(EulerSequence::XYZ);
    /// let angles = Vector3::new(0.1, -0.7, 2.5);
    /// let back = conv.from_rotation(&conv.to_rotation(&angles));
    /// assert!((back.angles - angles).norm() < 1e-14 && !back.gimbal_lock);
    /// ```
    #[must_use]
    pub fn to_rotation<T: RealField + Copy>(&self, angles: &Vector3<T>) -> Rotation3<T> {
        let ax = self.product_axes();
        let a = self.product_order(angles);
        ax[0].rotation(a.x) * ax[1].rotation(a.y) * ax[2].rotation(a.z)
    }

    /// The unit quaternion for the given angles.
    #[must_use]
    pub fn to_quaternion<T: RealField + Copy>(&self, angles: &Vector3<T>) -> UnitQuaternion<T> {
        let ax = self.product_axes();
        let a = self.product_order(angles);
        ax[0].quaternion(a.x) * ax[1].quaternion(a.y) * ax[2].quaternion(a.z)
    }

    /// Euler angles of a unit quaternion (either sign), with the gimbal-lock flag
    /// (tolerance [`GIMBAL_LOCK_TOLERANCE`]).
    #[must_use]
    pub fn from_quaternion<T: RealField + Copy>(
        &self,
        q: &UnitQuaternion<T>,
    ) -> EulerDecomposition<T> {
        let ax = self.product_axes();
        let (i, j) = (ax[0].index(), ax[1].index());
        let (a1, a2, a3, lock) = if self.sequence.is_proper() {
            proper_intrinsic(q.quaternion(), i, j)
        } else {
            // R = R_i(α) R_j(β) R_k(γ)  ⇒  R P = R_i(α) R_j(β + π/2) R_i(−εγ),  P = R_j(π/2).
            let k = ax[2].index();
            let eps: T = real(parity(i, j, k));
            let p = Axis::from_index(j).quaternion(T::frac_pi_2());
            let qp = q.quaternion() * p.quaternion();
            let (alpha, beta, gamma, lock) = proper_intrinsic(&qp, i, j);
            (alpha, beta - T::frac_pi_2(), wrap(-(eps * gamma)), lock)
        };
        EulerDecomposition {
            angles: self.product_order(&Vector3::new(a1, a2, a3)),
            gimbal_lock: lock,
        }
    }

    /// Euler angles of a rotation matrix (through its quaternion; see [`Self::from_quaternion`]).
    #[must_use]
    pub fn from_rotation<T: RealField + Copy>(&self, r: &Rotation3<T>) -> EulerDecomposition<T> {
        self.from_quaternion(&rotation_to_quat(r))
    }

    /// The rotation matrix from the quaternion path (for cross-checks).
    #[must_use]
    pub fn to_rotation_via_quaternion<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
    ) -> Rotation3<T> {
        quat_to_rotation(&self.to_quaternion(angles))
    }

    /// The matrix `E(a)` with `ω_space = E(a) ȧ` (columns: the space-frame axis of each rate).
    #[must_use]
    pub fn rate_matrix_space<T: RealField + Copy>(&self, angles: &Vector3<T>) -> Matrix3<T> {
        let ax = self.product_axes();
        let a = self.product_order(angles);
        let r1 = ax[0].rotation(a.x);
        let r12 = r1 * ax[1].rotation(a.y);
        let c1 = ax[0].unit::<T>();
        let c2 = r1 * ax[1].unit::<T>();
        let c3 = r12 * ax[2].unit::<T>();
        self.columns_in_convention_order(c1, c2, c3)
    }

    /// The matrix `E'(a)` with `ω_body = E'(a) ȧ` (columns: the body-frame axis of each rate).
    #[must_use]
    pub fn rate_matrix_body<T: RealField + Copy>(&self, angles: &Vector3<T>) -> Matrix3<T> {
        let ax = self.product_axes();
        let a = self.product_order(angles);
        let r3 = ax[2].rotation(a.z);
        let r23 = ax[1].rotation(a.y) * r3;
        let c1 = r23.inverse() * ax[0].unit::<T>();
        let c2 = r3.inverse() * ax[1].unit::<T>();
        let c3 = ax[2].unit::<T>();
        self.columns_in_convention_order(c1, c2, c3)
    }

    fn columns_in_convention_order<T: RealField + Copy>(
        &self,
        c1: Vector3<T>,
        c2: Vector3<T>,
        c3: Vector3<T>,
    ) -> Matrix3<T> {
        match self.kind {
            RotationKind::Intrinsic => Matrix3::from_columns(&[c1, c2, c3]),
            RotationKind::Extrinsic => Matrix3::from_columns(&[c3, c2, c1]),
        }
    }

    /// Space-frame angular velocity `ω = vee(Ṙ Rᵀ)` from angles and their rates.
    #[must_use]
    pub fn omega_space<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        rates: &Vector3<T>,
    ) -> Vector3<T> {
        self.rate_matrix_space(angles) * rates
    }

    /// Body-frame angular velocity `ω' = vee(Rᵀ Ṙ) = Rᵀ ω` from angles and their rates.
    #[must_use]
    pub fn omega_body<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        rates: &Vector3<T>,
    ) -> Vector3<T> {
        self.rate_matrix_body(angles) * rates
    }

    /// `det E(a)`: `−sin a₂` (proper) or `ε cos a₂` (Tait–Bryan), sign flipped for extrinsic.
    #[must_use]
    pub fn rate_determinant<T: RealField + Copy>(&self, angles: &Vector3<T>) -> T {
        let [e1, e2, e3] = self.product_axes();
        let mid = angles.y;
        let d = if self.sequence.is_proper() {
            -mid.sin()
        } else {
            mid.cos() * real::<T>(parity(e1.index(), e2.index(), e3.index()))
        };
        match self.kind {
            RotationKind::Intrinsic => d,
            RotationKind::Extrinsic => -d,
        }
    }

    /// Euler rates from the space-frame angular velocity, `ȧ = E(a)⁻¹ ω`.
    ///
    /// # Errors
    /// [`KinematicsError::EulerRateSingular`] when `|det E| < RATE_SINGULARITY_TOLERANCE`.
    pub fn try_rates_from_omega_space<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        omega: &Vector3<T>,
    ) -> Result<Vector3<T>, KinematicsError> {
        self.try_rates_from_omega_space_with_tolerance(angles, omega, RATE_SINGULARITY_TOLERANCE)
    }

    /// As [`Self::try_rates_from_omega_space`] with a caller-chosen bound on `|det E|`.
    ///
    /// # Errors
    /// [`KinematicsError::EulerRateSingular`] when `|det E| < tolerance`.
    pub fn try_rates_from_omega_space_with_tolerance<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        omega: &Vector3<T>,
        tolerance: f64,
    ) -> Result<Vector3<T>, KinematicsError> {
        self.check_rate_singularity(angles, tolerance)?;
        solve3(&self.rate_matrix_space(angles), omega)
            .ok_or_else(|| self.rate_error(angles, tolerance))
    }

    /// Euler rates from the body-frame angular velocity, `ȧ = E'(a)⁻¹ ω'`.
    ///
    /// # Errors
    /// [`KinematicsError::EulerRateSingular`] when `|det E'| < RATE_SINGULARITY_TOLERANCE`.
    pub fn try_rates_from_omega_body<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        omega_body: &Vector3<T>,
    ) -> Result<Vector3<T>, KinematicsError> {
        self.try_rates_from_omega_body_with_tolerance(
            angles,
            omega_body,
            RATE_SINGULARITY_TOLERANCE,
        )
    }

    /// As [`Self::try_rates_from_omega_body`] with a caller-chosen bound on `|det E'|`.
    ///
    /// # Errors
    /// [`KinematicsError::EulerRateSingular`] when `|det E'| < tolerance`.
    pub fn try_rates_from_omega_body_with_tolerance<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        omega_body: &Vector3<T>,
        tolerance: f64,
    ) -> Result<Vector3<T>, KinematicsError> {
        self.check_rate_singularity(angles, tolerance)?;
        solve3(&self.rate_matrix_body(angles), omega_body)
            .ok_or_else(|| self.rate_error(angles, tolerance))
    }

    fn check_rate_singularity<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        tolerance: f64,
    ) -> Result<(), KinematicsError> {
        let det = self.rate_determinant(angles);
        // Written so that a NaN determinant is rejected too.
        let regular = det.abs() >= real(tolerance);
        if !regular {
            return Err(self.rate_error(angles, tolerance));
        }
        Ok(())
    }

    fn rate_error<T: RealField + Copy>(
        &self,
        angles: &Vector3<T>,
        tolerance: f64,
    ) -> KinematicsError {
        KinematicsError::EulerRateSingular {
            convention: *self,
            middle_angle: to_f64(angles.y),
            determinant: to_f64(self.rate_determinant(angles)),
            tolerance,
            singular_at: self.singular_at(),
        }
    }
}

/// Solves the 3×3 system by Cramer's rule (the matrix is well conditioned when this is called).
fn solve3<T: RealField + Copy>(m: &Matrix3<T>, b: &Vector3<T>) -> Option<Vector3<T>> {
    let c0 = m.column(0).into_owned();
    let c1 = m.column(1).into_owned();
    let c2 = m.column(2).into_owned();
    let det = c0.dot(&c1.cross(&c2));
    if det == T::zero() {
        return None;
    }
    Some(Vector3::new(
        b.dot(&c1.cross(&c2)) / det,
        c0.dot(&b.cross(&c2)) / det,
        c0.dot(&c1.cross(b)) / det,
    ))
}

/// Proper intrinsic decomposition `R = R_i(α) R_j(β) R_i(γ)` of a (not necessarily normalized)
/// quaternion; returns `(α, β, γ, gimbal_lock)` with `β ∈ [0, π]`.
fn proper_intrinsic<T: RealField + Copy>(q: &Quaternion<T>, i: usize, j: usize) -> (T, T, T, bool) {
    let k = 3 - i - j;
    let eps: T = real(parity(i, j, k));
    let v = [q.i, q.j, q.k];
    let (a, b, c, d) = (q.w, v[i], v[j], eps * v[k]);
    let ab = a.hypot(b);
    let cd = c.hypot(d);
    let beta = T::atan2(cd, ab) * real::<T>(2.0);
    let mut half_sum = T::atan2(b, a);
    let mut half_diff = T::atan2(d, c);
    // Exact lock (a vanishing pair): only α ± γ is defined; put it all into α. Near (but not at)
    // lock the computed pair is kept: it reproduces the rotation to round-off.
    if cd == T::zero() {
        half_diff = half_sum;
    } else if ab == T::zero() {
        half_sum = half_diff;
    }
    let alpha = wrap(half_sum + half_diff);
    let gamma = wrap(half_sum - half_diff);
    let tol: T = real(GIMBAL_LOCK_TOLERANCE);
    let lock = beta < tol || beta > T::pi() - tol;
    (alpha, beta, gamma, lock)
}
