//! Shared helpers: integrate a first-order system with DOP853 at a tight tolerance.

use nalgebra::SVector;
use tumble_integrators::{
    Action, Direction, Driver, Event, ExplicitRungeKutta, NoObserver, Ode, Report, Tolerances,
};

/// Integrates `problem` from `y` over `[0, t_end]` at `tol`, with optional events; `y` holds the
/// end state.
pub fn integrate<P: Ode<SVector<f64, S>>, const S: usize>(
    problem: &P,
    y: &mut SVector<f64, S>,
    t_end: f64,
    tol: f64,
    events: &mut [Event<'_, SVector<f64, S>>],
) -> Report<SVector<f64, S>> {
    let mut stepper = ExplicitRungeKutta::dop853().stepper(y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            problem,
            y,
            &Tolerances::new(tol, tol).unwrap(),
            events,
            &mut NoObserver,
        )
        .unwrap()
}

/// An event at every upward zero crossing of component `i` minus `level`.
pub fn crossing<const S: usize>(
    i: usize,
    level: f64,
    direction: Direction,
) -> Event<'static, SVector<f64, S>> {
    Event::new(
        move |_t, y: &SVector<f64, S>| y[i] - level,
        direction,
        Action::Continue,
    )
}

/// Proptest settings: `default_cases` cases, or `PROPTEST_CASES` when set (to stress the bounds
/// with many more random cases than CI runs: `PROPTEST_CASES=200000 cargo test ...`).
/// `ProptestConfig::with_cases` alone would ignore the variable.
pub fn proptest_config(default_cases: u32) -> proptest::prelude::ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    proptest::prelude::ProptestConfig::with_cases(cases)
}
