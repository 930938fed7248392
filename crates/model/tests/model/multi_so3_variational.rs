//! The LGVI on the product `SO(3)ᴹ × ℝⁿ` (`lgvi` and its compositions) on models with several
//! orientations on SO(3), whose kinetic energy couples the rotations: its observed orders
//! against a vector-space reference, the exact flow of two free bodies, the spatial angular
//! momentum conserved to round-off (discrete Noether) where `rkmk4` drifts, an energy error
//! that oscillates without drift, scalar coordinates beside the rotations, and no allocation in
//! a step.

use nalgebra::{Matrix3, SVector};
use tumble_integrators::registry::{self, build};
use tumble_integrators::rigid::{ProductLagrangian, ProductLgvi, ProductState};
use tumble_integrators::{Driver, ExplicitRungeKutta, NoObserver, Stepper, Tolerances};
use tumble_model::{ModelScene, from_text};
use tumble_scenarios::{Scene, StepControl};

use crate::multi_so3_lie::{
    Count, MODEL, S, TWO_HOOPS, Y, flat, reference, two_free_bodies_against_the_exact_flow,
};
use crate::support::{column, run, shipped};

/// Runs `n` fixed steps of `h` of the registry's `method` on `field` from `state`.
struct Steps<'f, F, const M: usize, const N: usize> {
    field: &'f F,
    state: ProductState<M, N>,
    h: f64,
    n: u32,
}

impl<F: ProductLagrangian<M, N>, const M: usize, const N: usize>
    build::Receive<F, ProductState<M, N>> for Steps<'_, F, M, N>
{
    type Output = ProductState<M, N>;
    fn receive<St: Stepper<F, State = ProductState<M, N>> + Clone>(
        self,
        mut stepper: St,
    ) -> ProductState<M, N> {
        let mut state = self.state;
        Driver::new(0.0, self.h * f64::from(self.n))
            .unwrap()
            .run_fixed(
                &mut stepper,
                self.field,
                &mut state,
                self.h,
                &mut NoObserver,
            )
            .unwrap();
        state
    }
}

/// The model's state after `n` steps of `h` of `method` on its Lagrangian on the product.
fn lagrangian_run<const M: usize, const Z: usize, const N: usize>(
    scene: &ModelScene,
    method: &str,
    h: f64,
    n: u32,
) -> SVector<f64, Z> {
    let params = scene.info().default_params();
    let field = scene.product::<M, Z, N>(&params).unwrap();
    let state = field.split(&scene.initial_state(&params));
    let info = registry::find(method).unwrap();
    let end = build::product_lagrangian::<_, _, M, N>(
        info,
        Steps {
            field: &field,
            state,
            h,
            n,
        },
    )
    .unwrap();
    field.flatten(&end.rotations, &end.vector)
}

/// The observed orders of `method` from the errors at `steps` (each twice the last) to `t_end`.
fn observed_orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect()
}

/// Runs `method` on `scene`'s Lagrangian to `t_end` at each of `steps` (each twice the last),
/// prints the errors against `exact` and the observed orders, and checks each order is
/// `order` ± 0.3.
fn assert_orders<const Z: usize, const N: usize>(
    scene: &ModelScene,
    exact: &SVector<f64, Z>,
    t_end: f64,
    (method, order, steps): (&str, f64, &[u32]),
    what: &str,
) {
    let errors: Vec<f64> = steps
        .iter()
        .map(|&n| {
            let end = lagrangian_run::<2, Z, N>(scene, method, t_end / f64::from(n), n);
            (end - exact).amax()
        })
        .collect();
    let observed = observed_orders(&errors);
    let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
    println!(
        "{method} on {what}: errors {shown:?} at {steps:?} steps to t = {t_end}, orders \
         {observed:.3?}"
    );
    for p in observed {
        assert!(
            (p - order).abs() <= 0.3,
            "{method} on {what}: observed order {p}"
        );
    }
}

