//! One step of the Lie–Gauss methods as equations and their solution: what a step asks of a
//! model at a stage ([`StageModel`]), the rates of the chart's canonical equations, and the
//! simplified Newton solve of the stages and the initial chart momentum together ([`solve`];
//! the linear algebra is [`super::newton`]). The construction is in the [`super`] module doc.

use nalgebra::{Matrix3, SVector, Vector3};

use tumble_kinematics::so3::{
    ExpCoefficients, hat, right_jacobian_derivative, right_jacobian_derivative_transpose,
};

use super::newton::{Newton, Responses, same_step};
use crate::rigid::coupled::{CoupledLagrangian, velocities_of};
use crate::rigid::problem::RigidBody;
use crate::tables::GaussTableau;

/// What a step needs of a model at a stage.
pub(super) trait StageModel<const N: usize> {
    /// `(Ω, q̇, ∂T/∂q)` at `q` for momenta `(Π, p)`; `None` if the kinetic energy is singular.
    fn velocities(
        &self,
        q: &SVector<f64, N>,
        momentum: &Vector3<f64>,
        p: &SVector<f64, N>,
    ) -> Option<(Vector3<f64>, SVector<f64, N>, SVector<f64, N>)>;

    /// The body-frame moment `M(R, q)` and `∂V/∂q`.
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>);

    /// `true` when `V` is constant.
    fn force_free(&self) -> bool;
}

pub(super) struct OnBody<'a, B: ?Sized>(pub(super) &'a B);

impl<B: RigidBody + ?Sized> StageModel<0> for OnBody<'_, B> {
    fn velocities(
        &self,
        _q: &SVector<f64, 0>,
        momentum: &Vector3<f64>,
        _p: &SVector<f64, 0>,
    ) -> Option<(Vector3<f64>, SVector<f64, 0>, SVector<f64, 0>)> {
        Some((
            self.0.body().omega(momentum),
            SVector::zeros(),
            SVector::zeros(),
        ))
    }
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        _q: &SVector<f64, 0>,
    ) -> (Vector3<f64>, SVector<f64, 0>) {
        (self.0.torque(rotation), SVector::zeros())
    }
    fn force_free(&self) -> bool {
        self.0.is_torque_free()
    }
}

pub(super) struct OnCoupled<'a, L: ?Sized>(pub(super) &'a L);

impl<L: CoupledLagrangian<N> + ?Sized, const N: usize> StageModel<N> for OnCoupled<'_, L> {
    fn velocities(
        &self,
        q: &SVector<f64, N>,
        momentum: &Vector3<f64>,
        p: &SVector<f64, N>,
    ) -> Option<(Vector3<f64>, SVector<f64, N>, SVector<f64, N>)> {
        let jet = self.0.kinetic_jet(q);
        let (omega, qdot) = velocities_of(&jet.blocks, q, momentum, p).ok()?;
        let tq = jet.configuration_gradient(&omega, &qdot);
        Some((omega, qdot, tq))
    }
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        self.0.potential_derivatives(rotation, q)
    }
    fn force_free(&self) -> bool {
        false
    }
}

/// The rates of the chart's canonical equations at a stage: `(u̇, q̇, Ṗ, ṗ)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rates<const N: usize> {
    pub(super) u: Vector3<f64>,
    pub(super) q: SVector<f64, N>,
    pub(super) pu: Vector3<f64>,
    pub(super) p: SVector<f64, N>,
}

/// The rates at a stage `(u, q, P, p)` of a step from `R_k = r0`, and the stage's moment rotated
/// into the frame of `R_k` (`E M`).
pub(super) fn rates<M: StageModel<N>, const N: usize>(
    model: &M,
    r0: &Matrix3<f64>,
    u: &Vector3<f64>,
    q: &SVector<f64, N>,
    pu: &Vector3<f64>,
    p: &SVector<f64, N>,
) -> Option<(Rates<N>, Vector3<f64>)> {
    let co = ExpCoefficients::new(u.norm_squared());
    let uh = hat(u);
    let uh2 = uh * uh;
    let jr = Matrix3::identity() - uh * co.a + uh2 * co.b;
    let jr_inv = Matrix3::identity() + uh * 0.5 + uh2 * co.inv;
    let pi = jr_inv.transpose() * pu;
    let (omega, qdot, tq) = model.velocities(q, &pi, p)?;
    let w = jr_inv * omega;
    let mut dpu = right_jacobian_derivative_transpose(&co, u, &w, &pi);
    let mut dp = tq;
    let mut moment = Vector3::zeros();
    if !model.force_free() {
        let e = Matrix3::identity() + uh * co.sinc + uh2 * co.a;
        let (m, vq) = model.forces(&(r0 * e), q);
        dpu += jr.transpose() * m;
        dp -= vq;
        moment = e * m;
    }
    Some((
        Rates {
            u: w,
            q: qdot,
            pu: dpu,
            p: dp,
        },
        moment,
    ))
}

