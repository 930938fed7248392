//! The rigid-body problems and their conventions: the sign of the moment of a potential, the
//! automatic derivatives of a coupled model, the registry entries, and typed errors.

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::registry::{Family, Order, find};
use tumble_integrators::rigid::{
    CoupledLgvi, CoupledState, CoupledVectorField, Dmv, HeavyTop, Lgvi, RigidBody, RigidBodyState,
    coupled_energy, coupled_potential_gradient, coupled_torque, coupled_velocities,
};
use tumble_integrators::{Error, NoObserver, Stepper};
use tumble_kinematics::so3::exp;

use crate::rigid_support::*;

/// Central difference of `V(R exp(hat η))` in η: `−M` to O(δ²).
fn fd_gradient(v: impl Fn(&Matrix3<f64>) -> f64, r: &Matrix3<f64>) -> Vector3<f64> {
    let d = 1e-6;
    Vector3::from_fn(|i, _| {
        let mut e = Vector3::zeros();
        e[i] = d;
        (v(&(r * exp(&e).matrix())) - v(&(r * exp(&(-e)).matrix()))) / (2.0 * d)
    })
}

#[test]
fn heavy_top_moment_is_minus_the_body_gradient_of_the_potential() {
    // M = w (Rᵀe₃) × ρ = −∂V/∂η: the torque of the weight at the centre of mass.
    let top = asymmetric_top();
    let r = *exp(&Vector3::new(0.7, -0.4, 1.9)).matrix();
    let fd = fd_gradient(|r| top.potential(r), &r);
    let m = top.torque(&r);
    eprintln!("M = {m:?}, −∂V/∂η (finite differences) = {:?}", -fd);
    assert!((m + fd).norm() < 1e-8 * m.norm(), "{m:?} vs {:?}", -fd);
    // The opposite sign convention, w ρ × Rᵀe₃, is exactly −M.
    let up = r.row(2).transpose();
    let other = top.center().cross(&up) * top.weight();
    assert!((other + m).norm() < 1e-14);
}

#[test]
fn heavy_top_energy_is_conserved_by_its_equations_with_this_moment() {
    // Integrating ṁ = m × Ω + M(R) accurately conserves H = ½ m·J⁻¹m + V(R); with the sign of M
    // flipped the energy changes at O(1).
    let top = asymmetric_top();
    let s0 = initial_state();
    let e0 = top.hamiltonian(&s0);
    let s = gauss_reference(&top, &s0, 5.0, 1e-3);
    let rel = ((top.hamiltonian(&s) - e0) / e0).abs();
    eprintln!("heavy top, Gauss s = 6: relative energy change over t = 5: {rel:.2e}");
    assert!(rel < 1e-13, "{rel:e}");

    struct Flipped(HeavyTop);
    impl RigidBody for Flipped {
        fn body(&self) -> &tumble_integrators::rigid::FreeRigidBody {
            self.0.body()
        }
        fn potential(&self, r: &Matrix3<f64>) -> f64 {
            self.0.potential(r)
        }
        fn torque(&self, r: &Matrix3<f64>) -> Vector3<f64> {
            -self.0.torque(r)
        }
    }
    let flipped = Flipped(top);
    let s = gauss_reference(&flipped, &s0, 5.0, 1e-3);
    let rel = ((flipped.hamiltonian(&s) - e0) / e0).abs();
    eprintln!("with the moment's sign flipped: {rel:.2e}");
    assert!(rel > 1e-2, "{rel:e}");
}

