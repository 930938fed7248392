//! The Lie-group Runge–Kutta methods (`rkmk4`, `cg3`) on models with several orientations on
//! SO(3), integrated on the product group `SO(3)ᴹ × ℝʸ`: their observed orders against a
//! vector-space reference, agreement with Gauss–Legendre, conservation of the energy and of
//! `L_z` at the method's accuracy, every rotation orthogonal to round-off where the classical
//! RK4 (the same coefficients on the nine numbers) drifts, the exact free-body flow, scalar
//! coordinates beside the rotations (two hoops with beads against the one-hoop model), and no
//! allocation in a step.

use nalgebra::{Matrix3, SVector};
use tumble_integrators::registry::{self, build};
use tumble_integrators::rigid::{
    ProductCrouchGrossman, ProductRkmk, ProductState, ProductVectorField, product_cg3,
    product_rkmk4,
};
use tumble_integrators::{Driver, ExplicitRungeKutta, NoObserver, Stepper, Tolerances};
use tumble_kinematics::so3::orthogonality_defect;
use tumble_model::{ModelProduct, ModelScene, from_text};
use tumble_scenarios::scenes::find;
use tumble_scenarios::{RunOptions, Scene, StepControl};

use crate::support::{column, run, shipped};

pub(crate) const MODEL: &str = "double-spherical-pendulum-so3";

/// The double pendulum's state: 2 × 12 numbers for the orientations, none for coordinates.
pub(crate) const S: usize = 24;
/// Beside the rotations: the two body angular velocities.
pub(crate) const Y: usize = 6;

/// Two bodies on SO(3), no joint, no gravity: each a torque-free body (inertias `A`, `B`,
/// initial body momenta `(0.4, −0.8, 0.6)` and `(−0.5, 0.7, 0.9)`).
const TWO_FREE_BODIES: &str = r#"
[model]
name = "two-free-bodies-so3"
[parameters]
A1 = 1.0
A2 = 2.0
A3 = 3.0
B1 = 2.0
B2 = 3.0
B3 = 5.0
[frames.a]
orientation = "so3"
omega = ["0.4/A1", "-0.8/A2", "0.6/A3"]
[frames.b]
orientation = "so3"
omega = ["-0.5/B1", "0.7/B2", "0.9/B3"]
[bodies.a]
frame = "a"
mass = "1"
inertia = ["A1", "A2", "A3"]
[bodies.b]
frame = "b"
origin = ["3", "0", "0"]
mass = "2"
inertia = ["B1", "B2", "B3"]
"#;

/// Two free hoops, each with a bead (`alpha`, `beta`), under gravity: the product SO(3)² × ℝ⁴,
/// scalar coordinates beside the rotations.
pub(crate) const TWO_HOOPS: &str = r#"
[model]
name = "two-free-hoops-so3"
[parameters]
M = 1.0
m = 0.1
a = 1.0
g = 9.81
[coordinates]
alpha = { initial = "0.5", rate = "0" }
beta = { initial = "1.0", rate = "0.3" }
[frames.p]
orientation = "so3"
euler = "zyz"
angles = ["0", "1.5707963267948966", "0"]
omega = ["-4", "0", "0"]
[frames.s]
orientation = "so3"
euler = "zyz"
angles = ["0", "1.2", "0"]
omega = ["-2.5*sin(1.2)", "0", "2.5*cos(1.2)"]
[bodies.p]
frame = "p"
mass = "M"
inertia = ["M*a^2/2", "M*a^2/2", "M*a^2"]
[bodies.s]
frame = "s"
origin = ["5", "0", "0"]
mass = "M"
inertia = ["M*a^2/2", "M*a^2/2", "M*a^2"]
[points.bead_p]
mass = "m"
frame = "p"
position = ["a*cos(alpha)", "a*sin(alpha)", "0"]
[points.bead_s]
mass = "m"
frame = "s"
position = ["a*cos(beta)", "a*sin(beta)", "0"]
[lagrangian]
gravity = ["0", "0", "-g"]
"#;

