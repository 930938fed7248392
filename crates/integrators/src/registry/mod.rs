//! The registry: every method with its name, order, family and properties.
//!
//! Names are lowercase, author + order (`yoshida6`, `kahan-li8`), Gauss–Legendre by order
//! (`gauss2` … `gauss12`), rigid-body methods by what they are (`lgvi`, `lgvi4` … `lgvi10`,
//! `lie-gauss4` … `lie-gauss10`, `rkmk4`, `cg3`, `split2` … `split8`, `split-exact2` …
//! `split-exact8`, `dmv`, `exact`).
//!
//! # Rows build steppers
//!
//! A row of [`ROWS`] is [`MethodInfo::new`]`(name, stepping, summary)`: the [`Stepping`] is the
//! family's stepper and the `const` table it walks, and the entry's order, stages, family,
//! properties and problem kinds are derived from it ([`Stepping::order`] …). [`build`] turns a
//! row into its stepper for a kind of problem and hands it to a receiver; nothing else maps
//! names to steppers. Adding an explicit pair, a Gauss table or a composition table is its
//! table and one row (`docs/architecture.md`, "Recipes"); the registry tests check that names
//! are unique and lowercase and that every composition and Gauss table is listed.
//!
//! # Compositions of a scene's base method
//!
//! A composition table (`yoshida4` … `sofroniou-spaletta10`) named alone composes Störmer–Verlet
//! and needs a separable Hamiltonian. Composed with another symmetric method of order 2 — a
//! *base* of [`BASES`]: `lgvi` (rigid bodies, coupled rigid bodies), `split2` and
//! `split-exact2` (rigid bodies), `gauss2`, the implicit midpoint rule (any first-order ODE) — it is named `TABLE:BASE`
//! (`kahan-li8:lgvi`, `yoshida6:split2`, `mclachlan4:gauss2`) and runs every problem its base
//! runs, at the table's order. The short names `lgvi4` … `lgvi10`, `split4` … `split8` and
//! `split-exact4` … `split-exact8` are the same methods as `mclachlan4:lgvi`,
//! `kahan-li6:lgvi`, `kahan-li8:lgvi`, `sofroniou-spaletta10:lgvi`, `mclachlan4:split2` …
//! `kahan-li8:split2` and `mclachlan4:split-exact2` … `kahan-li8:split-exact2`; [`composed`] splits
//! a `TABLE:BASE` name into its table and base. The `TABLE:BASE` entries are not written out:
//! [`methods`] generates them from [`BASES`] × [`composition::ALL`], after [`ROWS`].
//!
//! # Order
//!
//! [`Order`] is a finite order `p` (global error `O(hᵖ)`) or [`Order::Exact`] for a method with
//! no truncation error (the exact free-rigid-body flow). It displays as the number or `exact`
//! and serializes as the number or `null` (`tumble integrators --json`); [`Properties::exact`]
//! says the same as a flag.

pub mod build;
mod stepping;

use std::sync::LazyLock;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

pub use stepping::{
    AnyExplicit, AnyGauss, Base, BaseStepper, ExplicitVisitor, GAUSS2_BASE, GaussVisitor,
    LGVI_BASE, SPLIT_EXACT2_BASE, SPLIT2_BASE, Stepping, VERLET_BASE,
};

use crate::control::PiController;
use crate::explicit::ExplicitRungeKutta;
use crate::tables::explicit as explicit_tables;
use crate::tables::gauss as gauss_tables;
use crate::tables::{CompositionTable, ExplicitTableau, composition, rk_pairs};
use crate::taylor::TaylorOrder;

/// Family of a method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum Family {
    /// Explicit Runge–Kutta (with or without error control).
    ExplicitRungeKutta,
    /// Symplectic partitioned methods for separable Hamiltonians (Euler, Störmer–Verlet).
    SymplecticPartitioned,
    /// Symmetric composition of a symmetric base method.
    Composition,
    /// Gauss–Legendre collocation.
    GaussLegendre,
    /// Lie-group methods (RKMK, Crouch–Grossman, variational).
    LieGroup,
    /// Splitting into exactly solvable flows.
    Splitting,
    /// The exact flow of a problem with a closed-form solution.
    ExactFlow,
    /// Taylor series of the solution, its coefficients from the problem.
    Taylor,
}