/// `lgvi`, `lgvi4` and `lgvi6` on the double spherical pendulum (SO(3)², the lower body's pivot
/// carried by the upper one, so the kinetic energy depends on the relative rotation), fixed
/// steps to t = 1 against vern9 at 1e-15: halving the step divides the error by `2ᵖ`, `p` the
/// method's order (2, 4, 6), to ±0.3.
#[test]
fn lgvi_and_its_compositions_on_two_orientations_converge_at_their_orders() {
    let scene = shipped(MODEL);
    let t_end = 1.0;
    let exact = reference(scene, t_end);
    for (method, order, steps) in [
        ("lgvi", 2.0, [50, 100, 200, 400]),
        ("lgvi4", 4.0, [25, 50, 100, 200]),
        ("lgvi6", 6.0, [20, 40, 80, 160]),
    ] {
        assert_orders::<S, Y>(scene, &exact, t_end, (method, order, &steps), MODEL);
    }
}

/// Two free bodies in one model (no joint, no gravity) by `lgvi` and `lgvi4` through the scene
/// to t = 20 at dt = 0.1 and 0.05: each body's rotation and angular velocity against the
/// built-in `free-body`'s exact flow (Jacobi elliptic functions) converge at orders 2 and 4
/// (±0.3).
#[test]
fn two_free_bodies_by_the_lgvi_on_the_product_converge_to_the_exact_flow() {
    for (method, order) in [("lgvi", 2.0), ("lgvi4", 4.0)] {
        let (coarse, fine) = two_free_bodies_against_the_exact_flow(method, 0.1);
        let observed = (coarse / fine).log2();
        println!(
            "two free bodies on SO(3) by {method} against the exact flow at t = 20: {coarse:.2e} \
             at dt = 0.1, {fine:.2e} at dt = 0.05, order {observed:.3}"
        );
        assert!((observed - order).abs() <= 0.3, "{method}: {observed}");
    }
}

/// The double spherical pendulum over t = 200 s (about a hundred swings) at dt = 1e-2, through
/// the scene's rows: the model is unchanged when both bodies turn together about the vertical,
/// so the LGVI's discrete Lagrangian is too and it conserves `L_z` exactly — the column stays
/// within round-off (1e-12 of the momenta's size), where `rkmk4` at the same step lets it
/// drift a hundred times further. The energy error of the LGVI oscillates at its `O(h²)`
/// size without growing: its largest value over the second 100 s is within 1.5 times that over
/// the first, and a quarter of it at half the step.
#[test]
fn lgvi_on_two_orientations_conserves_lz_exactly_and_the_energy_without_drift() {
    let scene = shipped(MODEL);
    let (t_end, dt) = (200.0, 1e-2);
    let (c, rows) = run(scene, &[], "lgvi", StepControl::Fixed(dt), t_end);
    assert_eq!(rows.last().unwrap()[0], t_end);
    let lz = column(&c, &rows, "Lz");
    let drift = |v: &[f64]| v.iter().map(|x| (x - v[0]).abs()).fold(0.0, f64::max);
    // Lz is a small difference of terms of the size of each body's momentum (|Π| ≈ 1).
    let lgvi_lz = drift(&lz);
    let (rc, rk) = run(scene, &[], "rkmk4", StepControl::Fixed(dt), t_end);
    let rkmk_lz = drift(&column(&rc, &rk, "Lz"));
    let energy_errors = |rows: &[Vec<f64>], columns: &[String]| {
        let t = column(columns, rows, "t");
        let energy = column(columns, rows, "energy");
        let (mut first, mut second) = (0.0f64, 0.0f64);
        for (t, e) in t.iter().zip(&energy) {
            let d = (e - energy[0]).abs() / energy[0].abs();
            if *t <= t_end / 2.0 {
                first = first.max(d);
            } else {
                second = second.max(d);
            }
        }
        (first, second)
    };
    let (first, second) = energy_errors(&rows, &c);
    let (hc, half) = run(scene, &[], "lgvi", StepControl::Fixed(dt / 2.0), t_end);
    let (first_half, second_half) = energy_errors(&half, &hc);
    println!(
        "{MODEL} to t = {t_end} at dt = {dt}: Lz drift lgvi {lgvi_lz:.2e}, rkmk4 {rkmk_lz:.2e}; \
         lgvi energy error {first:.2e} over the first half, {second:.2e} over the second; at \
         dt/2 {first_half:.2e}, {second_half:.2e}"
    );
    assert!(lgvi_lz < 1e-12, "lgvi Lz drift {lgvi_lz:e}");
    assert!(
        rkmk_lz > 100.0 * lgvi_lz,
        "rkmk4 {rkmk_lz:e}, lgvi {lgvi_lz:e}"
    );
    assert!(
        second < 1.5 * first,
        "energy error {first:e} then {second:e}"
    );
    let ratio = first.max(second) / first_half.max(second_half);
    assert!((ratio - 4.0).abs() < 1.2, "energy error ratio {ratio}");
}

