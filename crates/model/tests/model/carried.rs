//! Frames carried by other frames: a frame's `origin` on its parent, and frames carried by an
//! orientation on SO(3) (`satellite-panels-so3`: a bus on SO(3) with two hinged panels),
//! checked against the same systems written another way and against a closed-form relative
//! equilibrium.

use tumble_model::from_text;
use tumble_scenarios::{Scene, StepControl};

use crate::so3::difference;
use crate::support::{column, run, shipped};

/// The shipped double pendulum's point masses placed in frames instead: the upper rod's frame
/// turned by `θ₁` about y, the lower rod's frame carried by it with its `origin` at the upper
/// mass and turned by `θ₂ − θ₁` relative to it. The same Lagrangian, assembled from the frames'
/// rotations and origins, gives the same motion.
#[test]
fn a_frame_placed_on_its_parent_gives_the_double_pendulum_of_positions() {
    let text = r#"
[model]
name = "double-pendulum-frames"

[parameters]
m1 = { default = 1.0, unit = "kg" }
m2 = { default = 1.0, unit = "kg" }
l1 = { default = 1.0, unit = "m" }
l2 = { default = 1.0, unit = "m" }
g = { default = 9.81, unit = "m/s^2" }
theta1_0 = { default = 1.0, unit = "rad" }
theta2_0 = { default = 0.5, unit = "rad" }

[coordinates]
theta1 = { initial = "theta1_0" }
theta2 = { initial = "theta2_0" }

[frames.upper]
rotations = [["y", "-theta1"]]

[frames.lower]
parent = "upper"
origin = ["0", "0", "-l1"]
rotations = [["y", "theta1 - theta2"]]

[points.upper]
mass = "m1"
frame = "upper"
position = ["0", "0", "-l1"]

[points.lower]
mass = "m2"
frame = "lower"
position = ["0", "0", "-l2"]

[lagrangian]
gravity = ["0", "0", "-g"]
"#;
    let frames = from_text(text, "double-pendulum-frames.toml").unwrap();
    let step = StepControl::Fixed(0.01);
    let (fc, fr) = run(frames, &[], "gauss8", step, 3.0);
    let (pc, pr) = run(shipped("double-pendulum"), &[], "gauss8", step, 3.0);
    for name in ["theta1", "theta2", "theta1_dot", "theta2_dot", "energy"] {
        let d = difference(&column(&fc, &fr, name), &column(&pc, &pr, name));
        println!("double pendulum from frames, {name}: {d:.2e}");
        assert!(d <= 1e-11, "`{name}` differs by {d:e}");
    }
}

/// The satellite written with its bus in ZYZ Euler angles, the panels carried by that chain:
/// `φ̇, θ̇, ψ̇` from the bus's initial angular velocity by the inverse of
/// `ω = (−φ̇ sθ cψ + θ̇ sψ, φ̇ sθ sψ + θ̇ cψ, φ̇ cθ + ψ̇)`.
const SATELLITE_EULER: &str = r#"
[model]
name = "satellite-panels-euler"

[parameters]
M = 200.0
I1 = 40.0
I2 = 50.0
I3 = 60.0
m = 10.0
l = 3.0
w = 1.0
d = 0.8
k = 200.0
beta0 = 0.0
beta_init = 0.6
phi0 = 0.3
theta0 = 1.5
psi0 = 1.5
w1 = 0.2
w2 = 1.0
w3 = 0.1

[coordinates]
phi = { initial = "phi0", rate = "(-w1*cos(psi0) + w2*sin(psi0))/sin(theta0)" }
theta = { initial = "theta0", rate = "w1*sin(psi0) + w2*cos(psi0)" }
psi = { initial = "psi0", rate = "w3 - (-w1*cos(psi0) + w2*sin(psi0))/sin(theta0)*cos(theta0)" }
beta = { initial = "beta_init", rate = "0" }

[frames.bus]
euler = "zyz"
angles = ["phi", "theta", "psi"]

[frames.panel1]
parent = "bus"
origin = ["d", "0", "0"]
rotations = [["y", "-beta"]]