impl Family {
    /// Lowercase display name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Family::ExplicitRungeKutta => "explicit-runge-kutta",
            Family::SymplecticPartitioned => "symplectic-partitioned",
            Family::Composition => "composition",
            Family::GaussLegendre => "gauss-legendre",
            Family::LieGroup => "lie-group",
            Family::Splitting => "splitting",
            Family::ExactFlow => "exact-flow",
            Family::Taylor => "taylor",
        }
    }
}

/// A kind of problem a method integrates: what it needs of the equations. A model offers one or
/// more kinds (a free rigid body is also a rigid body, a Lie-group vector field and, flattened, a
/// first-order ODE); a method runs it when they share a kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum ProblemKind {
    /// A first-order system `y' = f(t, y)` on ℝⁿ ([`crate::Ode`]).
    Ode,
    /// A separable Hamiltonian `H = T(p) + V(q)` ([`crate::SeparableHamiltonian`]).
    Separable,
    /// A system split into parts whose flows are known ([`crate::SplitOde`]).
    Split,
    /// A vector field on `SO(3) × ℝⁿ`, `Ṙ = R hat ξ(t, R, y)`, `ẏ = f(t, R, y)`
    /// ([`crate::rigid::LieVectorField`]).
    LieVectorField,
    /// A vector field on the product `SO(3)ᴹ × ℝⁿ` of several orientations,
    /// `Ṙₖ = Rₖ hat ξₖ(t, R, y)`, `ẏ = f(t, R, y)` ([`crate::rigid::ProductVectorField`]).
    ProductVectorField,
    /// A Lagrangian on the product `SO(3)ᴹ × ℝⁿ` given by its derivatives
    /// ([`crate::rigid::ProductLagrangian`]): several orientations whose kinetic energy
    /// couples them.
    ProductLagrangian,
    /// A rigid body: inertia and a potential with its moment ([`crate::rigid::RigidBody`]).
    RigidBody,
    /// A torque-free rigid body ([`crate::rigid::FreeRigidBody`]).
    FreeRigidBody,
    /// A rigid body coupled to internal coordinates by a Lagrangian on `SO(3) × ℝⁿ`
    /// ([`crate::rigid::CoupledLagrangian`]).
    CoupledRigidBody,
    /// A first-order system that computes the normalized Taylor coefficients of its solution
    /// through a point ([`crate::TaylorSystem`]).
    TaylorSeries,
    /// A [`ProblemKind::TaylorSeries`] that also computes its coefficients in double-double
    /// arithmetic ([`crate::TaylorSystem::double_double`]).
    DoubleDoubleTaylorSeries,
}

impl ProblemKind {
    /// Lowercase display name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ProblemKind::Ode => "ode",
            ProblemKind::Separable => "separable",
            ProblemKind::Split => "split",
            ProblemKind::LieVectorField => "lie-vector-field",
            ProblemKind::ProductVectorField => "product-vector-field",
            ProblemKind::ProductLagrangian => "product-lagrangian",
            ProblemKind::RigidBody => "rigid-body",
            ProblemKind::FreeRigidBody => "free-rigid-body",
            ProblemKind::CoupledRigidBody => "coupled-rigid-body",
            ProblemKind::TaylorSeries => "taylor-series",
            ProblemKind::DoubleDoubleTaylorSeries => "taylor-series-dd",
        }
    }
}

/// Order of convergence of a method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// Global error `O(hᵖ)`.
    Finite(u32),
    /// No truncation error: the method is the exact flow.
    Exact,
    /// Chosen at each step from the tolerance (a Taylor method: `p = ⌈−½ ln ε + 1⌉`).
    Variable,
}

impl Order {
    /// The finite order, `None` for [`Order::Exact`].
    #[must_use]
    pub const fn value(self) -> Option<u32> {
        match self {
            Order::Finite(p) => Some(p),
            Order::Exact | Order::Variable => None,
        }
    }
}

