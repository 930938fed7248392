//! Hostile sweep files: malformed axes, grids too large, unknown metrics, broken TOML. Each is
//! refused before the output folder is made.

use super::Content::{Bytes, Text};
use super::{Case, run_table};

const SWEEP: &[&str] = &["sweep", "s.sweep.toml", "-o", "out", "--check", "off"];

macro_rules! sweep_case {
    ($name:expr, $text:expr, $($fragment:expr),+) => {
        Case::new($name, SWEEP, 1, &[$($fragment),+]).files(&[("s.sweep.toml", Text($text))])
    };
}

pub const CASES: &[Case] = &[
    sweep_case!("sweep file empty", "", "s.sweep.toml", "scene"),
    sweep_case!("sweep not TOML", "[[axes]\n", "s.sweep.toml:1"),
    sweep_case!(
        "sweep scene unknown",
        "scene = \"nope\"\n",
        "s.sweep.toml:1",
        "nope"
    ),
    sweep_case!(
        "sweep without axes",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n",
        "s.sweep.toml",
        "axes"
    ),
    sweep_case!(
        "axis parameter unknown",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"zeta\"\nvalues = [1.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:5",
        "zeta"
    ),
    sweep_case!(
        "axis range reversed",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [6.0, 1.0]\ncount = 3\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:6",
        "range"
    ),
    sweep_case!(
        "axis range with NaN",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [nan, 1.0]\ncount = 3\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:6"
    ),
    sweep_case!(
        "axis count zero",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 2.0]\ncount = 0\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:7",
        "count"
    ),
    sweep_case!(
        "axis count negative",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 2.0]\ncount = -4\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:7",
        "count"
    ),
    sweep_case!(
        "a 10^12-point grid",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 2.0]\ncount = 1000000\n[[axes]]\nparameter = \"alpha0\"\nrange = [0.1, 2.0]\ncount = 1000000\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "points"
    ),
    sweep_case!(
        "log axis through zero",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [0.0, 2.0]\ncount = 3\nspacing = \"log\"\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "log"
    ),
    sweep_case!(
        "axis values empty",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = []\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml:6",
        "values"
    ),
    sweep_case!(
        "axis values and range",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\nrange = [1.0, 2.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "range"
    ),
    sweep_case!(
        "axis repeated",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[[axes]]\nparameter = \"omega0\"\nvalues = [2.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "omega0"
    ),
    sweep_case!(
        "axis value out of the domain",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"a\"\nvalues = [1.0, -1.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "`a`"
    ),
    sweep_case!(
        "metric unknown",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[metrics]\nrecord = [\"happiness\"]\n",
        "s.sweep.toml",
        "happiness"
    ),
    sweep_case!(
        "metric column unknown",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[metrics]\nrecord = [\"max:nowhere\"]\n",
        "s.sweep.toml",
        "nowhere"
    ),
    sweep_case!(
        "metric crossing without a level",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[metrics]\nrecord = [\"first_time:alpha>\"]\n",
        "s.sweep.toml",
        "first_time"
    ),
    sweep_case!(
        "run dt above the horizon",
        "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 5.0\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "dt"
    ),
    sweep_case!(
        "run tol of 2",
        "scene = \"free-hoop\"\n[run]\nintegrator = \"dop853\"\ntol = 2.0\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml",
        "tol"
    ),
    sweep_case!(
        "samples and counts mixed",
        "scene = \"free-hoop\"\nsamples = 5\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 2.0]\ncount = 3\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "s.sweep.toml"
    ),
    sweep_case!(
        "sweep step too coarse at a corner",
        "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\nt_end = 1.0\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 100.0]\ncount = 3\n[[axes]]\nparameter = \"alpha0\"\nvalues = [2.0, 0.5]\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "run.dt = 0.01 does not resolve",
        "point 5 (omega0 = 100, alpha0 = 0.5)",
        "--set run.dt=0.002",
        "--allow-coarse-step"
    ),
    sweep_case!(
        "random sweep step too coarse at a corner",
        "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\nt_end = 1.0\n[[axes]]\nparameter = \"omega0\"\nrange = [1.0, 100.0]\n[random]\nsamples = 1000\nseed = 1\n[metrics]\nrecord = [\"max_tilt\"]\n",
        "a corner of the axes (omega0 = 100)",
        "--set run.dt=0.002"
    ),
    Case::new(
        "sweep point time limit zero",
        &["sweep", "--point-seconds", "0", "-o", "out"],
        1,
        &["--point-seconds 0", "positive"],
    ),
    Case::new(
        "sweep point time limit not a number",
        &["sweep", "--point-seconds", "NaN", "-o", "out"],
        1,
        &["--point-seconds NaN"],
    ),
    Case::new("sweep file binary", SWEEP, 1, &["s.sweep.toml"])
        .files(&[("s.sweep.toml", Bytes(b"\xff\xfe\x00\x00\x01binary"))]),
    Case::new(
        "set an unknown run key",
        &["sweep", "--set", "run.speed=3", "-o", "out"],
        1,
        &["run.speed"],
    ),
    Case::new(
        "set axis values garbage",
        &["sweep", "--set", "axes.omega0.values=[1,,2]", "-o", "out"],
        1,
        &["axes.omega0.values"],
    ),
    sweep_case!(
        "sweep value listed twice",
        "scene = \"free-hoop\"\n[run]\nt_end = 0.1\n[[axes]]\nparameter = \"omega0\"\n\
         values = [1.0, 2.0, 1.0]\n",
        "s.sweep.toml:6",
        "listed twice",
        "values 1 and 3"
    ),
    Case::new(
        "output folder is a file",
        &["sweep", "-o", "taken"],
        1,
        &["taken", "not a directory"],
    )
    .files(&[("taken", Text("a file\n"))]),
];

#[test]
fn hostile_sweep_files() {
    run_table(CASES);
}
