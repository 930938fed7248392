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

use crate::expr::{Fun, Graph, Id};

/// A 3-vector of nodes.
pub type V3 = [Id; 3];
/// A 3×3 matrix of nodes, by rows.
pub type M3 = [[Id; 3]; 3];

/// The input layout of a model: `t`, then `n` coordinates, `n` rates, then the parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of generalized coordinates.
    pub n: usize,
}

impl Layout {
    /// The input number of time.
    pub const T: u32 = 0;

    /// The input number of coordinate `i`.
    #[must_use]
    pub fn q(self, i: usize) -> u32 {
        1 + i as u32
    }

    /// The input number of the rate of coordinate `i`.
    #[must_use]
    pub fn qd(self, i: usize) -> u32 {
        (1 + self.n + i) as u32
    }

    /// The input number of parameter `j`.
    #[must_use]
    pub fn param(self, j: usize) -> u32 {
        (1 + 2 * self.n + j) as u32
    }

    /// Whether input `k` is a parameter (fixed during a run).
    #[must_use]
    pub fn is_param(self, k: u32) -> bool {
        k as usize > 2 * self.n
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

    /// The total time derivative `∂e/∂t + Σᵢ ∂e/∂qᵢ q̇ᵢ` of an expression of `t` and the
    /// coordinates.
    pub fn time_derivative(&mut self, e: Id, layout: Layout) -> Id {
        let mut terms = vec![self.g.diff(e, Layout::T)];
        for i in 0..layout.n {
            let d = self.g.diff(e, layout.q(i));
            let qd = self.g.input(layout.qd(i));
            terms.push(self.g.mul(d, qd));
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
    /// `M(q, t)`, row-major, `n × n`.
    pub mass: Vec<Id>,
    /// `f(q, q̇, t)`.
    pub force: Vec<Id>,
    /// The energy function `h = Σ q̇ᵢ pᵢ − L`.
    pub energy: Id,
    /// The momenta `pᵢ = ∂L/∂q̇ᵢ`.
    pub momenta: Vec<Id>,
    /// `∂L/∂qᵢ`: zero for a cyclic coordinate.
    pub dl_dq: Vec<Id>,
    /// `∂L/∂t`: zero when the energy function is conserved.
    pub dl_dt: Id,
    /// The Lagrangian.
    pub lagrangian: Id,
}

/// The Euler–Lagrange equations of `lagrangian` in the layout's coordinates.
pub fn equations(g: &mut Graph, lagrangian: Id, layout: Layout) -> Equations {
    let n = layout.n;
    let momenta: Vec<Id> = (0..n).map(|i| g.diff(lagrangian, layout.qd(i))).collect();
    let mut mass = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            mass.push(g.diff(momenta[i], layout.qd(j)));
        }
    }
    let mut force = Vec::with_capacity(n);
    let mut dl_dq = Vec::with_capacity(n);
    for i in 0..n {
        let dl = g.diff(lagrangian, layout.q(i));
        dl_dq.push(dl);
        let mut terms = vec![dl];
        for j in 0..n {
            let d = g.diff(momenta[i], layout.q(j));
            let qd = g.input(layout.qd(j));
            let m = g.mul(d, qd);
            terms.push(g.neg(m));
        }
        let dt = g.diff(momenta[i], Layout::T);
        terms.push(g.neg(dt));
        force.push(g.sum(&terms));
    }
    let pq: Vec<Id> = (0..n)
        .map(|i| {
            let qd = g.input(layout.qd(i));
            g.mul(qd, momenta[i])
        })
        .collect();
    let sum = g.sum(&pq);
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
pub fn cholesky_factor(m: &mut [f64], n: usize) -> f64 {
    let mut scale = 0.0f64;
    for i in 0..n {
        scale = scale.max(m[i * n + i].abs());
    }
    let mut worst = f64::INFINITY;
    for j in 0..n {
        let mut d = m[j * n + j];
        for k in 0..j {
            d -= m[j * n + k] * m[j * n + k];
        }
        let ratio = d / scale;
        worst = worst.min(ratio);
        if !(d > 0.0) {
            return ratio.min(0.0);
        }
        let d = d.sqrt();
        m[j * n + j] = d;
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s -= m[i * n + k] * m[j * n + k];
            }
            m[i * n + j] = s / d;
        }
    }
    worst
}

/// Solves `L Lᵀ x = b` in place with the factor of [`cholesky_factor`].
pub fn cholesky_substitute(m: &[f64], b: &mut [f64], n: usize) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= m[i * n + k] * b[k];
        }
        b[i] = s / m[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= m[k * n + i] * b[k];
        }
        b[i] = s / m[i * n + i];
    }
}
