//! The driver's contract: bad parameters are errors, the horizon is hit exactly, observers
//! are called every n steps, cancellation stops the run, non-finite states and
//! non-convergence are typed errors with time and state, counting is exact, runtime-sized
//! states give the same results as fixed-size ones.

use std::cell::Cell;

use nalgebra::{DVector, SVector};
use tumble_integrators::verification::{HarmonicOscillator, Kepler, RigidBodyEuler};
use tumble_integrators::{
    Counted, Driver, Error, ExplicitRungeKutta, Flow, FnObserver, FnOde, HamiltonianOde,
    NoObserver, Status, Tolerances, gauss4, gauss6,
};

type V1 = SVector<f64, 1>;
type V2 = SVector<f64, 2>;
type V3 = SVector<f64, 3>;

#[test]
fn bad_parameters_are_errors() {
    let problem = HamiltonianOde(HarmonicOscillator);
    let mut y = V2::new(1.0, 0.0);
    let mut st = ExplicitRungeKutta::rk4().stepper(&y);
    let d = Driver::new(0.0, 1.0).unwrap();
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = d
            .run_fixed(&mut st, &problem, &mut y, h, &mut NoObserver)
            .unwrap_err();
        assert!(
            matches!(e, Error::InvalidParameter { name: "h", .. }),
            "{e}"
        );
    }
    let e = d
        .run_fixed(&mut st, &problem, &mut y, 2.0, &mut NoObserver)
        .unwrap_err();
    assert!(matches!(e, Error::StepLargerThanHorizon { .. }), "{e}");
    assert!(Driver::new(1.0, 1.0).is_err());
    assert!(Driver::new(1.0, 0.0).is_err());
    assert!(Driver::new(f64::NAN, 1.0).is_err());
    assert!(Driver::new(0.0, 1.0).unwrap().every(0).is_err());
    for (r, a) in [(0.0, 1e-6), (1e-6, -1.0), (f64::NAN, 1e-6)] {
        assert!(Tolerances::new(r, a).is_err());
    }
    let mut st8 = ExplicitRungeKutta::dop853().stepper(&y);
    let bad = Tolerances {
        rtol: -1.0,
        atol: 1e-6,
    };
    let e = d
        .run_adaptive(&mut st8, &problem, &mut y, &bad, &mut [], &mut NoObserver)
        .unwrap_err();
    assert!(matches!(e, Error::InvalidParameter { name: "rtol", .. }));
}

#[test]
fn fixed_steps_land_exactly_on_the_horizon() {
    let problem = HamiltonianOde(HarmonicOscillator);
    let mut y = V2::new(1.0, 0.0);
    let mut st = ExplicitRungeKutta::rk4().stepper(&y);
    let report = Driver::new(0.0, 1.0)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.3, &mut NoObserver)
        .unwrap();
    assert_eq!(report.t, 1.0);
    assert_eq!(report.steps, 4, "0.3, 0.3, 0.3, 0.1");
    let exact = HarmonicOscillator::exact(1.0, 0.0, 1.0);
    assert!((y[0] - exact[0]).abs() < 1e-3);
    // an integer number of steps up to rounding: all steps equal
    let mut y = V2::new(1.0, 0.0);
    let report = Driver::new(0.0, 1.0)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.1, &mut NoObserver)
        .unwrap();
    assert_eq!((report.t, report.steps), (1.0, 10));
}

