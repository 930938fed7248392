//! The exact flow of the free (torque-free) rigid body.
//!
//! # Problem
//!
//! A rigid body with body-frame inertia `J` (symmetric positive definite, not necessarily
//! diagonal) has orientation `R` (body → space) and body angular momentum `m`; the spatial
//! angular momentum `L = R m` is constant, and
//! `ṁ = m × ω`, `Ṙ = R hat(ω)`, `ω = J⁻¹ m` (Euler's equations), with invariants
//! `|m|² = M²` and `2E = m · J⁻¹ m`.
//!
//! # Solution
//!
//! In the principal frame (`J = Q diag(I) Qᵀ`) the axes are relabelled so that axis 3 is the
//! one about which `m` circulates (the largest moment when `M² > 2E I₂`, the smallest when
//! `M² < 2E I₂`), and `bᵢ = 1/Iᵢ`. Then (Jacobi; Landau & Lifshitz §37)
//!
//! ```text
//! m₁ = s₁ a₁ cn u,   m₂ = s₁s₃ a₂ sn u,   m₃ = s₃ a₃ dn u,    u = λ t + u₀,
//! a₁² = m₁² + m₂² (I₁/I₂)(I₃ − I₂)/(I₃ − I₁),   a₃² = m₃² + m₂² (I₃/I₂)(I₂ − I₁)/(I₃ − I₁),
//! λ = a₃ √((b₁ − b₃)(b₂ − b₃)),   a₂ = a₁ a₃ (b₁ − b₃)/λ,
//! k² = a₁² (b₁ − b₂) / (a₃² (b₂ − b₃)),   1 − k² = (M² − 2E I₂) / (I₂ a₃² (b₂ − b₃)),
//! ```
//!
//! where every amplitude is a sum of terms of one sign (no cancellation), `s₃ = sign m₃`
//! (constant), `s₁ = sign m₁(0)` so that the initial amplitude `φ₀ = atan2(sn u₀, cn u₀)` lies
//! in `[−π/2, π/2]` and `u₀ = F(φ₀ | k²)`; on the separatrix (`k = 1`) `cn` keeps its sign, so
//! the choice of `s₁` is what makes the formula valid there too.
//!
//! The orientation is `R(t) = P R_z(φ(t)) B(m(t))` where `B(m)` is the rotation with rows
//! `(m₂, −m₁, 0)/ρ`, `(m₃m₁, m₃m₂, −ρ²)/(Mρ)`, `m/M` (`ρ² = m₁² + m₂²`) — that is
//! `B = R_x(θ) R_z(ψ)` of the ZXZ angles of `m` — so that `Bᵀ e₃ = m/M`; `P = R(0) B(m₀)ᵀ` is
//! constant and maps `e₃` to `L/|L|`. The precession angle obeys
//! `φ̇ = M (b₁m₁² + b₂m₂²)/ρ² = M b₃ + M (b₁ − b₃)/(1 − n sn² u)` with `n = (b₁ − b₂)/(b₃ − b₂) ≤ 0`,
//! hence `φ(t) = M b₃ t + M (b₁ − b₃)/λ · [Π(n; am u | k²) − Π(n; am u₀ | k²)]`,
//! the incomplete elliptic integral of the third kind (Carlson's `R_J`), continued beyond a
//! half period by `Π(n; am(u + 2K)) = Π(n; am u) + 2Π(n)`.
//!
//! Special cases, exact in closed form: a sphere (`R(t) = exp(t hat(ω)) R₀`); an axisymmetric
//! body (`I_a = I_b = I⊥ ≠ I_s`, symmetry axis `e`):
//! `R(t) = exp(t hat(L)/I⊥) R₀ exp(t (1/I_s − 1/I⊥)(m·e) hat(e))`; and `m` exactly along a
//! principal axis (`R(t) = R₀ exp(t hat(ω))`), which includes the unstable middle-axis
//! equilibrium where the separatrix formula's `u₀` would be infinite.
//!
//! These formulas are derived here from Euler's equations (each sign checked by substitution)
//! rather than copied from Celledoni, Fassò, Säfström & Zanna (2008), whose published version
//! has a sign error in one case and a wrong separatrix formula; the tests compare with a
//! Gauss–Legendre integration to 1e-12.
//!
//! # References
//! * L. D. Landau, E. M. Lifshitz, *Mechanics*, 3rd ed., §37.
//! * E. Celledoni, F. Fassò, N. Säfström, A. Zanna, "The exact computation of the free rigid body
//!   motion and its use in splitting methods", SIAM J. Sci. Comput. 30(4) (2008) 2084–2112.
//! * B. C. Carlson, Numer. Algorithms 10 (1995) 13–26.

