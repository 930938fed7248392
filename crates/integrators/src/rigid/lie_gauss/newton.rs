//! The simplified Newton iteration of the Lie–Gauss stages through the eigenbasis of the
//! Gauss matrix `A` (Hairer & Wanner, *Solving ODEs II*, §IV.8): `𝟙 − hA ⊗ J` applied as one
//! complex `d × d` inverse per conjugate pair of eigenvalues, the stages' response to the chart
//! momentum, and the last step's collocation polynomial carried into the next step's chart
//! as its starting guess ([`super`] module doc).
//!
//! # One simplified-Newton module for Gauss and Lie–Gauss?
//!
//! Both solve with `𝟙 − hA ⊗ J`. Gauss–Legendre ([`crate::gauss`]) factors the whole
//! `sn × sn` matrix by faer's LU once per step and applies it to one right-hand side per
//! iteration; Newton is its opt-in solver (fixed point is the default). Lie–Gauss applies the
//! inverse to the residual every iteration *and* to three more columns (`Y`, the stages'
//! response to `P₀`, for the 3 × 3 Schur complement), keeps the factorization across steps,
//! and so forms explicit inverses of the `s/2` complex `d × d` blocks of the eigenbasis and
//! applies them as matrix–vector products. The part the two could share is the eigenbasis of
//! `A` and `factor`/`apply_inverse` below; the rest (`Y`, the predictor, the chart moves) is
//! Lie–Gauss's own. Gauss is not moved onto it here: its Newton iterates would change in the
//! last bits (a different factorization rounds differently), and its outputs are kept
//! identical; moving it is a change of its own, measured against faer's LU on the scenes.

use nalgebra::{Matrix3, Vector3};

use tumble_kinematics::so3::{dexp as dexp_right, dexpinv, exp_quat, log_quat};

use crate::tables::GaussTableau;

pub(super) type C64 = nalgebra::Complex<f64>;

/// `W_u`, `W_P`, `W_ι`: how `u₁`, `P₁` and the impulse answer a change of `P₀` through the
/// stages, `h Σ bⱼ J₀[•, ·] Yⱼ` ([`solve`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Responses {
    pub(super) u: Matrix3<f64>,
    pub(super) p: Matrix3<f64>,
    pub(super) impulse: Matrix3<f64>,
}

/// The simplified Newton iteration's workspace: the eigendecomposition `A = T Λ T⁻¹` of the
/// tableau (formed once), the Jacobian `J₀` of the chart equations at the step's start, the
/// complex LU factors of `𝟙 − hλₖJ₀` (one `d × d` system per eigenvalue instead of one
/// `sd × sd` system), and `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`, the stages' response to the initial chart
/// momentum `P₀`. Allocated when the stepper is built, never in a step.
#[derive(Debug, Clone)]
pub(super) struct Newton<const S: usize> {
    pub(super) d: usize,
    pub(super) t: [[C64; S]; S],
    pub(super) t_inv: [[C64; S]; S],
    pub(super) lambda: [C64; S],
    /// 1 for a real eigenvalue, 2 for the first of a conjugate pair, 0 for the second.
    pub(super) weight: [f64; S],
    /// `(h, W)` of the factorization held, kept for the next step when it continues.
    pub(super) w: Option<(f64, Responses)>,
    pub(super) jac: Vec<f64>,
    /// `G = ∂(E M)/∂z` (3 × d, row-major), the rotated moment's dependence on a stage, and the
    /// rotated moment at the state where `J` was formed.
    pub(super) moment_jac: Vec<f64>,
    pub(super) moment_base: Vector3<f64>,
    pub(super) lu: Vec<C64>,
    pub(super) pivots: Vec<usize>,
    /// `(𝟙 − hλₖJ)⁻¹`, row-major, real and imaginary parts apart (`S d²` each), formed from
    /// the LU factors: an iteration applies it as one matrix–vector product per eigenvalue,
    /// whose rows are independent, instead of two triangular solves, whose are not.
    pub(super) inv_re: Vec<f64>,
    pub(super) inv_im: Vec<f64>,
    /// `T⁻¹ g` of one eigenvalue, real and imaginary parts (`d` each).
    pub(super) hat_re: Vec<f64>,
    pub(super) hat_im: Vec<f64>,
    /// `Y`, `S d × 3`, stage-major.
    pub(super) y: Vec<f64>,
    pub(super) hat: Vec<C64>,
    /// Stage values, rates, residuals, increments (`S d` each), one flat state (`d`).
    pub(super) z: Vec<f64>,
    pub(super) k: Vec<f64>,
    pub(super) g: Vec<f64>,
    pub(super) dz: Vec<f64>,
    pub(super) tmp: Vec<f64>,
    pub(super) tmp2: Vec<f64>,
    pub(super) tmp3: Vec<f64>,
    /// The start `z₀` (flat; its `P` block is `Π_k`, not the iterated `P₀`).
    pub(super) origin: Vec<f64>,
    /// The last step's solution, for the next step's starting guess: its stage values and its
    /// start `z₀` with the solved `P₀` (flat, in the last step's chart), and `(h, u₁)`.
    pub(super) last_z: Vec<f64>,
    pub(super) last_origin: Vec<f64>,
    pub(super) last: Option<(f64, Vector3<f64>)>,
    /// `ℓᵢⱼ`: the Lagrange basis of the nodes `0, c₁ … c_S` at `1 + cᵢ`, the last step's
    /// collocation polynomial carried into this step (`j = 0` the node 0, `j = m` the node `c_m`).
    pub(super) extrapolation: [[f64; S]; S],
    pub(super) extrapolation_origin: [f64; S],
    /// The same basis at `1`.
    pub(super) end: [f64; S],
    pub(super) end_origin: f64,
}

