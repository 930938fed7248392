//! The exact free-rigid-body flow against Gauss–Legendre with s = 6 stages (order 12,
//! `gauss12`) at a small step, over 100 time units, for every
//! case of the solution: each side of the separatrix, on it, symmetric, nearly symmetric,
//! spherical, spinning about a principal axis, and a body whose inertia is not diagonal.
//! Also: invariants to round-off, the group property, and time reversal.

use nalgebra::{Matrix3, Rotation3, SVector, Vector3};
use tumble_integrators::rigid::FreeRigidBody;
use tumble_integrators::{Driver, FnOde, NoObserver, gauss12};
use tumble_kinematics::so3::{exp, hat};

type Y = SVector<f64, 12>;

fn pack(r: &Rotation3<f64>, m: &Vector3<f64>) -> Y {
    let mut y = Y::zeros();
    y.fixed_rows_mut::<9>(0)
        .copy_from_slice(r.matrix().as_slice());
    y.fixed_rows_mut::<3>(9).copy_from(m);
    y
}

fn unpack(y: &Y) -> (Matrix3<f64>, Vector3<f64>) {
    (
        Matrix3::from_column_slice(&y.as_slice()[..9]),
        Vector3::from_column_slice(&y.as_slice()[9..]),
    )
}

/// Euler's equations with the orientation, integrated by Gauss–Legendre of order 12 at step h.
fn reference(
    body: &FreeRigidBody,
    r0: &Rotation3<f64>,
    m0: &Vector3<f64>,
    t: f64,
    h: f64,
) -> (Matrix3<f64>, Vector3<f64>) {
    let problem = FnOde(|_t: f64, y: &Y, dy: &mut Y| {
        let (r, m) = unpack(y);
        let w = body.omega(&m);
        let rd = r * hat(&w);
        dy.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
        dy.fixed_rows_mut::<3>(9).copy_from(&m.cross(&w));
    });
    let mut y = pack(r0, m0);
    let mut st = gauss12().stepper(&y);
    Driver::new(0.0, t)
        .unwrap()
        .run_fixed(&mut st, &problem, &mut y, h, &mut NoObserver)
        .unwrap();
    unpack(&y)
}

fn r0() -> Rotation3<f64> {
    exp(&Vector3::new(0.3, -0.2, 0.9))
}

/// Relative difference of the exact flow and the reference at t (momentum relative to |m|).
fn compare(body: &FreeRigidBody, m0: Vector3<f64>, t: f64, h: f64) -> (f64, f64) {
    let flow = body.flow(&r0(), &m0).unwrap();
    let (r, m) = flow.at(t);
    let (rr, mr) = reference(body, &r0(), &m0, t, h);
    ((m - mr).norm() / m0.norm(), (r.matrix() - rr).amax())
}

fn assert_agrees(name: &str, body: FreeRigidBody, m0: Vector3<f64>, t: f64) {
    let (em, er) = compare(&body, m0, t, 0.01);
    eprintln!("{name}: |Δm|/|m| = {em:.2e}, max |ΔR| = {er:.2e} at t = {t}");
    assert!(em < 1e-12 && er < 1e-12, "{name}: {em:e} {er:e}");
}

fn moments(a: f64, b: f64, c: f64) -> FreeRigidBody {
    FreeRigidBody::from_principal_moments(Vector3::new(a, b, c)).unwrap()
}

#[test]
fn reference_integration_is_converged() {
    // The reference itself: order-12 Gauss at h = 0.01 and 0.005 agree to round-off.
    let body = moments(1.0, 2.0, 3.0);
    let m0 = Vector3::new(0.2, 0.3, 1.0);
    let (r1, m1) = reference(&body, &r0(), &m0, 100.0, 0.01);
    let (r2, m2) = reference(&body, &r0(), &m0, 100.0, 0.005);
    assert!((m1 - m2).norm() < 2e-13 && (r1 - r2).amax() < 2e-13);
}

#[test]
fn exact_flow_circulating_about_the_axis_of_largest_moment() {
    assert_agrees(
        "I=(1,2,3), near e3",
        moments(1.0, 2.0, 3.0),
        Vector3::new(0.2, 0.3, 1.0),
        100.0,
    );
    assert_agrees(
        "I=(1,2,3), near e3, signs",
        moments(1.0, 2.0, 3.0),
        Vector3::new(-0.4, 0.3, -1.0),
        100.0,
    );
}