use nalgebra::{Matrix3, Rotation3, SymmetricEigen, Vector3};

use tumble_kinematics::so3::exp;

use crate::error::Error;
use crate::special::{
    complete_k_mc, complete_pi_mc, incomplete_f_mc, incomplete_pi_scd, jacobi_reduced,
};

/// Relative tolerance under which two principal moments are treated as equal (the body as
/// axisymmetric): eigenvalues of a rotated diagonal tensor differ by round-off only.
pub const SYMMETRY_TOLERANCE: f64 = 1e-14;

/// A torque-free rigid body: its principal moments and axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeRigidBody {
    /// Principal moments, ascending.
    moments: Vector3<f64>,
    /// Principal axes as the columns of a right-handed rotation `Q` (body frame): `J = Q diag Qᵀ`.
    axes: Rotation3<f64>,
    /// `Q` is exactly the identity (the body frame is principal, moments ascending along x, y, z).
    principal: bool,
}

/// Which closed form a flow uses. (The general variant is larger than the others; flows are
/// built once per run or per splitting step, so boxing it would cost an allocation for nothing.)
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(clippy::large_enum_variant)]
enum Kind {
    /// All moments equal: `R(t) = exp(t ω_space) R₀`.
    Sphere { omega_space: Vector3<f64> },
    /// `m` exactly along a principal axis: `R(t) = R₀ exp(t ω_body)`.
    PrincipalSpin { omega_body: Vector3<f64> },
    /// Axisymmetric: `R(t) = exp(t L/I⊥) R₀ exp(t rate axis)`.
    Symmetric {
        precession: Vector3<f64>,
        axis_body: Vector3<f64>,
        rate: f64,
    },
    /// Asymmetric: elliptic functions.
    General(General),
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct General {
    /// Body components of the reduced axes (columns): `m_body = C m_red`.
    c: Matrix3<f64>,
    /// `P`, from the aligned frame (L along e₃) to space.
    p: Rotation3<f64>,
    b: Vector3<f64>,
    a1: f64,
    a2: f64,
    a3: f64,
    s1: f64,
    s3: f64,
    lambda: f64,
    u0: f64,
    m: f64,
    mc: f64,
    quarter_period: f64,
    n: f64,
    pi_complete: f64,
    pi0: f64,
    precession_coefficient: f64,
    big_m: f64,
}

/// The exact solution from one initial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactFlow {
    r0: Rotation3<f64>,
    m0: Vector3<f64>,
    l_space: Vector3<f64>,
    kind: Kind,
}

fn invalid(name: &'static str, value: f64, reason: &'static str) -> Error {
    Error::InvalidParameter {
        name,
        value,
        reason,
    }
}