/// The result of a step: `E₁ − 𝟙`, `Π_{k+1} − Π_k`, `q_{k+1} − q_k`, `p_{k+1} − p_k`.
pub(super) struct Increments<const N: usize> {
    pub(super) rotation: Matrix3<f64>,
    pub(super) momentum: Vector3<f64>,
    pub(super) q: SVector<f64, N>,
    pub(super) p: SVector<f64, N>,
}

/// Why a step failed: `(iterations, last increment)`, or a singular kinetic energy.
pub(super) enum Failure {
    NoConvergence(usize, f64),
    Singular,
}

/// Flat layout of a chart state or rate `(u, q, P, p)`: `d = 6 + 2N` entries.
pub(super) fn pack<const N: usize>(r: &Rates<N>, out: &mut [f64]) {
    out[..3].copy_from_slice(r.u.as_slice());
    out[3..3 + N].copy_from_slice(r.q.as_slice());
    out[3 + N..6 + N].copy_from_slice(r.pu.as_slice());
    out[6 + N..6 + 2 * N].copy_from_slice(r.p.as_slice());
}

pub(super) fn unpack<const N: usize>(x: &[f64]) -> Rates<N> {
    Rates {
        u: Vector3::from_column_slice(&x[..3]),
        q: SVector::from_column_slice(&x[3..3 + N]),
        pu: Vector3::from_column_slice(&x[3 + N..6 + N]),
        p: SVector::from_column_slice(&x[6 + N..6 + 2 * N]),
    }
}

/// Forms `J = ∂F/∂z` and `G = ∂(E M)/∂z` at the chart state in `newton.tmp` (whose rates and
/// rotated moment are in `newton.tmp2` and `newton.moment_base`) by forward differences, each
/// coordinate stepped by √ε of its scale; inverts `𝟙 − hλₖJ`; forms `Y = (𝟙 − hA ⊗ J)⁻¹ E`
/// column by column; returns `W_u = h Σ bⱼ J[u, ·] Yⱼ`, `W_P = h Σ bⱼ J[P, ·] Yⱼ` and
/// `W_ι = h Σ bⱼ G Yⱼ`.
pub(super) fn linearize<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    r0: &Matrix3<f64>,
    h: f64,
) -> Result<Responses, Failure> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let scale_p = (pcol..d)
        .map(|c| newton.tmp[c].abs())
        .fold(f64::MIN_POSITIVE, f64::max);
    for c in 0..d {
        let base = newton.tmp[c];
        let typical = if c < 3 {
            1.0
        } else if (3..pcol).contains(&c) {
            base.abs().max(1.0)
        } else {
            base.abs().max(scale_p)
        };
        let step = f64::EPSILON.sqrt() * typical;
        newton.tmp[c] = base + step;
        let z = unpack::<N>(&newton.tmp);
        newton.tmp[c] = base;
        let (kc, mc) = rates(model, r0, &z.u, &z.q, &z.pu, &z.p).ok_or(Failure::Singular)?;
        pack(&kc, &mut newton.tmp3);
        for r in 0..d {
            newton.jac[r * d + c] = (newton.tmp3[r] - newton.tmp2[r]) / step;
        }
        for r in 0..3 {
            newton.moment_jac[r * d + c] = (mc[r] - newton.moment_base[r]) / step;
        }
    }
    if !newton.factor(h) {
        return Err(Failure::Singular);
    }
    newton.respond_to_momentum(pcol);
    let mut w_u = Matrix3::zeros();
    let mut w_p = Matrix3::zeros();
    let mut w_i = Matrix3::zeros();
    for c in 0..3 {
        quadrature(table, &newton.y, h, 3, c, &mut newton.tmp3);
        w_u.set_column(c, &rows3(&newton.jac, 0, &newton.tmp3));
        w_p.set_column(c, &rows3(&newton.jac, pcol, &newton.tmp3));
        w_i.set_column(c, &rows3(&newton.moment_jac, 0, &newton.tmp3));
    }
    let responses = Responses {
        u: w_u,
        p: w_p,
        impulse: w_i,
    };
    newton.w = Some((h, responses));
    Ok(responses)
}