impl std::fmt::Display for Order {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Order::Finite(p) => write!(f, "{p}"),
            Order::Exact => f.write_str("exact"),
            Order::Variable => f.write_str("variable"),
        }
    }
}

impl Serialize for Order {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Order::Finite(p) => serializer.serialize_u32(*p),
            Order::Exact => serializer.serialize_none(),
            Order::Variable => serializer.serialize_str("variable"),
        }
    }
}

/// The inverse of the [`Serialize`] form: a number, `null` (or `"exact"`) for the exact flow,
/// `"variable"`.
impl<'de> Deserialize<'de> for Order {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Written {
            Finite(u32),
            Word(String),
        }
        match Option::<Written>::deserialize(deserializer)? {
            Some(Written::Finite(p)) => Ok(Order::Finite(p)),
            None => Ok(Order::Exact),
            Some(Written::Word(w)) => match w.as_str() {
                "exact" => Ok(Order::Exact),
                "variable" => Ok(Order::Variable),
                _ => Err(serde::de::Error::custom(format!(
                    "order `{w}`: expected a number, null (the exact flow) or \"variable\""
                ))),
            },
        }
    }
}

/// `order == p` for a finite order `p`; never for [`Order::Exact`].
impl PartialEq<u32> for Order {
    fn eq(&self, other: &u32) -> bool {
        *self == Order::Finite(*other)
    }
}

/// Finite orders compare as numbers; [`Order::Exact`] is above every finite order, and so is
/// [`Order::Variable`] (a Taylor method's order grows as the tolerance tightens).
impl PartialOrd<u32> for Order {
    fn partial_cmp(&self, other: &u32) -> Option<std::cmp::Ordering> {
        match self {
            Order::Finite(p) => p.partial_cmp(other),
            Order::Exact | Order::Variable => Some(std::cmp::Ordering::Greater),
        }
    }
}

/// Qualitative properties of a method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Properties {
    /// Stages are explicit (no equation to solve); `false` means implicit.
    pub explicit: bool,
    /// The flow map is symplectic.
    pub symplectic: bool,
    /// The method is symmetric (time-reversible).
    pub symmetric: bool,
    /// Has an error estimate and adaptive step-size control.
    pub adaptive: bool,
    /// Has a dense output (continuous extension) for events and output at chosen times:
    /// the method's own interpolant (explicit Runge–Kutta, Gauss–Legendre), or for methods
    /// without one a partial step of the method itself ([`crate::restep::Restepped`], of the
    /// method's order, on the group for Lie-group methods).
    pub dense_output: bool,
    /// Stays on a Lie group.
    pub lie_group: bool,
    /// No truncation error (the exact flow); its [`Order`] is [`Order::Exact`].
    pub exact: bool,
}

/// One registry entry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MethodInfo {
    /// Lowercase unique name.
    pub name: &'static str,
    /// Order of convergence.
    pub order: Order,
    /// Family.
    pub family: Family,
    /// Properties.
    pub properties: Properties,
    /// Number of stages (right-hand-side evaluations or base steps per step).
    pub stages: u32,
    /// What the method needs of the problem, in words.
    pub problem: &'static str,
    /// The kinds of problem it integrates.
    pub problems: &'static [ProblemKind],
    /// One line: what it is, and its source.
    pub summary: &'static str,
    /// What its stepper is built from ([`build`]).
    #[serde(skip)]
    pub stepping: Stepping,
}

impl MethodInfo {
    /// The entry of a method built from `stepping`: order, stages, family, properties and
    /// problems derived from it.
    #[must_use]
    pub const fn new(name: &'static str, stepping: Stepping, summary: &'static str) -> Self {
        Self {
            name,
            order: stepping.order(),
            family: stepping.family(),
            properties: stepping.properties(),
            stages: stepping.stages(),
            problem: stepping.problem(),
            problems: stepping.problems(),
            summary,
            stepping,
        }
    }

    /// The same entry registered under another family (`lgvi4`, a composition of the LGVI,
    /// is listed as a Lie-group method).
    #[must_use]
    pub const fn in_family(mut self, family: Family) -> Self {
        self.family = family;
        self
    }
}

