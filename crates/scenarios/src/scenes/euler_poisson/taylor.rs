//! The Taylor coefficients of the free hoop, written out by hand: the equations of
//! [`super::EulerPoissonHoop`] (and of the full model, whose other two rows of `R` move as `Γ`
//! does) as a [`TaylorSystem`].
//!
//! With `s, c = sin α, cos α` and `S, C = sin 2α, cos 2α`, the closed-form velocities are
//! linear in `Π` with coefficients affine in `S, C` (the `xy` block's determinant does not
//! depend on `α`):
//!
//! `ω_x = (jd + μ/2) Π_x/d + (μ/2d)(C Π_x + S Π_y)`, `ω_y = (jd + μ/2) Π_y/d + (μ/2d)(S Π_x − C Π_y)`,
//! `d = jd (jd + μ)`, `ω_z = (Π_z − p_α)/(Ma²)`, `α̇ = p_α/μ − ω_z`,
//!
//! and the right-hand side is polynomial in `(Γ, Π, s, c, S, C, ω)`:
//! `Γ̇ = Γ × ω`, `Π̇ = Π × ω + k (−Γ_z s, Γ_z c, G)`, `ṗ_α = μ (S D/2 − C W) + k G`, with
//! `G = Γ_x s − Γ_y c`, `D = ω_x² − ω_y²`, `W = ω_x ω_y`. So the normalized coefficients follow
//! from Cauchy products (`(ab)ₖ = Σⱼ aⱼ bₖ₋ⱼ`) and the sine–cosine recursion
//! (`k sₖ = Σⱼ₌₁ᵏ j uⱼ cₖ₋ⱼ`, `k cₖ = −Σⱼ₌₁ᵏ j uⱼ sₖ₋ⱼ` for `s, c = sin u, cos u`): Moore 1966,
//! ch. 11; Jorba & Zou 2005, §3; Griewank & Walther 2008, §13.2. Per order, 29 products on the
//! reduction (6 more for each further row of `R`).
//!
//! Two forms of the same recursion:
//! - on the reduction ([`TaylorHoop::reduced`]) one product at a time, in the order of
//!   operations the map's lanes ([`super::lanes`]) repeat bit for bit;
//! - on the full model ([`TaylorHoop::full`], the scene's `taylor`) with the products of each
//!   stage of an order side by side ([`CrossSums`]): the sine–cosine sums (4 lanes), `ω_x, ω_y`
//!   (2) and `D, W` (2) in one eight-lane pass over the lower orders, each stage then finishing
//!   its own lanes; then `Ṙ`, `Π × ω`, the gravity terms and `ṗ_α`'s sums (16) in a second
//!   pass. The same sums, grouped `Σⱼ (aⱼ bₖ₋ⱼ − cⱼ dₖ₋ⱼ)` instead of
//!   `Σⱼ aⱼ bₖ₋ⱼ − Σⱼ cⱼ dₖ₋ⱼ`: the two forms agree to round-off, not bit for bit.

use std::cell::RefCell;

use crate::scenes::cauchy;
use tumble_integrators::rigid::taylor::PATTERN;
use tumble_integrators::taylor::{CrossSums, TaylorError, TaylorSystem, check_finite};

use super::EulerPoissonHoop;

/// The reduced state `(Γ, Π, α, p_α)` ([`super::State`]): where its parts are.
const N_REDUCED: usize = 8;
const GAMMA: [usize; 3] = [0, 1, 2];
const PI: usize = 3;
const ALPHA: usize = 6;
const P_ALPHA: usize = 7;

/// The full model's flat state `(R column-major, Π, α, p_α)` ∈ ℝ¹⁴
/// ([`crate::scenes::free_hoop::flatten`]): row `a` of `R` is components `a, a + 3, a + 6`,
/// `Γ` (the third row) `2, 5, 8`.
const N_FULL: usize = 14;
const FULL_PI: usize = 9;
const FULL_ALPHA: usize = 12;
const FULL_P_ALPHA: usize = 13;

/// The series of the reduced state's components and of the intermediate quantities, each
/// contiguous (component-major, so that every Cauchy product reads two slices).
#[derive(Debug, Clone, Default)]
struct Series {
    /// Coefficients per order a series holds.
    len: usize,
    /// The state: component `i`'s coefficients at `i * len ..`.
    x: Vec<f64>,
    /// `sin α, cos α, sin 2α, cos 2α, ω_x, ω_y, ω_z, D, W`, one series each.
    aux: Vec<f64>,
}

