//! What a registry row builds its stepper from: the family's stepper and the `const` table it
//! walks ([`Stepping`]), and everything the row's [`MethodInfo`](super::MethodInfo) derives
//! from it — order, stages, family, properties and the kinds of problem it integrates.
//!
//! Tables of explicit Runge–Kutta and Gauss–Legendre methods carry their size in their type
//! (`ExplicitTableau<S>`, `GaussTableau<S>`). A row names the size through the variant of
//! [`AnyExplicit`] or [`AnyGauss`] (`AnyExplicit::S7(…)` for a 7-row table); the compiler
//! checks it against the table. The variants are the sizes the built-in tables use: a table
//! of a new size adds its size to the list at the foot of this file (one token), and every
//! size is compiled once per problem the dispatch runs.

use crate::explicit::ExplicitRungeKutta;
use crate::tables::{CompositionTable, ErrorEstimator, ExplicitTableau, GaussTableau};
use crate::taylor::TaylorOrder;

use super::{Family, Order, ProblemKind, Properties};

/// How a registry method builds its stepper: the family, and the table it walks.
///
/// Matched without a wildcard by the builders of [`super::build`], so a new variant is a
/// compile error wherever a stepper is built until each kind of problem says what it does
/// with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Explicit Runge–Kutta ([`crate::ExplicitRkStepper`]) walking a table, with its
    /// step-size controller; adaptive when the table has an error estimator.
    Explicit(AnyExplicit),
    /// Gauss–Legendre collocation ([`crate::GaussStepper`]) on a first-order ODE.
    Gauss(AnyGauss),
    /// Symplectic Euler on a separable Hamiltonian.
    SymplecticEuler,
    /// Störmer–Verlet on a separable Hamiltonian.
    StormerVerlet,
    /// Strang splitting of a split system.
    Strang,
    /// A composition table applied to a symmetric order-2 base ([`crate::Composition`]).
    Composition {
        /// The coefficients.
        table: &'static CompositionTable,
        /// The base method composed.
        base: &'static Base,
    },
    /// The Lie group variational integrator ([`crate::rigid::Lgvi`],
    /// [`crate::rigid::CoupledLgvi`]).
    Lgvi,
    /// Variational Lie–Gauss on a Gauss–Legendre table ([`crate::rigid::LieGauss`],
    /// [`crate::rigid::CoupledLieGauss`]).
    LieGauss(AnyGauss),
    /// Runge–Kutta–Munthe-Kaas with the classical RK4 coefficients ([`crate::rigid::rkmk4`]).
    Rkmk4,
    /// Crouch–Grossman of order 3 ([`crate::rigid::cg3`]).
    Cg3,
    /// Strang splitting into exact principal-axis rotations
    /// ([`crate::rigid::PrincipalAxisSplitting`]).
    PrincipalAxisSplitting,
    /// Potential kicks around the exact free flow ([`crate::rigid::ExactSplitting`]).
    ExactSplitting,
    /// Discrete Moser–Veselov ([`crate::rigid::Dmv`]).
    Dmv,
    /// The exact free-rigid-body flow ([`crate::rigid::ExactStepper`]).
    ExactFlow,
    /// A Taylor-series method ([`crate::TaylorStepper`]) on a problem that computes its Taylor
    /// coefficients: order from the tolerance or fixed.
    Taylor(crate::taylor::TaylorOrder),
    /// The adaptive Taylor method in double-double arithmetic
    /// ([`crate::taylor::DoubleDoubleTaylorStepper`]).
    TaylorDoubleDouble,
}

/// A symmetric method of order 2 that the composition tables compose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BaseStepper {
    /// Störmer–Verlet (a composition table named alone).
    StormerVerlet,
    /// The LGVI on a rigid body or a coupled one.
    Lgvi,
    /// The principal-axis splitting `split2`.
    PrincipalAxisSplitting,
    /// The exact-flow splitting `split-exact2`.
    ExactSplitting,
    /// `gauss2`, the implicit midpoint rule.
    Gauss2,
}

