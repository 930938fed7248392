//! The hoop-tilt map's runs, [`LANES`] at a time: the adaptive Taylor method on the
//! Euler–Poisson hoop with one trajectory per SIMD lane, and the map's metrics read off each
//! step's Taylor polynomial.
//!
//! # Lanes
//!
//! The coefficient recursions of [`super::TaylorHoop`] are written here on arrays of
//! [`LANES`] numbers, one trajectory per lane, so that each multiply and add of a Cauchy
//! product is one instruction for every lane (the layout `[component][order][lane]` makes
//! the lane loop the innermost, contiguous one). Every lane has its own parameters, state,
//! time, step size, step count and failure: a lane that reaches the horizon or fails stops
//! being committed while the others go on (heyoka's batch mode works the same way: Biscani &
//! Izzo, MNRAS 504, 2021, §5). The arithmetic of a lane is the arithmetic of a run alone:
//! each lane's operations are element-wise IEEE operations in the order of the scalar
//! recursion (no operation mixes lanes, no fused multiply–add), so a trajectory's numbers do
//! not depend on which other trajectories share its batch, nor on the batch's width. They
//! are, step for step and bit for bit, those of the scalar Taylor method of
//! [`super::simulate`] (the same order, steps and states: tested).
//!
//! # Metrics on the polynomial
//!
//! The tilt is `asin |Γ_z| / |Γ|`. Within a step of size `h` from `t`, `Γ_z(t + τ)` is the
//! step's Taylor polynomial of degree `p`; its extrema are the roots of its derivative
//! (degree `p − 1`), which is sampled at [`SAMPLES`] + 1 equally spaced points of `[0, h]`
//! (all lanes at once) and refined by safeguarded Newton iteration on each sign change (the
//! way heyoka locates events: on the step's polynomial, not by re-integration). The largest
//! tilt of a run is the largest of its value at `t = 0`, at the end of every step and at every
//! interior extremum found. The first time the tilt exceeds a threshold is solved by bisection
//! on the polynomial, between the last point known to be at or below the threshold and the
//! first above it. The relative energy error is that of the rows ([`crate::scene::run_vector`]):
//! at `t = 0` and at the end of every step.
//!
//! Sampling misses a pair of extrema closer together than `h / SAMPLES` (an oscillation of
//! `Γ_z` faster than the step's own resolution, which Jorba & Zou's step size, a fraction
//! `e⁻²` of the series' radius of convergence, does not allow).

use std::time::Instant;

use tumble_integrators::Error as IntegrationError;
use tumble_integrators::taylor::{
    TaylorError, clock_step, jorba_zou_order, jorba_zou_step, jorba_zou_tolerance, two_sum,
};

use super::{EulerPoissonHoop, State};
use crate::error::SceneError;
use crate::params::Params;
use crate::scene::{CancelFlag, RunPlan, StepControl};
use crate::scene::{energy_scale, relative_energy_error};
use crate::scenes::free_hoop::FreeHoopScene;

/// Trajectories per batch: 8 `f64`, one 512-bit vector or two 256-bit ones.
pub const LANES: usize = 8;

/// Intervals of a step on which the derivative of `Γ_z` is sampled for sign changes.
pub const SAMPLES: usize = 8;

/// One number per lane.
type V = [f64; LANES];

/// Components of the state `(Γ, Π, α, p_α)`.
const N: usize = 8;
const ALPHA: usize = 6;
const P_ALPHA: usize = 7;

// The series of the scalar recursions' intermediate quantities, in their order.
use super::taylor::{AUX, COS, COS2, D, SIN, SIN2, W, WX, WY, WZ};

/// What the map needs from one run of the free hoop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiltRun {
    /// The largest tilt over `[0, t_end]` (rad).
    pub max_tilt: f64,
    /// The tilt at `t_end` (rad).
    pub final_tilt: f64,
    /// The first time the tilt exceeds the threshold, if it was asked for and does.
    pub first_exceeds: Option<f64>,
    /// The largest relative energy error at the steps' ends.
    pub max_energy_rel_err: f64,
    /// Steps taken.
    pub steps: u64,
}

