//! The registry: every method with its name, order, family and properties.
//!
//! Names are lowercase, author + order (`yoshida6`, `kahan-li8`), Gauss–Legendre by order
//! (`gauss2` … `gauss12`), rigid-body methods by what they are (`lgvi`, `lgvi4` … `lgvi10`,
//! `lie-gauss4` … `lie-gauss10`, `rkmk4`, `cg3`, `split2` … `split8`, `split-exact2` … `split-exact8`, `dmv`, `exact`). To add a method, append a
//! [`MethodInfo`] to [`METHODS`]; the registry tests check that names are unique and lowercase
//! and that every composition and Gauss table is listed.
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
//! a `TABLE:BASE` name into its table and base.
//!
//! # Order
//!
//! [`Order`] is a finite order `p` (global error `O(hᵖ)`) or [`Order::Exact`] for a method with
//! no truncation error (the exact free-rigid-body flow). It displays as the number or `exact`
//! and serializes as the number or `null` (`tumble integrators --json`); [`Properties::exact`]
//! says the same as a flag.

use serde::{Serialize, Serializer};

use crate::tables::{CompositionTable, composition};

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
    /// A rigid body: inertia and a potential with its moment ([`crate::rigid::RigidBody`]).
    RigidBody,
    /// A torque-free rigid body ([`crate::rigid::FreeRigidBody`]).
    FreeRigidBody,
    /// A rigid body coupled to internal coordinates by a Lagrangian on `SO(3) × ℝⁿ`
    /// ([`crate::rigid::CoupledLagrangian`]).
    CoupledRigidBody,
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
            ProblemKind::RigidBody => "rigid-body",
            ProblemKind::FreeRigidBody => "free-rigid-body",
            ProblemKind::CoupledRigidBody => "coupled-rigid-body",
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
}

impl Order {
    /// The finite order, `None` for [`Order::Exact`].
    #[must_use]
    pub const fn value(self) -> Option<u32> {
        match self {
            Order::Finite(p) => Some(p),
            Order::Exact => None,
        }
    }
}

impl std::fmt::Display for Order {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Order::Finite(p) => write!(f, "{p}"),
            Order::Exact => f.write_str("exact"),
        }
    }
}

impl Serialize for Order {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Order::Finite(p) => serializer.serialize_u32(*p),
            Order::Exact => serializer.serialize_none(),
        }
    }
}

/// `order == p` for a finite order `p`; never for [`Order::Exact`].
impl PartialEq<u32> for Order {
    fn eq(&self, other: &u32) -> bool {
        *self == Order::Finite(*other)
    }
}

/// Finite orders compare as numbers; [`Order::Exact`] is above every finite order.
impl PartialOrd<u32> for Order {
    fn partial_cmp(&self, other: &u32) -> Option<std::cmp::Ordering> {
        match self {
            Order::Finite(p) => p.partial_cmp(other),
            Order::Exact => Some(std::cmp::Ordering::Greater),
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
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
}

const EXPLICIT: Properties = Properties {
    explicit: true,
    symplectic: false,
    symmetric: false,
    adaptive: false,
    dense_output: true,
    lie_group: false,
    exact: false,
};
const ADAPTIVE: Properties = Properties {
    adaptive: true,
    ..EXPLICIT
};
const SYMPLECTIC_EXPLICIT: Properties = Properties {
    explicit: true,
    symplectic: true,
    symmetric: true,
    adaptive: false,
    dense_output: true,
    lie_group: false,
    exact: false,
};
const GAUSS: Properties = Properties {
    explicit: false,
    dense_output: true,
    ..SYMPLECTIC_EXPLICIT
};
/// Explicit, symplectic, symmetric, on the group (splittings, exact flows).
const LIE_SYMPLECTIC_EXPLICIT: Properties = Properties {
    lie_group: true,
    ..SYMPLECTIC_EXPLICIT
};
/// Implicit, symplectic, symmetric, on the group (variational integrators).
const LIE_VARIATIONAL: Properties = Properties {
    explicit: false,
    ..LIE_SYMPLECTIC_EXPLICIT
};
/// Explicit, neither symplectic nor symmetric, on the group (RKMK, Crouch–Grossman).
const LIE_EXPLICIT: Properties = Properties {
    lie_group: true,
    ..EXPLICIT
};

const RIGID_BODY: &str = "rigid body: inertia J (any symmetric positive definite) and potential V(R) with its moment M(R)";

const fn split_entry(
    name: &'static str,
    table: &'static crate::tables::CompositionTable,
    summary: &'static str,
) -> MethodInfo {
    MethodInfo {
        name,
        order: Order::Finite(table.order),
        family: Family::Splitting,
        properties: LIE_SYMPLECTIC_EXPLICIT,
        stages: table.gammas.len() as u32,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody],
        summary,
    }
}

const fn lgvi_entry(
    name: &'static str,
    table: &'static crate::tables::CompositionTable,
    summary: &'static str,
) -> MethodInfo {
    MethodInfo {
        name,
        order: Order::Finite(table.order),
        family: Family::LieGroup,
        properties: LIE_VARIATIONAL,
        stages: table.gammas.len() as u32,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody, ProblemKind::CoupledRigidBody],
        summary,
    }
}