/// `out = h Σⱼ bⱼ xⱼ`, with `xⱼ` column `col` of a stage-major array of `stride` columns: the
/// quadrature of a stage correction, which the rows of the one simplified-Newton Jacobian map
/// to the corrections of `u₁`, `P₁` and the impulse (`h Σⱼ bⱼ J xⱼ = J h Σⱼ bⱼ xⱼ`).
pub(super) fn quadrature<const S: usize>(
    table: &GaussTableau<S>,
    x: &[f64],
    h: f64,
    stride: usize,
    col: usize,
    out: &mut [f64],
) {
    let d = out.len();
    for (c, o) in out.iter_mut().enumerate() {
        let mut acc = 0.0;
        for j in 0..S {
            acc += table.b[j] * x[(j * d + c) * stride + col];
        }
        *o = h * acc;
    }
}

/// Rows `first … first + 2` of the row-major `rows × d` matrix `m` applied to `v`.
pub(super) fn rows3(m: &[f64], first: usize, v: &[f64]) -> Vector3<f64> {
    let d = v.len();
    Vector3::from_fn(|r, _| {
        m[(first + r) * d..(first + r + 1) * d]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum()
    })
}

/// One step of the `S`-stage method (module doc) from `(R_k, Π_k, q_k, p_k)`: simplified Newton
/// on the stage values `Zᵢ` and the initial chart momentum `P₀` together.
///
/// The unknowns are the stages `Z` and `P₀`; the equations are the stage equations
/// `G = Z − z₀(P₀) − h (A ⊗ 𝟙) F(Z) = 0` and the transform
/// `r = J_r(u₁)(Π_k + ι) − P₀ − h Σ bⱼ F_P(Zⱼ) = 0`, with `u₁ = h Σ bⱼ F_u(Zⱼ)` and the impulse
/// `ι = h Σ bⱼ Eⱼ M(R_k Eⱼ, Qⱼ)`. Newton's matrix is taken with one Jacobian `J₀ = ∂F/∂z` and
/// one `G₀ = ∂(E M)/∂z` for every stage (forward differences at the stages' mean). Eliminating
/// the stages, `ΔZ = X + Y ΔP₀` with `X = −(𝟙 − hA ⊗ J₀)⁻¹ G` and `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`
/// (`E` the stages' dependence on `P₀`), leaves a 3 × 3 system
/// `(𝟙 − D W_u + W_P − J_r(u₁) W_ι) ΔP₀ = r + D v_u − v_P + J_r(u₁) v_ι`, where
/// `D = ∂(J_r(u₁) m)/∂u₁`, `W_• = h Σ bⱼ J₀[•, ·] Yⱼ` (`G₀` for `ι`) and `v_•` the same of `X`.
pub(super) fn solve<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    start: &Start<'_, N>,
    iteration: Iteration,
) -> Result<(Increments<N>, usize), Failure> {
    let Begun {
        k0,
        mut w,
        reused,
        predicted,
    } = begin(table, newton, model, start, iteration.reuse)?;
    // Linearizations after the start's (or the last step's kept matrix).
    let mut relinearized = 0u32;
    let mut chart_p0 = predicted.unwrap_or(*start.pi0);
    let mut moments = [Vector3::zeros(); S];
    let mut previous = f64::INFINITY;
    let mut iterations = 0;
    loop {
        iterations += 1;
        let dp0 = correction(table, newton, model, start, &w, chart_p0, &mut moments)?;
        let measure = apply_correction(newton, start, &k0, &dp0);
        chart_p0 += dp0;
        if !measure.is_finite() {
            return Err(Failure::NoConvergence(iterations, measure));
        }
        // Round-off reached: the increment is at the last bits, or it stopped decreasing once
        // it was small (the iterates then wander within round-off of the solution). (A stop on
        // the contraction θ seen over two iterations, once θ·increment is below an ulp, saves
        // an iteration but leaves errors near 1e-13: the free body's energy then wanders to
        // 2e-14 over 2·10⁴ steps instead of 6e-16, and the order tests meet that floor.)
        if measure <= 2.0 * f64::EPSILON || (measure >= previous && previous <= 1e-10) {
            break;
        }
        // The contraction of the last iteration (0 at the first, which has no previous one).
        let theta = if previous.is_finite() {
            measure / previous
        } else {
            0.0
        };
        // Within a few ulps and barely contracting (long steps, where the simplified Newton
        // matrix is far from the stages' Jacobians): the iterates creep within round-off of
        // the solution, a few ulps a step; more iterations would not change them beyond that,
        // and without this stop such steps ran into the iteration limit at increments of 3 to 9 ε.
        if measure <= 16.0 * f64::EPSILON && theta > 0.5 {
            break;
        }
        if iterations >= iteration.max_iterations {
            return Err(Failure::NoConvergence(iterations, measure));
        }
        // A matrix formed at z₀ is replaced once the stages lie within O(h²) of the solution
        // (after the first iteration) by the Jacobian at their mean Σ bᵢ Zᵢ, the state near
        // mid-step: O(h²) from the average of the stages' Jacobians, against O(h) for the
        // start's. The last step's mid-step matrix is kept while it contracts 20-fold.
        // On a long step the stages move far from where the matrix was formed; while an
        // iteration contracts less than twofold the matrix is formed again at the stages'
        // mean, up to three times a step.
        let first = relinearized == 0
            && ((iterations == 1 && !reused)
                || (iterations >= 2 && theta > 0.05 && measure > 1e-9));
        if first || (relinearized < 3 && iterations >= 2 && theta > 0.5) {
            relinearized += 1;
            w = relinearize(table, newton, model, start)?;
        }
        previous = measure;
    }
    Ok((finish(table, newton, start, &moments, chart_p0), iterations))
}