/// The series of [`Series::aux`].
pub(super) const SIN: usize = 0;
pub(super) const COS: usize = 1;
pub(super) const SIN2: usize = 2;
pub(super) const COS2: usize = 3;
pub(super) const WX: usize = 4;
pub(super) const WY: usize = 5;
pub(super) const WZ: usize = 6;
pub(super) const D: usize = 7;
pub(super) const W: usize = 8;
pub(super) const AUX: usize = 9;

impl Series {
    /// Room for orders `0 ..= order` (grown once).
    fn reserve(&mut self, order: usize) {
        if self.len < order + 1 {
            self.len = order + 1;
            self.x = vec![0.0; N_REDUCED * self.len];
            self.aux = vec![0.0; AUX * self.len];
        }
    }
}

/// The lanes of the full model's last stage ([`FullWork::main`]): `Ṙ` and `Π × ω` in
/// [`PATTERN`]'s lanes `0 .. 12`, then these.
const GZ_SIN: usize = 12;
const GZ_COS: usize = 13;
/// `G = Γ_x sin α − Γ_y cos α`.
const G: usize = 14;
/// `S D/2 − C W`.
const SD_CW: usize = 15;

/// The lanes of the full model's first three stages ([`FullWork::head`]): the sine–cosine
/// sums (4 lanes), then `ω_x, ω_y`'s (2), then `D, W` (2).
const TRIG: usize = 0;
const OMEGA: usize = 4;
const DW: usize = 6;

/// The full model's workspace: the factors of each stage's Cauchy sums, by order.
#[derive(Debug, Clone, Default)]
struct FullWork {
    /// The first three stages side by side, so that their sums over the lower orders are one
    /// pass over eight lanes:
    /// - from [`TRIG`]: `k sₖ`, `k cₖ` of `sin α, cos α` and `(k/2)` of `sin 2α, cos 2α`: `j αⱼ`
    ///   against `(cos α, sin α, cos 2α, sin 2α)ₖ₋ⱼ`;
    /// - from [`OMEGA`]: `Σ C Π_x + S Π_y` and `Σ S Π_x − C Π_y` (the sums in `ω_x, ω_y`);
    /// - from [`DW`]: `D = ω_x² − ω_y²`, `W = ω_x ω_y`.
    head: CrossSums<f64, 8>,
    /// `Ṙ`, `Π × ω` and the sums of the gravity terms and of `ṗ_α` (lanes above).
    main: CrossSums<f64, 16>,
}

impl FullWork {
    fn reserve(&mut self, order: usize) {
        self.head.reserve(order);
        self.main.reserve(order);
    }
}

/// Which state the recursion runs on, with its workspace.
#[derive(Debug, Clone)]
enum Form {
    Reduced(RefCell<Series>),
    Full {
        /// Boxed: sixteen growable series, against the reduction's two.
        work: Box<RefCell<FullWork>>,
        arch: pulp::Arch,
    },
}

/// The free hoop's equations as a [`TaylorSystem`] (module doc): on the Euler–Poisson state
/// ([`TaylorHoop::reduced`]) or on the full model's ([`TaylorHoop::full`]).
#[derive(Debug, Clone)]
pub struct TaylorHoop {
    eq: EulerPoissonHoop,
    form: Form,
}

impl TaylorHoop {
    /// On `(Γ, Π, α, p_α)`.
    #[must_use]
    pub fn reduced(eq: EulerPoissonHoop) -> Self {
        Self {
            eq,
            form: Form::Reduced(RefCell::new(Series::default())),
        }
    }

    /// On the full model's flat state `(R, Π, α, p_α)` ∈ ℝ¹⁴.
    #[must_use]
    pub fn full(eq: EulerPoissonHoop) -> Self {
        Self {
            eq,
            form: Form::Full {
                work: Box::new(RefCell::new(FullWork::default())),
                arch: pulp::Arch::new(),
            },
        }
    }
}

impl TaylorSystem for TaylorHoop {
    fn dim(&self) -> usize {
        match self.form {
            Form::Reduced(_) => N_REDUCED,
            Form::Full { .. } => N_FULL,
        }
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        match &self.form {
            Form::Reduced(series) => reduced(&self.eq, &mut series.borrow_mut(), x0, order, coeffs),
            Form::Full { work, arch } => arch.dispatch(Full {
                eq: &self.eq,
                work: &mut work.borrow_mut(),
                x0,
                order,
                coeffs,
            }),
        }
    }
}