impl FreeRigidBody {
    /// From the body-frame inertia tensor.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if `J` is not finite, not symmetric, not positive definite, or
    /// violates the triangle inequality `I₁ + I₂ ≥ I₃`.
    pub fn from_inertia(j: &Matrix3<f64>) -> Result<Self, Error> {
        if j.iter().any(|x| !x.is_finite()) {
            return Err(invalid("inertia", f64::NAN, "every entry must be finite"));
        }
        let asym = (j - j.transpose()).amax();
        if asym > 1e-12 * j.amax() {
            return Err(invalid("inertia", asym, "the tensor must be symmetric"));
        }
        // A diagonal tensor is already in principal form: its axes are exact signed unit
        // vectors (the iterative eigensolver would return them perturbed by ~1e-16, and every
        // frame change of the exact flow and the splittings would carry that error).
        let diagonal = (0..3).all(|r| (0..3).all(|c| r == c || j[(r, c)] == 0.0));
        let (eigenvalues, eigenvectors) = if diagonal {
            (j.diagonal(), Matrix3::identity())
        } else {
            let eig = SymmetricEigen::new((j + j.transpose()) * 0.5);
            (eig.eigenvalues, eig.eigenvectors)
        };
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&a, &b| eigenvalues[a].total_cmp(&eigenvalues[b]));
        let moments = Vector3::new(
            eigenvalues[idx[0]],
            eigenvalues[idx[1]],
            eigenvalues[idx[2]],
        );
        let mut q = Matrix3::from_columns(&[
            eigenvectors.column(idx[0]).into_owned(),
            eigenvectors.column(idx[1]).into_owned(),
            eigenvectors.column(idx[2]).into_owned(),
        ]);
        if q.determinant() < 0.0 {
            q.set_column(2, &(-q.column(2)));
        }
        Self::check_moments(&moments)?;
        let axes = if diagonal {
            Rotation3::from_matrix_unchecked(q)
        } else {
            Rotation3::from_matrix(&q)
        };
        let principal = *axes.matrix() == Matrix3::identity();
        Ok(FreeRigidBody {
            moments,
            axes,
            principal,
        })
    }

    /// From principal moments (any order) along the body axes x, y, z.
    ///
    /// # Errors
    /// As [`Self::from_inertia`].
    pub fn from_principal_moments(i: Vector3<f64>) -> Result<Self, Error> {
        Self::from_inertia(&Matrix3::from_diagonal(&i))
    }

    fn check_moments(i: &Vector3<f64>) -> Result<(), Error> {
        // Written so that a NaN moment is rejected too.
        let positive = i[0] > 0.0;
        if !positive {
            return Err(invalid(
                "inertia",
                i[0],
                "principal moments must be positive",
            ));
        }
        if i[0] + i[1] < i[2] * (1.0 - 1e-12) {
            return Err(invalid(
                "inertia",
                i[2],
                "principal moments must satisfy I1 + I2 >= I3",
            ));
        }
        Ok(())
    }

    /// Principal moments, ascending.
    #[must_use]
    pub fn principal_moments(&self) -> Vector3<f64> {
        self.moments
    }

    /// Principal axes: the rotation `Q` whose columns are the body-frame principal axes, in the
    /// order of [`Self::principal_moments`], so that `J = Q diag(I) Qᵀ`.
    #[must_use]
    pub fn principal_axes(&self) -> Rotation3<f64> {
        self.axes
    }

    /// Body-frame inertia tensor `J = Q diag(I) Qᵀ`.
    #[must_use]
    pub fn inertia(&self) -> Matrix3<f64> {
        self.axes.matrix() * Matrix3::from_diagonal(&self.moments) * self.axes.matrix().transpose()
    }

    /// Body angular velocity `ω = J⁻¹ m`.
    #[must_use]
    #[inline]
    pub fn omega(&self, m: &Vector3<f64>) -> Vector3<f64> {
        if self.principal {
            // Q = 1: the products with Q below change no bit of a finite m.
            return m.component_div(&self.moments);
        }
        let q = self.axes.matrix();
        q * (q.transpose() * m).component_div(&self.moments)
    }

    /// Kinetic energy `½ m · J⁻¹ m`.
    #[must_use]
    pub fn energy(&self, m: &Vector3<f64>) -> f64 {
        0.5 * m.dot(&self.omega(m))
    }

    /// The exact flow from `R(0) = r0`, `m(0) = m0` (body frame).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite initial state.
    pub fn flow(&self, r0: &Rotation3<f64>, m0: &Vector3<f64>) -> Result<ExactFlow, Error> {
        if m0.iter().chain(r0.matrix().iter()).any(|x| !x.is_finite()) {
            return Err(invalid(
                "state",
                f64::NAN,
                "the initial state must be finite",
            ));
        }
        let l_space = r0 * m0;
        let i = self.moments;
        let q = *self.axes.matrix();
        let mp = q.transpose() * m0; // principal components
        let kind = self.kind(r0, m0, &mp, &q, &l_space, &i);
        Ok(ExactFlow {
            r0: *r0,
            m0: *m0,
            l_space,
            kind,
        })
    }

    fn kind(
        &self,
        r0: &Rotation3<f64>,
        m0: &Vector3<f64>,
        mp: &Vector3<f64>,
        q: &Matrix3<f64>,
        l_space: &Vector3<f64>,
        i: &Vector3<f64>,
    ) -> Kind {
        let close = |a: f64, b: f64| (a - b).abs() <= SYMMETRY_TOLERANCE * i[2];
        if close(i[0], i[2]) {
            let iso = (i[0] + i[1] + i[2]) / 3.0;
            return Kind::Sphere {
                omega_space: l_space / iso,
            };
        }
        // m exactly along a principal axis.
        for axis in 0..3 {
            let others = (0..3).filter(|&j| j != axis).all(|j| mp[j] == 0.0);
            if others {
                return Kind::PrincipalSpin {
                    omega_body: self.omega(m0),
                };
            }
        }
        if close(i[0], i[1]) || close(i[1], i[2]) {
            let (sym, perp) = if close(i[0], i[1]) {
                (2, 0.5 * (i[0] + i[1]))
            } else {
                (0, 0.5 * (i[1] + i[2]))
            };
            let axis_body = q.column(sym).into_owned();
            let rate = (perp - i[sym]) / (i[sym] * perp) * m0.dot(&axis_body);
            return Kind::Symmetric {
                precession: l_space / perp,
                axis_body,
                rate,
            };
        }
        Kind::General(general(r0, mp, q, i))
    }
}