/// Whether [`tilt_runs`] runs `plan`: the adaptive Taylor method (order from the tolerance)
/// to a horizon, rows neither at given times nor thinned out of the energy check.
#[must_use]
pub fn runs(plan: &RunPlan) -> bool {
    matches!(
        plan.method.stepping,
        tumble_integrators::registry::Stepping::Taylor(
            tumble_integrators::taylor::TaylorOrder::FromTolerance
        )
    ) && matches!(plan.step, StepControl::Tolerance(_))
        && plan.times.is_none()
        && plan.observe == crate::scene::Observe::EveryStep
}

/// Runs the reduced free hoop at every point of `params` with `plan` (one [`runs`]), in
/// batches of [`LANES`], and returns each run's [`TiltRun`] or its error, in order.
/// `threshold` (rad) is the tilt whose first crossing [`TiltRun::first_exceeds`] reports.
/// Each result is the same whatever the other points are (module doc).
#[must_use]
pub fn tilt_runs(
    params: &[Params],
    plan: &RunPlan,
    threshold: Option<f64>,
) -> Vec<Result<TiltRun, SceneError>> {
    let models: Vec<Result<(EulerPoissonHoop, State), SceneError>> = params
        .iter()
        .map(|p| {
            FreeHoopScene::model(p)
                .map(|(model, s0)| (EulerPoissonHoop::new(&model), EulerPoissonHoop::reduce(&s0)))
        })
        .collect();
    let ready: Vec<usize> = (0..models.len()).filter(|&i| models[i].is_ok()).collect();
    let mut runs: Vec<Option<Result<TiltRun, SceneError>>> = vec![None; params.len()];
    let mut batch = Batch::new(plan);
    for chunk in ready.chunks(LANES) {
        let members: Vec<(EulerPoissonHoop, State)> = chunk
            .iter()
            .filter_map(|&i| models[i].as_ref().ok().copied())
            .collect();
        for (&i, r) in chunk.iter().zip(batch.run(&members, plan, threshold)) {
            runs[i] = Some(r);
        }
    }
    models
        .into_iter()
        .zip(runs)
        .map(|(model, run)| match (model, run) {
            (Err(e), _) => Err(e),
            (Ok(_), Some(r)) => r,
            // Every point whose model builds is in a chunk.
            (Ok(_), None) => Err(SceneError::Interrupted { t: 0.0 }),
        })
        .collect()
}

/// Where a lane stands.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Lane {
    /// Stepping.
    Running,
    /// At the horizon.
    Done,
    /// Failed (its error is kept aside).
    Failed,
    /// No trajectory (a batch with fewer points than lanes).
    Empty,
}

/// The per-lane constants of [`super::TaylorHoop`]'s recursions.
#[derive(Debug, Clone, Copy, Default)]
struct Constants {
    /// `(jd + μ/2) / d` and `(μ/2) / d` of `ω_x, ω_y`.
    a0: V,
    a1: V,
    jn: V,
    mu: V,
    k: V,
}

/// The workspace of a batch: the series of every lane, allocated once per call of
/// [`tilt_runs`] for the plan's order.
struct Batch {
    /// Order of the method (the same for every lane: both tolerances are the plan's).
    order: usize,
    /// Coefficients per series.
    len: usize,
    /// The state's series: `x[(i * len + k)][lane]`.
    x: Vec<V>,
    /// The intermediate series, likewise.
    aux: Vec<V>,
    /// The widest SIMD instructions of this CPU, found once: the recursions and sums are
    /// compiled for each and run with the widest (the same numbers, lane by lane: each
    /// instruction set does element-wise IEEE arithmetic, and none fuses a multiply and an
    /// add unless asked to).
    arch: pulp::Arch,
}

