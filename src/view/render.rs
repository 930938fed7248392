//! A drawing's frame rendered in software, as the viewer's page shows it: the same camera (a
//! 40° perspective from `(2.5, −3.9, 2.0)` times the scene's reach, lab z up), the same lights
//! (a white-over-grey hemisphere light of intensity 1.6 and a white directional light of 2.0
//! from `(3, −2, 5)`, diffuse shading of a 0.1-metal surface in linear light, written in sRGB),
//! the bodies shaded and hidden by depth, the lab axes dashed, the body axes, the ω and L arrows
//! and the trail. No window and no GPU: a z-buffered rasterizer of triangles and lines.
//!
//! The lighting follows three.js's physically based conventions (diffuse `albedo/π` times the
//! irradiance: `1.6 × mix(ground, sky, ½ + ½ n_z)` from the hemisphere, `2.0 × max(0, n·l)`
//! from the sun; three.js documentation, *HemisphereLight*, *MeshStandardMaterial*).

use nalgebra::{UnitQuaternion, Vector3};

use super::geometry::{Form, Piece, Render, Triangle};
use super::run::{Drawing, Frames};

/// Okabe–Ito colours of the x, y, z axes (as the page's `AXIS_COLOURS`).
pub const AXIS_COLOURS: [&str; 3] = ["#d55e00", "#009e73", "#0072b2"];
/// The trail's colour.
pub const TRAIL_COLOUR: &str = "#e69f00";
/// Vertical field of view of the camera (degrees).
const FIELD_OF_VIEW: f64 = 40.0;

/// `#rrggbb` as bytes (black for anything else).
#[must_use]
pub fn rgb(hex: &str) -> [u8; 3] {
    let byte = |k: usize| {
        hex.get(1 + 2 * k..3 + 2 * k)
            .and_then(|h| u8::from_str_radix(h, 16).ok())
            .unwrap_or(0)
    };
    [byte(0), byte(1), byte(2)]
}