/// Whether a step of length `h` continues one of length `last` with the same step: equal to a
/// relative 1e-6. A fixed-step run takes `t_{k+1} − t_k` with `t_k = t₀ + k h`, whose rounding
/// moves the length by up to `ulp(t_k)` (relative `1e-10` at `t = 10⁴`, `h = 0.01`); the kept
/// Newton matrix and the carried polynomial are approximations far coarser than that.
pub(super) fn same_step(last: f64, h: f64) -> bool {
    (h - last).abs() <= 1e-6 * h.abs()
}

/// The Lagrange basis polynomial of node `m` of `0, c₁ … c_S` (node 0 is `0`) at `x`.
fn lagrange<const S: usize>(c: &[f64; S], m: usize, x: f64) -> f64 {
    let node = |j: usize| if j == 0 { 0.0 } else { c[j - 1] };
    (0..=S)
        .filter(|&j| j != m)
        .map(|j| (x - node(j)) / (node(m) - node(j)))
        .product()
}

impl<const S: usize> Newton<S> {
    /// Drops what the next step would carry over from the last: its Newton matrix and its
    /// collocation polynomial.
    pub(super) fn forget(&mut self) {
        self.w = None;
        self.last = None;
    }

    /// Starting stages for a step of length `h` that continues the last step with the same
    /// `h`: the last step's collocation polynomial (through its start and its stages) at
    /// `1 + cᵢ`, moved into this step's chart — `u` by `log(E₁ᵀ exp(hat u))`, the chart
    /// momentum through the body momentum `Π = J_r(u)⁻ᵀ P` it represents, `P' = J_r(u')ᵀ Π` —
    /// and returns the step's `P₀` guess, the body momentum of that polynomial at `1`. `None`
    /// (and nothing written) when there is no such last step.
    pub(super) fn predict(&mut self, h: f64, pcol: usize) -> Option<Vector3<f64>> {
        let (h_last, u1) = self.last?;
        if !same_step(h_last, h) {
            return None;
        }
        let d = self.d;
        let back = exp_quat(&u1).inverse();
        let to_chart = |v: &mut [f64]| {
            let u_old = Vector3::new(v[0], v[1], v[2]);
            let p_old = Vector3::new(v[pcol], v[pcol + 1], v[pcol + 2]);
            let pi = dexpinv(&u_old).transpose() * p_old;
            let u_new = log_quat(&(back * exp_quat(&u_old)));
            let p_new = dexp_right(&u_new).transpose() * pi;
            v[..3].copy_from_slice(u_new.as_slice());
            v[pcol..pcol + 3].copy_from_slice(p_new.as_slice());
        };
        for i in 0..S {
            for c in 0..d {
                let mut acc = self.extrapolation_origin[i] * self.last_origin[c];
                for m in 0..S {
                    acc += self.extrapolation[i][m] * self.last_z[m * d + c];
                }
                self.z[i * d + c] = acc;
            }
            to_chart(&mut self.z[i * d..(i + 1) * d]);
        }
        // P₀: the polynomial's body momentum at 1 (in the new chart u = 0, where P = Π).
        let mut end = [0.0; 3];
        let mut u_end = [0.0; 3];
        for (b, (e, ue)) in end.iter_mut().zip(u_end.iter_mut()).enumerate() {
            *e = self.end_origin * self.last_origin[pcol + b];
            *ue = self.end_origin * self.last_origin[b];
            for m in 0..S {
                *e += self.end[m] * self.last_z[m * d + pcol + b];
                *ue += self.end[m] * self.last_z[m * d + b];
            }
        }
        Some(dexpinv(&Vector3::from(u_end)).transpose() * Vector3::from(end))
    }