impl Batch {
    fn new(plan: &RunPlan) -> Self {
        let tol = match plan.step {
            StepControl::Tolerance(tol) => tol,
            StepControl::Fixed(_) => f64::NAN,
        };
        let order = jorba_zou_order(tol) as usize;
        let len = order + 1;
        Batch {
            order,
            len,
            x: vec![[0.0; LANES]; N * len],
            aux: vec![[0.0; LANES]; AUX * len],
            arch: pulp::Arch::new(),
        }
    }

    /// Runs up to [`LANES`] trajectories together.
    #[allow(clippy::too_many_lines)]
    fn run(
        &mut self,
        members: &[(EulerPoissonHoop, State)],
        plan: &RunPlan,
        threshold: Option<f64>,
    ) -> Vec<Result<TiltRun, SceneError>> {
        let tol = match plan.step {
            StepControl::Tolerance(tol) => tol,
            StepControl::Fixed(dt) => {
                return members
                    .iter()
                    .map(|_| {
                        Err(SceneError::InvalidOption {
                            option: "dt",
                            value: dt,
                            reason: "the map's lanes run the adaptive Taylor method, with a \
                                     tolerance"
                                .to_string(),
                        })
                    })
                    .collect();
            }
        };
        let (t0, t_end) = (0.0, plan.t_end);
        let h_max = t_end - t0;
        let p = self.order;
        let started = Instant::now();
        let mut c = Constants::default();
        let mut state = [[0.0; N]; LANES];
        // The rounding error each lane's state carries (the scalar method's compensated sum).
        let mut carry = [[0.0; N]; LANES];
        let mut lanes = [Lane::Empty; LANES];
        let mut errors: [Option<SceneError>; LANES] = std::array::from_fn(|_| None);
        let mut metrics = [Track::default(); LANES];
        let mut t = [t0; LANES];
        let mut steps = [0u64; LANES];
        for (l, (eq, y0)) in members.iter().enumerate() {
            let half_mu = 0.5 * eq.mu;
            c.a0[l] = (eq.jd + half_mu) * eq.inv_det;
            c.a1[l] = half_mu * eq.inv_det;
            c.jn[l] = eq.jn;
            c.mu[l] = eq.mu;
            c.k[l] = eq.k;
            state[l].copy_from_slice(y0.as_slice());
            lanes[l] = Lane::Running;
            metrics[l].start(eq, y0, threshold, t0);
        }
        // A lane without a trajectory repeats the first one (its numbers are never read).
        for l in members.len()..LANES {
            c.a0[l] = c.a0[0];
            c.a1[l] = c.a1[0];
            c.jn[l] = c.jn[0];
            c.mu[l] = c.mu[0];
            c.k[l] = c.k[0];
            state[l] = state[0];
        }
        // The step each lane takes in this round (NaN: none) and whether it is its last.
        let mut step_of = [f64::NAN; LANES];
        let mut last_of = [false; LANES];
        while lanes.contains(&Lane::Running) {
            // The coefficients at every lane's point (a stopped lane's are not read).
            let arch = self.arch;
            arch.dispatch(Expand {
                batch: self,
                c: &c,
                state: &state,
                p,
            });
            let elapsed = plan.deadline.map(|_| started.elapsed().as_secs_f64());
            for l in 0..LANES {
                if lanes[l] != Lane::Running {
                    continue;
                }
                let fail = |e: IntegrationError| Some(SceneError::Integration(e));
                if let Some(reason) = self.non_finite(l, p) {
                    errors[l] = fail(IntegrationError::Taylor {
                        t: t[l],
                        h: f64::NAN,
                        reason,
                        state: state[l].to_vec(),
                    });
                    lanes[l] = Lane::Failed;
                    continue;
                }
                // Jorba & Zou's step at this point (the driver's proposal).
                let x0 = state[l].iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let (_, scale) = jorba_zou_tolerance(tol, tol, x0);
                let h_jz = jorba_zou_step(self.norm(l, p - 1), self.norm(l, p), p as u32, scale);
                if cancelled(plan.cancel) {
                    errors[l] = Some(SceneError::Interrupted { t: t[l] });
                    lanes[l] = Lane::Failed;
                    continue;
                }
                if let (Some(seconds), Some(e)) = (plan.deadline, elapsed)
                    && e >= seconds
                {
                    errors[l] = fail(IntegrationError::TimeLimit {
                        t: t[l],
                        seconds,
                        state: state[l].to_vec(),
                    });
                    lanes[l] = Lane::Failed;
                    continue;
                }
                if steps[l] >= plan.max_steps {
                    errors[l] = fail(IntegrationError::TooManySteps {
                        t: t[l],
                        max_steps: plan.max_steps,
                        state: state[l].to_vec(),
                    });
                    lanes[l] = Lane::Failed;
                    continue;
                }
                let mut step = h_jz;
                // A step of zero or NaN size (no finite step from the coefficients) is an
                // underflow, as the driver's shrinking steps would end.
                if !(step >= 16.0 * f64::EPSILON * t[l].abs().max(1.0)) {
                    errors[l] = fail(IntegrationError::StepSizeUnderflow {
                        t: t[l],
                        h: step,
                        state: state[l].to_vec(),
                    });
                    lanes[l] = Lane::Failed;
                    continue;
                }
                step = step.min(h_max);
                let last = t[l] + step >= t_end;
                if last {
                    step = t_end - t[l];
                }
                // The step the lane's clock takes, as the scalar method sums it.
                step_of[l] = clock_step(t[l], step);
                last_of[l] = last;
            }
            // Every stepping lane's state at the end of its step, and Γ_z' at the sampling
            // points of its step, all lanes at once (a lane that does not step is not read).
            let (ends, slopes) = arch.dispatch(Ends {
                batch: self,
                p,
                step: &step_of,
            });
            for l in 0..LANES {
                let step = step_of[l];
                if lanes[l] != Lane::Running || step.is_nan() {
                    continue;
                }
                step_of[l] = f64::NAN;
                // x₀ + (increment + carry), the error of the addition carried (as
                // `TaylorStepper::commit` does).
                let mut end = [0.0; N];
                let mut next_carry = [0.0; N];
                for i in 0..N {
                    (end[i], next_carry[i]) = two_sum(state[l][i], ends[i][l] + carry[l][i]);
                }
                if end.iter().any(|v| !v.is_finite()) {
                    errors[l] = Some(SceneError::Integration(IntegrationError::NonFinite {
                        t: t[l],
                        h: step,
                        state: state[l].to_vec(),
                    }));
                    lanes[l] = Lane::Failed;
                    continue;
                }
                state[l] = end;
                carry[l] = next_carry;
                steps[l] += 1;
                let t_next = if last_of[l] { t_end } else { t[l] + step };
                let eq = &members[l].0;
                let slope: [f64; SAMPLES + 1] = std::array::from_fn(|i| slopes[i][l]);
                metrics[l].step(self, l, p, t[l], step, &slope, eq, &State::from(end));
                t[l] = t_next;
                if last_of[l] {
                    lanes[l] = Lane::Done;
                }
            }
        }
        members
            .iter()
            .enumerate()
            .map(|(l, _)| match errors[l].take() {
                Some(e) => Err(e),
                None => Ok(metrics[l].finish(&state[l], steps[l])),
            })
            .collect()
    }

