//! The time of one right-hand-side evaluation of a model file beside the hand-written built-in
//! scene on the same physics, measured in one run with the two sides alternating:
//!
//! - `heavy-top`: the built-in's flattened rigid body `(R, Π) ∈ ℝ¹²` against
//!   `models/heavy-top.toml` (ZXZ Euler angles, `(q, q̇) ∈ ℝ⁶`);
//! - `free-hoop`: the built-in's flattened SO(3) × ℝ model `∈ ℝ¹⁴` against
//!   `models/free-hoop-euler.toml` (ZYZ angles and the bead, `(q, q̇) ∈ ℝ⁸`).
//!
//! Each round times a batch of evaluations of each side at states along a short trajectory;
//! the table gives the median over rounds of the time per evaluation and the ratio
//! model / built-in. Run: `cargo bench -p tumble-model --bench model_rhs`.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use nalgebra::SVector;
use tumble_integrators::Ode;
use tumble_model::ModelScene;
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

/// Alternates the two sides `ROUNDS` times; the medians.
fn side_by_side(mut builtin: impl FnMut(), mut model: impl FnMut()) -> (f64, f64) {
    let (mut b, mut m) = (Vec::new(), Vec::new());
    for _ in 0..ROUNDS {
        b.push(batch(&mut builtin));
        m.push(batch(&mut model));
    }
    (median(b), median(m))
}

fn main() {
    println!(
        "time per right-hand-side evaluation (median of {ROUNDS} alternating batches of {BATCH})"
    );
    println!(
        "{:<10}  {:>12}  {:>12}  {:>8}  {:>12}",
        "scene", "built-in ns", "model ns", "ratio", "model instr."
    );

    // Heavy top.
    let params = HeavyTopScene.info().default_params();
    let (top, s0) = HeavyTopScene::top_and_state(&params).unwrap();
    let flat = FlatRigidBody(top);
    let y = flatten_top(&s0);
    let mut dy = y;
    let scene = shipped("heavy-top");
    let mp = scene.info().default_params();
    let ode = scene.ode(&mp);
    let y0 = scene.initial_state(&mp);
    let ym = SVector::<f64, 6>::from_column_slice(&y0);
    let mut dym = ym;
    let (b, m) = side_by_side(
        || flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy)),
        || ode.rhs(black_box(0.0), black_box(&ym), black_box(&mut dym)),
    );
    black_box((dy, dym));
    println!(
        "{:<10}  {b:>12.1}  {m:>12.1}  {:>8.2}  {:>12}",
        "heavy-top",
        m / b,
        scene.rhs_instructions()
    );

    // Free hoop.
    let params = FreeHoopScene.info().default_params();
    let (model, s0) = FreeHoopScene::model(&params).unwrap();
    let flat = FlatFreeHoop::new(model).unwrap();
    let y = flatten_hoop(&s0);
    let mut dy = y;
    let scene = shipped("free-hoop-euler");
    let mp = scene.info().default_params();
    let ode = scene.ode(&mp);
    let y0 = scene.initial_state(&mp);
    let ym = SVector::<f64, 8>::from_column_slice(&y0);
    let mut dym = ym;
    let (b, m) = side_by_side(
        || flat.rhs(black_box(0.0), black_box(&y), black_box(&mut dy)),
        || ode.rhs(black_box(0.0), black_box(&ym), black_box(&mut dym)),
    );
    black_box((dy, dym));
    println!(
        "{:<10}  {b:>12.1}  {m:>12.1}  {:>8.2}  {:>12}",
        "free-hoop",
        m / b,
        scene.rhs_instructions()
    );
}
