//! `free-hoop` on SO(3) × ℝ: agreement with its Euler-angle twin, conservation laws under the
//! variational integrator, and a tumble through horizontal that the Euler-angle chart cannot
//! follow.

use std::f64::consts::FRAC_PI_2;

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledLgvi, CoupledState, KineticBlocks, Scalar, coupled_energy,
    coupled_kinetic_gradient, coupled_state_from_velocities,
};
use tumble_integrators::{
    Driver, ExplicitRungeKutta, Flow, FnObserver, NoObserver, Status, Stepper, Tolerances, gauss12,
};
use tumble_scenarios::scene::Rows;
use tumble_scenarios::scenes::find;
use tumble_scenarios::scenes::free_hoop::{FlatFreeHoop, FreeHoop, flatten, unflatten};
use tumble_scenarios::scenes::hoop::{FreeHoopEuler, HoopParams, tilt_from_normal};
use tumble_scenarios::{EulerLagrange, LagrangianOde, RunOptions};

fn params(g: f64) -> HoopParams {
    HoopParams::new(1.0, 0.3, 1.0, g).unwrap()
}

/// SO(3) model by Gauss–Legendre s = 6 on the flattened equations.
fn so3_run(model: FreeHoop, s0: &CoupledState<1>, t_end: f64, h: f64) -> CoupledState<1> {
    let flat = FlatFreeHoop::new(model).unwrap();
    let mut y = flatten(s0);
    let mut st = gauss12().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(&mut st, &flat, &mut y, h, &mut NoObserver)
        .unwrap();
    unflatten(&y)
}

/// Euler-angle twin by DOP853 at tolerance 1e-13; returns the end state and min/max θ.
fn euler_run(p: HoopParams, y0: SVector<f64, 8>, t_end: f64) -> (SVector<f64, 8>, f64, f64) {
    let ode = LagrangianOde::<_, 4, 8>::new(EulerLagrange::new(FreeHoopEuler { hoop: p })).unwrap();
    let mut y = y0;
    let mut st = ExplicitRungeKutta::dop853().stepper(&y);
    let (mut lo, mut hi) = (f64::MAX, f64::MIN);
    let mut obs = FnObserver(|_t: f64, s: &SVector<f64, 8>| {
        lo = lo.min(s[1]);
        hi = hi.max(s[1]);
        Flow::Continue
    });
    let mut events = [FreeHoopEuler::chart_edge_event()];
    let report = Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut st,
            &ode,
            &mut y,
            &Tolerances::new(1e-13, 1e-13).unwrap(),
            &mut events,
            &mut obs,
        )
        .unwrap();
    assert_eq!(report.status, Status::Completed, "the Euler chart was left");
    (y, lo, hi)
}

#[test]
fn so3_model_agrees_with_its_euler_angle_twin_over_10_s() {
    let p = params(9.81);
    let model = FreeHoop { hoop: p };
    for (omega0, alpha0, theta0) in [
        (1.0, 0.5, FRAC_PI_2),
        (3.0, 1.0, 1.2),
        (6.0, 0.3, FRAC_PI_2),
    ] {
        let s0 = model.initial_state(theta0, omega0, alpha0, 0.4);
        let so3 = so3_run(model, &s0, 10.0, 2e-3);
        let y0 = SVector::<f64, 8>::from([0.0, theta0, 0.0, alpha0, omega0, 0.0, 0.0, 0.4]);
        let (eu, lo, hi) = euler_run(p, y0, 10.0);
        assert!(
            lo > 0.05 && hi < std::f64::consts::PI - 0.05,
            "θ in [{lo}, {hi}]"
        );
        let tilt_so3 = FreeHoop::tilt(&so3);
        let tilt_eu = tilt_from_normal(&FreeHoopEuler::normal(&SVector::<f64, 4>::new(
            eu[0], eu[1], eu[2], eu[3],
        )));
        let d_alpha = (so3.q[0] - eu[3]).abs();
        let d_tilt = (tilt_so3 - tilt_eu).abs();
        eprintln!(
            "ω0 = {omega0}: |Δα| = {d_alpha:.1e}, |Δtilt| = {d_tilt:.1e}, tilt {tilt_so3:.4}"
        );
        assert!(
            d_alpha < 1e-9 && d_tilt < 1e-9,
            "ω0 = {omega0}: {d_alpha:e}, {d_tilt:e}"
        );
    }
}

