//! Hostile scene files: not TOML, wrong types, unknown keys, values out of their domains.

use super::Content::{Bytes, Made, Text};
use super::{Case, run_table};

const SIM: &[&str] = &["simulate", "s.toml", "--t-end", "0.1"];

macro_rules! scene_case {
    ($name:expr, $text:expr, $($fragment:expr),+) => {
        Case::new($name, SIM, 1, &[$($fragment),+]).files(&[("s.toml", Text($text))])
    };
}

fn huge_scene() -> Vec<u8> {
    let mut text = String::from("scene = \"free-body\"\n[parameters]\n");
    text.push_str(&format!("# {}\n", "x".repeat(2_000_000)));
    text.push_str("I1 = \"one\"\n");
    text.into_bytes()
}

pub const CASES: &[Case] = &[
    Case::new(
        "scene file missing",
        &["simulate", "gone.toml"],
        1,
        &["gone.toml"],
    ),
    scene_case!("scene file empty", "", "s.toml", "scene"),
    scene_case!("scene file not TOML", "scene = = 1\n", "s.toml:1"),
    scene_case!(
        "scene unknown",
        "scene = \"warp-drive\"\n",
        "s.toml:1",
        "warp-drive"
    ),
    scene_case!("scene not a string", "scene = 3\n", "s.toml:1", "scene"),
    scene_case!(
        "unknown top-level key",
        "scene = \"free-body\"\ncolour = \"red\"\n",
        "s.toml:2",
        "colour"
    ),
    scene_case!(
        "unknown parameter",
        "scene = \"free-body\"\n[parameters]\nI7 = 1.0\n",
        "s.toml:3",
        "I7"
    ),
    scene_case!(
        "parameter a string",
        "scene = \"free-body\"\n[parameters]\nI1 = \"one\"\n",
        "s.toml:3",
        "I1"
    ),
    scene_case!(
        "parameter nan",
        "scene = \"free-body\"\n[parameters]\nI1 = nan\n",
        "s.toml:3",
        "I1"
    ),
    scene_case!(
        "parameter inf",
        "scene = \"free-body\"\n[parameters]\nm1 = inf\n",
        "s.toml:3",
        "m1"
    ),
    scene_case!(
        "parameter negative",
        "scene = \"free-hoop\"\n[parameters]\na = -1.0\n",
        "s.toml:3",
        "`a`"
    ),
    scene_case!(
        "parameter an array",
        "scene = \"free-body\"\n[parameters]\nI1 = [1, 2]\n",
        "s.toml:3",
        "I1"
    ),
    scene_case!(
        "parameters not a table",
        "scene = \"free-body\"\nparameters = 5\n",
        "s.toml:2",
        "parameters"
    ),
    scene_case!(
        "bead mass zero",
        "scene = \"free-hoop\"\n[parameters]\nm = 0.0\n",
        "s.toml:3",
        "`m`"
    ),
    scene_case!(
        "run dt and tol",
        "scene = \"free-body\"\n[run]\ndt = 0.01\ntol = 1e-8\n",
        "s.toml",
        "tol"
    ),
    scene_case!(
        "run dt negative",
        "scene = \"free-body\"\n[run]\ndt = -0.01\n",
        "s.toml:3",
        "dt"
    ),
    scene_case!(
        "run every a fraction",
        "scene = \"free-body\"\n[run]\nevery = 2.5\n",
        "s.toml:3",
        "every"
    ),
    scene_case!(
        "run every zero",
        "scene = \"free-body\"\n[run]\nevery = 0\n",
        "s.toml:3",
        "every"
    ),
    scene_case!(
        "run integrator unknown",
        "scene = \"free-body\"\n[run]\nintegrator = \"magic\"\n",
        "s.toml:3",
        "magic"
    ),
    scene_case!(
        "run unknown key",
        "scene = \"free-body\"\n[run]\nspeed = 2\n",
        "s.toml:3",
        "speed"
    ),
    scene_case!(
        "run at not increasing",
        "scene = \"free-body\"\n[run]\nintegrator = \"dop853\"\nat = [0.05, 0.01]\n",
        "s.toml:4",
        "at"
    ),
    scene_case!(
        "run t_end zero",
        "scene = \"free-body\"\n[run]\nt_end = 0\n",
        "s.toml:3",
        "t_end"
    ),
    scene_case!(
        "body on a hoop",
        "scene = \"free-hoop\"\n[body]\nmesh = \"x.obj\"\n",
        "s.toml:2",
        "body"
    ),
    scene_case!(
        "body mesh missing",
        "scene = \"dzhanibekov\"\n[body]\nmesh = \"nowhere.obj\"\n",
        "s.toml:3",
        "body.mesh",
        "nowhere.obj"
    ),
    Case::new("scene file binary", SIM, 1, &["s.toml"])
        .files(&[("s.toml", Bytes(b"\x00\xff\xfe\x00garbage\x89PNG"))]),
    Case::new(
        "scene file with a 2 MB comment",
        SIM,
        1,
        &["s.toml:4", "I1"],
    )
    .files(&[("s.toml", Made(huge_scene))]),
    Case::new(
        "scene file is a folder",
        &["simulate", "d.toml"],
        1,
        &["d.toml"],
    )
    .files(&[("d.toml/inner", Text(""))]),
    // Not UTF-8: the byte, its line and column.
    Case::new(
        "scene file not UTF-8",
        SIM,
        1,
        &[
            "s.toml",
            "not UTF-8 text",
            "byte 0xE9 at line 2, column 6",
            "save it as UTF-8",
        ],
    )
    .files(&[("s.toml", Bytes(b"scene = \"free-body\"\n# caf\xe9\n"))]),
    // A [body] with no initial angular velocity: the parameters the user writes are named.
    scene_case!(
        "body scene file without an angular velocity",
        "scene = \"free-body\"\n[[body.shape]]\nshape = \"box:1,2,3\"\nmass = 1.0\n",
        "omega_x0, omega_y0, omega_z0",
        "omega_z0 = 1.0"
    ),
    scene_case!(
        "run every and at together",
        "scene = \"free-body\"\n[run]\nevery = 2\nat = [0.05]\n",
        "s.toml:4",
        "`run.at` and `run.every` both choose which rows"
    ),
];

#[test]
fn hostile_scene_files() {
    run_table(CASES);
}