    /// The normalized Taylor coefficients of every lane's solution through its state, orders
    /// `0 ..= p` ([`super::TaylorHoop`]'s recursions, lane by lane, in its order of operations).
    #[inline(always)]
    fn expand(&mut self, c: &Constants, state: &[[f64; N]; LANES], p: usize) {
        let len = self.len;
        let (x, aux) = (&mut self.x, &mut self.aux);
        for i in 0..N {
            for l in 0..LANES {
                x[i * len][l] = state[l][i];
            }
        }
        for l in 0..LANES {
            let a = state[l][ALPHA];
            (aux[SIN * len][l], aux[COS * len][l]) = a.sin_cos();
            (aux[SIN2 * len][l], aux[COS2 * len][l]) = (2.0 * a).sin_cos();
        }
        for k in 0..p {
            if k > 0 {
                let (mut ss, mut cc, mut ss2, mut cc2) =
                    ([0.0; LANES], [0.0; LANES], [0.0; LANES], [0.0; LANES]);
                for j in 1..=k {
                    let a = &x[ALPHA * len + j];
                    let (cs, sn) = (&aux[COS * len + k - j], &aux[SIN * len + k - j]);
                    let (cs2, sn2) = (&aux[COS2 * len + k - j], &aux[SIN2 * len + k - j]);
                    let jf = j as f64;
                    for l in 0..LANES {
                        let u = jf * a[l];
                        ss[l] += u * cs[l];
                        cc[l] += u * sn[l];
                        ss2[l] += u * cs2[l];
                        cc2[l] += u * sn2[l];
                    }
                }
                let inv = 1.0 / k as f64;
                for l in 0..LANES {
                    aux[SIN * len + k][l] = ss[l] * inv;
                    aux[COS * len + k][l] = -cc[l] * inv;
                    aux[SIN2 * len + k][l] = 2.0 * ss2[l] * inv;
                    aux[COS2 * len + k][l] = -2.0 * cc2[l] * inv;
                }
            }
            let xs = |i: usize| &x[i * len..i * len + k + 1];
            let at = |q: usize| &aux[q * len..q * len + k + 1];
            let (px, py, pz) = (xs(3), xs(4), xs(5));
            let (s2, c2) = (at(SIN2), at(COS2));
            let (c2px, s2py) = (cauchy(c2, px, k), cauchy(s2, py, k));
            let (s2px, c2py) = (cauchy(s2, px, k), cauchy(c2, py, k));
            let (pzk, pak) = (pz[k], xs(P_ALPHA)[k]);
            let (pxk, pyk) = (px[k], py[k]);
            let mut w = [[0.0; LANES]; 3];
            for l in 0..LANES {
                w[0][l] = c.a0[l] * pxk[l] + c.a1[l] * (c2px[l] + s2py[l]);
                w[1][l] = c.a0[l] * pyk[l] + c.a1[l] * (s2px[l] - c2py[l]);
                w[2][l] = (pzk[l] - pak[l]) / c.jn[l];
            }
            aux[WX * len + k] = w[0];
            aux[WY * len + k] = w[1];
            aux[WZ * len + k] = w[2];
            let at = |q: usize| &aux[q * len..q * len + k + 1];
            let (wx, wy) = (at(WX), at(WY));
            let (xx, yy, xy) = (cauchy(wx, wx, k), cauchy(wy, wy, k), cauchy(wx, wy, k));
            let mut dk = [0.0; LANES];
            for l in 0..LANES {
                dk[l] = xx[l] - yy[l];
            }
            aux[D * len + k] = dk;
            aux[W * len + k] = xy;
            let at = |q: usize| &aux[q * len..q * len + k + 1];
            let xs = |i: usize| &x[i * len..i * len + k + 1];
            let (wx, wy, wz) = (at(WX), at(WY), at(WZ));
            let (gx, gy, gz) = (xs(0), xs(1), xs(2));
            let (px, py, pz) = (xs(3), xs(4), xs(5));
            let (s, cs) = (at(SIN), at(COS));
            let scale = 1.0 / (k + 1) as f64;
            let sub = |a: V, b: V| -> V { std::array::from_fn(|l| a[l] - b[l]) };
            let g0 = sub(cauchy(gy, wz, k), cauchy(gz, wy, k));
            let g1 = sub(cauchy(gz, wx, k), cauchy(gx, wz, k));
            let g2 = sub(cauchy(gx, wy, k), cauchy(gy, wx, k));
            let gg = sub(cauchy(gx, s, k), cauchy(gy, cs, k));
            let (gzs, gzc) = (cauchy(gz, s, k), cauchy(gz, cs, k));
            let p0 = sub(cauchy(py, wz, k), cauchy(pz, wy, k));
            let p1 = sub(cauchy(pz, wx, k), cauchy(px, wz, k));
            let p2 = sub(cauchy(px, wy, k), cauchy(py, wx, k));
            let (sd, cw) = (cauchy(at(SIN2), at(D), k), cauchy(at(COS2), at(W), k));
            let (pak, wzk) = (xs(P_ALPHA)[k], wz[k]);
            let mut next = [[0.0; LANES]; N];
            for l in 0..LANES {
                let kl = c.k[l];
                next[0][l] = g0[l];
                next[1][l] = g1[l];
                next[2][l] = g2[l];
                next[3][l] = p0[l] - kl * gzs[l];
                next[4][l] = p1[l] + kl * gzc[l];
                next[5][l] = p2[l] + kl * gg[l];
                next[ALPHA][l] = pak[l] / c.mu[l] - wzk[l];
                next[P_ALPHA][l] = c.mu[l] * (0.5 * sd[l] - cw[l]) + kl * gg[l];
            }
            for (i, v) in next.iter().enumerate() {
                let slot = &mut x[i * len + k + 1];
                for l in 0..LANES {
                    slot[l] = v[l] * scale;
                }
            }
        }
    }

