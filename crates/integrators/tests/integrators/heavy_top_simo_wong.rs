//! The heavy top of Simo & Wong (1991): `J = diag(5, 5, 1)`, `M g l = 20`,
//! `Λ₀ = exp(hat(0.05, 0, 0))`, body angular velocity `W₀ = (0, 0, 50)`, `H ≈ 1269.975`,
//! `t ∈ [0, 10]`, `h ∈ {0.001, 0.003, 0.009}`: a fast top (spin period 0.13) precessing slowly,
//! a hard case for methods that are not made for rotation.
//!
//! Oracles: the energy (relative error bounded, no blow-up); the vertical angular momentum
//! `L·e₃` (gravity's symmetry) and the spin `m₃` (the body's symmetry about its axis), conserved
//! to round-off by the variational and splitting methods (discrete Noether theorem; each
//! sub-flow of the splittings conserves both). `rkmk4` (not symplectic) is run alongside for
//! comparison: its error is larger and not structured.

use tumble_integrators::rigid::EulerEquations;
use tumble_integrators::rigid::{
    ExactSplitting, GroupState, HeavyTop, Lgvi, PrincipalAxisSplitting, RigidBody,
    RigidBodyMonitor, RigidBodyState, rkmk4,
};
use tumble_integrators::{Driver, Flow, Observer, Stepper};

const T_END: f64 = 10.0;

/// Also tracks the largest change of the spin `m₃` and the energy error in each half of the run.
struct Watch<'a> {
    monitor: RigidBodyMonitor<'a, HeavyTop>,
    top: &'a HeavyTop,
    e0: f64,
    m3: f64,
    spin: f64,
    halves: [f64; 2],
}

impl Observer<RigidBodyState> for Watch<'_> {
    fn observe(&mut self, t: f64, s: &RigidBodyState) -> Flow {
        self.monitor.observe(t, s);
        let e = ((self.top.hamiltonian(s) - self.e0) / self.e0).abs();
        let half = usize::from(t > 0.5 * T_END);
        self.halves[half] = self.halves[half].max(e);
        self.spin = self.spin.max((s.momentum.z - self.m3).abs());
        Flow::Continue
    }
}

impl Observer<GroupState<3>> for Watch<'_> {
    fn observe(&mut self, t: f64, s: &GroupState<3>) -> Flow {
        Observer::<RigidBodyState>::observe(self, t, &RigidBodyState::from(*s))
    }
}

struct Outcome {
    energy: f64,
    halves: [f64; 2],
    vertical: f64,
    spin: f64,
    defect: f64,
}

fn run<St: Stepper<P>, P: ?Sized>(
    mut st: St,
    problem: &P,
    s0: St::State,
    top: &HeavyTop,
    h: f64,
) -> Outcome
where
    for<'a> Watch<'a>: Observer<St::State>,
{
    let init = HeavyTop::simo_wong_initial();
    let mut watch = Watch {
        monitor: RigidBodyMonitor::new(top),
        top,
        e0: top.hamiltonian(&init),
        m3: init.momentum.z,
        spin: 0.0,
        halves: [0.0; 2],
    };
    let mut s = s0;
    Driver::new(0.0, T_END)
        .unwrap()
        .run_fixed(&mut st, problem, &mut s, h, &mut watch)
        .unwrap();
    let d = watch.monitor.deviations();
    let l0 = init.spatial_momentum().norm();
    Outcome {
        energy: d.energy_relative,
        halves: watch.halves,
        vertical: d.vertical_momentum / l0,
        spin: watch.spin / init.momentum.norm(),
        defect: d.orthogonality,
    }
}

#[test]
fn simo_wong_initial_energy_is_1269_975() {
    let top = HeavyTop::simo_wong();
    let h = top.hamiltonian(&HeavyTop::simo_wong_initial());
    let expected = 1250.0 + 20.0 * 0.05f64.cos();
    assert!(
        (h - expected).abs() < 4.0 * f64::EPSILON * expected,
        "{h} vs {expected}"
    );
    assert!((h - 1269.975).abs() < 1e-3, "{h}");
}

#[test]
fn simo_wong_heavy_top_energy_stays_bounded_for_lgvi_and_the_splittings() {
    let top = HeavyTop::simo_wong();
    let s0 = HeavyTop::simo_wong_initial();
    let mut lines = vec![];
    let mut failures = vec![];
    let mut check = |ok: bool, what: String| {
        if !ok {
            failures.push(what);
        }
    };
    for h in [0.001, 0.003, 0.009] {
        let results = [
            ("lgvi", run(Lgvi::default(), &top, s0, &top, h)),
            (
                "split2",
                run(PrincipalAxisSplitting::new(), &top, s0, &top, h),
            ),
            (
                "split-exact2",
                run(ExactSplitting::new(), &top, s0, &top, h),
            ),
            (
                "rkmk4",
                run(
                    rkmk4::<3>(),
                    &EulerEquations(top),
                    GroupState::from(s0),
                    &top,
                    h,
                ),
            ),
        ];
        for (name, o) in &results {
            lines.push(format!(
                "h = {h}: {name:>12}: max |ΔH|/H = {:.2e} (halves {:.2e}, {:.2e}), |ΔL·e₃|/|L| = {:.1e}, |Δm₃|/|m| = {:.1e}, ‖RᵀR − 𝟙‖ = {:.1e}",
                o.energy, o.halves[0], o.halves[1], o.vertical, o.spin, o.defect
            ));
            check(
                o.defect < 1e-13,
                format!("{name} h = {h}: defect {:e}", o.defect),
            );
            if *name == "rkmk4" {
                continue;
            }
            // Bounded: the error of the second half is not larger than that of the first by
            // more than 10 % (a drift would double it), and it is small.
            check(
                o.halves[1] <= 1.1 * o.halves[0] && o.energy < 0.02,
                format!(
                    "{name} h = {h}: energy {:e}, halves {:?}",
                    o.energy, o.halves
                ),
            );
            check(
                o.vertical < 1e-13,
                format!("{name} h = {h}: L·e₃ drift {:e}", o.vertical),
            );
            if *name != "split2" {
                check(
                    o.spin < 1e-13,
                    format!("{name} h = {h}: m₃ drift {:e}", o.spin),
                );
            }
        }
    }
    eprintln!("{}", lines.join("\n"));
    assert!(failures.is_empty(), "{failures:#?}");
}
