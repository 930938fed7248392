//! Loading meshes from OBJ (`tobj`) and STL (`stl_io`, ASCII and binary) files.
//!
//! Both readers produce a triangle soup that is then indexed by **exact** vertex equality
//! (bitwise, with `−0.0 = 0.0`): files that repeat a vertex per face (STL always does; OBJ
//! files split into objects or groups do) get their shared edges back, so the topology checks
//! of [`TriangleMesh`] see the surface as it is. Nothing is merged by proximity: two vertices a
//! rounding error apart are different vertices, and the mesh will fail validation as open
//! rather than be silently welded.
//!
//! OBJ polygons are split into triangle fans (by `tobj`); points and lines are ignored; all
//! objects and groups of the file are one mesh. OBJ coordinates are read as `f64`. STL
//! coordinates are `f32` by the format and converted exactly; STL facet normals are ignored
//! (orientation comes from the vertex order, as the format specifies). A binary STL whose
//! 80-byte header happens to begin with `solid` (some exporters write that) is recognized by
//! its size, `84 + 50 n` bytes for `n` triangles.

use std::collections::HashMap;
use std::fs;
use std::io::Cursor;
use std::path::Path;

use nalgebra::Point3;

use crate::error::{LoadError, MeshError};
use crate::mesh::{TriangleMesh, ValidationOptions};

/// Mesh file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ.
    Obj,
    /// STL, ASCII or binary.
    Stl,
}

impl MeshFormat {
    /// The format of a file by its extension (`.obj`, `.stl`, any case), if known.
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Self::Obj),
            "stl" => Some(Self::Stl),
            _ => None,
        }
    }
}

/// Loads and validates a mesh, choosing the reader by the file's extension.
///
/// # Errors
/// [`LoadError::UnknownFormat`] for another extension; otherwise as [`load_obj`] / [`load_stl`].
pub fn load_mesh(
    path: impl AsRef<Path>,
    options: &ValidationOptions,
) -> Result<TriangleMesh, LoadError> {
    let path = path.as_ref();
    match MeshFormat::from_path(path) {
        Some(MeshFormat::Obj) => load_obj(path, options),
        Some(MeshFormat::Stl) => load_stl(path, options),
        None => Err(LoadError::UnknownFormat {
            path: path.to_owned(),
        }),
    }
}

/// Loads and validates a Wavefront OBJ mesh.
///
/// # Errors
/// [`LoadError::Io`] if the file cannot be read, [`LoadError::Obj`] if it does not parse,
/// [`LoadError::Mesh`] if the mesh is not a valid closed surface.
pub fn load_obj(
    path: impl AsRef<Path>,
    options: &ValidationOptions,
) -> Result<TriangleMesh, LoadError> {
    let path = path.as_ref();
    let bytes = fs::read(path).map_err(|source| LoadError::Io {
        path: path.to_owned(),
        source,
    })?;
    parse_obj(&bytes, path, options)
}

/// Parses and validates the Wavefront OBJ text `bytes` (read from `path`, named in errors).
///
/// # Errors
/// [`LoadError::Obj`] if it does not parse, [`LoadError::Mesh`] if a face names a vertex that
/// does not exist or the mesh is not a valid closed surface.
pub fn parse_obj(
    bytes: &[u8],
    path: &Path,
    options: &ValidationOptions,
) -> Result<TriangleMesh, LoadError> {
    let load_options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // Materials are irrelevant to mass properties: a missing .mtl must not fail the load.
    let (models, _materials) = tobj::load_obj_buf(&mut Cursor::new(bytes), &load_options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|source| LoadError::Obj {
        path: path.to_owned(),
        source,
    })?;
    let mut soup = Soup::default();
    let mut face = 0;
    for model in &models {
        let positions = &model.mesh.positions;
        for triangle in model.mesh.indices.chunks(3) {
            let mut corners = [Point3::origin(); 3];
            let out_of_range = |index: usize| LoadError::Mesh {
                path: path.to_owned(),
                source: MeshError::VertexIndexOutOfRange {
                    face,
                    index,
                    vertex_count: positions.len() / 3,
                },
            };
            if triangle.len() != 3 {
                return Err(out_of_range(usize::MAX));
            }
            for (corner, &index) in corners.iter_mut().zip(triangle) {
                let index = index as usize;
                let xyz = index
                    .checked_mul(3)
                    .and_then(|k| positions.get(k..k.checked_add(3)?))
                    .ok_or_else(|| out_of_range(index))?;
                *corner = Point3::new(xyz[0], xyz[1], xyz[2]);
            }
            soup.push(corners);
            face += 1;
        }
    }
    soup.into_mesh(path, options)
}

