//! `taylor-dd` on models: the double-double functions of order 0 against published constants
//! and identities, the double-double series of the graph against closed forms, Kepler's third
//! law on a model of scalar coordinates, and the heavy top's three invariants on the model
//! with its orientation on SO(3) — every check far below `f64`'s round-off.

use nalgebra::DVector;
use tumble_integrators::taylor::{DoubleDouble, DoubleDoubleTaylorStepper, SeriesScalar};
use tumble_integrators::{Driver, NoObserver, TaylorSystem, Tolerances};
use tumble_model::expr::scalar::{TapeScalar, exp, ln, sin_cos, sqrt};
use tumble_model::expr::tape::Tape;
use tumble_model::expr::taylor::{TaylorPlan, TaylorWork};
use tumble_model::expr::{Fun, Graph};
use tumble_scenarios::Scene;

use crate::support::shipped;

type Dd = DoubleDouble;

fn dd(x: f64) -> Dd {
    Dd::from_f64(x)
}

/// A constant from its first two parts (each the nearest `f64` to what remains; mpmath at
/// 300 bits), to about `1e-33` relative.
fn constant(hi: f64, lo: f64) -> Dd {
    Dd::new_add(hi, lo)
}

const PI: (f64, f64) = (std::f64::consts::PI, 1.224_646_799_147_353_2e-16);
const E: (f64, f64) = (std::f64::consts::E, 1.445_646_891_729_250_2e-16);
const LN_2: (f64, f64) = (std::f64::consts::LN_2, 2.319_046_813_846_299_6e-17);
const SQRT_2: (f64, f64) = (std::f64::consts::SQRT_2, -9.667_293_313_452_913e-17);

/// `|a − b|`, as an `f64`.
fn gap(a: Dd, b: Dd) -> f64 {
    (a - b).hi().abs()
}

/// Relative double-double agreement: `2⁻¹⁰² ≈ 2e-31`, a few units of double-double's
/// round-off (`2⁻¹⁰⁶`).
const CLOSE: f64 = 2e-31;

