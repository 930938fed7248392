//! Symmetric composition coefficients.
//!
//! A composition of a one-step method `Φ_h` with coefficients `γ₁ … γ_m`,
//! `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}`, with `Σ γᵢ = 1` and `γᵢ = γ_{m+1−i}` (symmetric),
//! is symmetric, and if `Φ` is symmetric of order 2 the order conditions reduce to
//! `Σ γᵢ = 1` and conditions on odd powers; each table below reaches the order in its name.
//! All tables are listed in the order the substeps are taken; symmetric tables read the
//! same both ways.
//!
//! Where the paper defines a coefficient by an equation (Yoshida 4, Suzuki 4, McLachlan 4)
//! or published fewer than 20 digits (Yoshida 8), the literals were computed at 60 digits
//! by `crates/integrators/tools/gen_tables.py`, which also checks every table's order
//! conditions in a faithful matrix representation of the free Lie algebra (residuals below
//! 1e-26 for the 26-digit published tables, below 1e-58 for the generated ones). The middle
//! coefficient of Yoshida's and McLachlan's tables is derived, `γ₀ = 1 − 2 Σ γᵢ`.
//!
//! # References
//! - H. Yoshida, *Construction of higher order symplectic integrators*, Phys. Lett. A 150
//!   (1990) 262–268 (triple jump; order 6 solution A; order 8 solution D).
//! - M. Suzuki, *Fractal decomposition of exponential operators with applications to
//!   many-body theories and Monte Carlo simulations*, Phys. Lett. A 146 (1990) 319–323.
//! - R. I. McLachlan, *On the numerical integration of ordinary differential equations by
//!   symmetric composition methods*, SIAM J. Sci. Comput. 16 (1995) 151–168 (order 4 with
//!   5 stages, `γ₁ = 0.28`).
//! - W. Kahan, R.-C. Li, *Composition constants for raising the orders of unconventional
//!   schemes for ordinary differential equations*, Math. Comp. 66 (1997) 1089–1099
//!   (`s9odr6a`, `s17odr8a`).
//! - M. Sofroniou, G. Spaletta, *Derivation of symmetric composition constants for
//!   symmetric integrators*, Optim. Methods Softw. 20 (2005) 597–613 (`s35odr10`).
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., §V.3.2,
//!   where the 26-digit values of Yoshida 6, Kahan–Li 6/8 are reprinted.

use super::CompositionTable;

/// `[w_h … w_1, 1 − 2Σw, w_1 … w_h]` from `[w_h … w_1]` (outermost first).
const fn with_middle<const H: usize, const N: usize>(half: [f64; H]) -> [f64; N] {
    assert!(N == 2 * H + 1);
    let mut out = [0.0; N];
    let mut sum = 0.0;
    let mut i = 0;
    while i < H {
        out[i] = half[i];
        out[N - 1 - i] = half[i];
        sum += half[i];
        i += 1;
    }
    out[H] = 1.0 - 2.0 * sum;
    out
}

/// `[g_1 … g_h, g_{h−1} … g_1]` from `[g_1 … g_h]` (the last entry is the middle one).
const fn palindrome<const H: usize, const N: usize>(half: [f64; H]) -> [f64; N] {
    assert!(N == 2 * H - 1);
    let mut out = [0.0; N];
    let mut i = 0;
    while i < H {
        out[i] = half[i];
        out[N - 1 - i] = half[i];
        i += 1;
    }
    out
}

const YOSHIDA4_GAMMAS: [f64; 3] = with_middle([1.35120719195965763404768780897]);

/// Yoshida's (and Suzuki's, Forest–Ruth's) triple jump, order 4:
/// `γ₁ = γ₃ = 1/(2 − 2^{1/3})`, `γ₂ = 1 − 2γ₁ = −2^{1/3}/(2 − 2^{1/3})`.
pub const YOSHIDA4: CompositionTable = CompositionTable {
    name: "yoshida4",
    order: 4,
    gammas: &YOSHIDA4_GAMMAS,
};

const SUZUKI4_P: f64 = 0.414490771794375737142354062861;
const SUZUKI4_GAMMAS: [f64; 5] = with_middle([SUZUKI4_P, SUZUKI4_P]);

/// Suzuki's fractal, order 4 with 5 stages: `γ = (p, p, 1 − 4p, p, p)`,
/// `p = 1/(4 − 4^{1/3})`.
pub const SUZUKI4: CompositionTable = CompositionTable {
    name: "suzuki4",
    order: 4,
    gammas: &SUZUKI4_GAMMAS,
};

