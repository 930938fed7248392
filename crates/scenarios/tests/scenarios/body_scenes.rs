//! Rigid-body scenes with a `[body]` table: the same body from a mesh and from primitives, a
//! body moved in its file, the T-handle's flip period against the elliptic closed form, the
//! disk-and-rod top against the built-in heavy top, the dumbbell of point masses, and bad bodies.

use std::path::{Path, PathBuf};

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use tumble_inertia::{MassSpec, THandle, shapes};
use tumble_kinematics::EulerConvention;
use tumble_scenarios::scene::Rows;
use tumble_scenarios::scene_file::{SceneFile, SceneFileError};
use tumble_scenarios::scenes::find;
use tumble_scenarios::{Params, RunOptions, StepControl};

/// Columns of the rigid-body rows.
const Q: usize = 1;
const W: usize = 5;

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn run(file: &SceneFile, params: &Params, integrator: &str, dt: f64, t_end: f64) -> Vec<Vec<f64>> {
    let opts = RunOptions {
        integrator: Some(integrator.into()),
        step: Some(StepControl::Fixed(dt)),
        t_end: Some(t_end),
        ..Default::default()
    };
    let mut rows = Rows::default();
    file.scene.run(params, &opts, &mut rows).unwrap();
    rows.0
}

fn rotation(row: &[f64]) -> Matrix3<f64> {
    let q = nalgebra::Quaternion::new(row[Q], row[Q + 1], row[Q + 2], row[Q + 3]);
    *UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .matrix()
}

fn omega(row: &[f64]) -> Vector3<f64> {
    Vector3::new(row[W], row[W + 1], row[W + 2])
}

fn zyz(angles: [f64; 3]) -> Rotation3<f64> {
    EulerConvention::ARTICLE.to_rotation(&Vector3::from(angles))
}

fn set_initial(params: &mut Params, r0: &Rotation3<f64>, w0: &Vector3<f64>) {
    let a = EulerConvention::ARTICLE.from_rotation(r0).angles;
    for (name, value) in [
        ("phi0", a.x),
        ("theta0", a.y),
        ("psi0", a.z),
        ("omega_x0", w0.x),
        ("omega_y0", w0.y),
        ("omega_z0", w0.z),
    ] {
        params.set(name, value).unwrap();
    }
}

#[test]
fn a_box_from_a_mesh_and_from_a_primitive_move_the_same_to_round_off() {
    let dir = tempfile::tempdir().unwrap();
    let sides = Vector3::new(0.3, 0.2, 0.1);
    let mesh = shapes::box_mesh(&sides).unwrap();
    mesh.write_obj(
        std::fs::File::create(dir.path().join("box.obj")).unwrap(),
        "box",
    )
    .unwrap();
    let from_mesh = SceneFile::load(&write(
        dir.path(),
        "mesh.toml",
        "scene = \"free-body\"\n[body]\nmesh = \"box.obj\"\nmass = 2.0\n",
    ))
    .unwrap();
    let from_shape = SceneFile::load(&write(
        dir.path(),
        "shape.toml",
        "scene = \"free-body\"\n[[body.shape]]\nshape = \"box:0.3,0.2,0.1\"\nmass = 2.0\n",
    ))
    .unwrap();
    let (r0, w0) = (zyz([0.3, 1.0, -0.4]), Vector3::new(1.0, 5.0, 0.5));
    let mut a = from_mesh.params.clone();
    let mut b = from_shape.params.clone();
    set_initial(&mut a, &r0, &w0);
    set_initial(&mut b, &r0, &w0);
    let ra = run(&from_mesh, &a, "split4", 1e-3, 5.0);
    let rb = run(&from_shape, &b, "split4", 1e-3, 5.0);
    assert_eq!(ra.len(), rb.len());
    let mut worst = 0.0f64;
    for (x, y) in ra.iter().zip(&rb) {
        worst = worst.max((rotation(x) - rotation(y)).amax());
        worst = worst.max((omega(x) - omega(y)).amax() / w0.norm());
    }
    assert!(worst < 1e-12, "mesh and primitive differ by {worst:e}");
    // The rows are in the body's frame: at t = 0 they are the initial orientation and ω.
    assert!((rotation(&ra[0]) - r0.matrix()).amax() < 1e-15);
    assert!((omega(&ra[0]) - w0).amax() < 1e-14 * w0.norm());
}