#[test]
fn double_double_functions_reproduce_published_constants_and_reference_values_to_2e_minus_31() {
    let pi = constant(PI.0, PI.1);
    let checks = [
        ("sqrt 2", sqrt(dd(2.0)), constant(SQRT_2.0, SQRT_2.1)),
        ("exp 1", exp(dd(1.0)), constant(E.0, E.1)),
        ("ln 2", ln(dd(2.0)), constant(LN_2.0, LN_2.1)),
        ("4 atan 1", dd(4.0) * dd(1.0).fun(Fun::Atan), pi),
        ("atan2(0, -1)", dd(0.0).atan2_with(dd(-1.0)), pi),
        ("6 asin 1/2", dd(6.0) * dd(0.5).fun(Fun::Asin), pi),
        ("3 acos 1/2", dd(3.0) * dd(0.5).fun(Fun::Acos), pi),
        ("2 acos 0", dd(2.0) * dd(0.0).fun(Fun::Acos), pi),
        (
            "2^(1/2)",
            dd(2.0).real_pow(dd(0.5)),
            constant(SQRT_2.0, SQRT_2.1),
        ),
        ("e^(-ln 2)", exp(-constant(LN_2.0, LN_2.1)), dd(0.5)),
        (
            "sinh ln 2",
            constant(LN_2.0, LN_2.1).fun(Fun::Sinh),
            dd(0.75),
        ),
        (
            "cosh ln 2",
            constant(LN_2.0, LN_2.1).fun(Fun::Cosh),
            dd(1.25),
        ),
        (
            "tanh ln 2",
            constant(LN_2.0, LN_2.1).fun(Fun::Tanh),
            dd(3.0).quotient(dd(5.0)),
        ),
        ("sin pi/6", sin_cos(pi.quotient(dd(6.0))).0, dd(0.5)),
        ("cos pi/3", sin_cos(pi.quotient(dd(3.0))).1, dd(0.5)),
        ("tan pi/4", pi.quotient(dd(4.0)).fun(Fun::Tan), dd(1.0)),
        // Values of mpmath at 300 bits, first two parts: large and small arguments, where
        // the reductions' third parts and the expm1 forms matter.
        (
            "sin 1e6",
            sin_cos(dd(1e6)).0,
            constant(-0.349_993_502_171_292_94, -1.595_284_880_932_396_8e-17),
        ),
        (
            "exp 700",
            exp(dd(700.0)),
            constant(1.014_232_054_735_004_5e304, 1.666_657_192_073_467_3e287),
        ),
        (
            "ln 1e300",
            ln(dd(1e300)),
            constant(690.775_527_898_213_7, 2.374_766_002_880_024_3e-14),
        ),
        (
            "ln 1e-310 (subnormal)",
            ln(dd(1e-310)),
            constant(-713.801_378_828_154_2, -8.592_254_740_270_771e-15),
        ),
        (
            "ln(1 + 2^-30)",
            ln(dd(1.0 + 2f64.powi(-30))),
            constant(9.313_225_741_817_976e-10, 2.692_645_221_273_596e-28),
        ),
        (
            "asin(1 - 2^-40)",
            dd(1.0 - 2f64.powi(-40)).fun(Fun::Asin),
            constant(1.570_794_978_095_744_2, 7.176_619_355_118_427e-17),
        ),
        (
            "sinh 0.1 (series)",
            dd(0.1).fun(Fun::Sinh),
            constant(0.100_166_750_019_844_03, 3.361_396_128_768_150_4e-18),
        ),
        ("tanh 50", dd(50.0).fun(Fun::Tanh), dd(1.0)),
        ("2 atan inf", dd(2.0) * dd(f64::INFINITY).fun(Fun::Atan), pi),
        ("atan2(-0, -1)", dd(-0.0).atan2_with(dd(-1.0)), -pi),
        ("(-2)^3", dd(-2.0).real_pow(dd(3.0)), dd(-8.0)),
        ("3^-4", dd(3.0).int_pow(-4), dd(1.0).quotient(dd(81.0))),
    ];
    for (name, got, want) in checks {
        let err = gap(got, want) / want.hi().abs();
        println!("{name}: {err:.1e}");
        assert!(err <= CLOSE, "{name}: {got:?} against {want:?}: {err:e}");
    }
    // sin π = 0 to the part of π beyond double-double: |sin(π_dd)| = |π − π_dd| < 1e-32.
    assert!(sin_cos(pi).0.hi().abs() < 1e-32);
    // Outside the domains: NaN (which the Taylor methods report as non-finite), as in f64.
    for (name, v) in [
        ("(-8)^(1/3)", dd(-8.0).real_pow(dd(1.0).quotient(dd(3.0)))),
        ("asin 1.5", dd(1.5).fun(Fun::Asin)),
        ("ln -1", ln(dd(-1.0))),
        ("sqrt -1", sqrt(dd(-1.0))),
        ("sin 1e16", sin_cos(dd(1e16)).0),
    ] {
        assert!(v.hi().is_nan(), "{name}: {v:?}");
    }
}

