//! LGVI over 2²⁰ ≈ 10⁶ steps (h = 0.02, t = 2·10⁴):
//!
//! - on the free asymmetric body (non-diagonal `J`): the rotation stays on `SO(3)` to round-off,
//!   the spatial angular momentum and `|m|` are conserved to round-off, and so is the energy —
//!   the torque-free LGVI is the discrete Moser–Veselov map, which conserves `½ m·J⁻¹m` exactly —
//!   so the energy error is pure round-off. The LGVI applies `F = 𝟙 + G` as compensated
//!   increments (`R + RG`, `m + Gᵀm`, Kahan carries between steps), so the round-off does not
//!   accumulate measurably: every invariant stays at a few ε over the whole run, and the per-block
//!   maxima of the energy error do not grow (exponent ≈ 0; a random walk would give ½, a drift 1);
//! - on the asymmetric heavy top (chaotic, energy not conserved by the map): the energy error is
//!   bounded with no drift (per-block maxima over blocks `[2ᵏ, 2ᵏ⁺¹)` steps, `k = 10 … 19`,
//!   fitted against the step count: exponent ≈ 0), and the vertical angular momentum `L·e₃`
//!   (gravity's symmetry) is conserved to round-off.
//!
//! The invariants are watched on the fly by the crate's `RigidBodyMonitor` (running maxima);
//! a second observer keeps the per-block maxima. Nothing is stored per step.

use tumble_integrators::rigid::{Lgvi, RigidBody, RigidBodyMonitor, RigidBodyState};
use tumble_integrators::verification::fit_power_law;
use tumble_integrators::{Driver, Flow, Observer};

use crate::rigid_support::*;

const STEPS: u64 = 1 << 20;
const H: f64 = 0.02;

/// Forwards to the monitor and keeps the maximum relative energy error per block of steps.
struct Blocks<'a, B: RigidBody> {
    monitor: RigidBodyMonitor<'a, B>,
    body: &'a B,
    e0: f64,
    step: u64,
    block_start: u64,
    current: f64,
    ns: Vec<f64>,
    maxima: Vec<f64>,
}

impl<B: RigidBody> Observer<RigidBodyState> for Blocks<'_, B> {
    fn observe(&mut self, t: f64, s: &RigidBodyState) -> Flow {
        self.monitor.observe(t, s);
        let err = ((self.body.hamiltonian(s) - self.e0) / self.e0).abs();
        if self.step >= self.block_start {
            self.current = self.current.max(err);
            if self.step + 1 == 2 * self.block_start {
                self.ns.push(1.5 * self.block_start as f64);
                self.maxima.push(self.current);
                self.current = 0.0;
                self.block_start *= 2;
            }
        }
        self.step += 1;
        Flow::Continue
    }
}

struct Summary {
    deviations: tumble_integrators::rigid::Deviations,
    drift: f64,
    maxima: Vec<f64>,
    final_defect: f64,
}

fn long_run<B: RigidBody>(problem: &B, s0: RigidBodyState) -> Summary {
    let mut obs = Blocks {
        monitor: RigidBodyMonitor::new(problem),
        body: problem,
        e0: problem.hamiltonian(&s0),
        step: 0,
        block_start: 1 << 10,
        current: 0.0,
        ns: vec![],
        maxima: vec![],
    };
    let mut s = s0;
    let report = Driver::new(0.0, STEPS as f64 * H)
        .unwrap()
        .run_fixed(&mut Lgvi::default(), problem, &mut s, H, &mut obs)
        .unwrap();
    assert_eq!(report.steps, STEPS);
    Summary {
        deviations: obs.monitor.deviations(),
        drift: fit_power_law(&obs.ns, &obs.maxima),
        maxima: obs.maxima,
        final_defect: s.orthogonality_defect(),
    }
}

fn describe(name: &str, r: &Summary, s0: &RigidBodyState) -> String {
    let d = &r.deviations;
    let maxima: Vec<String> = r.maxima.iter().map(|m| format!("{m:.2e}")).collect();
    format!(
        "{name}, {STEPS} steps of h = {H}: max ‖RᵀR − 𝟙‖ = {:.2e} (final {:.2e}); \
         max |L − L₀|/|L₀| = {:.2e}; max |ΔL·e₃|/|L₀| = {:.2e}; Casimir ||m| − |m₀||/|m₀| = {:.2e}; \
         max relative energy error {:.3e}, per-block maxima [{}], exponent {:.3}",
        d.orthogonality,
        r.final_defect,
        d.spatial_momentum / s0.spatial_momentum().norm(),
        d.vertical_momentum / s0.spatial_momentum().norm(),
        d.casimir / s0.momentum.norm(),
        d.energy_relative,
        maxima.join(" "),
        r.drift,
    )
}

/// Round-off of `n` steps with uncompensated updates would be a random walk, ~ε√n ≈ 2e-13 after
/// 10⁶ steps; the bound allows a factor 10 on that.
fn roundoff() -> f64 {
    10.0 * f64::EPSILON * (STEPS as f64).sqrt()
}

#[test]
fn lgvi_keeps_a_free_body_on_so3_and_its_invariants_to_roundoff_over_a_million_steps() {
    let body = asymmetric_body();
    let s0 = initial_state();
    let r = long_run(&body, s0);
    eprintln!("{}", describe("lgvi, free body", &r, &s0));
    let d = &r.deviations;
    let l0 = s0.spatial_momentum().norm();
    // With compensated increments nothing accumulates: a few roundings of one step (≈ 2e-16
    // each) bound every deviation over the whole run.
    let few = 50.0 * f64::EPSILON;
    for (what, value) in [
        ("‖RᵀR − 𝟙‖", d.orthogonality),
        ("|L − L₀|/|L₀|", d.spatial_momentum / l0),
        ("||m| − |m₀||/|m₀|", d.casimir / s0.momentum.norm()),
        ("|H − H₀|/H₀", d.energy_relative),
    ] {
        assert!(value < few, "{what} = {value:e} > {few:e}");
    }
    assert!(r.drift.abs() < 0.2, "round-off growth exponent {}", r.drift);
}

#[test]
fn lgvi_energy_error_of_a_heavy_top_stays_bounded_over_a_million_steps() {
    let top = asymmetric_top();
    let s0 = initial_state();
    let r = long_run(&top, s0);
    eprintln!("{}", describe("lgvi, asymmetric heavy top", &r, &s0));
    let d = &r.deviations;
    let l0 = s0.spatial_momentum().norm();
    assert!(
        d.orthogonality < roundoff(),
        "orthogonality defect {:e}",
        d.orthogonality
    );
    assert!(
        d.vertical_momentum / l0 < roundoff(),
        "vertical angular momentum drift {:e}",
        d.vertical_momentum / l0
    );
    assert!(
        d.energy_relative < 1e-2,
        "energy error {:e}",
        d.energy_relative
    );
    assert!(r.drift.abs() < 0.05, "energy drift exponent {}", r.drift);
}