#[test]
fn coupled_model_derivatives_match_finite_differences() {
    let model = BeadOnHoop::standard();
    let s = hoop_initial(&model);
    let m = coupled_torque(&model, &s.rotation, &s.q);
    let fd = fd_gradient(
        |r| {
            use tumble_integrators::rigid::CoupledLagrangian;
            model.potential(r, &s.q)
        },
        &s.rotation,
    );
    assert!(
        (m + fd).norm() < 1e-8 * m.norm().max(1.0),
        "{m:?} vs {fd:?}"
    );
    let gq = coupled_potential_gradient(&model, &s.rotation, &s.q);
    let d = 1e-6;
    let v = |a: f64| {
        use tumble_integrators::rigid::CoupledLagrangian;
        model.potential(&s.rotation, &SVector::<f64, 1>::new(a))
    };
    let fdq = (v(s.q[0] + d) - v(s.q[0] - d)) / (2.0 * d);
    assert!((gq[0] - fdq).abs() < 1e-8, "{} vs {fdq}", gq[0]);
    // Legendre transform and its inverse are consistent.
    let (omega, qdot) = coupled_velocities(&model, &s.q, &s.momentum, &s.p).unwrap();
    assert!((omega - Vector3::new(0.5, -1.0, 3.0)).norm() < 1e-14);
    assert!((qdot[0] - 1.5).abs() < 1e-14);
}

#[test]
fn coupled_model_energy_is_conserved_by_its_continuous_equations() {
    let model = BeadOnHoop::standard();
    let s0 = hoop_initial(&model);
    let e0 = coupled_energy(&model, &s0).unwrap();
    let s = hoop_reference(&model, &s0, 2.0, 1e-3);
    let rel = ((coupled_energy(&model, &s).unwrap() - e0) / e0).abs();
    let lz = (s.spatial_momentum().z - s0.spatial_momentum().z).abs();
    eprintln!(
        "bead on a hoop, Gauss s = 6 over t = 2: |ΔH|/H = {rel:.2e}, |ΔL_z| = {lz:.2e} (α: {} → {}, H = {e0})",
        s0.q[0], s.q[0]
    );
    assert!(rel < 1e-13 && lz < 1e-13, "{rel:e} {lz:e}");
}

#[test]
fn registry_lists_every_rigid_body_method_with_its_properties() {
    for (name, order) in [
        ("lgvi", 2),
        ("rkmk4", 4),
        ("cg3", 3),
        ("split2", 2),
        ("split4", 4),
        ("split6", 6),
        ("split8", 8),
        ("split-exact2", 2),
        ("dmv", 2),
    ] {
        let m = find(name).unwrap();
        assert_eq!(m.order, order, "{name}");
        assert!(m.properties.lie_group && !m.properties.exact, "{name}");
        let symplectic = !matches!(name, "rkmk4" | "cg3");
        assert_eq!(m.properties.symplectic, symplectic, "{name}");
        assert_eq!(m.properties.symmetric, symplectic, "{name}");
        assert_eq!(
            m.properties.explicit,
            !matches!(name, "lgvi" | "dmv"),
            "{name}"
        );
    }
    assert_eq!(find("split6").unwrap().stages, 9);
    assert_eq!(find("split8").unwrap().family, Family::Splitting);
    let exact = find("exact").unwrap();
    assert_eq!(exact.order, Order::Exact);
    assert!(exact.order > 100);
    assert!(exact.properties.exact && exact.properties.lie_group);
    assert_eq!(exact.order.to_string(), "exact");
    assert_eq!(find("rkmk4").unwrap().order.to_string(), "4");
}

#[test]
fn non_convergence_is_a_typed_error_with_time_and_state() {
    let body = asymmetric_body();
    let s0 = initial_state();
    let err = Lgvi::new()
        .with_max_iterations(1)
        .step(&body, 1.5, &mut s0.clone(), 0.1)
        .unwrap_err();
    match err {
        Error::NoConvergence { t, h, state, .. } => {
            assert_eq!((t, h), (1.5, 0.1));
            assert_eq!(state.len(), 12);
            assert_eq!(state[9..], *s0.momentum.as_slice());
        }
        other => panic!("{other:?}"),
    }
    let mut dmv = Dmv::new();
    dmv.max_iterations = 1;
    assert!(matches!(
        dmv.step(&body, 0.0, &mut s0.clone(), 0.1),
        Err(Error::NoConvergence { .. })
    ));
    let model = BeadOnHoop::standard();
    let c0 = hoop_initial(&model);
    let err = CoupledLgvi::<1>::new()
        .with_max_iterations(1)
        .step(&model, 2.0, &mut c0.clone(), 0.01)
        .unwrap_err();
    assert!(
        matches!(err, Error::NoConvergence { t, ref state, .. } if t == 2.0 && state.len() == 14),
        "{err:?}"
    );
}

