//! `taylor-dd`, the Taylor method in double-double arithmetic, against truths computed in
//! double-double here: the closed-form motion of a symmetric free body (final state to below
//! `1e-25`), and the heavy top's energy and vertical angular momentum (conserved to below
//! `1e-25`); the driver's state is the carried one rounded, at the driver's times.

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::registry::{self, Stepping};
use tumble_integrators::rigid::{FreeRigidBody, HeavyTop, RigidBody, TaylorHeavyTop};
use tumble_integrators::taylor::{DoubleDouble, DoubleDoubleTaylorStepper, SeriesScalar};
use tumble_integrators::{Driver, NoObserver, Order, ProblemKind, Tolerances};

type Y = SVector<f64, 12>;
type Dd = DoubleDouble;

fn dd(x: f64) -> Dd {
    Dd::from_f64(x)
}

/// `sin x`, `cos x` in double-double for `|x| ≤ 4`: the Taylor series to the term `x⁶¹/61!`
/// (below `4⁶¹/61! ≈ 1e-47`), summed from the small end.
fn sin_cos(x: Dd) -> (Dd, Dd) {
    assert!(x.hi().abs() <= 4.0, "reduce the angle first: {x:?}");
    let mut terms = [dd(0.0); 62];
    terms[0] = dd(1.0);
    for k in 1..62 {
        terms[k] = (terms[k - 1] * x).quotient(dd(k as f64));
    }
    let (mut s, mut c) = (dd(0.0), dd(0.0));
    for k in (0..62).rev() {
        let sign = if (k / 2) % 2 == 0 { 1.0 } else { -1.0 };
        if k % 2 == 1 {
            s += terms[k] * dd(sign);
        } else {
            c += terms[k] * dd(sign);
        }
    }
    (s, c)
}

/// `x` reduced by whole turns to `[−π, π]`, with 2π in double-double.
fn reduce(x: Dd) -> Dd {
    let turns = (x.hi() / std::f64::consts::TAU).round();
    x - twofloat::consts::TAU * dd(turns)
}

/// `√x` by one Newton step from the `f64` root (quadratic: ~1e-32 relative).
fn sqrt(x: Dd) -> Dd {
    let s = dd(x.hi().sqrt());
    s + (x - s * s).quotient(dd(2.0) * s)
}

type M3 = [[Dd; 3]; 3];

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// The rotation by `angle` about the unit axis `u` (Rodrigues: `1 + sin θ û + (1 − cos θ) û²`).
fn rotation(u: [Dd; 3], angle: Dd) -> M3 {
    let (s, c) = sin_cos(reduce(angle));
    let hat = [
        [dd(0.0), -u[2], u[1]],
        [u[2], dd(0.0), -u[0]],
        [-u[1], u[0], dd(0.0)],
    ];
    let hat2 = mul(&hat, &hat);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let one = if i == j { dd(1.0) } else { dd(0.0) };
            one + s * hat[i][j] + (dd(1.0) - c) * hat2[i][j]
        })
    })
}

/// Runs `taylor-dd` on `system` from `y0` to `t_end` at tolerance `tol`; the driver's final
/// state and the stepper (which carries the state in double-double).
fn run(
    system: &TaylorHeavyTop,
    y0: Y,
    t_end: f64,
    tol: f64,
) -> (Y, DoubleDoubleTaylorStepper<Y>, u64) {
    let mut y = y0;
    let mut stepper = DoubleDoubleTaylorStepper::new(&y);
    let report = Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            system,
            &mut y,
            &Tolerances::new(tol, tol).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.t, t_end);
    (y, stepper, report.steps)
}

fn flat(r: &Matrix3<f64>, m: &Vector3<f64>) -> Y {
    let mut y = Y::zeros();
    y.as_mut_slice()[..9].copy_from_slice(r.as_slice());
    y.as_mut_slice()[9..].copy_from_slice(m.as_slice());
    y
}

