//! The Lie-group methods (LGVI and its compositions, Lie–Gauss, RKMK, Crouch–Grossman, the
//! splittings and the free-body methods) on models with an orientation on SO(3): against the
//! built-in scenes' hand-written models at the same method and step, the exact free-body flow,
//! observed orders, the variational method's bounded energy error, the symbolic derivatives
//! against automatic differentiation, and no allocation in a step.

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::registry;
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledState, KineticBlocks, coupled_potential_gradient, coupled_torque,
    coupled_velocities,
};
use tumble_integrators::{Order, Stepper};
use tumble_model::from_text;
use tumble_scenarios::scenes::find;
use tumble_scenarios::{RunOptions, Scene, StepControl};

use crate::so3::twins;
use crate::support::{column, run, shipped};

/// The heavy top written as a model (`mgl R₃₃`) runs every method of the built-in
/// `heavy-top`'s rigid-body and Lie-vector-field kinds and matches it column by column.
#[test]
fn every_lie_group_method_on_the_heavy_top_model_matches_the_builtin() {
    let model = shipped("heavy-top-so3");
    for method in [
        "lgvi",
        "lgvi4",
        "lie-gauss4",
        "lie-gauss8",
        "rkmk4",
        "cg3",
        "split2",
        "split-exact4",
        "kahan-li6:lgvi",
    ] {
        // A TABLE:BASE composition is generated, not listed.
        assert!(
            method.contains(':') || model.info().integrators().contains(&method),
            "{method} is not offered"
        );
        twins("heavy-top", "heavy-top-so3", method, 1e-3, 1.0, 1e-12);
    }
}

/// The free hoop written as a model (hoop and bead from their energies) runs the coupled
/// Lie-group methods on SO(3) × ℝ and matches the built-in `free-hoop`'s closed forms.
#[test]
fn every_lie_group_method_on_the_free_hoop_model_matches_the_builtin() {
    for method in [
        "lgvi",
        "lgvi4",
        "lie-gauss4",
        "lie-gauss6",
        "mclachlan4:lgvi",
    ] {
        twins("free-hoop", "free-hoop-so3", method, 0.01, 3.0, 1e-12);
    }
}

/// The same free hoop turning on SO(3) the whole time, through the attitude where Euler angles
/// lock (the hoop flat), with the coupled LGVI: energy and `L_z` bounded, the run finite.
#[test]
fn the_coupled_lgvi_runs_a_flat_hoop_model() {
    let (c, r) = run(
        shipped("free-hoop-so3"),
        &[("theta0", 0.0), ("alpha_dot0", 1.0)],
        "lgvi",
        StepControl::Fixed(1e-3),
        5.0,
    );
    let energy = column(&c, &r, "energy");
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max)
        / energy[0].abs();
    println!("flat hoop, lgvi at dt = 1e-3: energy error {drift:.2e}");
    assert!(drift < 1e-5, "{drift:e}");
}

/// A torque-free asymmetric body written as a model offers the free-body methods (`dmv`,
/// `exact`) and follows the exact elliptic-function flow of the built-in `free-body` with
/// Lie–Gauss 8, to the method's error at `dt = 0.01`.
#[test]
fn a_free_body_model_follows_the_exact_flow_with_lie_group_methods() {
    let model = from_text(FREE_BODY, "free-body-lie").unwrap_or_else(|e| panic!("{e}"));
    let names = model.info().integrators();
    for method in ["dmv", "exact", "lgvi", "rkmk4", "lie-gauss8"] {
        assert!(names.contains(&method), "{method} not in {names:?}");
    }
    let (bc, br) = run(
        find("free-body").unwrap(),
        &[],
        "exact",
        StepControl::Fixed(20.0),
        20.0,
    );
    let at = |c: &[String], r: &[f64], n: &str| r[c.iter().position(|x| x == n).unwrap()];
    for (method, dt, tol) in [
        ("lie-gauss8", 0.01, 1e-13),
        ("lgvi6", 0.01, 1e-13),
        ("exact", 20.0, 1e-13),
    ] {
        let (mc, mr) = run(model, &[], method, StepControl::Fixed(dt), 20.0);
        let (m_last, b_last) = (mr.last().unwrap(), br.last().unwrap());
        assert_eq!(m_last[0], 20.0);
        let mut worst = 0.0f64;
        for name in ["qw", "qx", "qy", "qz", "omega_x", "omega_y", "omega_z"] {
            worst = worst.max((at(&mc, m_last, name) - at(&bc, b_last, name)).abs());
        }
        println!(
            "free body model, {method} at dt = {dt}: {worst:.2e} from the exact flow at t = 20"
        );
        assert!(worst < tol, "{method}: {worst:e}");
    }
}

