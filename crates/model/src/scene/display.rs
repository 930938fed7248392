//! How a model's state is shown in its rows and read back from them.

use tumble_scenarios::scene::continuous_quaternion;

use crate::file::Model;
use crate::mechanics::Layout;

/// How a model's state is shown in its rows: each orientation on SO(3) as a unit quaternion
/// (sign continuous along the run) and its body angular velocity, the scalar coordinates and
/// rates as they are.
#[derive(Debug, Clone)]
pub(super) struct Display {
    pub(super) coordinates: Vec<String>,
    pub(super) rates: Vec<String>,
}

impl Display {
    pub(super) fn of(model: &Model) -> Self {
        let single = model.orientations.len() == 1;
        let prefix = |name: &str| {
            if single {
                String::new()
            } else {
                format!("{name}_")
            }
        };
        let mut coordinates = Vec::new();
        let mut rates = Vec::new();
        for o in &model.orientations {
            let p = prefix(&o.name);
            coordinates.extend(["qw", "qx", "qy", "qz"].map(|c| format!("{p}{c}")));
            rates.extend(["omega_x", "omega_y", "omega_z"].map(|c| format!("{p}{c}")));
        }
        coordinates.extend(model.coordinates.iter().cloned());
        rates.extend(model.coordinates.iter().map(|c| format!("{c}_dot")));
        Display { coordinates, rates }
    }

    /// Number of values shown.
    pub(super) fn len(&self) -> usize {
        self.coordinates.len() + self.rates.len()
    }

    /// Writes the shown values of the state `y` into `out`.
    pub(super) fn write(
        &self,
        layout: Layout,
        y: &[f64],
        previous: &mut [Option<nalgebra::Quaternion<f64>>],
        out: &mut [f64],
    ) {
        let (n, k, v) = (layout.n, layout.so3, layout.velocities_at());
        for f in 0..k {
            let r = nalgebra::Matrix3::from_row_slice(&y[n + 9 * f..n + 9 * f + 9]);
            let q = continuous_quaternion(&r, &mut previous[f]);
            out[4 * f..4 * f + 4].copy_from_slice(&[q.w, q.i, q.j, q.k]);
        }
        out[4 * k..4 * k + n].copy_from_slice(&y[..n]);
        let base = 4 * k + n;
        out[base..base + 3 * k].copy_from_slice(&y[v + n..v + n + 3 * k]);
        out[base + 3 * k..base + 3 * k + n].copy_from_slice(&y[v..v + n]);
    }

    /// The state `y` of shown values (the inverse of [`Display::write`]).
    pub(super) fn read(&self, layout: Layout, shown: &[f64], y: &mut [f64]) {
        let (n, k, v) = (layout.n, layout.so3, layout.velocities_at());
        for f in 0..k {
            let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                shown[4 * f],
                shown[4 * f + 1],
                shown[4 * f + 2],
                shown[4 * f + 3],
            ));
            let r = q.to_rotation_matrix();
            for a in 0..3 {
                for b in 0..3 {
                    y[n + 9 * f + 3 * a + b] = r[(a, b)];
                }
            }
        }
        y[..n].copy_from_slice(&shown[4 * k..4 * k + n]);
        let base = 4 * k + n;
        y[v + n..v + n + 3 * k].copy_from_slice(&shown[base..base + 3 * k]);
        y[v..v + n].copy_from_slice(&shown[base + 3 * k..base + 3 * k + n]);
    }
}
