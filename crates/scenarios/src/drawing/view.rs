//! What a scene declares for `tumble view` and `tumble animate` to draw ([`Drawing`]): its
//! objects (pieces in their own frames), how each object's pose follows the scene's rows
//! ([`Motion`]), the point the trail follows and the scene's size. A scene returns it from
//! [`Scene::drawing`](crate::Scene::drawing); the drawings of the built-in scenes are built here.

use nalgebra::{UnitQuaternion, Vector3};
use tumble_inertia::{MassSpec, THandle};
use tumble_kinematics::EulerConvention;

use super::pieces::{self, Form, Piece};
use super::{BodyDrawing, Part};
use crate::error::SceneError;
use crate::params::Params;

/// How an object's pose follows the rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Fixed at the origin.
    Fixed,
    /// Turned about the origin by the rows' quaternion `qw … qz`.
    Quaternion,
    /// A hoop in a vertical plane at azimuth φ (the `phi` column, or `omega t` when driven).
    VerticalPlane {
        /// The azimuth's constant rate when it is driven.
        omega: Option<f64>,
    },
    /// The bead on the free hoop (body x-y plane, angle `alpha`) at radius `a`.
    BeadFree {
        /// The hoop's radius.
        a: f64,
    },
    /// The bead on a vertical hoop at azimuth φ, `alpha` from the bottom.
    BeadVertical {
        /// The hoop's radius.
        a: f64,
        /// The azimuth's constant rate when it is driven.
        omega: Option<f64>,
    },
    /// The scene's body number `k`, placed by [`Scene::placements`](crate::Scene::placements).
    PlacedBody(usize),
    /// The scene's point mass number `k`, placed by
    /// [`Scene::placements`](crate::Scene::placements).
    PlacedPoint(usize),
}

/// One drawn object.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// What it is (`body`, `hoop`, `bead`, `pivot`, `point`).
    pub name: &'static str,
    /// Colour, `#rrggbb`.
    pub colour: &'static str,
    /// Its pieces in its own frame.
    pub pieces: Vec<Piece>,
    /// How its pose follows the rows.
    pub motion: Motion,
    /// Whether its own axes (the body frame) are drawn.
    pub axes: bool,
}

/// What the trail follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Trail {
    /// A point of an object (by index), in its own frame.
    Tip(usize, Vector3<f64>),
    /// An object's position (by index): the bead, a model's first point mass.
    Object(usize),
}

/// A scene's drawing: its objects, what the trail follows, and its size (metres: the camera and
/// the arrows are scaled by it).
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// The objects, drawn in this order.
    pub objects: Vec<Object>,
    /// What the trail follows.
    pub trail: Trail,
    /// The scene's size.
    pub reach: f64,
}

/// Where a scene's placed bodies and point masses are at one row ([`Motion::PlacedBody`],
/// [`Motion::PlacedPoint`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// Each body's orientation (body → scene frame, by rows) and its frame's origin.
    pub bodies: Vec<([[f64; 3]; 3], [f64; 3])>,
    /// Each point mass's position (scene frame).
    pub points: Vec<[f64; 3]>,
}

/// The fixed point, a small grey sphere.
#[must_use]
pub fn pivot(reach: f64) -> Object {
    Object {
        name: "pivot",
        colour: "#555555",
        pieces: vec![Piece::centred(Form::Sphere(0.025 * reach))],
        motion: Motion::Fixed,
        axes: false,
    }
}

fn bead(a: f64, motion: Motion) -> Object {
    Object {
        name: "bead",
        colour: "#d55e00",
        pieces: vec![Piece::centred(Form::Sphere(0.06 * a))],
        motion,
        axes: false,
    }
}

/// A rigid body turned by the rows' quaternion, its axes drawn.
fn body(pieces: Vec<Piece>) -> Object {
    Object {
        name: "body",
        colour: "#0072b2",
        pieces,
        motion: Motion::Quaternion,
        axes: true,
    }
}