/// `B(m)`: rows `(m₂, −m₁, 0)/ρ`, `(m₃m₁, m₃m₂, −ρ²)/(Mρ)`, `m/M`.
fn align(m: &Vector3<f64>) -> Rotation3<f64> {
    let rho2 = m.x * m.x + m.y * m.y;
    let rho = rho2.sqrt();
    let big_m = (rho2 + m.z * m.z).sqrt();
    Rotation3::from_matrix_unchecked(Matrix3::new(
        m.y / rho,
        -m.x / rho,
        0.0,
        m.z * m.x / (big_m * rho),
        m.z * m.y / (big_m * rho),
        -rho / big_m,
        m.x / big_m,
        m.y / big_m,
        m.z / big_m,
    ))
}

fn general(r0: &Rotation3<f64>, mp: &Vector3<f64>, q: &Matrix3<f64>, i: &Vector3<f64>) -> General {
    // Which side of the separatrix: δ = M² − 2E I₂ (the m₂ terms cancel exactly).
    // 1 − I₂/Iⱼ written as (Iⱼ − I₂)/Iⱼ: no cancellation for nearly equal moments.
    let t1 = mp.x * mp.x * ((i[0] - i[1]) / i[0]);
    let t3 = mp.z * mp.z * ((i[2] - i[1]) / i[2]);
    let delta = t1 + t3;
    // Within the rounding of its two terms, δ cannot tell the sides apart: on the separatrix.
    let on_separatrix = delta.abs() <= 8.0 * f64::EPSILON * (t1.abs() + t3.abs());
    // Reduced labels: axis 3 is the circulation axis. For δ < 0 swap 1 ↔ 3 with a sign on the
    // (new) first axis so the frame stays right-handed: (e₃, e₂, −e₁) has determinant +1.
    let (perm, c_pr) = if delta >= 0.0 {
        ([0usize, 1, 2], Matrix3::identity())
    } else {
        (
            [2usize, 1, 0],
            Matrix3::new(0.0, 0.0, -1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0),
        )
    };
    // c_pr maps reduced components to principal components: principal = c_pr · reduced.
    let c = q * c_pr;
    let mr = c.transpose() * (q * mp);
    let ir = Vector3::new(i[perm[0]], i[perm[1]], i[perm[2]]);
    let b = ir.map(|x| 1.0 / x);
    // Differences of inverse moments without cancellation: bᵢ − bⱼ = (Iⱼ − Iᵢ)/(Iᵢ Iⱼ), exact to
    // a few ulps even for nearly equal moments (1/1000 − 1/1001 by subtraction loses 6 digits).
    let db = |i: usize, j: usize| (ir[j] - ir[i]) / (ir[i] * ir[j]);
    let (b01, b02, b12) = (db(0, 1), db(0, 2), db(1, 2));
    let (m1, m2, m3) = (mr.x, mr.y, mr.z);
    let a1 = (m1 * m1 + m2 * m2 * (ir[0] / ir[1]) * (ir[2] - ir[1]) / (ir[2] - ir[0])).sqrt();
    let a3 = (m3 * m3 + m2 * m2 * (ir[2] / ir[1]) * (ir[1] - ir[0]) / (ir[2] - ir[0])).sqrt();
    let lambda = a3 * (b02 * b12).sqrt();
    let a2 = a1 * a3 * b02 / lambda;
    let denom = a3 * a3 * b12;
    let mut m = a1 * a1 * b01 / denom;
    let mut mc = delta / (ir[1] * denom);
    if on_separatrix || mc <= 0.0 || m >= 1.0 {
        m = 1.0;
        mc = 0.0;
    }
    let s3 = if m3 < 0.0 { -1.0 } else { 1.0 };
    let s1 = if m1 < 0.0 { -1.0 } else { 1.0 };
    // Initial amplitude: cn u₀ = m₁/(s₁a₁) ≥ 0, sn u₀ = m₂/(s₁s₃a₂), dn u₀ = |m₃|/a₃.
    let cn0 = m1 / (s1 * a1);
    let sn0 = m2 / (s1 * s3 * a2);
    let h = sn0.hypot(cn0);
    let (sn0, cn0) = (sn0 / h, cn0 / h);
    let dn0 = m3.abs() / a3;
    let u0 = if mc == 0.0 {
        sn0.atanh()
    } else {
        incomplete_f_mc(sn0, cn0, mc)
    };
    let quarter_period = if mc == 0.0 {
        f64::INFINITY
    } else {
        complete_k_mc(mc)
    };
    let n = -b01 / b12;
    let pi_complete = if mc == 0.0 {
        f64::INFINITY
    } else {
        complete_pi_mc(n, mc)
    };
    let pi0 = incomplete_pi_scd(n, sn0, cn0, dn0);
    let big_m = mr.norm();
    let p = r0 * Rotation3::from_matrix_unchecked(c) * align(&mr).inverse();
    General {
        c,
        p,
        b,
        a1,
        a2,
        a3,
        s1,
        s3,
        lambda,
        u0,
        m,
        mc,
        quarter_period,
        n,
        pi_complete,
        pi0,
        precession_coefficient: big_m * b02 / lambda,
        big_m,
    }
}

