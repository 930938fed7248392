//! Dense output has its order, and event location finds the zero crossings of the
//! pendulum's angle (k = 0.999, crossings at t = 2jK(k²)) to 1e-10 in time.

use nalgebra::SVector;
use tumble_integrators::verification::{HarmonicOscillator, OrderStudy, Pendulum};
use tumble_integrators::{
    Action, DenseOutput, Direction, Driver, Event, ExplicitRungeKutta, HamiltonianOde, NoObserver,
    Status, Stepper, Tolerances, special::ellip_k,
};

type V2 = SVector<f64, 2>;

/// Local interpolation error at θ = 1/3 of one step from the exact state: O(h^(q+1)).
fn dense_error<const S: usize>(method: ExplicitRungeKutta<S>, h: f64) -> f64 {
    let problem = HamiltonianOde(HarmonicOscillator);
    let t0 = 0.7;
    let mut y = V2::from(HarmonicOscillator::exact(1.0, 0.0, t0));
    let mut st = method.stepper(&y);
    st.step(&problem, t0, &mut y, h).unwrap();
    let mut out = V2::zeros();
    let t = t0 + h / 3.0;
    st.interpolate(&problem, t, &mut out);
    let exact = HarmonicOscillator::exact(1.0, 0.0, t);
    (out[0] - exact[0]).abs().max((out[1] - exact[1]).abs())
}

#[test]
fn dense_outputs_have_their_orders() {
    for (name, order, fit) in [
        (
            "rk4 (cubic Hermite)",
            3.0,
            OrderStudy::new(0.4, 5).run(|h| Ok(dense_error(ExplicitRungeKutta::rk4(), h))),
        ),
        (
            "dp5",
            4.0,
            OrderStudy::new(0.4, 5).run(|h| Ok(dense_error(ExplicitRungeKutta::dp5(), h))),
        ),
        (
            "dop853",
            7.0,
            OrderStudy::new(0.8, 4).run(|h| Ok(dense_error(ExplicitRungeKutta::dop853(), h))),
        ),
    ] {
        let fit = fit.unwrap();
        eprintln!("dense {name}: local slope {:.3}", fit.slope);
        fit.check(order + 1.0, 0.3)
            .unwrap_or_else(|m| panic!("{name}: {m}"));
    }
}

#[test]
fn pendulum_zero_crossings_are_located_to_1e10() {
    let k = 0.999;
    let big_k = ellip_k(k * k).unwrap();
    let problem = HamiltonianOde(Pendulum);
    let mut y = V2::from(Pendulum::initial(k));
    let mut st = ExplicitRungeKutta::dop853().stepper(&y);
    let mut events = [Event::new(
        |_t, y: &V2| y[0],
        Direction::Either,
        Action::Continue,
    )];
    let report = Driver::new(0.0, 40.0)
        .unwrap()
        .run_adaptive(
            &mut st,
            &problem,
            &mut y,
            &Tolerances::new(1e-14, 1e-14).unwrap(),
            &mut events,
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.status, Status::Completed);
    // crossings at 2K, 4K, 6K, 8K < 40 (2K ≈ 8.99)
    assert_eq!(report.events.len(), 4, "{:?}", report.events);
    for (j, ev) in report.events.iter().enumerate() {
        let exact = 2.0 * (j as f64 + 1.0) * big_k;
        let err = (ev.t - exact).abs();
        eprintln!(
            "crossing {}: t = {:.15} exact {exact:.15} |Δt| = {err:.2e}",
            j + 1,
            ev.t
        );
        assert!(err <= 1e-10, "crossing {j}: {err:e}");
        assert!(ev.state[0].abs() <= 1e-9);
    }
}

#[test]
fn terminal_event_with_direction_stops_at_the_first_rising_crossing() {
    let k = 0.999;
    let big_k = ellip_k(k * k).unwrap();
    let problem = HamiltonianOde(Pendulum);
    let mut y = V2::from(Pendulum::initial(k));
    let mut st = ExplicitRungeKutta::dop853().stepper(&y);
    // q rises through 0 at 4K (at 2K it falls).
    let mut events = [Event::new(
        |_t, y: &V2| y[0],
        Direction::Rising,
        Action::Terminate,
    )];
    let report = Driver::new(0.0, 40.0)
        .unwrap()
        .run_adaptive(
            &mut st,
            &problem,
            &mut y,
            &Tolerances::new(1e-14, 1e-14).unwrap(),
            &mut events,
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.status, Status::Terminated(0));
    assert!((report.t - 4.0 * big_k).abs() <= 1e-10, "{}", report.t);
    assert!(y[0].abs() <= 1e-9 && y[1] > 0.0);
}

#[test]
fn events_work_with_fixed_steps_too() {
    let k = 0.999;
    let big_k = ellip_k(k * k).unwrap();
    let problem = HamiltonianOde(Pendulum);
    let mut y = V2::from(Pendulum::initial(k));
    let mut st = ExplicitRungeKutta::dop853().stepper(&y);
    let mut events = [Event::new(
        |_t, y: &V2| y[0],
        Direction::Falling,
        Action::Continue,
    )];
    let report = Driver::new(0.0, 10.0)
        .unwrap()
        .run_fixed_with_events(
            &mut st,
            &problem,
            &mut y,
            0.005,
            &mut events,
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.events.len(), 1);
    assert!((report.events[0].t - 2.0 * big_k).abs() <= 1e-10);
}