const fn composition_entry(
    table: &'static crate::tables::CompositionTable,
    summary: &'static str,
) -> MethodInfo {
    MethodInfo {
        name: table.name,
        order: Order::Finite(table.order),
        family: Family::Composition,
        properties: SYMPLECTIC_EXPLICIT,
        stages: table.gammas.len() as u32,
        problem: "separable Hamiltonian H = T(p) + V(q), whose Störmer–Verlet the table composes",
        problems: &[ProblemKind::Separable],
        summary,
    }
}

const fn lie_gauss_entry(name: &'static str, stages: u32) -> MethodInfo {
    MethodInfo {
        name,
        order: Order::Finite(2 * stages),
        family: Family::LieGroup,
        properties: LIE_VARIATIONAL,
        stages,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody, ProblemKind::CoupledRigidBody],
        summary: "variational Lie–Gauss: Gauss–Legendre discrete Lagrangian in exponential coordinates centred at each step (Marsden & West 2001; Bogfjellmo & Marthinsen 2016), fixed-point stages",
    }
}

/// A symmetric method of order 2 that the composition tables compose (`TABLE:BASE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Base {
    /// The base's registry name.
    pub name: &'static str,
    /// What a composition of it needs of the problem, in words.
    pub problem: &'static str,
    /// The kinds of problem it integrates (and so its compositions).
    pub problems: &'static [ProblemKind],
    /// Its properties, which its compositions share.
    pub properties: Properties,
    /// What its compositions are, in one line.
    pub summary: &'static str,
}

const LGVI_BASE: Base = Base {
    name: "lgvi",
    problem: RIGID_BODY,
    problems: &[ProblemKind::RigidBody, ProblemKind::CoupledRigidBody],
    properties: LIE_VARIATIONAL,
    summary: "the table before the colon composing the LGVI (Lee, Leok & McClamroch 2005)",
};
const SPLIT2_BASE: Base = Base {
    name: "split2",
    problem: RIGID_BODY,
    problems: &[ProblemKind::RigidBody],
    properties: LIE_SYMPLECTIC_EXPLICIT,
    summary: "the table before the colon composing split2, the principal-axis splitting",
};
const SPLIT_EXACT2_BASE: Base = Base {
    name: "split-exact2",
    problem: RIGID_BODY,
    problems: &[ProblemKind::RigidBody],
    properties: LIE_SYMPLECTIC_EXPLICIT,
    summary: "the table before the colon composing split-exact2, potential kicks around the exact free flow",
};
const GAUSS2_BASE: Base = Base {
    name: "gauss2",
    problem: "first-order ODE y' = f(t, y)",
    problems: &[ProblemKind::Ode],
    properties: GAUSS,
    summary: "the table before the colon composing gauss2, the implicit midpoint rule",
};

/// The symmetric order-2 methods that `TABLE:BASE` names compose.
pub const BASES: [Base; 4] = [LGVI_BASE, SPLIT2_BASE, SPLIT_EXACT2_BASE, GAUSS2_BASE];

const fn composed_entry(
    name: &'static str,
    table: &'static CompositionTable,
    base: Base,
) -> MethodInfo {
    MethodInfo {
        name,
        order: Order::Finite(table.order),
        family: Family::Composition,
        properties: base.properties,
        stages: table.gammas.len() as u32,
        problem: base.problem,
        problems: base.problems,
        summary: base.summary,
    }
}

/// The table and the base of a `TABLE:BASE` name (`kahan-li8:lgvi`), `None` for any other name.
#[must_use]
pub fn composed(name: &str) -> Option<(&'static CompositionTable, &'static Base)> {
    let (table, base) = name.split_once(':')?;
    let table = composition::ALL.into_iter().find(|t| t.name == table)?;
    let base = BASES.iter().find(|b| b.name == base)?;
    Some((table, base))
}