/// `n` fixed steps of `h` with `stepper` on the model's product field from its initial state.
fn product_run<St>(scene: &ModelScene, mut stepper: St, h: f64, n: u32) -> ProductState<2, Y>
where
    St: for<'a> Stepper<ModelProduct<'a, 2, S, Y>, State = ProductState<2, Y>>,
{
    let params = scene.info().default_params();
    let field = scene.product::<2, S, Y>(&params).unwrap();
    let y0 = scene.initial_state(&params);
    let mut state = ProductState {
        rotations: std::array::from_fn(|k| Matrix3::from_row_slice(&y0[9 * k..9 * k + 9])),
        vector: SVector::from_column_slice(&y0[18..]),
    };
    Driver::new(0.0, h * f64::from(n))
        .unwrap()
        .run_fixed(&mut stepper, &field, &mut state, h, &mut NoObserver)
        .unwrap();
    state
}

/// The model state `(R₁, R₂, ω₁, ω₂)` of a product state.
pub(crate) fn flat(state: &ProductState<2, Y>) -> SVector<f64, S> {
    let mut z = SVector::<f64, S>::zeros();
    for (k, r) in state.rotations.iter().enumerate() {
        for a in 0..3 {
            for b in 0..3 {
                z[9 * k + 3 * a + b] = r[(a, b)];
            }
        }
    }
    z.rows_mut(18, Y).copy_from(&state.vector);
    z
}

/// The model's state at `t_end` by vern9 at a tolerance of 1e-15 (a vector-space method).
pub(crate) fn reference(scene: &ModelScene, t_end: f64) -> SVector<f64, S> {
    let params = scene.info().default_params();
    let ode = scene.ode(&params);
    let mut y = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let mut stepper = ExplicitRungeKutta::vern9().stepper(&y);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &ode,
            &mut y,
            &Tolerances::new(1e-15, 1e-15).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    y
}

/// `rkmk4` and `cg3` on SO(3) × SO(3) × ℝ⁶, fixed steps to t = 1 against vern9 at 1e-15:
/// halving the step divides the error by `2ᵖ`, `p` the method's order (4 and 3) to ±0.3.
#[test]
fn rkmk4_and_cg3_on_two_orientations_converge_at_their_orders() {
    let scene = shipped(MODEL);
    let t_end = 1.0;
    let exact = reference(scene, t_end);
    let error = |state: ProductState<2, Y>| (flat(&state) - exact).amax();
    for (name, order, steps) in [("rkmk4", 4.0, [40, 80, 160]), ("cg3", 3.0, [80, 160, 320])] {
        let errors: Vec<f64> = steps
            .iter()
            .map(|&n| {
                let h = t_end / f64::from(n);
                if name == "rkmk4" {
                    error(product_run(scene, product_rkmk4::<2, Y>(), h, n))
                } else {
                    error(product_run(scene, product_cg3::<2, Y>(), h, n))
                }
            })
            .collect();
        let observed: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
        println!(
            "{name} on {MODEL}: errors {shown:?} at {steps:?} steps to t = {t_end}, orders \
             {observed:.3?}"
        );
        for p in observed {
            assert!((p - order).abs() <= 0.3, "{name}: observed order {p}");
        }
    }
}

/// The quaternion columns' sign chosen to agree with `other` (`q` and `−q` are one rotation).
fn same_sign(columns: &[String], row: &[f64], other: &[f64]) -> Vec<f64> {
    let mut out = row.to_vec();
    for prefix in ["upper_", "lower_"] {
        let at: Vec<usize> = ["qw", "qx", "qy", "qz"]
            .iter()
            .map(|c| {
                columns
                    .iter()
                    .position(|x| *x == format!("{prefix}{c}"))
                    .unwrap()
            })
            .collect();
        let dot: f64 = at.iter().map(|&i| row[i] * other[i]).sum();
        if dot < 0.0 {
            for &i in &at {
                out[i] = -row[i];
            }
        }
    }
    out
}

