//! The hoop family: a bead on a hoop that is driven, free to turn about a vertical axis, or free
//! to rotate in every direction.
//!
//! # Geometry (shared by every hoop scene)
//!
//! A thin uniform hoop of mass `M` and radius `a` has body inertia
//! `diag(Ma²/2, Ma²/2, Ma²)` about its centre, normal along body z; its centre is a fixed pivot
//! at the origin. A frictionless bead of mass `m` sits at body position `a (cos α, sin α, 0)`.
//! The orientation is given by the article's Euler angles, `R = R_z(φ) R_y(θ) R_z(ψ)` (intrinsic
//! ZYZ, body → lab); with `θ = π/2` the hoop stands vertical and body x points straight down, so
//! `α = 0` is the bottom of the hoop. Lab z is up; gravity is `(0, 0, −g)`.
//!
//! The Lagrangian is built as the article builds it: `ω` in the body frame from the Euler rates,
//! `T_hoop = ½ ω·(I ω)`, the bead's velocity `v = ω × r + a α̇ (−sin α, cos α, 0)` (body
//! components), `T_bead = ½ m |v|²`, and `V = m g (R r)_z`.
//!
//! # Scenes
//!
//! * [`DrivenHoop`] (`driven-hoop`, coordinate α): the hoop stands vertical and is spun at a
//!   constant `ω` about lab z. Equation of motion `α̈ = (ω² cos α − g/a) sin α`; equilibria 0, π
//!   and `cos α* = g/(aω²)` for `ω² > g/a` (`ω² = 2g/a` gives 60°); small oscillations
//!   `Ω² = g/a − ω²` at the bottom and `Ω² = ω² − g²/(a²ω²)` about `α*`; the Jacobi integral
//!   `½α̇² − ½ω² sin²α − (g/a) cos α` (per `m a²`) is conserved.
//! * [`SpinningHoop`] (`spinning-hoop`, coordinates φ, α): the vertical hoop turns freely about
//!   the lab z axis. `L_z = (Ma²/2 + m a² sin²α) φ̇` and the energy are conserved; with `M = 1`,
//!   `a = 0.4`, `m = 0.2`, `φ̇ = 5` and the bead at the top, `φ̇ = 25/6` when the bead is 45° from
//!   the top.
//! * [`FreeHoopEuler`] (coordinates φ, θ, ψ, α): the hoop free to rotate about its centre in
//!   every direction, in Euler angles — the AD twin and cross-check of the SO(3) model, singular
//!   at `θ = 0, π` (hoop horizontal), where its mass matrix becomes singular and the
//!   accelerations are an error.
//!
//! # Separable Hamiltonians
//!
//! Both scenes are also separable Hamiltonians `H = T(p) + V(q)` in the smallest coordinates
//! they need, so Störmer–Verlet (`verlet`), `symplectic-euler`, `strang` (drift and kick) and
//! the composition tables named alone (`yoshida4` … `sofroniou-spaletta10`, which compose
//! Störmer–Verlet) run them, besides the first-order methods on the right-hand sides:
//!
//! * `driven-hoop` in the rotating frame, per unit `m a²` (so that a massless bead is no
//!   exception): `H = ½p² − ½ω² sin²α − (g/a) cos α` with `p = α̇`, the Jacobi integral, on the
//!   state `(α, α̇)` of the right-hand side ([`SeparableHamiltonian`] for [`DrivenHoop`]).
//! * `spinning-hoop` by the Routh reduction of its cyclic angle φ (Goldstein, *Classical
//!   Mechanics*, §8.3): `p_φ = L_z` is a constant of the motion and α moves under
//!   `H_red = p_α²/(2 m a²) + L_z²/(2 I(α)) − m g a cos α`, `I(α) = Ma²/2 + m a² sin²α`, while
//!   `φ̇ = L_z / I(α)`. [`SpinningHoopHamiltonian`] keeps φ in the state by exchanging the pair
//!   `(φ, L_z)` for `(L_z, −φ)`, so that one step of the separable method advances α, α̇ and φ
//!   together, symplectically on the whole phase space, with `L_z` unchanged by every step.
//!
//! The rows are the scene's columns whatever the model: `φ̇ = L_z / I(α)` and `α̇` from the
//! state, energy and angular momentum from them.

