//! Several orientations on SO(3) in one model: the double spherical pendulum of two rigid
//! bodies (`models/double-spherical-pendulum-so3.toml`) conserves its energy and vertical
//! angular momentum, each computed here from the rows by Newton's definitions; it agrees with
//! the same system written in Euler angles; two free bodies each follow the exact
//! torque-free flow. (The Lie-group methods on the product of the orientations:
//! `multi_so3_lie`.)

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use tumble_kinematics::{EulerConvention, EulerSequence};
use tumble_model::{ModelScene, from_text};
use tumble_scenarios::scenes::find;
use tumble_scenarios::{Scene, StepControl};

use crate::support::{column, run, shipped};

const MODEL: &str = "double-spherical-pendulum-so3";

/// The value of parameter `name` of `scene` at its defaults.
fn param(scene: &ModelScene, name: &str) -> f64 {
    scene
        .model()
        .params
        .iter()
        .find(|p| p.name == name)
        .unwrap_or_else(|| panic!("no parameter {name}"))
        .default
}

/// The rotation of the quaternion in columns `{prefix}qw … {prefix}qz` of `row`.
fn rotation(columns: &[String], row: &[f64], prefix: &str) -> Matrix3<f64> {
    let at = |c: &str| {
        row[columns
            .iter()
            .position(|x| x == &format!("{prefix}{c}"))
            .unwrap()]
    };
    let q = Quaternion::new(at("qw"), at("qx"), at("qy"), at("qz"));
    *UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .matrix()
}

/// The body angular velocity in columns `{prefix}omega_x …` of `row`.
fn omega(columns: &[String], row: &[f64], prefix: &str) -> Vector3<f64> {
    let at = |c: &str| {
        row[columns
            .iter()
            .position(|x| x == &format!("{prefix}{c}"))
            .unwrap()]
    };
    Vector3::new(at("omega_x"), at("omega_y"), at("omega_z"))
}

/// The energy `T + V` and the angular momentum about the pivot of the double pendulum in the
/// state `(R₁, ω₁, R₂, ω₂)`, by the definitions: each centre of mass's position `r` and
/// velocity `v = ṙ` (the joint at `R₁ (0, 0, −l₁)` moving with the upper body),
/// `T = Σ ½ m |v|² + ½ ω·(I ω)`, `V = Σ m g r_z`, `L = Σ m r × v + R I ω`.
fn newton(
    scene: &ModelScene,
    r1: &Matrix3<f64>,
    w1: &Vector3<f64>,
    r2: &Matrix3<f64>,
    w2: &Vector3<f64>,
) -> (f64, Vector3<f64>) {
    let p = |n: &str| param(scene, n);
    let (m1, m2, g) = (p("m1"), p("m2"), p("g"));
    let i1 = Matrix3::from_diagonal(&Vector3::new(p("J1x"), p("J1y"), p("J1z")));
    let i2 = Matrix3::from_diagonal(&Vector3::new(p("J2x"), p("J2y"), p("J2z")));
    let (c1, joint, c2) = (
        Vector3::new(0.0, 0.0, -p("a1")),
        Vector3::new(0.0, 0.0, -p("l1")),
        Vector3::new(0.0, 0.0, -p("a2")),
    );
    let (s1, s2) = (r1 * w1, r2 * w2);
    let (x1, xj, x2) = (r1 * c1, r1 * joint, r2 * c2);
    let (v1, vj) = (s1.cross(&x1), s1.cross(&xj));
    let (rc2, v2) = (xj + x2, vj + s2.cross(&x2));
    let kinetic = 0.5 * m1 * v1.norm_squared()
        + 0.5 * w1.dot(&(i1 * w1))
        + 0.5 * m2 * v2.norm_squared()
        + 0.5 * w2.dot(&(i2 * w2));
    let potential = m1 * g * x1.z + m2 * g * rc2.z;
    let momentum = m1 * x1.cross(&v1) + r1 * i1 * w1 + m2 * rc2.cross(&v2) + r2 * i2 * w2;
    (kinetic + potential, momentum)
}

/// Largest deviation of `values` from their first, relative to `scale`.
fn drift(values: &[f64], scale: f64) -> f64 {
    values
        .iter()
        .map(|v| (v - values[0]).abs())
        .fold(0.0, f64::max)
        / scale
}