#[test]
fn a_mesh_rotated_and_translated_in_its_file_moves_the_same_seen_in_its_own_frame() {
    // The T-handle, and the same solid written turned by G and moved by t. Started in the same
    // physical state (orientation R0 Gᵀ of the moved file's frame, ω' = G ω), the moved body's
    // rows map back: R'(t) G = R(t), Gᵀ ω'(t) = ω(t).
    let dir = tempfile::tempdir().unwrap();
    let handle = THandle::STANDARD.mesh().unwrap();
    let g = zyz([0.7, 1.1, -0.3]);
    let moved = handle
        .transformed(&Isometry3::from_parts(
            Translation3::new(0.5, -1.0, 2.0),
            UnitQuaternion::from_rotation_matrix(&g),
        ))
        .unwrap();
    for (name, mesh) in [("plain.obj", &handle), ("moved.obj", &moved)] {
        mesh.write_obj(std::fs::File::create(dir.path().join(name)).unwrap(), name)
            .unwrap();
    }
    let scene = |mesh: &str| {
        let text = format!("scene = \"free-body\"\n[body]\nmesh = \"{mesh}\"\nmass = 0.05\n");
        SceneFile::load(&write(dir.path(), &format!("{mesh}.toml"), &text)).unwrap()
    };
    let (plain, turned) = (scene("plain.obj"), scene("moved.obj"));
    let (r0, w0) = (zyz([0.2, 0.5, 0.1]), Vector3::new(3.0, 1.0, -2.0));
    let mut a = plain.params.clone();
    let mut b = turned.params.clone();
    set_initial(&mut a, &r0, &w0);
    set_initial(&mut b, &(r0 * g.inverse()), &(g * w0));
    let ra = run(&plain, &a, "split8", 1e-3, 3.0);
    let rb = run(&turned, &b, "split8", 1e-3, 3.0);
    let mut worst = 0.0f64;
    for (x, y) in ra.iter().zip(&rb) {
        worst = worst.max((rotation(y) * g.matrix() - rotation(x)).amax());
        worst = worst.max((g.inverse() * omega(y) - omega(x)).amax() / w0.norm());
    }
    assert!(
        worst < 1e-11,
        "the moved mesh's motion differs by {worst:e}"
    );
}

/// The flip spacing of a torque-free body from the closed form: with `I_a < I_b < I_c`, the
/// component of ω along the intermediate axis is a multiple of `sn(λ t, k)` (Landau &
/// Lifshitz, Mechanics, §37), whose zeros are `2K(k)/λ` apart.
fn half_period(moments: [f64; 3], m: [f64; 3]) -> f64 {
    let [ia, ib, ic] = moments;
    let two_e: f64 = (0..3).map(|i| m[i] * m[i] / moments[i]).sum();
    let d: f64 = m.iter().map(|x| x * x).sum();
    let (k2, lambda) = if d > two_e * ib {
        (
            (ib - ia) * (two_e * ic - d) / ((ic - ib) * (d - two_e * ia)),
            ((ic - ib) * (d - two_e * ia) / (ia * ib * ic)).sqrt(),
        )
    } else {
        (
            (ic - ib) * (d - two_e * ia) / ((ib - ia) * (two_e * ic - d)),
            ((ib - ia) * (two_e * ic - d) / (ia * ib * ic)).sqrt(),
        )
    };
    2.0 * ellip::ellipk(k2).unwrap() / lambda
}