mod scenes;
mod taylor;

pub use scenes::{DRIVEN_HOOP, DrivenHoopScene, SPINNING_HOOP, SpinningHoopScene};
pub(crate) use scenes::{critical_spin, critical_spin_guide, hoop_rate};
pub use taylor::{TaylorDrivenHoop, TaylorSpinningHoop};

use std::f64::consts::FRAC_PI_2;

use nalgebra::{RealField, SVector, Vector3};
use tumble_integrators::{Action, Direction, Event, Ode, SeparableHamiltonian};
use tumble_kinematics::EulerConvention;

use crate::error::{ModelError, finite, non_negative, positive};
use crate::lagrangian::Lagrangian;

/// Parameters shared by the hoop scenes (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoopParams {
    /// Hoop mass `M` (kg).
    pub hoop_mass: f64,
    /// Bead mass `m` (kg).
    pub bead_mass: f64,
    /// Hoop radius `a` (m).
    pub radius: f64,
    /// Gravitational acceleration `g` (m/s²).
    pub gravity: f64,
}

impl HoopParams {
    /// Validated parameters.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming `M`, `m`, `a` or `g`: masses and radius must be
    /// positive (the bead may be massless: `m ≥ 0`), `g` finite and not negative.
    pub fn new(
        hoop_mass: f64,
        bead_mass: f64,
        radius: f64,
        gravity: f64,
    ) -> Result<Self, ModelError> {
        Ok(HoopParams {
            hoop_mass: positive("M", hoop_mass)?,
            bead_mass: non_negative("m", bead_mass)?,
            radius: positive("a", radius)?,
            gravity: non_negative("g", gravity)?,
        })
    }

    /// The hoop's moment about a diameter, `Ma²/2`.
    #[must_use]
    pub fn diameter_moment(&self) -> f64 {
        0.5 * self.hoop_mass * self.radius * self.radius
    }

    /// The hoop's moment about its normal, `Ma²`.
    #[must_use]
    pub fn normal_moment(&self) -> f64 {
        self.hoop_mass * self.radius * self.radius
    }
}

fn c<D: RealField + Copy>(x: f64) -> D {
    nalgebra::convert(x)
}

/// `L = ½ ω·(I ω) + ½ m |ω × r + v_rel|² − m g (R r)_z` for the hoop at ZYZ angles `angles`
/// with rates `rates` and the bead at `alpha` with rate `alpha_dot`.
pub fn hoop_lagrangian<D: RealField + Copy>(
    p: &HoopParams,
    angles: &Vector3<D>,
    rates: &Vector3<D>,
    alpha: D,
    alpha_dot: D,
) -> D {
    let conv = EulerConvention::ARTICLE;
    let w = conv.omega_body(angles, rates);
    let half: D = c(0.5);
    let i_perp: D = c(p.diameter_moment());
    let i_3: D = c(p.normal_moment());
    let t_hoop = half * (i_perp * (w.x * w.x + w.y * w.y) + i_3 * w.z * w.z);
    let a: D = c(p.radius);
    let (s, co) = alpha.sin_cos();
    let r = Vector3::new(a * co, a * s, D::zero());
    let v_rel = Vector3::new(-(a * s), a * co, D::zero()) * alpha_dot;
    let v = w.cross(&r) + v_rel;
    let t_bead = half * c::<D>(p.bead_mass) * v.norm_squared();
    let z = (conv.to_rotation(angles) * r).z;
    t_hoop + t_bead - c::<D>(p.bead_mass * p.gravity) * z
}