/// The start of a step: `(R_k, Π_k, q_k, p_k)` and the step `h`.
pub(super) struct Start<'a, const N: usize> {
    pub(super) r0: &'a Matrix3<f64>,
    pub(super) pi0: &'a Vector3<f64>,
    pub(super) q0: &'a SVector<f64, N>,
    pub(super) p0: &'a SVector<f64, N>,
    pub(super) h: f64,
}

/// How a step iterates: its iteration limit, and whether it may continue the last step (keep
/// its Newton matrix and start from its collocation polynomial).
#[derive(Debug, Clone, Copy)]
pub(super) struct Iteration {
    pub(super) max_iterations: usize,
    pub(super) reuse: bool,
}

/// How the iteration starts ([`begin`]).
struct Begun<const N: usize> {
    /// The rates `F(z₀)`.
    k0: Rates<N>,
    /// The Newton matrix's responses.
    w: Responses,
    /// `w` is the last step's, kept because this step continues it with the same `h`.
    reused: bool,
    /// The `P₀` guess of the continued collocation polynomial, when the stages start from it.
    predicted: Option<Vector3<f64>>,
}

/// The start of the iteration: the rates `F(z₀)`, the Newton matrix's responses (the last
/// step's, when this step continues it with the same `h`; else formed at `z₀`), and the
/// starting stages in `newton.z` — the last step's collocation polynomial continued, with its
/// `P₀` guess, or `Zᵢ = z₀ + cᵢ h F(z₀)`.
fn begin<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    start: &Start<'_, N>,
    reuse: bool,
) -> Result<Begun<N>, Failure> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let (r0, pi0, q0, p0, h) = (start.r0, start.pi0, start.q0, start.p0, start.h);
    let zero = Vector3::zeros();
    let (k0, m0) = rates(model, r0, &zero, q0, pi0, p0).ok_or(Failure::Singular)?;
    newton.moment_base = m0;
    let z0 = Rates {
        u: zero,
        q: *q0,
        pu: *pi0,
        p: *p0,
    };
    pack(&z0, &mut newton.origin);
    pack(&k0, &mut newton.tmp2);
    newton.tmp.copy_from_slice(&newton.origin);
    // A step that continues the last one with the same h starts from the last step's
    // mid-step factorization (simplified Newton across steps); any other starts from J at z₀.
    let (w, reused) = match newton.w {
        Some((h_last, w)) if reuse && same_step(h_last, h) => (w, true),
        _ => (linearize(table, newton, model, r0, h)?, false),
    };
    // Start: the last step's collocation polynomial continued, if this step continues it with
    // the same h; else Zᵢ = z₀ + cᵢ h F(z₀).
    let predicted = if reuse { newton.predict(h, pcol) } else { None };
    if predicted.is_none() {
        for i in 0..S {
            for c in 0..d {
                newton.z[i * d + c] = newton.origin[c] + table.c[i] * h * newton.tmp2[c];
            }
        }
    }
    newton.last = None;
    Ok(Begun {
        k0,
        w,
        reused,
        predicted,
    })
}