/// sRGB byte to linear light.
fn linear(c: u8) -> f64 {
    let c = f64::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light to an sRGB byte.
fn srgb(x: f64) -> u8 {
    let x = x.clamp(0.0, 1.0);
    let c = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (255.0 * c).round() as u8
}

/// A perspective camera looking at the origin.
#[derive(Debug, Clone, Copy)]
pub struct Camera {
    eye: Vector3<f64>,
    right: Vector3<f64>,
    up: Vector3<f64>,
    forward: Vector3<f64>,
    /// Pixels per unit of `tan` of the angle off the axis.
    focal: f64,
    size: (u32, u32),
}

impl Camera {
    /// The page's camera for a scene of `reach` metres, on a frame of `size` device pixels.
    #[must_use]
    pub fn viewer(reach: f64, size: (u32, u32)) -> Self {
        let eye = Vector3::new(2.5, -3.9, 2.0) * reach;
        let forward = (-eye).normalize();
        let right = forward.cross(&Vector3::z()).normalize();
        let up = right.cross(&forward);
        let focal = 0.5 * f64::from(size.1) / (0.5 * FIELD_OF_VIEW.to_radians()).tan();
        Camera {
            eye,
            right,
            up,
            forward,
            focal,
            size,
        }
    }

    /// Device coordinates of `p` (x right, y down, pixel centres at half-integers) and its
    /// inverse depth; `None` behind the camera.
    #[must_use]
    pub fn project(&self, p: &Vector3<f64>) -> Option<[f64; 3]> {
        let d = p - self.eye;
        let depth = d.dot(&self.forward);
        if depth <= 1e-9 * self.eye.norm() {
            return None;
        }
        let w = 1.0 / depth;
        Some([
            0.5 * f64::from(self.size.0) + self.focal * d.dot(&self.right) * w,
            0.5 * f64::from(self.size.1) - self.focal * d.dot(&self.up) * w,
            w,
        ])
    }
}

/// An RGB frame with a depth buffer.
pub struct Canvas {
    /// Size in device pixels.
    pub size: (u32, u32),
    /// RGB bytes, row by row.
    pub rgb: Vec<u8>,
    /// Inverse depth of the nearest surface at each pixel (0: nothing).
    depth: Vec<f64>,
}

impl Canvas {
    /// A white frame.
    #[must_use]
    pub fn new(size: (u32, u32)) -> Self {
        let n = size.0 as usize * size.1 as usize;
        Canvas {
            size,
            rgb: vec![255; 3 * n],
            depth: vec![0.0; n],
        }
    }

    /// Clears to white.
    pub fn clear(&mut self) {
        self.rgb.fill(255);
        self.depth.fill(0.0);
    }

    /// Writes `colour` at pixel `(x, y)` if `w` (inverse depth) is nearer than what is there,
    /// within the relative `bias`.
    fn plot(&mut self, x: usize, y: usize, w: f64, bias: f64, colour: [u8; 3]) {
        let k = y * self.size.0 as usize + x;
        if w * (1.0 + bias) >= self.depth[k] {
            self.depth[k] = self.depth[k].max(w);
            self.rgb[3 * k..3 * k + 3].copy_from_slice(&colour);
        }
    }

    /// Pixel bounds of a box, clipped to the frame.
    fn bounds(&self, lo: [f64; 2], hi: [f64; 2]) -> Option<([usize; 2], [usize; 2])> {
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let x0 = lo[0].floor().max(0.0);
        let y0 = lo[1].floor().max(0.0);
        let x1 = hi[0].ceil().min(w);
        let y1 = hi[1].ceil().min(h);
        (x0 < x1 && y0 < y1).then_some(([x0 as usize, y0 as usize], [x1 as usize, y1 as usize]))
    }

    /// A triangle with a colour (linear light) at each corner, interpolated perspective-
    /// correctly, hidden by what is nearer.
    pub fn triangle(&mut self, corners: [[f64; 3]; 3], colours: [[f64; 3]; 3]) {
        let [a, b, c] = corners;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.abs() < 1e-12 {
            return;
        }
        let lo = [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])];
        let hi = [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])];
        let Some((p0, p1)) = self.bounds(lo, hi) else {
            return;
        };
        for y in p0[1]..p1[1] {
            let py = y as f64 + 0.5;
            for x in p0[0]..p1[0] {
                let px = x as f64 + 0.5;
                let l0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
                let l1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
                let l2 = 1.0 - l0 - l1;
                if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                    continue;
                }
                let (m0, m1, m2) = (l0 * a[2], l1 * b[2], l2 * c[2]);
                let w = m0 + m1 + m2;
                let k = y * self.size.0 as usize + x;
                if w <= self.depth[k] {
                    continue;
                }
                let colour = [0, 1, 2].map(|i| {
                    srgb((m0 * colours[0][i] + m1 * colours[1][i] + m2 * colours[2][i]) / w)
                });
                self.depth[k] = w;
                self.rgb[3 * k..3 * k + 3].copy_from_slice(&colour);
            }
        }
    }

    /// A segment `width` device pixels wide between two projected points, hidden by surfaces
    /// nearer than it (with a small bias, so that lines on a surface show).
    pub fn segment(&mut self, a: [f64; 3], b: [f64; 3], width: f64, colour: [u8; 3]) {
        let half = 0.5 * width.max(1.0);
        let lo = [a[0].min(b[0]) - half, a[1].min(b[1]) - half];
        let hi = [a[0].max(b[0]) + half, a[1].max(b[1]) + half];
        let Some((p0, p1)) = self.bounds(lo, hi) else {
            return;
        };
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let length2 = dx * dx + dy * dy;
        for y in p0[1]..p1[1] {
            let py = y as f64 + 0.5;
            for x in p0[0]..p1[0] {
                let px = x as f64 + 0.5;
                let t = if length2 > 0.0 {
                    (((px - a[0]) * dx + (py - a[1]) * dy) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (ex, ey) = (a[0] + t * dx - px, a[1] + t * dy - py);
                if ex * ex + ey * ey <= half * half {
                    self.plot(x, y, a[2] + t * (b[2] - a[2]), 2e-3, colour);
                }
            }
        }
    }
}

/// The lights: the shade (linear light) of a surface of `albedo` (linear) with normal `n`.
fn shade(albedo: [f64; 3], n: &Vector3<f64>) -> [f64; 3] {
    let sun = Vector3::new(3.0, -2.0, 5.0).normalize();
    let (sky, ground) = ([1.0, 1.0, 1.0], rgb("#8899aa").map(linear));
    let mix = 0.5 + 0.5 * n.z;
    let direct = 2.0 * n.dot(&sun).max(0.0);
    // Diffuse of a 0.1-metal surface: 0.9 albedo / π.
    [0, 1, 2].map(|i| {
        let hemi = 1.6 * (ground[i] + (sky[i] - ground[i]) * mix);
        0.9 * albedo[i] * (hemi + direct) / std::f64::consts::PI
    })
}

/// Draws a drawing's frame `k` (of `frames`, from [`Drawing::frames`]) with the trail up to
/// `trail_end` (an index into `frames.trail`, which may be denser than the frames).
pub struct Renderer<'a> {
    drawing: &'a Drawing,
    /// Each object's triangles in its own frame.
    triangles: Vec<Vec<Triangle>>,
    /// Device pixels per frame pixel (lines are this many times wider).
    pub scale: f64,
    camera: Camera,
}

/// Where the labels of the axes go: text, device position, colour.
pub type Label = (String, (i32, i32), [u8; 3]);

