//! Every rigid-body method keeps `R` on `SO(3)` to round-off: RKMK4 and Crouch–Grossman (only
//! ever multiply by exponentials) over 2¹⁷ steps, and every method (the LGVI compositions
//! `lgvi4` … `lgvi10` included) over 10⁴ steps; the
//! diagnostics observers report running maxima equal to those computed by hand.

use tumble_integrators::rigid::{
    EulerEquations, GroupState, RigidBody, RigidBodyMonitor, RigidBodyState, cg3, rkmk4,
};
use tumble_integrators::{Flow, FnObserver};

use crate::rigid_support::*;

#[test]
fn rkmk4_and_cg3_stay_on_so3_to_roundoff_over_131072_steps() {
    let body = asymmetric_body();
    let s0 = initial_state();
    let field = EulerEquations(&body);
    let steps = 1u64 << 17;
    let h = 0.05;
    let t_end = steps as f64 * h;
    for name in ["rkmk4", "cg3"] {
        let mut monitor = RigidBodyMonitor::new(&body);
        let g0 = GroupState::<3>::from(s0);
        let _g = if name == "rkmk4" {
            run(&mut rkmk4::<3>(), &field, g0, t_end, h, &mut monitor).unwrap()
        } else {
            run(&mut cg3::<3>(), &field, g0, t_end, h, &mut monitor).unwrap()
        };
        let d = monitor.deviations();
        eprintln!(
            "{name}, {steps} steps of h = {h}: max ‖RᵀR − 𝟙‖ = {:.2e}; (not conserved by the method) \
             max |ΔH|/H = {:.2e}, max |ΔL|/|L| = {:.2e}",
            d.orthogonality,
            d.energy_relative,
            d.spatial_momentum / s0.spatial_momentum().norm()
        );
        // A random walk of one rounding per step: ~ε√n ≈ 8e-14; factor 10 for the constant.
        let bound = 10.0 * f64::EPSILON * (steps as f64).sqrt();
        assert!(
            d.orthogonality < bound,
            "{name}: defect {:e}",
            d.orthogonality
        );
    }
}

#[test]
fn every_rigid_body_method_stays_on_so3_over_ten_thousand_steps() {
    let body = asymmetric_body();
    let s0 = initial_state();
    let steps = 10_000u64;
    let h = 0.05;
    for name in [
        "lgvi",
        "lgvi4",
        "lgvi6",
        "lgvi8",
        "lgvi10",
        "rkmk4",
        "cg3",
        "split2",
        "split4",
        "split6",
        "split8",
        "split-exact2",
        "dmv",
        "exact",
    ] {
        let s = solve_free(name, &body, &s0, steps as f64 * h, h).unwrap();
        let defect = s.orthogonality_defect();
        // A random walk of a few roundings per base step (compositions take `stages` of them).
        let stages = tumble_integrators::registry::find(name).unwrap().stages;
        let bound = 10.0 * f64::EPSILON * (steps as f64 * f64::from(stages)).sqrt();
        eprintln!("{name}: ‖RᵀR − 𝟙‖ = {defect:.2e} after {steps} steps");
        assert!(defect < bound, "{name}: {defect:e}");
    }
}

#[test]
fn monitor_keeps_the_running_maxima_of_every_invariant() {
    let top = asymmetric_top();
    let s0 = initial_state();
    let mut monitor = RigidBodyMonitor::new(&top);
    let _ = run(
        &mut tumble_integrators::rigid::PrincipalAxisSplitting::new(),
        &top,
        s0,
        5.0,
        0.1,
        &mut monitor,
    )
    .unwrap();
    // The same run, with the maxima computed by hand.
    let (e0, l0, c0) = (
        top.hamiltonian(&s0),
        s0.spatial_momentum(),
        s0.momentum.norm(),
    );
    let mut by_hand = [0.0f64; 5];
    let mut count = 0u64;
    let mut observer = FnObserver(|_t: f64, s: &RigidBodyState| {
        by_hand[0] = by_hand[0].max((top.hamiltonian(s) - e0).abs());
        by_hand[1] = by_hand[1].max((s.spatial_momentum() - l0).norm());
        by_hand[2] = by_hand[2].max((s.spatial_momentum().z - l0.z).abs());
        by_hand[3] = by_hand[3].max((s.momentum.norm() - c0).abs());
        by_hand[4] = by_hand[4].max(s.orthogonality_defect());
        count += 1;
        Flow::Continue
    });
    let _ = run(
        &mut tumble_integrators::rigid::PrincipalAxisSplitting::new(),
        &top,
        s0,
        5.0,
        0.1,
        &mut observer,
    )
    .unwrap();
    let d = monitor.deviations();
    assert_eq!(d.observations, count);
    assert_eq!(count, 51);
    assert_eq!(
        [
            d.energy,
            d.spatial_momentum,
            d.vertical_momentum,
            d.casimir,
            d.orthogonality
        ],
        by_hand
    );
    assert_eq!(d.energy_relative, d.energy / e0.abs());
    assert!(d.energy > 0.0 && d.spatial_momentum > 0.0);
    assert_eq!(monitor.initial().unwrap().energy, e0);
}