/// The double pendulum run through the scene (`RunOptions`, the rows a user sees) by `rkmk4`
/// on the product group at dt = 2.5e-4 and by `gauss12` on the nine numbers of each rotation
/// at dt = 1e-3, to t = 4: every column of every row at the common times (quaternions, angular
/// velocities, energy, `L_z`, the joint and bob positions) agrees to 1e-10 (`rkmk4`'s own error
/// at this step, `O(h⁴)`, is about 2e-11; `gauss12`'s is below 1e-14).
#[test]
fn rkmk4_on_two_orientations_agrees_with_gauss12() {
    let scene = shipped(MODEL);
    let (c, lie) = run(scene, &[], "rkmk4", StepControl::Fixed(2.5e-4), 4.0);
    let (gc, gauss) = run(scene, &[], "gauss12", StepControl::Fixed(1e-3), 4.0);
    assert_eq!(c, gc);
    assert_eq!(lie.len(), 4 * (gauss.len() - 1) + 1);
    assert_eq!(lie.last().unwrap()[0], 4.0);
    let skip = |name: &str| name == "energy_rel_err";
    let mut worst = 0.0f64;
    for (k, g) in gauss.iter().enumerate() {
        let l = &lie[4 * k];
        assert!((l[0] - g[0]).abs() < 1e-12, "{} {}", l[0], g[0]);
        let l = same_sign(&c, l, g);
        for (i, name) in c.iter().enumerate().skip(1) {
            if !skip(name) {
                worst = worst.max((l[i] - g[i]).abs());
            }
        }
    }
    println!(
        "{MODEL}: rkmk4 at dt = 2.5e-4 against gauss12 at dt = 1e-3 to t = 4, {} common rows: \
         largest difference {worst:.2e}",
        gauss.len()
    );
    assert!(worst <= 1e-10, "{worst:e}");
}

/// `rkmk4` on the product over a long run (t = 200 s, about a hundred swings of the joint):
/// the energy and `L_z` (the model's columns), which the method does not conserve exactly,
/// drift by its truncation error — at dt = 1e-3 the energy by less than 1e-10 of its size and
/// `L_z` (a small difference of large terms, −0.05) by less than 4e-9 of its own, and halving
/// the step shrinks both drifts at least eightfold (a fourth-order error, not a bias).
#[test]
fn rkmk4_on_two_orientations_conserves_energy_and_lz_over_a_long_run() {
    let scene = shipped(MODEL);
    let drifts = |dt: f64| {
        let (c, r) = run(scene, &[], "rkmk4", StepControl::Fixed(dt), 200.0);
        assert_eq!(r.last().unwrap()[0], 200.0);
        let drift = |name: &str| {
            let v = column(&c, &r, name);
            v.iter().map(|x| (x - v[0]).abs()).fold(0.0, f64::max) / v[0].abs()
        };
        (drift("energy"), drift("Lz"))
    };
    let ((de, dl), (de2, dl2)) = (drifts(1e-3), drifts(5e-4));
    println!(
        "{MODEL}: rkmk4 to t = 200: energy drift {de:.2e} at dt = 1e-3, {de2:.2e} at 5e-4; Lz \
         drift {dl:.2e}, {dl2:.2e}"
    );
    assert!(de < 1e-10, "energy drift {de:e}");
    assert!(dl < 4e-9, "Lz drift {dl:e}");
    assert!(de2 < de / 8.0, "energy drift {de:e} then {de2:e}");
    assert!(dl2 < dl / 8.0, "Lz drift {dl:e} then {dl2:e}");
}

