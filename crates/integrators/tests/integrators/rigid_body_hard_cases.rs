//! Hard cases for the rigid-body methods, each with the figures it reached in its message:
//!
//! - the T-handle spun about its intermediate axis, 1e-3 away from it (close to the separatrix):
//!   the first flip time of every method against the exact one;
//! - a very flat body, principal moments 1 : 1000 : 1001 (a plate at the triangle-inequality
//!   limit, nearly symmetric): every method against Gauss–Legendre s = 6.

use nalgebra::{Matrix3, Vector3};
use tumble_integrators::registry::{self, build, build::Receive};
use tumble_integrators::rigid::{EulerEquations, FreeRigidBody, GroupState, RigidBodyState};
use tumble_integrators::{ProblemKind, State, Stepper};
use tumble_kinematics::so3::exp;

use crate::rigid_support::*;

/// The standard T-handle of the `dzhanibekov` scene (80 mm crossbar of 20 mm × 20 mm section,
/// 60 mm stem of the same section, unit density): two boxes about their common centre of mass.
/// Moments ≈ (1.97, 3.21, 4.81)·1e-8, ratio 1 : 1.63 : 2.44; the crossbar (body x) is the
/// intermediate axis.
fn t_handle() -> FreeRigidBody {
    let block = |a: f64, b: f64, c: f64| {
        let m = a * b * c;
        let i = Vector3::new(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 12.0);
        (m, i)
    };
    let (mb, ib) = block(0.08, 0.02, 0.02);
    let (ms, is) = block(0.02, 0.02, 0.06);
    let zc = (mb * 0.01 - ms * 0.03) / (mb + ms);
    let shift = mb * (0.01 - zc).powi(2) + ms * (0.03 + zc).powi(2);
    let i = ib + is + Vector3::new(shift, shift, 0.0);
    FreeRigidBody::from_inertia(&Matrix3::from_diagonal(&i)).unwrap()
}

/// First time `mx` of the state changes sign from positive: the step over which it happens is
/// found by stepping, the time within it by bisection on the step size of the method's own
/// step from the state at its start (the method's continuous extension).
fn flip_time<P: ?Sized, St: Stepper<P> + Clone>(
    fresh: &St,
    problem: &P,
    s0: St::State,
    mx: &dyn Fn(&St::State) -> f64,
    h: f64,
    t_max: f64,
) -> f64 {
    let make = || fresh.clone();
    let mut stepper = make();
    let mut s = s0;
    let mut k = 0u64;
    while (k as f64) * h < t_max {
        let t = k as f64 * h;
        let mut next = s.clone();
        stepper.step(problem, t, &mut next, h).unwrap();
        if mx(&next) <= 0.0 {
            let (mut a, mut b) = (0.0, h);
            for _ in 0..60 {
                let c = 0.5 * (a + b);
                let mut y = s.clone();
                make().step(problem, t, &mut y, c).unwrap();
                if mx(&y) > 0.0 {
                    a = c;
                } else {
                    b = c;
                }
            }
            return t + 0.5 * (a + b);
        }
        s = next;
        k += 1;
    }
    f64::NAN
}

/// Runs [`flip_time`] with the stepper it receives.
struct Flip<'a, P: ?Sized, S> {
    problem: &'a P,
    s0: S,
    mx: &'a dyn Fn(&S) -> f64,
    h: f64,
    t_max: f64,
}

impl<P: ?Sized, S: State> Receive<P, S> for Flip<'_, P, S> {
    type Output = f64;
    fn receive<St: Stepper<P, State = S> + Clone>(self, stepper: St) -> f64 {
        flip_time(&stepper, self.problem, self.s0, self.mx, self.h, self.t_max)
    }
}

