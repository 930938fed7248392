//! Lagrangian mechanics on the expression graph: rotations, angular velocities, kinetic
//! energies, and the equations of motion `M(q, t) q̈ = f(q, q̇, t)` with the energy function
//! and the momenta, all as nodes of one [`Graph`].
//!
//! The recipe is the article's (Rundquist, *Rigid bodies, formulation and examples*):
//! the angular velocity of a body from its orientation's rates, in the body frame;
//! `T = ½ M |v_c|² + ½ ω·(I_c ω)` for a rigid body with its inertia tensor `I_c` about the
//! centre of mass computed once; `½ m |v|²` for a point mass, its velocity the time derivative
//! of its position taken symbolically. In a frame turning at `Ω` (the Earth), velocities are
//! `ṙ + Ω × r` and a body's angular velocity `ω + Rᵀ Ω`, so that the Coriolis and centrifugal
//! forces follow from `T` (Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §4.10).
//!
//! With `L = T − V` the Euler–Lagrange equations are
//! `Σⱼ ∂²L/∂q̇ᵢ∂q̇ⱼ q̈ⱼ = ∂L/∂qᵢ − Σⱼ ∂²L/∂q̇ᵢ∂qⱼ q̇ⱼ − ∂²L/∂q̇ᵢ∂t`;
//! the energy function (Jacobi integral) is `h = Σ q̇ᵢ ∂L/∂q̇ᵢ − L`, conserved when
//! `∂L/∂t = 0`, and the momentum `∂L/∂q̇ₖ` of a cyclic coordinate (`∂L/∂qₖ = 0`) is conserved.

use crate::expr::scalar::TapeScalar;
use crate::expr::{Fun, Graph, Id};

/// A 3-vector of nodes.
pub type V3 = [Id; 3];
/// A 3×3 matrix of nodes, by rows.
pub type M3 = [[Id; 3]; 3];

/// The input layout of a model: `t`, then the configuration (`n` coordinates, then the
/// rotation matrix of each of `so3` frames integrated on SO(3), by rows), then the velocities
/// (`n` rates, then each SO(3) frame's body angular velocity), then the parameters. Inputs
/// `1 ..` are the state `y` in order: input `k + 1` is `y[k]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of scalar generalized coordinates.
    pub n: usize,
    /// Number of orientations integrated on SO(3).
    pub so3: usize,
}

impl Layout {
    /// The input number of time.
    pub const T: u32 = 0;

    /// The input number of coordinate `i`.
    #[must_use]
    pub fn q(self, i: usize) -> u32 {
        1 + i as u32
    }

    /// The input number of entry `(a, b)` of SO(3) frame `f`'s rotation matrix.
    #[must_use]
    pub fn rot(self, f: usize, a: usize, b: usize) -> u32 {
        (1 + self.n + 9 * f + 3 * a + b) as u32
    }

    /// The input number of the rate of coordinate `i`.
    #[must_use]
    pub fn qd(self, i: usize) -> u32 {
        (1 + self.n + 9 * self.so3 + i) as u32
    }

    /// The input number of component `c` of SO(3) frame `f`'s body angular velocity.
    #[must_use]
    pub fn omega(self, f: usize, c: usize) -> u32 {
        (1 + 2 * self.n + 9 * self.so3 + 3 * f + c) as u32
    }

    /// Number of velocities (the mass matrix's size): the rates and the angular velocities.
    #[must_use]
    pub fn dof(self) -> usize {
        self.n + 3 * self.so3
    }

    /// The input number of velocity `i` (rates first, then angular velocities): `i < dof()`.
    #[must_use]
    pub fn velocity(self, i: usize) -> u32 {
        if i < self.n {
            self.qd(i)
        } else {
            let k = i - self.n;
            self.omega(k / 3, k % 3)
        }
    }

    /// Length of the state `y`: configuration, then velocities.
    #[must_use]
    pub fn state_len(self) -> usize {
        2 * self.n + 12 * self.so3
    }

    /// Index in `y` of the first velocity.
    #[must_use]
    pub fn velocities_at(self) -> usize {
        self.n + 9 * self.so3
    }

    /// The input number of parameter `j`.
    #[must_use]
    pub fn param(self, j: usize) -> u32 {
        (1 + self.state_len() + j) as u32
    }

    /// Whether input `k` is a parameter (fixed during a run).
    #[must_use]
    pub fn is_param(self, k: u32) -> bool {
        k as usize > self.state_len()
    }

