//! The registry: every method with its name, order, family and properties.
//!
//! Names are lowercase, author + order (`yoshida6`, `kahan-li8`), Gauss–Legendre by order
//! (`gauss2` … `gauss12`). To add a method, append a [`MethodInfo`] to [`METHODS`] (the next
//! issue adds the Lie-group family: `lgvi`, `rkmk4`, …); the registry tests check that names
//! are unique and lowercase and that every composition and Gauss table is listed.

use serde::Serialize;

use crate::tables::composition;

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
    /// Has a dense output (continuous extension) used for events.
    pub dense_output: bool,
    /// Stays on a Lie group.
    pub lie_group: bool,
}

/// One registry entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct MethodInfo {
    /// Lowercase unique name.
    pub name: &'static str,
    /// Order of convergence.
    pub order: u32,
    /// Family.
    pub family: Family,
    /// Properties.
    pub properties: Properties,
    /// Number of stages (right-hand-side evaluations or base steps per step).
    pub stages: u32,
    /// What the method needs of the problem.
    pub problem: &'static str,
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
    dense_output: false,
    lie_group: false,
};
const GAUSS: Properties = Properties {
    explicit: false,
    ..SYMPLECTIC_EXPLICIT
};

const fn composition_entry(
    table: &'static crate::tables::CompositionTable,
    summary: &'static str,
) -> MethodInfo {
    MethodInfo {
        name: table.name,
        order: table.order,
        family: Family::Composition,
        properties: SYMPLECTIC_EXPLICIT,
        stages: table.gammas.len() as u32,
        problem: "any symmetric order-2 base stepper (default: Störmer–Verlet on a separable Hamiltonian)",
        summary,
    }
}

const fn gauss_entry(name: &'static str, stages: u32) -> MethodInfo {
    MethodInfo {
        name,
        order: 2 * stages,
        family: Family::GaussLegendre,
        properties: GAUSS,
        stages,
        problem: "first-order ODE y' = f(t, y)",
        summary: "Gauss–Legendre collocation; fixed-point to stagnation or Newton (faer LU), compensated summation (Hairer–McLachlan–Razakarivony 2008)",
    }
}

/// Every method of this crate.
pub const METHODS: &[MethodInfo] = &[
    MethodInfo {
        name: "rk4",
        order: 4,
        family: Family::ExplicitRungeKutta,
        properties: EXPLICIT,
        stages: 4,
        problem: "first-order ODE y' = f(t, y)",
        summary: "classical Runge–Kutta (Kutta 1901), cubic Hermite dense output",
    },
    MethodInfo {
        name: "dp5",
        order: 5,
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 7,
        problem: "first-order ODE y' = f(t, y)",
        summary: "Dormand–Prince 5(4) (1980), FSAL, PI control, Shampine's order-4 dense output",
    },
    MethodInfo {
        name: "dop853",
        order: 8,
        family: Family::ExplicitRungeKutta,
        properties: ADAPTIVE,
        stages: 12,
        problem: "first-order ODE y' = f(t, y)",
        summary: "Dormand–Prince 8(5,3) as in Hairer's DOP853, order-7 dense output",
    },
    MethodInfo {
        name: "symplectic-euler",
        order: 1,
        family: Family::SymplecticPartitioned,
        properties: Properties {
            symmetric: false,
            ..SYMPLECTIC_EXPLICIT
        },
        stages: 1,
        problem: "separable Hamiltonian H = T(p) + V(q)",
        summary: "symplectic Euler (kick, then drift), compensated summation",
    },
    MethodInfo {
        name: "verlet",
        order: 2,
        family: Family::SymplecticPartitioned,
        properties: SYMPLECTIC_EXPLICIT,
        stages: 1,
        problem: "separable Hamiltonian H = T(p) + V(q)",
        summary: "Störmer–Verlet (kick–drift–kick), compensated summation",
    },
    MethodInfo {
        name: "strang",
        order: 2,
        family: Family::Splitting,
        properties: Properties {
            symplectic: false,
            ..SYMPLECTIC_EXPLICIT
        },
        stages: 1,
        problem: "split system given by the flows of its parts",
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
