//! Hostile meshes for `tumble inertia` and a scene's `[body]`: empty, binary garbage,
//! non-finite or huge coordinates, open and non-manifold surfaces, faces naming missing
//! vertices, STL headers that lie.

use super::Content::{Bytes, Made, Text};
use super::{Case, run_table};

const TETRA: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

/// A binary STL: 80-byte header, a triangle count, 50 bytes a triangle.
fn binary_stl(count: u32, triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&count.to_le_bytes());
    for t in triangles {
        out.extend_from_slice(&[0u8; 12]);
        for v in t {
            for c in v {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

fn stl_lying_count() -> Vec<u8> {
    binary_stl(
        4_000_000_000,
        &[[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]],
    )
}

/// A closed tetrahedron (four triangles) whose header counts five.
fn stl_wrong_count() -> Vec<u8> {
    let a = [0.0, 0.0, 0.0];
    let b = [1.0, 0.0, 0.0];
    let c = [0.0, 1.0, 0.0];
    let d = [0.0, 0.0, 1.0];
    binary_stl(5, &[[a, c, b], [a, b, d], [a, d, c], [b, c, d]])
}

fn stl_nan() -> Vec<u8> {
    let a = [0.0, 0.0, 0.0];
    let b = [1.0, 0.0, 0.0];
    let c = [0.0, 1.0, 0.0];
    let d = [0.0, 0.0, f32::NAN];
    binary_stl(4, &[[a, c, b], [a, b, d], [a, d, c], [b, c, d]])
}

fn stl_open() -> Vec<u8> {
    binary_stl(1, &[[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
}

fn random_bytes() -> Vec<u8> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..4096)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

fn obj_huge_index() -> Vec<u8> {
    format!("{TETRA}f 1 2 18446744073709551615\n").into_bytes()
}

macro_rules! obj_case {
    ($name:expr, $text:expr, $($fragment:expr),+) => {
        Case::new($name, &["inertia", "m.obj"], 1, &["m.obj", $($fragment),+])
            .files(&[("m.obj", Text($text))])
    };
}

pub const CASES: &[Case] = &[
    obj_case!("OBJ empty", "", "no faces"),
    obj_case!("OBJ comments only", "# nothing here\n\n", "no faces"),
    obj_case!("OBJ vertices only", TETRA, "no faces"),
    obj_case!("OBJ face to a missing vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 9\n", "out of bounds"),
    obj_case!("OBJ face to vertex 0", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 0 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "OBJ"),
    obj_case!("OBJ face with two vertices", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "no faces"),
    obj_case!("OBJ vertex with a NaN", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "non-finite"),
    obj_case!("OBJ vertex with inf", "v 0 0 0\nv inf 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "non-finite"),
    obj_case!("OBJ huge coordinates", "v 0 0 0\nv 1e300 0 0\nv 0 1e300 0\nv 0 0 1e300\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "too large", "bounding-box diagonal"),
    obj_case!("OBJ vertex with text", "v 0 zero 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "OBJ"),
    obj_case!("OBJ one open triangle", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "open"),
    obj_case!("OBJ tetrahedron missing a face", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n", "open"),
    obj_case!("OBJ non-manifold edge", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 -1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 2 5\n", "non-manifold"),
    obj_case!("OBJ a flat closed surface", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n", "m.obj"),
    obj_case!("OBJ degenerate faces", "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "m.obj"),
    Case::new("OBJ binary garbage", &["inertia", "m.obj"], 1, &["m.obj"])
        .files(&[("m.obj", Made(random_bytes))]),
    Case::new("OBJ face index 2^64 - 1", &["inertia", "m.obj"], 1, &["m.obj"])
        .files(&[("m.obj", Made(obj_huge_index))]),
    Case::new("STL empty", &["inertia", "m.stl"], 1, &["m.stl"]).files(&[("m.stl", Bytes(b""))]),
    Case::new("STL header only", &["inertia", "m.stl"], 1, &["m.stl"])
        .files(&[("m.stl", Bytes(&[0u8; 84]))]),
    Case::new("STL claiming 4e9 triangles", &["inertia", "m.stl"], 1, &["m.stl"])
        .files(&[("m.stl", Made(stl_lying_count))]),
    Case::new("STL binary garbage", &["inertia", "m.stl"], 1, &["m.stl"])
        .files(&[("m.stl", Made(random_bytes))]),
    Case::new("STL with a NaN vertex", &["inertia", "m.stl"], 1, &["m.stl", "non-finite"])
        .files(&[("m.stl", Made(stl_nan))]),
    Case::new("STL one open triangle", &["inertia", "m.stl"], 1, &["m.stl", "open"])
        .files(&[("m.stl", Made(stl_open))]),
    Case::new("ASCII STL truncated", &["inertia", "m.stl"], 1, &["m.stl"])
        .files(&[("m.stl", Text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0"))]),
    Case::new("mesh of an unknown format", &["inertia", "m.ply"], 1, &["m.ply", "unknown mesh format"])
        .files(&[("m.ply", Text("ply\n"))]),
    Case::new("mesh is a folder", &["inertia", "m.obj"], 1, &["m.obj"])
        .files(&[("m.obj/x", Text(""))]),
    Case::new("inertia with a negative density", &["inertia", "m.obj", "--density", "-1"], 1, &["density"])
        .files(&[("m.obj", Text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"))]),
    Case::new("inertia with a NaN mass", &["inertia", "m.obj", "--mass", "nan"], 1, &["mass"])
        .files(&[("m.obj", Text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"))]),
    Case::new("inertia with bad Euler angles", &["inertia", "m.obj", "--euler", "1,2"], 1, &["euler"])
        .files(&[("m.obj", Text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"))]),
    obj_case!("OBJ negative index beyond the start", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf -1 -2 -9\n", "OBJ"),
    Case::new("ASCII STL with a NaN vertex", &["inertia", "m.stl"], 1, &["m.stl"])
        .files(&[("m.stl", Text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 nan\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n"))]),
    // The size a binary STL's header implies, against the file's: said in bytes.
    Case::new(
        "STL binary with a wrong triangle count",
        &["inertia", "m.stl"],
        1,
        &["m.stl", "not a whole binary STL file", "counts 5 triangles", "334 bytes", "284 bytes"],
    )
    .files(&[("m.stl", Made(stl_wrong_count))]),
    Case::new(
        "mesh too small for its integrals",
        &["inertia", "m.obj"],
        1,
        &["m.obj", "mesh is too small", "smaller unit"],
    )
    .files(&[("m.obj", Text("v 0 0 0\nv 1e-70 0 0\nv 0 1e-70 0\nv 0 0 1e-70\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"))]),
];

#[test]
fn hostile_meshes() {
    run_table(CASES);
}
