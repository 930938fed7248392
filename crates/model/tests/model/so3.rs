//! Orientations integrated on SO(3) (`orientation = "so3"`): the equations from `T` and `V`
//! alone against the built-in scenes' hand-written Euler–Poincaré equations, the exact
//! free-body flow, and a hoop through the attitude where Euler angles lock.

use tumble_model::from_text;
use tumble_scenarios::scenes::find;
use tumble_scenarios::{Scene, StepControl};

use crate::support::{column, run, shipped};

/// Largest difference of two columns, relative to the larger of 1 and their magnitude.
pub(crate) fn difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "row counts");
    let scale = a.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Every column the two runs share (the state shown as quaternions and body angular
/// velocities, the energy, the tilt) agrees to `tol`.
pub(crate) fn twins(builtin: &str, model: &str, integrator: &str, dt: f64, t_end: f64, tol: f64) {
    let step = StepControl::Fixed(dt);
    let (bc, br) = run(find(builtin).unwrap(), &[], integrator, step, t_end);
    let (mc, mr) = run(shipped(model), &[], integrator, step, t_end);
    let shared: Vec<&String> = mc
        .iter()
        .filter(|c| bc.contains(c) && *c != "energy_rel_err")
        .collect();
    assert!(shared.len() >= 8, "{shared:?}");
    for name in shared {
        let d = difference(&column(&bc, &br, name), &column(&mc, &mr, name));
        println!("{model} {name}: {d:.2e}");
        assert!(d <= tol, "{model} `{name}` differs from {builtin} by {d:e}");
    }
}

/// The hoop and bead on SO(3) × ℝ from their kinetic and potential energy agree with the
/// built-in `free-hoop`'s hand-written equations, column by column, at the same method.
#[test]
fn the_free_hoop_on_so3_from_its_energies_matches_the_builtin() {
    twins("free-hoop", "free-hoop-so3", "gauss8", 0.01, 5.0, 1e-12);
}

/// The heavy top on SO(3) with the potential `mgl R₃₃`: the gravity torque derived from it
/// reproduces the built-in's Euler equations with `mgl Γ × e₃`.
#[test]
fn the_heavy_top_on_so3_from_its_potential_matches_the_builtin() {
    twins("heavy-top", "heavy-top-so3", "gauss12", 1e-3, 2.0, 1e-12);
}

/// A torque-free asymmetric body on SO(3) (the built-in `free-body`'s inertia and initial
/// momentum) follows the exact flow (Jacobi elliptic functions) to the method's accuracy, and
/// conserves its energy and spatial angular momentum.
#[test]
fn a_free_body_on_so3_follows_the_exact_flow() {
    let text = r#"
[model]
name = "free-body-so3"
[parameters]
I1 = 1.0
I2 = 2.0
I3 = 3.0
[frames.body]
orientation = "so3"
omega = ["0.4/I1", "-0.8/I2", "0.6/I3"]
[bodies.body]
frame = "body"
mass = "1"
inertia = ["I1", "I2", "I3"]
[outputs]
Lx = "body_R11*I1*body_omega_x + body_R12*I2*body_omega_y + body_R13*I3*body_omega_z"
[run]
integrator = "vern9"
tol = 1e-13
t_end = 20.0
"#;
    let model = from_text(text, "free-body-so3").unwrap_or_else(|e| panic!("{e}"));
    let tol = StepControl::Tolerance(1e-13);
    let (mc, mr) = run(model, &[], "vern9", tol, 20.0);
    let (bc, br) = run(
        find("free-body").unwrap(),
        &[],
        "exact",
        StepControl::Fixed(20.0),
        20.0,
    );
    let (m_last, b_last) = (mr.last().unwrap(), br.last().unwrap());
    assert_eq!(m_last[0], 20.0);
    assert_eq!(b_last[0], 20.0);
    let at = |c: &[String], r: &[f64], n: &str| r[c.iter().position(|x| x == n).unwrap()];
    let mut worst = 0.0f64;
    for name in ["qw", "qx", "qy", "qz", "omega_x", "omega_y", "omega_z"] {
        worst = worst.max((at(&mc, m_last, name) - at(&bc, b_last, name)).abs());
    }
    println!("free body on SO(3) against the exact flow at t = 20: {worst:.2e}");
    assert!(worst < 1e-10, "{worst:e}");
    let energy = column(&mc, &mr, "energy");
    let lx = column(&mc, &mr, "Lx");
    for (e, l) in energy.iter().zip(&lx) {
        assert!((e - energy[0]).abs() < 1e-12 * energy[0], "energy {e}");
        assert!((l - 0.4).abs() < 1e-11, "L_x {l}");
    }
}

/// Where Euler angles lock (the hoop lying flat: theta = 0 in ZYZ) the Euler-angle model is
/// refused, and the model on SO(3) runs through it, conserving its energy and `L_z`.
#[test]
fn a_flat_hoop_runs_on_so3_where_euler_angles_lock() {
    let flat = [("theta0", 0.0), ("alpha_dot0", 1.0)];
    let mut params = shipped("free-hoop-euler").info().default_params();
    for (k, v) in flat {
        params.set(k, v).unwrap();
    }
    let options = tumble_scenarios::RunOptions {
        t_end: Some(1.0),
        ..Default::default()
    };
    let mut rows = tumble_scenarios::scene::Rows::default();
    let refused = shipped("free-hoop-euler")
        .run(&params, &options, &mut rows)
        .unwrap_err()
        .to_string();
    assert!(refused.contains("singular"), "{refused}");

    let (c, r) = run(
        shipped("free-hoop-so3"),
        &flat,
        "vern9",
        StepControl::Tolerance(1e-12),
        10.0,
    );
    let energy = column(&c, &r, "energy");
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max)
        / energy[0].abs();
    println!(
        "flat hoop on SO(3): energy drift {drift:.2e}, {} rows",
        r.len()
    );
    assert!(drift < 1e-10, "{drift:e}");
    // It started flat (tilt pi/2: the hoop's plane horizontal) and tilted.
    let tilt = column(&c, &r, "tilt");
    assert!((tilt[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert!(tilt.iter().any(|t| *t < 1.5), "{:?}", &tilt[..5]);
}

/// Each mistake in an orientation on SO(3) is refused before any work, naming the key and what
/// to write instead.
#[test]
fn mistakes_in_an_so3_frame_are_refused_with_what_to_write() {
    let model = |frames: &str, coordinates: &str| {
        format!(
            "[model]\nname = \"m\"\n[parameters]\nI = 1.0\nlen = {{ default = 1.0, unit = \"m\" }}\n[coordinates]\n{coordinates}\n{frames}\n\
             [bodies.b]\nframe = \"b\"\nmass = \"1\"\ninertia = [\"I\", \"2*I\", \"3*I\"]\n"
        )
    };
    let one = "x = { initial = \"0\" }";
    for (frames, coordinates, expected) in [
        (
            "[frames.b]\norientation = \"SO3\"",
            one,
            "unknown orientation \"SO3\"; write \"so3\"",
        ),
        (
            "[frames.b]\nangles = [\"0\", \"0\", \"0\"]\nomega = [\"1\", \"0\", \"0\"]",
            one,
            "`frames.b.omega`: is the initial angular velocity of an orientation on SO(3)",
        ),
        (
            "[frames.a]\norientation = \"so3\"\n[frames.b]\norientation = \"so3\"\nparent = \"a\"",
            one,
            "`frames.b.parent`: an orientation on SO(3) turns in the model frame; leave `parent` out",
        ),
        (
            "[frames.a]\norientation = \"so3\"\n[frames.b]\norientation = \"so3\"\n\
             [frames.c]\norientation = \"so3\"\n[frames.d]\norientation = \"so3\"\n\
             [frames.e]\norientation = \"so3\"",
            one,
            "5 frames with orientation = \"so3\" (`a`, `b`, `c`, `d`, `e`): a model may have at most 4",
        ),
        (
            "[frames.b]\nangles = [\"x\", \"0\", \"0\"]\nparent = \"a\"\n[frames.a]\norientation = \"so3\"",
            one,
            "`frames.b.parent`: no frame `a` declared before this one",
        ),
        (
            "[frames.b]\norientation = \"so3\"\nangles = [\"0\", \"0\", \"0\"]\nrotations = [[\"x\", \"1\"]]",
            one,
            "by `angles` or by `rotations`, not both",
        ),
        (
            "[frames.b]\norientation = \"so3\"\nangles = [\"x\", \"0\", \"0\"]",
            one,
            "`frames.b.angles",
        ),
        (
            "[frames.b]\norientation = \"so3\"\nomega = [\"len\", \"0\", \"0\"]",
            one,
            "a rate of turn",
        ),
        (
            "[frames.b]\norientation = \"so3\"",
            "p = { initial = \"0\" }\nq = { initial = \"0\" }\nr = { initial = \"0\" }\ns = { initial = \"0\" }",
            "or 3 beside an orientation on SO(3)",
        ),
    ] {
        let text = model(frames, coordinates);
        let err = from_text(&text, "so3-mistake.toml")
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"))
            .to_string();
        assert!(err.contains(expected), "{err}\n(expected `{expected}`)");
    }
}

/// The T-handle read from the same mesh and turning on SO(3) about its centre of mass agrees
/// with the built-in `dzhanibekov` column by column through its first flip (omega_x changes
/// sign at t = 0.94 s; each flip amplifies round-off, to 3e-12 by t = 4 s).
#[test]
fn the_t_handle_from_its_mesh_on_so3_matches_the_builtin() {
    twins("dzhanibekov", "t-handle-so3", "gauss8", 1e-3, 2.0, 1e-12);
}
