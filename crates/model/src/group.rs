//! A model with one orientation on SO(3) as the problems of the Lie-group methods: a rigid
//! body in a potential ([`ModelRigidBody`], [`tumble_integrators::rigid::RigidBody`]) when the
//! orientation is its only coordinate, a body coupled to the scalar coordinates
//! ([`ModelCoupled`], [`CoupledLagrangian`]) when there are some.
//!
//! Both need the Lagrangian in the form the methods integrate:
//!
//! ```text
//! L(R, Ω, q, q̇) = ½ Ωᵀ J(q) Ω + Ωᵀ B(q) q̇ + ½ q̇ᵀ M(q) q̇ − V(R, q),
//! ```
//!
//! the kinetic energy a quadratic form in the velocities `v = (q̇, Ω)` whose matrix depends on
//! the scalar coordinates only, and nothing depending on time. Its blocks are the model's mass
//! matrix `∂²L/∂v²` (at `R = 𝟙`: a matrix that depends on `R` only through `RᵀR = 𝟙`, as the
//! kinetic energy of a body whose centre is written as `R c`, is the same at every rotation),
//! their derivatives in `q` are symbolic derivatives on the expression graph, and the
//! potential's are those of `L` at `v = 0`: `V = −L`, `∂V/∂q = −∂L/∂q`, and the body-frame moment
//! `M = −∂/∂η V(R exp(hat η))|₀` is the left-trivialized derivative of `L` along `R`
//! ([`Algebra::rotation_derivative`]). Every quantity is an instruction tape evaluated in a
//! workspace allocated once per run.
//!
//! Whether a model has the form is checked numerically at sample states (rotations
//! `exp(hat η)`, coordinates and rates in ±1.5, `t` in [0, 3]) at the run's parameters:
//! `∂L/∂t = 0`, the mass matrix the same as at `(𝟙, q, 0, 0)`, the momenta `p = M v`, and
//! `L(v) − L(0) = ½ v·p`, each to `1e-10` of the sample's own magnitude. A rotating frame
//! (terms linear in the velocities), a coordinate prescribed in time, or an inertia that turns
//! with the body fails it, and the Lie-group methods are not offered.

use std::cell::RefCell;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use tumble_integrators::rigid::{
    CoupledLagrangian, FreeRigidBody, KineticBlocks, KineticJet, RigidBody, Scalar,
};

use crate::expr::tape::Tape;
use crate::file::Model;
use crate::mechanics::{Algebra, Layout};

/// The tapes of a model with one orientation on SO(3) for the Lie-group methods.
#[derive(Debug)]
pub(crate) struct Group {
    layout: Layout,
    /// The mass matrix (`dof × dof`, row-major; rates then angular velocity) at `R = 𝟙`,
    /// `v = 0`, `t = 0`: a function of `q` and the parameters.
    blocks: Tape,
    /// `blocks`, then `∂/∂qᵢ` of it for each `i`.
    jet: Tape,
    /// `∂²/∂qᵢ∂qⱼ` of the mass matrix, `i` major.
    hessian: Tape,
    /// At `v = 0`, `t = 0`: the moment `τ(L)` (3), `∂L/∂q` (`n`), `L`.
    forces: Tape,
    /// At any input: `∂L/∂t`, `L`, the momenta (`dof`), the mass matrix (`dof²`).
    check: Tape,
}

/// A short, fixed sequence of sample values in [0, 1) (golden-ratio steps).
pub(crate) struct Samples(pub(crate) f64);

impl Samples {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = (self.0 + 0.618_033_988_749_894_9).fract();
        self.0
    }
}