#[test]
fn exact_flow_circulating_about_the_axis_of_smallest_moment() {
    assert_agrees(
        "I=(1,2,3), near e1",
        moments(1.0, 2.0, 3.0),
        Vector3::new(1.0, 0.3, 0.2),
        100.0,
    );
    assert_agrees(
        "I=(1,2,3), near e1, signs",
        moments(1.0, 2.0, 3.0),
        Vector3::new(-1.0, -0.5, 0.3),
        100.0,
    );
}

#[test]
fn exact_flow_close_to_the_separatrix_on_both_sides() {
    // M² − 2E I₂ = m₃²/3 − m₁² changes sign at m₃ = √3 m₁.
    for eps in [1e-3, -1e-3] {
        let m0 = Vector3::new(1.0, 0.5, 3f64.sqrt() * (1.0 + eps));
        assert_agrees(
            &format!("I=(1,2,3), separatrix {eps:+e}"),
            moments(1.0, 2.0, 3.0),
            m0,
            100.0,
        );
    }
}

#[test]
fn exact_flow_on_the_separatrix() {
    // m₃ = √3 m₁ with I = (1, 2, 3) lies on the separatrix to rounding, and the solution
    // treats it as on it (k = 1, hyperbolic functions): the
    // flow then follows the heteroclinic orbit towards ±e₂. The motion is unstable
    // (perturbations grow like e^{λt}, λ = a₃√((b₁−b₃)(b₂−b₃))), so any reference integration
    // leaves the orbit after ~ln(1/ε)/λ; with |m| small λ is small and the whole window of 100
    // time units is resolved.
    let m0 = Vector3::new(1.0, 0.5, 3f64.sqrt()) * 0.05;
    assert_agrees(
        "I=(1,2,3), on the separatrix",
        moments(1.0, 2.0, 3.0),
        m0,
        100.0,
    );
}

#[test]
fn exact_flow_of_symmetric_nearly_symmetric_and_spherical_bodies() {
    assert_agrees(
        "symmetric I=(2,2,3)",
        moments(2.0, 2.0, 3.0),
        Vector3::new(0.2, 0.3, 1.0),
        100.0,
    );
    assert_agrees(
        "symmetric I=(1,3,3)",
        moments(1.0, 3.0, 3.0),
        Vector3::new(0.2, 0.3, 1.0),
        100.0,
    );
    assert_agrees(
        "nearly symmetric I=(2,2+1e-6,3)",
        moments(2.0, 2.0 + 1e-6, 3.0),
        Vector3::new(0.2, 0.3, 1.0),
        100.0,
    );
    assert_agrees(
        "sphere",
        moments(2.0, 2.0, 2.0),
        Vector3::new(0.2, 0.3, 1.0),
        100.0,
    );
}

#[test]
fn exact_flow_spinning_about_a_principal_axis() {
    for axis in 0..3 {
        let mut m0 = Vector3::zeros();
        m0[axis] = 1.5;
        assert_agrees(
            &format!("spin about e{}", axis + 1),
            moments(1.0, 2.0, 3.0),
            m0,
            100.0,
        );
    }
}

#[test]
fn exact_flow_of_a_body_with_non_diagonal_inertia() {
    let q = exp(&Vector3::new(0.4, 1.1, -0.3));
    let j =
        q.matrix() * Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)) * q.matrix().transpose();
    let body = FreeRigidBody::from_inertia(&j).unwrap();
    assert_agrees(
        "rotated I=(1,2,3)",
        body,
        Vector3::new(0.7, -0.3, 1.0),
        100.0,
    );
}

