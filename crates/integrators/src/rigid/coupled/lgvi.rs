//! The coupled LGVI ([`CoupledLgvi`]) and its compositions `lgvi4` … `lgvi10` on a coupled
//! model ([`super`] module doc, "The variational integrator").

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use tumble_kinematics::so3::hat;

use super::model::{CoupledLagrangian, KineticJet, a_right, coupled_velocities, solve_small};
use crate::composition::Composition;
use crate::error::{Error, check_step};
use crate::rigid::lgvi::MAX_NEWTON_ITERATIONS;
use crate::rigid::state::CoupledState;
use crate::stepper::Stepper;
use crate::tables::composition::{KAHAN_LI6, KAHAN_LI8, MCLACHLAN4, SOFRONIOU_SPALETTA10};

/// `lgvi4` on a coupled model: [`CoupledLgvi`] composed with McLachlan's 5-stage order-4
/// coefficients.
#[must_use]
pub fn coupled_lgvi4<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&MCLACHLAN4, CoupledLgvi::new())
}

/// `lgvi6` on a coupled model: [`CoupledLgvi`] composed with Kahan & Li's 9-stage order-6
/// coefficients.
#[must_use]
pub fn coupled_lgvi6<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&KAHAN_LI6, CoupledLgvi::new())
}

/// `lgvi8` on a coupled model: [`CoupledLgvi`] composed with Kahan & Li's 17-stage order-8
/// coefficients.
#[must_use]
pub fn coupled_lgvi8<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&KAHAN_LI8, CoupledLgvi::new())
}

/// `lgvi10` on a coupled model: [`CoupledLgvi`] composed with Sofroniou & Spaletta's 35-stage
/// order-10 coefficients.
#[must_use]
pub fn coupled_lgvi10<const N: usize>() -> Composition<CoupledLgvi<N>> {
    Composition::new(&SOFRONIOU_SPALETTA10, CoupledLgvi::new())
}

/// The variational integrator of a [`CoupledLagrangian`] (see the module doc): order 2,
/// symplectic, symmetric.
///
/// Implements [`Stepper<L>`] on [`CoupledState<N>`]. The Newton unknowns are `w` and the
/// increment `d = q_{k+1} − q_k` (not `q_{k+1}`: `v = d/h` then carries no cancellation when
/// `q` is large, e.g. an angle that keeps winding up); `q ← q + d` and `R ← R + R G`
/// (`cay(w) = 𝟙 + G`) are summed with Kahan compensation carried between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledLgvi<const N: usize> {
    max_iterations: usize,
    carry: SVector<f64, N>,
    carry_rotation: Matrix3<f64>,
    last: Option<(f64, CoupledState<N>)>,
    /// The moment and `∂V/∂q` at the end of the last step.
    end: Option<(Vector3<f64>, SVector<f64, N>)>,
}

impl<const N: usize> Default for CoupledLgvi<N> {
    fn default() -> Self {
        Self {
            max_iterations: MAX_NEWTON_ITERATIONS,
            carry: SVector::zeros(),
            carry_rotation: Matrix3::zeros(),
            last: None,
            end: None,
        }
    }
}

impl<const N: usize> CoupledLgvi<N> {
    /// A stepper allowing [`MAX_NEWTON_ITERATIONS`] Newton iterations per step.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The same stepper allowing `n` Newton iterations per step before
    /// [`Error::NoConvergence`].
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }
}

/// The known parts of the discrete equations at step `k`.
struct StepData<const N: usize> {
    h: f64,
    q0: SVector<f64, N>,
    /// `Π_k + (h/2) M(R_k, q_k)`.
    pi: Vector3<f64>,
    /// `p_k − (h/2) V_q(R_k, q_k)`.
    p: SVector<f64, N>,
}

/// `T` and its partial derivatives at `ξ = w/h`, `q̄ = q_k + d/2`, `v = d/h`.
struct Partials<const N: usize> {
    xi: Vector3<f64>,
    v: SVector<f64, N>,
    jet: KineticJet<N>,
    t_xi: Vector3<f64>,
    t_v: SVector<f64, N>,
    t_q: SVector<f64, N>,
}

