//! Taylor-mode automatic differentiation on a [`Tape`]: the normalized Taylor coefficients
//! `uₖ = u⁽ᵏ⁾(t₀)/k!` of every node along series of the inputs, one order at a time.
//!
//! Each node's coefficient of order `k` follows from its operands' coefficients of orders
//! `0 ..= k` (and its own of orders below `k`) by the recursions of automatic differentiation
//! (Moore 1966, ch. 11; Griewank & Walther 2008, ch. 13; Jorba & Zou 2005, §3):
//!
//! | node | recursion (`k ≥ 1`) |
//! |---|---|
//! | `a ± b`, `−a` | `aₖ ± bₖ`, `−aₖ` |
//! | `a · b` | `Σⱼ₌₀ᵏ aⱼ bₖ₋ⱼ` (Cauchy product; `a₀ bₖ` when `a` is constant) |
//! | `a / b` | `(aₖ − Σⱼ₌₁ᵏ bⱼ uₖ₋ⱼ) / b₀` |
//! | `eᵃ` | `(1/k) Σⱼ₌₁ᵏ j aⱼ uₖ₋ⱼ` |
//! | `ln a` | `(aₖ − (1/k) Σⱼ₌₁ᵏ⁻¹ j uⱼ aₖ₋ⱼ) / a₀` |
//! | `√a` | `(aₖ − Σⱼ₌₁ᵏ⁻¹ uⱼ uₖ₋ⱼ) / (2 u₀)` |
//! | `sin a`, `cos a` | the pair `s' = c a'`, `c' = −s a'`: `sₖ = (1/k) Σ j aⱼ cₖ₋ⱼ`, `cₖ = −(1/k) Σ j aⱼ sₖ₋ⱼ` |
//! | `sinh a`, `cosh a` | the pair `s' = c a'`, `c' = s a'` |
//! | `tan a`, `tanh a` | `u' = v a'` with `v = 1 ± u²` carried along |
//! | `atan a` | `v u' = a'` with `v = 1 + a²` |
//! | `asin a`, `acos a` | `w u' = ±a'` with `w = √(1 − a²)` carried along |
//! | `atan2(y, x)` | `v u' = x y' − y x'` with `v = x² + y²` |
//! | `aⁿ`, `n ≥ 2` | repeated Cauchy products (exact where `a₀ = 0`) |
//! | `aⁿ`, `n < 0` | `uₖ = (1/(k a₀)) Σⱼ₌₀ᵏ⁻¹ (n(k − j) − j) aₖ₋ⱼ uⱼ` |
//! | `aᵇ` | `exp(b ln a)`, with `ln a` and `b ln a` carried along |
//! | `\|a\|` | `σ aₖ`, `σ` the sign of the first non-zero coefficient of `a` (piecewise) |
//! | `sign a` | `0` (piecewise constant) |
//!
//! Order 0 is each node's value, computed with the same `f64` functions as [`Tape::run`].
//! Nodes of the prelude (depending on parameters only) and fixed inputs are constant series,
//! set once; time is the series `t₀ + h`. Storage — a series of `max_order + 1` numbers per
//! slot and per auxiliary series — is allocated once by [`TaylorWork::new`].
//!
//! # References
//! - R. E. Moore, *Interval Analysis*, Prentice-Hall 1966.
//! - A. Griewank, A. Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008, ch. 13.
//! - À. Jorba, M. Zou, *A software package for the numerical integration of ODEs by means of
//!   high-order Taylor methods*, Experimental Mathematics 14 (2005) 99–117.

use super::Fun;
use super::scalar::TapeScalar;
use super::tape::{Op, Tape};

/// What the series recursions need of a tape besides its instructions: which operands are
/// constant series, and where each instruction's auxiliary series are.
#[derive(Debug, Clone, PartialEq)]
pub struct TaylorPlan {
    /// Inputs `0 .. varying_inputs` are series set by the caller; the rest are constant.
    varying_inputs: usize,
    /// Per body instruction: whether operands `a` and `b` are constant series.
    constant: Vec<(bool, bool)>,
    /// Per body instruction: the index of its first auxiliary series.
    aux: Vec<u32>,
    /// Number of auxiliary series.
    aux_len: usize,
}