const FREE_BODY: &str = r#"
[model]
name = "free-body-lie"
[parameters]
I1 = 1.0
I2 = 2.0
I3 = 3.0
[frames.body]
orientation = "so3"
omega = ["0.4/I1", "-0.8/I2", "0.6/I3"]
[bodies.body]
frame = "body"
mass = "1"
inertia = ["I1", "I2", "I3"]
[run]
integrator = "lgvi"
dt = 0.01
t_end = 20.0
"#;

/// The error at `t_end` of `method` at step `dt` on the free hoop model, against Gauss–Legendre
/// 12 at a step ten times smaller (state columns, max norm).
fn hoop_error(method: &str, dt: f64, reference: &(Vec<String>, Vec<Vec<f64>>)) -> f64 {
    let model = shipped("free-hoop-so3");
    let (c, r) = run(model, &[], method, StepControl::Fixed(dt), 1.0);
    let last = r.last().unwrap();
    let (rc, rr) = reference;
    let reference = rr.last().unwrap();
    [
        "qw",
        "qx",
        "qy",
        "qz",
        "alpha",
        "omega_x",
        "omega_y",
        "omega_z",
        "alpha_dot",
    ]
    .iter()
    .map(|n| {
        let i = c.iter().position(|x| x == n).unwrap();
        let j = rc.iter().position(|x| x == n).unwrap();
        (last[i] - reference[j]).abs()
    })
    .fold(0.0, f64::max)
}

/// The observed orders of the coupled LGVI (2), its composition `lgvi4` (4) and Lie–Gauss 4
/// (4) on the free hoop model: the error's slope between steps `h` and `h/2`, within ±0.3.
#[test]
fn lie_group_methods_on_a_model_show_their_orders() {
    let reference = run(
        shipped("free-hoop-so3"),
        &[],
        "gauss12",
        StepControl::Fixed(1e-3),
        1.0,
    );
    for (method, h) in [("lgvi", 0.02), ("lgvi4", 0.05), ("lie-gauss4", 0.05)] {
        let order = match registry::find(method).unwrap().order {
            Order::Finite(p) => f64::from(p),
            _ => unreachable!("{method} has a finite order"),
        };
        let (coarse, fine) = (
            hoop_error(method, h, &reference),
            hoop_error(method, h / 2.0, &reference),
        );
        let observed = (coarse / fine).log2();
        println!("{method}: error {coarse:.2e} at h = {h}, {fine:.2e} at h/2: order {observed:.2}");
        assert!(
            (observed - order).abs() <= 0.3,
            "{method}: observed {observed}, order {order}"
        );
    }
}

/// The variational method's energy error on the heavy top model stays bounded: over 10⁵ steps
/// of `lgvi` (t = 100 s, ~800 spin periods about the symmetry axis) the largest relative error
/// of the second half is no larger than that of the first, and both are small.
#[test]
fn the_lgvi_energy_error_on_a_model_is_bounded_over_a_long_run() {
    let (c, r) = run(
        shipped("heavy-top-so3"),
        &[],
        "lgvi",
        StepControl::Fixed(1e-3),
        100.0,
    );
    let err = column(&c, &r, "energy_rel_err");
    let half = err.len() / 2;
    let first = err[..half].iter().copied().fold(0.0, f64::max);
    let second = err[half..].iter().copied().fold(0.0, f64::max);
    println!(
        "heavy top model, lgvi, dt = 1e-3: energy error {first:.2e} to t = 50, {second:.2e} to t = 100"
    );
    assert!(first < 1e-3, "{first:e}");
    assert!(second <= 1.5 * first, "{first:e} then {second:e}: growing");
}

