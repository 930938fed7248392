//! `tumble inertia`: mass properties of a closed triangle mesh (OBJ or STL).
//!
//! Prints mass, volume, centre of mass, the inertia tensor about the centre of mass (body
//! frame), the principal moments (ascending) and axes (columns of a right-handed rotation), and
//! the article's ZYZ Euler angles that turn the body into its principal frame. With `--euler`
//! the body is first turned by the given ZYZ angles, and everything is reported for the turned
//! body (tensor `R I Rᵀ`, centre `R c`). `--json` prints one object instead.

use std::path::PathBuf;

use super::args::parse_triple;
use anyhow::{Context, Result};
use nalgebra::{Matrix3, Point3, Vector3};
use serde::Serialize;
use tumble_inertia::{MassProperties, MassSpec, ValidationOptions, load_mesh};

/// Flags of `tumble inertia`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh file: Wavefront OBJ (.obj) or STL (.stl, ASCII or binary), coordinates in metres.
    /// The surface must be closed, consistently oriented with outward normals, and free of
    /// degenerate faces.
    pub file: PathBuf,
    /// Uniform density in kg/m³. If neither --density nor --mass is given, the density is 1
    /// kg/m³ (mass then equals volume).
    #[arg(
        long,
        value_name = "RHO",
        conflicts_with = "mass",
        allow_negative_numbers = true
    )]
    pub density: Option<f64>,
    /// Total mass in kg, spread uniformly (density = mass / volume).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub mass: Option<f64>,
    /// Turn the body by the article's ZYZ Euler angles (radians), R = Rz(φ) Ry(θ) Rz(ψ), and
    /// report the turned body: inertia R I Rᵀ, centre of mass R c.
    #[arg(long, value_name = "PHI,THETA,PSI", allow_hyphen_values = true)]
    pub euler: Option<String>,
    /// Print one JSON object: mass, volume, center_of_mass, inertia (row-major 3×3),
    /// principal_moments (ascending), principal_axes (3×3, columns are the axes),
    /// principal_euler_zyz.
    #[arg(long)]
    pub json: bool,
    /// Accept an inverted mesh (inward-facing normals) by reversing all its faces, with a
    /// note on stderr; without this flag an inverted mesh is an error.
    #[arg(long)]
    pub flip_inverted: bool,
}

/// The `--json` output; field order is the documented key order.
#[derive(Serialize)]
struct Report {
    mass: f64,
    volume: f64,
    center_of_mass: [f64; 3],
    inertia: [[f64; 3]; 3],
    principal_moments: [f64; 3],
    principal_axes: [[f64; 3]; 3],
    principal_euler_zyz: [f64; 3],
}

// `+ 0.0` everywhere below turns −0.0 (from sign flips of exact zeros) into 0.0 for display.

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[(i, j)] + 0.0))
}

fn triple(v: &Vector3<f64>) -> [f64; 3] {
    [v.x + 0.0, v.y + 0.0, v.z + 0.0]
}

fn point(p: &Point3<f64>) -> [f64; 3] {
    triple(&p.coords)
}

/// Parses `PHI,THETA,PSI` (radians, finite; `pi/2`-style expressions accepted).
fn parse_euler(text: &str) -> Result<Vector3<f64>> {
    parse_triple("euler", text)
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let file = args.file.display().to_string();
    let options = ValidationOptions {
        flip_inverted: args.flip_inverted,
        ..ValidationOptions::default()
    };
    let mesh = load_mesh(&args.file, &options)?;
    if mesh.was_flipped() {
        eprintln!(
            "note: {file}: the mesh was inverted (inward normals); its faces were reversed as \
             --flip-inverted asked"
        );
    }
    let (spec, mass_note) = match (args.density, args.mass) {
        (_, Some(mass)) => (MassSpec::TotalMass(mass), "given by --mass"),
        (Some(density), None) => (MassSpec::Density(density), "given by --density"),
        (None, None) => (MassSpec::Density(1.0), "default density 1 kg/m³"),
    };
    let mut body = mesh.mass_properties(spec).with_context(|| match spec {
        MassSpec::Density(rho) => format!("{file}: --density {rho}"),
        MassSpec::TotalMass(m) => format!("{file}: --mass {m}"),
    })?;
    let euler = args.euler.as_deref().map(parse_euler).transpose()?;
    if let Some(angles) = &euler {
        body = body.turned_zyz(angles);
    }
    let principal_euler = body.principal_euler_zyz();
    if args.json {
        let report = Report {
            mass: body.mass(),
            volume: mesh.volume(),
            center_of_mass: point(&body.center_of_mass()),
            inertia: rows(body.inertia()),
            principal_moments: triple(&body.principal().moments),
            principal_axes: rows(body.principal().axes.matrix()),
            principal_euler_zyz: triple(&principal_euler.angles),
        };
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_human(
            &file,
            &body,
            mesh.volume(),
            (mesh.vertices().len(), mesh.faces().len()),
            mass_note,
            euler.as_ref(),
            &principal_euler,
        );
    }
    Ok(())
}

fn sci(x: f64) -> String {
    format!("{:+.9e}", x + 0.0)
}

fn vector(v: &Vector3<f64>) -> String {
    format!("({}, {}, {})", sci(v.x), sci(v.y), sci(v.z))
}

fn print_human(
    file: &str,
    body: &MassProperties,
    volume: f64,
    (vertices, faces): (usize, usize),
    mass_note: &str,
    euler: Option<&Vector3<f64>>,
    principal_euler: &tumble_kinematics::EulerDecomposition<f64>,
) {
    let p = body.principal();
    println!("{file}: closed mesh, {vertices} vertices, {faces} triangles (SI units: m, kg)");
    if let Some(a) = euler {
        println!(
            "turned by ZYZ Euler angles (φ, θ, ψ) = {} rad: R = Rz(φ) Ry(θ) Rz(ψ), \
             inertia R I Rᵀ, centre of mass R c",
            vector(a)
        );
    }
    println!("mass              {} kg ({mass_note})", sci(body.mass()));
    println!("volume            {} m³", sci(volume));
    println!("density           {} kg/m³", sci(body.mass() / volume));
    println!(
        "centre of mass    {} m",
        vector(&body.center_of_mass().coords)
    );
    println!("inertia about the centre of mass (kg·m², body frame):");
    for i in 0..3 {
        let row = body.inertia().row(i).transpose();
        println!("    [{}  {}  {}]", sci(row.x), sci(row.y), sci(row.z));
    }
    println!(
        "principal moments (kg·m², ascending): I1 = {}, I2 = {}, I3 = {}",
        sci(p.moments[0]),
        sci(p.moments[1]),
        sci(p.moments[2])
    );
    println!("principal axes (right-handed, body frame):");
    for k in 0..3 {
        let axis = p.axes.matrix().column(k).into_owned();
        println!("    e{} = {}", k + 1, vector(&axis));
    }
    let a = principal_euler.angles;
    println!(
        "principal frame as ZYZ Euler angles: φ = {}, θ = {}, ψ = {} rad",
        sci(a.x),
        sci(a.y),
        sci(a.z)
    );
    if euler.is_none() {
        println!("    (pass them as --euler to see the off-diagonal terms vanish)");
    } else {
        println!(
            "    (turning the body as reported here by these angles makes its tensor diagonal)"
        );
    }
    if principal_euler.gimbal_lock {
        println!(
            "    gimbal lock: θ is at 0 or π, so only φ ± ψ is determined; the angles above are \
             one valid choice"
        );
    }
}
