//! A chosen stepper and a custom observer on the free rigid body: the T-handle's flips.
//!
//! A body spun close to its intermediate principal axis flips over every half period of its
//! body-frame angular momentum (the Dzhanibekov effect). The exact free flow gives that period
//! in closed form, `4K(k)/λ` (Jacobi elliptic functions; Landau & Lifshitz, *Mechanics*, §37),
//! so a flip counter is a check any method can be held to.
//!
//! The observer here counts sign changes of the momentum component along the intermediate
//! axis and tracks the largest error in the energy and in the spatial angular momentum
//! `L = R m` (conserved exactly by the flow; a Lie-group variational integrator keeps it to
//! round-off). The stepper is picked on the command line:
//!
//! ```text
//! cargo run --release --example t_handle_flips -- lgvi8
//! ```
//!
//! `lgvi` (the Lee–Leok–McClamroch integrator, order 2), `lgvi4`, `lgvi8` (its compositions with
//! McLachlan's and Kahan–Li's coefficients), `split4` (principal-axis splitting composed to
//! order 4) or `exact`. It exits non-zero if a check fails.

use std::error::Error;

use nalgebra::Vector3;
use tumble_integrators::rigid::{ExactStepper, FreeRigidBody, Lgvi, RigidBodyState, split4};
use tumble_integrators::tables::composition::{KAHAN_LI8, MCLACHLAN4};
use tumble_integrators::{Composition, Driver, Flow, Observer, Stepper};

/// Counts flips and tracks conserved quantities along a run.
struct FlipCounter<'a> {
    body: &'a FreeRigidBody,
    energy0: f64,
    momentum0: Vector3<f64>,
    last_sign: f64,
    flip_times: Vec<f64>,
    energy_error: f64,
    momentum_error: f64,
    last: Option<(f64, f64)>,
}

impl Observer<RigidBodyState> for FlipCounter<'_> {
    fn observe(&mut self, t: f64, state: &RigidBodyState) -> Flow {
        let m2 = state.momentum[1];
        let sign = m2.signum();
        if sign != self.last_sign {
            // The crossing, by linear interpolation between the two observed steps.
            if let Some((t0, m0)) = self.last {
                self.flip_times.push(t0 + (t - t0) * m0 / (m0 - m2));
            }
            self.last_sign = sign;
        }
        self.last = Some((t, m2));
        let energy = self.body.energy(&state.momentum);
        self.energy_error = self
            .energy_error
            .max(((energy - self.energy0) / self.energy0).abs());
        let drift = (state.spatial_momentum() - self.momentum0).norm() / self.momentum0.norm();
        self.momentum_error = self.momentum_error.max(drift);
        Flow::Continue
    }
}

fn run<St: Stepper<FreeRigidBody, State = RigidBodyState>>(
    mut stepper: St,
    body: &FreeRigidBody,
    state: &mut RigidBodyState,
    t_end: f64,
    h: f64,
    counter: &mut FlipCounter<'_>,
) -> Result<(), tumble_integrators::Error> {
    Driver::new(0.0, t_end)?.run_fixed(&mut stepper, body, state, h, counter)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let method = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "lgvi8".to_owned());
    // A T-handle's principal moments (kg·m²), spun at 10 rad/s about the intermediate axis with
    // a 1 % wobble.
    let body = FreeRigidBody::from_principal_moments(Vector3::new(2.0e-4, 5.0e-4, 6.5e-4))?;
    let omega0 = Vector3::new(0.1, 10.0, 0.0);
    let m0 = body.inertia() * omega0;
    let r0 = nalgebra::Rotation3::identity();
    let flow = body.flow(&r0, &m0)?;
    let half_period = flow
        .momentum_period()
        .ok_or("this spin has no flip period")?
        / 2.0;

    let mut state = RigidBodyState::new(&r0, m0);
    let mut counter = FlipCounter {
        body: &body,
        energy0: body.energy(&m0),
        momentum0: state.spatial_momentum(),
        last_sign: m0[1].signum(),
        flip_times: Vec::new(),
        energy_error: 0.0,
        momentum_error: 0.0,
        last: None,
    };
    let t_end = 10.0 * half_period;
    let h = half_period / 2000.0;
    // The bound on the flip period's relative error at this step (2000 steps per flip): a
    // second-order method is at (h λ)² ≈ 1e-5, the higher orders far below.
    let bound = match method.as_str() {
        "lgvi" => {
            run(Lgvi::default(), &body, &mut state, t_end, h, &mut counter)?;
            1e-4
        }
        "lgvi4" => {
            let stepper = Composition::new(&MCLACHLAN4, Lgvi::default());
            run(stepper, &body, &mut state, t_end, h, &mut counter)?;
            1e-8
        }
        "lgvi8" => {
            let stepper = Composition::new(&KAHAN_LI8, Lgvi::default());
            run(stepper, &body, &mut state, t_end, h, &mut counter)?;
            1e-8
        }
        "split4" => {
            run(split4(), &body, &mut state, t_end, h, &mut counter)?;
            1e-8
        }
        "exact" => {
            run(
                ExactStepper::default(),
                &body,
                &mut state,
                t_end,
                h,
                &mut counter,
            )?;
            1e-8
        }
        other => {
            return Err(
                format!("unknown method `{other}`: lgvi, lgvi4, lgvi8, split4 or exact").into(),
            );
        }
    };

    let flips = &counter.flip_times;
    let measured = (flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64;
    let period_error = (measured - half_period).abs() / half_period;
    let (exact_r, exact_m) = flow.at(t_end);
    let final_error = (state.momentum - exact_m).norm() / m0.norm();
    let rotation_error = (state.rotation3().matrix() - exact_r.matrix()).norm();
    println!("{method}: {} flips in {t_end:.4} s", flips.len());
    println!(
        "  time between flips {measured:.9} s, closed form 2K(k)/λ = {half_period:.9} s, relative difference {period_error:.1e}"
    );
    println!(
        "  at t = {t_end:.4} s: momentum error {final_error:.1e}, rotation error {rotation_error:.1e}"
    );
    println!(
        "  largest relative error of the energy {:.1e}, of the spatial angular momentum {:.1e}",
        counter.energy_error, counter.momentum_error
    );
    if flips.len() < 9 || period_error > bound || counter.momentum_error > 1e-12 {
        return Err("a check failed: flip count, flip period or spatial angular momentum".into());
    }
    Ok(())
}