/// The recursion on the reduction, one Cauchy product at a time (the lanes' order of
/// operations).
fn reduced(
    eq: &EulerPoissonHoop,
    series: &mut Series,
    x0: &[f64],
    order: usize,
    coeffs: &mut [f64],
) -> Result<(), TaylorError> {
    let (g, pi, alpha, p) = (GAMMA, PI, ALPHA, P_ALPHA);
    series.reserve(order);
    let Series { len, x, aux } = series;
    let len = *len;
    for (i, v) in x0[..N_REDUCED].iter().enumerate() {
        x[i * len] = *v;
    }
    let half_mu = 0.5 * eq.mu;
    let (a0, a1) = ((eq.jd + half_mu) * eq.inv_det, half_mu * eq.inv_det);
    (aux[SIN * len], aux[COS * len]) = x0[alpha].sin_cos();
    (aux[SIN2 * len], aux[COS2 * len]) = (2.0 * x0[alpha]).sin_cos();
    for k in 0..order {
        // Orders 0 ..= k are known; order k + 1 of the state is written.
        let xs = |i: usize| &x[i * len..i * len + k + 1];
        if k > 0 {
            // sin/cos of α and of 2α: k sₖ = Σ j αⱼ cₖ₋ⱼ, k cₖ = −Σ j αⱼ sₖ₋ⱼ.
            let a = xs(alpha);
            let (mut ss, mut cc) = (0.0, 0.0);
            let (mut ss2, mut cc2) = (0.0, 0.0);
            for j in 1..=k {
                let u = j as f64 * a[j];
                ss += u * aux[COS * len + k - j];
                cc += u * aux[SIN * len + k - j];
                ss2 += u * aux[COS2 * len + k - j];
                cc2 += u * aux[SIN2 * len + k - j];
            }
            let inv = 1.0 / k as f64;
            aux[SIN * len + k] = ss * inv;
            aux[COS * len + k] = -cc * inv;
            aux[SIN2 * len + k] = 2.0 * ss2 * inv;
            aux[COS2 * len + k] = -2.0 * cc2 * inv;
        }
        let at = |q: usize| &aux[q * len..q * len + k + 1];
        // ωₖ, linear in Π with coefficients affine in sin 2α, cos 2α.
        let (px, py, pz) = (xs(pi), xs(pi + 1), xs(pi + 2));
        let (s2, c2) = (at(SIN2), at(COS2));
        let wx = a0 * px[k] + a1 * (cauchy(c2, px, k) + cauchy(s2, py, k));
        let wy = a0 * py[k] + a1 * (cauchy(s2, px, k) - cauchy(c2, py, k));
        let wz = (pz[k] - xs(p)[k]) / eq.jn;
        aux[WX * len + k] = wx;
        aux[WY * len + k] = wy;
        aux[WZ * len + k] = wz;
        let at = |q: usize| &aux[q * len..q * len + k + 1];
        let (wx, wy) = (at(WX), at(WY));
        let dk = cauchy(wx, wx, k) - cauchy(wy, wy, k);
        let wk = cauchy(wx, wy, k);
        aux[D * len + k] = dk;
        aux[W * len + k] = wk;
        let at = |q: usize| &aux[q * len..q * len + k + 1];
        let (wx, wy, wz) = (at(WX), at(WY), at(WZ));
        let scale = 1.0 / (k + 1) as f64;
        let mut next = [0.0; N_REDUCED];
        // Γ̇ = Γ × ω.
        let (gx, gy, gz) = (xs(g[0]), xs(g[1]), xs(g[2]));
        next[g[0]] = cauchy(gy, wz, k) - cauchy(gz, wy, k);
        next[g[1]] = cauchy(gz, wx, k) - cauchy(gx, wz, k);
        next[g[2]] = cauchy(gx, wy, k) - cauchy(gy, wx, k);
        // Π̇ = Π × ω + k (−Γ_z s, Γ_z c, G), G = Γ_x s − Γ_y c.
        let (s, c) = (at(SIN), at(COS));
        let gg = cauchy(gx, s, k) - cauchy(gy, c, k);
        next[pi] = cauchy(py, wz, k) - cauchy(pz, wy, k) - eq.k * cauchy(gz, s, k);
        next[pi + 1] = cauchy(pz, wx, k) - cauchy(px, wz, k) + eq.k * cauchy(gz, c, k);
        next[pi + 2] = cauchy(px, wy, k) - cauchy(py, wx, k) + eq.k * gg;
        // α̇ = p/μ − ω_z; ṗ = μ (S D/2 − C W) + k G.
        next[alpha] = xs(p)[k] / eq.mu - wz[k];
        next[p] =
            eq.mu * (0.5 * cauchy(at(SIN2), at(D), k) - cauchy(at(COS2), at(W), k)) + eq.k * gg;
        for (i, v) in next.iter().enumerate() {
            x[i * len + k + 1] = v * scale;
        }
    }
    for k in 0..=order {
        for i in 0..N_REDUCED {
            coeffs[k * N_REDUCED + i] = x[i * len + k];
        }
    }
    check_finite(coeffs, N_REDUCED, order)
}

