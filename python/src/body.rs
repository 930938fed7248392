//! `inertia`: mass properties of a closed triangle mesh, from a file or from arrays.

use std::path::PathBuf;

use nalgebra::{Matrix3, Point3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tumble_inertia::{MassProperties, MassSpec, TriangleMesh, ValidationOptions, load_mesh};

use crate::{refused, value_error};

/// The rows of a 3×3 matrix.
fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[(i, j)]))
}

/// Native-endian `f64` triples from `bytes` (the Python half checked the shape and dtype).
fn points(bytes: &[u8]) -> PyResult<Vec<Point3<f64>>> {
    if !bytes.len().is_multiple_of(24) {
        return Err(PyValueError::new_err(
            "vertices: expected an array of shape (N, 3) of float64",
        ));
    }
    Ok(bytes
        .chunks_exact(24)
        .map(|c| {
            let x = |k: usize| {
                let mut b = [0; 8];
                b.copy_from_slice(&c[8 * k..8 * k + 8]);
                f64::from_ne_bytes(b)
            };
            Point3::new(x(0), x(1), x(2))
        })
        .collect())
}

/// Native-endian `i64` index triples from `bytes`, each index checked to be non-negative.
fn triangles(bytes: &[u8]) -> PyResult<Vec<[usize; 3]>> {
    if !bytes.len().is_multiple_of(24) {
        return Err(PyValueError::new_err(
            "faces: expected an array of shape (M, 3) of integers",
        ));
    }
    bytes
        .chunks_exact(24)
        .enumerate()
        .map(|(row, c)| {
            let mut face = [0usize; 3];
            for k in 0..3 {
                let mut b = [0; 8];
                b.copy_from_slice(&c[8 * k..8 * k + 8]);
                let i = i64::from_ne_bytes(b);
                face[k] = usize::try_from(i).map_err(|_| {
                    PyValueError::new_err(format!(
                        "faces[{row}, {k}] = {i}: a vertex index must be 0 or more"
                    ))
                })?;
            }
            Ok(face)
        })
        .collect()
}

/// Mass properties of a mesh (see the Python docstring of `tumble.inertia`).
#[pyfunction]
#[pyo3(signature = (path=None, vertices=None, faces=None, density=None, mass=None))]
pub(crate) fn inertia<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    vertices: Option<Vec<u8>>,
    faces: Option<Vec<u8>>,
    density: Option<f64>,
    mass: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (mesh, source) = match (path, vertices, faces) {
        (Some(path), None, None) => (
            load_mesh(&path, &ValidationOptions::default()).map_err(refused)?,
            path.display().to_string(),
        ),
        (None, Some(v), Some(f)) => (
            TriangleMesh::try_new(points(&v)?, triangles(&f)?)
                .map_err(|e| value_error(format!("the mesh: {}", crate::message(&e))))?,
            "the mesh".to_string(),
        ),
        _ => {
            return Err(PyValueError::new_err(
                "give a mesh file's path, or vertices and faces",
            ));
        }
    };
    let (spec, what) = match (density, mass) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "density and mass: give one (a uniform density, or the total mass)",
            ));
        }
        (Some(rho), None) => (MassSpec::Density(rho), format!("density={rho}")),
        (None, Some(m)) => (MassSpec::TotalMass(m), format!("mass={m}")),
        (None, None) => (MassSpec::Density(1.0), "density=1".to_string()),
    };
    let part = mesh
        .mass_properties(spec)
        .map_err(|e| value_error(format!("{source}: {what}: {}", crate::message(&e))))?;
    let body = MassProperties::combine_all(&[part]).map_err(refused)?;
    let principal = body.principal();
    let out = PyDict::new(py);
    out.set_item("mass", body.mass())?;
    out.set_item("volume", mesh.volume())?;
    let c = body.center_of_mass();
    out.set_item("center_of_mass", [c.x, c.y, c.z])?;
    out.set_item("inertia", rows(body.inertia()))?;
    out.set_item("principal_moments", <[f64; 3]>::from(principal.moments))?;
    out.set_item("principal_axes", rows(principal.axes.matrix()))?;
    let euler = body.principal_euler_zyz().angles;
    out.set_item("principal_euler_zyz", [euler.x, euler.y, euler.z])?;
    Ok(out)
}