const fn gauss_entry(name: &'static str, stages: u32) -> MethodInfo {
    MethodInfo {
        name,
        order: Order::Finite(2 * stages),
        family: Family::GaussLegendre,
        properties: GAUSS,
        stages,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Gauss–Legendre collocation; fixed-point to stagnation or Newton (faer LU), compensated summation (Hairer–McLachlan–Razakarivony 2008)",
    }
}

/// Every method of this crate.
pub const METHODS: &[MethodInfo] = &[
    MethodInfo {
        name: "rk4",
        order: Order::Finite(4),
        family: Family::ExplicitRungeKutta,
        properties: EXPLICIT,
        stages: 4,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "classical Runge–Kutta (Kutta 1901), cubic Hermite dense output",
    },
    MethodInfo {
        name: "dp5",
        order: Order::Finite(5),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 7,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Dormand–Prince 5(4) (1980), FSAL, PI control, Shampine's order-4 dense output",
    },
    MethodInfo {
        name: "dop853",
        order: Order::Finite(8),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 12,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Dormand–Prince 8(5,3) as in Hairer's DOP853, order-7 dense output",
    },
    MethodInfo {
        name: "tsit5",
        order: Order::Finite(5),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 7,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Tsitouras 5(4) (2011), FSAL, PI control, order-4 dense output",
    },
    MethodInfo {
        name: "vern6",
        order: Order::Finite(6),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 9,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Verner's most efficient 6(5) pair (2010), FSAL, order-6 interpolant (3 extra stages, on demand)",
    },
    MethodInfo {
        name: "vern7",
        order: Order::Finite(7),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 10,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Verner's most efficient 7(6) pair (2010), order-7 interpolant as corrected in 2024 (6 extra stages, on demand)",
    },
    MethodInfo {
        name: "vern8",
        order: Order::Finite(8),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 13,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Verner's most efficient 8(7) pair (2010), order-8 interpolant (8 extra stages, on demand)",
    },
    MethodInfo {
        name: "vern9",
        order: Order::Finite(9),
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 16,
        problem: "first-order ODE y' = f(t, y)",
        problems: &[ProblemKind::Ode],
        summary: "Verner's most efficient 9(8) pair (2010), order-9 interpolant (10 extra stages, on demand)",
    },
    MethodInfo {
        name: "symplectic-euler",
        order: Order::Finite(1),
        family: Family::SymplecticPartitioned,
        properties: Properties {
            symmetric: false,
            ..SYMPLECTIC_EXPLICIT
        },
        stages: 1,
        problem: "separable Hamiltonian H = T(p) + V(q)",
        problems: &[ProblemKind::Separable],
        summary: "symplectic Euler (kick, then drift), compensated summation",
    },
    MethodInfo {
        name: "verlet",
        order: Order::Finite(2),
        family: Family::SymplecticPartitioned,
        properties: SYMPLECTIC_EXPLICIT,
        stages: 1,
        problem: "separable Hamiltonian H = T(p) + V(q)",
        problems: &[ProblemKind::Separable],
        summary: "Störmer–Verlet (kick–drift–kick), compensated summation",
    },
    MethodInfo {
        name: "strang",
        order: Order::Finite(2),
        family: Family::Splitting,
        properties: Properties {
            symplectic: false,
            ..SYMPLECTIC_EXPLICIT
        },
        stages: 1,
        problem: "split system given by the flows of its parts",
        problems: &[ProblemKind::Split],
        summary: "Strang splitting (symplectic when every sub-flow is)",
    },
    composition_entry(&composition::YOSHIDA4, "triple jump (Yoshida 1990)"),
    composition_entry(&composition::YOSHIDA6, "Yoshida 1990, solution A"),
    composition_entry(
        &composition::YOSHIDA8,
        "Yoshida 1990, solution D (refined to 30 digits)",
    ),
    composition_entry(
        &composition::SUZUKI4,
        "Suzuki's fractal, 5 stages (Suzuki 1990)",
    ),
    composition_entry(
        &composition::MCLACHLAN4,
        "5 stages, γ₁ = 0.28 (McLachlan 1995)",
    ),
    composition_entry(&composition::KAHAN_LI6, "s9odr6a (Kahan & Li 1997)"),
    composition_entry(&composition::KAHAN_LI8, "s17odr8a (Kahan & Li 1997)"),
    composition_entry(
        &composition::SOFRONIOU_SPALETTA10,
        "s35odr10 (Sofroniou & Spaletta 2005)",
    ),
    gauss_entry("gauss2", 1),
    gauss_entry("gauss4", 2),
    gauss_entry("gauss6", 3),
    gauss_entry("gauss8", 4),
    gauss_entry("gauss10", 5),
    gauss_entry("gauss12", 6),
    MethodInfo {
        name: "lgvi",
        order: Order::Finite(2),
        family: Family::LieGroup,
        properties: LIE_VARIATIONAL,
        stages: 1,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody, ProblemKind::CoupledRigidBody],
        summary: "Lie group variational integrator (Lee, Leok & McClamroch 2005/2007), Newton on the Cayley vector",
    },
    lgvi_entry(
        "lgvi4",
        &composition::MCLACHLAN4,
        "lgvi composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    lgvi_entry(
        "lgvi6",
        &composition::KAHAN_LI6,
        "lgvi composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    lgvi_entry(
        "lgvi8",
        &composition::KAHAN_LI8,
        "lgvi composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    lgvi_entry(
        "lgvi10",
        &composition::SOFRONIOU_SPALETTA10,
        "lgvi composed with sofroniou-spaletta10 (Sofroniou & Spaletta 2005, s35odr10)",
    ),
    lie_gauss_entry("lie-gauss4", 2),
    lie_gauss_entry("lie-gauss6", 3),
    lie_gauss_entry("lie-gauss8", 4),
    lie_gauss_entry("lie-gauss10", 5),
    MethodInfo {
        name: "rkmk4",
        order: Order::Finite(4),
        family: Family::LieGroup,
        properties: LIE_EXPLICIT,
        stages: 4,
        problem: "vector field on SO(3) × R^n: R' = R hat(xi(t, R, y)), y' = f(t, R, y)",
        problems: &[ProblemKind::LieVectorField],
        summary: "Runge–Kutta–Munthe-Kaas with the classical RK4 coefficients and the exact dexpinv (Munthe-Kaas 1999)",
    },
    MethodInfo {
        name: "cg3",
        order: Order::Finite(3),
        family: Family::LieGroup,
        properties: LIE_EXPLICIT,
        stages: 3,
        problem: "vector field on SO(3) × R^n: R' = R hat(xi(t, R, y)), y' = f(t, R, y)",
        problems: &[ProblemKind::LieVectorField],
        summary: "Crouch–Grossman order 3 (Crouch & Grossman 1993; coefficients as in Owren & Marthinsen 1999)",
    },
    MethodInfo {
        name: "split2",
        order: Order::Finite(2),
        family: Family::Splitting,
        properties: LIE_SYMPLECTIC_EXPLICIT,
        stages: 1,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody],
        summary: "Strang splitting into exact principal-axis rotations (and potential kicks): McLachlan 1993, Touma & Wisdom 1994, Dullweber, Leimkuhler & McLachlan 1997",
    },
    split_entry(
        "split4",
        &composition::MCLACHLAN4,
        "split2 composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    split_entry(
        "split6",
        &composition::KAHAN_LI6,
        "split2 composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    split_entry(
        "split8",
        &composition::KAHAN_LI8,
        "split2 composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    MethodInfo {
        name: "split-exact2",
        order: Order::Finite(2),
        family: Family::Splitting,
        properties: LIE_SYMPLECTIC_EXPLICIT,
        stages: 1,
        problem: RIGID_BODY,
        problems: &[ProblemKind::RigidBody],
        summary: "Strang splitting: potential kicks and the exact free-rigid-body flow (Celledoni, Fassò, Säfström & Zanna 2008); exact for V = 0",
    },
    split_entry(
        "split-exact4",
        &composition::MCLACHLAN4,
        "split-exact2 composed with mclachlan4 (McLachlan 1995, 5 stages)",
    ),
    split_entry(
        "split-exact6",
        &composition::KAHAN_LI6,
        "split-exact2 composed with kahan-li6 (Kahan & Li 1997, s9odr6a)",
    ),
    split_entry(
        "split-exact8",
        &composition::KAHAN_LI8,
        "split-exact2 composed with kahan-li8 (Kahan & Li 1997, s17odr8a)",
    ),
    MethodInfo {
        name: "dmv",
        order: Order::Finite(2),
        family: Family::LieGroup,
        properties: LIE_VARIATIONAL,
        stages: 1,
        problem: "free rigid body (inertia J)",
        problems: &[ProblemKind::FreeRigidBody],
        summary: "discrete Moser–Veselov (Moser & Veselov 1991), quaternion fixed point as in Hairer, Lubich & Wanner §VII.5",
    },
    MethodInfo {
        name: "exact",
        order: Order::Exact,
        family: Family::ExactFlow,
        properties: Properties {
            exact: true,
            ..LIE_SYMPLECTIC_EXPLICIT
        },
        stages: 1,
        problem: "free rigid body (inertia J)",
        problems: &[ProblemKind::FreeRigidBody],
        summary: "exact free-rigid-body flow: Jacobi elliptic functions and Carlson's R_J (Celledoni, Fassò, Säfström & Zanna 2008, corrected)",
    },
    composed_entry("yoshida4:lgvi", &composition::YOSHIDA4, LGVI_BASE),
    composed_entry("yoshida6:lgvi", &composition::YOSHIDA6, LGVI_BASE),
    composed_entry("yoshida8:lgvi", &composition::YOSHIDA8, LGVI_BASE),
    composed_entry("suzuki4:lgvi", &composition::SUZUKI4, LGVI_BASE),
    composed_entry("mclachlan4:lgvi", &composition::MCLACHLAN4, LGVI_BASE),
    composed_entry("kahan-li6:lgvi", &composition::KAHAN_LI6, LGVI_BASE),
    composed_entry("kahan-li8:lgvi", &composition::KAHAN_LI8, LGVI_BASE),
    composed_entry(
        "sofroniou-spaletta10:lgvi",
        &composition::SOFRONIOU_SPALETTA10,
        LGVI_BASE,
    ),
    composed_entry("yoshida4:split2", &composition::YOSHIDA4, SPLIT2_BASE),
    composed_entry("yoshida6:split2", &composition::YOSHIDA6, SPLIT2_BASE),
    composed_entry("yoshida8:split2", &composition::YOSHIDA8, SPLIT2_BASE),
    composed_entry("suzuki4:split2", &composition::SUZUKI4, SPLIT2_BASE),
    composed_entry("mclachlan4:split2", &composition::MCLACHLAN4, SPLIT2_BASE),
    composed_entry("kahan-li6:split2", &composition::KAHAN_LI6, SPLIT2_BASE),
    composed_entry("kahan-li8:split2", &composition::KAHAN_LI8, SPLIT2_BASE),
    composed_entry(
        "sofroniou-spaletta10:split2",
        &composition::SOFRONIOU_SPALETTA10,
        SPLIT2_BASE,
    ),
    composed_entry(
        "yoshida4:split-exact2",
        &composition::YOSHIDA4,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "yoshida6:split-exact2",
        &composition::YOSHIDA6,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "yoshida8:split-exact2",
        &composition::YOSHIDA8,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "suzuki4:split-exact2",
        &composition::SUZUKI4,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "mclachlan4:split-exact2",
        &composition::MCLACHLAN4,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "kahan-li6:split-exact2",
        &composition::KAHAN_LI6,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "kahan-li8:split-exact2",
        &composition::KAHAN_LI8,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry(
        "sofroniou-spaletta10:split-exact2",
        &composition::SOFRONIOU_SPALETTA10,
        SPLIT_EXACT2_BASE,
    ),
    composed_entry("yoshida4:gauss2", &composition::YOSHIDA4, GAUSS2_BASE),
    composed_entry("yoshida6:gauss2", &composition::YOSHIDA6, GAUSS2_BASE),
    composed_entry("yoshida8:gauss2", &composition::YOSHIDA8, GAUSS2_BASE),
    composed_entry("suzuki4:gauss2", &composition::SUZUKI4, GAUSS2_BASE),
    composed_entry("mclachlan4:gauss2", &composition::MCLACHLAN4, GAUSS2_BASE),
    composed_entry("kahan-li6:gauss2", &composition::KAHAN_LI6, GAUSS2_BASE),
    composed_entry("kahan-li8:gauss2", &composition::KAHAN_LI8, GAUSS2_BASE),
    composed_entry(
        "sofroniou-spaletta10:gauss2",
        &composition::SOFRONIOU_SPALETTA10,
        GAUSS2_BASE,
    ),
];

/// Every method.
#[must_use]
pub fn methods() -> &'static [MethodInfo] {
    METHODS
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