#[test]
fn double_double_functions_satisfy_their_identities_over_a_wide_range() {
    for i in -40..=40 {
        // Arguments that are not short in binary: i·0.37 + 1/7.
        let x = dd(f64::from(i) * 0.37) + dd(1.0).quotient(dd(7.0));
        let (s, c) = sin_cos(x);
        assert!(gap(s * s + c * c, dd(1.0)) <= CLOSE, "sin² + cos² at {x:?}");
        let y = x.quotient(dd(8.0));
        let (s2, c2) = sin_cos(y + y);
        let (s1, c1) = sin_cos(y);
        assert!(gap(s2, dd(2.0) * s1 * c1) <= CLOSE, "sin 2y at {y:?}");
        assert!(gap(c2, c1 * c1 - s1 * s1) <= CLOSE, "cos 2y at {y:?}");
        let e = exp(x);
        assert!(
            gap(ln(e), x) <= CLOSE * x.hi().abs().max(1.0),
            "ln exp at {x:?}"
        );
        assert!(gap(e * exp(-x), dd(1.0)) <= CLOSE, "exp x exp −x at {x:?}");
        let r = sqrt(x * x + dd(1.0));
        assert!(gap(r * r, x * x + dd(1.0)) <= CLOSE * r.hi() * r.hi());
        // atan2 in every quadrant returns the angle of (cos θ, sin θ).
        let theta = x.quotient(dd(5.0)); // within (−π, π]
        let (st, ct) = sin_cos(theta);
        assert!(gap(st.atan2_with(ct), theta) <= CLOSE, "atan2 at {theta:?}");
        // cosh² − sinh² = 1 across the series branch of sinh (|u| < ½) and its exp branch.
        let u = x.quotient(dd(16.0));
        let (sh, ch) = (u.fun(Fun::Sinh), u.fun(Fun::Cosh));
        assert!(
            gap(ch * ch - sh * sh, dd(1.0)) <= CLOSE * ch.hi() * ch.hi(),
            "at {u:?}"
        );
    }
}

#[test]
fn double_double_series_of_exp_sin_and_a_quotient_are_the_closed_form_coefficients() {
    // exp(t), sin(t), 1/(1 − t) at t₀ = 0: coefficients 1/k!, (−1)^((k−1)/2)/k! for odd k, 1.
    const ORDER: usize = 30;
    let mut g = Graph::default();
    let t = g.input(0);
    let one = g.constant(1.0);
    let e = g.call(Fun::Exp, t);
    let s = g.call(Fun::Sin, t);
    let d = g.sub(one, t);
    let q = g.div(one, d);
    let outputs = [e, s, q];
    let tape = Tape::new(&g, &outputs);
    let plan = TaylorPlan::new(&tape, 1);
    let mut work = TaylorWork::<Dd>::new(&tape, &plan, &[], ORDER);
    for k in 0..=ORDER {
        work.set_input(0, k, dd(if k == 1 { 1.0 } else { 0.0 }));
        work.run_order(&tape, &plan, k);
    }
    let mut factorial = dd(1.0);
    for k in 0..=ORDER {
        if k > 0 {
            factorial *= dd(k as f64);
        }
        let inv = dd(1.0).quotient(factorial);
        let sin_k = if k % 2 == 0 {
            dd(0.0)
        } else if k % 4 == 1 {
            inv
        } else {
            -inv
        };
        for (name, i, want) in [("exp", 0, inv), ("sin", 1, sin_k), ("1/(1−t)", 2, dd(1.0))] {
            let got = work.output(&tape, i, k);
            assert!(
                gap(got, want) <= CLOSE * (k + 1) as f64 * want.hi().abs().max(1e-300),
                "{name}, order {k}: {got:?} against {want:?}"
            );
        }
    }
}

/// Runs `taylor-dd` on `system` from `y0` to `t_end` at tolerance `tol`; the double-double
/// state it carries at `t_end`.
fn run_dd(system: &dyn TaylorSystem, y0: &[f64], t_end: f64, tol: f64) -> Vec<Dd> {
    let mut y = DVector::from_column_slice(y0);
    let mut stepper = DoubleDoubleTaylorStepper::new(&y);
    let report = Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &system,
            &mut y,
            &Tolerances::new(tol, tol).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    assert_eq!(report.t, t_end);
    stepper.state().to_vec()
}

const KEPLER: &str = r#"
[model]
name = "kepler-polar"
summary = "a point mass about a fixed centre of attraction, in polar coordinates"

[parameters]
mu = { default = 1.0, description = "G M" }

[coordinates]
r = { initial = "0.5", rate = "0" }
theta = { initial = "0", rate = "2.5" }