/// One simplified-Newton correction: evaluates the stages in `newton.z` (rates into
/// `newton.k`, rotated moments into `moments`), forms the residuals `G` and `r` at the chart
/// momentum `chart_p0`, leaves `X` in `newton.dz` and returns `ΔP₀` from the 3 × 3 Schur
/// complement ([`solve`]).
fn correction<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    start: &Start<'_, N>,
    w: &Responses,
    chart_p0: Vector3<f64>,
    moments: &mut [Vector3<f64>; S],
) -> Result<Vector3<f64>, Failure> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let (r0, pi0, h) = (start.r0, start.pi0, start.h);
    for i in 0..S {
        let z = unpack::<N>(&newton.z[i * d..(i + 1) * d]);
        let (ki, mi) = rates(model, r0, &z.u, &z.q, &z.pu, &z.p).ok_or(Failure::Singular)?;
        pack(&ki, &mut newton.k[i * d..(i + 1) * d]);
        moments[i] = mi;
    }
    let mut u1 = Vector3::zeros();
    let mut dpu = Vector3::zeros();
    let mut impulse = Vector3::zeros();
    for i in 0..S {
        let c = h * table.b[i];
        u1 += Vector3::from_column_slice(&newton.k[i * d..i * d + 3]) * c;
        dpu += Vector3::from_column_slice(&newton.k[i * d + pcol..i * d + pcol + 3]) * c;
        impulse += moments[i] * c;
    }
    // The transform as J_r(u₁)(Π_k + impulse) − P₁ = 0 (the same equation times J_r(u₁)),
    // whose derivatives in P₀ and the stages are simple.
    let m = pi0 + impulse;
    let co1 = ExpCoefficients::new(u1.norm_squared());
    let jr1 = co1.right_jacobian(&u1);
    let r = jr1 * m - (chart_p0 + dpu);
    // −G = z₀ + h Σ aᵢⱼ Kⱼ − Zᵢ (z₀ with the current P₀).
    for i in 0..S {
        for c in 0..d {
            let start = if (pcol..pcol + 3).contains(&c) {
                chart_p0[c - pcol]
            } else {
                newton.origin[c]
            };
            let mut acc = start - newton.z[i * d + c];
            for j in 0..S {
                acc += h * table.a[i][j] * newton.k[j * d + c];
            }
            newton.g[i * d + c] = acc;
        }
    }
    newton.apply_inverse();
    quadrature(table, &newton.dz, h, 1, 0, &mut newton.tmp3);
    let v_u = rows3(&newton.jac, 0, &newton.tmp3);
    let v_p = rows3(&newton.jac, pcol, &newton.tmp3);
    let v_i = rows3(&newton.moment_jac, 0, &newton.tmp3);
    let dm = right_jacobian_derivative(&co1, &u1, &m);
    let Some(schur) = (Matrix3::identity() - dm * w.u + w.p - jr1 * w.impulse).try_inverse() else {
        return Err(Failure::Singular);
    };
    Ok(schur * (r + dm * v_u - v_p + jr1 * v_i))
}

