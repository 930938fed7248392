//! The free hoop's Euler–Poisson reduction: the motion of [`super::free_hoop`] with only what
//! its tilt, its bead and its energy depend on — 8 numbers instead of 14.
//!
//! # Model
//!
//! Gravity acts on the hoop through the lab vertical seen from the body, `Γ = Rᵀ e_z` (the
//! Poisson vector of the heavy top: Leimanis, *The General Problem of the Motion of Coupled
//! Rigid Bodies about a Fixed Point*, 1965, §1; Marsden & Ratiu, *Introduction to Mechanics
//! and Symmetry*, §15.8), and the full model's right-hand side reads `R` only through it: the
//! moment of gravity `m g a (Γ × e)` and `∂V/∂α = m g a Γ·e'`, with `e = (cos α, sin α, 0)`
//! ([`super::free_hoop::FreeHoop::potential_derivatives`]). Since `Ṙ = R hat ω`,
//! `Γ̇ = Γ × ω`, and the state `(Γ, Π, α, p_α) ∈ ℝ⁸` closes:
//!
//! * `Γ̇ = Γ × ω`, `Π̇ = Π × ω + m g a (Γ × e)`,
//! * `α̇` and `ω` from `(Π, p_α)` in closed form: the kinetic matrix
//!   `J = diag(Ma²/2, Ma²/2, Ma²) + μ (𝟙 − e eᵀ)`, `B = (0, 0, μ)`, `M = μ` (`μ = m a²`) has an
//!   `xy` block of determinant `jd (jd + μ)` (`jd = Ma²/2`) and a `z` block giving
//!   `ω_z = (Π_z − p_α)/(Ma²)`, `α̇ = p_α/μ − ω_z`;
//! * `ṗ_α = μ (sin α cos α (ω_x² − ω_y²) − cos 2α ω_x ω_y) − m g a Γ·e'`.
//!
//! The rotation about the vertical (the full model's remaining degree of freedom, cyclic:
//! gravity is invariant under it) is not integrated. What the rows need is exact in these
//! variables: `tilt = asin |n_z|` with `n_z = e_zᵀ R e_z = Γ_z`, the energy
//! `½ (ω·Π + α̇ p_α) + m g a Γ·e`, and `L_z = e_zᵀ R Π = Γ·Π`.
//!
//! # Agreement with the full model
//!
//! The map `R ↦ Rᵀ e_z` is linear and carries the full vector field to this one, so a
//! Runge–Kutta method (explicit or implicit) with the same steps gives the same `Γ, Π, α, p_α`
//! on both, and the same dense output: the two agree to round-off at fixed steps of a
//! Gauss–Legendre method (which also keeps `RᵀR = 𝟙` and `|Γ| = 1`, by which the two tilts
//! are normalised, to round-off). With error
//! control the steps differ (the full model's error estimate also weighs the rest of `R`), and
//! the two agree to the tolerance (tests in `tumble-studies`' sweep suite).
//!
//! # The Taylor method
//!
//! The right-hand side is polynomial in `Γ, Π, p_α` and the sines and cosines of `α` and
//! `2α`, so the Taylor coefficients of the solution follow by hand-written recursions
//! ([`TaylorHoop`], on this state or on the full model's): the map's method. At a fixed order
//! and step both models compute the same polynomials for `(Γ, Π, α, p_α)`.

use nalgebra::SVector;
use tumble_integrators::{Ode, ProblemKind};

use super::free_hoop::FreeHoopScene;
use crate::error::SceneError;
use crate::params::Params;
use crate::scene::{
    Recorder, Reduction, RunPlan, RunSummary, TiltLanes, run_taylor_vector, run_vector,
};

pub mod lanes;
mod taylor;
pub use taylor::TaylorHoop;

/// The state `(Γ_x, Γ_y, Γ_z, Π_x, Π_y, Π_z, α, p_α)`.
pub type State = SVector<f64, 8>;

/// The columns of its rows: the free hoop's columns that do not need the full rotation.
pub const COLUMNS: [&str; 10] = [
    "t",
    "alpha",
    "omega_x",
    "omega_y",
    "omega_z",
    "alpha_dot",
    "energy",
    "energy_rel_err",
    "Lz",
    "tilt",
];

/// Column of the energy in a row (the relative error follows it).
const ENERGY_COLUMN: usize = 6;