    /// The first non-finite coefficient of lane `l` (lowest order first), as
    /// [`tumble_integrators::taylor::check_finite`] names it.
    fn non_finite(&self, l: usize, p: usize) -> Option<TaylorError> {
        (0..=p).find_map(|k| {
            (0..N)
                .find(|&i| !self.x[i * self.len + k][l].is_finite())
                .map(|i| TaylorError::NonFinite {
                    order: k,
                    component: i,
                })
        })
    }

    /// `‖xⱼ‖∞` of lane `l`.
    fn norm(&self, l: usize, j: usize) -> f64 {
        (0..N).fold(0.0f64, |m, i| m.max(self.x[i * self.len + j][l].abs()))
    }

    /// Every lane's increment over `τ` from its point, `Σₖ₌₁ᵖ xₖ τᵏ` (Horner, as the scalar
    /// method sums it before adding it to the state with compensation):
    /// `[component][lane]`. A NaN `τ` gives NaN.
    #[inline(always)]
    fn increment(&self, p: usize, tau: &V) -> [V; N] {
        std::array::from_fn(|i| {
            let x = &self.x[i * self.len..];
            let mut s = x[p];
            for xk in x[1..p].iter().rev() {
                for l in 0..LANES {
                    s[l] = s[l] * tau[l] + xk[l];
                }
            }
            for l in 0..LANES {
                s[l] *= tau[l];
            }
            s
        })
    }