#[test]
fn lgvi_conserves_lz_to_round_off_and_bounds_the_energy_error() {
    let model = FreeHoop { hoop: params(9.81) };
    let mut s = model.initial_state(1.3, 3.0, 0.7, 1.0);
    let (e0, l0) = (coupled_energy(&model, &s).unwrap(), s.spatial_momentum());
    let (mut max_de, mut max_dlz) = (0.0f64, 0.0f64);
    let mut obs = FnObserver(|_t: f64, st: &CoupledState<1>| {
        max_de = max_de.max(((coupled_energy(&model, st).unwrap() - e0) / e0).abs());
        max_dlz = max_dlz.max((st.spatial_momentum().z - l0.z).abs() / l0.norm());
        Flow::Continue
    });
    let mut st = CoupledLgvi::<1>::new();
    Driver::new(0.0, 20.0)
        .unwrap()
        .run_fixed(&mut st, &model, &mut s, 1e-3, &mut obs)
        .unwrap();
    eprintln!("LGVI h = 1e-3 over 20 s: max |ΔE/E| = {max_de:.1e}, max |ΔLz|/|L| = {max_dlz:.1e}");
    // Round-off only: a random walk of ~ε per step over n = 2·10⁴ steps is ~ε√n ≈ 1.6e-14;
    // allow a factor 50 for the rounding of each step's Newton solve and rotation product.
    let round_off = 50.0 * f64::EPSILON * (2e4f64).sqrt();
    assert!(max_dlz < round_off, "{max_dlz:e} vs {round_off:e}");
    assert!(max_de < 1e-5, "{max_de:e}");
}

#[test]
fn without_gravity_the_whole_angular_momentum_is_conserved() {
    let model = FreeHoop { hoop: params(0.0) };
    let mut s = model.initial_state(1.3, 3.0, 0.7, 1.0);
    let l0 = s.spatial_momentum();
    let mut st = CoupledLgvi::<1>::new();
    Driver::new(0.0, 10.0)
        .unwrap()
        .run_fixed(&mut st, &model, &mut s, 1e-3, &mut NoObserver)
        .unwrap();
    let drift = (s.spatial_momentum() - l0).norm() / l0.norm();
    eprintln!("g = 0, 10⁴ LGVI steps: |ΔL|/|L| = {drift:.1e}");
    assert!(drift < 50.0 * f64::EPSILON * (1e4f64).sqrt(), "{drift:e}");
}

#[test]
fn tumbling_through_horizontal_runs_on_so3_and_stops_the_euler_chart() {
    // No gravity, bead on body x: body y is principal; the hoop turns steadily about it and its
    // normal passes through the vertical (tilt π/2) at t = 0.3 / 1 rad/s.
    let p = params(0.0);
    let model = FreeHoop { hoop: p };
    let theta0 = 0.3;
    let conv = tumble_kinematics::EulerConvention::ARTICLE;
    let rot = conv.to_rotation(&Vector3::new(0.0, theta0, 0.0));
    let mut s = coupled_state_from_velocities(
        &model,
        rot.matrix(),
        &Vector3::new(0.0, -1.0, 0.0),
        &SVector::<f64, 1>::new(0.0),
        &SVector::<f64, 1>::new(0.0),
    );
    let mut max_tilt = 0.0f64;
    let mut obs = FnObserver(|_t: f64, st: &CoupledState<1>| {
        max_tilt = max_tilt.max(FreeHoop::tilt(st));
        Flow::Continue
    });
    let mut st = CoupledLgvi::<1>::new();
    Driver::new(0.0, 1.0)
        .unwrap()
        .run_fixed(&mut st, &model, &mut s, 1e-3, &mut obs)
        .unwrap();
    assert!(max_tilt > FRAC_PI_2 - 1e-6, "max tilt {max_tilt}");
    // The Euler-angle twin stops at the chart's edge with its singularity.
    let ode = LagrangianOde::<_, 4, 8>::new(EulerLagrange::new(FreeHoopEuler { hoop: p })).unwrap();
    let mut y = SVector::<f64, 8>::from([0.0, theta0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0]);
    let mut stepper = ExplicitRungeKutta::dop853().stepper(&y);
    let mut events = [FreeHoopEuler::chart_edge_event()];
    let report = Driver::new(0.0, 1.0)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &ode,
            &mut y,
            &Tolerances::new(1e-12, 1e-12).unwrap(),
            &mut events,
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.status, Status::Terminated(0));
    assert!((report.t - 0.3).abs() < 1e-9);
    let (q, qd) = LagrangianOde::<FreeHoopEuler, 4, 8>::split(&y);
    assert!(ode.equations().accelerations(report.t, &q, &qd).is_err());
}