/// The model's symbolic derivatives — the blocks' jet and Hessian in `q`, the moment of the
/// potential and `∂V/∂q` — agree with automatic differentiation (dual numbers) through the
/// same tapes, at a state of the free hoop model with gravity.
#[test]
fn a_models_symbolic_derivatives_match_automatic_differentiation() {
    let scene = shipped("free-hoop-so3");
    let params = scene.info().default_params();
    let model = scene
        .coupled::<1>(&params)
        .expect("the free hoop is a coupled model");
    let q = SVector::<f64, 1>::new(0.7);
    let r = *tumble_kinematics::so3::exp(&Vector3::new(0.3, -1.1, 0.4)).matrix();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs());
    let same = |a: &KineticBlocks<f64, 1>, b: &KineticBlocks<f64, 1>| {
        a.rotational
            .iter()
            .zip(b.rotational.iter())
            .all(|(x, y)| close(*x, *y))
            && a.coupling
                .iter()
                .zip(b.coupling.iter())
                .all(|(x, y)| close(*x, *y))
            && a.internal
                .iter()
                .zip(b.internal.iter())
                .all(|(x, y)| close(*x, *y))
    };
    // The defaults of the trait differentiate the generic evaluations.
    struct Generic<'a, L>(&'a L);
    impl<L: CoupledLagrangian<1>> CoupledLagrangian<1> for Generic<'_, L> {
        fn kinetic<D: tumble_integrators::rigid::Scalar>(
            &self,
            q: &SVector<D, 1>,
        ) -> KineticBlocks<D, 1> {
            self.0.kinetic(q)
        }
        fn potential<D: tumble_integrators::rigid::Scalar>(
            &self,
            rotation: &Matrix3<D>,
            q: &SVector<D, 1>,
        ) -> D {
            self.0.potential(rotation, q)
        }
    }
    let ad = Generic(&model);
    let (jet, jet_ad) = (model.kinetic_jet(&q), ad.kinetic_jet(&q));
    assert!(same(&jet.blocks, &jet_ad.blocks));
    assert!(same(&jet.derivatives[0], &jet_ad.derivatives[0]));
    assert!(same(
        &model.kinetic_hessian(&q)[0][0],
        &ad.kinetic_hessian(&q)[0][0]
    ));
    let (moment, grad) = model.potential_derivatives(&r, &q);
    let (moment_ad, grad_ad) = (
        coupled_torque(&ad, &r, &q),
        coupled_potential_gradient(&ad, &r, &q),
    );
    println!("moment {moment:?} against {moment_ad:?}; dV/dq {grad:?} against {grad_ad:?}");
    assert!(
        moment
            .iter()
            .zip(moment_ad.iter())
            .all(|(a, b)| close(*a, *b))
    );
    assert!(close(grad[0], grad_ad[0]));
    assert!(moment.norm() > 0.1, "gravity tilts the hoop: {moment:?}");
}

/// A step of the coupled LGVI and of Lie–Gauss on a model allocates nothing (the tapes'
/// workspaces are allocated once, when the run's model is made).
#[test]
fn a_lie_group_step_on_a_model_allocates_nothing() {
    let scene = shipped("free-hoop-so3");
    let params = scene.info().default_params();
    let model = scene.coupled::<1>(&params).unwrap();
    let s0 = tumble_integrators::rigid::coupled_state_from_velocities(
        &model,
        &Matrix3::identity(),
        &Vector3::new(0.0, 0.0, 4.0),
        &SVector::<f64, 1>::new(0.5),
        &SVector::<f64, 1>::zeros(),
    );
    struct Count<'a, L>(&'a L, &'a mut CoupledState<1>);
    impl<L: CoupledLagrangian<1>> tumble_integrators::registry::build::Receive<L, CoupledState<1>>
        for Count<'_, L>
    {
        type Output = u64;
        fn receive<St: Stepper<L, State = CoupledState<1>> + Clone>(self, mut stepper: St) -> u64 {
            let Count(model, state) = self;
            stepper.step(model, 0.0, state, 0.01).unwrap();
            allocation_counter::measure(|| {
                for k in 1..20 {
                    stepper
                        .step(model, f64::from(k) * 0.01, state, 0.01)
                        .unwrap();
                }
            })
            .count_total
        }
    }
    for method in ["lgvi", "lgvi4", "lie-gauss6"] {
        let mut state = s0;
        let info = registry::find(method).unwrap();
        let count = tumble_integrators::registry::build::coupled::<_, _, 1>(
            info,
            Count(&model, &mut state),
        )
        .unwrap();
        assert_eq!(count, 0, "{method} allocated {count} times in 19 steps");
        let (omega, _) = coupled_velocities(&model, &state.q, &state.momentum, &state.p).unwrap();
        assert!(omega.iter().all(|x| x.is_finite()));
    }
}