#[test]
fn the_t_handle_mesh_flips_with_the_exact_elliptic_period_to_1e_10() {
    let file = SceneFile::load(&scenes_dir().join("t-handle-flip.toml")).unwrap();
    assert_eq!(file.scene.info().name, "dzhanibekov");
    let params = file.params.clone();
    // The handle's tensor from the closed-form composition of its two boxes (independent of
    // the mesh): x, y, z are principal by symmetry.
    let props = THandle::STANDARD
        .mass_properties(MassSpec::TotalMass(0.05))
        .unwrap();
    let j = props.inertia().diagonal();
    let w0 = Vector3::new(
        params.get("omega_x0").unwrap(),
        params.get("omega_y0").unwrap(),
        params.get("omega_z0").unwrap(),
    );
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| j[a].total_cmp(&j[b]));
    let middle = order[1];
    assert_eq!(middle, 0, "the crossbar x is the intermediate axis");
    let expected = half_period(order.map(|i| j[i]), order.map(|i| j[i] * w0[i]));
    // ω along the intermediate axis at time t, from the scene (exact flow, one step).
    let spin = |t: f64| {
        let rows = run(&file, &params, "exact", t, t);
        omega(rows.last().unwrap())[middle]
    };
    // Sign changes on a coarse grid, then bisection to round-off.
    let rows = run(&file, &params, "exact", 1e-3, 10.0);
    let mut flips = Vec::new();
    for pair in rows.windows(2) {
        let (a, b) = (omega(&pair[0])[middle], omega(&pair[1])[middle]);
        if a.signum() != b.signum() {
            let (mut lo, mut hi, sign_lo) = (pair[0][0], pair[1][0], a.signum());
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if spin(mid).signum() == sign_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            flips.push(0.5 * (lo + hi));
        }
    }
    assert!(flips.len() >= 3, "{} flips in 10 s", flips.len());
    for pair in flips.windows(2) {
        let spacing = pair[1] - pair[0];
        let rel = ((spacing - expected) / expected).abs();
        assert!(
            rel < 1e-10,
            "flip spacing {spacing} vs 2K/λ = {expected}: {rel:e}"
        );
    }
}

#[test]
fn the_disk_and_rod_top_moves_as_the_built_in_top_with_its_closed_form_moments() {
    let file = SceneFile::load(&scenes_dir().join("disk-rod-top.toml")).unwrap();
    let p = &file.params;
    // Closed forms about the pivot: disk (1 kg, R = 0.1, h = 0.01) at 0.2 m, rod (0.1 kg,
    // 0.25 m) from the pivot up.
    let axial = 1.0 * 0.01 / 2.0;
    let transverse = (3.0 * 0.01 + 1e-4) / 12.0 + 0.04 + 0.1 * 0.0625 / 3.0;
    let mgl = 9.81 * (1.0 * 0.2 + 0.1 * 0.125);
    let rel = |x: f64, y: f64| ((x - y) / y).abs();
    assert!(rel(p.get("I1").unwrap(), axial) < 1e-14);
    assert!(rel(p.get("I2").unwrap(), transverse) < 1e-14);
    assert!(rel(p.get("I3").unwrap(), transverse) < 1e-14);
    let weight = p.get("mass").unwrap() * p.get("g").unwrap();
    assert!(rel(weight * p.get("cz").unwrap(), mgl) < 1e-14);
    // The built-in Lagrange top with those moments, tilted 0.3 about lab x, spun at 100 rad/s.
    let builtin = find("heavy-top").unwrap();
    let mut q = builtin.info().default_params();
    for (name, value) in [
        ("I1", transverse),
        ("I2", transverse),
        ("I3", axial),
        ("mgl", mgl),
        ("tilt0", 0.3),
        ("spin0", 100.0),
    ] {
        q.set(name, value).unwrap();
    }
    let opts = RunOptions {
        integrator: Some("gauss8".into()),
        step: Some(StepControl::Fixed(1e-3)),
        t_end: Some(1.0),
        ..Default::default()
    };
    let mut expected = Rows::default();
    builtin.run(&q, &opts, &mut expected).unwrap();
    let rows = run(&file, &file.params, "gauss8", 1e-3, 1.0);
    let mut worst = 0.0f64;
    for (x, y) in rows.iter().zip(&expected.0) {
        worst = worst.max((rotation(x) - rotation(y)).amax());
        worst = worst.max((omega(x) - omega(y)).amax() / 100.0);
    }
    assert!(worst < 1e-10, "the disk-and-rod top differs by {worst:e}");
    assert!(
        (rotation(&rows[0]) - Rotation3::from_axis_angle(&Vector3::x_axis(), 0.3).matrix()).amax()
            < 1e-15
    );
}

