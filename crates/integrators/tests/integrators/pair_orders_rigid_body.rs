//! Observed orders of Verner's 6(5) and 9(8) pairs at fixed steps on Hairer's rigid-body
//! problem (`t ∈ [0, 20]`) and its forced version (`t ∈ [0, 10]`), against Gauss–Legendre of
//! order 12 at 4000 steps (itself within 1e-14 of 2000 steps), measured by the shared
//! harness (`verification::OrderStudy`: fit above the 1e-13 floor, at least three points).
//!
//! Verner's "most efficient" pairs minimise their principal error coefficients, so the next
//! order's terms dominate over much of the `f64` range. For the 6(5) pair the Euclidean norm
//! of the order-7 error coefficients (elementary weights minus `1/γ` over the 48 trees of
//! order 7) is 2.6e-6 against 9.3e-4 for order 8, a factor 355 (computed at 50 digits from
//! `tools/rk_pairs_data.py`); on the rigid body the global error reaches the round-off floor
//! (2e-14 … 5e-14 for this pair) before the order-6 term takes over, and the observed slope
//! is 6.6 … 7.0. Order 6 itself is observed on `y' = 7t⁶`, where every error term but the
//! order-7 quadrature defect `Σ bᵢcᵢ⁶ − 1/7 = −8.1e-7` vanishes.

use nalgebra::SVector;
use tumble_integrators::verification::{OrderFit, OrderStudy, RigidBodyEuler, max_abs_diff};
use tumble_integrators::{
    Driver, Error, ExplicitRungeKutta, NoObserver, Ode, VectorState, gauss12,
};

type V3 = SVector<f64, 3>;

fn reference(problem: &RigidBodyEuler, t_end: f64, steps: f64) -> V3 {
    let mut y = V3::from(RigidBodyEuler::INITIAL);
    let mut st = gauss12().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(&mut st, problem, &mut y, t_end / steps, &mut NoObserver)
        .unwrap();
    y
}

fn fixed<const S: usize, P: Ode<Y>, Y: VectorState>(
    method: ExplicitRungeKutta<S>,
    problem: &P,
    y0: Y,
    t_end: f64,
    h: f64,
) -> Result<Y, Error> {
    let mut y = y0;
    let mut st = method.stepper(&y);
    Driver::new(0.0, t_end)?.run_fixed(&mut st, problem, &mut y, h, &mut NoObserver)?;
    Ok(y)
}

/// Max-norm global error of `method` on the (forced) rigid body at step `h`.
fn rigid_body_study<const S: usize>(
    method: ExplicitRungeKutta<S>,
    forced: bool,
    study: OrderStudy,
) -> OrderFit {
    let problem = RigidBodyEuler { forced };
    let t_end = if forced { 10.0 } else { 20.0 };
    let exact = reference(&problem, t_end, 4000.0);
    let check = reference(&problem, t_end, 2000.0);
    assert!(max_abs_diff(exact.as_slice(), check.as_slice()) < 1e-14);
    let y0 = V3::from(RigidBodyEuler::INITIAL);
    let fit = study
        .on_span(t_end)
        .run(|h| {
            let y = fixed(method, &problem, y0, t_end, h)?;
            Ok(max_abs_diff(y.as_slice(), exact.as_slice()))
        })
        .unwrap();
    let points: Vec<String> = fit
        .points
        .iter()
        .map(|(h, e)| format!("N={}:{e:.2e}", (t_end / h).round()))
        .collect();
    eprintln!(
        "forced={forced}: slope {:.3} on {} points [{}]",
        fit.slope,
        fit.used_points(),
        points.join(" ")
    );
    fit
}

/// Verner 9(8) on both problems: steps `T/50 … T/141` in ratios `√2` keep the global error
/// between 8e-9 and 6e-13 on the free body (slope 8.78 measured) and 8e-10 … 1.3e-12 on the
/// forced one, where `T/141` is already at 6e-14, below the floor (slope 9.23 on three
/// points); `T/25` is pre-asymptotic (slope 10 … 11 from there to `T/50`).
#[test]
fn vern9_has_order_nine_on_the_rigid_body_and_the_forced_rigid_body() {
    for forced in [false, true] {
        let fit = rigid_body_study(
            ExplicitRungeKutta::vern9(),
            forced,
            OrderStudy::new(if forced { 10.0 } else { 20.0 } / 50.0, 4).with_ratio(2f64.sqrt()),
        );
        fit.check(9.0, 0.3)
            .unwrap_or_else(|e| panic!("forced={forced}: {e}"));
    }
}

/// Verner 6(5) on both problems at `T/100 … T/400`: the slope is measured between 6 and 7
/// (6.6 … 7.0, see the module doc); asserted is convergence at no less than order 6 and no
/// more than the order-7 term that dominates at these steps.
#[test]
fn vern6_converges_at_order_six_to_seven_on_the_rigid_body_where_its_order_seven_terms_dominate() {
    for forced in [false, true] {
        let t_end = if forced { 10.0 } else { 20.0 };
        let fit = rigid_body_study(
            ExplicitRungeKutta::vern6(),
            forced,
            OrderStudy::new(t_end / 100.0, 3),
        );
        assert_eq!(fit.used_points(), 3, "forced={forced}: {:?}", fit.points);
        assert!(
            (6.0 - 0.3..=7.0 + 0.3).contains(&fit.slope),
            "forced={forced}: slope {}",
            fit.slope
        );
    }
}

/// `y' = 7t⁶`, `y(0) = 0` on `[0, 1]`: a step from `tₙ` integrates every power `t^k`,
/// `k < 6`, exactly (quadrature conditions up to order 6), and misses `t⁶` by
/// `7h⁷ (Σ bᵢcᵢ⁶ − 1/7)`; no higher term exists, so the global error is `C h⁶` from the
/// largest step on.
struct Septic;

impl Ode<SVector<f64, 1>> for Septic {
    fn rhs(&self, t: f64, _y: &SVector<f64, 1>, dy: &mut SVector<f64, 1>) {
        dy[0] = 7.0 * t.powi(6);
    }
}

#[test]
fn vern6_has_order_six_where_its_order_seven_quadrature_defect_is_alone() {
    let fit = OrderStudy::new(1.0, 5)
        .on_span(1.0)
        .run(|h| {
            let y = fixed(
                ExplicitRungeKutta::vern6(),
                &Septic,
                SVector::<f64, 1>::zeros(),
                1.0,
                h,
            )?;
            Ok((y[0] - 1.0).abs())
        })
        .unwrap();
    eprintln!(
        "vern6 on y' = 7t^6: slope {:.3} {:?}",
        fit.slope, fit.points
    );
    fit.check(6.0, 0.3).unwrap();
}