/// The angular momentum about the pivot in the lab, `R (I ω' + m r × v)`, for the hoop at ZYZ
/// angles `angles` with rates `rates` and the bead at `alpha` with rate `alpha_dot`.
#[must_use]
pub fn hoop_angular_momentum(
    p: &HoopParams,
    angles: &Vector3<f64>,
    rates: &Vector3<f64>,
    alpha: f64,
    alpha_dot: f64,
) -> Vector3<f64> {
    let conv = EulerConvention::ARTICLE;
    let w = conv.omega_body(angles, rates);
    let l_hoop = Vector3::new(
        p.diameter_moment() * w.x,
        p.diameter_moment() * w.y,
        p.normal_moment() * w.z,
    );
    let (s, co) = alpha.sin_cos();
    let r = Vector3::new(p.radius * co, p.radius * s, 0.0);
    let v = w.cross(&r) + Vector3::new(-p.radius * s, p.radius * co, 0.0) * alpha_dot;
    conv.to_rotation(angles) * (l_hoop + r.cross(&v) * p.bead_mass)
}

/// The tilt of the hoop: the angle between its plane and the vertical, `asin |n_z|` with `n`
/// the hoop's normal in the lab (`R e_z`); 0 when standing, π/2 when horizontal.
#[must_use]
pub fn tilt_from_normal(normal: &Vector3<f64>) -> f64 {
    let nz = (normal.z / normal.norm()).abs().min(1.0);
    nz.asin()
}

/// `driven-hoop`: coordinate α; the hoop stands vertical and turns at constant `ω` about lab z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenHoop {
    /// Shared hoop parameters.
    pub hoop: HoopParams,
    /// Drive rate `ω` (rad/s).
    pub omega: f64,
}

impl DrivenHoop {
    /// Validated scene.
    ///
    /// # Errors
    /// As [`HoopParams::new`]; `omega` must be finite.
    pub fn new(hoop: HoopParams, omega: f64) -> Result<Self, ModelError> {
        Ok(DrivenHoop {
            hoop,
            omega: finite("omega", omega)?,
        })
    }

    /// The Jacobi integral per unit `m a²`: `½α̇² − ½ω² sin²α − (g/a) cos α`.
    #[must_use]
    pub fn jacobi_integral(&self, alpha: f64, alpha_dot: f64) -> f64 {
        let s = alpha.sin();
        0.5 * alpha_dot * alpha_dot
            - 0.5 * self.omega * self.omega * s * s
            - self.hoop.gravity / self.hoop.radius * alpha.cos()
    }

    /// The energy function `h = p·q̇ − L` of the Lagrangian (`L` with the hoop's drive, so
    /// `h` is the Jacobi integral in joules): `h = m a² J − ½ (M a²/2) ω²`, `J` the
    /// [`Self::jacobi_integral`] per unit `m a²` (the hoop's drive energy enters `L` as the
    /// constant `½ (M a²/2) ω²`, which is not multiplied by a velocity).
    #[must_use]
    pub fn energy(&self, alpha: f64, alpha_dot: f64) -> f64 {
        let p = &self.hoop;
        p.bead_mass * p.radius * p.radius * self.jacobi_integral(alpha, alpha_dot)
            - 0.5 * p.diameter_moment() * self.omega * self.omega
    }

    /// The magnitude of [`Self::energy`]: its kinetic term plus the amplitudes of its
    /// potential terms, `m a² (½α̇² + ½ω² + g/a) + ½ (M a²/2) ω²` (the energy scale of
    /// [`crate::scene::run_vector`]: `E` carries the round-off of `cos α` times `m g a`
    /// whatever `cos α` is).
    #[must_use]
    pub fn energy_magnitude(&self, alpha_dot: f64) -> f64 {
        let p = &self.hoop;
        let w2 = self.omega * self.omega;
        p.bead_mass * p.radius * p.radius * (0.5 * alpha_dot * alpha_dot + 0.5 * w2)
            + p.bead_mass * p.gravity * p.radius
            + 0.5 * p.diameter_moment() * w2
    }

    /// The off-axis equilibrium `α* = acos(g/(aω²))`, when `ω² > g/a`.
    #[must_use]
    pub fn off_axis_equilibrium(&self) -> Option<f64> {
        let ratio = self.hoop.gravity / (self.hoop.radius * self.omega * self.omega);
        (ratio < 1.0).then(|| ratio.acos())
    }
}