#[test]
fn the_dumbbell_of_point_masses_has_its_closed_form_moments_and_follows_the_exact_solution() {
    let file = SceneFile::load(&scenes_dir().join("dumbbell.toml")).unwrap();
    let p = &file.params;
    let moments = [
        2.0 * 0.1 * 0.04f64.powi(2),
        2.0 * 0.15f64.powi(2),
        0.045 + 3.2e-4,
    ];
    for (name, value) in ["I1", "I2", "I3"].iter().zip(moments) {
        let got = p.get(name).unwrap();
        assert!(
            ((got - value) / value).abs() < 1e-14,
            "{name} = {got}, not {value}"
        );
    }
    let rows = run(&file, p, "split4", 1e-3, 5.0);
    let err = file
        .scene
        .info()
        .columns()
        .iter()
        .position(|c| c == "exact_err")
        .unwrap();
    let worst = rows.iter().map(|r| r[err]).fold(0.0f64, f64::max);
    assert!(worst < 1e-6, "distance from the exact solution {worst:e}");
    assert!((omega(&rows[0]) - Vector3::new(3.0, 0.5, 0.2)).amax() < 1e-14);
}

fn fails(dir: &Path, text: &str, key: &str, line: usize, words: &str) {
    let path = write(dir, "bad.toml", text);
    let e = SceneFile::load(&path).unwrap_err();
    let message = e.to_string();
    assert!(
        matches!(e, SceneFileError::Body { .. } | SceneFileError::File(_)),
        "{message}"
    );
    assert!(message.contains(&format!("bad.toml:{line}:")), "{message}");
    assert!(message.contains(key), "{message}");
    assert!(message.contains(words), "{message}");
}

#[test]
fn bad_bodies_name_the_file_the_line_and_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let open = Path::new(env!("CARGO_MANIFEST_DIR")).join("../inertia/tests/data/open.obj");
    fails(
        d,
        &format!(
            "scene = \"free-body\"\n[body]\nmesh = {:?}\nmass = 1.0\n",
            open.display().to_string()
        ),
        "`body.mesh`",
        3,
        "mesh is open",
    );
    fails(
        d,
        "scene = \"free-body\"\n[[body.shape]]\nshape = \"box:1,1,1\"\nmass = -2.0\n",
        "`body.shape[1].mass`",
        4,
        "mass must be positive",
    );
    write(d, "empty.csv", "# no points\n");
    fails(
        d,
        "scene = \"free-body\"\n[body]\npoints = \"empty.csv\"\n",
        "`body.points`",
        3,
        "no point masses",
    );
    fails(
        d,
        "scene = \"free-body\"\n[body]\npoint = []\n",
        "`body.point`",
        2,
        "no point masses",
    );
    fails(
        d,
        "scene = \"free-body\"\n[body]\n",
        "`body`",
        2,
        "has no mass",
    );
    fails(
        d,
        "scene = \"free-body\"\n[[body.shape]]\nshape = \"rod:1\"\nmass = 1.0\n",
        "`body`",
        2,
        "three positive moments",
    );
    fails(
        d,
        "scene = \"free-body\"\n[body]\npoint = [[1, 0, 0, 0], [1, 1, 0, 0]]\n",
        "`body`",
        2,
        "three positive moments",
    );
    fails(
        d,
        "scene = \"heavy-top\"\n[[body.shape]]\nshape = \"sphere:1\"\nmass = 1.0\n",
        "`body.pivot`",
        2,
        "fixed point",
    );
    fails(
        d,
        "scene = \"free-body\"\n[[body.shape]]\nshape = \"sphere:1\"\nmass = 1.0\n[parameters]\nI1 = 2.0\n",
        "`parameters.I1`",
        6,
        "computed from the [body] table",
    );
    fails(
        d,
        "scene = \"free-body\"\n[body]\nmesh = \"t.obj\"\nunits = \"inch\"\nmass = 1.0\n",
        "`body.units`",
        4,
        "inch",
    );
}