/// The Newton matrix `[A B; C D]` of the residuals `(E_R, E_q)` in `(w, d)`, factored once by
/// block elimination (`A⁻¹` and the inverse of the Schur complement `D − C A⁻¹ B`) and reused
/// by the iterations that follow (simplified Newton).
struct Factored<const N: usize> {
    a_inv: Matrix3<f64>,
    a_inv_b: SMatrix<f64, 3, N>,
    c: SMatrix<f64, N, 3>,
    schur_inv: SMatrix<f64, N, N>,
}

impl<const N: usize> Factored<N> {
    fn new(
        a: &Matrix3<f64>,
        b: &SMatrix<f64, 3, N>,
        c: &SMatrix<f64, N, 3>,
        d: &SMatrix<f64, N, N>,
    ) -> Option<Self> {
        let a_inv = a.try_inverse()?;
        let a_inv_b = a_inv * b;
        let schur = d - c * a_inv_b;
        let mut schur_inv = SMatrix::<f64, N, N>::zeros();
        for j in 0..N {
            let column = solve_small(schur, SVector::<f64, N>::from_fn(|i, _| f64::from(i == j)))?;
            schur_inv.set_column(j, &column);
        }
        Some(Self {
            a_inv,
            a_inv_b,
            c: *c,
            schur_inv,
        })
    }

    /// `(x, y)` with `[A B; C D] (x, y) = (r, s)`.
    fn solve(&self, r: &Vector3<f64>, s: &SVector<f64, N>) -> (Vector3<f64>, SVector<f64, N>) {
        let a_inv_r = self.a_inv * r;
        let y = self.schur_inv * (s - self.c * a_inv_r);
        (a_inv_r - self.a_inv_b * y, y)
    }
}

impl<const N: usize> StepData<N> {
    /// `T`'s partial derivatives `(T_ξ, T_v, T_q)` at `ξ = w/h`, `q̄ = q_k + d/2`, `v = d/h`,
    /// from the model's [`KineticJet`]: what the residuals, their Jacobian and the momenta at
    /// `k + 1` need.
    fn partials<L: CoupledLagrangian<N> + ?Sized>(
        &self,
        model: &L,
        w: &Vector3<f64>,
        d: &SVector<f64, N>,
    ) -> Partials<N> {
        let inv_h = 1.0 / self.h;
        let xi = w * inv_h;
        let v = d * inv_h;
        let jet = model.kinetic_jet(&SVector::from_fn(|i, _| self.q0[i] + 0.5 * d[i]));
        let (t_xi, t_v) = jet.momenta(&xi, &v);
        let t_q = jet.configuration_gradient(&xi, &v);
        Partials {
            xi,
            v,
            jet,
            t_xi,
            t_v,
            t_q,
        }
    }

    /// The residuals `(E_R, E_q)` at `(w, d)` from their partials.
    fn residual(&self, w: &Vector3<f64>, at: &Partials<N>) -> (Vector3<f64>, SVector<f64, N>) {
        (
            self.pi - a_right(w) * at.t_xi,
            self.p + at.t_q * (0.5 * self.h) - at.t_v,
        )
    }