    /// `Γ_z'` of every lane at the [`SAMPLES`] + 1 points `τᵢ = i h / SAMPLES` of its step
    /// `h` (Horner on `k xₖ`): `[point][lane]`.
    #[inline(always)]
    fn slopes(&self, p: usize, h: &V) -> [V; SAMPLES + 1] {
        let x = &self.x[2 * self.len..];
        std::array::from_fn(|i| {
            let tau: V = std::array::from_fn(|l| node(h[l], i));
            let mut d = [0.0; LANES];
            for k in (1..=p).rev() {
                let kf = k as f64;
                for l in 0..LANES {
                    d[l] = d[l] * tau[l] + kf * x[k][l];
                }
            }
            d
        })
    }

    /// Component `i` of lane `l` at `τ` (Horner).
    #[inline]
    fn poly(&self, l: usize, i: usize, p: usize, tau: f64) -> f64 {
        let x = &self.x[i * self.len..];
        let mut s = x[p][l];
        for k in (0..p).rev() {
            s = s * tau + x[k][l];
        }
        s
    }

    /// `(Γ_z'(τ), Γ_z''(τ))` of lane `l`.
    #[inline]
    fn slope(&self, l: usize, p: usize, tau: f64) -> (f64, f64) {
        let x = &self.x[2 * self.len..];
        let (mut d1, mut d2) = (0.0, 0.0);
        for k in (1..=p).rev() {
            d2 = d2 * tau + d1;
            d1 = d1 * tau + k as f64 * x[k][l];
        }
        (d1, d2)
    }