#[test]
fn bad_steps_and_dimensions_are_errors() {
    let body = asymmetric_body();
    let mut s = initial_state();
    assert!(matches!(
        Lgvi::default().step(&body, 0.0, &mut s, f64::NAN),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Lgvi::default().step(&body, 0.0, &mut s, 0.0),
        Err(Error::InvalidParameter { .. })
    ));
    assert_eq!(s, initial_state());
    assert!(matches!(
        CoupledVectorField::<_, 1, 4>::new(BeadOnHoop::standard()),
        Err(Error::DimensionMismatch {
            expected: 5,
            found: 4
        })
    ));
    let c = hoop_initial(&BeadOnHoop::standard());
    assert!(c.to_group::<6>().is_err());
    let back = CoupledState::<1>::from_group(&c.to_group::<5>().unwrap()).unwrap();
    assert_eq!(back, c);
    // A non-finite state is reported by the driver with the state before the step.
    let mut bad = RigidBodyState {
        momentum: Vector3::new(f64::NAN, 0.0, 1.0),
        ..initial_state()
    };
    let err = run(&mut Lgvi::default(), &body, bad, 1.0, 0.1, &mut NoObserver).unwrap_err();
    assert!(
        matches!(
            err,
            Error::NoConvergence { .. } | Error::NonFinite { .. } | Error::SingularMatrix { .. }
        ),
        "{err:?}"
    );
    bad.momentum = Vector3::new(1.0, 0.0, 0.0);
    assert!(run(&mut Lgvi::default(), &body, bad, 1.0, 0.1, &mut NoObserver).is_ok());
}

/// The smallest iteration limit with which one step succeeds: the Newton iterations the step
/// needs to reach round-off (success means the increment fell to 4ε or stagnated below 1e-10).
fn iterations_needed(step: impl Fn(usize) -> bool) -> usize {
    (1..=30).find(|&k| step(k)).unwrap_or(usize::MAX)
}

#[test]
fn lgvi_newton_converges_to_roundoff_in_a_few_iterations() {
    let body = asymmetric_body();
    let top = HeavyTop::simo_wong();
    let model = BeadOnHoop::standard();
    let mut lines = vec![];
    for h in [0.02, 0.2, 1.0] {
        let k = iterations_needed(|k| {
            Lgvi::new()
                .with_max_iterations(k)
                .step(&body, 0.0, &mut initial_state(), h)
                .is_ok()
        });
        lines.push(format!("free body h = {h}: {k}"));
        assert!(k <= 5, "free body h = {h}: {k} iterations");
    }
    for h in [0.001, 0.009] {
        let k = iterations_needed(|k| {
            Lgvi::new()
                .with_max_iterations(k)
                .step(&top, 0.0, &mut HeavyTop::simo_wong_initial(), h)
                .is_ok()
        });
        lines.push(format!("Simo–Wong top h = {h}: {k}"));
        assert!(k <= 4, "Simo–Wong h = {h}: {k} iterations");
    }
    for h in [0.001, 0.02, 0.05] {
        let k = iterations_needed(|k| {
            CoupledLgvi::<1>::new()
                .with_max_iterations(k)
                .step(&model, 0.0, &mut hoop_initial(&model), h)
                .is_ok()
        });
        lines.push(format!("bead on a hoop h = {h}: {k}"));
    }
    eprintln!("Newton iterations per step: {}", lines.join(", "));
    // The coupled step is a simplified Newton (the Jacobian of the first iterate is reused
    // until an iteration shrinks the increment less than fourfold): linear convergence, a few
    // more iterations than Newton's 3–5 (measured 4, 6, 8 at h = 0.001, 0.02, 0.05), each a
    // third of the cost (22.6 → 7.7 µs a step on the free hoop). Asserted: at most twice
    // Newton's bound.
    let coupled: Vec<usize> = lines
        .iter()
        .filter(|l| l.starts_with("bead"))
        .filter_map(|l| l.rsplit(' ').next()?.parse().ok())
        .collect();
    assert_eq!(coupled.len(), 3);
    assert!(coupled.iter().all(|&k| k <= 10), "{lines:?}");
}