    /// The Newton matrix of the residuals at `(w, d)`, factored, with the model's kinetic
    /// jet and Hessian ([`CoupledLagrangian::kinetic_hessian`]) at `q̄`:
    ///
    /// ```text
    /// ∂E_R/∂w = −(−½ hat T_ξ + ¼ (w·T_ξ) 𝟙 + ¼ w T_ξᵀ) − A_R(w) J/h,
    /// ∂E_R/∂d = −A_R(w) (½ ∂_q T_ξ + B/h),         ∂_{q_j} T_ξ = ∂_j J ξ + ∂_j B v,
    /// ∂E_q/∂w = ½ ∂_ξ T_q − Bᵀ/h,                  (∂_ξ T_q)_{ij} = (∂_i J ξ + ∂_i B v)_j,
    /// ∂E_q/∂d = (h/4) ∂_q T_q + ½ ∂_v T_q − ½ ∂_q T_v − M/h,
    ///           (∂_v T_q)_{ij} = (∂_i Bᵀ ξ + ∂_i M v)_j,
    ///           (∂_q T_q)_{ij} = ½ ξᵀ ∂_{ij}J ξ + ξᵀ ∂_{ij}B v + ½ vᵀ ∂_{ij}M v.
    /// ```
    ///
    /// The term `(h/4) ∂_q T_q` is `O(h²)` against `−M/h`; without it the simplified
    /// iteration contracts only by that factor a step (3e-3 at h = 0.06 on a bead on a hoop),
    /// takes twice the iterations and stops at round-off on a biased side.
    fn jacobian<L: CoupledLagrangian<N> + ?Sized>(
        &self,
        model: &L,
        w: &Vector3<f64>,
        d: &SVector<f64, N>,
        at: &Partials<N>,
    ) -> Option<Factored<N>> {
        let inv_h = 1.0 / self.h;
        let k = &at.jet.blocks;
        let (xi, v, t) = (&at.xi, &at.v, &at.t_xi);
        let a_r = a_right(w);
        let d_ar = hat(t) * (-0.5)
            + Matrix3::from_diagonal_element(0.25 * w.dot(t))
            + w * t.transpose() * 0.25;
        let a = -(d_ar + a_r * k.rotational * inv_h);
        // ∂T_ξ/∂q_j and ∂T_v/∂q_j, column by column.
        let dtxi_dq = SMatrix::<f64, 3, N>::from_fn(|r, j| {
            let dj = &at.jet.derivatives[j];
            (dj.rotational * xi + dj.coupling * v)[r]
        });
        let dtv_dq = SMatrix::<f64, N, N>::from_fn(|r, j| {
            let dj = &at.jet.derivatives[j];
            (dj.coupling.transpose() * xi + dj.internal * v)[r]
        });
        let b = -(a_r * (dtxi_dq * 0.5 + k.coupling * inv_h));
        let c = dtxi_dq.transpose() * 0.5 - k.coupling.transpose() * inv_h;
        let hessian = model.kinetic_hessian(&SVector::from_fn(|i, _| self.q0[i] + 0.5 * d[i]));
        let t_qq = SMatrix::<f64, N, N>::from_fn(|i, j| {
            let e = &hessian[i][j];
            0.5 * xi.dot(&(e.rotational * xi))
                + xi.dot(&(e.coupling * v))
                + 0.5 * v.dot(&(e.internal * v))
        });
        let dd = t_qq * (0.25 * self.h) + (dtv_dq.transpose() - dtv_dq) * 0.5 - k.internal * inv_h;
        Factored::new(&a, &b, &c, &dd)
    }
}

impl<const N: usize, L: CoupledLagrangian<N> + ?Sized> Stepper<L> for CoupledLgvi<N> {
    type State = CoupledState<N>;

