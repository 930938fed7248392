//! The free hoop in Euler angles: energy and L_z conserved with gravity, all of L without, and
//! the singularity at θ = 0 reported as an error rather than a NaN.

use nalgebra::{SVector, Vector4};
use tumble_integrators::{Driver, ExplicitRungeKutta, NoObserver, Status, Tolerances};
use tumble_scenarios::scenes::hoop::{FreeHoopEuler, HoopParams};
use tumble_scenarios::{EulerLagrange, LagrangianOde, ModelError};

use crate::support::integrate;

fn model(g: f64) -> LagrangianOde<FreeHoopEuler, 4, 8> {
    let scene = FreeHoopEuler {
        hoop: HoopParams::new(1.0, 0.3, 1.0, g).unwrap(),
    };
    LagrangianOde::new(EulerLagrange::new(scene)).unwrap()
}

fn start() -> SVector<f64, 8> {
    // Standing hoop (θ = π/2) spun about the vertical at 3 rad/s, bead at 40° with a push.
    SVector::<f64, 8>::from([
        0.0,
        std::f64::consts::FRAC_PI_2,
        0.0,
        0.7,
        3.0,
        0.0,
        0.0,
        0.5,
    ])
}

fn energy_and_l(
    m: &LagrangianOde<FreeHoopEuler, 4, 8>,
    y: &SVector<f64, 8>,
) -> (f64, nalgebra::Vector3<f64>) {
    let (q, qd) = LagrangianOde::<FreeHoopEuler, 4, 8>::split(y);
    let e = m.equations().energy(0.0, &q, &qd);
    let l = m.equations().lagrangian().angular_momentum(&q, &qd);
    (e, l)
}

#[test]
fn free_hoop_conserves_energy_and_lz_with_gravity() {
    let m = model(9.81);
    let mut y = start();
    let (e0, l0) = energy_and_l(&m, &y);
    integrate(&m, &mut y, 3.0, 1e-12, &mut []);
    let (e1, l1) = energy_and_l(&m, &y);
    assert!(((e1 - e0) / e0).abs() < 1e-9, "{e0} → {e1}");
    assert!((l1.z - l0.z).abs() < 1e-9 * l0.norm(), "{l0} → {l1}");
    // The hoop has tilted: θ left π/2.
    assert!((y[1] - std::f64::consts::FRAC_PI_2).abs() > 1e-3);
}

#[test]
fn free_hoop_conserves_the_whole_angular_momentum_without_gravity() {
    let m = model(0.0);
    let mut y = start();
    let (_, l0) = energy_and_l(&m, &y);
    integrate(&m, &mut y, 3.0, 1e-12, &mut []);
    let (_, l1) = energy_and_l(&m, &y);
    assert!((l1 - l0).norm() < 1e-9 * l0.norm(), "{l0} → {l1}");
}

#[test]
fn euler_angle_model_reports_its_singularity_at_theta_zero() {
    let m = model(9.81);
    let (q, qd) = (
        Vector4::new(0.0, 0.0, 0.0, 0.3),
        Vector4::new(1.0, 0.0, 0.0, 0.0),
    );
    match m.equations().accelerations(0.0, &q, &qd) {
        Err(ModelError::SingularMassMatrix { condition, .. }) => assert!(condition > 1e10),
        other => panic!("expected a singular mass matrix, got {other:?}"),
    }
    // A hoop falling flat (θ → 0) is stopped at the chart's edge by the event on sin θ, where
    // the model's mass matrix is singular: the run ends there, not in NaNs.
    // Without gravity and with the bead on body x, body y is a principal axis: the hoop turns
    // steadily about it, θ(t) = 0.2 − t, and reaches the edge at t = 0.2.
    let m = model(0.0);
    let mut y = SVector::<f64, 8>::from([0.0, 0.2, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0]);
    let mut stepper = ExplicitRungeKutta::dop853().stepper(&y);
    let mut events = [FreeHoopEuler::chart_edge_event()];
    let report = Driver::new(0.0, 5.0)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &m,
            &mut y,
            &Tolerances::new(1e-10, 1e-10).unwrap(),
            &mut events,
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.status, Status::Terminated(0));
    assert!(
        (report.t - 0.2).abs() < 1e-9,
        "edge reached at t = {}",
        report.t
    );
    assert!(y[1].abs() < 1e-9, "θ at the edge: {}", y[1]);
    let (q, qd) = LagrangianOde::<FreeHoopEuler, 4, 8>::split(&y);
    assert!(matches!(
        m.equations().accelerations(report.t, &q, &qd),
        Err(ModelError::SingularMassMatrix { .. })
    ));
}