    pub(super) fn new(table: &GaussTableau<S>, n: usize) -> Self {
        let d = 6 + 2 * n;
        let a = faer::Mat::<f64>::from_fn(S, S, |i, j| table.a[i][j]);
        // The Gauss–Legendre matrices have S distinct eigenvalues (their reciprocals are the
        // roots of the Padé denominator), so A is diagonalizable. Complex eigenvalues come in
        // conjugate pairs; T is built with conjugate columns for each pair, so that for a real
        // right-hand side the solution of the conjugate system is the conjugate, and only one
        // system per pair is solved (`weight` 2, the other `weight` 0).
        let zero = C64::new(0.0, 0.0);
        let mut t = [[zero; S]; S];
        let mut lambda = [zero; S];
        let mut weight = [0.0; S];
        if let Ok(e) = a.eigen() {
            let mut col = 0;
            for k in 0..S {
                let l = e.S()[k];
                if l.im < -1e-12 || col >= S {
                    continue;
                }
                let complex = l.im > 1e-12;
                for i in 0..S {
                    t[i][col] = e.U()[(i, k)];
                }
                lambda[col] = l;
                weight[col] = if complex { 2.0 } else { 1.0 };
                col += 1;
                if complex && col < S {
                    for i in 0..S {
                        t[i][col] = e.U()[(i, k)].conj();
                    }
                    lambda[col] = l.conj();
                    col += 1;
                }
            }
        }
        let tm = nalgebra::DMatrix::<C64>::from_fn(S, S, |i, j| t[i][j]);
        let ti = tm
            .try_inverse()
            .unwrap_or_else(|| nalgebra::DMatrix::zeros(S, S));
        Self {
            d,
            t,
            t_inv: std::array::from_fn(|i| std::array::from_fn(|j| ti[(i, j)])),
            lambda,
            weight,
            w: None,
            jac: vec![0.0; d * d],
            moment_jac: vec![0.0; 3 * d],
            moment_base: Vector3::zeros(),
            lu: vec![C64::new(0.0, 0.0); S * d * d],
            pivots: vec![0; S * d],
            inv_re: vec![0.0; S * d * d],
            inv_im: vec![0.0; S * d * d],
            hat_re: vec![0.0; d],
            hat_im: vec![0.0; d],
            y: vec![0.0; S * d * 3],
            hat: vec![C64::new(0.0, 0.0); S * d],
            z: vec![0.0; S * d],
            k: vec![0.0; S * d],
            g: vec![0.0; S * d],
            dz: vec![0.0; S * d],
            tmp: vec![0.0; d],
            tmp2: vec![0.0; d],
            tmp3: vec![0.0; d],
            origin: vec![0.0; d],
            last_z: vec![0.0; S * d],
            last_origin: vec![0.0; d],
            last: None,
            extrapolation: std::array::from_fn(|i| {
                std::array::from_fn(|m| lagrange(&table.c, m + 1, 1.0 + table.c[i]))
            }),
            extrapolation_origin: std::array::from_fn(|i| lagrange(&table.c, 0, 1.0 + table.c[i])),
            end: std::array::from_fn(|m| lagrange(&table.c, m + 1, 1.0)),
            end_origin: lagrange(&table.c, 0, 1.0),
        }
    }

