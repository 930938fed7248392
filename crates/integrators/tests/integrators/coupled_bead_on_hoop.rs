//! The bead on a hoop (`SO(3) × ℝ`, the design's `free-hoop` geometry): a thin hoop whose centre
//! is a fixed pivot, free to turn in every direction, with a bead sliding on it in gravity. The
//! coupled variational integrator over 2¹⁷ steps: the vertical angular momentum `L·e₃` (gravity's
//! symmetry) is conserved to round-off by the discrete Noether theorem, the energy error is
//! bounded with no drift (per-block maxima over `[2ᵏ, 2ᵏ⁺¹)` steps, `k = 10 … 16`, exponent ≈ 0;
//! the blocks start at 1024 steps, t ≈ 5, once the bead has been round the hoop and the energy
//! error has seen its whole range), `R` stays on `SO(3)`. `q ← q + d` is compensated (Kahan),
//! and the angle `α` winds up to ~−1800 in this run without costing the conservation of `L·e₃`.
//! Its order is measured in `rigid_body_orders.rs`.

use tumble_integrators::rigid::{CoupledLgvi, CoupledMonitor, CoupledState, coupled_energy};
use tumble_integrators::verification::fit_power_law;
use tumble_integrators::{Driver, Flow, Observer};

use crate::rigid_support::*;

const STEPS: u64 = 1 << 17;
const H: f64 = 0.005;

struct Blocks<'a> {
    monitor: CoupledMonitor<'a, BeadOnHoop, 1>,
    model: &'a BeadOnHoop,
    e0: f64,
    step: u64,
    block_start: u64,
    current: f64,
    ns: Vec<f64>,
    maxima: Vec<f64>,
}

impl Observer<CoupledState<1>> for Blocks<'_> {
    fn observe(&mut self, t: f64, s: &CoupledState<1>) -> Flow {
        self.monitor.observe(t, s);
        let err = ((coupled_energy(self.model, s).unwrap() - self.e0) / self.e0).abs();
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

#[test]
fn coupled_lgvi_conserves_vertical_momentum_and_bounds_energy_on_the_bead_on_a_hoop() {
    let model = BeadOnHoop::standard();
    let s0 = hoop_initial(&model);
    let mut obs = Blocks {
        monitor: CoupledMonitor::new(&model),
        model: &model,
        e0: coupled_energy(&model, &s0).unwrap(),
        step: 0,
        block_start: 1 << 10,
        current: 0.0,
        ns: vec![],
        maxima: vec![],
    };
    let mut s = s0;
    let report = Driver::new(0.0, STEPS as f64 * H)
        .unwrap()
        .run_fixed(
            &mut CoupledLgvi::<1>::default(),
            &model,
            &mut s,
            H,
            &mut obs,
        )
        .unwrap();
    assert_eq!(report.steps, STEPS);
    assert!(obs.monitor.failure().is_none());
    let d = obs.monitor.deviations();
    let drift = fit_power_law(&obs.ns, &obs.maxima);
    let maxima: Vec<String> = obs.maxima.iter().map(|m| format!("{m:.2e}")).collect();
    let l0 = s0.spatial_momentum().norm();
    eprintln!(
        "coupled lgvi, bead on a hoop, {STEPS} steps of h = {H}: max |ΔL·e₃|/|L₀| = {:.2e}, \
         max ‖RᵀR − 𝟙‖ = {:.2e}, max |ΔH|/H = {:.3e}, per-block maxima [{}], exponent {drift:.3}; \
         (not conserved: max |ΔL|/|L₀| = {:.2e})",
        d.vertical_momentum / l0,
        d.orthogonality,
        d.energy_relative,
        maxima.join(" "),
        d.spatial_momentum / l0,
    );
    let bound = 10.0 * f64::EPSILON * (STEPS as f64).sqrt();
    assert!(
        d.vertical_momentum / l0 < bound,
        "L·e₃ drift {:e}",
        d.vertical_momentum / l0
    );
    assert!(d.orthogonality < bound, "defect {:e}", d.orthogonality);
    assert!(
        d.energy_relative < 1e-3,
        "energy error {:e}",
        d.energy_relative
    );
    assert!(drift.abs() < 0.05, "energy drift exponent {drift}");
}