    fn step(
        &mut self,
        model: &L,
        t: f64,
        state: &mut CoupledState<N>,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let continues = self
            .last
            .as_ref()
            .is_some_and(|(t1, s1)| crate::state::same_time(*t1, t) && s1 == state);
        if !continues {
            self.carry = SVector::zeros();
            self.carry_rotation = Matrix3::zeros();
        }
        let failure =
            |iterations: usize, increment: f64, state: &CoupledState<N>| Error::NoConvergence {
                t,
                h,
                iterations,
                increment,
                state: crate::state::State::to_vec(state),
            };
        let r0 = state.rotation;
        let q0 = state.q;
        // The moment and ∂V/∂q at the end of the last step are those at the start of this one
        // when it continues (the same configuration, bit for bit).
        let (torque0, grad0) = match self.end {
            Some(end) if continues => end,
            _ => model.potential_derivatives(&r0, &q0),
        };
        let data = StepData {
            h,
            q0,
            pi: state.momentum + torque0 * (0.5 * h),
            p: state.p - grad0 * (0.5 * h),
        };
        // The explicit guess w = hΩ_k, d = h q̇_k, within O(h²) of the solution. (A guess
        // within O(h³), w = h (Ω + (h/2) Ω̇) from the continuous rates, saves half an iteration
        // a step but lets the energy of lgvi6 on the free hoop drift, 6.0e-11 with growth t^0.58
        // over 2²⁰ steps against 7.4e-12 bounded: the solve then stops on a side of the root
        // that depends on the guess, and the map is no longer symmetric to round-off.)
        let (omega, qdot) = coupled_velocities(model, &q0, &state.momentum, &state.p)
            .map_err(|_| failure(0, f64::NAN, state))?;
        let mut w = omega * h;
        let mut d = qdot * h;
        // Each block is measured relative to its own size (w ~ hΩ and d ~ hq̇ may differ by
        // orders of magnitude), with the explicit guess as a floor for components near zero.
        let floor_w = w.amax().max(f64::MIN_POSITIVE);
        let floor_d = d.amax().max(f64::MIN_POSITIVE);
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        // Newton's matrix is formed at the first iterate and again only when an iteration
        // fails to shrink the increment fourfold (simplified Newton: the explicit guess is
        // within O(h²) of the solution, so the reused matrix contracts fast). Every iteration
        // evaluates the model's kinetic jet once, at the current iterate; the matrix is built
        // from the same jet.
        let mut at = data.partials(model, &w, &d);
        let mut jacobian: Option<Factored<N>> = None;
        while iterations < self.max_iterations {
            iterations += 1;
            let fresh = jacobian.is_none();
            let matrix = match jacobian.take() {
                Some(m) => m,
                None => data
                    .jacobian(model, &w, &d, &at)
                    .ok_or_else(|| Error::SingularMatrix {
                        t,
                        h,
                        state: crate::state::State::to_vec(state),
                    })?,
            };
            let (er, eq) = data.residual(&w, &at);
            let (dw, dd) = matrix.solve(&(-er), &(-eq));
            jacobian = Some(matrix);
            let size = (dw.amax() / w.amax().max(floor_w)).max(dd.amax() / d.amax().max(floor_d));
            if !size.is_finite() {
                return Err(failure(iterations, size, state));
            }
            if size >= previous {
                converged = previous <= 1e-8;
                if !fresh && !converged {
                    // A reused matrix that no longer contracts far from the root (a large
                    // step): form it at the current iterate and take a Newton step from there.
                    jacobian = None;
                    continue;
                }
                // Stagnation: the previous iterate was as good as round-off allows (`at` is
                // still its jet).
                break;
            }
            w += dw;
            d += dd;
            at = data.partials(model, &w, &d);
            // (A stop on the contraction estimate θ/(1 − θ) |δ| below round-off, as the rigid
            // LGVI has, saves an iteration here but lets e · R Π wander 15 times further over
            // 10⁵ steps: the simplified iteration runs to round-off.)
            if size <= 4.0 * f64::EPSILON {
                converged = true;
                break;
            }
            if size > 0.25 * previous {
                jacobian = None;
            }
            previous = size;
        }
        if !converged {
            return Err(failure(iterations, previous, state));
        }
        // q₁ = q₀ + d with Kahan compensation.
        let mut q1 = q0;
        for i in 0..N {
            crate::state::compensated_add(&mut q1[i], d[i], &mut self.carry[i]);
        }
        // R₁ = R₀ cay(w) = R₀ + R₀ G with G = 4 (hat w + ½ hat w²)/(4 + |w|²): applied as a
        // compensated increment so that its rounding does not repeat identically from step to
        // step.
        let wh = hat(&w);
        let g = (wh + wh * wh * 0.5) * (4.0 / (4.0 + w.norm_squared()));
        let mut r1 = r0;
        crate::rigid::state::compensated_add_all(&mut r1, &(r0 * g), &mut self.carry_rotation);
        // Momenta at k + 1: T's partial derivatives at the solution.
        let (torque1, grad1) = model.potential_derivatives(&r1, &q1);
        state.momentum = a_right(&w).transpose() * at.t_xi + torque1 * (0.5 * h);
        state.p = at.t_v + at.t_q * (0.5 * h) - grad1 * (0.5 * h);
        self.end = Some((torque1, grad1));
        state.rotation = r1;
        state.q = q1;
        self.last = Some((t + h, *state));
        Ok(())
    }