/// Applies `ΔZ = X + Y ΔP₀` to the stages and returns the size of the correction: the largest
/// of `|ΔP₀|/|Π_k|` and, block by block, the change against the size of the block's values
/// (floors: the step's own scale, for blocks that are zero at the start).
fn apply_correction<const S: usize, const N: usize>(
    newton: &mut Newton<S>,
    start: &Start<'_, N>,
    k0: &Rates<N>,
    dp0: &Vector3<f64>,
) -> f64 {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let (pi0, h) = (start.pi0, start.h);
    let mut change = [0.0f64; 4];
    let mut size = [0.0f64; 4];
    for i in 0..S {
        for c in 0..d {
            let x = i * d + c;
            let delta = newton.dz[x]
                + newton.y[x * 3] * dp0[0]
                + newton.y[x * 3 + 1] * dp0[1]
                + newton.y[x * 3 + 2] * dp0[2];
            newton.z[x] += delta;
            let block = if c < 3 {
                0
            } else if c < pcol {
                1
            } else if c < pcol + 3 {
                2
            } else {
                3
            };
            change[block] = change[block].max(delta.abs());
            size[block] = size[block].max(newton.z[x].abs());
        }
    }
    let floors = [
        h.abs() * k0.u.amax(),
        h.abs() * k0.q.amax(),
        pi0.amax(),
        h.abs() * k0.p.amax(),
    ];
    let mut measure = if dp0.amax() == 0.0 {
        0.0
    } else {
        dp0.amax() / pi0.amax().max(f64::MIN_POSITIVE)
    };
    for b in 0..4 {
        if change[b] > 0.0 {
            measure = measure.max(change[b] / size[b].max(floors[b]).max(f64::MIN_POSITIVE));
        }
    }
    measure
}

/// Forms the Newton matrix again at the stages' mean `Σ bᵢ Zᵢ` ([`linearize`]).
fn relinearize<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    start: &Start<'_, N>,
) -> Result<Responses, Failure> {
    let d = 6 + 2 * N;
    for c in 0..d {
        newton.tmp[c] = (0..S).map(|i| table.b[i] * newton.z[i * d + c]).sum();
    }
    let mid = unpack::<N>(&newton.tmp);
    let (km, mm) =
        rates(model, start.r0, &mid.u, &mid.q, &mid.pu, &mid.p).ok_or(Failure::Singular)?;
    pack(&km, &mut newton.tmp2);
    newton.moment_base = mm;
    linearize(table, newton, model, start.r0, start.h)
}

/// The increments of the converged step from its stages' rates (in `newton.k`) and rotated
/// moments; keeps the step's solution for the next step's starting guess.
fn finish<const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    start: &Start<'_, N>,
    moments: &[Vector3<f64>; S],
    chart_p0: Vector3<f64>,
) -> Increments<N> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let (pi0, h) = (start.pi0, start.h);
    let mut u1 = Vector3::zeros();
    let mut impulse = Vector3::zeros();
    let mut dq = SVector::<f64, N>::zeros();
    let mut dp = SVector::<f64, N>::zeros();
    for i in 0..S {
        let c = h * table.b[i];
        let ki = unpack::<N>(&newton.k[i * d..(i + 1) * d]);
        u1 += ki.u * c;
        impulse += moments[i] * c;
        dq += ki.q * c;
        dp += ki.p * c;
    }
    // Kept for the next step's starting guess.
    newton.last_z.copy_from_slice(&newton.z);
    newton.last_origin.copy_from_slice(&newton.origin);
    newton.last_origin[pcol..pcol + 3].copy_from_slice(chart_p0.as_slice());
    newton.last = Some((h, u1));
    // E₁ − 𝟙 from Rodrigues' formula (no rounding of 1 − O(θ²) on the diagonal).
    let co = ExpCoefficients::new(u1.norm_squared());
    let uh = hat(&u1);
    let g = uh * co.sinc + uh * uh * co.a;
    // Π_{k+1} − Π_k = E₁ᵀ (Π_k + impulse) − Π_k = Gᵀ (Π_k + impulse) + impulse.
    let momentum = g.transpose() * (pi0 + impulse) + impulse;
    Increments {
        rotation: g,
        momentum,
        q: dq,
        p: dp,
    }
}
