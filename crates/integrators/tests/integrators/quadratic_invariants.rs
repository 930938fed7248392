//! Gauss–Legendre conserves quadratic invariants — the angular momentum of Kepler — to
//! round-off, with fixed-point and with Newton stage solvers, while RK4 drifts.

use nalgebra::SVector;
use tumble_integrators::verification::Kepler;
use tumble_integrators::{
    Driver, ExplicitRungeKutta, Flow, FnObserver, HamiltonianOde, Stepper, gauss4, gauss6, gauss8,
};

type V4 = SVector<f64, 4>;

fn max_drift<St: Stepper<HamiltonianOde<Kepler>, State = V4>>(mut st: St, steps: f64) -> f64 {
    let problem = HamiltonianOde(Kepler);
    let mut y = V4::from(Kepler::initial(0.6));
    let l0 = Kepler::angular_momentum(y.as_slice());
    let mut worst = 0.0_f64;
    let t_end = 20.0 * std::f64::consts::PI;
    let mut obs = FnObserver(|_t, y: &V4| {
        worst = worst.max((Kepler::angular_momentum(y.as_slice()) - l0).abs() / l0.abs());
        Flow::Continue
    });
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, t_end / steps, &mut obs)
        .unwrap();
    worst
}

#[test]
fn gauss_conserves_angular_momentum_to_round_off() {
    let y0 = V4::from(Kepler::initial(0.6));
    let steps = 10_000.0_f64;
    // round-off bound: a few ε per step, random: 10 ε √n
    let bound = 10.0 * f64::EPSILON * steps.sqrt();
    for (name, drift) in [
        ("gauss4", max_drift(gauss4().stepper(&y0), steps)),
        ("gauss6", max_drift(gauss6().stepper(&y0), steps)),
        ("gauss8", max_drift(gauss8().stepper(&y0), steps)),
        (
            "gauss6-newton",
            max_drift(gauss6().with_newton().stepper(&y0), steps),
        ),
    ] {
        eprintln!("{name}: max relative drift of L = {drift:.2e} (bound {bound:.1e})");
        assert!(drift <= bound, "{name}: {drift:e}");
    }
    let rk4 = max_drift(ExplicitRungeKutta::rk4().stepper(&y0), steps);
    eprintln!("rk4: max relative drift of L = {rk4:.2e}");
    assert!(rk4 > 1e3 * bound, "RK4 does not conserve L: {rk4:e}");
}