/// A symmetric body `J = diag(I₁, I₁, I₃)` turns as `R(t) = exp(t L̂ / I₁) R₀ exp(λ t ê₃)`,
/// `m(t) = exp(−λ t ê₃) m₀`, `λ = (1/I₃ − 1/I₁) m₃`, `L = R₀ m₀` (Landau & Lifshitz, Mechanics,
/// §33; with `Ṙ = R ω̂`, `ω = m/I₁ + λ e₃`): the closed form, evaluated in double-double.
#[test]
fn taylor_dd_reaches_1e_minus_25_on_the_symmetric_free_bodys_closed_form() {
    let (i1, i3) = (1.5, 2.5);
    let body = FreeRigidBody::from_principal_moments(Vector3::new(i1, i1, i3)).unwrap();
    let m0 = Vector3::new(0.3, -0.4, 1.1);
    let t_end = 20.0;
    let (y, stepper, steps) = run(
        &TaylorHeavyTop::free(&body),
        flat(&Matrix3::identity(), &m0),
        t_end,
        1e-31,
    );
    // The closed form at t_end, R₀ = 1, L = m₀.
    let m = [dd(m0.x), dd(m0.y), dd(m0.z)];
    let l = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    let axis = [m[0].quotient(l), m[1].quotient(l), m[2].quotient(l)];
    let t = dd(t_end);
    let lambda = (dd(1.0).quotient(dd(i3)) - dd(1.0).quotient(dd(i1))) * m[2];
    let e3 = [dd(0.0), dd(0.0), dd(1.0)];
    let r = mul(
        &rotation(axis, (t * l).quotient(dd(i1))),
        &rotation(e3, lambda * t),
    );
    let back = rotation(e3, -(lambda * t));
    let m_t: [Dd; 3] =
        std::array::from_fn(|i| back[i][0] * m[0] + back[i][1] * m[1] + back[i][2] * m[2]);
    let mut exact = [dd(0.0); 12];
    for col in 0..3 {
        for row in 0..3 {
            exact[col * 3 + row] = r[row][col];
        }
    }
    exact[9..].copy_from_slice(&m_t);
    let carried = stepper.state();
    let error = (0..12)
        .map(|i| (carried[i] - exact[i]).hi().abs())
        .fold(0.0f64, f64::max);
    assert!(
        error < 1e-25,
        "taylor-dd at tol 1e-31 ends {error:.1e} from the closed form ({steps} steps)"
    );
    // The driver's state is the carried one rounded: within half an ulp of the closed form.
    for i in 0..12 {
        assert_eq!(y[i], carried[i].hi(), "component {i}");
        let e = exact[i].hi();
        assert!(
            (y[i] - e).abs() <= f64::EPSILON * e.abs() + 1e-25,
            "component {i}"
        );
    }
}

/// Simo & Wong's heavy top over 10 s: `H = ½ m·J⁻¹m + w (Rᵀe₃)·ρ` and `L_z = (R m)_z`,
/// evaluated in double-double on the carried state, keep their initial values to below `1e-25`
/// relative; the `f64` Taylor method at its tightest keeps them only to round-off.
#[test]
fn taylor_dd_keeps_the_heavy_tops_energy_and_lz_to_1e_minus_25() {
    let top = HeavyTop::simo_wong();
    let s0 = HeavyTop::simo_wong_initial();
    let y0 = flat(&s0.rotation, &s0.momentum);
    let (_, stepper, _) = run(&TaylorHeavyTop::new(&top), y0, 10.0, 1e-30);
    let j = top.body().inertia();
    let (w, rho) = (top.weight(), top.center());
    let invariants = |x: &[Dd]| {
        // J is diagonal here: ω = m / J.
        let m = [x[9], x[10], x[11]];
        let kinetic = (0..3)
            .map(|i| (m[i] * m[i]).quotient(dd(j[(i, i)])))
            .fold(dd(0.0), |a, b| a + b)
            * dd(0.5);
        // Rᵀe₃ is R's third row: components 2, 5, 8.
        let gamma = [x[2], x[5], x[8]];
        let potential =
            dd(w) * (gamma[0] * dd(rho.x) + gamma[1] * dd(rho.y) + gamma[2] * dd(rho.z));
        let lz = gamma[0] * m[0] + gamma[1] * m[1] + gamma[2] * m[2];
        (kinetic + potential, lz)
    };
    assert_eq!(
        j,
        Matrix3::from_diagonal(&j.diagonal()),
        "the energy above assumes principal axes"
    );
    let start: Vec<Dd> = y0.iter().map(|&v| dd(v)).collect();
    let (h0, lz0) = invariants(&start);
    let (h, lz) = invariants(stepper.state());
    let dh = (h - h0).quotient(h0).hi().abs();
    let dlz = (lz - lz0).quotient(lz0).hi().abs();
    assert!(dh < 1e-25 && dlz < 1e-25, "energy {dh:.1e}, Lz {dlz:.1e}");
}

#[test]
fn taylor_dd_is_registered_for_double_double_taylor_series() {
    let m = registry::find("taylor-dd").unwrap();
    assert!(matches!(m.stepping, Stepping::TaylorDoubleDouble));
    assert_eq!(m.order, Order::Variable);
    assert!(m.properties.adaptive && m.properties.dense_output);
    assert_eq!(m.problems, &[ProblemKind::DoubleDoubleTaylorSeries]);
}
