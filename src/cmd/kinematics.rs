//! `tumble kinematics`: the angular velocity of a body whose orientation is given by Euler angles
//! and their rates, in the space (lab) frame and in the body frame, and the rates recovered from
//! it (or the gimbal-lock singularity reported).
//!
//! The defaults are the start of the article's spinning hoop: the hoop stands vertical
//! (θ = π/2 in the ZYZ convention) and turns about the lab's vertical axis at φ̇ = 5 rad/s.

use anyhow::{Context, Result, bail};
use nalgebra::Vector3;
use tumble_kinematics::EulerConvention;

use super::args::parse_triple;

/// Flags of `tumble kinematics`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Euler convention: a sequence such as zyz, zxz, zyx, xyz (intrinsic by default), or
    /// `extrinsic-xyz`, `intrinsic-zyz`.
    #[arg(long, default_value = "zyz")]
    pub convention: String,
    /// The three angles in rad, comma-separated in the order the convention names them;
    /// `pi`, `pi/2`, `-pi/4`, `2pi/3` are accepted.
    #[arg(long, default_value = "0,pi/2,0", allow_hyphen_values = true)]
    pub angles: String,
    /// The three angle rates in rad/s, comma-separated.
    #[arg(long, default_value = "5,0,0", allow_hyphen_values = true)]
    pub rates: String,
}

fn fmt_vec(v: &Vector3<f64>) -> String {
    format!("({}, {}, {})", fmt_num(v.x), fmt_num(v.y), fmt_num(v.z))
}

/// Twelve decimals, or twelve significant digits in exponent form for large or tiny values.
fn fmt_num(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:+.12e}")
    } else {
        format!("{x:+.12}")
    }
}

/// `|v|` without overflow or underflow of the squares.
fn norm(v: &Vector3<f64>) -> f64 {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        m
    } else {
        m * (v / m).norm()
    }
}

/// Largest |angle| taken: beyond it an angle has lost its fraction of a turn (ulp(1e9) is
/// 1.2e-7 rad).
const MAX_ANGLE: f64 = 1e9;

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let conv: EulerConvention = args
        .convention
        .parse()
        .with_context(|| format!("--convention `{}`", args.convention))?;
    let angles = parse_triple("angles", &args.angles)?;
    let rates = parse_triple("rates", &args.rates)?;
    if let Some(a) = angles.iter().find(|a| a.abs() > MAX_ANGLE) {
        bail!(
            "--angles: {a:e} rad is beyond {MAX_ANGLE:e} rad, where an angle keeps no fraction of a \
             turn; give it modulo 2 pi"
        );
    }
    let r = conv.to_rotation(&angles);
    let w_space = conv.omega_space(&angles, &rates);
    let w_body = conv.omega_body(&angles, &rates);
    if !(w_space.iter().chain(w_body.iter()).all(|w| w.is_finite())) {
        bail!("--rates: the angular velocity overflows double precision; give smaller rates");
    }

    println!("convention     {conv} (active rotation, body frame -> space frame)");
    println!("angles   [rad] {}", fmt_vec(&angles));
    println!("rates  [rad/s] {}", fmt_vec(&rates));
    println!("rotation R     {}", fmt_vec(&r.matrix().row(0).transpose()));
    println!("               {}", fmt_vec(&r.matrix().row(1).transpose()));
    println!("               {}", fmt_vec(&r.matrix().row(2).transpose()));
    println!(
        "omega space    {}  rad/s  (vee(dR/dt R^T))",
        fmt_vec(&w_space)
    );
    println!(
        "omega body     {}  rad/s  (vee(R^T dR/dt) = R^T omega)",
        fmt_vec(&w_body)
    );
    println!(
        "|omega|        {} rad/s",
        fmt_num(norm(&w_space)).trim_start_matches('+')
    );
    match conv.try_rates_from_omega_space(&angles, &w_space) {
        Ok(back) if back.iter().all(|x| x.is_finite()) => println!(
            "rates from omega {}  (max deviation {:.1e})",
            fmt_vec(&back),
            (back - rates).amax()
        ),
        Ok(_) => println!("rates from omega: not recoverable here: the inverse map overflows"),
        Err(e) => println!("rates from omega: not recoverable here: {e}"),
    }
    Ok(())
}