    fn reset(&mut self) {
        *self = Self {
            max_iterations: self.max_iterations,
            ..Self::default()
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigid::coupled::{KineticBlocks, Scalar};

    /// A bead on a tilted hoop with a spring along it: `J`, `B` and `M` all depend on `q`.
    struct Bead;

    impl CoupledLagrangian<1> for Bead {
        fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
            let (s, c) = (q[0].sin(), q[0].cos());
            let a = D::from(0.7) + D::from(0.2) * s;
            let r = Vector3::new(a * c, a * s, D::from(0.3) * c);
            let dr = Vector3::new(-(a * s), a * c, -(D::from(0.3) * s))
                + Vector3::new(c, s, D::from(0.0)) * (D::from(0.2) * c);
            let m = D::from(0.4);
            let body =
                Matrix3::from_diagonal(&Vector3::new(D::from(1.0), D::from(1.5), D::from(2.0)));
            KineticBlocks {
                rotational: body + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m,
                coupling: SMatrix::<D, 3, 1>::from_column_slice((r.cross(&dr) * m).as_slice()),
                internal: SMatrix::<D, 1, 1>::new(m * dr.norm_squared()),
            }
        }

        fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
            let r = Vector3::new(q[0].cos(), q[0].sin(), D::from(0.3));
            (rotation * r).z * D::from(3.0) + q[0] * q[0] * D::from(0.5)
        }
    }

    #[test]
    fn newton_matrix_matches_central_differences_of_the_residuals() {
        // The matrix solved by the simplified Newton iteration against central differences of
        // the residuals (E_R, E_q) in (w, d): equal to the differences' accuracy.
        let h = 0.05;
        let q0 = SVector::<f64, 1>::new(0.4);
        let data = StepData {
            h,
            q0,
            pi: Vector3::new(0.3, -0.2, 0.9),
            p: SVector::<f64, 1>::new(0.25),
        };
        let w = Vector3::new(0.02, -0.03, 0.05);
        let d = SVector::<f64, 1>::new(0.015);
        let at = data.partials(&Bead, &w, &d);
        let f = data.jacobian(&Bead, &w, &d, &at).unwrap();
        // Rebuild the matrix from its factors' action on unit vectors.
        let mut x = nalgebra::SMatrix::<f64, 4, 4>::zeros();
        for j in 0..4 {
            let (r, s) = (
                Vector3::from_fn(|i, _| f64::from(i == j)),
                SVector::<f64, 1>::new(f64::from(j == 3)),
            );
            let (a, b) = f.solve(&r, &s);
            x.set_column(j, &nalgebra::Vector4::new(a[0], a[1], a[2], b[0]));
        }
        let matrix = x.try_inverse().unwrap();
        let residual = |w: &Vector3<f64>, d: &SVector<f64, 1>| {
            let (r, s) = data.residual(w, &data.partials(&Bead, w, d));
            nalgebra::Vector4::new(r[0], r[1], r[2], s[0])
        };
        let eps = 1e-6;
        for j in 0..4 {
            let mut wp = w;
            let mut dp = d;
            let mut wm = w;
            let mut dm = d;
            if j < 3 {
                wp[j] += eps;
                wm[j] -= eps;
            } else {
                dp[0] += eps;
                dm[0] -= eps;
            }
            let column = (residual(&wp, &dp) - residual(&wm, &dm)) / (2.0 * eps);
            for i in 0..4 {
                let scale = 1.0 / h;
                let diff = (matrix[(i, j)] - column[i]).abs();
                assert!(
                    diff < 1e-7 * scale,
                    "({i}, {j}): {} vs {}",
                    matrix[(i, j)],
                    column[i]
                );
            }
        }
    }
}