/// A row for an explicit Runge–Kutta method, named after its table.
const fn explicit(method: AnyExplicit, summary: &'static str) -> MethodInfo {
    MethodInfo::new(method.name(), Stepping::Explicit(method), summary)
}

/// A row for a Gauss–Legendre table, named after it.
const fn gauss(table: AnyGauss) -> MethodInfo {
    MethodInfo::new(
        table.name(),
        Stepping::Gauss(table),
        "Gauss–Legendre collocation; fixed-point to stagnation or Newton (faer LU), compensated summation (Hairer–McLachlan–Razakarivony 2008)",
    )
}

/// A row for a composition table named alone: it composes Störmer–Verlet.
const fn composes_verlet(table: &'static CompositionTable, summary: &'static str) -> MethodInfo {
    MethodInfo::new(
        table.name,
        Stepping::Composition {
            table,
            base: &VERLET_BASE,
        },
        summary,
    )
}

/// A row for a composition of `base` under a short name (`lgvi4`, `split4`), listed in the
/// base's family.
const fn short(
    name: &'static str,
    table: &'static CompositionTable,
    base: &'static Base,
    family: Family,
    summary: &'static str,
) -> MethodInfo {
    MethodInfo::new(name, Stepping::Composition { table, base }, summary).in_family(family)
}

/// A row for variational Lie–Gauss on a Gauss–Legendre table.
const fn lie_gauss(table: AnyGauss, name: &'static str) -> MethodInfo {
    MethodInfo::new(
        name,
        Stepping::LieGauss(table),
        "variational Lie–Gauss: Gauss–Legendre discrete Lagrangian in exponential coordinates centred at each step (Marsden & West 2001; Bogfjellmo & Marthinsen 2016), fixed-point stages",
    )
}

/// The explicit Runge–Kutta method of `table` with `controller`.
const fn rk<const S: usize>(
    table: &'static ExplicitTableau<S>,
    controller: PiController,
) -> ExplicitRungeKutta<S> {
    ExplicitRungeKutta { table, controller }
}

use AnyExplicit as E;
use AnyGauss as G;
use PiController as Pi;