/// The double spherical pendulum of two rigid bodies on SO(3) × SO(3), run for 20 s (about
/// ten swings of the joint) by an explicit pair, Gauss–Legendre and the Taylor method: its
/// energy and vertical angular momentum, computed from the rows by their definitions, agree
/// with the model's `energy` and `Lz` columns and are conserved to the method's accuracy.
#[test]
fn the_double_spherical_pendulum_on_so3_conserves_energy_and_lz() {
    let scene = shipped(MODEL);
    assert_eq!(scene.model().layout.so3, 2);
    for (method, step) in [
        ("vern9", StepControl::Tolerance(1e-12)),
        ("gauss8", StepControl::Fixed(5e-3)),
        ("taylor", StepControl::Tolerance(1e-12)),
    ] {
        let (c, r) = run(scene, &[], method, step, 20.0);
        assert_eq!(r.last().unwrap()[0], 20.0, "{method}");
        let (mut energy, mut lz, mut worst_column) = (Vec::new(), Vec::new(), 0.0f64);
        let (e_col, lz_col) = (column(&c, &r, "energy"), column(&c, &r, "Lz"));
        for (k, row) in r.iter().enumerate() {
            let (r1, r2) = (rotation(&c, row, "upper_"), rotation(&c, row, "lower_"));
            let (w1, w2) = (omega(&c, row, "upper_"), omega(&c, row, "lower_"));
            let (e, l) = newton(scene, &r1, &w1, &r2, &w2);
            worst_column = worst_column
                .max((e - e_col[k]).abs() / e.abs())
                .max((l.z - lz_col[k]).abs() / l.norm());
            energy.push(e);
            lz.push(l.z);
        }
        // The joint swings: each crossing of x = 0 is half a swing.
        let joint_x = column(&c, &r, "joint_x");
        let crossings = joint_x.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
        let (de, dl) = (drift(&energy, energy[0].abs()), drift(&lz, lz[0].abs()));
        println!(
            "{MODEL} with {method}: {} rows, {crossings} crossings of the joint, energy drift \
             {de:.2e}, Lz drift {dl:.2e} (Lz = {:.4}), columns against the definitions {worst_column:.2e}",
            r.len(),
            lz[0]
        );
        assert!(crossings >= 10, "{method}: {crossings} crossings");
        assert!(worst_column < 1e-12, "{method}: {worst_column:e}");
        assert!(de < 1e-10, "{method}: energy drift {de:e}");
        assert!(dl < 1e-10, "{method}: Lz drift {dl:e}");
    }
}

/// The same double pendulum written with intrinsic x-y-z Euler angles for each body (its rates
/// from the body angular velocities by the inverse of `ω = E'(a) ȧ`), run with the same method
/// and step: every row's rotations (from the angles by `tumble-kinematics`) and body angular
/// velocities (`E'(a) ȧ`) agree with the model on SO(3) to 1e-10, the angles staying away
/// from the lock at a middle angle of ±π/2.
#[test]
fn the_double_spherical_pendulum_on_so3_matches_its_euler_angle_twin() {
    let scene = shipped(MODEL);
    let mut parameters = String::new();
    for p in &scene.model().params {
        parameters += &format!("{} = {:?}\n", p.name, p.default);
    }
    let mut coordinates = String::new();
    for b in ["1", "2"] {
        let wx = format!("(w{b}x0*cos(a{b}z0) - w{b}y0*sin(a{b}z0))/cos(a{b}y0)");
        coordinates += &format!(
            "a{b}x = {{ initial = \"a{b}x0\", rate = \"{wx}\" }}\n\
             a{b}y = {{ initial = \"a{b}y0\", rate = \"w{b}x0*sin(a{b}z0) + w{b}y0*cos(a{b}z0)\" }}\n\
             a{b}z = {{ initial = \"a{b}z0\", rate = \"w{b}z0 - {wx}*sin(a{b}y0)\" }}\n"
        );
    }
    let text = format!(
        r#"
[model]
name = "double-spherical-pendulum-euler"
[parameters]
{parameters}
[coordinates]
{coordinates}
[frames.upper]
euler = "xyz"
angles = ["a1x", "a1y", "a1z"]
[frames.lower]
euler = "xyz"
angles = ["a2x", "a2y", "a2z"]
[bodies.upper]
frame = "upper"
mass = "m1"
com = ["0", "0", "-a1"]
inertia = ["J1x", "J1y", "J1z"]
[bodies.lower]
frame = "lower"
origin = ["-l1*sin(a1y)", "l1*sin(a1x)*cos(a1y)", "-l1*cos(a1x)*cos(a1y)"]
mass = "m2"
com = ["0", "0", "-a2"]
inertia = ["J2x", "J2y", "J2z"]
[lagrangian]
gravity = ["0", "0", "-g"]
"#
    );
    let euler =
        from_text(&text, "double-spherical-pendulum-euler").unwrap_or_else(|e| panic!("{e}"));
    let step = StepControl::Fixed(1e-3);
    let (ec, er) = run(euler, &[], "gauss12", step, 4.0);
    let (sc, sr) = run(scene, &[], "gauss12", step, 4.0);
    assert_eq!(er.len(), sr.len());
    let xyz = EulerConvention::intrinsic(EulerSequence::XYZ);
    let (mut worst, mut middle) = (0.0f64, 0.0f64);
    for (e, s) in er.iter().zip(&sr) {
        assert_eq!(e[0], s[0]);
        let at = |n: &str| e[ec.iter().position(|x| x == n).unwrap()];
        for (b, prefix) in [("1", "upper_"), ("2", "lower_")] {
            let angles = Vector3::new(
                at(&format!("a{b}x")),
                at(&format!("a{b}y")),
                at(&format!("a{b}z")),
            );
            let rates = Vector3::new(
                at(&format!("a{b}x_dot")),
                at(&format!("a{b}y_dot")),
                at(&format!("a{b}z_dot")),
            );
            middle = middle.max(angles.y.abs());
            let r = *xyz.to_rotation(&angles).matrix();
            let w = xyz.omega_body(&angles, &rates);
            worst = worst
                .max((r - rotation(&sc, s, prefix)).amax())
                .max((w - omega(&sc, s, prefix)).amax());
        }
        let energy = |c: &[String], row: &[f64]| row[c.iter().position(|x| x == "energy").unwrap()];
        worst = worst.max((energy(&ec, e) - energy(&sc, s)).abs() / energy(&sc, s).abs());
    }
    println!(
        "{MODEL} against its Euler-angle twin, gauss12 at dt = 1e-3 to t = 4: {} rows, largest \
         difference {worst:.2e}, largest middle angle {middle:.3}",
        sr.len()
    );
    assert!(middle < 1.2, "{middle}");
    assert!(worst <= 1e-10, "{worst:e}");
}