#[test]
fn t_handle_flip_time_of_every_method_matches_the_exact_one_within_its_error() {
    let body = t_handle();
    let i = body.principal_moments();
    let axis = body.principal_axes().matrix().column(1).into_owned();
    assert_eq!(axis, Vector3::x(), "the crossbar is the intermediate axis");
    // Two turns per second about the crossbar, 1e-3 of it about the other two axes.
    let w0 = 4.0 * std::f64::consts::PI;
    let m0 = Vector3::new(i[1] * w0, i[0] * w0 * 1e-3, i[2] * w0 * 1e-3);
    let s0 = RigidBodyState::new(&exp(&Vector3::new(0.3, -0.2, 0.9)), m0);
    // Exact flip: scan, then bisect on the closed form.
    let flow = body.flow(&s0.rotation3(), &m0).unwrap();
    let mut t = 0.0;
    while flow.at(t + 1e-3).1.x > 0.0 {
        t += 1e-3;
    }
    let (mut a, mut b) = (t, t + 1e-3);
    for _ in 0..80 {
        let c = 0.5 * (a + b);
        if flow.at(c).1.x > 0.0 {
            a = c;
        } else {
            b = c;
        }
    }
    let exact = 0.5 * (a + b);
    let mx = |s: &RigidBodyState| s.momentum.x;
    let gx = |g: &GroupState<3>| g.vector.x;
    let field = EulerEquations(&body);
    let g0 = GroupState::from(s0);
    let t_max = 2.0 * exact;
    let flip = |name: &str, h: f64| -> f64 {
        let method = registry::find(name).unwrap();
        let on_body = Flip {
            problem: &body,
            s0,
            mx: &mx,
            h,
            t_max,
        };
        match method.problems[0] {
            ProblemKind::LieVectorField => {
                let on_field = Flip {
                    problem: &field,
                    s0: g0,
                    mx: &gx,
                    h,
                    t_max,
                };
                build::lie_vector_field::<_, _, 3>(method, on_field)
            }
            ProblemKind::FreeRigidBody => build::free_rigid_body(method, on_body),
            _ => build::rigid_body(method, on_body),
        }
        .unwrap()
    };
    // The step: 1/40 of a turn.
    let h = 0.5 / 20.0;
    let mut lines = vec![format!("exact first flip at t = {exact:.12}")];
    let mut failures = vec![];
    for (name, order) in [
        ("lgvi", 2),
        ("dmv", 2),
        ("rkmk4", 4),
        ("cg3", 3),
        ("split2", 2),
        ("split4", 4),
        ("split6", 6),
        ("split8", 8),
        ("exact", 0),
    ] {
        let (t1, t2) = (flip(name, h), flip(name, h / 2.0));
        let err = (t1 - exact).abs();
        // Richardson: the method's own error estimate at h from the runs at h and h/2.
        let estimate = if order == 0 {
            0.0
        } else {
            let r = 2f64.powi(order);
            (t1 - t2).abs() * r / (r - 1.0)
        };
        let floor = 1e-12;
        lines.push(format!(
            "{name:>7}: flip at {t1:.12} (h = {h}), error {err:.2e}, estimated {estimate:.2e}; at h/2 error {:.2e}",
            (t2 - exact).abs()
        ));
        if err > 1.5 * estimate + floor {
            failures.push(format!("{name}: error {err:e}, estimate {estimate:e}"));
        }
    }
    eprintln!("{}", lines.join("\n"));
    assert!(failures.is_empty(), "{failures:#?}\n{}", lines.join("\n"));
}

#[test]
fn very_flat_body_one_to_thousand_every_method_converges_at_its_order() {
    let body = FreeRigidBody::from_principal_moments(Vector3::new(1.0, 1000.0, 1001.0)).unwrap();
    let s0 = RigidBodyState::new(
        &exp(&Vector3::new(0.3, -0.2, 0.9)),
        Vector3::new(0.6, 800.0, 600.0),
    );
    let t_end = 10.0;
    let scale = s0.momentum.norm();
    let reference = gauss_reference(&body, &s0, t_end, 1e-3);
    let check = gauss_reference(&body, &s0, t_end, 5e-4);
    let ref_error = state_error(&reference, &check, scale);
    assert!(ref_error < 1e-11, "{ref_error:e}");
    let exact_error = state_error(&exact_state(&body, &s0, t_end), &reference, scale);
    let mut lines = vec![format!(
        "flat body 1 : 1000 : 1001, t = {t_end}: Gauss s = 6 reference self-check {ref_error:.1e}; \
         the closed-form exact flow differs from it by {exact_error:.1e}"
    )];
    let mut failures = vec![];
    // (method, order, steps over [0, 10]): each in its asymptotic range. split2's error
    // constant grows like |m|²/(I₁I₂) here: O(1) errors until h ≈ 1e-3.
    for (name, order, n) in [
        ("lgvi", 2.0, 800.0),
        ("dmv", 2.0, 800.0),
        ("rkmk4", 4.0, 200.0),
        ("cg3", 3.0, 400.0),
        ("split2", 2.0, 51200.0),
        ("split4", 4.0, 800.0),
        ("split6", 6.0, 200.0),
        ("split8", 8.0, 100.0),
    ] {
        let h = t_end / n;
        let e1 = state_error(
            &solve_free(name, &body, &s0, t_end, h).unwrap(),
            &reference,
            scale,
        );
        let e2 = state_error(
            &solve_free(name, &body, &s0, t_end, h / 2.0).unwrap(),
            &reference,
            scale,
        );
        let p = (e1 / e2).log2();
        lines.push(format!(
            "{name:>7}: {n} steps error {e1:.2e}, {} steps {e2:.2e}, local order {p:.2}",
            2.0 * n
        ));
        if (p - order).abs() > 0.3 {
            failures.push(format!("{name}: local order {p}, nominal {order}"));
        }
    }
    eprintln!("{}", lines.join("\n"));
    assert!(failures.is_empty(), "{failures:#?}\n{}", lines.join("\n"));
    // The exact flow is limited by b₂ − b₃ = 1/1000 − 1/1001 losing six digits; still within
    // 1e-9 here.
    assert!(exact_error < 1e-9, "{exact_error:e}");
}
