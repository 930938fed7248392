//! `tumble inertia`: mass properties of a body assembled from closed triangle meshes (OBJ or
//! STL), point masses and primitives.
//!
//! Prints mass, volume, centre of mass, the inertia tensor about the centre of mass (body
//! frame), the principal moments (ascending) and axes (columns of a right-handed rotation), and
//! the article's ZYZ Euler angles that turn the body into its principal frame. `--json` prints
//! one object instead.
//!
//! Sources, all combined into one rigid body: mesh files (positional, in `--units`, with
//! `--density` or `--mass`), point masses (`--point m,x,y,z`, `--points FILE.csv`) and shapes
//! (`--shape box:a,b,c` …). The flags `--mass`, `--density`, `--at` and `--euler` that follow a
//! `--shape` belong to it (its mass, where its centre goes, its ZYZ turn about its centre);
//! before the first `--shape`, `--mass`/`--density` give the meshes' mass and `--euler` turns the
//! whole body (everything is then reported for the turned body: tensor `R I Rᵀ`, centre `R c`).

use std::path::PathBuf;

use super::args::parse_triple;
use anyhow::{Context, Result, bail};
use clap::ArgMatches;
use nalgebra::{Matrix3, Point3, Vector3};
use serde::Serialize;
use tumble_inertia::{
    MassProperties, MassSpec, Placement, Shape, Units, ValidationOptions, load_mesh, parse_points,
};
use tumble_scenarios::drawing::Part;

/// Flags of `tumble inertia`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh files: Wavefront OBJ (.obj) or STL (.stl, ASCII or binary), coordinates in
    /// --units. Each surface must be closed, consistently oriented with outward normals, and
    /// free of degenerate faces.
    #[arg(value_name = "FILE")]
    pub files: Vec<PathBuf>,
    #[command(flatten)]
    pub body: BodyArgs,
    /// Print one JSON object: mass, volume, center_of_mass, inertia (row-major 3×3),
    /// principal_moments (ascending), principal_axes (3×3, columns are the axes),
    /// principal_euler_zyz.
    #[arg(long)]
    pub json: bool,
}

/// The flags that describe a body besides its mesh files (shared with `tumble view --inertia`).
#[derive(clap::Args, Debug)]
pub struct BodyArgs {
    /// Length unit of the mesh files' coordinates (densities stay in kg/m³).
    #[arg(long, value_name = "mm|cm|m", default_value = "m")]
    pub units: String,
    /// Uniform density in kg/m³: of the meshes, or of the --shape it follows. If the meshes
    /// have neither --density nor --mass, their density is 1 kg/m³ (mass then equals volume).
    #[arg(long, value_name = "RHO", allow_negative_numbers = true, action = clap::ArgAction::Append)]
    pub density: Vec<f64>,
    /// Total mass in kg, spread uniformly: of the meshes (all of them together), or of the
    /// --shape it follows.
    #[arg(long, value_name = "M", allow_negative_numbers = true, action = clap::ArgAction::Append)]
    pub mass: Vec<f64>,
    /// ZYZ Euler angles (radians), R = Rz(φ) Ry(θ) Rz(ψ): after a --shape, the shape's turn
    /// about its centre; before any --shape, the whole body is turned and reported turned
    /// (inertia R I Rᵀ, centre of mass R c).
    #[arg(long, value_name = "PHI,THETA,PSI", allow_hyphen_values = true, action = clap::ArgAction::Append)]
    pub euler: Vec<String>,
    /// A primitive part: box:a,b,c, cylinder:r,h, sphere:r, torus:R,r, hoop:r, rod:l (metres;
    /// symmetry axis z, centred), followed by its --mass or --density (hoop and rod: --mass)
    /// and optionally --at and --euler. Repeatable.
    #[arg(long, value_name = "KIND:DIMS", action = clap::ArgAction::Append)]
    pub shape: Vec<String>,
    /// Where the centre of the --shape it follows goes (metres, body frame).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, action = clap::ArgAction::Append)]
    pub at: Vec<String>,
    /// A point mass: mass in kg and position in metres. Repeatable.
    #[arg(long, value_name = "M,X,Y,Z", allow_hyphen_values = true, action = clap::ArgAction::Append)]
    pub point: Vec<String>,
    /// A CSV file of point masses, one `m,x,y,z` a line (kg, m); `#` comments and a header
    /// line `m,x,y,z` are allowed. Repeatable.
    #[arg(long, value_name = "FILE.csv", action = clap::ArgAction::Append)]
    pub points: Vec<PathBuf>,
    /// Accept an inverted mesh (inward-facing normals) by reversing all its faces, with a
    /// note on stderr; without this flag an inverted mesh is an error.
    #[arg(long)]
    pub flip_inverted: bool,
}