/// Loads and validates an STL mesh (ASCII or binary).
///
/// # Errors
/// [`LoadError::Io`] if the file cannot be read, [`LoadError::Stl`] if it does not parse,
/// [`LoadError::Mesh`] if the mesh is not a valid closed surface.
pub fn load_stl(
    path: impl AsRef<Path>,
    options: &ValidationOptions,
) -> Result<TriangleMesh, LoadError> {
    let path = path.as_ref();
    let bytes = fs::read(path).map_err(|source| LoadError::Io {
        path: path.to_owned(),
        source,
    })?;
    parse_stl(bytes, path, options)
}

/// Parses and validates the STL file `bytes` (ASCII or binary, read from `path`, named in
/// errors).
///
/// # Errors
/// [`LoadError::Stl`] if it does not parse, [`LoadError::Mesh`] if the mesh is not a valid
/// closed surface.
pub fn parse_stl(
    mut bytes: Vec<u8>,
    path: &Path,
    options: &ValidationOptions,
) -> Result<TriangleMesh, LoadError> {
    // Not ASCII (which starts with `solid`): a binary file, whose size its header fixes.
    if !bytes.starts_with(b"solid") && !looks_like_binary_stl(&bytes) {
        let count = bytes
            .get(80..84)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]));
        return Err(LoadError::BinaryStlSize {
            path: path.to_owned(),
            count,
            size: bytes.len() as u64,
        });
    }
    if looks_like_binary_stl(&bytes) && bytes.starts_with(b"solid") {
        // The header is free text that binary readers ignore; blank its first byte so that
        // `stl_io` does not take the file for ASCII.
        bytes[0] = b' ';
    }
    let stl_error = |source| LoadError::Stl {
        path: path.to_owned(),
        source,
    };
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(stl_error)?;
    let mut soup = Soup::default();
    for triangle in reader {
        let triangle = triangle.map_err(stl_error)?;
        soup.push(
            triangle
                .vertices
                .map(|v| Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))),
        );
    }
    soup.into_mesh(path, options)
}

/// Binary STL: 80-byte header, `u32` little-endian triangle count, 50 bytes per triangle.
fn looks_like_binary_stl(bytes: &[u8]) -> bool {
    bytes.len() >= 84 && {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        (bytes.len() - 84) as u64 == 50 * u64::from(count)
    }
}

/// Triangles indexed by exact vertex equality.
#[derive(Default)]
struct Soup {
    vertices: Vec<Point3<f64>>,
    faces: Vec<[usize; 3]>,
    index: HashMap<[u64; 3], usize>,
}

impl Soup {
    fn push(&mut self, corners: [Point3<f64>; 3]) {
        let face = corners.map(|p| {
            // `+ 0.0` maps −0.0 to 0.0; NaNs keep their bits (and fail validation later).
            let key = [p.x, p.y, p.z].map(|x| (x + 0.0).to_bits());
            *self.index.entry(key).or_insert_with(|| {
                self.vertices.push(p);
                self.vertices.len() - 1
            })
        });
        self.faces.push(face);
    }

    fn into_mesh(
        self,
        path: &Path,
        options: &ValidationOptions,
    ) -> Result<TriangleMesh, LoadError> {
        TriangleMesh::try_new_with(self.vertices, self.faces, options).map_err(|source| {
            LoadError::Mesh {
                path: path.to_owned(),
                source,
            }
        })
    }
}