/// The recursion on the full model, stage by stage element-wise (module doc), the
/// coefficients written in place order by order.
#[inline(always)]
fn full(
    eq: &EulerPoissonHoop,
    work: &mut FullWork,
    x0: &[f64],
    order: usize,
    coeffs: &mut [f64],
) -> Result<(), TaylorError> {
    const N: usize = N_FULL;
    coeffs[..N].copy_from_slice(&x0[..N]);
    work.reserve(order);
    let half_mu = 0.5 * eq.mu;
    let (a0, a1) = ((eq.jd + half_mu) * eq.inv_det, half_mu * eq.inv_det);
    // sin 2α = 2 s c, cos 2α = (c − s)(c + s): one library call, each within an ulp or two.
    let (sin, cos) = x0[FULL_ALPHA].sin_cos();
    let mut trig = [sin, cos, 2.0 * sin * cos, (cos - sin) * (cos + sin)];
    // Reciprocals, so that no division lies on the chain from one order to the next.
    let (inv_jn, inv_mu) = (1.0 / eq.jn, 1.0 / eq.mu);
    for k in 0..order {
        let x = &coeffs[k * N..(k + 1) * N];
        // The terms of every stage whose factors are all of lower orders first: four
        // independent passes. Each stage's end terms (`j = 0` and `j = k`, which hold its
        // order-k factors) then follow from the factors as computed, not read back.
        let middle_head = work.head.middle(k);
        let middle_main = work.main.middle(k);
        if k > 0 {
            // k sₖ = Σⱼ₌₁ᵏ j αⱼ cₖ₋ⱼ, k cₖ = −Σⱼ₌₁ᵏ j αⱼ sₖ₋ⱼ; twice that for 2α.
            let u = [k as f64 * x[FULL_ALPHA]; 4];
            let t = work.head.finish_lanes(
                k,
                1,
                TRIG,
                &middle_head,
                [&u, &[0.0; 4], &[0.0; 4], &[0.0; 4]],
            );
            work.head.set_left_lanes(k, TRIG, u, [0.0; 4]);
            let inv = 1.0 / k as f64;
            trig = [t[0] * inv, -t[1] * inv, 2.0 * t[2] * inv, -2.0 * t[3] * inv];
        }
        let [sin, cos, sin2, cos2] = trig;
        work.head
            .set_right_lanes(k, TRIG, [cos, sin, cos2, sin2], [0.0; 4]);
        // ωₖ, linear in Π with coefficients affine in sin 2α, cos 2α.
        let (px, py, pz) = (x[FULL_PI], x[FULL_PI + 1], x[FULL_PI + 2]);
        let omega_factors = [[cos2, sin2], [sin2, cos2], [px, px], [-py, py]];
        let [f1, f2, f3, f4] = &omega_factors;
        let o = work
            .head
            .finish_lanes(k, 0, OMEGA, &middle_head, [f1, f2, f3, f4]);
        let [f1, f2, f3, f4] = omega_factors;
        work.head.set_left_lanes(k, OMEGA, f1, f2);
        work.head.set_right_lanes(k, OMEGA, f3, f4);
        let omega = [
            a0 * px + a1 * o[0],
            a0 * py + a1 * o[1],
            (pz - x[FULL_P_ALPHA]) * inv_jn,
        ];
        let [wx, wy, wz] = omega;
        let dw_factors = [[wx, wx], [wy, 0.0], [wx, wy], [wy, 0.0]];
        let [f1, f2, f3, f4] = &dw_factors;
        let [dk, wk] = work
            .head
            .finish_lanes(k, 0, DW, &middle_head, [f1, f2, f3, f4]);
        let [f1, f2, f3, f4] = dw_factors;
        work.head.set_left_lanes(k, DW, f1, f2);
        work.head.set_right_lanes(k, DW, f3, f4);
        // Γ = (x₂, x₅, x₈), the third row of R.
        let (gx, gy, gz) = (x[2], x[5], x[8]);
        let mut first = [0.0; 16];
        let mut second = [0.0; 16];
        let mut w_first = [0.0; 16];
        let mut w_second = [0.0; 16];
        for i in 0..12 {
            first[i] = x[PATTERN.first[i]];
            second[i] = x[PATTERN.second[i]];
            w_first[i] = omega[PATTERN.w_first[i]];
            w_second[i] = omega[PATTERN.w_second[i]];
        }
        first[12..].copy_from_slice(&[gz, gz, gx, sin2]);
        second[12..].copy_from_slice(&[0.0, 0.0, gy, cos2]);
        w_first[12..].copy_from_slice(&[sin, cos, sin, 0.5 * dk]);
        w_second[12..].copy_from_slice(&[0.0, 0.0, cos, wk]);
        let sums = work
            .main
            .finish_with(k, 0, middle_main, [&first, &second, &w_first, &w_second]);
        work.main.set(k, first, second, w_first, w_second);
        let (p_alpha, scale) = (x[FULL_P_ALPHA], 1.0 / (k + 1) as f64);
        let next = &mut coeffs[(k + 1) * N..(k + 2) * N];
        // Ṙ = R hat(ω) row by row.
        for i in 0..9 {
            next[i] = sums[i] * scale;
        }
        // Π̇ = Π × ω + k (−Γ_z s, Γ_z c, G).
        next[FULL_PI] = (sums[9] - eq.k * sums[GZ_SIN]) * scale;
        next[FULL_PI + 1] = (sums[10] + eq.k * sums[GZ_COS]) * scale;
        next[FULL_PI + 2] = (sums[11] + eq.k * sums[G]) * scale;
        // α̇ = p/μ − ω_z; ṗ = μ (S D/2 − C W) + k G.
        next[FULL_ALPHA] = (p_alpha * inv_mu - wz) * scale;
        next[FULL_P_ALPHA] = (eq.mu * sums[SD_CW] + eq.k * sums[G]) * scale;
    }
    check_finite(coeffs, N, order)
}

