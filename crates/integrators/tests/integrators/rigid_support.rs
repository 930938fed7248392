//! Shared helpers of the rigid-body tests: test bodies, Gauss–Legendre references, the bead on
//! a hoop as a coupled model, and runners for every rigid-body method by registry name.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use tumble_integrators::registry::build::{self, Receive};
use tumble_integrators::registry::{self, AnyGauss, MethodInfo, Stepping};
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledLgvi, CoupledState, CoupledVectorField, EulerEquations,
    FreeRigidBody, GroupState, HeavyTop, KineticBlocks, RigidBody, RigidBodyState, Scalar,
};
use tumble_integrators::tables::gauss::GAUSS12;
use tumble_integrators::verification::{OrderFit, OrderStudy};
use tumble_integrators::{
    Driver, Error, FnOde, NoObserver, Observer, ProblemKind, State, Stepper, gauss12,
};
use tumble_kinematics::so3::{exp, hat};

/// The asymmetric test body: principal moments (1, 2, 3) about axes rotated away from the body
/// axes, so that `J` is not diagonal.
pub fn asymmetric_body() -> FreeRigidBody {
    let q = exp(&Vector3::new(0.4, 1.1, -0.3));
    let j =
        q.matrix() * Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)) * q.matrix().transpose();
    FreeRigidBody::from_inertia(&j).unwrap()
}

/// A generic initial state (not near a separatrix or an axis).
pub fn initial_state() -> RigidBodyState {
    RigidBodyState::new(
        &exp(&Vector3::new(0.3, -0.2, 0.9)),
        Vector3::new(0.7, -0.3, 1.0),
    )
}

/// An asymmetric heavy top with non-diagonal inertia and an off-axis centre of mass.
pub fn asymmetric_top() -> HeavyTop {
    HeavyTop::new(asymmetric_body(), 1.5, Vector3::new(0.1, -0.2, 0.5)).unwrap()
}

/// Largest of the momentum error (relative to |m₀|) and the max-norm rotation error.
pub fn state_error(a: &RigidBodyState, b: &RigidBodyState, scale: f64) -> f64 {
    ((a.momentum - b.momentum).norm() / scale).max((a.rotation - b.rotation).amax())
}

type Y12 = SVector<f64, 12>;

fn pack(s: &RigidBodyState) -> Y12 {
    let mut y = Y12::zeros();
    y.fixed_rows_mut::<9>(0)
        .copy_from_slice(s.rotation.as_slice());
    y.fixed_rows_mut::<3>(9).copy_from(&s.momentum);
    y
}

fn unpack(y: &Y12) -> RigidBodyState {
    RigidBodyState {
        rotation: Matrix3::from_column_slice(&y.as_slice()[..9]),
        momentum: Vector3::from_column_slice(&y.as_slice()[9..]),
    }
}

/// Euler's equations with orientation and torque, integrated by Gauss–Legendre s = 6 at step `h`.
pub fn gauss_reference<B: RigidBody>(
    problem: &B,
    s0: &RigidBodyState,
    t_end: f64,
    h: f64,
) -> RigidBodyState {
    let ode = FnOde(|_t: f64, y: &Y12, dy: &mut Y12| {
        let s = unpack(y);
        let w = problem.body().omega(&s.momentum);
        let rd = s.rotation * hat(&w);
        dy.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
        dy.fixed_rows_mut::<3>(9)
            .copy_from(&(s.momentum.cross(&w) + problem.torque(&s.rotation)));
    });
    let mut y = pack(s0);
    let mut st = gauss12().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(&mut st, &ode, &mut y, h, &mut NoObserver)
        .unwrap();
    unpack(&y)
}

/// The exact free flow from `s0` at `t`.
pub fn exact_state(body: &FreeRigidBody, s0: &RigidBodyState, t: f64) -> RigidBodyState {
    let (r, m) = body.flow(&s0.rotation3(), &s0.momentum).unwrap().at(t);
    RigidBodyState {
        rotation: r.into_inner(),
        momentum: m,
    }
}

/// Runs `stepper` on `problem` from `s0` over `[0, t_end]` with step `h`, observing with `obs`.
pub fn run<P: ?Sized, St: Stepper<P>, O: Observer<St::State>>(
    stepper: &mut St,
    problem: &P,
    mut s: St::State,
    t_end: f64,
    h: f64,
    obs: &mut O,
) -> Result<St::State, Error> {
    Driver::new(0.0, t_end)?.run_fixed(stepper, problem, &mut s, h, obs)?;
    Ok(s)
}