[frames.panel2]
parent = "bus"
origin = ["-d", "0", "0"]
rotations = [["y", "pi - beta"]]

[bodies.bus]
frame = "bus"
mass = "M"
inertia = ["I1", "I2", "I3"]

[bodies.panel1]
frame = "panel1"
mass = "m"
com = ["l/2", "0", "0"]
inertia = ["m*w^2/12", "m*l^2/12", "m*(l^2 + w^2)/12"]

[bodies.panel2]
frame = "panel2"
mass = "m"
com = ["l/2", "0", "0"]
inertia = ["m*w^2/12", "m*l^2/12", "m*(l^2 + w^2)/12"]

[lagrangian]
potential = "k*(beta - beta0)^2"

[outputs]
# R = Rz(phi) Ry(theta) Rz(psi): its third column and third row.
n_x = "cos(phi)*sin(theta)"
n_y = "sin(phi)*sin(theta)"
n_z = "cos(theta)"
a_31 = "-sin(theta)*cos(psi)"
a_32 = "sin(theta)*sin(psi)"
"#;

/// The same outputs from the rotation matrix on SO(3).
const SO3_OUTPUTS: &str = r#"
[outputs]
n_x = "bus_R13"
n_y = "bus_R23"
n_z = "bus_R33"
a_31 = "bus_R31"
a_32 = "bus_R32"
"#;

/// The panels carried by a bus on SO(3) move as the panels carried by the bus in Euler angles:
/// two formulations (the bus's angular velocity as state with `Ṙ = R ω̂`, or from the angles'
/// rates; each panel's angular velocity `R_hingeᵀ ω_bus + β̇ e_y` and centre `R_bus (hinge +
/// R_hinge c)` composed from its parent, or differentiated along the chain) agree on the
/// bus's attitude, the hinge angle and its rate, and the energy, over 10 s (the bus tumbles
/// while the panels swing through ±0.6 rad).
#[test]
fn panels_carried_by_an_so3_bus_move_as_in_euler_angles() {
    let so3_text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../models/satellite-panels-so3.toml"),
    )
    .unwrap();
    let (head, _) = so3_text.split_once("[outputs]").unwrap();
    let so3 = from_text(&format!("{head}{SO3_OUTPUTS}"), "satellite-so3.toml").unwrap();
    let euler = from_text(SATELLITE_EULER, "satellite-euler.toml").unwrap();
    let step = StepControl::Tolerance(1e-13);
    let (sc, sr) = run(so3, &[], "vern9", step, 10.0);
    let (ec, er) = run(euler, &[], "vern9", step, 10.0);
    // The runs' adaptive steps differ: compare their final rows.
    let at =
        |c: &[String], r: &[Vec<f64>], name: &str| -> f64 { *column(c, r, name).last().unwrap() };
    let mut worst = 0.0f64;
    for name in [
        "n_x", "n_y", "n_z", "a_31", "a_32", "beta", "beta_dot", "energy",
    ] {
        let (a, b) = (at(&sc, &sr, name), at(&ec, &er, name));
        let d = (a - b).abs() / a.abs().max(1.0);
        println!("satellite at t = 10, {name}: so3 {a:.12} euler {b:.12}, {d:.2e}");
        worst = worst.max(d);
    }
    assert!(worst <= 1e-12, "{worst:e}");
    // The panels did swing and the bus did tumble (no trivial agreement).
    let beta = column(&sc, &sr, "beta");
    let (lo, hi) = beta
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), b| (l.min(*b), h.max(*b)));
    assert!(hi - lo > 0.5, "beta in [{lo}, {hi}]");
}