impl ExactFlow {
    /// The state `(R(t), m(t))` at time `t` (body angular momentum).
    #[must_use]
    pub fn at(&self, t: f64) -> (Rotation3<f64>, Vector3<f64>) {
        match &self.kind {
            Kind::Sphere { omega_space } => (exp(&(omega_space * t)) * self.r0, self.m0),
            Kind::PrincipalSpin { omega_body } => (self.r0 * exp(&(omega_body * t)), self.m0),
            Kind::Symmetric {
                precession,
                axis_body,
                rate,
            } => {
                let spin = exp(&(axis_body * (rate * t)));
                let r = exp(&(precession * t)) * self.r0 * spin;
                // m = Rᵀ L = exp(−t rate ê) m₀: written without Rᵀ, so that an orientation that
                // is orthogonal only to round-off does not leak its defect into m (restarting the
                // flow every step, as splittings do, would otherwise drift L linearly).
                let m = spin.inverse() * self.m0;
                (r, m)
            }
            Kind::General(g) => g.at(t),
        }
    }

    /// The constant spatial angular momentum `L = R m`.
    #[must_use]
    pub fn spatial_momentum(&self) -> Vector3<f64> {
        self.l_space
    }

    /// The period of the body angular momentum `m(t)` (the orientation does not return in
    /// general): `4K(k)/λ` for an asymmetric body, `2π/|(1/I_s − 1/I⊥) m·e|` for an
    /// axisymmetric one. `None` when `m` is constant (a sphere, a spin about a principal axis, an
    /// axisymmetric body spinning about its axis) or on the separatrix (where the period is
    /// infinite). For a spin near the intermediate axis the body flips every half period.
    #[must_use]
    pub fn momentum_period(&self) -> Option<f64> {
        match &self.kind {
            Kind::Sphere { .. } | Kind::PrincipalSpin { .. } => None,
            Kind::Symmetric { rate, .. } => {
                (*rate != 0.0).then(|| 2.0 * std::f64::consts::PI / rate.abs())
            }
            Kind::General(g) => g
                .quarter_period
                .is_finite()
                .then(|| 4.0 * g.quarter_period / g.lambda),
        }
    }
}

impl General {
    fn at(&self, t: f64) -> (Rotation3<f64>, Vector3<f64>) {
        let u = self.lambda * t + self.u0;
        let j = jacobi_reduced(u, self.m, self.mc, self.quarter_period);
        let mr = Vector3::new(
            self.s1 * self.a1 * j.cn,
            self.s1 * self.s3 * self.a2 * j.sn,
            self.s3 * self.a3 * j.dn,
        );
        let (rs, rc, rd) = j.reduced;
        let pi_u = if j.half_periods != 0.0 {
            2.0 * j.half_periods * self.pi_complete
        } else {
            0.0
        } + incomplete_pi_scd(self.n, rs, rc, rd);
        let phi = self.big_m * self.b[2] * t + self.precession_coefficient * (pi_u - self.pi0);
        let r_red = self.p * Rotation3::from_axis_angle(&Vector3::z_axis(), phi) * align(&mr);
        let c = Rotation3::from_matrix_unchecked(self.c);
        (r_red * c.inverse(), self.c * mr)
    }
}