[points.planet]
mass = "1"
position = ["r*cos(theta)", "r*sin(theta)", "0"]

[lagrangian]
potential = "-mu/r"
"#;

#[test]
fn taylor_dd_on_a_polar_kepler_model_returns_to_periapsis_after_keplers_period_to_1e_minus_29() {
    // Periapsis r = 1/2 at θ̇ = 5/2 (v = 5/4), μ = 1: E = v²/2 − μ/r = −39/32, a = −μ/(2E) =
    // 16/39, e = 1 − r/a = 7/32, and the period T = 2π √(a³/μ) (Kepler's third law). All
    // initial values are exact in binary. The driver's final time is T rounded to f64; the
    // exact state there is the periapsis state advanced by T_f64 − T along ẏ(0) =
    // (0, 5/2, −7/8, 0) (r̈ = r θ̇² − μ/r², θ̈ = −2 ṙ θ̇ / r = 0; the next term is below 1e-32).
    let scene = tumble_model::from_text(KEPLER, "kepler-polar").unwrap();
    let params = scene.info().default_params();
    let y0 = scene.initial_state(&params);
    assert_eq!(y0, [0.5, 0.0, 0.0, 2.5]);
    let a = dd(16.0).quotient(dd(39.0));
    let pi = constant(PI.0, PI.1);
    let period = dd(2.0) * pi * sqrt(a * a * a);
    let t_end = period.hi();
    let late = dd(t_end) - period;
    let taylor = scene.taylor(&params);
    let y = run_dd(&taylor, &y0, t_end, 1e-31);
    let want = [
        dd(0.5),
        dd(2.0) * pi + dd(2.5) * late,
        dd(-0.875) * late,
        dd(2.5),
    ];
    let worst = y
        .iter()
        .zip(&want)
        .map(|(g, w)| gap(*g, *w))
        .fold(0.0, f64::max);
    println!("kepler, one period T = {period:?}: {worst:.2e}");
    assert!(worst < 1e-29, "{y:?} against {want:?}: {worst:e}");
}

#[test]
fn taylor_dd_on_the_so3_heavy_top_model_keeps_energy_vertical_momentum_and_spin_to_1e_minus_29() {
    // heavy-top-so3: state (R by rows, ω in the body). With I = diag(I₁, I₁, I₃) and V = mgl R₃₃
    // the flow keeps E = ½ ω·Iω + mgl R₃₃, the vertical angular momentum Σⱼ R₃ⱼ Iⱼ ωⱼ and the
    // spin ω₃, exactly, whether or not R is orthogonal to the last bit.
    let scene = shipped("heavy-top-so3");
    let params = scene.info().default_params();
    let get = |name: &str| params.get(name).unwrap();
    let inertia = [get("I1"), get("I2"), get("I3")].map(dd);
    let mgl = dd(get("mgl"));
    let invariants = |y: &[Dd]| {
        let w = &y[9..12];
        let energy =
            dd(0.5) * (0..3).fold(dd(0.0), |s, j| s + inertia[j] * w[j] * w[j]) + mgl * y[8];
        let vertical = (0..3).fold(dd(0.0), |s, j| s + y[6 + j] * inertia[j] * w[j]);
        [energy, vertical, w[2]]
    };
    let y0 = scene.initial_state(&params);
    let start = invariants(&y0.iter().map(|v| dd(*v)).collect::<Vec<_>>());
    let taylor = scene.taylor(&params);
    let end = invariants(&run_dd(&taylor, &y0, 10.0, 1e-30));
    for (name, (a, b)) in ["energy", "vertical momentum", "spin"]
        .iter()
        .zip(start.iter().zip(&end))
    {
        let drift = gap(*a, *b) / a.hi().abs();
        println!("heavy-top-so3 under taylor-dd, 10 s: {name} {a:?} drifts {drift:.2e}");
        assert!(drift < 1e-29, "{name}: {a:?} → {b:?}");
    }
}