impl Group {
    /// The tapes of `model` (one orientation on SO(3)), built on its graph.
    pub(crate) fn new(model: &mut Model) -> Self {
        let layout = model.layout;
        let (n, dof) = (layout.n, layout.dof());
        let eq = model.equations.clone();
        let g = &mut model.graph;
        let velocity = |k: u32| (0..dof).any(|i| layout.velocity(i) == k);
        let rotation = |k: u32| (0..3).any(|a| (0..3).any(|b| layout.rot(0, a, b) == k));
        let mut first = eq.mass.clone();
        for i in 0..n {
            for &m in &eq.mass {
                first.push(g.diff(m, layout.q(i)));
            }
        }
        let mut second = Vec::with_capacity(n * n * dof * dof);
        for i in 0..n {
            for j in 0..n {
                for k in 0..dof * dof {
                    let d = first[(1 + i) * dof * dof + k];
                    second.push(g.diff(d, layout.q(j)));
                }
            }
        }
        let mut forces = Algebra { g: &mut *g }
            .rotation_derivative(eq.lagrangian, layout, 0)
            .to_vec();
        forces.extend_from_slice(&eq.dl_dq);
        forces.push(eq.lagrangian);
        let mut check = vec![eq.dl_dt, eq.lagrangian];
        check.extend_from_slice(&eq.momenta);
        check.extend_from_slice(&eq.mass);
        let on_q = |k: u32| layout.is_param(k) || k == Layout::T || velocity(k) || rotation(k);
        let on_configuration = |k: u32| layout.is_param(k) || k == Layout::T || velocity(k);
        Group {
            layout,
            blocks: Tape::with_fixed(g, &eq.mass, &on_q),
            jet: Tape::with_fixed(g, &first, &on_q),
            hessian: Tape::with_fixed(g, &second, &on_q),
            forces: Tape::with_fixed(g, &forces, &on_configuration),
            check: Tape::new(g, &check),
        }
    }

    /// Why the model is not of the form the Lie-group methods integrate at the inputs
    /// `template` (the parameters set, the rest zero), or `None` when it is (see the module
    /// doc).
    pub(crate) fn misfit(&self, template: &[f64]) -> Option<&'static str> {
        let layout = self.layout;
        let (n, dof) = (layout.n, layout.dof());
        let mut samples = Samples(std::f64::consts::FRAC_1_PI);
        let mut inputs = template.to_vec();
        let mut w = self.check.workspace();
        for _ in 0..6 {
            inputs[0] = 3.0 * samples.next();
            let eta = Vector3::from_fn(|_, _| 3.0 * samples.next() - 1.5);
            let r = tumble_kinematics::so3::exp(&eta);
            for a in 0..3 {
                for b in 0..3 {
                    inputs[layout.rot(0, a, b) as usize] = r.matrix()[(a, b)];
                }
            }
            for i in 0..n {
                inputs[layout.q(i) as usize] = 3.0 * samples.next() - 1.5;
            }
            for i in 0..dof {
                inputs[layout.velocity(i) as usize] = 3.0 * samples.next() - 1.5;
            }
            self.check.run_all(&mut w, &inputs);
            let out = |i: usize| self.check.output(&w, i);
            let (dl_dt, l) = (out(0), out(1));
            let p = |i: usize| out(2 + i);
            let m = |i: usize, j: usize| out(2 + dof + i * dof + j);
            let v = |i: usize| inputs[layout.velocity(i) as usize];
            // At the same configuration with R = 𝟙, v = 0, t = 0: the blocks; with v = 0, t = 0:
            // L(0).
            let mut at = template.to_vec();
            for i in 0..n {
                at[layout.q(i) as usize] = inputs[layout.q(i) as usize];
            }
            for a in 0..3 {
                at[layout.rot(0, a, a) as usize] = 1.0;
            }
            let blocks = self.blocks.eval(&at);
            for a in 0..3 {
                for b in 0..3 {
                    at[layout.rot(0, a, b) as usize] = inputs[layout.rot(0, a, b) as usize];
                }
            }
            let l0 = self.forces.eval(&at)[3 + n];
            let pv: f64 = (0..dof).map(|i| p(i) * v(i)).sum();
            let largest = (0..dof * dof).fold(0.0f64, |s, k| s.max(blocks[k].abs()));
            let scale = 1e-10 * (l.abs() + pv.abs() + largest).max(f64::MIN_POSITIVE);
            if !(dl_dt.abs() <= scale) {
                return Some("its Lagrangian depends on time (a coordinate prescribed in time)");
            }
            let mut same = true;
            for i in 0..dof {
                for j in 0..dof {
                    same &= (m(i, j) - blocks[i * dof + j]).abs() <= scale;
                }
            }
            if !same {
                return Some("its mass matrix changes with the orientation or the velocities");
            }
            let linear = (0..dof).any(|i| {
                let mv: f64 = (0..dof).map(|j| blocks[i * dof + j] * v(j)).sum();
                !((p(i) - mv).abs() <= scale)
            });
            if linear || !((l - l0 - 0.5 * pv).abs() <= scale) {
                return Some(
                    "its kinetic energy has terms linear in the velocities (a rotating frame)",
                );
            }
        }
        None
    }

    /// The workspace of a tape at `template`, its prelude run.
    fn workspace(tape: &Tape, template: &[f64]) -> Vec<f64> {
        let mut w = tape.workspace();
        let k = tape.inputs().min(template.len());
        w[..k].copy_from_slice(&template[..k]);
        tape.run_prelude(&mut w);
        w
    }

    /// `template` with `R = 𝟙` (the inputs of the blocks' tapes).
    fn at_identity(&self, template: &[f64]) -> Vec<f64> {
        let mut at = template.to_vec();
        for a in 0..3 {
            at[self.layout.rot(0, a, a) as usize] = 1.0;
        }
        at
    }
}