/// A Lie-group method on a model without an orientation on SO(3) is refused before any work,
/// naming the orientation it needs and the methods that apply.
#[test]
fn a_lie_group_method_on_a_model_without_so3_is_refused_with_what_to_use() {
    let scene = shipped("heavy-top");
    assert!(
        scene
            .not_on_group()
            .unwrap()
            .contains("orientation = \"so3\""),
        "{:?}",
        scene.not_on_group()
    );
    let options = RunOptions {
        integrator: Some("lgvi".into()),
        ..RunOptions::default()
    };
    let err = options.resolve(scene.info()).unwrap_err().to_string();
    println!("{err}");
    for expected in ["lgvi", "orientation = \"so3\"", "gauss8"] {
        assert!(err.contains(expected), "`{expected}` not in: {err}");
    }
}

/// The T-handle read from its mesh and turning about its centre of mass on SO(3) (its frame's
/// origin an expression of `R`, so the mass matrix is constant only on the group) matches the
/// built-in `dzhanibekov` through its first flip (`omega_x` changes sign at t = 0.94 s) with
/// the Lie-group methods too (to 1e-13 and better; the inertia's products at round-off are
/// zero, so the principal axes are exact as the built-in's are).
#[test]
fn the_t_handle_model_matches_the_builtin_with_lie_group_methods() {
    for method in ["rkmk4", "lie-gauss8", "lgvi4", "exact"] {
        twins("dzhanibekov", "t-handle-so3", method, 1e-3, 2.0, 1e-12);
    }
}

/// Every fixed-step method of a Lie-group kind that a shipped model on SO(3) lists runs it for
/// 100 steps, its energy error below 1e-6 (a method listed but not built would fail here).
#[test]
fn every_shipped_so3_model_runs_every_lie_group_method_it_lists() {
    use tumble_integrators::ProblemKind as K;
    let group = [
        K::RigidBody,
        K::FreeRigidBody,
        K::LieVectorField,
        K::ProductVectorField,
        K::ProductLagrangian,
        K::CoupledRigidBody,
    ];
    // lgvi…lgvi10, lie-gauss4…10, rkmk4, cg3, split2…8, split-exact2…8; dmv and exact for the
    // free body; the coupled lgvi…lgvi10 and lie-gauss4…10 beside a coordinate; rkmk4, cg3 and
    // lgvi…lgvi10 on the product of several orientations.
    for (name, expected) in [
        ("heavy-top-so3", 19),
        ("free-hoop-so3", 9),
        ("t-handle-so3", 21),
        // rkmk4, cg3 and lgvi…lgvi10 on the product SO(3)² of two orientations.
        ("double-spherical-pendulum-so3", 7),
    ] {
        let scene = shipped(name);
        let mut ran = 0;
        for method in scene.info().integrators() {
            let info = registry::find(method).unwrap();
            if info.properties.adaptive || !info.problems.iter().any(|k| group.contains(k)) {
                continue;
            }
            let (c, r) = run(scene, &[], method, StepControl::Fixed(1e-3), 0.1);
            let worst = column(&c, &r, "energy_rel_err")
                .into_iter()
                .fold(0.0, f64::max);
            assert!(worst < 1e-6, "{name} with {method}: energy error {worst:e}");
            ran += 1;
        }
        println!("{name}: {ran} Lie-group methods");
        assert_eq!(ran, expected, "{name}");
    }
}