impl<'a> Renderer<'a> {
    /// A renderer of `drawing` on frames of `size` device pixels, `scale` per frame pixel.
    #[must_use]
    pub fn new(drawing: &'a Drawing, size: (u32, u32), scale: f64) -> Self {
        let triangles = drawing
            .objects()
            .map(|(_, pieces, _)| {
                let mut out = Vec::new();
                for p in pieces {
                    p.triangles(&mut out);
                }
                out
            })
            .collect();
        Renderer {
            drawing,
            triangles,
            scale,
            camera: Camera::viewer(drawing.reach(), size),
        }
    }

    /// A polyline through `points`.
    fn polyline(&self, canvas: &mut Canvas, points: &[Vector3<f64>], width: f64, colour: [u8; 3]) {
        let projected: Vec<Option<[f64; 3]>> =
            points.iter().map(|p| self.camera.project(p)).collect();
        for pair in projected.windows(2) {
            if let [Some(a), Some(b)] = pair {
                canvas.segment(*a, *b, width * self.scale, colour);
            }
        }
    }

    /// Three axes of `length` from `origin` turned by `turn`; dashed for the lab. Returns the
    /// labels' places.
    fn axes(
        &self,
        canvas: &mut Canvas,
        origin: &Vector3<f64>,
        turn: &UnitQuaternion<f64>,
        length: f64,
        names: [&str; 3],
        dashed: bool,
    ) -> Vec<Label> {
        let mut labels = Vec::new();
        for (k, name) in names.iter().enumerate() {
            let colour = rgb(AXIS_COLOURS[k]);
            let dir = turn * Vector3::ith(k, 1.0);
            if dashed {
                // Dashes of length/20 and gaps of length/40, as the page's.
                let mut s = 0.0;
                while s < length {
                    let e = (s + length / 20.0).min(length);
                    self.polyline(canvas, &[origin + dir * s, origin + dir * e], 1.0, colour);
                    s = e + length / 40.0;
                }
            } else {
                self.polyline(canvas, &[*origin, origin + dir * length], 1.5, colour);
            }
            if let Some(p) = self.camera.project(&(origin + dir * (1.08 * length))) {
                labels.push(((*name).to_string(), (p[0] as i32, p[1] as i32), colour));
            }
        }
        labels
    }

    /// Shaded triangles of one object in its pose.
    fn solid(
        &self,
        canvas: &mut Canvas,
        triangles: &[Triangle],
        at: &Vector3<f64>,
        turn: &UnitQuaternion<f64>,
        colour: [u8; 3],
        lit: bool,
    ) {
        let albedo = colour.map(linear);
        for t in triangles {
            let corners = t.corners.map(|c| at + turn * c);
            let Some(projected) = corners
                .iter()
                .map(|c| self.camera.project(c))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let colours = [0, 1, 2].map(|i| {
                if !lit {
                    return albedo;
                }
                let mut n = turn * t.normals[i];
                // Seen from behind (inside a hollow form): lit as its other side.
                if n.dot(&(self.camera.eye - corners[i])) < 0.0 {
                    n = -n;
                }
                shade(albedo, &n)
            });
            canvas.triangle([projected[0], projected[1], projected[2]], colours);
        }
    }

    /// An arrow from the origin to `v` (a shaft and a cone, unlit, as three.js's ArrowHelper).
    fn arrow(&self, canvas: &mut Canvas, v: &Vector3<f64>, colour: [u8; 3]) {
        let reach = self.drawing.reach();
        let length = v.norm();
        if length <= 1e-9 * reach {
            return;
        }
        let dir = v / length;
        let head = (0.12 * reach).min(0.4 * length);
        self.polyline(
            canvas,
            &[Vector3::zeros(), dir * (length - head)],
            2.0,
            colour,
        );
        let cone = Piece::new(
            Form::Cylinder {
                radius: 0.25 * head,
                height: head,
            },
            Vector3::zeros(),
            UnitQuaternion::identity(),
        );
        // A cone: the cylinder's top rim pulled to its axis.
        let mut triangles = Vec::new();
        cone.triangles(&mut triangles);
        for t in &mut triangles {
            for c in &mut t.corners {
                if c.z > 0.0 {
                    *c = Vector3::new(0.0, 0.0, c.z);
                }
            }
        }
        let turn = UnitQuaternion::rotation_between(&Vector3::z(), &dir).unwrap_or_else(|| {
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        });
        let at = dir * (length - 0.5 * head);
        self.solid(canvas, &triangles, &at, &turn, colour, false);
    }