/// After 10⁵ steps of 2e-3 (t = 200 s), `rkmk4` and `cg3` on the product leave each rotation
/// orthogonal to round-off (‖RᵀR − 𝟙‖ within `10 ε √n`, a random walk of one rounding per step:
/// 7e-13), where the classical RK4 — the same coefficients applied to the nine numbers of each
/// rotation — drifts off SO(3) by orders of magnitude more (above 1e-9).
#[test]
fn the_product_methods_keep_every_rotation_orthogonal_where_rk4_drifts() {
    let scene = shipped(MODEL);
    let (h, n) = (2e-3, 100_000);
    let defect = |s: &ProductState<2, Y>| {
        s.rotations
            .iter()
            .map(orthogonality_defect)
            .fold(0.0, f64::max)
    };
    let rkmk = defect(&product_run(scene, product_rkmk4::<2, Y>(), h, n));
    let cg = defect(&product_run(scene, product_cg3::<2, Y>(), h, n));
    let params = scene.info().default_params();
    let ode = scene.ode(&params);
    let mut y = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let mut rk4 = ExplicitRungeKutta::rk4().stepper(&y);
    Driver::new(0.0, h * f64::from(n))
        .unwrap()
        .run_fixed(&mut rk4, &ode, &mut y, h, &mut NoObserver)
        .unwrap();
    let flat_defect = (0..2)
        .map(|k| orthogonality_defect(&Matrix3::from_row_slice(&y.as_slice()[9 * k..9 * k + 9])))
        .fold(0.0, f64::max);
    println!(
        "{MODEL}, {n} steps of {h}: ‖RᵀR − 𝟙‖ rkmk4 {rkmk:.2e}, cg3 {cg:.2e}, rk4 on the nine \
         numbers {flat_defect:.2e}"
    );
    let bound = 10.0 * f64::EPSILON * f64::from(n).sqrt();
    assert!(rkmk < bound, "rkmk4: {rkmk:e}");
    assert!(cg < bound, "cg3: {cg:e}");
    assert!(flat_defect > 1e-9, "rk4: {flat_defect:e}");
}

/// Two free bodies on the product, `rkmk4` through the scene to t = 20 at dt = 0.1 and 0.05:
/// each body's rotation and angular velocity against the built-in `free-body`'s exact flow
/// (Jacobi elliptic functions) converge at order 4 (±0.3), the error at dt = 0.05 below 2e-8.
#[test]
fn two_free_bodies_by_rkmk4_converge_to_the_exact_flow() {
    let (coarse, fine) = two_free_bodies_against_the_exact_flow("rkmk4", 0.1);
    let order = (coarse / fine).log2();
    println!(
        "two free bodies on SO(3) by rkmk4 against the exact flow at t = 20: {coarse:.2e} at dt = \
         0.1, {fine:.2e} at dt = 0.05, order {order:.3}"
    );
    assert!((order - 4.0).abs() <= 0.3, "{order}");
    assert!(fine < 2e-8, "{fine:e}");
}

/// The largest difference at t = 20 between the two free bodies of [`TWO_FREE_BODIES`] run by
/// `method` through the scene, at `dt` and at `dt / 2`, and the built-in `free-body`'s exact
/// flow of each (rotation matrix and angular velocity).
pub(crate) fn two_free_bodies_against_the_exact_flow(method: &str, dt: f64) -> (f64, f64) {
    let model = from_text(TWO_FREE_BODIES, "two-free-bodies-so3").unwrap_or_else(|e| panic!("{e}"));
    let bodies = [
        (
            "a_",
            [
                ("I1", 1.0),
                ("I2", 2.0),
                ("I3", 3.0),
                ("m1", 0.4),
                ("m2", -0.8),
                ("m3", 0.6),
            ],
        ),
        (
            "b_",
            [
                ("I1", 2.0),
                ("I2", 3.0),
                ("I3", 5.0),
                ("m1", -0.5),
                ("m2", 0.7),
                ("m3", 0.9),
            ],
        ),
    ];
    let value =
        |c: &[String], row: &[f64], name: &str| row[c.iter().position(|x| x == name).unwrap()];
    let rotation = |c: &[String], row: &[f64], p: &str| {
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            value(c, row, &format!("{p}qw")),
            value(c, row, &format!("{p}qx")),
            value(c, row, &format!("{p}qy")),
            value(c, row, &format!("{p}qz")),
        ))
        .to_rotation_matrix()
        .into_inner()
    };
    let exact: Vec<(Vec<String>, Vec<f64>)> = bodies
        .iter()
        .map(|(_, set)| {
            let (bc, br) = run(
                find("free-body").unwrap(),
                set,
                "exact",
                StepControl::Fixed(20.0),
                20.0,
            );
            (bc, br.last().unwrap().clone())
        })
        .collect();
    let error = |dt: f64| {
        let (mc, mr) = run(model, &[], method, StepControl::Fixed(dt), 20.0);
        let last = mr.last().unwrap();
        assert_eq!(last[0], 20.0);
        let mut worst = 0.0f64;
        for ((prefix, _), (bc, b)) in bodies.iter().zip(&exact) {
            worst = worst.max((rotation(&mc, last, prefix) - rotation(bc, b, "")).amax());
            for axis in ["omega_x", "omega_y", "omega_z"] {
                let d = value(&mc, last, &format!("{prefix}{axis}")) - value(bc, b, axis);
                worst = worst.max(d.abs());
            }
        }
        worst
    };
    (error(dt), error(dt / 2.0))
}

