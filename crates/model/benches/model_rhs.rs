//! The time of one right-hand-side evaluation of a model file beside the hand-written built-in
//! scene on the same physics, measured in one run with the two sides alternating:
//!
//! - `heavy-top`: the built-in's flattened rigid body `(R, Π) ∈ ℝ¹²` against
//!   `models/heavy-top.toml` (ZXZ Euler angles, `(q, q̇) ∈ ℝ⁶`);
//! - `free-hoop`: the built-in's flattened SO(3) × ℝ model `∈ ℝ¹⁴` against
//!   `models/free-hoop-euler.toml` (ZYZ angles and the bead, `(q, q̇) ∈ ℝ⁸`);
//! - both again against the models with the orientation on SO(3)
//!   (`models/heavy-top-so3.toml` on ℝ¹², `models/free-hoop-so3.toml` on ℝ¹⁴): the same state
//!   and the same physics as the built-ins, only written as energies.
//!
//! Each model runs two ways: its tape compiled to native code at load (`tumble-jit`, the
//! default) and interpreted. Each round times a batch of evaluations of each of the three
//! sides in turn; the table gives the median over rounds of the time per evaluation, the
//! ratios to the built-in, and the time to compile the model's tape (median of 5).
//! Run: `cargo bench -p tumble-model --bench model_rhs`.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use nalgebra::SVector;
use tumble_integrators::Ode;
use tumble_model::{Evaluation, ModelScene};
use tumble_scenarios::Scene;
use tumble_scenarios::scenes::free_hoop::{FlatFreeHoop, FreeHoopScene, flatten as flatten_hoop};
use tumble_scenarios::scenes::rigid::{FlatRigidBody, HeavyTopScene, flatten as flatten_top};

const BATCH: usize = 20_000;
const ROUNDS: usize = 15;

fn shipped(name: &str) -> &'static ModelScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../models/{name}.toml"));
    tumble_model::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Nanoseconds per call of `f`, one batch.
fn batch(mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..BATCH {
        f();
    }
    start.elapsed().as_secs_f64() * 1e9 / BATCH as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Alternates the sides `ROUNDS` times; the medians.
fn side_by_side<const K: usize>(sides: &mut [&mut dyn FnMut(); K]) -> [f64; K] {
    let mut t: [Vec<f64>; K] = std::array::from_fn(|_| Vec::new());
    for _ in 0..ROUNDS {
        for (k, side) in sides.iter_mut().enumerate() {
            t[k].push(batch(&mut **side));
        }
    }
    t.map(median)
}

/// Milliseconds to compile the model's right-hand side (median of 5).
fn compile_ms(scene: &ModelScene) -> f64 {
    median(
        (0..5)
            .map(|_| {
                let start = Instant::now();
                black_box(scene.compile_rhs().unwrap_or_else(|e| panic!("{e}")));
                start.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    )
}

fn report(name: &str, [b, native, interpreted]: [f64; 3], scene: &ModelScene) {
    println!(
        "{name:<10}  {:<16}  {b:>11.1}  {native:>10.1}  {:>6.2}  {interpreted:>15.1}  {:>6.2}  {:>6}  {:>10.1}",
        scene.info().name,
        native / b,
        interpreted / b,
        scene.rhs_instructions(),
        compile_ms(scene),
    );
}

/// Times a model's right-hand side, native and interpreted, beside the built-in's `builtin`.
fn model_sides<const S: usize>(name: &str, scene: &ModelScene, builtin: &mut dyn FnMut()) {
    let mp = scene.info().default_params();
    let native = scene.ode_with(&mp, Evaluation::Native);
    let interpreted = scene.ode_with(&mp, Evaluation::Interpreted);
    assert_eq!(
        scene.evaluation(),
        Evaluation::Native,
        "no code generator here"
    );
    let ym = SVector::<f64, S>::from_column_slice(&scene.initial_state(&mp));
    let (mut dn, mut di) = (ym, ym);
    let times = side_by_side(&mut [
        builtin,
        &mut || native.rhs(black_box(0.0), black_box(&ym), black_box(&mut dn)),
        &mut || interpreted.rhs(black_box(0.0), black_box(&ym), black_box(&mut di)),
    ]);
    assert_eq!(dn, di, "native and interpreted evaluations differ");
    report(name, times, scene);
}

fn main() {
    println!(
        "time per right-hand-side evaluation (median of {ROUNDS} alternating batches of {BATCH})"
    );
    println!(
        "{:<10}  {:>11}  {:>10}  {:>6}  {:>15}  {:>6}  {:>6}  {:>10}",
        "scene",
        "built-in ns",
        "native ns",
        "ratio",
        "interpreted ns",
        "ratio",
        "instr.",
        "compile ms"
    );

    // Heavy top.
    let params = HeavyTopScene.info().default_params();
    let (top, s0) = HeavyTopScene::top_and_state(&params).unwrap();
    let flat = FlatRigidBody(top);
    let y = flatten_top(&s0);
    let mut dy = y;
    model_sides::<6>("heavy-top", shipped("heavy-top"), &mut || {
        flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy));
    });
    model_sides::<12>("heavy-top", shipped("heavy-top-so3"), &mut || {
        flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy));
    });

    // Free hoop.
    let params = FreeHoopScene.info().default_params();
    let (model, s0) = FreeHoopScene::model(&params).unwrap();
    let flat = FlatFreeHoop::new(model).unwrap();
    let y = flatten_hoop(&s0);
    let mut dy = y;
    model_sides::<8>("free-hoop", shipped("free-hoop-euler"), &mut || {
        flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy));
    });
    model_sides::<14>("free-hoop", shipped("free-hoop-so3"), &mut || {
        flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy));
    });
}