/// The relative equilibrium of a satellite spinning at `Ω` about the hinge axis (the bus's y,
/// its largest principal axis at every hinge angle): with `I_yy(β) = I₂ + 2 (m l²/12 + m (d² +
/// d l cos β + l²/4))` and `V = k (β − β₀)²`, `∂L/∂β = 0` gives
/// `2 k (β* − β₀) = −Ω² m d l sin β*`: the spin pulls the panels from their rest angle toward
/// the bus's plane. Started there, the hinge angle and the angular velocity stay put; started
/// at the rest angle instead, the panels oscillate about `β*`, reaching `2 (β₀ − β*)` from
/// where they started (to 10 %: the spin changes as they swing).
#[test]
fn a_spinning_satellite_holds_its_panels_at_the_centrifugal_equilibrium() {
    let (m, l, d, k, beta0, spin) = (10.0, 3.0, 0.8, 200.0, 0.5, 1.0);
    // Newton on 2k(β − β₀) + Ω² m d l sin β = 0 (a contraction: 2k ≫ Ω² m d l).
    let mut beta = beta0;
    for _ in 0..50 {
        let f = 2.0 * k * (beta - beta0) + spin * spin * m * d * l * f64::sin(beta);
        let df = 2.0 * k + spin * spin * m * d * l * f64::cos(beta);
        beta -= f / df;
    }
    assert!(
        (beta0 - beta) > 0.02,
        "the equilibrium lies off the rest angle: {beta}"
    );
    let model = shipped("satellite-panels-so3");
    let set = |start: f64| {
        [
            ("beta0", beta0),
            ("beta_init", start),
            ("w1", 0.0),
            ("w2", spin),
            ("w3", 0.0),
        ]
    };
    let step = StepControl::Tolerance(1e-13);
    let (c, r) = run(model, &set(beta), "vern9", step, 20.0);
    let drift = |name: &str, value: f64| {
        column(&c, &r, name)
            .iter()
            .map(|x| (x - value).abs())
            .fold(0.0, f64::max)
    };
    let (db, dw) = (drift("beta", beta), drift("omega_y", spin));
    println!("at beta* = {beta:.12}: beta drifts {db:.2e}, omega_y {dw:.2e}");
    assert!(db < 1e-10 && dw < 1e-10, "{db:e} {dw:e}");
    let (c, r) = run(model, &set(beta0), "vern9", step, 20.0);
    let swing = column(&c, &r, "beta")
        .iter()
        .map(|b| (b - beta0).abs())
        .fold(0.0, f64::max);
    println!(
        "from the rest angle: swings by {swing:.4} (2 (beta0 - beta*) = {:.4})",
        2.0 * (beta0 - beta)
    );
    let expected = 2.0 * (beta0 - beta);
    assert!(
        (swing - expected).abs() < 0.1 * expected,
        "{swing} against {expected}"
    );
}

/// The satellite's mass matrix depends on the hinge angle only (the panels' velocities are
/// written as `ω_bus × x + ẋ` in the bus's axes), so the variational Lie-group methods run
/// it: LGVI conserves its energy to a bounded error, and Lie–Gauss 4 shows its order.
#[test]
fn a_satellite_with_carried_panels_runs_the_lie_group_methods_at_their_orders() {
    let model = shipped("satellite-panels-so3");
    let (c, r) = run(model, &[], "lgvi", StepControl::Fixed(1e-3), 20.0);
    let energy = column(&c, &r, "energy");
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max)
        / energy[0].abs();
    println!("satellite, lgvi at dt = 1e-3 over 20 s: energy error {drift:.2e}");
    assert!(drift < 1e-5, "{drift:e}");
    let (rc, rr) = run(model, &[], "gauss12", StepControl::Fixed(1e-3), 1.0);
    let state = [
        "qw", "qx", "qy", "qz", "beta", "omega_x", "omega_y", "omega_z", "beta_dot",
    ];
    let error = |dt: f64| {
        let (c, r) = run(model, &[], "lie-gauss4", StepControl::Fixed(dt), 1.0);
        state
            .iter()
            .map(|n| {
                (column(&c, &r, n).last().unwrap() - column(&rc, &rr, n).last().unwrap()).abs()
            })
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (error(0.1), error(0.05));
    let observed = (coarse / fine).log2();
    println!("lie-gauss4: {coarse:.2e} at h = 0.1, {fine:.2e} at h/2: order {observed:.2}");
    assert!((observed - 4.0).abs() <= 0.3, "{observed}");
}