/// The registry entry called `name`; `lie-gauss12` (Lie–Gauss on the 6-stage table, built and
/// tested but not registered) as the row it would be.
pub fn method(name: &str) -> Result<MethodInfo, Error> {
    if name == "lie-gauss12" {
        return Ok(MethodInfo::new(
            "lie-gauss12",
            Stepping::LieGauss(AnyGauss::S6(&GAUSS12)),
            "",
        ));
    }
    Ok(*registry::find(name)?)
}

/// Runs the stepper it receives with fixed steps `h` from `s0` over `[0, t_end]`; the final
/// state.
struct Fixed<'a, P: ?Sized, S> {
    problem: &'a P,
    s0: S,
    t_end: f64,
    h: f64,
}

impl<P: ?Sized, S: State> Receive<P, S> for Fixed<'_, P, S> {
    type Output = Result<S, Error>;
    fn receive<St: Stepper<P, State = S> + Clone>(self, mut stepper: St) -> Self::Output {
        run(
            &mut stepper,
            self.problem,
            self.s0,
            self.t_end,
            self.h,
            &mut NoObserver,
        )
    }
}

/// Final state of the method called `name` on a [`RigidBody`]: as a rigid body, or as the
/// vector field of Euler's equations on SO(3) × ℝ³ for the methods that integrate one.
pub fn solve_body<B: RigidBody>(
    name: &str,
    problem: &B,
    s0: &RigidBodyState,
    t_end: f64,
    h: f64,
) -> Result<RigidBodyState, Error> {
    let method = method(name)?;
    if method.problems.contains(&ProblemKind::LieVectorField) {
        let field = EulerEquations(problem);
        let run = Fixed {
            problem: &field,
            s0: GroupState::<3>::from(*s0),
            t_end,
            h,
        };
        let g = build::lie_vector_field::<_, _, 3>(&method, run)??;
        return Ok(RigidBodyState::from(g));
    }
    let run = Fixed {
        problem,
        s0: *s0,
        t_end,
        h,
    };
    build::rigid_body(&method, run)?
}

/// Final state of `name` on the free body: the methods of [`solve_body`] plus `dmv` and `exact`.
pub fn solve_free(
    name: &str,
    body: &FreeRigidBody,
    s0: &RigidBodyState,
    t_end: f64,
    h: f64,
) -> Result<RigidBodyState, Error> {
    let method = method(name)?;
    if method.problems.contains(&ProblemKind::FreeRigidBody) {
        let run = Fixed {
            problem: body,
            s0: *s0,
            t_end,
            h,
        };
        return build::free_rigid_body(&method, run)?;
    }
    solve_body(name, body, s0, t_end, h)
}

/// Final state of the method called `name` on a rigid body coupled to `N` coordinates.
pub fn solve_coupled<L: CoupledLagrangian<N>, const N: usize>(
    name: &str,
    model: &L,
    s0: &CoupledState<N>,
    t_end: f64,
    h: f64,
) -> Result<CoupledState<N>, Error> {
    let run = Fixed {
        problem: model,
        s0: *s0,
        t_end,
        h,
    };
    build::coupled::<L, _, N>(&method(name)?, run)?
}

/// A bead of mass `m` sliding without friction on a thin hoop (mass `hoop_mass`, radius `a`)
/// whose centre is a fixed pivot, in gravity `−g e₃`: `SO(3) × ℝ` with `q = α`, the bead at body
/// position `a (cos α, sin α, 0)` (design, §5).
#[derive(Debug, Clone, Copy)]
pub struct BeadOnHoop {
    pub hoop_mass: f64,
    pub bead_mass: f64,
    pub radius: f64,
    pub g: f64,
}

impl BeadOnHoop {
    pub fn standard() -> Self {
        Self {
            hoop_mass: 1.0,
            bead_mass: 0.2,
            radius: 0.4,
            g: 9.81,
        }
    }
}

impl CoupledLagrangian<1> for BeadOnHoop {
    fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
        let a = D::from(self.radius);
        let m = D::from(self.bead_mass);
        let big = self.hoop_mass * self.radius * self.radius;
        let (s, c) = (q[0].sin(), q[0].cos());
        let r = Vector3::new(a * c, a * s, D::from(0.0));
        let dr = Vector3::new(-a * s, a * c, D::from(0.0));
        let hoop = Matrix3::from_diagonal(&Vector3::new(
            D::from(0.5 * big),
            D::from(0.5 * big),
            D::from(big),
        ));
        let bead = (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m;
        KineticBlocks {
            rotational: hoop + bead,
            coupling: SMatrix::<D, 3, 1>::from_column_slice((r.cross(&dr) * m).as_slice()),
            internal: SMatrix::<D, 1, 1>::new(m * dr.norm_squared()),
        }
    }

    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
        let a = D::from(self.radius);
        let r = Vector3::new(a * q[0].cos(), a * q[0].sin(), D::from(0.0));
        (rotation * r).z * D::from(self.bead_mass * self.g)
    }
}