/// The registry's rows, in the order the registry lists them; the `TABLE:BASE` compositions
/// ([`BASES`] × [`composition::ALL`]) follow them in [`methods`].
pub const ROWS: &[MethodInfo] = &[
    explicit(
        E::S5(rk(&explicit_tables::RK4, Pi::DP5)),
        "classical Runge–Kutta (Kutta 1901), cubic Hermite dense output",
    ),
    explicit(
        E::S7(rk(&explicit_tables::DP5, Pi::DP5)),
        "Dormand–Prince 5(4) (1980), FSAL, PI control, Shampine's order-4 dense output",
    ),
    explicit(
        E::S16(rk(&explicit_tables::DOP853, Pi::DOP853)),
        "Dormand–Prince 8(5,3) as in Hairer's DOP853, order-7 dense output",
    ),
    explicit(
        E::S7(rk(&rk_pairs::TSIT5, Pi::DP5)),
        "Tsitouras 5(4) (2011), FSAL, PI control, order-4 dense output",
    ),
    explicit(
        E::S12(rk(&rk_pairs::VERN6, Pi::VERNER)),
        "Verner's most efficient 6(5) pair (2010), FSAL, order-6 interpolant (3 extra stages, on demand)",
    ),
    explicit(
        E::S16(rk(&rk_pairs::VERN7, Pi::VERNER)),
        "Verner's most efficient 7(6) pair (2010), order-7 interpolant as corrected in 2024 (6 extra stages, on demand)",
    ),
    explicit(
        E::S21(rk(&rk_pairs::VERN8, Pi::VERNER)),
        "Verner's most efficient 8(7) pair (2010), order-8 interpolant (8 extra stages, on demand)",
    ),
    explicit(
        E::S26(rk(&rk_pairs::VERN9, Pi::VERNER)),
        "Verner's most efficient 9(8) pair (2010), order-9 interpolant (10 extra stages, on demand)",
    ),
    MethodInfo::new(
        "symplectic-euler",
        Stepping::SymplecticEuler,
        "symplectic Euler (kick, then drift), compensated summation",
    ),
    MethodInfo::new(
        "verlet",
        Stepping::StormerVerlet,
        "Störmer–Verlet (kick–drift–kick), compensated summation",
    ),
    MethodInfo::new(
        "strang",
        Stepping::Strang,
        "Strang splitting (symplectic when every sub-flow is)",
    ),
    composes_verlet(&composition::YOSHIDA4, "triple jump (Yoshida 1990)"),
    composes_verlet(&composition::YOSHIDA6, "Yoshida 1990, solution A"),
    composes_verlet(
        &composition::YOSHIDA8,
        "Yoshida 1990, solution D (refined to 30 digits)",
    ),
    composes_verlet(
        &composition::SUZUKI4,
        "Suzuki's fractal, 5 stages (Suzuki 1990)",
    ),
    composes_verlet(
        &composition::MCLACHLAN4,
        "5 stages, γ₁ = 0.28 (McLachlan 1995)",
    ),
    composes_verlet(&composition::KAHAN_LI6, "s9odr6a (Kahan & Li 1997)"),
    composes_verlet(&composition::KAHAN_LI8, "s17odr8a (Kahan & Li 1997)"),
    composes_verlet(
        &composition::SOFRONIOU_SPALETTA10,
        "s35odr10 (Sofroniou & Spaletta 2005)",
    ),
    gauss(G::S1(&gauss_tables::GAUSS2)),
    gauss(G::S2(&gauss_tables::GAUSS4)),
    gauss(G::S3(&gauss_tables::GAUSS6)),
    gauss(G::S4(&gauss_tables::GAUSS8)),
    gauss(G::S5(&gauss_tables::GAUSS10)),
    gauss(G::S6(&gauss_tables::GAUSS12)),
    MethodInfo::new(
        "lgvi",
        Stepping::Lgvi,
        "Lie group variational integrator (Lee, Leok & McClamroch 2005/2007), Newton on the Cayley vector; on several orientations, the trapezoidal discrete Lagrangian in exponential coordinates",
    ),
    short(
        "lgvi4",
        &composition::MCLACHLAN4,
        &LGVI_BASE,
        Family::LieGroup,
        "lgvi composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    short(
        "lgvi6",
        &composition::KAHAN_LI6,
        &LGVI_BASE,
        Family::LieGroup,
        "lgvi composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    short(
        "lgvi8",
        &composition::KAHAN_LI8,
        &LGVI_BASE,
        Family::LieGroup,
        "lgvi composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    short(
        "lgvi10",
        &composition::SOFRONIOU_SPALETTA10,
        &LGVI_BASE,
        Family::LieGroup,
        "lgvi composed with sofroniou-spaletta10 (Sofroniou & Spaletta 2005, s35odr10)",
    ),
    lie_gauss(G::S2(&gauss_tables::GAUSS4), "lie-gauss4"),
    lie_gauss(G::S3(&gauss_tables::GAUSS6), "lie-gauss6"),
    lie_gauss(G::S4(&gauss_tables::GAUSS8), "lie-gauss8"),
    lie_gauss(G::S5(&gauss_tables::GAUSS10), "lie-gauss10"),
    MethodInfo::new(
        "rkmk4",
        Stepping::Rkmk4,
        "Runge–Kutta–Munthe-Kaas with the classical RK4 coefficients and the exact dexpinv (Munthe-Kaas 1999)",
    ),
    MethodInfo::new(
        "cg3",
        Stepping::Cg3,
        "Crouch–Grossman order 3 (Crouch & Grossman 1993; coefficients as in Owren & Marthinsen 1999)",
    ),
    MethodInfo::new(
        "split2",
        Stepping::PrincipalAxisSplitting,
        "Strang splitting into exact principal-axis rotations (and potential kicks): McLachlan 1993, Touma & Wisdom 1994, Dullweber, Leimkuhler & McLachlan 1997",
    ),
    short(
        "split4",
        &composition::MCLACHLAN4,
        &SPLIT2_BASE,
        Family::Splitting,
        "split2 composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    short(
        "split6",
        &composition::KAHAN_LI6,
        &SPLIT2_BASE,
        Family::Splitting,
        "split2 composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    short(
        "split8",
        &composition::KAHAN_LI8,
        &SPLIT2_BASE,
        Family::Splitting,
        "split2 composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    MethodInfo::new(
        "split-exact2",
        Stepping::ExactSplitting,
        "Strang splitting: potential kicks and the exact free-rigid-body flow (Celledoni, Fassò, Säfström & Zanna 2008); exact for V = 0",
    ),
    short(
        "split-exact4",
        &composition::MCLACHLAN4,
        &SPLIT_EXACT2_BASE,
        Family::Splitting,
        "split-exact2 composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    short(
        "split-exact6",
        &composition::KAHAN_LI6,
        &SPLIT_EXACT2_BASE,
        Family::Splitting,
        "split-exact2 composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    short(
        "split-exact8",
        &composition::KAHAN_LI8,
        &SPLIT_EXACT2_BASE,
        Family::Splitting,
        "split-exact2 composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    MethodInfo::new(
        "dmv",
        Stepping::Dmv,
        "discrete Moser–Veselov (Moser & Veselov 1991), quaternion fixed point as in Hairer, Lubich & Wanner §VII.5",
    ),
    MethodInfo::new(
        "exact",
        Stepping::ExactFlow,
        "exact free-rigid-body flow: Jacobi elliptic functions and Carlson's R_J (Celledoni, Fassò, Säfström & Zanna 2008, corrected)",
    ),
    MethodInfo::new(
        "taylor",
        Stepping::Taylor(TaylorOrder::FromTolerance),
        "Taylor series by automatic differentiation, order p = ceil(-ln(eps)/2 + 1) and step from the last two coefficients (Jorba & Zou 2005), the step's polynomial as dense output",
    ),
    MethodInfo::new(
        "taylor-dd",
        Stepping::TaylorDoubleDouble,
        "the Taylor method of `taylor` with its state, coefficients and sums in double-double arithmetic (about 32 digits; Dekker 1971): errors to about 1e-30, the references' method",
    ),
    MethodInfo::new(
        "taylor8",
        Stepping::Taylor(TaylorOrder::Fixed(8)),
        "Taylor series of order 8 by automatic differentiation, fixed steps, the step's polynomial as dense output",
    ),
    MethodInfo::new(
        "taylor16",
        Stepping::Taylor(TaylorOrder::Fixed(16)),
        "Taylor series of order 16 by automatic differentiation, fixed steps, the step's polynomial as dense output",
    ),
];