    /// SO(3) frame `f`'s rotation matrix as inputs.
    pub fn rotation(self, g: &mut Graph, f: usize) -> M3 {
        [0, 1, 2].map(|a| [0, 1, 2].map(|b| g.input(self.rot(f, a, b))))
    }

    /// SO(3) frame `f`'s body angular velocity as inputs.
    pub fn angular_velocity(self, g: &mut Graph, f: usize) -> V3 {
        [0, 1, 2].map(|c| g.input(self.omega(f, c)))
    }
}

/// Vector and matrix operations on nodes.
pub struct Algebra<'g> {
    /// The graph the nodes are built in.
    pub g: &'g mut Graph,
}

impl Algebra<'_> {
    /// The zero vector.
    pub fn zero3(&mut self) -> V3 {
        let z = self.g.constant(0.0);
        [z; 3]
    }

    /// The identity matrix.
    pub fn identity(&mut self) -> M3 {
        let (z, o) = (self.g.constant(0.0), self.g.constant(1.0));
        [[o, z, z], [z, o, z], [z, z, o]]
    }

    /// `a + b`.
    pub fn add3(&mut self, a: V3, b: V3) -> V3 {
        [0, 1, 2].map(|i| self.g.add(a[i], b[i]))
    }

    /// `s a`.
    pub fn scale3(&mut self, s: Id, a: V3) -> V3 {
        [0, 1, 2].map(|i| self.g.mul(s, a[i]))
    }

    /// `a · b`.
    pub fn dot(&mut self, a: V3, b: V3) -> Id {
        let t = [0, 1, 2].map(|i| self.g.mul(a[i], b[i]));
        self.g.sum(&t)
    }

    /// `a × b`.
    pub fn cross(&mut self, a: V3, b: V3) -> V3 {
        let c = |g: &mut Graph, i: usize, j: usize| {
            let x = g.mul(a[i], b[j]);
            let y = g.mul(a[j], b[i]);
            g.sub(x, y)
        };
        [c(self.g, 1, 2), c(self.g, 2, 0), c(self.g, 0, 1)]
    }

    /// `A b`.
    pub fn mat_vec(&mut self, a: &M3, b: V3) -> V3 {
        [0, 1, 2].map(|i| self.dot(a[i], b))
    }

    /// `Aᵀ b`.
    pub fn mat_t_vec(&mut self, a: &M3, b: V3) -> V3 {
        [0, 1, 2].map(|i| {
            let col = [a[0][i], a[1][i], a[2][i]];
            self.dot(col, b)
        })
    }

    /// `A B`.
    pub fn mat_mul(&mut self, a: &M3, b: &M3) -> M3 {
        let mut out = [[a[0][0]; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let col = [b[0][j], b[1][j], b[2][j]];
                out[i][j] = self.dot(a[i], col);
            }
        }
        out
    }

    /// The rotation by `angle` about coordinate axis `axis` (0, 1, 2 for x, y, z), active,
    /// right-handed: `R_z(θ) = [[c, −s, 0], [s, c, 0], [0, 0, 1]]`.
    pub fn axis_rotation(&mut self, axis: usize, angle: Id) -> M3 {
        let c = self.g.call(Fun::Cos, angle);
        let s = self.g.call(Fun::Sin, angle);
        let ns = self.g.neg(s);
        let (z, o) = (self.g.constant(0.0), self.g.constant(1.0));
        match axis {
            0 => [[o, z, z], [z, c, ns], [z, s, c]],
            1 => [[c, z, s], [z, o, z], [ns, z, c]],
            _ => [[c, ns, z], [s, c, z], [z, z, o]],
        }
    }

    /// The left-trivialized derivative of `e` along SO(3) frame `f`'s rotation `R`: the vector
    /// `τ` with `d/dε e(R exp(ε ĥ))|₀ = τ · h`. With `A = (∂e/∂R)ᵀ R`,
    /// `τ = (A₂₃ − A₃₂, A₃₁ − A₁₃, A₁₂ − A₂₁)` (`tr(A ĥ)` written out). For
    /// `e = −m g l e_z · R e₃` (a heavy top) it is the gravity torque `m g l Γ × e₃`,
    /// `Γ = Rᵀ e_z` (Holm, *Geometric Mechanics* II, §7).
    pub fn rotation_derivative(&mut self, e: Id, layout: Layout, f: usize) -> V3 {
        let r = layout.rotation(self.g, f);
        let de: M3 = [0, 1, 2].map(|a| [0, 1, 2].map(|b| self.g.diff(e, layout.rot(f, a, b))));
        // A_ab = Σ_c ∂e/∂R_ca R_cb.
        let mut a = [[de[0][0]; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let terms = [0, 1, 2].map(|c| self.g.mul(de[c][i], r[c][j]));
                a[i][j] = self.g.sum(&terms);
            }
        }
        let pair = |g: &mut Graph, (i, j): (usize, usize)| g.sub(a[i][j], a[j][i]);
        [
            pair(self.g, (1, 2)),
            pair(self.g, (2, 0)),
            pair(self.g, (0, 1)),
        ]
    }

    /// The total time derivative of an expression of `t` and the configuration:
    /// `∂e/∂t + Σᵢ ∂e/∂qᵢ q̇ᵢ + Σ_f ω_f · τ_f(e)`, the last sum over the SO(3) frames, whose
    /// rotations move as `Ṙ = R ω̂` ([`Self::rotation_derivative`]).
    pub fn time_derivative(&mut self, e: Id, layout: Layout) -> Id {
        let mut terms = vec![self.g.diff(e, Layout::T)];
        for i in 0..layout.n {
            let d = self.g.diff(e, layout.q(i));
            let qd = self.g.input(layout.qd(i));
            terms.push(self.g.mul(d, qd));
        }
        for f in 0..layout.so3 {
            let tau = self.rotation_derivative(e, layout, f);
            let w = layout.angular_velocity(self.g, f);
            terms.push(self.dot(w, tau));
        }
        self.g.sum(&terms)
    }

    /// [`Self::time_derivative`] of each component.
    pub fn time_derivative3(&mut self, v: V3, layout: Layout) -> V3 {
        v.map(|e| self.time_derivative(e, layout))
    }
}