/// Two hoops with beads (SO(3)² × ℝ⁴: scalar coordinates beside the rotations, a bead's
/// kinetic energy coupling its angle to its hoop's rotation): `lgvi` and `lgvi4` converge at
/// orders 2 and 4 (±0.3) against vern9 at 1e-15, to t = 1.
#[test]
fn lgvi_with_scalar_coordinates_beside_two_orientations_converges_at_its_order() {
    const Z: usize = 28;
    const W: usize = 10;
    let model = from_text(TWO_HOOPS, "two-free-hoops-so3").unwrap_or_else(|e| panic!("{e}"));
    let params = model.info().default_params();
    let t_end = 1.0;
    let ode = model.ode(&params);
    let mut exact = SVector::<f64, Z>::from_column_slice(&model.initial_state(&params));
    let mut stepper = ExplicitRungeKutta::vern9().stepper(&exact);
    Driver::new(0.0, t_end)
        .unwrap()
        .run_adaptive(
            &mut stepper,
            &ode,
            &mut exact,
            &Tolerances::new(1e-15, 1e-15).unwrap(),
            &mut [],
            &mut NoObserver,
        )
        .unwrap();
    for (method, order, steps) in [
        ("lgvi", 2.0, [100, 200, 400]),
        ("lgvi4", 4.0, [50, 100, 200]),
    ] {
        assert_orders::<Z, W>(
            model,
            &exact,
            t_end,
            (method, order, &steps),
            "two hoops with beads",
        );
    }
}

/// After 2·10⁴ steps every rotation is still orthogonal to round-off: each moves by an
/// exponential.
#[test]
fn lgvi_keeps_every_rotation_orthogonal() {
    let scene = shipped(MODEL);
    let (h, n) = (1e-2, 20_000);
    let end = lagrangian_run::<2, S, Y>(scene, "lgvi", h, n);
    let worst = (0..2)
        .map(|k| {
            tumble_kinematics::so3::orthogonality_defect(&Matrix3::from_row_slice(
                &end.as_slice()[9 * k..9 * k + 9],
            ))
        })
        .fold(0.0, f64::max);
    println!("{MODEL}: ‖RᵀR − 𝟙‖ after {n} lgvi steps of {h}: {worst:.2e}");
    assert!(
        worst < 10.0 * f64::EPSILON * f64::from(n).sqrt(),
        "{worst:e}"
    );
    // The same state in the vector-space layout the scene shows (no rotation lost).
    let params = scene.info().default_params();
    let field = scene.product::<2, S, Y>(&params).unwrap();
    let s = field.split(end.as_slice());
    assert_eq!(flat(&s), end);
}