#[test]
fn free_hoop_scene_runs_with_lgvi_and_with_gauss() {
    let scene = find("free-hoop").unwrap();
    let params = scene.info().default_params();
    for integrator in ["lgvi", "gauss8"] {
        let mut rows = Rows::default();
        let opts = RunOptions {
            integrator: Some(integrator.into()),
            step: Some(tumble_scenarios::StepControl::Fixed(1e-3)),
            t_end: Some(6.0),
            ..Default::default()
        };
        let summary = scene.run(&params, &opts, &mut rows).unwrap();
        let cols = scene.info().columns();
        assert_eq!(cols.len(), rows.0[0].len());
        let lz = cols.iter().position(|c| c == "Lz").unwrap();
        let lz0 = rows.0[0][lz];
        assert!(
            rows.0
                .iter()
                .all(|r| (r[lz] - lz0).abs() < 1e-10 * lz0.abs().max(1.0)),
            "{integrator}"
        );
        assert!(
            summary.max_energy_rel_err < 1e-5,
            "{integrator}: {}",
            summary.max_energy_rel_err
        );
        // The quaternion's sign is continuous along the run (no q → −q jumps).
        assert!(
            rows.0
                .windows(2)
                .all(|w| (1..5).map(|i| w[0][i] * w[1][i]).sum::<f64>() > 0.9)
        );
        // Quaternion stays unit.
        assert!(rows.0.iter().all(|r| {
            ((r[1] * r[1] + r[2] * r[2] + r[3] * r[3] + r[4] * r[4]) - 1.0).abs() < 1e-12
        }));
    }
}

/// The free hoop with only its Lagrangian: every derivative by automatic differentiation (the
/// trait's defaults), against which the scene's closed forms are checked.
struct ByAutomaticDifferentiation(FreeHoop);

impl CoupledLagrangian<1> for ByAutomaticDifferentiation {
    fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
        self.0.kinetic(q)
    }
    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
        self.0.potential(rotation, q)
    }
}