impl BodyArgs {
    /// Whether any flag was given (the units left at their default).
    pub fn any(&self) -> bool {
        !(self.density.is_empty()
            && self.mass.is_empty()
            && self.euler.is_empty()
            && self.shape.is_empty()
            && self.at.is_empty()
            && self.point.is_empty()
            && self.points.is_empty()
            && !self.flip_inverted
            && self.units == "m")
    }
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

/// A `--shape` with the flags that follow it.
#[derive(Default)]
struct ShapeFlags {
    spec: String,
    mass: Option<f64>,
    density: Option<f64>,
    at: Option<String>,
    euler: Option<String>,
}

/// The flags as the command line orders them: those before the first `--shape` (the meshes'
/// mass and the whole body's turn), and each shape with the flags that follow it.
pub(crate) struct Ordered {
    mesh_mass: Option<f64>,
    mesh_density: Option<f64>,
    pub(crate) turn: Option<String>,
    shapes: Vec<ShapeFlags>,
}

/// Sorts the repeatable flags by their position on the command line.
pub(crate) fn ordered(args: &BodyArgs, matches: Option<&ArgMatches>) -> Result<Ordered> {
    let indices = |id: &str, n: usize| -> Vec<usize> {
        matches
            .and_then(|m| m.indices_of(id))
            .map_or_else(|| (0..n).collect(), Iterator::collect)
    };
    let shape_at = indices("shape", args.shape.len());
    // The shape a flag at command-line index `i` follows, if any.
    let owner = |i: usize| shape_at.iter().rposition(|&s| s < i);
    let mut out = Ordered {
        mesh_mass: None,
        mesh_density: None,
        turn: None,
        shapes: args
            .shape
            .iter()
            .map(|spec| ShapeFlags {
                spec: spec.clone(),
                ..ShapeFlags::default()
            })
            .collect(),
    };
    fn put<T: Clone>(slot: &mut Option<T>, value: &T, what: &str) -> Result<()> {
        if slot.is_some() {
            bail!("{what} is given twice");
        }
        *slot = Some(value.clone());
        Ok(())
    }
    for (value, i) in args.mass.iter().zip(indices("mass", args.mass.len())) {
        match owner(i) {
            Some(k) => put(
                &mut out.shapes[k].mass,
                value,
                &format!("--shape {}: --mass", args.shape[k]),
            )?,
            None => put(&mut out.mesh_mass, value, "--mass (of the meshes)")?,
        }
    }
    for (value, i) in args
        .density
        .iter()
        .zip(indices("density", args.density.len()))
    {
        match owner(i) {
            Some(k) => put(
                &mut out.shapes[k].density,
                value,
                &format!("--shape {}: --density", args.shape[k]),
            )?,
            None => put(&mut out.mesh_density, value, "--density (of the meshes)")?,
        }
    }
    for (value, i) in args.euler.iter().zip(indices("euler", args.euler.len())) {
        match owner(i) {
            Some(k) => put(
                &mut out.shapes[k].euler,
                value,
                &format!("--shape {}: --euler", args.shape[k]),
            )?,
            None => put(&mut out.turn, value, "--euler (turning the whole body)")?,
        }
    }
    for (value, i) in args.at.iter().zip(indices("at", args.at.len())) {
        match owner(i) {
            Some(k) => put(
                &mut out.shapes[k].at,
                value,
                &format!("--shape {}: --at", args.shape[k]),
            )?,
            None => bail!(
                "--at {value}: --at places the --shape it follows, and no --shape comes before it"
            ),
        }
    }
    if out.mesh_mass.is_some() && out.mesh_density.is_some() {
        bail!("--mass and --density both given for the meshes; give one");
    }
    Ok(out)
}

/// The assembled body, the volume of its solid parts and a description of its sources.
pub(crate) struct Assembled {
    pub(crate) body: MassProperties,
    volume: f64,
    pub(crate) sources: Vec<String>,
    mass_note: String,
    /// The parts as given, in the body's frame (before the whole body's --euler turn), to draw.
    pub(crate) parts: Vec<Part>,
}

/// Reads and validates every source, then combines them.
pub(crate) fn assemble(files: &[PathBuf], args: &BodyArgs, flags: &Ordered) -> Result<Assembled> {
    let units: Units = args
        .units
        .parse()
        .map_err(|e| anyhow::anyhow!("--units: {e}"))?;
    let options = ValidationOptions {
        flip_inverted: args.flip_inverted,
        ..ValidationOptions::default()
    };
    let mut parts = Vec::new();
    let mut sources = Vec::new();
    let mut drawn = Vec::new();
    let mut volume = 0.0;
    // Meshes: one material; a total mass is spread over their total volume.
    let mut meshes = Vec::new();
    for path in files {
        let file = path.display().to_string();
        let mesh = load_mesh(path, &options)?;
        if mesh.was_flipped() {
            eprintln!(
                "note: {file}: the mesh was inverted (inward normals); its faces were reversed                  as --flip-inverted asked"
            );
        }
        let mesh = mesh
            .scaled(units.metres())
            .with_context(|| format!("{file}: --units {units}"))?;
        sources.push(format!(
            "{file}: closed mesh, {} vertices, {} triangles ({units})",
            mesh.vertices().len(),
            mesh.faces().len()
        ));
        meshes.push((file, mesh));
    }
    let mesh_volume: f64 = meshes.iter().map(|(_, m)| m.volume()).sum();
    let (spec, mass_note) = match (flags.mesh_density, flags.mesh_mass) {
        (_, Some(mass)) if meshes.len() > 1 => (
            MassSpec::Density(mass / mesh_volume),
            "given by --mass, spread over the meshes".to_string(),
        ),
        (_, Some(mass)) => (MassSpec::TotalMass(mass), "given by --mass".to_string()),
        (Some(density), None) => (MassSpec::Density(density), "given by --density".to_string()),
        (None, None) => (
            MassSpec::Density(1.0),
            if meshes.is_empty() {
                "the sum of the parts".to_string()
            } else {
                "default density 1 kg/m³".to_string()
            },
        ),
    };
    if meshes.is_empty() && (flags.mesh_mass.is_some() || flags.mesh_density.is_some()) {
        bail!(
            "--mass/--density before any --shape give the meshes' mass, but no mesh file is              given; put them after the --shape they belong to"
        );
    }
    for (file, mesh) in &meshes {
        volume += mesh.volume();
        drawn.push(Part::Mesh(mesh.clone()));
        parts.push(
            mesh.mass_properties(spec)
                .with_context(|| match (spec, flags.mesh_mass) {
                    (_, Some(m)) => format!("{file}: --mass {m}"),
                    (MassSpec::Density(rho), None) => format!("{file}: --density {rho}"),
                    (MassSpec::TotalMass(m), None) => format!("{file}: --mass {m}"),
                })?,
        );
    }
    // Point masses, each file and flag checked and named.
    let mut points = Vec::new();
    for path in &args.points {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).with_context(|| format!("{file}: cannot read"))?;
        let read = parse_points(&text).with_context(|| file.clone())?;
        if read.is_empty() {
            bail!("{file}: no point masses (one `m,x,y,z` a line)");
        }
        sources.push(format!("{file}: {} point masses", read.len()));
        points.extend(read);
    }
    for raw in &args.point {
        let read = parse_points(raw).map_err(|e| match e {
            tumble_inertia::BodyError::PointLine { reason, .. } => {
                anyhow::anyhow!("--point {raw}: {reason}")
            }
            other => anyhow::anyhow!("--point {raw}: {other}"),
        })?;
        if read.len() != 1 {
            bail!("--point {raw}: expected one point `m,x,y,z`");
        }
        points.extend(read);
    }
    if !args.point.is_empty() {
        sources.push(format!("{} point mass(es) from --point", args.point.len()));
    }
    if !points.is_empty() {
        parts.push(MassProperties::from_point_masses(&points).context("point masses")?);
        drawn.push(Part::Points(points));
    }
    // Shapes, placed.
    for s in &flags.shapes {
        let what = format!("--shape {}", s.spec);
        let shape = Shape::parse(&s.spec).with_context(|| what.clone())?;
        let spec = match (s.mass, s.density) {
            (Some(m), None) => MassSpec::TotalMass(m),
            (None, Some(rho)) => MassSpec::Density(rho),
            (Some(_), Some(_)) => bail!("{what}: both --mass and --density follow it; give one"),
            (None, None) => {
                bail!("{what}: give its --mass (or, for a solid, its --density) after it")
            }
        };
        let placement = Placement {
            at: s
                .at
                .as_deref()
                .map(|t| parse_triple("at", t))
                .transpose()
                .with_context(|| what.clone())?
                .unwrap_or_default(),
            euler: s
                .euler
                .as_deref()
                .map(|t| parse_triple("euler", t))
                .transpose()
                .with_context(|| what.clone())?
                .unwrap_or_default(),
        };
        let props = shape.mass_properties(spec).with_context(|| what.clone())?;
        volume += shape.volume().unwrap_or(0.0);
        parts.push(placement.place(&props));
        drawn.push(Part::Shape(shape, placement));
        sources.push(what);
    }
    if parts.is_empty() {
        bail!("no body given: name mesh files, or give --point, --points or --shape (see --help)");
    }
    let mut body = MassProperties::combine_all(&parts).context("combining the parts")?;
    if let Some(turn) = &flags.turn {
        body = body.turned_zyz(&parse_triple("euler", turn)?);
    }
    let mass_note = if parts.len() > 1 && !meshes.is_empty() {
        format!("meshes: {mass_note}; with the other parts")
    } else {
        mass_note
    };
    Ok(Assembled {
        body,
        volume,
        sources,
        mass_note,
        parts: drawn,
    })
}