/// A tilted, spinning hoop with the bead off the bottom and moving.
pub fn hoop_initial(model: &BeadOnHoop) -> CoupledState<1> {
    let r = exp(&Vector3::new(1.2, 0.3, 0.1));
    tumble_integrators::rigid::coupled_state_from_velocities(
        model,
        r.matrix(),
        &Vector3::new(0.5, -1.0, 3.0),
        &SVector::<f64, 1>::new(0.6),
        &SVector::<f64, 1>::new(1.5),
    )
}

type Y14 = SVector<f64, 14>;

/// The bead on the hoop integrated by Gauss–Legendre s = 6 on the flattened continuous equations
/// (R, Π, α, p_α).
pub fn hoop_reference(
    model: &BeadOnHoop,
    s0: &CoupledState<1>,
    t_end: f64,
    h: f64,
) -> CoupledState<1> {
    let field = CoupledVectorField::<_, 1, 5>::new(*model).unwrap();
    let ode = FnOde(|t: f64, y: &Y14, dy: &mut Y14| {
        use tumble_integrators::rigid::LieVectorField;
        let r = Matrix3::from_column_slice(&y.as_slice()[..9]);
        let v = SVector::<f64, 5>::from_column_slice(&y.as_slice()[9..14]);
        let (xi, dv) = field.eval(t, &r, &v);
        let rd = r * hat(&xi);
        dy.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
        dy.fixed_rows_mut::<5>(9).copy_from(&dv);
    });
    let g = s0.to_group::<5>().unwrap();
    let mut y = Y14::zeros();
    y.fixed_rows_mut::<9>(0)
        .copy_from_slice(g.rotation.as_slice());
    y.fixed_rows_mut::<5>(9).copy_from(&g.vector);
    let mut st = gauss12().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(&mut st, &ode, &mut y, h, &mut NoObserver)
        .unwrap();
    CoupledState::from_group(&GroupState::<5> {
        rotation: Matrix3::from_column_slice(&y.as_slice()[..9]),
        vector: SVector::<f64, 5>::from_column_slice(&y.as_slice()[9..14]),
    })
    .unwrap()
}

/// Max of the rotation error and the errors of (Π, α, p_α).
pub fn coupled_error(a: &CoupledState<1>, b: &CoupledState<1>) -> f64 {
    (a.rotation - b.rotation)
        .amax()
        .max((a.momentum - b.momentum).amax())
        .max((a.q - b.q).amax())
        .max((a.p - b.p).amax())
}

/// The coupled LGVI on the hoop.
pub fn hoop_lgvi(
    model: &BeadOnHoop,
    s0: &CoupledState<1>,
    t_end: f64,
    h: f64,
) -> Result<CoupledState<1>, Error> {
    run(
        &mut CoupledLgvi::<1>::default(),
        model,
        *s0,
        t_end,
        h,
        &mut NoObserver,
    )
}

/// `(name, nominal order, first number of steps, number of step sizes, ratio)`.
pub type Plan = (&'static str, f64, f64, usize, f64);

/// Runs an order study of `plan` over `span` and prints its points.
pub fn study(plan: &Plan, span: f64, error: impl FnMut(f64) -> Result<f64, Error>) -> OrderFit {
    let (name, nominal, n0, count, ratio) = *plan;
    let fit = OrderStudy::new(span / n0, count)
        .with_ratio(ratio)
        .on_span(span)
        .run(error)
        .unwrap();
    let errors: Vec<String> = fit
        .points
        .iter()
        .map(|(h, e)| format!("{h:.3e}:{e:.2e}"))
        .collect();
    eprintln!(
        "{name}: observed order {:.3} (nominal {nominal}) from {} points [{}]",
        fit.slope,
        fit.used_points(),
        errors.join(" ")
    );
    fit
}

/// Runs an order study of every plan over `span` and asserts each order within 0.3.
pub fn check_all(
    plans: &[Plan],
    span: f64,
    mut error: impl FnMut(&str, f64) -> Result<f64, Error>,
) {
    let mut failures = vec![];
    for plan in plans {
        let fit = study(plan, span, |h| error(plan.0, h));
        if let Err(e) = fit.check(plan.1, 0.3) {
            failures.push(format!("{}: {e}", plan.0));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