/// A symmetric order-2 method that composition tables compose, with what its compositions
/// share: the kinds of problem, the properties and the words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Base {
    /// The base's registry name (the `BASE` of `TABLE:BASE`).
    pub name: &'static str,
    /// Its stepper.
    pub stepper: BaseStepper,
    /// What a composition of it needs of the problem, in words.
    pub problem: &'static str,
    /// The kinds of problem it integrates (and so its compositions).
    pub problems: &'static [ProblemKind],
    /// Its properties, which its compositions share.
    pub properties: Properties,
    /// What its compositions are, in one line.
    pub summary: &'static str,
}

/// Receives an explicit method of whichever size its table has ([`AnyExplicit::visit`]).
pub trait ExplicitVisitor {
    /// What the visit returns.
    type Output;
    /// Called with the method.
    fn visit<const S: usize>(self, method: ExplicitRungeKutta<S>) -> Self::Output;
}

/// Receives a Gauss–Legendre table of whichever size it has ([`AnyGauss::visit`]).
pub trait GaussVisitor {
    /// What the visit returns.
    type Output;
    /// Called with the table.
    fn visit<const S: usize>(self, table: &'static GaussTableau<S>) -> Self::Output;
}

const fn embedded<const S: usize>(table: &ExplicitTableau<S>) -> bool {
    !matches!(table.error, ErrorEstimator::None)
}

/// Declares an enum with one variant per size, the `const` accessors a row derives its entry
/// from (each an expression in the sized value `$v`), and the visit that hands the sized value
/// to a visitor.
macro_rules! sized {
    (
        $(#[$doc:meta])* $name:ident($item:ident), $visitor:ident, |$v:ident| {
            $($(#[$fdoc:meta])* fn $f:ident -> $ty:ty = $e:expr;)*
        },
        $sizes:tt
    ) => {
        sized!(@enum [$(#[$doc])*] $name $item $visitor $v $sizes);
        impl $name {
            $(sized!(@fn [$(#[$fdoc])*] $f $ty, $v, $e, $sizes);)*
        }
    };
    (@fn [$(#[$fdoc:meta])*] $f:ident $ty:ty, $v:ident, $e:expr,
        [$($variant:ident = $s:literal),+ $(,)?]) => {
        $(#[$fdoc])*
        #[must_use]
        pub const fn $f(self) -> $ty {
            match self {
                $(Self::$variant($v) => $e,)+
            }
        }
    };
    (@enum [$(#[$doc:meta])*] $name:ident $item:ident $visitor:ident $v:ident
        [$($variant:ident = $s:literal),+ $(,)?]) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum $name {
            $(
                #[doc = concat!("A table of size ", stringify!($s), ".")]
                $variant($item<$s>),
            )+
        }

        impl $name {
            /// The table's size `S` (the type parameter of its table).
            #[must_use]
            pub const fn size(self) -> usize {
                match self {
                    $(Self::$variant(_) => $s,)+
                }
            }

            /// Hands the sized value to `visitor`.
            pub fn visit<V: $visitor>(self, visitor: V) -> V::Output {
                match self {
                    $(Self::$variant($v) => visitor.visit($v),)+
                }
            }
        }
    };
}

/// A Gauss–Legendre table, by reference.
type GaussRef<const S: usize> = &'static GaussTableau<S>;

sized! {
    /// An explicit Runge–Kutta method (table and controller) of any built-in table size.
    AnyExplicit(ExplicitRungeKutta), ExplicitVisitor, |m| {
        /// Order of the propagated solution.
        fn order -> u32 = m.table.order;
        /// The table's registry name.
        fn name -> &'static str = m.table.name;
        /// Stages evaluated per step attempt.
        fn stages -> u32 = m.table.stages as u32;
        /// The table has an error estimator (the method adapts its step).
        fn adaptive -> bool = embedded(m.table);
    },
    [S5 = 5, S7 = 7, S12 = 12, S16 = 16, S21 = 21, S26 = 26]
}

sized! {
    /// A Gauss–Legendre table of any built-in number of stages.
    AnyGauss(GaussRef), GaussVisitor, |t| {
        /// Order `2S`.
        fn order -> u32 = t.order;
        /// The table's registry name.
        fn name -> &'static str = t.name;
    },
    [S1 = 1, S2 = 2, S3 = 3, S4 = 4, S5 = 5, S6 = 6]
}

pub(super) const EXPLICIT: Properties = Properties {
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
pub(super) const SYMPLECTIC_EXPLICIT: Properties = Properties {
    explicit: true,
    symplectic: true,
    symmetric: true,
    adaptive: false,
    dense_output: true,
    lie_group: false,
    exact: false,
};
pub(super) const GAUSS: Properties = Properties {
    explicit: false,
    dense_output: true,
    ..SYMPLECTIC_EXPLICIT
};
/// Explicit, symplectic, symmetric, on the group (splittings, exact flows).
pub(super) const LIE_SYMPLECTIC_EXPLICIT: Properties = Properties {
    lie_group: true,
    ..SYMPLECTIC_EXPLICIT
};
/// Implicit, symplectic, symmetric, on the group (variational integrators).
pub(super) const LIE_VARIATIONAL: Properties = Properties {
    explicit: false,
    ..LIE_SYMPLECTIC_EXPLICIT
};
/// Explicit, neither symplectic nor symmetric, on the group (RKMK, Crouch–Grossman).
const LIE_EXPLICIT: Properties = Properties {
    lie_group: true,
    ..EXPLICIT
};

pub(super) const RIGID_BODY: &str = "rigid body: inertia J (any symmetric positive definite) and potential V(R) with its moment M(R)";
/// The LGVI's: [`RIGID_BODY`], or several orientations by their Lagrangian.
const LGVI_PROBLEM: &str = "rigid body: inertia J (any symmetric positive definite) and potential V(R) with its moment M(R); or a Lagrangian on SO(3)^m × R^n given with its derivatives (several orientations)";
pub(super) const ODE: &str = "first-order ODE y' = f(t, y)";
const SEPARABLE: &str = "separable Hamiltonian H = T(p) + V(q)";
const TAYLOR: &str =
    "first-order ODE whose Taylor coefficients the problem computes (automatic differentiation)";
const TAYLOR_DD: &str =
    "first-order ODE whose Taylor coefficients the problem computes in double-double arithmetic";
const FREE_BODY: &str = "free rigid body (inertia J)";
const LIE_FIELD: &str =
    "vector field on SO(3) × R^n or SO(3)^m × R^n: R_k' = R_k hat(xi_k(t, R, y)), y' = f(t, R, y)";

const RIGID_KINDS: &[ProblemKind] = &[ProblemKind::RigidBody, ProblemKind::CoupledRigidBody];
/// The LGVI's: the rigid kinds, and a Lagrangian on the product of several rotation groups.
const LGVI_KINDS: &[ProblemKind] = &[
    ProblemKind::RigidBody,
    ProblemKind::CoupledRigidBody,
    ProblemKind::ProductLagrangian,
];

impl Stepping {
    /// Order of convergence: the table's where there is one.
    #[must_use]
    pub const fn order(self) -> Order {
        Order::Finite(match self {
            Stepping::Explicit(m) => m.order(),
            Stepping::Gauss(t) | Stepping::LieGauss(t) => t.order(),
            Stepping::Composition { table, .. } => table.order,
            Stepping::SymplecticEuler => 1,
            Stepping::Cg3 => 3,
            Stepping::Rkmk4 => 4,
            Stepping::StormerVerlet
            | Stepping::Strang
            | Stepping::Lgvi
            | Stepping::PrincipalAxisSplitting
            | Stepping::ExactSplitting
            | Stepping::Dmv => 2,
            Stepping::Taylor(TaylorOrder::Fixed(p)) => p,
            Stepping::Taylor(TaylorOrder::FromTolerance) | Stepping::TaylorDoubleDouble => {
                return Order::Variable;
            }
            Stepping::ExactFlow => return Order::Exact,
        })
    }

    /// Stages: right-hand-side evaluations per attempt, or base steps per step.
    #[must_use]
    pub const fn stages(self) -> u32 {
        match self {
            Stepping::Explicit(m) => m.stages(),
            Stepping::Gauss(t) | Stepping::LieGauss(t) => t.size() as u32,
            Stepping::Composition { table, .. } => table.gammas.len() as u32,
            Stepping::Rkmk4 => 4,
            Stepping::Cg3 => 3,
            Stepping::SymplecticEuler
            | Stepping::StormerVerlet
            | Stepping::Strang
            | Stepping::Lgvi
            | Stepping::PrincipalAxisSplitting
            | Stepping::ExactSplitting
            | Stepping::Dmv
            | Stepping::ExactFlow
            | Stepping::Taylor(_)
            | Stepping::TaylorDoubleDouble => 1,
        }
    }

    /// The family a method of this stepping belongs to (a composition of a base under a
    /// short name, `lgvi4` or `split4`, is registered under its base's family instead).
    #[must_use]
    pub const fn family(self) -> Family {
        match self {
            Stepping::Explicit(_) => Family::ExplicitRungeKutta,
            Stepping::Gauss(_) => Family::GaussLegendre,
            Stepping::SymplecticEuler | Stepping::StormerVerlet => Family::SymplecticPartitioned,
            Stepping::Composition { .. } => Family::Composition,
            Stepping::Lgvi
            | Stepping::LieGauss(_)
            | Stepping::Rkmk4
            | Stepping::Cg3
            | Stepping::Dmv => Family::LieGroup,
            Stepping::Strang | Stepping::PrincipalAxisSplitting | Stepping::ExactSplitting => {
                Family::Splitting
            }
            Stepping::ExactFlow => Family::ExactFlow,
            Stepping::Taylor(_) | Stepping::TaylorDoubleDouble => Family::Taylor,
        }
    }

    /// Qualitative properties.
    #[must_use]
    pub const fn properties(self) -> Properties {
        match self {
            Stepping::Explicit(m) if m.adaptive() => ADAPTIVE,
            Stepping::Explicit(_) => EXPLICIT,
            Stepping::Gauss(_) => GAUSS,
            Stepping::SymplecticEuler => Properties {
                symmetric: false,
                ..SYMPLECTIC_EXPLICIT
            },
            Stepping::StormerVerlet => SYMPLECTIC_EXPLICIT,
            Stepping::Strang => Properties {
                symplectic: false,
                ..SYMPLECTIC_EXPLICIT
            },
            Stepping::Composition { base, .. } => base.properties,
            Stepping::Lgvi | Stepping::LieGauss(_) | Stepping::Dmv => LIE_VARIATIONAL,
            Stepping::Rkmk4 | Stepping::Cg3 => LIE_EXPLICIT,
            Stepping::PrincipalAxisSplitting | Stepping::ExactSplitting => LIE_SYMPLECTIC_EXPLICIT,
            Stepping::ExactFlow => Properties {
                exact: true,
                ..LIE_SYMPLECTIC_EXPLICIT
            },
            Stepping::Taylor(TaylorOrder::FromTolerance) | Stepping::TaylorDoubleDouble => ADAPTIVE,
            Stepping::Taylor(TaylorOrder::Fixed(_)) => EXPLICIT,
        }
    }

    /// What the method needs of the problem, in words.
    #[must_use]
    pub const fn problem(self) -> &'static str {
        match self {
            Stepping::Explicit(_) | Stepping::Gauss(_) => ODE,
            Stepping::SymplecticEuler | Stepping::StormerVerlet => SEPARABLE,
            Stepping::Strang => "split system given by the flows of its parts",
            Stepping::Composition { base, .. } => base.problem,
            Stepping::Lgvi => LGVI_PROBLEM,
            Stepping::LieGauss(_) | Stepping::PrincipalAxisSplitting | Stepping::ExactSplitting => {
                RIGID_BODY
            }
            Stepping::Rkmk4 | Stepping::Cg3 => LIE_FIELD,
            Stepping::Dmv | Stepping::ExactFlow => FREE_BODY,
            Stepping::Taylor(_) => TAYLOR,
            Stepping::TaylorDoubleDouble => TAYLOR_DD,
        }
    }

    /// The kinds of problem it integrates.
    #[must_use]
    pub const fn problems(self) -> &'static [ProblemKind] {
        match self {
            Stepping::Explicit(_) | Stepping::Gauss(_) => &[ProblemKind::Ode],
            Stepping::SymplecticEuler | Stepping::StormerVerlet => &[ProblemKind::Separable],
            Stepping::Strang => &[ProblemKind::Split],
            Stepping::Composition { base, .. } => base.problems,
            Stepping::Lgvi => LGVI_KINDS,
            Stepping::LieGauss(_) => RIGID_KINDS,
            Stepping::PrincipalAxisSplitting | Stepping::ExactSplitting => {
                &[ProblemKind::RigidBody]
            }
            Stepping::Rkmk4 | Stepping::Cg3 => {
                &[ProblemKind::LieVectorField, ProblemKind::ProductVectorField]
            }
            Stepping::Dmv | Stepping::ExactFlow => &[ProblemKind::FreeRigidBody],
            Stepping::Taylor(_) => &[ProblemKind::TaylorSeries],
            Stepping::TaylorDoubleDouble => &[ProblemKind::DoubleDoubleTaylorSeries],
        }
    }
}

/// Störmer–Verlet as the base of a composition table named alone.
pub const VERLET_BASE: Base = Base {
    name: "verlet",
    stepper: BaseStepper::StormerVerlet,
    problem: "separable Hamiltonian H = T(p) + V(q), whose Störmer–Verlet the table composes",
    problems: &[ProblemKind::Separable],
    properties: SYMPLECTIC_EXPLICIT,
    summary: "",
};
/// The LGVI as a base (`TABLE:lgvi`).
pub const LGVI_BASE: Base = Base {
    name: "lgvi",
    stepper: BaseStepper::Lgvi,
    problem: LGVI_PROBLEM,
    problems: LGVI_KINDS,
    properties: LIE_VARIATIONAL,
    summary: "the table before the colon composing the LGVI (Lee, Leok & McClamroch 2005)",
};
/// The principal-axis splitting as a base (`TABLE:split2`).
pub const SPLIT2_BASE: Base = Base {
    name: "split2",
    stepper: BaseStepper::PrincipalAxisSplitting,
    problem: RIGID_BODY,
    problems: &[ProblemKind::RigidBody],
    properties: LIE_SYMPLECTIC_EXPLICIT,
    summary: "the table before the colon composing split2, the principal-axis splitting",
};
/// The exact-flow splitting as a base (`TABLE:split-exact2`).
pub const SPLIT_EXACT2_BASE: Base = Base {
    name: "split-exact2",
    stepper: BaseStepper::ExactSplitting,
    problem: RIGID_BODY,
    problems: &[ProblemKind::RigidBody],
    properties: LIE_SYMPLECTIC_EXPLICIT,
    summary: "the table before the colon composing split-exact2, potential kicks around the exact free flow",
};
/// The implicit midpoint rule as a base (`TABLE:gauss2`).
pub const GAUSS2_BASE: Base = Base {
    name: "gauss2",
    stepper: BaseStepper::Gauss2,
    problem: ODE,
    problems: &[ProblemKind::Ode],
    properties: GAUSS,
    summary: "the table before the colon composing gauss2, the implicit midpoint rule",
};