/// [`full`] compiled for the instruction set `pulp` finds at run time (inlined into its
/// target-feature function, so that the element-wise passes use the widest vectors).
struct Full<'a> {
    eq: &'a EulerPoissonHoop,
    work: &'a mut FullWork,
    x0: &'a [f64],
    order: usize,
    coeffs: &'a mut [f64],
}

impl pulp::WithSimd for Full<'_> {
    type Output = Result<(), TaylorError>;
    #[inline(always)]
    fn with_simd<V: pulp::Simd>(self, _: V) -> Self::Output {
        full(self.eq, self.work, self.x0, self.order, self.coeffs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::free_hoop::{FREE_HOOP, FlatFreeHoop, FreeHoopScene};
    use nalgebra::{Rotation3, SVector};
    use tumble_integrators::Ode;

    /// The free hoop of the map's parameters, with the bead off-centre and spinning.
    fn model() -> crate::scenes::free_hoop::FreeHoop {
        let mut p = FREE_HOOP.default_params();
        p.set("m", 0.1).unwrap();
        p.set("omega0", 5.0).unwrap();
        FreeHoopScene::model(&p).unwrap().0
    }

    /// A full state where every coefficient is at work: tilted, spinning about every axis,
    /// the bead moving.
    fn full_state() -> SVector<f64, 14> {
        let r = Rotation3::from_euler_angles(0.4, -1.1, 0.7);
        let mut y = SVector::<f64, 14>::zeros();
        y.fixed_rows_mut::<9>(0)
            .copy_from_slice(r.matrix().as_slice());
        y.fixed_rows_mut::<3>(9).copy_from_slice(&[1.2, -0.7, 0.9]);
        y[12] = 2.3;
        y[13] = 0.35;
        y
    }

    /// `x(h)` by 2000 RK4 steps of `f`: an independent solution over a short step, to
    /// round-off (the error is `~ (h/2000)⁴`).
    fn rk4<const N: usize>(
        f: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
        mut y: SVector<f64, N>,
        h: f64,
    ) -> SVector<f64, N> {
        let steps = 2000;
        let dt = h / f64::from(steps);
        for _ in 0..steps {
            let k1 = f(&y);
            let k2 = f(&(y + k1 * (dt / 2.0)));
            let k3 = f(&(y + k2 * (dt / 2.0)));
            let k4 = f(&(y + k3 * dt));
            y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0);
        }
        y
    }

    /// Checks `system`'s coefficients at `x0` against the right-hand side `f`: `x₁ = F(x₀)`,
    /// `x₂ = ½ dF/dt` along the flow (a central difference), and the order-24 polynomial at
    /// `h = 0.05` against RK4's solution over that step (every coefficient counts there).
    fn check<const N: usize>(
        system: &TaylorHoop,
        f: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
        x0: SVector<f64, N>,
    ) {
        assert_eq!(system.dim(), N);
        let order = 24;
        let mut c = vec![0.0; (order + 1) * N];
        system
            .coefficients(0.0, x0.as_slice(), order, &mut c)
            .unwrap();
        let f0 = f(&x0);
        for i in 0..N {
            assert!(
                (c[N + i] - f0[i]).abs() <= 1e-14 * (1.0 + f0[i].abs()),
                "x1[{i}]: {} vs {}",
                c[N + i],
                f0[i]
            );
        }
        let h = 1e-5;
        let (fp, fm) = (f(&(x0 + f0 * h)), f(&(x0 - f0 * h)));
        for i in 0..N {
            let x2 = (fp[i] - fm[i]) / (2.0 * h) / 2.0;
            assert!(
                (c[2 * N + i] - x2).abs() <= 1e-8 * (1.0 + x2.abs()),
                "x2[{i}]: {} vs {x2}",
                c[2 * N + i]
            );
        }
        let h = 0.05;
        let exact = rk4(&f, x0, h);
        for i in 0..N {
            let sum = (0..=order).rev().fold(0.0, |s, k| s * h + c[k * N + i]);
            assert!(
                (sum - exact[i]).abs() <= 1e-13 * (1.0 + exact[i].abs()),
                "x({h})[{i}]: {sum} vs {}",
                exact[i]
            );
        }
    }

    /// On the reduction: the coefficients against [`EulerPoissonHoop`]'s right-hand side.
    #[test]
    fn reduced_coefficients_follow_the_right_hand_side_and_the_flow() {
        let eq = EulerPoissonHoop::new(&model());
        let x0 = EulerPoissonHoop::reduce(&crate::scenes::free_hoop::unflatten(&full_state()));
        let f = |y: &super::super::State| {
            let mut dy = super::super::State::zeros();
            eq.rhs(0.0, y, &mut dy);
            dy
        };
        check(&TaylorHoop::reduced(eq), f, x0);
    }

    /// On the full model: the coefficients against the full free hoop's right-hand side (the
    /// scene's own, through its coupled-body equations).
    #[test]
    fn full_coefficients_follow_the_full_models_right_hand_side_and_the_flow() {
        let model = model();
        let flat = FlatFreeHoop::new(model).unwrap();
        let f = |y: &SVector<f64, 14>| {
            let mut dy = SVector::<f64, 14>::zeros();
            flat.rhs(0.0, y, &mut dy);
            dy
        };
        check(
            &TaylorHoop::full(EulerPoissonHoop::new(&model)),
            f,
            full_state(),
        );
    }

    /// A singular point is a typed error, not a NaN: a NaN state's first coefficient says so.
    #[test]
    fn a_non_finite_state_is_an_error() {
        let eq = EulerPoissonHoop::new(&model());
        let mut x0 = [0.0; 8];
        x0[3] = f64::NAN;
        let mut c = vec![0.0; 3 * 8];
        let e = TaylorHoop::reduced(eq)
            .coefficients(0.0, &x0, 2, &mut c)
            .unwrap_err();
        assert!(matches!(e, TaylorError::NonFinite { order: 0, .. }), "{e}");
        // The full model alike, the NaN in Π_x (component 9).
        let mut x0 = [0.0; 14];
        x0[9] = f64::NAN;
        let mut c = vec![0.0; 3 * 14];
        let e = TaylorHoop::full(eq)
            .coefficients(0.0, &x0, 2, &mut c)
            .unwrap_err();
        assert!(
            matches!(
                e,
                TaylorError::NonFinite {
                    order: 0,
                    component: 9
                }
            ),
            "{e}"
        );
    }
}