#[test]
fn closed_form_jet_hessian_and_moment_equal_automatic_differentiation() {
    let model = FreeHoop {
        hoop: HoopParams::new(1.3, 0.4, 0.7, 9.81).unwrap(),
    };
    let ad = ByAutomaticDifferentiation(model);
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 4.0 * f64::EPSILON * scale;
    for k in 0..40 {
        let alpha = -7.0 + 0.37 * f64::from(k);
        let q = SVector::<f64, 1>::new(alpha);
        let rotation = tumble_kinematics::so3::exp(&Vector3::new(0.3 * alpha, 1.1, -0.2 * alpha));
        let r = rotation.matrix();
        let (closed, auto) = (model.kinetic_jet(&q), ad.kinetic_jet(&q));
        let scale = closed.blocks.rotational.amax();
        for (x, y) in [
            (closed.blocks, auto.blocks),
            (closed.derivatives[0], auto.derivatives[0]),
        ] {
            for (a, b) in x.rotational.iter().zip(y.rotational.iter()) {
                assert!(close(*a, *b, scale), "J at alpha {alpha}: {a} vs {b}");
            }
            assert!(close(x.coupling[2], y.coupling[2], scale), "B at {alpha}");
            assert!(x.coupling[0].abs() + y.coupling[0].abs() <= 4.0 * f64::EPSILON * scale);
            assert!(close(x.internal[0], y.internal[0], scale), "M at {alpha}");
        }
        let (h1, h2) = (model.kinetic_hessian(&q), ad.kinetic_hessian(&q));
        for (a, b) in h1[0][0].rotational.iter().zip(h2[0][0].rotational.iter()) {
            assert!(close(*a, *b, scale), "J'' at alpha {alpha}: {a} vs {b}");
        }
        let ((m1, g1), (m2, g2)) = (
            model.potential_derivatives(r, &q),
            ad.potential_derivatives(r, &q),
        );
        let scale = 0.4 * 9.81 * 0.7;
        for (a, b) in m1.iter().zip(m2.iter()) {
            assert!(close(*a, *b, scale), "moment at alpha {alpha}: {a} vs {b}");
        }
        assert!(close(g1[0], g2[0], scale), "dV/dalpha at {alpha}");
    }
}

#[test]
fn closed_form_lgvi_steps_match_the_automatic_differentiation_ones() {
    // The same 200 steps of the coupled LGVI with the closed forms and with automatic
    // differentiation: the maps agree to round-off (their iterations stop at the same accuracy).
    let model = FreeHoop { hoop: params(9.81) };
    let ad = ByAutomaticDifferentiation(model);
    let s0 = model.initial_state(1.2, 4.0, 0.7, 0.3);
    let (mut a, mut b) = (s0, s0);
    let (mut st_a, mut st_b) = (CoupledLgvi::<1>::new(), CoupledLgvi::<1>::new());
    for k in 0..200 {
        let t = 0.01 * f64::from(k);
        Stepper::step(&mut st_a, &model, t, &mut a, 0.01).unwrap();
        Stepper::step(&mut st_b, &ad, t, &mut b, 0.01).unwrap();
    }
    let d = (a.rotation - b.rotation)
        .amax()
        .max((a.momentum - b.momentum).amax())
        .max((a.q - b.q).amax())
        .max((a.p - b.p).amax());
    assert!(
        d < 1e-12,
        "closed form and AD LGVI differ by {d:e} after 200 steps"
    );
}

/// `∂T/∂α` at fixed velocities, as `coupled_kinetic_gradient` gives it from the closed-form jet,
/// is the central difference of `T = ½ Ω·JΩ + Ω·B α̇ + ½ M α̇²` built from the blocks.
#[test]
fn kinetic_gradient_is_the_central_difference_of_the_kinetic_energy() {
    let model = FreeHoop {
        hoop: HoopParams::new(1.3, 0.4, 0.7, 9.81).unwrap(),
    };
    let omega = Vector3::new(0.7, -1.9, 2.3);
    let qdot = SVector::<f64, 1>::new(-1.4);
    let kinetic = |alpha: f64| {
        let k: KineticBlocks<f64, 1> = model.kinetic(&SVector::<f64, 1>::new(alpha));
        0.5 * omega.dot(&(k.rotational * omega))
            + omega.dot(&(k.coupling * qdot))
            + 0.5 * (qdot.transpose() * k.internal * qdot)[0]
    };
    for k in 0..30 {
        let alpha = -4.0 + 0.29 * f64::from(k);
        let g = coupled_kinetic_gradient(&model, &SVector::<f64, 1>::new(alpha), &omega, &qdot);
        let d = 1e-5;
        let fd = (kinetic(alpha + d) - kinetic(alpha - d)) / (2.0 * d);
        assert!(
            (g[0] - fd).abs() <= 1e-8 * (1.0 + fd.abs()),
            "alpha {alpha}: {} vs {fd}",
            g[0]
        );
    }
}