/// The workspaces of one run.
#[derive(Debug)]
struct Work {
    blocks: Vec<f64>,
    jet: Vec<f64>,
    hessian: Vec<f64>,
    forces: Vec<f64>,
}

/// A model's tapes at one run's parameters, their workspaces allocated once.
#[derive(Debug)]
struct Evaluator<'a> {
    group: &'a Group,
    /// The inputs at `R = 𝟙`, `v = 0`, `t = 0`, `q = 0`, for the generic evaluations.
    template: Vec<f64>,
    work: RefCell<Work>,
}

impl<'a> Evaluator<'a> {
    fn new(group: &'a Group, template: &[f64]) -> Self {
        let template = group.at_identity(template);
        let work = Work {
            blocks: Group::workspace(&group.blocks, &template),
            jet: Group::workspace(&group.jet, &template),
            hessian: Group::workspace(&group.hessian, &template),
            forces: Group::workspace(&group.forces, &template),
        };
        Evaluator {
            group,
            template,
            work: RefCell::new(work),
        }
    }

    fn set_q(&self, tape: &Tape, w: &mut [f64], q: &[f64]) {
        let layout = self.group.layout;
        for (i, x) in q.iter().enumerate() {
            let k = layout.q(i) as usize;
            if k < tape.inputs() {
                w[k] = *x;
            }
        }
    }

    /// The blocks of the mass matrix at `q` from the outputs `base ..` of a tape.
    fn blocks_of<const N: usize>(
        &self,
        tape: &Tape,
        w: &[f64],
        base: usize,
    ) -> KineticBlocks<f64, N> {
        let dof = N + 3;
        let m = |i: usize, j: usize| tape.output(w, base + i * dof + j);
        KineticBlocks {
            rotational: Matrix3::from_fn(|a, b| m(N + a, N + b)),
            coupling: SMatrix::<f64, 3, N>::from_fn(|a, i| m(N + a, i)),
            internal: SMatrix::<f64, N, N>::from_fn(m),
        }
    }

    fn blocks<const N: usize>(&self, q: &SVector<f64, N>) -> KineticBlocks<f64, N> {
        let w = &mut self.work.borrow_mut().blocks;
        let tape = &self.group.blocks;
        self.set_q(tape, w, q.as_slice());
        tape.run(w);
        self.blocks_of(tape, w, 0)
    }