/// The free hoop's Euler–Poisson equations on `ℝ⁸`, with its constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerPoissonHoop {
    /// `Ma²/2`, the hoop's moment about a diameter.
    jd: f64,
    /// `Ma²`, about its normal.
    jn: f64,
    /// `m a²`.
    mu: f64,
    /// `m g a`.
    k: f64,
    /// `1 / (jd (jd + μ))`, the inverse determinant of the kinetic matrix's `xy` block.
    inv_det: f64,
}

impl EulerPoissonHoop {
    /// The reduction of `model`.
    #[must_use]
    pub fn new(model: &super::free_hoop::FreeHoop) -> Self {
        let p = &model.hoop;
        let (jd, jn) = (p.diameter_moment(), p.normal_moment());
        let mu = p.bead_mass * p.radius * p.radius;
        EulerPoissonHoop {
            jd,
            jn,
            mu,
            k: p.bead_mass * p.gravity * p.radius,
            inv_det: 1.0 / (jd * (jd + mu)),
        }
    }

    /// The reduced state of a full one: `Γ` is the third row of `R`.
    #[must_use]
    pub fn reduce(state: &tumble_integrators::rigid::CoupledState<1>) -> State {
        let r = &state.rotation;
        let pi = &state.momentum;
        State::from([
            r[(2, 0)],
            r[(2, 1)],
            r[(2, 2)],
            pi.x,
            pi.y,
            pi.z,
            state.q[0],
            state.p[0],
        ])
    }

    /// `(ω, α̇)` at `y`, with `(sin α, cos α)`.
    #[inline]
    fn velocities(&self, y: &State, s: f64, c: f64) -> ([f64; 3], f64) {
        let (jd, mu) = (self.jd, self.mu);
        let mcs = mu * c * s;
        let wx = self.inv_det * ((jd + mu * c * c) * y[3] + mcs * y[4]);
        let wy = self.inv_det * (mcs * y[3] + (jd + mu * s * s) * y[4]);
        let wz = (y[5] - y[7]) / self.jn;
        let adot = y[7] / mu - wz;
        ([wx, wy, wz], adot)
    }

    /// The energy `T + V` at `y` and its magnitude `|T| + |m g a|` (the scale of its relative
    /// error), with `(sin α, cos α)`.
    #[inline]
    fn energy_at(&self, y: &State, s: f64, c: f64) -> (f64, f64, f64) {
        let (w, adot) = self.velocities(y, s, c);
        let kinetic = 0.5 * (w[0] * y[3] + w[1] * y[4] + w[2] * y[5] + adot * y[7]);
        let potential = self.k * (y[0] * c + y[1] * s);
        (kinetic + potential, kinetic.abs() + self.k.abs(), adot)
    }

    /// The energy `T + V` at `y` and its magnitude `|T| + |m g a|`, as the rows hold them.
    #[must_use]
    pub fn energy(&self, y: &State) -> (f64, f64) {
        let (s, c) = y[6].sin_cos();
        let (e, magnitude, _) = self.energy_at(y, s, c);
        (e, magnitude)
    }

    /// The tilt of the hoop's normal from the horizontal plane, `asin |Γ_z| / |Γ|`, from the
    /// three components of `Γ` (the rows' `tilt`).
    #[must_use]
    #[inline]
    pub fn tilt(gx: f64, gy: f64, gz: f64) -> f64 {
        let gamma = (gx * gx + gy * gy + gz * gz).sqrt();
        (gz / gamma).abs().min(1.0).asin()
    }

    /// Writes the row of `(t, y)` in [`COLUMNS`] order; the relative energy error's slot gets
    /// the energy's magnitude, `T` plus the potential's amplitude `m g a`, as the full model's
    /// rows do (the energy scale of [`crate::scene::run_vector`]).
    pub fn row(&self, t: f64, y: &State, out: &mut [f64]) {
        let (s, c) = y[6].sin_cos();
        let (w, _) = self.velocities(y, s, c);
        let (energy, magnitude, adot) = self.energy_at(y, s, c);
        let values = [
            t,
            y[6],
            w[0],
            w[1],
            w[2],
            adot,
            energy,
            magnitude,
            y[0] * y[3] + y[1] * y[4] + y[2] * y[5],
            Self::tilt(y[0], y[1], y[2]),
        ];
        out.copy_from_slice(&values);
    }
}