impl Lagrangian<1> for DrivenHoop {
    fn lagrangian<D: RealField + Copy>(&self, t: D, q: &SVector<D, 1>, qd: &SVector<D, 1>) -> D {
        let w: D = c(self.omega);
        let angles = Vector3::new(w * t, c(FRAC_PI_2), D::zero());
        let rates = Vector3::new(w, D::zero(), D::zero());
        hoop_lagrangian(&self.hoop, &angles, &rates, q[0], qd[0])
    }
}

/// Hand-written right-hand side of `driven-hoop`, state `(α, α̇)`:
/// `α̈ = (ω² cos α − g/a) sin α`.
impl Ode<SVector<f64, 2>> for DrivenHoop {
    fn rhs(&self, _t: f64, y: &SVector<f64, 2>, dy: &mut SVector<f64, 2>) {
        let (s, co) = y[0].sin_cos();
        dy[0] = y[1];
        dy[1] = (self.omega * self.omega * co - self.hoop.gravity / self.hoop.radius) * s;
    }
}

/// `driven-hoop` as a separable Hamiltonian per unit `m a²`, state `(α, p)` with `p = α̇` — the
/// same numbers as the state of the right-hand side:
/// `H = ½p² − ½ω² sin²α − (g/a) cos α`, the Jacobi integral ([`DrivenHoop::jacobi_integral`]).
/// Per unit `m a²` the bead's mass drops out, so a massless bead (`m = 0`) is no exception.
impl SeparableHamiltonian for DrivenHoop {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        0.5 * p[0] * p[0]
    }
    fn potential(&self, q: &[f64]) -> f64 {
        let (s, co) = q[0].sin_cos();
        -0.5 * self.omega * self.omega * s * s - self.hoop.gravity / self.hoop.radius * co
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
    }
    /// `∂V/∂α = −(ω² cos α − g/a) sin α`.
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        let (s, co) = q[0].sin_cos();
        out[0] = -(self.omega * self.omega * co - self.hoop.gravity / self.hoop.radius) * s;
    }
}

/// `spinning-hoop`: coordinates (φ, α); the vertical hoop turns freely about lab z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinningHoop {
    /// Shared hoop parameters.
    pub hoop: HoopParams,
}

impl SpinningHoop {
    /// The moment of hoop and bead about the vertical axis, `Ma²/2 + m a² sin²α`.
    #[must_use]
    pub fn axial_moment(&self, alpha: f64) -> f64 {
        let s = alpha.sin();
        self.hoop.diameter_moment()
            + self.hoop.bead_mass * self.hoop.radius * self.hoop.radius * s * s
    }

    /// `L_z = (Ma²/2 + m a² sin²α) φ̇`.
    #[must_use]
    pub fn angular_momentum_z(&self, alpha: f64, phi_dot: f64) -> f64 {
        self.axial_moment(alpha) * phi_dot
    }

    /// The magnitude of [`Self::energy`]: the kinetic energy plus the potential's amplitude,
    /// `½ I_z(α) φ̇² + ½ m a² α̇² + m g a` (the energy scale of
    /// [`crate::scene::run_vector`]).
    #[must_use]
    pub fn energy_magnitude(&self, alpha: f64, phi_dot: f64, alpha_dot: f64) -> f64 {
        let p = &self.hoop;
        0.5 * self.axial_moment(alpha) * phi_dot * phi_dot
            + 0.5 * p.bead_mass * p.radius * p.radius * alpha_dot * alpha_dot
            + p.bead_mass * p.gravity * p.radius
    }

    /// Energy `½ I_z(α) φ̇² + ½ m a² α̇² − m g a cos α`.
    #[must_use]
    pub fn energy(&self, alpha: f64, phi_dot: f64, alpha_dot: f64) -> f64 {
        let p = &self.hoop;
        0.5 * self.axial_moment(alpha) * phi_dot * phi_dot
            + 0.5 * p.bead_mass * p.radius * p.radius * alpha_dot * alpha_dot
            - p.bead_mass * p.gravity * p.radius * alpha.cos()
    }
}

impl Lagrangian<2> for SpinningHoop {
    fn lagrangian<D: RealField + Copy>(&self, _t: D, q: &SVector<D, 2>, qd: &SVector<D, 2>) -> D {
        let angles = Vector3::new(q[0], c(FRAC_PI_2), D::zero());
        let rates = Vector3::new(qd[0], D::zero(), D::zero());
        hoop_lagrangian(&self.hoop, &angles, &rates, q[1], qd[1])
    }
}