/// An orientation as a chain of rotations about fixed axes, `R = R_{a₁}(θ₁) ⋯ R_{a_k}(θ_k)`
/// (body → model frame), its angles expressions of the coordinates and time.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// `(axis, angle)` in product order.
    pub links: Vec<(usize, Id)>,
}

impl Chain {
    /// `R`.
    pub fn rotation(&self, alg: &mut Algebra<'_>) -> M3 {
        let mut r = alg.identity();
        for &(axis, angle) in &self.links {
            let step = alg.axis_rotation(axis, angle);
            r = alg.mat_mul(&r, &step);
        }
        r
    }

    /// The angular velocity in the body frame,
    /// `ω = Σᵢ (R_{i+1} ⋯ R_k)ᵀ eᵢ θ̇ᵢ` (each link turns what follows it).
    pub fn omega_body(&self, alg: &mut Algebra<'_>, layout: Layout) -> V3 {
        let mut omega = alg.zero3();
        // P = R_{i+1} ⋯ R_k, built from the end.
        let mut p = alg.identity();
        for &(axis, angle) in self.links.iter().rev() {
            let rate = alg.time_derivative(angle, layout);
            let mut e = alg.zero3();
            e[axis] = rate;
            let term = alg.mat_t_vec(&p, e);
            omega = alg.add3(omega, term);
            let step = alg.axis_rotation(axis, angle);
            p = alg.mat_mul(&step, &p);
        }
        omega
    }
}

/// The assembled equations of a model.
#[derive(Debug, Clone, PartialEq)]
pub struct Equations {
    /// `M`, row-major, `dof × dof` over the velocities ([`Layout::velocity`]).
    pub mass: Vec<Id>,
    /// `f`, one per velocity.
    pub force: Vec<Id>,
    /// The energy function `h = Σ q̇ᵢ pᵢ − L`.
    pub energy: Id,
    /// The momenta `∂L/∂vᵢ`, one per velocity (`Π` of each SO(3) frame after the rates').
    pub momenta: Vec<Id>,
    /// `∂L/∂qᵢ` of the scalar coordinates: zero for a cyclic coordinate.
    pub dl_dq: Vec<Id>,
    /// `∂L/∂t`: zero when the energy function is conserved.
    pub dl_dt: Id,
    /// The Lagrangian.
    pub lagrangian: Id,
}