    fn jet<const N: usize>(&self, q: &SVector<f64, N>) -> KineticJet<N> {
        let w = &mut self.work.borrow_mut().jet;
        let tape = &self.group.jet;
        self.set_q(tape, w, q.as_slice());
        tape.run(w);
        let size = (N + 3) * (N + 3);
        KineticJet {
            blocks: self.blocks_of(tape, w, 0),
            derivatives: std::array::from_fn(|i| self.blocks_of(tape, w, (1 + i) * size)),
        }
    }

    fn hessian<const N: usize>(&self, q: &SVector<f64, N>) -> [[KineticBlocks<f64, N>; N]; N] {
        let w = &mut self.work.borrow_mut().hessian;
        let tape = &self.group.hessian;
        self.set_q(tape, w, q.as_slice());
        tape.run(w);
        let size = (N + 3) * (N + 3);
        std::array::from_fn(|i| {
            std::array::from_fn(|j| self.blocks_of(tape, w, (i * N + j) * size))
        })
    }

    /// `(M, −∂L/∂q = ∂V/∂q, −L = V)` at `(R, q)` and `v = 0`.
    fn forces<const N: usize>(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>, f64) {
        let layout = self.group.layout;
        let w = &mut self.work.borrow_mut().forces;
        let tape = &self.group.forces;
        self.set_q(tape, w, q.as_slice());
        for a in 0..3 {
            for b in 0..3 {
                let k = layout.rot(0, a, b) as usize;
                if k < tape.inputs() {
                    w[k] = rotation[(a, b)];
                }
            }
        }
        tape.run(w);
        let out = |i: usize| tape.output(w, i);
        (
            Vector3::new(out(0), out(1), out(2)),
            SVector::from_fn(|i, _| -out(3 + i)),
            -out(3 + N),
        )
    }

    /// The inputs of a generic evaluation at `(R, q)`.
    fn generic_inputs<D: Scalar, const N: usize>(
        &self,
        rotation: Option<&Matrix3<D>>,
        q: &SVector<D, N>,
    ) -> Vec<D> {
        let layout = self.group.layout;
        let mut inputs: Vec<D> = self.template.iter().map(|&x| D::from(x)).collect();
        for i in 0..N {
            inputs[layout.q(i) as usize] = q[i];
        }
        if let Some(r) = rotation {
            for a in 0..3 {
                for b in 0..3 {
                    inputs[layout.rot(0, a, b) as usize] = r[(a, b)];
                }
            }
        }
        inputs
    }
}

/// A model with scalar coordinates beside its orientation on SO(3), at one run's parameters,
/// as a [`CoupledLagrangian`]: the blocks, their derivatives and the potential's from the
/// model's tapes (see the module doc), allocation-free in `f64`. The generic
/// [`CoupledLagrangian::kinetic`] and [`CoupledLagrangian::potential`] evaluate the same tapes
/// in any scalar (dual numbers: the derivatives by automatic differentiation, which the tests
/// compare with the symbolic ones); they allocate and are not used in a step.
#[derive(Debug)]
pub struct ModelCoupled<'a, const N: usize> {
    eval: Evaluator<'a>,
}

impl<'a, const N: usize> ModelCoupled<'a, N> {
    /// The model of `group` at the inputs `template` (the parameters set).
    pub(crate) fn new(group: &'a Group, template: &[f64]) -> Self {
        ModelCoupled {
            eval: Evaluator::new(group, template),
        }
    }
}