/// Hand-written right-hand side of `spinning-hoop`, state `(φ, α, φ̇, α̇)`:
/// `φ̈ = −2 m a² sin α cos α α̇ φ̇ / (Ma²/2 + m a² sin²α)`, `α̈ = sin α cos α φ̇² − (g/a) sin α`.
impl Ode<SVector<f64, 4>> for SpinningHoop {
    fn rhs(&self, _t: f64, y: &SVector<f64, 4>, dy: &mut SVector<f64, 4>) {
        let p = &self.hoop;
        let (s, co) = y[1].sin_cos();
        let (phi_dot, alpha_dot) = (y[2], y[3]);
        let ma2 = p.bead_mass * p.radius * p.radius;
        dy[0] = phi_dot;
        dy[1] = alpha_dot;
        dy[2] = -2.0 * ma2 * s * co * alpha_dot * phi_dot / (p.diameter_moment() + ma2 * s * s);
        dy[3] = s * co * phi_dot * phi_dot - p.gravity / p.radius * s;
    }
}

/// `spinning-hoop` as a separable Hamiltonian: the Routh reduction of the cyclic angle φ, with
/// φ carried along.
///
/// The Hamiltonian of the spinning hoop is
/// `H = p_α²/(2 m a²) + p_φ²/(2 I(α)) − m g a cos α`, `I(α) = Ma²/2 + m a² sin²α`.
/// φ is cyclic, so `p_φ = L_z = I(α) φ̇` is conserved and, for each value of it, `α` moves under
/// Routh's reduced Hamiltonian `H_red(α, p_α) = p_α²/(2 m a²) + p_φ²/(2 I(α)) − m g a cos α`,
/// separable with the centrifugal term `p_φ²/(2 I(α))` in the potential; φ follows from
/// `φ̇ = p_φ / I(α)` (Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §8.3;
/// Marsden & Ratiu, *Introduction to Mechanics and Symmetry*, 2nd ed., §8.9).
///
/// Rather than integrate `H_red` and reconstruct φ by quadrature, the model keeps the whole
/// phase space and exchanges the cyclic pair by the canonical map `(φ, p_φ) ↦ (p_φ, −φ)`: with
/// positions `q = (α, L_z)` and momenta `p = (α̇, −φ)`, `H = T(p) + W(q)` is separable, with
/// `T = ½ m a² α̇²` and `W(α, L_z) = L_z²/(2 I(α)) − m g a cos α`. The drift moves only `α`
/// (`α += h α̇`, `L_z` has no conjugate velocity in `T`), the kick is exact (`α̇ −= h ∂W/∂α`,
/// `φ += h L_z / I(α)` with `α` and `L_z` fixed), so Störmer–Verlet, symplectic Euler, Strang
/// splitting and their compositions are symplectic on the whole phase space, and `L_z` — a
/// position that no step changes — is conserved exactly.
///
/// State `(α, L_z, α̇, −φ)`. The bead's pair is stored per unit `m a²` (`α̇ = p_α/(m a²)`): its
/// components of [`SeparableHamiltonian::kinetic_gradient`] and
/// [`SeparableHamiltonian::potential_gradient`] are those of `H/(m a²)`,
/// `α̇` and `−(L_z/I)² sin α cos α + (g/a) sin α`, finite for a massless bead (`m = 0`, where
/// `p_α` would vanish); the `(L_z, −φ)` components are those of `H`. This is Störmer–Verlet of
/// `H` in the canonical variables with `p_α` scaled by the constant `1/(m a²)`, step for step,
/// for every `m > 0`, and its limit at `m = 0`. [`SeparableHamiltonian::kinetic`] and
/// [`SeparableHamiltonian::potential`] are `T` and `W`, so that `energy` is `H`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinningHoopHamiltonian {
    /// Shared hoop parameters.
    pub hoop: HoopParams,
}