/// The equations of motion of `lagrangian` in the layout's velocities `v = (q̇, ω_1, …)`:
/// `M v̇ = f` with `M = ∂²L/∂v²`, and `f = g − D_t(∂L/∂v)` where `D_t` is the time derivative
/// at fixed velocities ([`Algebra::time_derivative`]) and `g` the generalized force:
/// `∂L/∂qᵢ` for a scalar coordinate (Euler–Lagrange), `Π × ω + τ(L)` for an orientation on
/// SO(3) with `Π = ∂L/∂ω` (Euler–Poincaré with the configuration's torque: Holm, *Geometric
/// Mechanics* II, §7; Marsden & Ratiu, *Introduction to Mechanics and Symmetry*, §13).
pub fn equations(g: &mut Graph, lagrangian: Id, layout: Layout) -> Equations {
    let dof = layout.dof();
    let momenta: Vec<Id> = (0..dof)
        .map(|i| g.diff(lagrangian, layout.velocity(i)))
        .collect();
    let mut mass = Vec::with_capacity(dof * dof);
    for i in 0..dof {
        for j in 0..dof {
            mass.push(g.diff(momenta[i], layout.velocity(j)));
        }
    }
    let dl_dq: Vec<Id> = (0..layout.n)
        .map(|i| g.diff(lagrangian, layout.q(i)))
        .collect();
    let mut generalized = dl_dq.clone();
    for f in 0..layout.so3 {
        let mut alg = Algebra { g: &mut *g };
        let pi = [0, 1, 2].map(|c| momenta[layout.n + 3 * f + c]);
        let w = layout.angular_velocity(alg.g, f);
        let gyro = alg.cross(pi, w);
        let tau = alg.rotation_derivative(lagrangian, layout, f);
        generalized.extend(alg.add3(gyro, tau));
    }
    // f_i = g_i − Σⱼ ∂pᵢ/∂qⱼ q̇ⱼ − Σ_f ω_f · τ_f(pᵢ) − ∂pᵢ/∂t.
    let mut force = Vec::with_capacity(dof);
    for i in 0..dof {
        let mut terms = vec![generalized[i]];
        for j in 0..layout.n {
            let d = g.diff(momenta[i], layout.q(j));
            let qd = g.input(layout.qd(j));
            let m = g.mul(d, qd);
            terms.push(g.neg(m));
        }
        for f in 0..layout.so3 {
            let mut alg = Algebra { g: &mut *g };
            let tau = alg.rotation_derivative(momenta[i], layout, f);
            let w = layout.angular_velocity(alg.g, f);
            let wt = alg.dot(w, tau);
            terms.push(g.neg(wt));
        }
        let dt = g.diff(momenta[i], Layout::T);
        terms.push(g.neg(dt));
        force.push(g.sum(&terms));
    }
    let pv: Vec<Id> = (0..dof)
        .map(|i| {
            let v = g.input(layout.velocity(i));
            g.mul(v, momenta[i])
        })
        .collect();
    let sum = g.sum(&pv);
    let energy = g.sub(sum, lagrangian);
    let dl_dt = g.diff(lagrangian, Layout::T);
    Equations {
        mass,
        force,
        energy,
        momenta,
        dl_dq,
        dl_dt,
        lagrangian,
    }
}

/// Solves `M x = b` in place for a symmetric positive definite `M` (row-major `n × n`, its
/// lower triangle overwritten by the Cholesky factor), `b` becoming `x`. Returns the smallest
/// ratio of a pivot to the largest diagonal entry of `M` (`≤ 0`: not positive definite, and
/// `b` is left as it is).
pub fn cholesky_solve(m: &mut [f64], b: &mut [f64], n: usize) -> f64 {
    let worst = cholesky_factor(m, n);
    if worst > 0.0 {
        cholesky_substitute(m, b, n);
    }
    worst
}

/// Overwrites the lower triangle of the symmetric `M` (row-major `n × n`) with its Cholesky
/// factor `L` (`M = L Lᵀ`). Returns the smallest ratio of a pivot to the largest diagonal
/// entry of `M`; `≤ 0` when `M` is not positive definite (the factor is then incomplete).
pub fn cholesky_factor<S: TapeScalar>(m: &mut [S], n: usize) -> f64 {
    let mut scale = 0.0f64;
    for i in 0..n {
        scale = scale.max(m[i * n + i].leading().abs());
    }
    let mut worst = f64::INFINITY;
    for j in 0..n {
        let mut d = m[j * n + j];
        for k in 0..j {
            d = d - m[j * n + k] * m[j * n + k];
        }
        let ratio = d.leading() / scale;
        worst = worst.min(ratio);
        if !(d.leading() > 0.0) {
            return ratio.min(0.0);
        }
        let d = d.fun(Fun::Sqrt);
        m[j * n + j] = d;
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s = s - m[i * n + k] * m[j * n + k];
            }
            m[i * n + j] = s.quotient(d);
        }
    }
    worst
}

/// Solves `L Lᵀ x = b` in place with the factor of [`cholesky_factor`].
pub fn cholesky_substitute<S: TapeScalar>(m: &[S], b: &mut [S], n: usize) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s = s - m[i * n + k] * b[k];
        }
        b[i] = s.quotient(m[i * n + i]);
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s = s - m[k * n + i] * b[k];
        }
        b[i] = s.quotient(m[i * n + i]);
    }
}