impl<const N: usize> CoupledLagrangian<N> for ModelCoupled<'_, N> {
    fn kinetic<D: Scalar>(&self, q: &SVector<D, N>) -> KineticBlocks<D, N> {
        let out = self
            .eval
            .group
            .blocks
            .eval(&self.eval.generic_inputs(None, q));
        let m = |i: usize, j: usize| out[i * (N + 3) + j];
        KineticBlocks {
            rotational: Matrix3::from_fn(|a, b| m(N + a, N + b)),
            coupling: SMatrix::<D, 3, N>::from_fn(|a, i| m(N + a, i)),
            internal: SMatrix::<D, N, N>::from_fn(m),
        }
    }

    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, N>) -> D {
        let out = self
            .eval
            .group
            .forces
            .eval(&self.eval.generic_inputs(Some(rotation), q));
        -out[3 + N]
    }

    fn kinetic_blocks(&self, q: &SVector<f64, N>) -> KineticBlocks<f64, N> {
        self.eval.blocks(q)
    }

    fn potential_value(&self, rotation: &Matrix3<f64>, q: &SVector<f64, N>) -> f64 {
        self.eval.forces(rotation, q).2
    }

    fn kinetic_jet(&self, q: &SVector<f64, N>) -> KineticJet<N> {
        self.eval.jet(q)
    }

    fn kinetic_hessian(&self, q: &SVector<f64, N>) -> [[KineticBlocks<f64, N>; N]; N] {
        self.eval.hessian(q)
    }

    fn potential_derivatives(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        let (moment, grad, _) = self.eval.forces(rotation, q);
        (moment, grad)
    }
}

/// A model whose only coordinate is its orientation on SO(3), at one run's parameters, as a
/// [`RigidBody`]: the inertia (the mass matrix, constant) and the potential and its moment
/// from the model's tapes (see the module doc).
#[derive(Debug)]
pub struct ModelRigidBody<'a> {
    eval: Evaluator<'a>,
    body: FreeRigidBody,
    torque_free: bool,
}

impl<'a> ModelRigidBody<'a> {
    /// The body of `group` at the inputs `template`.
    ///
    /// # Errors
    /// The reason the inertia is not a rigid body's (not positive definite, or violating the
    /// triangle inequality).
    pub(crate) fn new(group: &'a Group, template: &[f64]) -> Result<Self, String> {
        let eval = Evaluator::new(group, template);
        // Symmetric, and products of inertia at the round-off of the largest entry (a mesh's
        // sums leave some ~1e-19 where the body is symmetric) set to zero: a diagonal tensor's
        // principal axes are then exact, as the built-in bodies' are.
        let j = eval.blocks::<0>(&SVector::zeros()).rotational;
        let noise = 64.0 * f64::EPSILON * j.amax();
        let j = ((j + j.transpose()) * 0.5).map(|x| if x.abs() <= noise { 0.0 } else { x });
        let body = FreeRigidBody::from_inertia(&j)
            .map_err(|e| format!("its inertia {j} is not a rigid body's: {e}"))?;
        // Torque-free when the potential and its moment vanish at every sample rotation.
        let mut samples = Samples(std::f64::consts::FRAC_1_PI);
        let torque_free = (0..6).all(|_| {
            let eta = Vector3::from_fn(|_, _| 3.0 * samples.next() - 1.5);
            let r = tumble_kinematics::so3::exp(&eta);
            let (moment, _, v) = eval.forces::<0>(r.matrix(), &SVector::zeros());
            v == 0.0 && moment == Vector3::zeros()
        });
        Ok(ModelRigidBody {
            eval,
            body,
            torque_free,
        })
    }

    /// Whether the potential vanishes (so the body is free: the torque-free methods apply).
    #[must_use]
    pub fn is_free(&self) -> bool {
        self.torque_free
    }
}

impl RigidBody for ModelRigidBody<'_> {
    fn body(&self) -> &FreeRigidBody {
        &self.body
    }

    fn potential(&self, rotation: &Matrix3<f64>) -> f64 {
        self.eval.forces::<0>(rotation, &SVector::zeros()).2
    }

    fn torque(&self, rotation: &Matrix3<f64>) -> Vector3<f64> {
        self.eval.forces::<0>(rotation, &SVector::zeros()).0
    }

    fn is_torque_free(&self) -> bool {
        self.torque_free
    }
}