    /// Factors `𝟙 − hλₖJ₀` for every eigenvalue (partial pivoting) and forms its inverse from
    /// the factors; `false` if one is singular.
    pub(super) fn factor(&mut self, h: f64) -> bool {
        let d = self.d;
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            let m = &mut self.lu[k * d * d..(k + 1) * d * d];
            let piv = &mut self.pivots[k * d..(k + 1) * d];
            let hl = self.lambda[k] * h;
            for i in 0..d {
                for j in 0..d {
                    let id = if i == j { 1.0 } else { 0.0 };
                    m[i * d + j] = C64::new(id, 0.0) - hl * self.jac[i * d + j];
                }
            }
            for col in 0..d {
                let mut p = col;
                for row in col + 1..d {
                    if m[row * d + col].l1_norm() > m[p * d + col].l1_norm() {
                        p = row;
                    }
                }
                piv[col] = p;
                if !(m[p * d + col].l1_norm() > 0.0) {
                    return false;
                }
                if p != col {
                    for j in 0..d {
                        m.swap(p * d + j, col * d + j);
                    }
                }
                let inv = C64::new(1.0, 0.0) / m[col * d + col];
                for row in col + 1..d {
                    let f = m[row * d + col] * inv;
                    m[row * d + col] = f;
                    for j in col + 1..d {
                        let v = m[col * d + j];
                        m[row * d + j] -= f * v;
                    }
                }
            }
            // Column e of the inverse: the permuted unit vector through both triangles.
            let x = &mut self.hat[k * d..(k + 1) * d];
            for e in 0..d {
                x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
                x[e] = C64::new(1.0, 0.0);
                for col in 0..d {
                    x.swap(col, piv[col]);
                }
                for i in 0..d {
                    let mut acc = x[i];
                    for j in 0..i {
                        acc -= m[i * d + j] * x[j];
                    }
                    x[i] = acc;
                }
                for i in (0..d).rev() {
                    let mut acc = x[i];
                    for j in i + 1..d {
                        acc -= m[i * d + j] * x[j];
                    }
                    x[i] = acc / m[i * d + i];
                }
                for (i, v) in x.iter().enumerate() {
                    self.inv_re[k * d * d + i * d + e] = v.re;
                    self.inv_im[k * d * d + i * d + e] = v.im;
                }
            }
        }
        true
    }

    /// `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`, `E` the unit vectors of the `P` block (`pcol …`) at every stage:
    /// `T⁻¹` maps such a column to `(Σᵢ (T⁻¹)ₖᵢ) e`, so `Y`'s column `c` is
    /// `Yⱼ = Σₖ wₖ Re(Tⱼₖ (Σᵢ (T⁻¹)ₖᵢ) (𝟙 − hλₖJ₀)⁻¹ e_{pcol + c})`, a column of each inverse.
    pub(super) fn respond_to_momentum(&mut self, pcol: usize) {
        let d = self.d;
        self.y.iter_mut().for_each(|x| *x = 0.0);
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            let sum: C64 = self.t_inv[k].iter().sum();
            for c in 0..3 {
                for r in 0..d {
                    let at = k * d * d + r * d + pcol + c;
                    let x = sum * C64::new(self.inv_re[at], self.inv_im[at]);
                    for j in 0..S {
                        self.y[(j * d + r) * 3 + c] += self.weight[k] * (self.t[j][k] * x).re;
                    }
                }
            }
        }
    }

    /// `dz = (𝟙 − hA ⊗ J₀)⁻¹ g` (both `S d`, stage-major) through the eigenbasis of `A`:
    /// `dz_i = Σₖ wₖ Re(Tᵢₖ (𝟙 − hλₖJ₀)⁻¹ Σⱼ (T⁻¹)ₖⱼ gⱼ)`.
    pub(super) fn apply_inverse(&mut self) {
        let d = self.d;
        self.dz.iter_mut().for_each(|x| *x = 0.0);
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            for c in 0..d {
                let (mut re, mut im) = (0.0, 0.0);
                for i in 0..S {
                    re += self.t_inv[k][i].re * self.g[i * d + c];
                    im += self.t_inv[k][i].im * self.g[i * d + c];
                }
                self.hat_re[c] = re;
                self.hat_im[c] = im;
            }
            let mr = &self.inv_re[k * d * d..(k + 1) * d * d];
            let mi = &self.inv_im[k * d * d..(k + 1) * d * d];
            for c in 0..d {
                let (rr, ri) = (&mr[c * d..(c + 1) * d], &mi[c * d..(c + 1) * d]);
                let (mut xr, mut xi) = (0.0, 0.0);
                for (((a, b), x), y) in rr.iter().zip(ri).zip(&self.hat_re).zip(&self.hat_im) {
                    xr += a * x - b * y;
                    xi += a * y + b * x;
                }
                let w = self.weight[k];
                for i in 0..S {
                    let t = self.t[i][k];
                    self.dz[i * d + c] += w * (t.re * xr - t.im * xi);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::gauss::{GAUSS4, GAUSS6, GAUSS8, GAUSS10};

    #[test]
    fn eigenbasis_solve_equals_the_dense_solve_of_the_newton_matrix() {
        use crate::tables::gauss::{GAUSS6, GAUSS8, GAUSS10};
        fn check<const S: usize>(table: &GaussTableau<S>) {
            let mut newton = Newton::<S>::new(table, 1);
            let d = newton.d;
            // A Jacobian with rotation-like and dissipative parts.
            for r in 0..d {
                for c in 0..d {
                    newton.jac[r * d + c] = ((r * 7 + c * 3) % 11) as f64 / 5.0 - 1.0;
                }
            }
            let h = 0.3;
            assert!(newton.factor(h));
            for x in 0..S * d {
                newton.g[x] = ((x * 5) % 13) as f64 / 6.0 - 1.0;
            }
            newton.apply_inverse();
            let n = S * d;
            let m = nalgebra::DMatrix::<f64>::from_fn(n, n, |row, col| {
                let (i, a) = (row / d, row % d);
                let (j, b) = (col / d, col % d);
                let id = if row == col { 1.0 } else { 0.0 };
                id - h * table.a[i][j] * newton.jac[a * d + b]
            });
            let g = nalgebra::DVector::from_column_slice(&newton.g);
            let lu = m.lu();
            let x = lu.solve(&g).unwrap();
            let err = (0..n)
                .map(|k| (x[k] - newton.dz[k]).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-12 * x.amax(), "S = {S}: {err:e}");
            // The response to the P block, Y = (𝟙 − hA ⊗ J)⁻¹ E, column by column.
            let pcol = 4;
            newton.respond_to_momentum(pcol);
            for c in 0..3 {
                let e = nalgebra::DVector::from_fn(
                    n,
                    |row, _| {
                        if row % d == pcol + c { 1.0 } else { 0.0 }
                    },
                );
                let y = lu.solve(&e).unwrap();
                let err = (0..n)
                    .map(|k| (y[k] - newton.y[k * 3 + c]).abs())
                    .fold(0.0, f64::max);
                assert!(err < 1e-12 * y.amax(), "S = {S}, Y column {c}: {err:e}");
            }
        }
        check(&GAUSS6);
        check(&GAUSS8);
        check(&GAUSS10);
    }

    #[test]
    fn extrapolation_basis_reproduces_polynomials_of_degree_s() {
        fn check<const S: usize>(table: &GaussTableau<S>) {
            let newton = Newton::<S>::new(table, 0);
            // A polynomial of degree S with coefficients of both signs.
            let p = |x: f64| (0..=S).fold(0.0, |acc, k| acc * x + (0.37 * k as f64 - 0.5));
            let carried = |origin: f64, basis: &[f64; S], x: f64| {
                let v = origin * p(0.0) + (0..S).map(|m| basis[m] * p(table.c[m])).sum::<f64>();
                assert!(
                    (v - p(x)).abs() < 1e-12 * p(x).abs().max(1.0),
                    "S = {S} at {x}"
                );
            };
            for i in 0..S {
                carried(
                    newton.extrapolation_origin[i],
                    &newton.extrapolation[i],
                    1.0 + table.c[i],
                );
            }
            carried(newton.end_origin, &newton.end, 1.0);
        }
        check(&GAUSS4);
        check(&GAUSS6);
        check(&GAUSS8);
        check(&GAUSS10);
    }
}