impl TaylorPlan {
    /// The plan of `tape`, whose inputs `0 .. varying_inputs` vary (time, coordinates, rates)
    /// and whose other inputs are fixed (parameters, set once).
    #[must_use]
    pub fn new(tape: &Tape, varying_inputs: usize) -> Self {
        let mut varying = vec![false; tape.slots];
        for v in varying.iter_mut().take(varying_inputs.min(tape.slots)) {
            *v = true;
        }
        for ins in &tape.body {
            varying[ins.dst as usize] = true;
        }
        let mut constant = Vec::with_capacity(tape.body.len());
        let mut aux = Vec::with_capacity(tape.body.len());
        let mut aux_len = 0usize;
        for ins in &tape.body {
            constant.push((!varying[ins.a as usize], !varying[ins.b as usize]));
            aux.push(aux_len as u32);
            aux_len += match ins.op {
                Op::Call(
                    Fun::Sin
                    | Fun::Cos
                    | Fun::Sinh
                    | Fun::Cosh
                    | Fun::Tan
                    | Fun::Tanh
                    | Fun::Atan
                    | Fun::Asin
                    | Fun::Acos,
                )
                | Op::Atan2 => 1,
                Op::Pow => 2,
                Op::Powi(n) if n > 2 => (n - 2) as usize,
                _ => 0,
            };
        }
        TaylorPlan {
            varying_inputs,
            constant,
            aux,
            aux_len,
        }
    }
}

/// The series of every slot of a tape (slot-major: slot `s`, order `k` at `s · stride + k`)
/// and the auxiliary series, for orders up to `stride − 1`, in the scalar `S` (`f64`, or
/// [`tumble_integrators::taylor::DoubleDouble`] for references).
#[derive(Debug, Clone)]
pub struct TaylorWork<S = f64> {
    stride: usize,
    series: Vec<S>,
    aux: Vec<S>,
}

impl<S: TapeScalar> TaylorWork<S> {
    /// Storage for orders `0 ..= max_order` (the one allocation), with the fixed inputs set
    /// from `fixed[k]` (for input `k ≥ varying_inputs`) and the prelude run: constant series.
    ///
    /// The prelude (nodes of the parameters only) runs in `S` too: the parameters' values are
    /// the problem's data, and what is computed from them (an inverse inertia, a frequency) is
    /// computed in the expansion's precision.
    #[must_use]
    pub fn new(tape: &Tape, plan: &TaylorPlan, fixed: &[f64], max_order: usize) -> Self {
        let stride = max_order + 1;
        let mut scalar = vec![S::ZERO; tape.slots];
        let m = fixed.len().min(tape.inputs);
        let from = plan.varying_inputs.min(m);
        for (w, v) in scalar[from..m].iter_mut().zip(&fixed[from..m]) {
            *w = S::of(*v);
        }
        tape.run_prelude_in(&mut scalar);
        let mut series = vec![S::ZERO; tape.slots * stride];
        for (s, v) in scalar.iter().enumerate() {
            series[s * stride] = *v;
        }
        TaylorWork {
            stride,
            series,
            aux: vec![S::ZERO; plan.aux_len * stride],
        }
    }

    /// The largest order this storage holds.
    #[must_use]
    pub fn max_order(&self) -> usize {
        self.stride - 1
    }

    /// Sets coefficient `k` of varying input `input`.
    #[inline]
    pub fn set_input(&mut self, input: usize, k: usize, value: S) {
        self.series[input * self.stride + k] = value;
    }

    /// Coefficient `k` of output `i` of `tape`.
    #[inline]
    #[must_use]
    pub fn output(&self, tape: &Tape, i: usize, k: usize) -> S {
        self.series[tape.outputs[i] as usize * self.stride + k]
    }