impl Ode<State> for EulerPoissonHoop {
    #[inline]
    fn rhs(&self, _t: f64, y: &State, dy: &mut State) {
        let (s, c) = y[6].sin_cos();
        let ([wx, wy, wz], adot) = self.velocities(y, s, c);
        let (gx, gy, gz) = (y[0], y[1], y[2]);
        let (px, py, pz) = (y[3], y[4], y[5]);
        // Γ × ω
        dy[0] = gy * wz - gz * wy;
        dy[1] = gz * wx - gx * wz;
        dy[2] = gx * wy - gy * wx;
        // Π × ω + k Γ × e, e = (c, s, 0)
        dy[3] = py * wz - pz * wy - self.k * gz * s;
        dy[4] = pz * wx - px * wz + self.k * gz * c;
        dy[5] = px * wy - py * wx + self.k * (gx * s - gy * c);
        dy[6] = adot;
        // ½ ωᵀ ∂J/∂α ω − ∂V/∂α, ∂V/∂α = k Γ·(−s, c, 0)
        dy[7] = self.mu * (s * c * (wx * wx - wy * wy) - (c * c - s * s) * wx * wy)
            - self.k * (gy * c - gx * s);
    }
}

/// Runs the reduction of `free-hoop` at `params` with `plan` (a plan of the scene's, of kind
/// [`tumble_integrators::ProblemKind::Ode`]): rows of [`COLUMNS`].
///
/// # Errors
/// Invalid parameters; an integration failure.
pub fn simulate(
    params: &Params,
    plan: &RunPlan,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError> {
    let (model, s0) = FreeHoopScene::model(params)?;
    let reduced = EulerPoissonHoop::new(&model);
    if plan.kind == ProblemKind::TaylorSeries {
        return run_taylor_vector(
            &TaylorHoop::reduced(reduced),
            EulerPoissonHoop::reduce(&s0),
            plan,
            COLUMNS.len(),
            ENERGY_COLUMN,
            |t, y, out| reduced.row(t, y, out),
            &mut [],
            recorder,
        );
    }
    run_vector(
        &reduced,
        EulerPoissonHoop::reduce(&s0),
        plan,
        COLUMNS.len(),
        ENERGY_COLUMN,
        |t, y, out| reduced.row(t, y, out),
        &mut [],
        recorder,
    )
}

/// The reduction of `free-hoop`, as [`crate::scene::Scene::reduction`] offers it.
pub static EULER_POISSON: Reduction = Reduction {
    name: "euler-poisson",
    summary: "free-hoop reduced to the lab vertical in the body frame, its angular momentum and \
              the bead (Γ = Rᵀe_z, Π, α, p_α: 8 numbers instead of R, Π, α, p_α: 14)",
    columns: &COLUMNS,
    simulate,
    lanes: Some(TiltLanes {
        width: lanes::LANES,
        runs: lanes::runs,
        run: lanes::tilt_runs,
    }),
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::scenes::free_hoop::{FREE_HOOP, FlatFreeHoop, flatten, unflatten};
    use nalgebra::SVector;

    /// A state of the full model away from the start (a short run of its own equations).
    fn full_state(params: &Params) -> (super::super::free_hoop::FreeHoop, SVector<f64, 14>) {
        let (model, s0) = FreeHoopScene::model(params).unwrap();
        let flat = FlatFreeHoop::new(model).unwrap();
        let mut y = flatten(&s0);
        let h = 1e-3;
        let mut k = [SVector::<f64, 14>::zeros(); 4];
        for _ in 0..700 {
            flat.rhs(0.0, &y, &mut k[0]);
            flat.rhs(0.0, &(y + k[0] * (h / 2.0)), &mut k[1]);
            flat.rhs(0.0, &(y + k[1] * (h / 2.0)), &mut k[2]);
            flat.rhs(0.0, &(y + k[2] * h), &mut k[3]);
            y += (k[0] + k[1] * 2.0 + k[2] * 2.0 + k[3]) * (h / 6.0);
        }
        // On SO(3) to round-off (the run leaves `RᵀR − 𝟙` at its error), so that the tilt
        // from a column of `R` and from its third row are the same number.
        let mut s = unflatten(&y);
        let r = nalgebra::Rotation3::from_matrix_eps(
            &s.rotation,
            1e-16,
            100,
            nalgebra::Rotation3::identity(),
        );
        s.rotation = *r.matrix();
        (model, flatten(&s))
    }

    fn params(omega0: f64, alpha0: f64, theta0: f64) -> Params {
        let mut p = FREE_HOOP.default_params();
        p.set("omega0", omega0).unwrap();
        p.set("alpha0", alpha0).unwrap();
        p.set("theta0", theta0).unwrap();
        p.set("alpha_dot0", 0.7).unwrap();
        p
    }

    /// The reduced field is the full field carried by `R ↦ Rᵀ e_z` (third row of `Ṙ`, and
    /// `Π̇, α̇, ṗ` as they are), to round-off, at states where the hoop has tilted.
    #[test]
    fn reduced_field_is_the_projection_of_the_full_field() {
        for (w, a, th) in [(4.0, 0.5, 1.5), (0.8, 2.85, 1.2), (7.0, 3.0, 0.3)] {
            let (model, y) = full_state(&params(w, a, th));
            let flat = FlatFreeHoop::new(model).unwrap();
            let mut dfull = SVector::<f64, 14>::zeros();
            flat.rhs(0.0, &y, &mut dfull);
            let reduced = EulerPoissonHoop::new(&model);
            let z = EulerPoissonHoop::reduce(&unflatten(&y));
            let mut dz = State::zeros();
            reduced.rhs(0.0, &z, &mut dz);
            // Ṙ column-major: row 2 of Ṙ is entries 2, 5, 8.
            let expected = [
                dfull[2], dfull[5], dfull[8], dfull[9], dfull[10], dfull[11], dfull[12], dfull[13],
            ];
            for (k, e) in expected.iter().enumerate() {
                assert!(
                    (dz[k] - e).abs() <= 1e-14 * (1.0 + e.abs()),
                    "({w}, {a}, {th}) component {k}: {} vs {e}",
                    dz[k]
                );
            }
        }
    }

    /// Every column of a reduced row equals the full row's column of the same name.
    #[test]
    fn reduced_rows_equal_the_full_rows_columns() {
        let scene = FreeHoopScene;
        let names = scene.info().columns();
        for (w, a, th) in [(4.0, 0.5, 1.5), (0.8, 2.85, 1.2), (7.0, 3.0, 0.3)] {
            let p = params(w, a, th);
            let (model, y) = full_state(&p);
            let mut full = vec![0.0; names.len()];
            super::super::free_hoop::write_row(&model, 0.7, &unflatten(&y), &mut None, &mut full);
            let reduced = EulerPoissonHoop::new(&model);
            let mut row = [0.0; COLUMNS.len()];
            reduced.row(0.7, &EulerPoissonHoop::reduce(&unflatten(&y)), &mut row);
            for (k, name) in COLUMNS.iter().enumerate() {
                if *name == "energy_rel_err" {
                    continue;
                }
                let j = names.iter().position(|n| n == name).unwrap();
                assert!(
                    (row[k] - full[j]).abs() <= 1e-14 * (1.0 + full[j].abs()),
                    "({w}, {a}, {th}) {name}: {} vs {}",
                    row[k],
                    full[j]
                );
            }
        }
    }

    /// The reduced equations conserve what the free hoop conserves, the energy and `L_z`
    /// (`Γ·Π`), to the tolerance of a tight run in which the hoop tilts.
    #[test]
    fn reduced_run_conserves_energy_and_lz() {
        let p = params(3.5, 1.1, 1.4);
        let (model, s0) = FreeHoopScene::model(&p).unwrap();
        let reduced = EulerPoissonHoop::new(&model);
        let mut rows = crate::scene::Rows::default();
        let plan = crate::scene::RunOptions {
            integrator: Some("vern9".into()),
            step: Some(crate::scene::StepControl::Tolerance(1e-13)),
            t_end: Some(10.0),
            ..Default::default()
        }
        .resolve(&FREE_HOOP)
        .unwrap();
        simulate(&p, &plan, &mut rows).unwrap();
        let mut first = [0.0; COLUMNS.len()];
        reduced.row(0.0, &EulerPoissonHoop::reduce(&s0), &mut first);
        let last = rows.0.last().unwrap();
        assert_eq!(last[0], 10.0);
        assert!(((last[6] - first[6]) / first[6]).abs() < 1e-11, "energy");
        assert!(
            (last[8] - first[8]).abs() < 1e-11 * (1.0 + first[8].abs()),
            "Lz"
        );
        // The tilt moved: the run is not trivial.
        assert!(rows.0.iter().any(|r| r[9] > first[9] + 0.1));
    }
}