/// The symmetric order-2 methods that `TABLE:BASE` names compose.
pub const BASES: [Base; 4] = [LGVI_BASE, SPLIT2_BASE, SPLIT_EXACT2_BASE, GAUSS2_BASE];

/// The table and the base of a `TABLE:BASE` name (`kahan-li8:lgvi`), `None` for any other name.
#[must_use]
pub fn composed(name: &str) -> Option<(&'static CompositionTable, &'static Base)> {
    let (table, base) = name.split_once(':')?;
    let table = composition::ALL.into_iter().find(|t| t.name == table)?;
    let base = BASES.iter().find(|b| b.name == base)?;
    Some((table, base))
}

/// Every method: [`ROWS`], then each base of [`BASES`] composed with each table of
/// [`composition::ALL`] (named `TABLE:BASE`).
static METHODS: LazyLock<Vec<MethodInfo>> = LazyLock::new(|| {
    let composed = BASES.iter().flat_map(|base| {
        composition::ALL.into_iter().map(move |table| {
            let name: &'static str = Box::leak(format!("{}:{}", table.name, base.name).into());
            MethodInfo::new(name, Stepping::Composition { table, base }, base.summary)
        })
    });
    ROWS.iter().copied().chain(composed).collect()
});

/// Every method.
#[must_use]
pub fn methods() -> &'static [MethodInfo] {
    &METHODS
}

/// The method called `name`.
///
/// # Errors
/// [`crate::Error::UnknownMethod`] if there is none.
pub fn find(name: &str) -> Result<&'static MethodInfo, crate::Error> {
    METHODS
        .iter()
        .find(|m| m.name == name)
        .ok_or_else(|| crate::Error::UnknownMethod(name.to_owned()))
}