const MCLACHLAN4_GAMMAS: [f64; 5] = with_middle([0.28, 0.625466428467670045012338905493]);

/// McLachlan's 5-stage method of order 4 (small error constant): `γ₁ = γ₅ = 0.28`,
/// `γ₂ = γ₄` the root near 0.6255 of `2γ₁³ + 2γ₂³ + (1 − 2γ₁ − 2γ₂)³ = 0`,
/// `γ₃ = 1 − 2(γ₁ + γ₂)`.
pub const MCLACHLAN4: CompositionTable = CompositionTable {
    name: "mclachlan4",
    order: 4,
    gammas: &MCLACHLAN4_GAMMAS,
};

const YOSHIDA6_GAMMAS: [f64; 7] = with_middle([
    0.784513610477557263819497633866,
    0.235573213359358133684793182979,
    -1.17767998417887100694641568096,
]);

/// Yoshida's order-6 solution A (7 stages).
pub const YOSHIDA6: CompositionTable = CompositionTable {
    name: "yoshida6",
    order: 6,
    gammas: &YOSHIDA6_GAMMAS,
};

const YOSHIDA8_GAMMAS: [f64; 15] = with_middle([
    0.914844246229791566748793489848,
    0.253693336566211354146146020690,
    -1.44485223686060515769473065754,
    -0.158240635368050175204066776760,
    1.93813913762252598657918648744,
    -1.96061023297531080760763337640,
    0.102799849391796440698115131601,
]);

/// Yoshida's order-8 solution D (15 stages). Yoshida published 15 digits whose order
/// conditions hold only to about 1e-12; these are the exact solution nearest to them,
/// refined by Gauss–Newton at 60 digits (`tools/gen_tables.py`). They agree with the
/// published values to 12–13 significant digits.
pub const YOSHIDA8: CompositionTable = CompositionTable {
    name: "yoshida8",
    order: 8,
    gammas: &YOSHIDA8_GAMMAS,
};

const KAHAN_LI6_GAMMAS: [f64; 9] = palindrome([
    0.39216144400731413927925056,
    0.33259913678935943859974864,
    -0.70624617255763935980996482,
    0.08221359629355080023149045,
    0.79854399093482996339895035,
]);

/// Kahan and Li's `s9odr6a`: order 6 with 9 stages.
pub const KAHAN_LI6: CompositionTable = CompositionTable {
    name: "kahan-li6",
    order: 6,
    gammas: &KAHAN_LI6_GAMMAS,
};

const KAHAN_LI8_GAMMAS: [f64; 17] = palindrome([
    0.13020248308889008087881763,
    0.56116298177510838456196441,
    -0.38947496264484728640807860,
    0.15884190655515560089621075,
    -0.39590389413323757733623154,
    0.18453964097831570709183254,
    0.25837438768632204729397911,
    0.29501172360931029887096624,
    -0.60550853383003451169892108,
]);

/// Kahan and Li's `s17odr8a`: order 8 with 17 stages.
pub const KAHAN_LI8: CompositionTable = CompositionTable {
    name: "kahan-li8",
    order: 8,
    gammas: &KAHAN_LI8_GAMMAS,
};

const SOFRONIOU_SPALETTA10_GAMMAS: [f64; 35] = palindrome([
    0.07879572252168641926390768,
    0.31309610341510852776481247,
    0.02791838323507806610952027,
    -0.22959284159390709415121340,
    0.13096206107716486317465686,
    -0.26973340565451071434460973,
    0.07497334315589143566613711,
    0.11199342399981020488957508,
    0.36613344954622675119314812,
    -0.39910563013603589787862981,
    0.10308739852747107731580277,
    0.41143087395589023782070412,
    -0.00486636058313526176219566,
    -0.39203335370863990644808194,
    0.05194250296244964703718290,
    0.05066509075992449633587434,
    0.04967437063972987905456880,
    0.04931773575959453791768001,
]);

/// Sofroniou and Spaletta's `s35odr10`: order 10 with 35 stages.
pub const SOFRONIOU_SPALETTA10: CompositionTable = CompositionTable {
    name: "sofroniou-spaletta10",
    order: 10,
    gammas: &SOFRONIOU_SPALETTA10_GAMMAS,
};

/// Every composition table, in registry order.
pub const ALL: [&CompositionTable; 8] = [
    &YOSHIDA4,
    &YOSHIDA6,
    &YOSHIDA8,
    &SUZUKI4,
    &MCLACHLAN4,
    &KAHAN_LI6,
    &KAHAN_LI8,
    &SOFRONIOU_SPALETTA10,
];