#[test]
fn exact_flow_conserves_its_invariants_and_is_a_group() {
    let body = moments(1.0, 2.0, 3.0);
    let m0 = Vector3::new(0.4, -0.8, 0.6);
    let flow = body.flow(&r0(), &m0).unwrap();
    let (e0, l) = (body.energy(&m0), r0() * m0);
    for k in 0..200 {
        let t = k as f64 * 0.731;
        let (r, m) = flow.at(t);
        assert!(((m.norm() - m0.norm()) / m0.norm()).abs() < 4e-15);
        assert!(((body.energy(&m) - e0) / e0).abs() < 1e-14);
        assert!((r * m - l).norm() < 1e-14 * l.norm());
        assert!((r.matrix().transpose() * r.matrix() - Matrix3::identity()).norm() < 1e-14);
    }
    // φ_{s+t} = φ_t ∘ φ_s, and φ_{−t} ∘ φ_t = id.
    let (rs, ms) = flow.at(3.3);
    let (rst, mst) = flow.at(3.3 + 17.9);
    let (r2, m2) = body.flow(&rs, &ms).unwrap().at(17.9);
    assert!((m2 - mst).norm() < 1e-13 && (r2.matrix() - rst.matrix()).amax() < 1e-13);
    let (rb, mb) = body.flow(&rst, &mst).unwrap().at(-(3.3 + 17.9));
    assert!((mb - m0).norm() < 1e-13 && (rb.matrix() - r0().matrix()).amax() < 1e-13);
}

#[test]
fn invalid_bodies_and_states_are_errors() {
    assert!(FreeRigidBody::from_principal_moments(Vector3::new(1.0, 1.0, 3.0)).is_err());
    assert!(FreeRigidBody::from_principal_moments(Vector3::new(-1.0, 2.0, 2.0)).is_err());
    assert!(FreeRigidBody::from_principal_moments(Vector3::new(f64::NAN, 2.0, 2.0)).is_err());
    let body = moments(1.0, 2.0, 3.0);
    assert!(
        body.flow(&r0(), &Vector3::new(f64::INFINITY, 0.0, 0.0))
            .is_err()
    );
}

#[test]
fn momentum_period_returns_the_body_momentum_to_its_start() {
    let body = moments(1.0, 2.0, 3.0);
    for m0 in [
        Vector3::new(0.2, 0.3, 1.0),
        Vector3::new(1.0, 0.3, 0.2),
        Vector3::new(1.0, 0.5, 1.8),
    ] {
        let flow = body.flow(&r0(), &m0).unwrap();
        let period = flow
            .momentum_period()
            .expect("asymmetric off the separatrix");
        let (_, m) = flow.at(period);
        assert!((m - m0).norm() < 1e-13 * m0.norm(), "{m} vs {m0}");
        // And not earlier: at half the period m differs.
        let (_, m_half) = flow.at(0.5 * period);
        assert!((m_half - m0).norm() > 1e-3 * m0.norm());
    }
    let sym = moments(2.0, 2.0, 3.0)
        .flow(&r0(), &Vector3::new(0.2, 0.3, 1.0))
        .unwrap();
    let (_, m) = sym.at(sym.momentum_period().unwrap());
    assert!((m - Vector3::new(0.2, 0.3, 1.0)).norm() < 1e-14);
    assert!(
        moments(2.0, 2.0, 2.0)
            .flow(&r0(), &Vector3::z())
            .unwrap()
            .momentum_period()
            .is_none()
    );
    assert!(
        body.flow(&r0(), &Vector3::new(0.0, 0.0, 1.0))
            .unwrap()
            .momentum_period()
            .is_none()
    );
}

#[test]
fn exact_flow_of_a_nearly_symmetric_flat_body_keeps_its_digits() {
    // 1 : 1000 : 1001 — inverse-moment differences and 1 − I₂/I₃ by subtraction lose three to
    // six digits (the flow then differed from the reference by 9.7e-11); written as
    // (Iⱼ − Iᵢ)/(IᵢIⱼ) it agrees to the reference's own accuracy (its h/2 self-check: ~2e-12).
    let body = moments(1.0, 1000.0, 1001.0);
    let m0 = Vector3::new(0.6, 800.0, 600.0);
    let (em, er) = compare(&body, m0, 10.0, 0.005);
    eprintln!("flat body 1:1000:1001: |Δm|/|m| = {em:.2e}, max |ΔR| = {er:.2e}");
    assert!(em < 1e-11 && er < 1e-11, "{em:e} {er:e}");
}
