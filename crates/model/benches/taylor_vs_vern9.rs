//! The Taylor method (`taylor`: coefficients by automatic differentiation on the model's tape,
//! order and step after Jorba & Zou) beside `vern9` on the same model file, the same tolerance
//! and the same horizon, measured in one run with the two sides alternating: time per run, per
//! step, steps, and the final-state error against `vern9` at
//! 1e-15 (the reference is not the Taylor method). The table gives medians over rounds.
//! Run: `cargo bench -p tumble-model --bench taylor_vs_vern9`.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use nalgebra::SVector;
use tumble_integrators::registry::{self, build};
use tumble_integrators::{AdaptiveStepper, DenseOutput, Driver, NoObserver, Stepper, Tolerances};
use tumble_model::ModelScene;
use tumble_scenarios::Scene;

const ROUNDS: usize = 9;

fn shipped(name: &str) -> &'static ModelScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../models/{name}.toml"));
    tumble_model::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs the adaptive stepper it is handed over `[0, t_end]`: the final state and the steps.
struct Run<'a, P, const S: usize> {
    problem: &'a P,
    y0: SVector<f64, S>,
    t_end: f64,
    tol: f64,
}

impl<P, const S: usize> build::ReceiveOde<P, SVector<f64, S>> for Run<'_, P, S> {
    type Output = (SVector<f64, S>, u64);
    fn adaptive<St: AdaptiveStepper<P, State = SVector<f64, S>> + DenseOutput<P>>(
        self,
        mut stepper: St,
    ) -> Self::Output {
        let mut y = self.y0;
        let tolerances = Tolerances::new(self.tol, self.tol).unwrap();
        let report = Driver::new(0.0, self.t_end)
            .unwrap()
            .run_adaptive(
                &mut stepper,
                self.problem,
                &mut y,
                &tolerances,
                &mut [],
                &mut NoObserver,
            )
            .unwrap();
        (y, report.steps)
    }
    fn interpolating<St: DenseOutput<P, State = SVector<f64, S>>>(self, _: St) -> Self::Output {
        unreachable!("both methods are adaptive")
    }
    fn plain<St: Stepper<P, State = SVector<f64, S>> + Clone>(self, _: St) -> Self::Output {
        unreachable!("both methods are adaptive")
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn max_diff<const S: usize>(a: &SVector<f64, S>, b: &SVector<f64, S>) -> f64 {
    (a - b).amax()
}

fn compare<const S: usize>(name: &str, t_end: f64) {
    let scene = shipped(name);
    let params = scene.info().default_params();
    let y0 = SVector::<f64, S>::from_column_slice(&scene.initial_state(&params));
    let ode = scene.ode(&params);
    let series = scene.taylor(&params);
    let (taylor, vern9) = (
        registry::find("taylor").unwrap(),
        registry::find("vern9").unwrap(),
    );
    let run_vern9 = |tol: f64| {
        let run = Run {
            problem: &ode,
            y0,
            t_end,
            tol,
        };
        build::ode(vern9, &y0, run).unwrap()
    };
    let run_taylor = |tol: f64| {
        let run = Run {
            problem: &series,
            y0,
            t_end,
            tol,
        };
        build::taylor(taylor, &y0, run).unwrap()
    };
    let (reference, _) = run_vern9(1e-15);
    for tol in [1e-10, 1e-12, 1e-14] {
        let (mut tt, mut tv) = (Vec::new(), Vec::new());
        let (mut yt, mut st, mut yv, mut sv) = (y0, 0, y0, 0);
        for _ in 0..ROUNDS {
            let start = Instant::now();
            (yt, st) = black_box(run_taylor(black_box(tol)));
            tt.push(start.elapsed().as_secs_f64());
            let start = Instant::now();
            (yv, sv) = black_box(run_vern9(black_box(tol)));
            tv.push(start.elapsed().as_secs_f64());
        }
        let (t, v) = (median(tt), median(tv));
        println!(
            "{:<18} {tol:>7.0e}  {:>9.1} {:>6} {:>8.2} {:>9.2e}  {:>9.1} {:>6} {:>8.2} {:>9.2e}  {:>6.2}",
            format!("{name} ({t_end})"),
            t * 1e6,
            st,
            t * 1e6 / st as f64,
            max_diff(&yt, &reference),
            v * 1e6,
            sv,
            v * 1e6 / sv as f64,
            max_diff(&yv, &reference),
            v / t,
        );
    }
}

fn main() {
    println!(
        "taylor vs vern9 on model files, default parameters (median of {ROUNDS} alternating runs)"
    );
    println!(
        "{:<18} {:>7}  {:>9} {:>6} {:>8} {:>9}  {:>9} {:>6} {:>8} {:>9}  {:>6}",
        "model (t_end)",
        "tol",
        "taylor µs",
        "steps",
        "µs/step",
        "error",
        "vern9 µs",
        "steps",
        "µs/step",
        "error",
        "vern9/taylor"
    );
    compare::<6>("heavy-top", 10.0);
    compare::<4>("double-pendulum", 20.0);
    compare::<4>("spherical-pendulum", 10.0);
    compare::<12>("heavy-top-so3", 10.0);
    compare::<14>("free-hoop-so3", 10.0);
}