/// The model's product field at a state: `ξₖ` is each body's angular velocity, `ẏ` the first-order
/// system's `(ω̇₁, ω̇₂)` (the same numbers, rearranged).
#[test]
fn the_product_field_is_the_first_order_system_rearranged() {
    let scene = shipped(MODEL);
    let params = scene.info().default_params();
    let field = scene.product::<2, S, Y>(&params).unwrap();
    let y0 = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let mut dy = SVector::<f64, S>::zeros();
    scene
        .ode(&params)
        .rhs_slice(0.3, y0.as_slice(), dy.as_mut_slice());
    let s = field.split(y0.as_slice());
    assert_eq!(field.flatten(&s.rotations, &s.vector), y0);
    let (xi, f) = field.eval(0.3, &s.rotations, &s.vector);
    for k in 0..2 {
        assert_eq!(xi[k].as_slice(), &y0.as_slice()[18 + 3 * k..21 + 3 * k]);
        // Ṙ = R hat ξ, as the system writes it.
        let r_dot = s.rotations[k] * tumble_kinematics::so3::hat(&xi[k]);
        let system = Matrix3::from_row_slice(&dy.as_slice()[9 * k..9 * k + 9]);
        assert!(
            (r_dot - system).amax() < 1e-14,
            "{}",
            (r_dot - system).amax()
        );
    }
    assert_eq!(f.as_slice(), &dy.as_slice()[18..]);
    assert!(scene.product::<3, S, Y>(&params).is_none());
}

/// Counts the allocations of 19 steps of 0.01 of the stepper it receives, after a first step
/// (which may allocate), on `F` from a state.
pub(crate) struct Count<'a, F>(pub(crate) &'a F, pub(crate) ProductState<2, Y>);

impl<F> build::Receive<F, ProductState<2, Y>> for Count<'_, F> {
    type Output = u64;
    fn receive<St: Stepper<F, State = ProductState<2, Y>> + Clone>(self, mut stepper: St) -> u64 {
        let Count(field, mut state) = self;
        stepper.step(field, 0.0, &mut state, 0.01).unwrap();
        allocation_counter::measure(|| {
            for k in 1..20 {
                stepper
                    .step(field, f64::from(k) * 0.01, &mut state, 0.01)
                    .unwrap();
            }
        })
        .count_total
    }
}

/// A step of `rkmk4` and `cg3` on the product allocates nothing (the model's workspaces are
/// allocated once, when the field is made).
#[test]
fn a_product_step_allocates_nothing() {
    let scene = shipped(MODEL);
    let params = scene.info().default_params();
    let field = scene.product::<2, S, Y>(&params).unwrap();
    let y0 = scene.initial_state(&params);
    let s0 = field.split(&y0);
    for method in ["rkmk4", "cg3"] {
        let info = registry::find(method).unwrap();
        let count = build::product_vector_field::<_, _, 2, Y>(info, Count(&field, s0)).unwrap();
        assert_eq!(count, 0, "{method} allocated {count} times in 19 steps");
    }
    // The steppers' types, as the registry builds them.
    let _: ProductRkmk<4, 2, Y> = product_rkmk4();
    let _: ProductCrouchGrossman<3, 2, Y> = product_cg3();
}