    /// The tilt of lane `l` at `τ`.
    fn tilt(&self, l: usize, p: usize, tau: f64) -> f64 {
        EulerPoissonHoop::tilt(
            self.poly(l, 0, p, tau),
            self.poly(l, 1, p, tau),
            self.poly(l, 2, p, tau),
        )
    }
}

/// [`Batch::expand`] compiled for the instruction set `pulp` finds (inlined into its
/// target-feature function: a closure would be compiled once, for the baseline).
struct Expand<'a> {
    batch: &'a mut Batch,
    c: &'a Constants,
    state: &'a [[f64; N]; LANES],
    p: usize,
}

impl pulp::WithSimd for Expand<'_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        self.batch.expand(self.c, self.state, self.p);
    }
}

/// [`Batch::increment`] and [`Batch::slopes`] likewise.
struct Ends<'a> {
    batch: &'a Batch,
    p: usize,
    step: &'a V,
}

impl pulp::WithSimd for Ends<'_> {
    type Output = ([V; N], [V; SAMPLES + 1]);
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Self::Output {
        (
            self.batch.increment(self.p, self.step),
            self.batch.slopes(self.p, self.step),
        )
    }
}

/// Sampling point `i` of a step `h`: `i h / SAMPLES`, the end exactly `h`.
#[inline]
fn node(h: f64, i: usize) -> f64 {
    if i == SAMPLES {
        h
    } else {
        h * i as f64 / SAMPLES as f64
    }
}

/// `Σⱼ₌₀ᵏ aⱼ bₖ₋ⱼ` in every lane (a multiply and an add, in the scalar recursion's order).
#[inline(always)]
fn cauchy(a: &[V], b: &[V], k: usize) -> V {
    let mut s = [0.0; LANES];
    for j in 0..=k {
        let (x, y) = (&a[j], &b[k - j]);
        for l in 0..LANES {
            s[l] += x[l] * y[l];
        }
    }
    s
}

fn cancelled(flag: Option<CancelFlag>) -> bool {
    flag.is_some_and(|CancelFlag(f)| f.load(std::sync::atomic::Ordering::Relaxed))
}

/// A lane's metrics so far.
#[derive(Debug, Clone, Copy, Default)]
struct Track {
    /// Largest tilt so far.
    max_tilt: f64,
    /// The threshold of [`TiltRun::first_exceeds`] while it is still to be found.
    threshold: Option<f64>,
    first_exceeds: Option<f64>,
    energy0: f64,
    energy_scale: f64,
    max_rel: f64,
}

impl Track {
    fn start(&mut self, eq: &EulerPoissonHoop, y0: &State, threshold: Option<f64>, t0: f64) {
        let tilt = EulerPoissonHoop::tilt(y0[0], y0[1], y0[2]);
        let (e, magnitude) = eq.energy(y0);
        *self = Track {
            max_tilt: tilt,
            threshold,
            first_exceeds: None,
            energy0: e,
            energy_scale: energy_scale(0.0, e, magnitude),
            max_rel: 0.0,
        };
        if threshold.is_some_and(|thr| tilt > thr) {
            self.first_exceeds = Some(t0);
            self.threshold = None;
        }
        self.max_rel = relative_energy_error(e, e, self.energy_scale);
    }