    /// Draws frame `k` with the trail's points `trail` (up to this frame) on `canvas`; returns
    /// the axes' labels to write over it.
    pub fn draw(
        &self,
        canvas: &mut Canvas,
        frames: &Frames,
        k: usize,
        trail: &[Vector3<f64>],
    ) -> Vec<Label> {
        canvas.clear();
        let reach = self.drawing.reach();
        let mut labels = Vec::new();
        for (i, (colour, _, axes)) in self.drawing.objects().enumerate() {
            let (at, turn) = (frames.positions[i][k], frames.turns[i][k]);
            self.solid(canvas, &self.triangles[i], &at, &turn, rgb(colour), true);
            if axes {
                labels.extend(self.axes(canvas, &at, &turn, 0.9 * reach, ["x", "y", "z"], false));
            }
        }
        labels.extend(self.axes(
            canvas,
            &Vector3::zeros(),
            &UnitQuaternion::identity(),
            1.35 * reach,
            ["X", "Y", "Z"],
            true,
        ));
        for v in &frames.vectors {
            self.arrow(canvas, &(v.series[k] * v.scale), rgb(v.colour));
        }
        self.polyline(canvas, trail, 1.5, rgb(TRAIL_COLOUR));
        labels
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere of radius r at distance d from a pinhole camera of focal length f (pixels)
    /// covers a disk of radius f r / √(d² − r²) in the image: its tangent cone's section.
    #[test]
    fn a_sphere_covers_the_disk_its_tangent_cone_cuts() {
        let size = (400, 400);
        let reach = 1.0;
        let camera = Camera::viewer(reach, size);
        let mut canvas = Canvas::new(size);
        let r = 0.5;
        let mut triangles = Vec::new();
        Piece::centred(Form::Sphere(r)).triangles(&mut triangles);
        for t in &triangles {
            let p = t.corners.map(|c| camera.project(&c).unwrap());
            canvas.triangle(p, [[0.0; 3]; 3]);
        }
        let covered = canvas.depth.iter().filter(|&&w| w > 0.0).count() as f64;
        let d = (Vector3::new(2.5, -3.9, 2.0) * reach).norm();
        let radius = camera.focal * r / (d * d - r * r).sqrt();
        let disk = std::f64::consts::PI * radius * radius;
        // The 32 x 16 polygon is inside the sphere: a little less than the disk.
        assert!(
            covered < disk && covered > 0.97 * disk,
            "covered {covered} px, disk {disk:.0} px"
        );
    }

    /// Depth hides the far one of two overlapping triangles whatever the order they are drawn.
    #[test]
    fn the_nearer_surface_hides_the_farther_in_either_order() {
        let size = (64, 64);
        let camera = Camera::viewer(1.0, size);
        let toward = -camera.forward;
        let square = |offset: f64| {
            let c = toward * offset;
            [
                [
                    c - camera.right - camera.up,
                    c + camera.right - camera.up,
                    c + camera.right + camera.up,
                ],
                [
                    c - camera.right - camera.up,
                    c + camera.right + camera.up,
                    c - camera.right + camera.up,
                ],
            ]
        };
        for near_first in [true, false] {
            let mut canvas = Canvas::new(size);
            let (near, far) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
            let order = if near_first {
                [(0.3, near), (-0.3, far)]
            } else {
                [(-0.3, far), (0.3, near)]
            };
            for (offset, colour) in order {
                for t in square(offset) {
                    canvas.triangle(t.map(|c| camera.project(&c).unwrap()), [colour; 3]);
                }
            }
            let centre = 3 * (32 * 64 + 32);
            assert_eq!(
                &canvas.rgb[centre..centre + 3],
                &[255, 0, 0],
                "near first: {near_first}"
            );
        }
    }

    /// Lambert's law: between two normals at the same height (the hemisphere light the same),
    /// the shade differs by the sun's cosine difference, and not at all once both face away.
    #[test]
    fn the_sun_lights_a_surface_by_the_cosine_of_its_angle() {
        let sun = Vector3::new(3.0, -2.0, 5.0).normalize();
        let albedo = [0.5; 3];
        let per_cosine = 0.9 * 0.5 * 2.0 / std::f64::consts::PI;
        for turn in [0.3_f64, 1.0, 2.0, 3.0] {
            let n = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn) * sun;
            let expected = per_cosine * (1.0 - n.dot(&sun).max(0.0));
            let got = shade(albedo, &sun)[0] - shade(albedo, &n)[0];
            assert!(
                (got - expected).abs() < 1e-12,
                "turn {turn}: {got} vs {expected}"
            );
        }
        let down = -Vector3::z();
        let below = Vector3::new(0.0, 1.0, -1.0).normalize();
        let hemi = |n: &Vector3<f64>| {
            0.9 * 0.5 * 1.6 * (linear(0x88) + (1.0 - linear(0x88)) * (0.5 + 0.5 * n.z))
                / std::f64::consts::PI
        };
        for n in [down, below] {
            assert!(n.dot(&sun) < 0.0);
            assert!((shade(albedo, &n)[0] - hemi(&n)).abs() < 1e-12);
        }
    }
}