impl SpinningHoopHamiltonian {
    /// The state `(α, L_z, α̇, −φ)` of the scene's `(φ, α, φ̇, α̇)`.
    #[must_use]
    pub fn from_rates(&self, y: &SVector<f64, 4>) -> SVector<f64, 4> {
        let l_z = SpinningHoop { hoop: self.hoop }.angular_momentum_z(y[1], y[2]);
        SVector::<f64, 4>::new(y[1], l_z, y[3], -y[0])
    }

    /// The scene's `(φ, α, φ̇, α̇)` of the state `(α, L_z, α̇, −φ)`, with `φ̇ = L_z / I(α)`.
    #[must_use]
    pub fn to_rates(&self, y: &SVector<f64, 4>) -> SVector<f64, 4> {
        let phi_dot = y[1] / SpinningHoop { hoop: self.hoop }.axial_moment(y[0]);
        SVector::<f64, 4>::new(-y[3], y[0], phi_dot, y[2])
    }
}

impl SeparableHamiltonian for SpinningHoopHamiltonian {
    fn dof(&self) -> usize {
        2
    }
    /// `T = ½ m a² α̇²`.
    fn kinetic(&self, p: &[f64]) -> f64 {
        let h = &self.hoop;
        0.5 * h.bead_mass * h.radius * h.radius * p[0] * p[0]
    }
    /// `W = L_z²/(2 I(α)) − m g a cos α`.
    fn potential(&self, q: &[f64]) -> f64 {
        let h = &self.hoop;
        let i = SpinningHoop { hoop: *h }.axial_moment(q[0]);
        0.5 * q[1] * q[1] / i - h.bead_mass * h.gravity * h.radius * q[0].cos()
    }
    /// `(α̇, 0)`: `L_z` has no conjugate velocity.
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
        out[1] = 0.0;
    }
    /// `(−(L_z/I)² sin α cos α + (g/a) sin α, L_z/I(α))`.
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        let h = &self.hoop;
        let (s, co) = q[0].sin_cos();
        let i = h.diameter_moment() + h.bead_mass * h.radius * h.radius * s * s;
        let phi_dot = q[1] / i;
        out[0] = -phi_dot * phi_dot * s * co + h.gravity / h.radius * s;
        out[1] = phi_dot;
    }
}

/// The free hoop in Euler angles, coordinates (φ, θ, ψ, α): the AD twin of the SO(3) model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHoopEuler {
    /// Shared hoop parameters.
    pub hoop: HoopParams,
}

impl Lagrangian<4> for FreeHoopEuler {
    fn lagrangian<D: RealField + Copy>(&self, _t: D, q: &SVector<D, 4>, qd: &SVector<D, 4>) -> D {
        let angles = Vector3::new(q[0], q[1], q[2]);
        let rates = Vector3::new(qd[0], qd[1], qd[2]);
        hoop_lagrangian(&self.hoop, &angles, &rates, q[3], qd[3])
    }
}

impl FreeHoopEuler {
    /// A terminal event at the edge of the Euler-angle chart, `sin θ = 0` (hoop horizontal),
    /// where the mass matrix is singular: integrators locate it to the interpolant's accuracy
    /// and stop there instead of stepping across it.
    #[must_use]
    pub fn chart_edge_event() -> Event<'static, SVector<f64, 8>> {
        Event::new(
            |_t, y: &SVector<f64, 8>| y[1].sin(),
            Direction::Either,
            Action::Terminate,
        )
    }

    /// The hoop's normal in the lab, `R e_z = (sin θ cos φ, sin θ sin φ, cos θ)`.
    #[must_use]
    pub fn normal(q: &SVector<f64, 4>) -> Vector3<f64> {
        let (st, ct) = q[1].sin_cos();
        Vector3::new(st * q[0].cos(), st * q[0].sin(), ct)
    }

    /// The lab-frame angular momentum about the pivot (space components).
    #[must_use]
    pub fn angular_momentum(&self, q: &SVector<f64, 4>, qd: &SVector<f64, 4>) -> Vector3<f64> {
        hoop_angular_momentum(
            &self.hoop,
            &Vector3::new(q[0], q[1], q[2]),
            &Vector3::new(qd[0], qd[1], qd[2]),
            q[3],
            qd[3],
        )
    }
}