/// A step of `lgvi` and of `lgvi6` on the product allocates nothing (the stepper's workspace
/// is allocated when it is built, the model's when the field is made).
#[test]
fn a_product_lgvi_step_allocates_nothing() {
    let scene = shipped(MODEL);
    let params = scene.info().default_params();
    let field = scene.product::<2, S, Y>(&params).unwrap();
    let s0 = field.split(&scene.initial_state(&params));
    for method in ["lgvi", "lgvi6"] {
        let info = registry::find(method).unwrap();
        let count = build::product_lagrangian::<_, _, 2, Y>(info, Count(&field, s0)).unwrap();
        assert_eq!(count, 0, "{method} allocated {count} times in 19 steps");
    }
}

/// The double spherical pendulum's file with `edit` applied: a variant of the shipped model.
fn variant(name: &str, edit: impl Fn(String) -> String) -> &'static ModelScene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(format!("{MODEL}.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let text = edit(text).replace(
        &format!("name = \"{MODEL}\""),
        &format!("name = \"{name}\""),
    );
    from_text(&text, name).unwrap_or_else(|e| panic!("{e}"))
}

/// `lgvi` and `lgvi4` on two variants of the double pendulum whose Lagrangian is not a
/// kinetic quadratic form minus a potential of the configuration: written in a frame turning
/// about the vertical at 0.7 rad/s (terms linear in the velocities: Coriolis), and hung from a
/// pivot driven up and down, `z = 0.1 m · cos(3 rad/s · t)` (a Lagrangian that depends on time, evaluated
/// at each step's two ends). Both converge at orders 2 and 4 (±0.3) against vern9 at 1e-15.
#[test]
fn lgvi_on_two_orientations_converges_in_a_rotating_frame_and_under_a_driven_pivot() {
    let rotating = variant("double-pendulum-turning", |text| {
        text.replace(
            "[bodies.upper]",
            "[rotating_frame]\nomega = [\"0\", \"0\", \"0.7\"]\n\n[bodies.upper]",
        )
    });
    let driven = variant("double-pendulum-driven", |text| {
        text.replace(
            "[parameters]\n",
            "[parameters]\nzd = { default = 0.1, unit = \"m\" }\nwd = { default = 3.0, unit = \"rad/s\" }\n",
        )
        .replace(
            "frame = \"upper\"\nmass = \"m1\"",
            "frame = \"upper\"\norigin = [\"0\", \"0\", \"zd*cos(wd*t)\"]\nmass = \"m1\"",
        )
        .replace(
            "origin = [\"-l1*upper_R13\", \"-l1*upper_R23\", \"-l1*upper_R33\"]",
            "origin = [\"-l1*upper_R13\", \"-l1*upper_R23\", \"zd*cos(wd*t) - l1*upper_R33\"]",
        )
    });
    for (what, scene) in [("turning frame", rotating), ("driven pivot", driven)] {
        let t_end = 1.0;
        let exact = reference(scene, t_end);
        // The variant differs from the shipped model's motion.
        assert!(
            (exact - reference(shipped(MODEL), t_end)).amax() > 1e-3,
            "{what}"
        );
        for (method, order, steps) in [("lgvi", 2.0, [50, 100, 200]), ("lgvi4", 4.0, [25, 50, 100])]
        {
            assert_orders::<S, Y>(scene, &exact, t_end, (method, order, &steps), what);
        }
    }
}

/// Two hoops with beads turn about the vertical through their own pivots unchanged, beads and
/// all: `lgvi` conserves `Lz = Σ R Π` exactly there too, scalar coordinates beside the
/// rotations (within 1e-12 over 20 s at dt = 1e-2, where `rkmk4` at the same step drifts at
/// least a hundred times further).
#[test]
fn lgvi_with_beads_beside_two_orientations_conserves_lz_exactly() {
    let model = from_text(TWO_HOOPS, "two-free-hoops-so3").unwrap_or_else(|e| panic!("{e}"));
    let drift = |method: &str| {
        let (c, rows) = run(model, &[], method, StepControl::Fixed(1e-2), 20.0);
        let lz = column(&c, &rows, "Lz");
        lz.iter().map(|x| (x - lz[0]).abs()).fold(0.0, f64::max)
    };
    let (lgvi, rkmk) = (drift("lgvi"), drift("rkmk4"));
    println!(
        "two hoops with beads to t = 20 at dt = 1e-2: Lz drift lgvi {lgvi:.2e}, rkmk4 {rkmk:.2e}"
    );
    assert!(lgvi < 1e-12, "{lgvi:e}");
    assert!(rkmk > 100.0 * lgvi, "rkmk4 {rkmk:e}, lgvi {lgvi:e}");
}

