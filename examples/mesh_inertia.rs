//! Mass properties of closed triangle meshes, checked against closed forms.
//!
//! 1. A regular tetrahedron from its four vertices: volume `a³/(6√2)` and, about its centroid,
//!    an isotropic inertia tensor `I = M a²/20 · 𝟙` for edge `a` and mass `M`.
//! 2. The same tetrahedron read from Wavefront OBJ text: the same numbers, bit for bit.
//! 3. A 1 × 2 × 3 box mesh turned by an arbitrary rotation and moved off the origin: its
//!    principal moments are the box formula's `M (b² + c²)/12, …`, its principal axes the
//!    rotated box edges, its centre of mass the offset.
//!
//! Run: `cargo run --example mesh_inertia`. It exits non-zero if a check fails.

use std::error::Error;
use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use tumble_inertia::{MassSpec, TriangleMesh, ValidationOptions, parse_obj, shapes};

fn check(what: &str, error: f64, bound: f64) -> Result<(), Box<dyn Error>> {
    println!("  {what}: {error:.1e}");
    if error > bound {
        return Err(format!("{what} is {error:e}, beyond {bound:e}").into());
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    // 1. Alternate corners of the cube [-1, 1]³: edge 2√2, outward-oriented faces.
    let vertices = vec![
        Point3::new(1.0, 1.0, 1.0),
        Point3::new(1.0, -1.0, -1.0),
        Point3::new(-1.0, 1.0, -1.0),
        Point3::new(-1.0, -1.0, 1.0),
    ];
    let faces = vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    let tetrahedron = TriangleMesh::try_new(vertices, faces)?;
    let density = 2700.0; // aluminium, kg/m³
    let props = tetrahedron.mass_properties(MassSpec::Density(density))?;
    let edge = 2.0 * 2.0_f64.sqrt();
    let volume = edge.powi(3) / (6.0 * 2.0_f64.sqrt());
    let expected = Matrix3::identity() * props.mass() * edge * edge / 20.0;
    println!(
        "regular tetrahedron, edge {edge:.6} m, {density} kg/m³: mass {:.6} kg",
        props.mass()
    );
    check(
        "relative volume error",
        (tetrahedron.volume() - volume).abs() / volume,
        1e-15,
    )?;
    check(
        "centre of mass distance from 0 (m)",
        props.center_of_mass().coords.norm(),
        1e-15,
    )?;
    check(
        "relative inertia error against M a²/20",
        (props.inertia() - expected).norm() / expected.norm(),
        1e-14,
    )?;

    // 2. The same solid from an OBJ file's text.
    let obj = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
    let from_obj = parse_obj(
        obj.as_bytes(),
        Path::new("tetrahedron.obj"),
        &ValidationOptions::default(),
    )?
    .mass_properties(MassSpec::Density(density))?;
    println!("the same tetrahedron from OBJ text:");
    check(
        "largest difference of the tensors (kg·m²)",
        (from_obj.inertia() - props.inertia()).amax(),
        0.0,
    )?;

    // 3. A box turned and moved: the principal frame undoes the turn.
    let sides = Vector3::new(1.0, 2.0, 3.0);
    let mass = 6.0;
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, -1.1, 0.7));
    let offset = Vector3::new(0.5, -2.0, 3.0);
    let placed = shapes::box_mesh(&sides)?
        .transformed(&Isometry3::from_parts(Translation3::from(offset), turn))?;
    let box_props = placed.mass_properties(MassSpec::TotalMass(mass))?;
    let (a, b, c) = (sides.x, sides.y, sides.z);
    let moments = Vector3::new(b * b + c * c, a * a + c * c, a * a + b * b) * mass / 12.0;
    let mut ascending = moments;
    ascending.as_mut_slice().sort_by(f64::total_cmp);
    let principal = box_props.principal();
    println!("a 1 × 2 × 3 m box of {mass} kg, turned and moved:");
    println!(
        "  principal moments {:.12?} kg·m²",
        principal.moments.as_slice()
    );
    check(
        "relative error of the principal moments",
        (principal.moments - ascending).norm() / ascending.norm(),
        1e-14,
    )?;
    check(
        "centre of mass error (m)",
        (box_props.center_of_mass().coords - offset).norm(),
        1e-14,
    )?;
    // Each principal axis is ± a turned box edge; the box's moments are distinct, so axis k
    // belongs to the edge whose moment is the k-th smallest.
    let edges = turn.to_rotation_matrix();
    let mut axis_error: f64 = 0.0;
    for (k, moment) in principal.moments.iter().enumerate() {
        let edge_index = (0..3)
            .min_by(|&i, &j| {
                (moments[i] - moment)
                    .abs()
                    .total_cmp(&(moments[j] - moment).abs())
            })
            .unwrap_or(0);
        let cosine = principal
            .axes
            .matrix()
            .column(k)
            .dot(&edges.matrix().column(edge_index));
        axis_error = axis_error.max(1.0 - cosine.abs());
    }
    check(
        "largest 1 − |cos| between principal axes and turned edges",
        axis_error,
        1e-14,
    )?;
    Ok(())
}