impl Drawing {
    /// A hoop of radius `a` moved as `hoop`, its bead moved as `bead`, the trail on the bead.
    #[must_use]
    pub fn hoop(a: f64, hoop: Motion, bead_motion: Motion) -> Self {
        Drawing {
            objects: vec![
                Object {
                    name: "hoop",
                    colour: "#0072b2",
                    pieces: vec![Piece::centred(Form::Torus {
                        major: a,
                        minor: 0.025 * a,
                    })],
                    motion: hoop,
                    axes: true,
                },
                bead(a, bead_motion),
                pivot(a),
            ],
            trail: Trail::Object(1),
            reach: a,
        }
    }

    /// A torque-free body of principal moments `moments` drawn as its equivalent box
    /// ([`pieces::equivalent_box`]), the trail at a point of its y axis.
    #[must_use]
    pub fn equivalent_box(moments: [f64; 3]) -> Self {
        let half = pieces::equivalent_box(moments);
        let sides = half.map(|v| 2.0 * v);
        let reach = 0.5 * Vector3::from(sides).norm();
        Drawing {
            objects: vec![body(vec![Piece::centred(Form::Box(sides))]), pivot(reach)],
            trail: Trail::Tip(0, Vector3::new(0.0, 0.6 * sides[1].max(0.6), 0.0)),
            reach,
        }
    }

    /// The standard T-handle's mesh ([`THandle::STANDARD`]) about its centre of mass, the
    /// trail on its intermediate principal axis, the one the handle flips about.
    ///
    /// # Errors
    /// The handle's mesh or mass properties cannot be built.
    pub fn t_handle() -> Result<Self, SceneError> {
        let mesh = THandle::STANDARD.mesh()?;
        let props = THandle::STANDARD.mass_properties(MassSpec::TotalMass(1.0))?;
        let parts = vec![Part::Mesh(mesh)];
        let center = props.center_of_mass();
        let reach = pieces::reach(&parts, &center);
        Ok(Drawing {
            objects: vec![body(pieces::parts(&parts, &center)), pivot(reach)],
            trail: Trail::Tip(
                0,
                props.principal().axes.matrix().column(1).into_owned() * 1.15 * reach,
            ),
            reach,
        })
    }

    /// The symmetric top: its axis along body z from the pivot and a disk at its end, the
    /// trail just beyond the disk.
    #[must_use]
    pub fn symmetric_top() -> Self {
        let z = |h: f64| Vector3::new(0.0, 0.0, h);
        let upright = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.0);
        Drawing {
            objects: vec![
                body(vec![
                    Piece::new(
                        Form::Cylinder {
                            radius: 0.02,
                            height: 1.0,
                        },
                        z(0.5),
                        upright,
                    ),
                    Piece::new(
                        Form::Cylinder {
                            radius: 0.4,
                            height: 0.06,
                        },
                        z(1.0),
                        upright,
                    ),
                ]),
                pivot(1.0),
            ],
            trail: Trail::Tip(0, z(1.1)),
            reach: 1.1,
        }
    }

    /// The drawing of a scene file's `[body]`: its parts about its fixed point, the trail on
    /// the intermediate principal axis (the flip axis of the Dzhanibekov effect; for a top, the
    /// axis it spins about wobbles with it).
    #[must_use]
    pub fn of_body(drawing: &BodyDrawing, params: &Params) -> Self {
        let reach = pieces::reach(&drawing.parts, &drawing.center).max(1e-9);
        let axes = ["frame_phi", "frame_theta", "frame_psi"].map(|k| params.get(k).unwrap_or(0.0));
        let q = EulerConvention::ARTICLE.to_rotation(&Vector3::from(axes));
        let tip = q.matrix().column(1).into_owned() * 1.15 * reach;
        Drawing {
            objects: vec![
                body(pieces::parts(&drawing.parts, &drawing.center)),
                pivot(reach),
            ],
            trail: Trail::Tip(0, tip),
            reach,
        }
    }

    /// Whether any object is placed by the scene ([`Motion::PlacedBody`],
    /// [`Motion::PlacedPoint`]).
    #[must_use]
    pub fn is_placed(&self) -> bool {
        self.objects
            .iter()
            .any(|o| matches!(o.motion, Motion::PlacedBody(_) | Motion::PlacedPoint(_)))
    }
}