/// Runs the subcommand; `matches` orders the flags that follow a `--shape`.
pub fn run(args: &Args, matches: Option<&ArgMatches>) -> Result<()> {
    // Flags in the wrong place or given twice are usage errors, reported as clap reports its
    // own (exit code 2).
    let flags = ordered(&args.body, matches).unwrap_or_else(|e| {
        clap::Error::raw(clap::error::ErrorKind::ArgumentConflict, format!("{e}\n")).exit()
    });
    let turn = flags
        .turn
        .as_deref()
        .map(|t| parse_triple("euler", t))
        .transpose()?;
    let Assembled {
        body,
        volume,
        sources,
        mass_note,
        ..
    } = assemble(&args.files, &args.body, &flags)?;
    let principal_euler = body.principal_euler_zyz();
    if args.json {
        let report = Report {
            mass: body.mass(),
            volume,
            center_of_mass: point(&body.center_of_mass()),
            inertia: rows(body.inertia()),
            principal_moments: triple(&body.principal().moments),
            principal_axes: rows(body.principal().axes.matrix()),
            principal_euler_zyz: triple(&principal_euler.angles),
        };
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_human(
            &sources,
            &body,
            volume,
            &mass_note,
            turn.as_ref(),
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
    sources: &[String],
    body: &MassProperties,
    volume: f64,
    mass_note: &str,
    euler: Option<&Vector3<f64>>,
    principal_euler: &tumble_kinematics::EulerDecomposition<f64>,
) {
    let p = body.principal();
    for source in sources {
        println!("{source}");
    }
    println!("(SI units below: m, kg)");
    if let Some(a) = euler {
        println!(
            "turned by ZYZ Euler angles (φ, θ, ψ) = {} rad: R = Rz(φ) Ry(θ) Rz(ψ), \
             inertia R I Rᵀ, centre of mass R c",
            vector(a)
        );
    }
    println!("mass              {} kg ({mass_note})", sci(body.mass()));
    println!("volume            {} m³ (of the solid parts)", sci(volume));
    if sources.len() == 1 && volume > 0.0 {
        println!("density           {} kg/m³", sci(body.mass() / volume));
    }
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