#[test]
fn observers_are_called_every_n_steps_and_can_stop() {
    let problem = HamiltonianOde(HarmonicOscillator);
    let mut y = V2::new(1.0, 0.0);
    let mut st = ExplicitRungeKutta::rk4().stepper(&y);
    let mut times = Vec::new();
    let mut obs = FnObserver(|t, _y: &V2| {
        times.push(t);
        Flow::Continue
    });
    Driver::new(0.0, 1.0)
        .unwrap()
        .every(4)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.1, &mut obs)
        .unwrap();
    // t0, after steps 4 and 8, and the end
    assert_eq!(times.len(), 4, "{times:?}");
    assert_eq!(times[0], 0.0);
    assert_eq!(*times.last().unwrap(), 1.0);
    let mut y = V2::new(1.0, 0.0);
    let mut calls = 0;
    let mut stop = FnObserver(|_t, _y: &V2| {
        calls += 1;
        if calls == 3 {
            Flow::Stop
        } else {
            Flow::Continue
        }
    });
    let r = Driver::new(0.0, 1.0)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.1, &mut stop)
        .unwrap();
    assert_eq!((r.status, r.steps), (Status::Stopped, 2));
}

#[test]
fn cancellation_stops_the_run() {
    let problem = HamiltonianOde(HarmonicOscillator);
    let mut y = V2::new(1.0, 0.0);
    let mut st = ExplicitRungeKutta::dop853().stepper(&y);
    let polls = Cell::new(0);
    let cancel = || {
        polls.set(polls.get() + 1);
        polls.get() > 5
    };
    let r = Driver::new(0.0, 100.0)
        .unwrap()
        .cancel(&cancel)
        .run_adaptive(
            &mut st,
            &problem,
            &mut y,
            &Tolerances::new(1e-10, 1e-10).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(r.status, Status::Cancelled);
    assert!(r.t < 100.0 && r.steps <= 5);
}

#[test]
fn a_blow_up_is_a_non_finite_error_with_time_and_state() {
    // y' = y², y(0) = 1 blows up at t = 1.
    let problem = FnOde(|_t: f64, y: &V1, dy: &mut V1| dy[0] = y[0] * y[0]);
    let mut y = V1::new(1.0);
    let mut st = ExplicitRungeKutta::rk4().stepper(&y);
    let e = Driver::new(0.0, 2.0)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.01, &mut NoObserver)
        .unwrap_err();
    match e {
        Error::NonFinite { t, state, .. } => {
            assert!(t > 0.9 && t < 1.1, "{t}");
            assert_eq!(state.len(), 1);
            // The state reported is the one at the start of the failing step: finite, and on
            // the exact solution 1/(1 − t) to the method's accuracy.
            assert!(state[0].is_finite() && state[0] > 1.0, "{state:?}");
        }
        other => panic!("expected NonFinite, got {other}"),
    }
    // adaptive: the step size collapses before the singularity
    let mut y = V1::new(1.0);
    let mut st = ExplicitRungeKutta::dp5().stepper(&y);
    let e = Driver::new(0.0, 2.0)
        .unwrap()
        .run_adaptive(
            &mut st,
            &problem,
            &mut y,
            &Tolerances::new(1e-8, 1e-8).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap_err();
    assert!(
        matches!(e, Error::StepSizeUnderflow { .. } | Error::NonFinite { .. }),
        "{e}"
    );
}

#[test]
fn stiff_fixed_point_fails_with_a_typed_error_and_newton_succeeds() {
    // y' = −1000 (y − cos t): h L = 100, the fixed-point map expands.
    let problem = FnOde(|t: f64, y: &V1, dy: &mut V1| dy[0] = -1000.0 * (y[0] - t.cos()));
    let mut y = V1::new(0.0);
    let mut st = gauss4().stepper(&y);
    let e = Driver::new(0.0, 1.0)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, 0.1, &mut NoObserver)
        .unwrap_err();
    match e {
        Error::NoConvergence { t, state, .. } => {
            assert_eq!(t, 0.0);
            assert_eq!(state, vec![0.0]);
        }
        other => panic!("expected NoConvergence, got {other}"),
    }
    // Newton converges; start on the smooth solution y = (10⁶ cos t + 10³ sin t)/(10⁶ + 1)
    // (Gauss is A- but not L-stable: a transient would not be damped).
    let smooth = |t: f64| (1e6 * t.cos() + 1e3 * t.sin()) / (1e6 + 1.0);
    let newton_error = |h: f64| {
        let mut y = V1::new(smooth(0.0));
        let mut st = gauss4().with_newton().stepper(&y);
        Driver::new(0.0, 1.0)
            .unwrap()
            .run_fixed(&mut st, &problem, &mut y, h, &mut NoObserver)
            .unwrap();
        (y[0] - smooth(1.0)).abs()
    };
    // Stiff order reduction (stage order 2) keeps the error at h = 0.1 near 1e-4; it
    // decreases with h.
    let (e1, e2) = (newton_error(0.1), newton_error(0.05));
    assert!(e1 < 1e-3 && e2 < 0.5 * e1, "{e1:e} {e2:e}");
}

