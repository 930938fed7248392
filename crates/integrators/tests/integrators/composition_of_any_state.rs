//! Compositions accept any base stepper of any state type: a Lie-group Störmer–Verlet step
//! for the pendulum on the circle, with state (rotation in SO(2), momentum) — not a vector
//! space — composes to order 4 (Yoshida) and 6 (Kahan–Li), measured by the shared harness.

use nalgebra::Rotation2;
use tumble_integrators::tables::composition::{KAHAN_LI6, YOSHIDA4};
use tumble_integrators::verification::{OrderStudy, Pendulum};
use tumble_integrators::{Composition, Driver, Error, NoObserver, State, Stepper};

/// Pendulum on the circle: orientation `R ∈ SO(2)` (angle from the bottom), momentum `p`.
#[derive(Debug, Clone, Copy)]
struct CircleState {
    r: Rotation2<f64>,
    p: f64,
}

impl State for CircleState {
    fn is_finite(&self) -> bool {
        self.r.angle().is_finite() && self.p.is_finite()
    }
    fn to_vec(&self) -> Vec<f64> {
        vec![self.r.angle(), self.p]
    }
}

/// The pendulum `H = p²/2 − cos θ` as a problem on SO(2).
struct CirclePendulum;

/// Lie-group Störmer–Verlet: half kick, exact rotation `R ← R exp(h p)`, half kick.
struct LieVerlet;

impl Stepper<CirclePendulum> for LieVerlet {
    type State = CircleState;
    fn step(
        &mut self,
        _: &CirclePendulum,
        _t: f64,
        s: &mut CircleState,
        h: f64,
    ) -> Result<(), Error> {
        s.p -= 0.5 * h * s.r.angle().sin();
        s.r *= Rotation2::new(h * s.p);
        s.p -= 0.5 * h * s.r.angle().sin();
        Ok(())
    }
}

fn error(
    table: &'static tumble_integrators::tables::CompositionTable,
    h: f64,
) -> Result<f64, Error> {
    let k = 0.9;
    let t_end = 6.0;
    let y0 = Pendulum::initial(k);
    let mut s = CircleState {
        r: Rotation2::new(y0[0]),
        p: y0[1],
    };
    let mut st = Composition::new(table, LieVerlet);
    Driver::new(0.0, t_end)?.run_fixed(&mut st, &CirclePendulum, &mut s, h, &mut NoObserver)?;
    let exact = Pendulum::exact(k, t_end)?;
    let dq = (s.r.angle() - exact[0] + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    Ok(dq.abs().max((s.p - exact[1]).abs()))
}

#[test]
fn compositions_of_a_lie_group_step_reach_their_order() {
    for (table, h0) in [(&YOSHIDA4, 6.0 / 32.0), (&KAHAN_LI6, 6.0 / 16.0)] {
        let fit = OrderStudy::new(h0, 5)
            .on_span(6.0)
            .run(|h| error(table, h))
            .unwrap();
        eprintln!("{} on SO(2): observed order {:.3}", table.name, fit.slope);
        fit.check(f64::from(table.order), 0.3).unwrap();
    }
}

/// Strang splitting of the rigid body into three exact rotations, composed to order 6 and 8.
#[test]
fn compositions_of_strang_splitting_reach_their_order_on_the_rigid_body() {
    use nalgebra::SVector;
    use tumble_integrators::tables::composition::{KAHAN_LI8, YOSHIDA6};
    use tumble_integrators::verification::{RigidBodyEuler, RigidBodySplit, max_abs_diff};
    use tumble_integrators::{Splitting, SplittingStepper, gauss12};
    type V3 = SVector<f64, 3>;
    let t_end = 5.0;
    let mut exact = V3::from(RigidBodyEuler::INITIAL);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_fixed(
            &mut gauss12().stepper(&exact),
            &RigidBodyEuler::default(),
            &mut exact,
            t_end / 1000.0,
            &mut NoObserver,
        )
        .unwrap();
    for (table, n0) in [(&YOSHIDA6, 20.0), (&KAHAN_LI8, 10.0)] {
        let fit = OrderStudy::new(t_end / n0, 4)
            .on_span(t_end)
            .run(|h| {
                let mut y = V3::from(RigidBodyEuler::INITIAL);
                let mut st =
                    Composition::new(table, SplittingStepper::<V3>::new(Splitting::Strang));
                Driver::new(0.0, t_end)?.run_fixed(
                    &mut st,
                    &RigidBodySplit,
                    &mut y,
                    h,
                    &mut NoObserver,
                )?;
                Ok(max_abs_diff(y.as_slice(), exact.as_slice()))
            })
            .unwrap();
        eprintln!(
            "{} of Strang on the rigid body: observed order {:.3}",
            table.name, fit.slope
        );
        fit.check(f64::from(table.order), 0.3).unwrap();
    }
}
