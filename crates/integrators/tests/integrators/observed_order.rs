//! Every fixed-step method's observed order is within ±0.3 of its nominal order on the
//! harmonic oscillator, Kepler (e = 0.6, three periods) and the pendulum near its separatrix
//! (k = 0.999), measured by the shared harness (halve the step, fit above 1e-13, ≥ 3 points).

use tumble_integrators::verification::OrderStudy;

use crate::support::{Exact, error_of};

/// Step ratio: halving, or `2^{1/3}` for orders ≥ 10 where halving would jump from the
/// pre-asymptotic regime straight to the round-off floor.
const HALF: f64 = 2.0;
const THIRD: f64 = 1.259_921_049_894_873_2;

/// (method, nominal order, steps of the coarsest run, ratio, number of runs)
type Case = (&'static str, f64, f64, f64, usize);

const HARMONIC: &[Case] = &[
    ("symplectic-euler", 1.0, 512.0, HALF, 5),
    ("verlet", 2.0, 64.0, HALF, 5),
    ("rk4", 4.0, 32.0, HALF, 5),
    ("dp5", 5.0, 16.0, HALF, 5),
    ("dop853", 8.0, 4.0, HALF, 5),
    ("tsit5", 5.0, 64.0, HALF, 5),
    ("vern7", 7.0, 16.0, HALF, 4),
    ("vern8", 8.0, 8.0, HALF, 3),
    ("yoshida4", 4.0, 32.0, HALF, 5),
    ("suzuki4", 4.0, 16.0, HALF, 5),
    ("mclachlan4", 4.0, 16.0, HALF, 5),
    ("yoshida6", 6.0, 16.0, HALF, 5),
    ("kahan-li6", 6.0, 16.0, HALF, 5),
    ("yoshida8", 8.0, 16.0, HALF, 5),
    ("kahan-li8", 8.0, 8.0, HALF, 5),
    ("sofroniou-spaletta10", 10.0, 4.0, HALF, 4),
    ("gauss2", 2.0, 128.0, HALF, 5),
    ("gauss4", 4.0, 16.0, HALF, 5),
    ("gauss6", 6.0, 8.0, HALF, 5),
    ("gauss8", 8.0, 4.0, HALF, 5),
    ("gauss10", 10.0, 4.0, HALF, 4),
    ("gauss12", 12.0, 4.0, THIRD, 7),
];

const KEPLER: &[Case] = &[
    ("symplectic-euler", 1.0, 16384.0, HALF, 4),
    ("verlet", 2.0, 2048.0, HALF, 5),
    ("rk4", 4.0, 1024.0, HALF, 5),
    ("dp5", 5.0, 1024.0, HALF, 4),
    ("tsit5", 5.0, 1024.0, HALF, 4),
    ("vern7", 7.0, 256.0, HALF, 4),
    ("vern8", 8.0, 128.0, HALF, 4),
    ("yoshida4", 4.0, 1024.0, HALF, 5),
    ("suzuki4", 4.0, 512.0, HALF, 5),
    ("mclachlan4", 4.0, 512.0, HALF, 5),
    ("yoshida6", 6.0, 256.0, HALF, 5),
    ("kahan-li6", 6.0, 256.0, HALF, 5),
    ("yoshida8", 8.0, 512.0, HALF, 4),
    ("kahan-li8", 8.0, 256.0, HALF, 4),
    ("sofroniou-spaletta10", 10.0, 256.0, THIRD, 4),
    ("gauss2", 2.0, 4096.0, HALF, 5),
    ("gauss4", 4.0, 512.0, HALF, 5),
    ("gauss6", 6.0, 256.0, HALF, 5),
    ("gauss8", 8.0, 256.0, HALF, 3),
    ("gauss10", 10.0, 203.0, THIRD, 5),
];

const PENDULUM: &[Case] = &[
    ("symplectic-euler", 1.0, 16384.0, HALF, 4),
    ("verlet", 2.0, 2048.0, HALF, 5),
    ("rk4", 4.0, 256.0, HALF, 5),
    ("dp5", 5.0, 256.0, HALF, 4),
    ("yoshida4", 4.0, 256.0, HALF, 5),
    ("suzuki4", 4.0, 128.0, HALF, 5),
    ("mclachlan4", 4.0, 128.0, HALF, 5),
    ("yoshida6", 6.0, 64.0, HALF, 5),
    ("kahan-li6", 6.0, 64.0, HALF, 5),
    ("yoshida8", 8.0, 64.0, HALF, 4),
    ("kahan-li8", 8.0, 32.0, HALF, 4),
    ("sofroniou-spaletta10", 10.0, 32.0, THIRD, 5),
    ("gauss2", 2.0, 1024.0, HALF, 5),
    ("gauss4", 4.0, 128.0, HALF, 5),
    ("gauss6", 6.0, 32.0, HALF, 5),
    ("gauss8", 8.0, 32.0, HALF, 4),
    ("gauss10", 10.0, 32.0, THIRD, 6),
];

fn check_problem(problem: Exact, cases: &[Case], floor: f64) {
    let mut failures = Vec::new();
    for &(name, nominal, coarsest, ratio, count) in cases {
        let span = problem.t_end();
        let mut study = OrderStudy::new(span / coarsest, count)
            .with_ratio(ratio)
            .on_span(span);
        study.floor = floor;
        let fit = study
            .run(|h| error_of(name, problem, h))
            .unwrap_or_else(|e| panic!("{name} on {problem:?} failed: {e}"));
        eprintln!(
            "{problem:?} {name:>22}: observed order {:6.3} (nominal {nominal}) on {} points",
            fit.slope,
            fit.used_points()
        );
        if let Err(msg) = fit.check(nominal, 0.3) {
            failures.push(format!("{name}: {msg}"));
        }
    }
    assert!(failures.is_empty(), "{problem:?}:\n{}", failures.join("\n"));
}

#[test]
fn every_method_has_its_order_on_the_harmonic_oscillator() {
    check_problem(Exact::Harmonic, HARMONIC, 1e-13);
}

/// The error is measured at apocentre after 2.5 periods, where the round-off floor of every
/// method is 2e-15 … 7e-15 (measured over the finest steps): the fit floor is 1e-14.
#[test]
fn every_method_has_its_order_on_kepler_e06() {
    check_problem(Exact::Kepler, KEPLER, 1e-14);
}

#[test]
fn every_method_has_its_order_on_the_pendulum_near_the_separatrix() {
    check_problem(Exact::Pendulum, PENDULUM, 1e-13);
}