/// A model on SO(3) invariant under turning its orientations together about an axis reports
/// the spatial angular momentum about that axis as conserved and writes it as a column:
/// - the satellite (no potential) all three components, equal at t = 0 to
///   `R₀ I(β₀) ω₀` with the system's inertia about its centre summed by hand (the bus's, and
///   each panel's `R_p I_p R_pᵀ + m (|c|² 𝟙 − c cᵀ)` at its centre `c`), and constant over 20 s;
/// - the double spherical pendulum (gravity along z) only `Lz`, equal at every row to the
///   bodies' angular momenta about the pivot written out in the model file (its output `Lz`,
///   renamed here: an output of the name takes the column).
#[test]
fn the_spatial_angular_momentum_of_a_model_on_so3_is_found_and_conserved() {
    use nalgebra::{Matrix3, Rotation3, Vector3};
    let satellite = shipped("satellite-panels-so3");
    let conserved = satellite.info().conserved.join("; ");
    for axis in ["Lx (", "Ly (", "Lz ("] {
        assert!(conserved.contains(axis), "{conserved}");
    }
    let (c, r) = run(satellite, &[], "gauss8", StepControl::Fixed(0.01), 20.0);
    // The bus's centre is the system's: its mass enters no term about it.
    let (i1, i2, i3, m, l, w, d) = (40.0, 50.0, 60.0, 10.0, 3.0, 1.0, 0.8);
    let (beta, phi, theta, psi) = (0.6, 0.3, 1.5, 1.5);
    let plate = Matrix3::from_diagonal(&Vector3::new(
        m * w * w / 12.0,
        m * l * l / 12.0,
        m * (l * l + w * w) / 12.0,
    ));
    let mut inertia = Matrix3::from_diagonal(&Vector3::new(i1, i2, i3));
    for (hinge, turn) in [(d, -beta), (-d, std::f64::consts::PI - beta)] {
        let rp = Rotation3::from_axis_angle(&Vector3::y_axis(), turn).into_inner();
        let centre = Vector3::new(hinge, 0.0, 0.0) + rp * Vector3::new(l / 2.0, 0.0, 0.0);
        inertia += rp * plate * rp.transpose()
            + m * (centre.norm_squared() * Matrix3::identity() - centre * centre.transpose());
    }
    let r0 = Rotation3::from_axis_angle(&Vector3::z_axis(), phi)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), theta)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
    let expected = r0 * (inertia * Vector3::new(0.2, 1.0, 0.1));
    for (k, axis) in ["Lx", "Ly", "Lz"].into_iter().enumerate() {
        let column = column(&c, &r, axis);
        let at_start = (column[0] - expected[k]).abs();
        let drift = column
            .iter()
            .map(|x| (x - column[0]).abs())
            .fold(0.0, f64::max);
        println!(
            "satellite {axis}: {:.12} (by hand {:.12}, {at_start:.1e}), drifts {drift:.1e}",
            column[0], expected[k]
        );
        assert!(at_start <= 1e-12 * expected.norm(), "{axis}: {at_start:e}");
        assert!(drift <= 1e-14 * expected.norm(), "{axis}: {drift:e}");
    }
    // The double spherical pendulum's own `Lz` output takes the name; renamed, both are shown.
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../models/double-spherical-pendulum-so3.toml"),
    )
    .unwrap()
    .replace("\nLz = ", "\nLz_by_hand = ");
    let pendulum = from_text(&text, "double-spherical-pendulum-so3.toml").unwrap();
    let conserved = pendulum.info().conserved.join("; ");
    assert!(
        conserved.contains("Lz (") && !conserved.contains("Lx (") && !conserved.contains("Ly ("),
        "{conserved}"
    );
    let (c, r) = run(pendulum, &[], "gauss8", StepControl::Fixed(5e-3), 20.0);
    let (found, written) = (column(&c, &r, "Lz"), column(&c, &r, "Lz_by_hand"));
    let d = difference(&found, &written);
    println!("double spherical pendulum: Lz against the model's own, {d:.1e}");
    assert!(d <= 1e-13, "{d:e}");
}