/// The first-order system `y' = F(t, y)` of a model's equations as nodes: what one
/// evaluation of its right-hand side computes, so that the whole of it is one tape (and one
/// compiled function) rather than a tape followed by a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct FirstOrder {
    /// `y'` in state order ([`Layout`]): `q̇`, then `R ω̂` of each SO(3) frame (by rows), then
    /// the accelerations `M⁻¹ f`.
    pub derivative: Vec<Id>,
    /// The pivots `d_j` of the Cholesky factorization of `M` (before their square roots): `M`
    /// is positive definite, and the accelerations are valid, where every one is positive.
    pub pivots: Vec<Id>,
}

/// [`FirstOrder`] of `equations`: the kinematics `q' = q̇`, `Ṙ = R ω̂`, and `v̇ = M⁻¹ f` by the
/// operations of [`cholesky_factor`] and [`cholesky_substitute`] on the nodes of `M` and `f`,
/// in their order. A mass matrix of the parameters alone (`constant_mass`) is inverted on the
/// nodes (its inverse then depends on the parameters only: a tape's prelude), and each
/// acceleration is the sum `Σⱼ (M⁻¹)ᵢⱼ fⱼ` in the order of `j`; otherwise `f` goes through
/// the forward and back substitutions. The graph folds the products with structural zeros
/// of `M` (a diagonal inertia), which changes no finite value.
pub fn first_order(
    g: &mut Graph,
    equations: &Equations,
    layout: Layout,
    constant_mass: bool,
) -> FirstOrder {
    let (n, dof) = (layout.n, layout.dof());
    let mut derivative: Vec<Id> = (0..n).map(|i| g.input(layout.qd(i))).collect();
    for f in 0..layout.so3 {
        let r = layout.rotation(g, f);
        let [wx, wy, wz] = layout.angular_velocity(g, f);
        let mut cross = |a: Id, b: Id, c: Id, d: Id| {
            let x = g.mul(a, b);
            let y = g.mul(c, d);
            g.sub(x, y)
        };
        for [r0, r1, r2] in r {
            derivative.push(cross(r1, wz, r2, wy));
            derivative.push(cross(r2, wx, r0, wz));
            derivative.push(cross(r0, wy, r1, wx));
        }
    }
    // The lower triangle of L (row-major, as `cholesky_factor` leaves it in M).
    let mut l = equations.mass.clone();
    let mut pivots = Vec::with_capacity(dof);
    for j in 0..dof {
        let mut d = l[j * dof + j];
        for k in 0..j {
            let p = g.mul(l[j * dof + k], l[j * dof + k]);
            d = g.sub(d, p);
        }
        pivots.push(d);
        let d = g.call(Fun::Sqrt, d);
        l[j * dof + j] = d;
        for i in j + 1..dof {
            let mut s = l[i * dof + j];
            for k in 0..j {
                let p = g.mul(l[i * dof + k], l[j * dof + k]);
                s = g.sub(s, p);
            }
            l[i * dof + j] = g.div(s, d);
        }
    }
    let substitute = |g: &mut Graph, b: &mut [Id]| {
        for i in 0..dof {
            let mut s = b[i];
            for k in 0..i {
                let p = g.mul(l[i * dof + k], b[k]);
                s = g.sub(s, p);
            }
            b[i] = g.div(s, l[i * dof + i]);
        }
        for i in (0..dof).rev() {
            let mut s = b[i];
            for k in i + 1..dof {
                let p = g.mul(l[k * dof + i], b[k]);
                s = g.sub(s, p);
            }
            b[i] = g.div(s, l[i * dof + i]);
        }
    };
    if constant_mass {
        // The inverse column by column, as the substitution of each unit vector.
        let (zero, one) = (g.constant(0.0), g.constant(1.0));
        let mut inverse = vec![zero; dof * dof];
        for j in 0..dof {
            let mut e = vec![zero; dof];
            e[j] = one;
            substitute(g, &mut e);
            for i in 0..dof {
                inverse[i * dof + j] = e[i];
            }
        }
        for i in 0..dof {
            let terms: Vec<Id> = (0..dof)
                .map(|j| g.mul(inverse[i * dof + j], equations.force[j]))
                .collect();
            derivative.push(g.sum(&terms));
        }
    } else {
        let mut b = equations.force.clone();
        substitute(g, &mut b);
        derivative.extend(b);
    }
    FirstOrder { derivative, pivots }
}
