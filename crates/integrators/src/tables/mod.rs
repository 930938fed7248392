//! Coefficient tables, as data.
//!
//! Every method's coefficients are a `const` in its own module, with its source cited.
//! Rationals are written as quotients of exactly representable integers (one correctly
//! rounded division); irrational coefficients are literals with 30 significant digits,
//! generated at 60-digit precision by `crates/integrators/tools/gen_tables.py` (mpmath) or
//! copied from the cited tables. Dependent coefficients are derived in `const` expressions.
//! The generic steppers ([`crate::explicit`], [`crate::gauss`], [`crate::composition`]) walk
//! these tables; the tests check them as data (row sums, order conditions, symplecticity,
//! symmetry).

pub mod composition;
pub mod explicit;
pub mod gauss;
pub mod rk_pairs;

/// Butcher tableau of an explicit Runge–Kutta method with `S` rows, its error estimator and
/// its dense output.
///
/// Rows `0 … stages−1` are the stages of one step; row `fsal` is `b` itself with `c = 1`,
/// i.e. the stage `f(t + h, y₁)` that is the first stage of the next step ("first same as
/// last") and the right end of the Hermite part of the dense output. Rows after `stages`
/// (other than `fsal`) are extra stages needed only by the dense output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitTableau<const S: usize> {
    /// Registry name.
    pub name: &'static str,
    /// Order of the propagated solution.
    pub order: u32,
    /// Number of stages evaluated per step attempt.
    pub stages: usize,
    /// Row whose coefficients are `b` with `c = 1`.
    pub fsal: usize,
    /// Nodes.
    pub c: [f64; S],
    /// Strictly lower-triangular coefficient matrix.
    pub a: [[f64; S]; S],
    /// Weights of the propagated solution.
    pub b: [f64; S],
    /// Error estimator.
    pub error: ErrorEstimator<S>,
    /// Dense output: rows read as [`Self::dense_form`] says (see [`crate::explicit`]).
    pub dense: &'static [[f64; S]],
    /// How the rows of [`Self::dense`] define the interpolant.
    pub dense_form: DenseForm,
    /// Order of the dense output.
    pub dense_order: u32,
}

/// How the rows `d` of an explicit table's dense output define the interpolant on a step
/// `[t, t + h]`, `θ = (τ − t)/h` (formulas in [`crate::explicit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DenseForm {
    /// The cubic Hermite interpolant of `y`, `y₁`, `f(t, y)`, `f(t + h, y₁)` corrected by
    /// the terms `r_{4+m} = h Σᵢ d_{m,i} kᵢ` (Hairer's form for DP5 and DOP853).
    Hermite,
    /// Continuous weights: `u(θ) = y + h Σᵢ bᵢ(θ) kᵢ` with `bᵢ(θ) = Σ_m d_{m,i} θ^(m+1)`
    /// (Verner's and Tsitouras' interpolants).
    Polynomial,
}

/// How an explicit pair estimates its local error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ErrorEstimator<const S: usize> {
    /// No estimate (fixed-step method).
    None,
    /// `err = h Σ eᵢ kᵢ` with `e = b − b̂`; `order` is the controller's `q` (lower order + 1).
    Embedded {
        /// `b − b̂`.
        weights: [f64; S],
        /// Exponent order `q`.
        order: u32,
    },
    /// Hairer's DOP853 estimator combining a 5th- and a 3rd-order difference:
    /// `err = |h| e₅² / √(n (e₅² + 0.01 e₃²))` in the scaled norm.
    Dop853 {
        /// Weights of the 5th-order difference.
        e5: [f64; S],
        /// Weights of the 3rd-order difference (`b − b̂₃`).
        e3: [f64; S],
        /// Exponent order `q`.
        order: u32,
    },
}

/// Butcher tableau of an `S`-stage Gauss–Legendre collocation method (order `2S`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussTableau<const S: usize> {
    /// Registry name (`gauss{2S}`).
    pub name: &'static str,
    /// Order `2S`.
    pub order: u32,
    /// Nodes: the zeros of the shifted Legendre polynomial `P_S(2x − 1)`.
    pub c: [f64; S],
    /// Weights of the Gauss quadrature on `[0, 1]`.
    pub b: [f64; S],
    /// `a_ij = ∫₀^{c_i} ℓ_j(τ) dτ` with `ℓ_j` the Lagrange basis on the nodes.
    pub a: [[f64; S]; S],
}

/// Coefficients `γ₁ … γ_m` of a composition `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}` of a
/// symmetric base method `Φ` of order 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompositionTable {
    /// Registry name.
    pub name: &'static str,
    /// Order of the composition when the base method is symmetric of order 2.
    pub order: u32,
    /// All coefficients, in the order in which the substeps are taken.
    pub gammas: &'static [f64],
}