    /// Computes coefficient `k` of every body node, after coefficient `k` of every varying
    /// input is set (and coefficients below `k` were computed by earlier calls).
    pub fn run_order(&mut self, tape: &Tape, plan: &TaylorPlan, k: usize) {
        let st = self.stride;
        let s = &mut self.series;
        let x = &mut self.aux;
        let kf = S::of(k as f64);
        for (idx, ins) in tape.body.iter().enumerate() {
            let (a, b, d) = (
                ins.a as usize * st,
                ins.b as usize * st,
                ins.dst as usize * st,
            );
            let (ca, cb) = plan.constant[idx];
            let e = plan.aux[idx] as usize * st;
            let v = match ins.op {
                Op::Const(c) => {
                    if k == 0 {
                        S::of(c)
                    } else {
                        S::ZERO
                    }
                }
                Op::Add => s[a + k] + s[b + k],
                Op::Sub => s[a + k] - s[b + k],
                Op::Neg => -s[a + k],
                Op::Mul => {
                    if ca {
                        s[a] * s[b + k]
                    } else if cb {
                        s[a + k] * s[b]
                    } else {
                        cauchy(s, a, s, b, k)
                    }
                }
                Op::Div => {
                    if cb {
                        s[a + k].quotient(s[b])
                    } else {
                        let mut acc = s[a + k];
                        for j in 1..=k {
                            acc = acc - s[b + j] * s[d + k - j];
                        }
                        acc.quotient(s[b])
                    }
                }
                Op::Powi(n) => powi(s, x, a, d, e, st, n, k),
                Op::Pow => {
                    // L = ln a at e, M = b L at e + st, u = exp(M).
                    let (l, m) = (e, e + st);
                    if k == 0 {
                        x[l] = s[a].fun(Fun::Log);
                        x[m] = s[b] * x[l];
                        s[a].real_pow(s[b])
                    } else {
                        x[l + k] = log_k(x, l, s, a, k);
                        x[m + k] = if cb {
                            s[b] * x[l + k]
                        } else {
                            cauchy(s, b, x, l, k)
                        };
                        weighted(x, m, s, d, k).quotient(kf)
                    }
                }
                Op::Atan2 => {
                    // y = a, x = b; v = x² + y² at e.
                    if k == 0 {
                        x[e] = s[b] * s[b] + s[a] * s[a];
                        s[a].atan2_with(s[b])
                    } else {
                        x[e + k] = cauchy(s, b, s, b, k) + cauchy(s, a, s, a, k);
                        let mut num = S::ZERO;
                        for j in 0..k {
                            let w = S::of((k - j) as f64);
                            num += w * (s[b + j] * s[a + k - j] - s[a + j] * s[b + k - j]);
                        }
                        for i in 1..k {
                            num = num - S::of(i as f64) * s[d + i] * x[e + k - i];
                        }
                        num.quotient(kf * x[e])
                    }
                }
                Op::Call(f) => call(f, s, x, a, d, e, k),
            };
            s[d + k] = v;
        }
    }
}

/// `Σⱼ₌₀ᵏ pⱼ qₖ₋ⱼ` of the series at `p[i..]` and `q[j..]`.
#[inline]
fn cauchy<S: TapeScalar>(p: &[S], i: usize, q: &[S], j: usize, k: usize) -> S {
    let mut acc = S::ZERO;
    for m in 0..=k {
        acc += p[i + m] * q[j + k - m];
    }
    acc
}

/// `Σⱼ₌₁ᵏ j aⱼ vₖ₋ⱼ` of the series `a` at `p[i..]` and `v` at `q[j..]`: `k uₖ` for `u' = v a'`.
#[inline]
fn weighted<S: TapeScalar>(p: &[S], i: usize, q: &[S], j: usize, k: usize) -> S {
    let mut acc = S::ZERO;
    for m in 1..=k {
        acc += S::of(m as f64) * p[i + m] * q[j + k - m];
    }
    acc
}

/// Coefficient `k ≥ 1` of `ln a`, whose lower coefficients are at `u[l..]`, `a` at `s[a..]`.
#[inline]
fn log_k<S: TapeScalar>(u: &[S], l: usize, s: &[S], a: usize, k: usize) -> S {
    let mut acc = S::ZERO;
    for j in 1..k {
        acc += S::of(j as f64) * u[l + j] * s[a + k - j];
    }
    (s[a + k] - acc.quotient(S::of(k as f64))).quotient(s[a])
}

/// Coefficient `k` of `aⁿ` (result at `s[d..]`, the chain `a², …, aⁿ⁻¹` at `x[e..]`).
#[allow(clippy::too_many_arguments)]
fn powi<S: TapeScalar>(
    s: &mut [S],
    x: &mut [S],
    a: usize,
    d: usize,
    e: usize,
    st: usize,
    n: i32,
    k: usize,
) -> S {
    if n < 0 {
        if k == 0 {
            return s[a].int_pow(n);
        }
        let r = f64::from(n);
        let mut acc = S::ZERO;
        for j in 0..k {
            acc += S::of(r * (k - j) as f64 - j as f64) * s[a + k - j] * s[d + j];
        }
        return acc.quotient(S::of(k as f64) * s[a]);
    }
    // n ≥ 2: p₂ = a·a, p_m = p_{m−1}·a; p_m (2 ≤ m < n) at x[e + (m − 2) st].
    let mut prev: Option<usize> = None;
    for m in 2..n {
        let at = e + (m as usize - 2) * st;
        x[at + k] = match prev {
            None => cauchy(s, a, s, a, k),
            Some(p) => cauchy(x, p, s, a, k),
        };
        prev = Some(at);
    }
    match prev {
        None => cauchy(s, a, s, a, k),
        Some(p) => cauchy(x, p, s, a, k),
    }
}