#[test]
fn evaluations_are_counted_exactly() {
    let problem = Counted::new(HamiltonianOde(HarmonicOscillator));
    let run = |n: f64, which: &str| {
        problem.reset();
        let mut y = V2::new(1.0, 0.0);
        let d = Driver::new(0.0, 1.0).unwrap();
        match which {
            "rk4" => d.run_fixed(
                &mut ExplicitRungeKutta::rk4().stepper(&y),
                &problem,
                &mut y,
                1.0 / n,
                &mut NoObserver,
            ),
            "dp5" => d.run_fixed(
                &mut ExplicitRungeKutta::dp5().stepper(&y),
                &problem,
                &mut y,
                1.0 / n,
                &mut NoObserver,
            ),
            _ => d.run_fixed(
                &mut ExplicitRungeKutta::dop853().stepper(&y),
                &problem,
                &mut y,
                1.0 / n,
                &mut NoObserver,
            ),
        }
        .unwrap();
        problem.evaluations().rhs
    };
    // first same as last: one evaluation saved per step after the first
    assert_eq!(run(10.0, "rk4"), 4 * 10 + 1);
    assert_eq!(run(10.0, "dp5"), 6 * 10 + 1);
    assert_eq!(run(10.0, "dop853"), 12 * 10 + 1);
}

#[test]
fn runtime_sized_states_match_fixed_size_states() {
    let problem = RigidBodyEuler { forced: true };
    let mut ys = V3::from(RigidBodyEuler::INITIAL);
    let mut yd = DVector::from_row_slice(&RigidBodyEuler::INITIAL);
    let d = Driver::new(0.0, 5.0).unwrap();
    let tol = Tolerances::new(1e-10, 1e-10).unwrap();
    d.run_adaptive(
        &mut ExplicitRungeKutta::dop853().stepper(&ys),
        &problem,
        &mut ys,
        &tol,
        &mut [],
        &mut NoObserver,
    )
    .unwrap();
    d.run_adaptive(
        &mut ExplicitRungeKutta::dop853().stepper(&yd),
        &problem,
        &mut yd,
        &tol,
        &mut [],
        &mut NoObserver,
    )
    .unwrap();
    assert_eq!(ys.as_slice(), yd.as_slice());
    let mut ys = V3::from(RigidBodyEuler::INITIAL);
    let mut yd = DVector::from_row_slice(&RigidBodyEuler::INITIAL);
    d.run_fixed(
        &mut gauss6().with_newton().stepper(&ys),
        &problem,
        &mut ys,
        0.05,
        &mut NoObserver,
    )
    .unwrap();
    d.run_fixed(
        &mut gauss6().with_newton().stepper(&yd),
        &problem,
        &mut yd,
        0.05,
        &mut NoObserver,
    )
    .unwrap();
    assert_eq!(ys.as_slice(), yd.as_slice());
    let mut k = DVector::from_row_slice(&Kepler::initial(0.5));
    d.run_fixed(
        &mut gauss6().stepper(&k),
        &HamiltonianOde(Kepler),
        &mut k,
        0.01,
        &mut NoObserver,
    )
    .unwrap();
    assert!(
        (Kepler::angular_momentum(k.as_slice()) - Kepler::angular_momentum(&Kepler::initial(0.5)))
            .abs()
            < 1e-14
    );
}