/// Two bodies on SO(3) with no joint and no gravity, each a torque-free body of its own
/// inertia and initial momentum: each follows the built-in `free-body`'s exact flow (Jacobi
/// elliptic functions) at the same parameters.
#[test]
fn two_free_bodies_on_so3_each_follow_the_exact_flow() {
    let text = r#"
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
    let model = from_text(text, "two-free-bodies-so3").unwrap_or_else(|e| panic!("{e}"));
    let (mc, mr) = run(model, &[], "vern9", StepControl::Tolerance(1e-13), 20.0);
    let last = mr.last().unwrap();
    assert_eq!(last[0], 20.0);
    let mut worst = 0.0f64;
    for (prefix, set) in [
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
    ] {
        let (bc, br) = run(
            find("free-body").unwrap(),
            &set,
            "exact",
            StepControl::Fixed(20.0),
            20.0,
        );
        let exact = br.last().unwrap();
        assert_eq!(exact[0], 20.0);
        // The rotations, whatever the quaternions' signs (the exact run's two rows, 20 s
        // apart, choose its sign afresh), and the body angular velocities.
        let (model_r, exact_r) = (rotation(&mc, last, prefix), rotation(&bc, exact, ""));
        worst = worst.max((model_r - exact_r).amax());
        let (model_w, exact_w) = (omega(&mc, last, prefix), omega(&bc, exact, ""));
        worst = worst.max((model_w - exact_w).amax());
    }
    println!("two free bodies on SO(3) against the exact flow at t = 20: {worst:.2e}");
    assert!(worst < 1e-10, "{worst:e}");
    let energy = column(&mc, &mr, "energy");
    // ½ Σ m²/I of both bodies.
    let expected =
        0.5 * (0.16 / 1.0 + 0.64 / 2.0 + 0.36 / 3.0 + 0.25 / 2.0 + 0.49 / 3.0 + 0.81 / 5.0);
    assert!((energy[0] - expected).abs() < 1e-15, "{}", energy[0]);
    assert!(
        drift(&energy, expected) < 1e-12,
        "{}",
        drift(&energy, expected)
    );
}

/// Where the model places its bodies: the upper body's frame at the pivot turned by its
/// rotation, the lower body's at the joint `R₁ (0, 0, −l₁)`, each turned by its own.
#[test]
fn the_double_spherical_pendulum_is_drawn_at_its_joint() {
    let scene = shipped(MODEL);
    let (c, r) = run(scene, &[], "vern9", StepControl::Tolerance(1e-10), 2.0);
    let params = scene.info().default_params();
    let poses = scene.poses(&params, &r);
    assert_eq!(poses.len(), r.len());
    let l1 = param(scene, "l1");
    for (k, (pose, row)) in poses.iter().zip(&r).enumerate() {
        let (r1, r2) = (rotation(&c, row, "upper_"), rotation(&c, row, "lower_"));
        let joint = r1 * Vector3::new(0.0, 0.0, -l1);
        let ((p1, o1), (p2, o2)) = (pose.bodies[0], pose.bodies[1]);
        assert_eq!(o1, [0.0; 3]);
        for i in 0..3 {
            assert!(
                (o2[i] - joint[i]).abs() < 1e-14,
                "row {k}: {o2:?} {joint:?}"
            );
            for j in 0..3 {
                assert!((p1[i][j] - r1[(i, j)]).abs() < 1e-14, "row {k}");
                assert!((p2[i][j] - r2[(i, j)]).abs() < 1e-14, "row {k}");
            }
        }
    }
}