/// Newton's matrix of the step is the derivative of its equation up to `O(h²)` (the module
/// doc of `ProductLgvi`): at dt = 1e-2, from the guess `ξ = v₀` (`O(h)` off), each iteration
/// gains a factor `O(h²)` and one more sees the increment stop shrinking, so a step takes at
/// most seven iterations and six on average, on the double pendulum (rotations only) and on two
/// hoops with beads (the momenta's derivatives along the bead angles enter). A matrix wrong at
/// `O(h)` gains only `O(h)` an iteration: with the mixed derivative untransposed, or without
/// the `P̂` term, the double pendulum takes 14 at most and 12 on average.
#[test]
fn the_product_lgvi_solves_its_step_in_a_few_newton_iterations() {
    fn most<const Z: usize, const W: usize>(scene: &ModelScene) -> (usize, f64) {
        let params = scene.info().default_params();
        let field = scene.product::<2, Z, W>(&params).unwrap();
        let mut state = field.split(&scene.initial_state(&params));
        let mut stepper = ProductLgvi::<2, W>::new();
        let (h, n) = (1e-2, 500);
        let (mut most, mut total) = (0, 0);
        for k in 0..n {
            stepper
                .step(&field, f64::from(k) * h, &mut state, h)
                .unwrap();
            most = most.max(stepper.iterations());
            total += stepper.iterations();
        }
        (most, total as f64 / f64::from(n))
    }
    let two_hoops = from_text(TWO_HOOPS, "two-free-hoops-so3").unwrap_or_else(|e| panic!("{e}"));
    for (what, (most, mean)) in [
        ("double pendulum", most::<S, Y>(shipped(MODEL))),
        ("two hoops with beads", most::<28, 10>(two_hoops)),
    ] {
        println!("{what}: Newton iterations a step at dt = 1e-2: at most {most}, mean {mean:.2}");
        assert!(most <= 7 && mean <= 6.0, "{what}: {most}, mean {mean}");
    }
}

/// Released from rest (all six angular velocities zero, so the step's first guess and each
/// velocity block start at zero), the double pendulum swings under `lgvi`: the bob falls, the
/// energy error stays at the method's `O(h²)` size, and `Lz`, zero at the start, stays zero to
/// round-off.
#[test]
fn lgvi_on_two_orientations_starts_from_rest() {
    let scene = shipped(MODEL);
    let rest = [
        ("w1x0", 0.0),
        ("w1y0", 0.0),
        ("w1z0", 0.0),
        ("w2x0", 0.0),
        ("w2y0", 0.0),
        ("w2z0", 0.0),
    ];
    let (c, rows) = run(scene, &rest, "lgvi", StepControl::Fixed(1e-2), 5.0);
    assert_eq!(rows.last().unwrap()[0], 5.0);
    let bob = column(&c, &rows, "bob_z");
    let fell = bob.iter().map(|z| bob[0] - z).fold(0.0, f64::max);
    let energy = column(&c, &rows, "energy_rel_err")
        .into_iter()
        .fold(0.0, f64::max);
    let lz = column(&c, &rows, "Lz")
        .into_iter()
        .fold(0.0, |m: f64, x| m.max(x.abs()));
    println!(
        "{MODEL} from rest, lgvi, dt = 1e-2 to t = 5: bob fell {fell:.3} m, energy error {energy:.2e}, |Lz| {lz:.1e}"
    );
    assert!(fell > 0.05, "{fell}");
    assert!(energy < 1e-4, "{energy:e}");
    assert!(lz < 1e-14, "{lz:e}");
}