    /// Takes in the step of lane `l` from `t` over `h`, whose end state is `y`.
    #[allow(clippy::too_many_arguments)]
    fn step(
        &mut self,
        batch: &Batch,
        l: usize,
        p: usize,
        t: f64,
        h: f64,
        slope: &[f64; SAMPLES + 1],
        eq: &EulerPoissonHoop,
        y: &State,
    ) {
        // The energy at the step's end.
        let (e, magnitude) = eq.energy(y);
        self.energy_scale = energy_scale(self.energy_scale, self.energy0, magnitude);
        let rel = relative_energy_error(e, self.energy0, self.energy_scale);
        self.max_rel = self.max_rel.max(rel);
        // Sample Γ_z' for sign changes; each is an extremum of Γ_z, a candidate for the
        // largest |Γ_z|. Candidates in increasing τ, the step's end last.
        let mut points = [(0.0, 0.0); SAMPLES + 1];
        let mut count = 0;
        for i in 1..=SAMPLES {
            let (before, now) = (slope[i - 1], slope[i]);
            if (before > 0.0 && now < 0.0) || (before < 0.0 && now > 0.0) {
                let root = extremum(batch, l, p, node(h, i - 1), node(h, i), before);
                points[count] = (root, batch.tilt(l, p, root));
                count += 1;
            }
        }
        points[count] = (h, EulerPoissonHoop::tilt(y[0], y[1], y[2]));
        count += 1;
        let points = &points[..count];
        for &(_, tilt) in points {
            if tilt > self.max_tilt {
                self.max_tilt = tilt;
            }
        }
        if let Some(thr) = self.threshold
            && let Some(&(tau, _)) = points.iter().find(|&&(_, tilt)| tilt > thr)
        {
            self.first_exceeds = Some(t + first_crossing(batch, l, p, tau, thr));
            self.threshold = None;
        }
    }

    fn finish(&self, y: &[f64; N], steps: u64) -> TiltRun {
        TiltRun {
            max_tilt: self.max_tilt,
            final_tilt: EulerPoissonHoop::tilt(y[0], y[1], y[2]),
            first_exceeds: self.first_exceeds,
            max_energy_rel_err: self.max_rel,
            steps,
        }
    }
}

/// The root of `Γ_z'` in `[a, b]`, where it changes sign (`g_a = Γ_z'(a)`): Newton's
/// iteration kept inside the bracket, bisection when it would leave it.
fn extremum(batch: &Batch, l: usize, p: usize, mut a: f64, mut b: f64, g_a: f64) -> f64 {
    let rising = g_a < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let (g, dg) = batch.slope(l, p, x);
        if g == 0.0 {
            return x;
        }
        if (g < 0.0) == rising {
            a = x;
        } else {
            b = x;
        }
        let newton = x - g / dg;
        let next = if newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if next == x || b - a <= 4.0 * f64::EPSILON * b.abs().max(f64::MIN_POSITIVE) {
            return next;
        }
        x = next;
    }
    x
}

/// The first `τ ∈ (0, b]` where lane `l`'s tilt exceeds `thr`, given that it does at `b`,
/// the first extremum or end of the step above it, and not at `τ = 0`: between them the tilt
/// has no maximum, so it crosses `thr` once, and bisection closes the bracket to adjacent
/// doubles.
fn first_crossing(batch: &Batch, l: usize, p: usize, b: f64, thr: f64) -> f64 {
    let (mut a, mut b) = (0.0, b);
    loop {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            return b;
        }
        if batch.tilt(l, p, mid) > thr {
            b = mid;
        } else {
            a = mid;
        }
    }
}

#[cfg(test)]
mod tests;