/// Coefficient `k` of `f(a)` (result at `s[d..]`, its auxiliary series at `x[e..]`).
fn call<S: TapeScalar>(f: Fun, s: &[S], x: &mut [S], a: usize, d: usize, e: usize, k: usize) -> S {
    let a0 = s[a];
    let kf = S::of(k as f64);
    let one = S::of(1.0);
    if k == 0 {
        match f {
            Fun::Sin => x[e] = a0.fun(Fun::Cos),
            Fun::Cos => x[e] = a0.fun(Fun::Sin),
            Fun::Sinh => x[e] = a0.fun(Fun::Cosh),
            Fun::Cosh => x[e] = a0.fun(Fun::Sinh),
            Fun::Tan => {
                let u = a0.fun(Fun::Tan);
                x[e] = one + u * u;
            }
            Fun::Tanh => {
                let u = a0.fun(Fun::Tanh);
                x[e] = one - u * u;
            }
            Fun::Atan => x[e] = one + a0 * a0,
            Fun::Asin | Fun::Acos => x[e] = (one - a0 * a0).fun(Fun::Sqrt),
            Fun::Sqrt | Fun::Exp | Fun::Log | Fun::Abs | Fun::Sign => {}
        }
        return a0.fun(f);
    }
    match f {
        Fun::Exp => weighted(s, a, s, d, k).quotient(kf),
        Fun::Log => log_k(s, d, s, a, k),
        Fun::Sqrt => {
            let mut acc = s[a + k];
            for j in 1..k {
                acc = acc - s[d + j] * s[d + k - j];
            }
            acc.quotient(S::of(2.0) * s[d])
        }
        Fun::Sin | Fun::Sinh => {
            // u' = c a', c' = ∓u a'.
            let u = weighted(s, a, x, e, k).quotient(kf);
            let c = weighted(s, a, s, d, k).quotient(kf);
            x[e + k] = if f == Fun::Sin { -c } else { c };
            u
        }
        Fun::Cos | Fun::Cosh => {
            // For cos: sn' = u a', u' = −sn a'; for cosh: u' = sn a'.
            let w = weighted(s, a, x, e, k).quotient(kf);
            x[e + k] = weighted(s, a, s, d, k).quotient(kf);
            if f == Fun::Cos { -w } else { w }
        }
        Fun::Tan | Fun::Tanh => {
            let u = weighted(s, a, x, e, k).quotient(kf);
            // v = 1 ± u², its coefficient k from u₀ … uₖ.
            let mut sq = S::of(2.0) * s[d] * u;
            for j in 1..k {
                sq += s[d + j] * s[d + k - j];
            }
            x[e + k] = if f == Fun::Tan { sq } else { -sq };
            u
        }
        Fun::Atan => {
            x[e + k] = cauchy(s, a, s, a, k);
            let mut acc = S::ZERO;
            for i in 1..k {
                acc += S::of(i as f64) * s[d + i] * x[e + k - i];
            }
            (s[a + k] - acc.quotient(kf)).quotient(x[e])
        }
        Fun::Asin | Fun::Acos => {
            // w² = 1 − a².
            let mut acc = -cauchy(s, a, s, a, k);
            for j in 1..k {
                acc = acc - x[e + j] * x[e + k - j];
            }
            x[e + k] = acc.quotient(S::of(2.0) * x[e]);
            let mut sum = S::ZERO;
            for i in 1..k {
                sum += S::of(i as f64) * s[d + i] * x[e + k - i];
            }
            let ak = if f == Fun::Asin { s[a + k] } else { -s[a + k] };
            (ak - sum.quotient(kf)).quotient(x[e])
        }
        Fun::Abs => {
            let sign = (0..=k)
                .map(|j| s[a + j].leading())
                .find(|c| *c != 0.0)
                .map_or(0.0, f64::signum);
            S::of(sign) * s[a + k]
        }
        Fun::Sign => S::ZERO,
    }
}