/// `tumble models` lists `rkmk4` and `cg3` for a model with two orientations on SO(3); the
/// other Lie-group methods are refused before any work, naming the model, why, and what runs
/// it (`rkmk4`, `cg3` and the vector-space methods).
#[test]
fn only_the_lie_group_methods_not_on_the_product_are_refused() {
    let scene = shipped(MODEL);
    let methods = scene.info().integrators();
    for listed in [
        "vern9", "gauss8", "taylor", "rkmk4", "cg3", "lgvi", "lgvi4", "lgvi10",
    ] {
        assert!(methods.contains(&listed), "{listed} not in {methods:?}");
    }
    for group in ["lie-gauss4", "split2", "dmv", "exact"] {
        assert!(!methods.contains(&group), "{group} in {methods:?}");
    }
    for method in ["lie-gauss6", "split2"] {
        let options = RunOptions {
            integrator: Some(method.into()),
            ..RunOptions::default()
        };
        let err = options.resolve(scene.info()).unwrap_err().to_string();
        println!("{err}");
        for expected in [
            method,
            MODEL,
            "2 orientations on SO(3) (`upper`, `lower`)",
            "SO(3)^2 × R^6",
            "lgvi4 … lgvi10), rkmk4 and cg3 run it on the product",
            "applicable: ",
            "lgvi",
            "rkmk4",
            "cg3",
            "vern9",
            "gauss8",
        ] {
            assert!(err.contains(expected), "`{expected}` not in: {err}");
        }
    }
}

/// Two free hoops, each with a bead (`alpha`, `beta`) and under gravity, in one model: the
/// product SO(3)² × ℝ⁴ with scalar coordinates beside the rotations. `rkmk4` on the product
/// (dt = 2.5e-4) follows each hoop as the shipped one-hoop model `free-hoop-so3` does under
/// `gauss12` (dt = 1e-3) at the same initial state, to 1e-12 over 2 s in every shown number
/// (quaternion, angular velocity, bead angle and rate).
#[test]
fn two_hoops_with_beads_by_rkmk4_follow_the_one_hoop_model() {
    let model = from_text(TWO_HOOPS, "two-free-hoops-so3").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.model().layout.so3, 2);
    assert_eq!(model.model().layout.n, 2);
    let (c, two) = run(model, &[], "rkmk4", StepControl::Fixed(2.5e-4), 2.0);
    let one = shipped("free-hoop-so3");
    let mut worst = 0.0f64;
    for (prefix, bead, set) in [
        (
            "p_",
            "alpha",
            [
                ("omega0", 4.0),
                ("theta0", std::f64::consts::FRAC_PI_2),
                ("alpha0", 0.5),
                ("alpha_dot0", 0.0),
            ],
        ),
        (
            "s_",
            "beta",
            [
                ("omega0", 2.5),
                ("theta0", 1.2),
                ("alpha0", 1.0),
                ("alpha_dot0", 0.3),
            ],
        ),
    ] {
        let (oc, rows) = run(one, &set, "gauss12", StepControl::Fixed(1e-3), 2.0);
        assert_eq!(two.len(), 4 * (rows.len() - 1) + 1);
        let at = |columns: &[String], row: &[f64], name: &str| {
            row[columns.iter().position(|x| x == name).unwrap()]
        };
        for (k, o) in rows.iter().enumerate() {
            let t = &two[4 * k];
            assert!((t[0] - o[0]).abs() < 1e-12);
            let dot: f64 = ["qw", "qx", "qy", "qz"]
                .iter()
                .map(|q| at(&c, t, &format!("{prefix}{q}")) * at(&oc, o, q))
                .sum();
            let sign = dot.signum();
            for q in ["qw", "qx", "qy", "qz"] {
                worst =
                    worst.max((sign * at(&c, t, &format!("{prefix}{q}")) - at(&oc, o, q)).abs());
            }
            for w in ["omega_x", "omega_y", "omega_z"] {
                worst = worst.max((at(&c, t, &format!("{prefix}{w}")) - at(&oc, o, w)).abs());
            }
            worst = worst.max((at(&c, t, bead) - at(&oc, o, "alpha")).abs());
            worst = worst.max((at(&c, t, &format!("{bead}_dot")) - at(&oc, o, "alpha_dot")).abs());
        }
    }
    println!(
        "two hoops with beads by rkmk4 (dt = 2.5e-4) against free-hoop-so3 by gauss12 (dt = 1e-3) \
         to t = 2: {worst:.2e}"
    );
    assert!(worst < 1e-12, "{worst:e}");
}
