//! Where a model's bodies and point masses are at each row of a run, and their mass properties
//! at the run's parameters: what `tumble view` and `tumble animate` draw. The positions and
//! orientations are the model's own expressions ([`crate::file::ModelDrawing`]), evaluated on
//! an instruction tape from the rows' time, coordinates and rates.

use tumble_scenarios::Params;
use tumble_scenarios::drawing::Part;

use crate::expr::Id;
use crate::expr::tape::Tape;
use crate::scene::ModelScene;

/// A body's mass properties at a run's parameters, in its own frame.
#[derive(Debug, Clone)]
pub struct BodyShape {
    /// Its name in the file.
    pub name: String,
    /// Mass.
    pub mass: f64,
    /// Centre of mass.
    pub com: [f64; 3],
    /// Inertia tensor about the centre of mass.
    pub inertia: [[f64; 3]; 3],
    /// Its parts, when the file gives its geometry.
    pub parts: Option<Vec<Part>>,
}

/// A point mass at a run's parameters.
#[derive(Debug, Clone)]
pub struct PointShape {
    /// Its name in the file.
    pub name: String,
    /// Mass.
    pub mass: f64,
}

/// A model's bodies and point masses at a run's parameters.
#[derive(Debug, Clone)]
pub struct Shapes {
    /// Bodies, in the file's order.
    pub bodies: Vec<BodyShape>,
    /// Point masses, in the file's order.
    pub points: Vec<PointShape>,
}

/// Where everything is at one row.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    /// Each body's orientation (body → model frame, by rows) and its frame's origin.
    pub bodies: Vec<([[f64; 3]; 3], [f64; 3])>,
    /// Each point mass's position (model frame).
    pub points: Vec<[f64; 3]>,
}

impl ModelScene {
    /// The inputs of a tape at `params`, time, coordinates and rates zero.
    fn parameter_inputs(&self, params: &Params) -> Vec<f64> {
        let layout = self.model().layout;
        let mut inputs = vec![0.0; layout.param(self.model().params.len()) as usize];
        for (j, (_, value)) in params.iter().enumerate() {
            inputs[layout.param(j) as usize] = value;
        }
        inputs
    }

    /// The bodies' and point masses' mass properties at `params`.
    #[must_use]
    pub fn shapes(&self, params: &Params) -> Shapes {
        let drawing = &self.model().drawing;
        let mut outputs: Vec<Id> = Vec::new();
        for b in &drawing.bodies {
            outputs.push(b.mass);
            outputs.extend_from_slice(&b.com);
            outputs.extend(b.inertia.iter().flatten());
        }
        outputs.extend(drawing.points.iter().map(|p| p.mass));
        let tape = Tape::new(&self.model().graph, &outputs);
        let mut w = tape.workspace();
        tape.run_all(&mut w, &self.parameter_inputs(params));
        let mut k = 0;
        let mut next = || {
            k += 1;
            tape.output(&w, k - 1)
        };
        let bodies = drawing
            .bodies
            .iter()
            .map(|b| BodyShape {
                name: b.name.clone(),
                mass: next(),
                com: [next(), next(), next()],
                inertia: [
                    [next(), next(), next()],
                    [next(), next(), next()],
                    [next(), next(), next()],
                ],
                parts: b.parts.clone(),
            })
            .collect();
        let points = drawing
            .points
            .iter()
            .map(|p| PointShape {
                name: p.name.clone(),
                mass: next(),
            })
            .collect();
        Shapes { bodies, points }
    }

    /// Where every body and point mass is at each of `rows` (the scene's rows: `t`, the
    /// coordinates, their rates, then the rest) at `params`. Rows shorter than `1 + 2n` give
    /// no pose.
    #[must_use]
    pub fn poses(&self, params: &Params, rows: &[Vec<f64>]) -> Vec<Pose> {
        let model = self.model();
        let (layout, drawing) = (model.layout, &model.drawing);
        let mut outputs: Vec<Id> = Vec::new();
        for b in &drawing.bodies {
            if let Some(r) = &b.rotation {
                outputs.extend(r.iter().flatten());
            }
            outputs.extend_from_slice(&b.origin);
        }
        for p in &drawing.points {
            outputs.extend_from_slice(&p.position);
        }
        let fixed = move |k: u32| layout.is_param(k);
        let tape = Tape::with_fixed(&model.graph, &outputs, &fixed);
        let mut w = tape.workspace();
        let inputs = self.parameter_inputs(params);
        let set = inputs.len().min(tape.inputs()).min(w.len());
        w[..set].copy_from_slice(&inputs[..set]);
        tape.run_prelude(&mut w);
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // `t`, then each orientation's quaternion and angular velocity, the coordinates, rates.
        let shown = 1 + 2 * layout.n + 7 * layout.so3;
        rows.iter()
            .filter(|row| row.len() >= shown)
            .map(|row| {
                // Time and the state are inputs 0 ..= state_len; a row shows orientations on
                // SO(3) as quaternions.
                let state = self.state_of_row(row);
                let varying = state.len().min(set);
                w[..varying].copy_from_slice(&state[..varying]);
                tape.run(&mut w);
                let mut k = 0;
                let mut next = || {
                    k += 1;
                    tape.output(&w, k - 1)
                };
                let bodies = drawing
                    .bodies
                    .iter()
                    .map(|b| {
                        let r = if b.rotation.is_some() {
                            [0, 1, 2].map(|_| [next(), next(), next()])
                        } else {
                            identity
                        };
                        (r, [next(), next(), next()])
                    })
                    .collect();
                let points = drawing
                    .points
                    .iter()
                    .map(|_| [next(), next(), next()])
                    .collect();
                Pose { bodies, points }
            })
            .collect()
    }
}
