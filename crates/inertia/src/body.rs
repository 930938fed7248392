//! A body assembled from sources: closed meshes (in a length unit), point masses and placed
//! primitives, combined into one [`MassProperties`].
//!
//! The same vocabulary serves the `tumble inertia` command and the `[body]` table of scene
//! files:
//!
//! * **Shapes** are written `KIND:DIMENSIONS` ([`Shape::parse`]): `box:a,b,c` (sides along x,
//!   y, z), `cylinder:r,h` (axis z), `sphere:r`, `torus:R,r` (axis z), `hoop:r` (thin ring in
//!   the x–y plane) and `rod:l` (thin, along z). Each is centred at its own origin
//!   ([`primitives`](crate::primitives)); a [`Placement`] turns it by the article's ZYZ Euler
//!   angles about that centre, then moves its centre to `at`. A solid shape takes a mass or a
//!   density; a hoop or a rod has no volume and takes a mass only.
//! * **Point masses** come as text, one `m, x, y, z` a line ([`parse_points`]).
//! * **Meshes** are in a length [`Units`]; [`TriangleMesh::scaled`] brings them to metres before
//!   their integrals are taken, so a density is always in kg/m³.
//!
//! [`MassProperties::combine_all`] then sums the parts about their common centre of mass.

use std::fmt;
use std::str::FromStr;

use nalgebra::Vector3;
use tumble_kinematics::angle::parse_angle;

use crate::error::InertiaError;
use crate::mass_properties::{MassProperties, PointMass};
use crate::mesh::MassSpec;

/// What is wrong with a body's description (a shape, a unit, a line of point masses).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BodyError {
    /// A shape kind that does not exist.
    #[error("unknown shape `{kind}` in `{text}`; shapes: {KNOWN_SHAPES}")]
    UnknownShape {
        /// The kind as written.
        kind: String,
        /// The whole specification.
        text: String,
    },
    /// A shape with the wrong number of dimensions.
    #[error("`{text}`: a {kind} takes {expected} ({form}), got {got} value(s)")]
    ShapeArity {
        /// The kind.
        kind: &'static str,
        /// How many values it takes.
        expected: usize,
        /// The form, e.g. `box:a,b,c`.
        form: &'static str,
        /// How many were given.
        got: usize,
        /// The whole specification.
        text: String,
    },
    /// A dimension that is not a number.
    #[error("`{text}`: value {index} (`{value}`) is not a number")]
    ShapeValue {
        /// 1-based position of the value.
        index: usize,
        /// The value as written.
        value: String,
        /// The whole specification.
        text: String,
    },
    /// A density for a shape without volume.
    #[error("a {kind} has no volume, so it takes a mass, not a density")]
    DensityWithoutVolume {
        /// The kind (`hoop`, `rod`).
        kind: &'static str,
    },
    /// An unknown length unit.
    #[error("unknown length unit `{text}`; units: mm, cm, m")]
    UnknownUnits {
        /// The unit as written.
        text: String,
    },
    /// A line of a point-mass list that is not `m, x, y, z` with a positive finite mass and a
    /// finite position.
    #[error("line {line}: {reason}")]
    PointLine {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A shape or the assembled body is not physical.
    #[error(transparent)]
    Inertia(#[from] InertiaError),
}

/// The shape kinds and their forms, for messages.
pub const KNOWN_SHAPES: &str =
    "box:a,b,c, cylinder:r,h, sphere:r, torus:R,r, hoop:r, rod:l (lengths in m)";

/// A length unit of a mesh file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Units {
    /// Metres (the default).
    #[default]
    Metre,
    /// Centimetres.
    Centimetre,
    /// Millimetres.
    Millimetre,
}

impl Units {
    /// Metres per unit: 1, 1e-2, 1e-3.
    #[must_use]
    pub fn metres(self) -> f64 {
        match self {
            Units::Metre => 1.0,
            Units::Centimetre => 1e-2,
            Units::Millimetre => 1e-3,
        }
    }
}

impl FromStr for Units {
    type Err = BodyError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "m" => Ok(Units::Metre),
            "cm" => Ok(Units::Centimetre),
            "mm" => Ok(Units::Millimetre),
            other => Err(BodyError::UnknownUnits {
                text: other.to_string(),
            }),
        }
    }
}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Units::Metre => "m",
            Units::Centimetre => "cm",
            Units::Millimetre => "mm",
        })
    }
}

/// A primitive shape with its dimensions (m), centred at its origin, symmetry axis z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Solid box, sides along x, y, z.
    Box(Vector3<f64>),
    /// Solid cylinder of radius and height.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height along z.
        height: f64,
    },
    /// Solid sphere.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// Solid torus.
    Torus {
        /// Radius of the centre-line circle.
        major: f64,
        /// Radius of the tube.
        minor: f64,
    },
    /// Thin hoop in the x–y plane.
    Hoop {
        /// Radius.
        radius: f64,
    },
    /// Thin rod along z.
    Rod {
        /// Length.
        length: f64,
    },
}

impl Shape {
    /// Parses `KIND:D1,D2,…` (see the [module docs](self)); dimensions are numbers or angle
    /// expressions (`pi` is accepted, for what it is worth). Their ranges are checked when the
    /// mass properties are computed.
    ///
    /// # Errors
    /// [`BodyError::UnknownShape`], [`BodyError::ShapeArity`], [`BodyError::ShapeValue`].
    pub fn parse(text: &str) -> Result<Self, BodyError> {
        let (kind, rest) = text.split_once(':').unwrap_or((text, ""));
        let kind = kind.trim();
        let (name, form, arity): (&'static str, &'static str, usize) = match kind {
            "box" => ("box", "box:a,b,c", 3),
            "cylinder" => ("cylinder", "cylinder:r,h", 2),
            "sphere" => ("sphere", "sphere:r", 1),
            "torus" => ("torus", "torus:R,r", 2),
            "hoop" => ("hoop", "hoop:r", 1),
            "rod" => ("rod", "rod:l", 1),
            _ => {
                return Err(BodyError::UnknownShape {
                    kind: kind.to_string(),
                    text: text.to_string(),
                });
            }
        };
        let parts: Vec<&str> = if rest.trim().is_empty() {
            Vec::new()
        } else {
            rest.split(',').collect()
        };
        if parts.len() != arity {
            return Err(BodyError::ShapeArity {
                kind: name,
                expected: arity,
                form,
                got: parts.len(),
                text: text.to_string(),
            });
        }
        let mut d = [0.0; 3];
        for (i, p) in parts.iter().enumerate() {
            d[i] = parse_angle(p).ok_or_else(|| BodyError::ShapeValue {
                index: i + 1,
                value: p.trim().to_string(),
                text: text.to_string(),
            })?;
        }
        Ok(match name {
            "box" => Shape::Box(Vector3::new(d[0], d[1], d[2])),
            "cylinder" => Shape::Cylinder {
                radius: d[0],
                height: d[1],
            },
            "sphere" => Shape::Sphere { radius: d[0] },
            "torus" => Shape::Torus {
                major: d[0],
                minor: d[1],
            },
            "hoop" => Shape::Hoop { radius: d[0] },
            _ => Shape::Rod { length: d[0] },
        })
    }

    /// The kind's name (`box`, `cylinder`, …).
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Box(_) => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Torus { .. } => "torus",
            Shape::Hoop { .. } => "hoop",
            Shape::Rod { .. } => "rod",
        }
    }

    /// The volume (m³) of a solid shape; `None` for a hoop or a rod.
    #[must_use]
    pub fn volume(&self) -> Option<f64> {
        use std::f64::consts::PI;
        match *self {
            Shape::Box(s) => Some(s.x * s.y * s.z),
            Shape::Cylinder { radius, height } => Some(PI * radius * radius * height),
            Shape::Sphere { radius } => Some(4.0 / 3.0 * PI * radius.powi(3)),
            Shape::Torus { major, minor } => Some(2.0 * PI * PI * major * minor * minor),
            Shape::Hoop { .. } | Shape::Rod { .. } => None,
        }
    }

    /// The shape's mass properties, centred at its origin, for a total mass or a uniform
    /// density.
    ///
    /// # Errors
    /// [`BodyError::DensityWithoutVolume`] for a density given to a hoop or a rod; an
    /// [`InertiaError`] for a dimension, mass or density that is not finite and positive.
    pub fn mass_properties(&self, spec: MassSpec) -> Result<MassProperties, BodyError> {
        let mass = match (spec, self.volume()) {
            (MassSpec::TotalMass(m), _) => m,
            (MassSpec::Density(_), None) => {
                return Err(BodyError::DensityWithoutVolume { kind: self.kind() });
            }
            (MassSpec::Density(rho), Some(volume)) => {
                if !(rho.is_finite() && rho > 0.0) {
                    return Err(InertiaError::InvalidDensity { density: rho }.into());
                }
                // Dimensions are checked by the constructor below; a bad one gives a bad
                // volume, which the constructor's own check reports by name.
                rho * volume
            }
        };
        let props = match *self {
            Shape::Box(s) => MassProperties::solid_box(mass, &s),
            Shape::Cylinder { radius, height } => {
                MassProperties::solid_cylinder(mass, radius, height)
            }
            Shape::Sphere { radius } => MassProperties::solid_sphere(mass, radius),
            Shape::Torus { major, minor } => MassProperties::solid_torus(mass, major, minor),
            Shape::Hoop { radius } => MassProperties::thin_hoop(mass, radius),
            Shape::Rod { length } => MassProperties::thin_rod(mass, length),
        };
        // A bad dimension with a density makes the mass bad too; name the dimension first.
        match props {
            Err(InertiaError::NonPositiveMass { .. } | InertiaError::NonFiniteMass { .. })
                if matches!(spec, MassSpec::Density(_)) =>
            {
                let dims = self.dimensions();
                let bad = dims.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0));
                Err(match bad {
                    Some(&(name, value)) => InertiaError::InvalidDimension {
                        name,
                        value,
                        requirement: "must be finite and positive",
                    },
                    None => InertiaError::NonPositiveMass { mass },
                }
                .into())
            }
            other => Ok(other?),
        }
    }

    fn dimensions(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Shape::Box(s) => vec![
                ("box side x", s.x),
                ("box side y", s.y),
                ("box side z", s.z),
            ],
            Shape::Cylinder { radius, height } => vec![("radius", radius), ("height", height)],
            Shape::Sphere { radius } | Shape::Hoop { radius } => vec![("radius", radius)],
            Shape::Torus { major, minor } => vec![("major radius", major), ("minor radius", minor)],
            Shape::Rod { length } => vec![("length", length)],
        }
    }
}

/// Where a part sits in the body frame: turned by the article's ZYZ Euler angles about its own
/// centre, then its centre moved to `at`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Placement {
    /// Position of the part's centre (m).
    pub at: Vector3<f64>,
    /// ZYZ Euler angles `(φ, θ, ψ)` (rad): `R = Rz(φ) Ry(θ) Rz(ψ)`.
    pub euler: Vector3<f64>,
}

impl Placement {
    /// `props`, given about its own centre at the origin, turned and moved into place: tensor
    /// `R I Rᵀ`, centre `R c + at`.
    #[must_use]
    pub fn place(&self, props: &MassProperties) -> MassProperties {
        props.turned_zyz(&self.euler).translated(&self.at)
    }
}

/// Parses point masses, one `m, x, y, z` a line (kg, m), separated by commas; blank lines and
/// lines starting with `#` are skipped, and a first line `m,x,y,z` is taken as a header.
///
/// # Errors
/// [`BodyError::PointLine`] naming the line: not four fields, a field that is not a number, a
/// mass that is not positive and finite, a position that is not finite. An empty list is not an
/// error here ([`MassProperties::from_point_masses`] refuses it).
pub fn parse_points(text: &str) -> Result<Vec<PointMass>, BodyError> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut points = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| BodyError::PointLine {
            line: e.position().map_or(0, |p| p.line() as usize),
            reason: e.to_string(),
        })?;
        let line = record.position().map_or(k + 1, |p| p.line() as usize);
        let fields: Vec<&str> = record.iter().collect();
        if fields.iter().all(|f| f.is_empty()) {
            continue;
        }
        if points.is_empty() && fields.first().is_some_and(|f| f.eq_ignore_ascii_case("m")) {
            continue;
        }
        let bad = |reason: String| BodyError::PointLine { line, reason };
        if fields.len() != 4 {
            return Err(bad(format!(
                "expected four values `m, x, y, z`, found {}",
                fields.len()
            )));
        }
        let mut v = [0.0; 4];
        for (i, f) in fields.iter().enumerate() {
            v[i] = f.parse::<f64>().map_err(|_| {
                bad(format!(
                    "`{f}` ({}) is not a number",
                    ["m", "x", "y", "z"][i]
                ))
            })?;
        }
        if !(v[0].is_finite() && v[0] > 0.0) {
            return Err(bad(format!("mass {} must be positive and finite", v[0])));
        }
        if !v[1..].iter().all(|x| x.is_finite()) {
            return Err(bad("the position must be finite".to_string()));
        }
        points.push(PointMass::new(
            v[0],
            nalgebra::Point3::new(v[1], v[2], v[3]),
        ));
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_parse_with_their_dimensions_and_refuse_bad_forms() {
        assert_eq!(
            Shape::parse("box:2,1,0.5").unwrap(),
            Shape::Box(Vector3::new(2.0, 1.0, 0.5))
        );
        assert_eq!(
            Shape::parse("torus: 1, 0.25").unwrap(),
            Shape::Torus {
                major: 1.0,
                minor: 0.25
            }
        );
        assert!(matches!(
            Shape::parse("cube:1"),
            Err(BodyError::UnknownShape { .. })
        ));
        assert!(matches!(
            Shape::parse("box:1,2"),
            Err(BodyError::ShapeArity { got: 2, .. })
        ));
        assert!(matches!(
            Shape::parse("rod"),
            Err(BodyError::ShapeArity { got: 0, .. })
        ));
        assert!(matches!(
            Shape::parse("sphere:x"),
            Err(BodyError::ShapeValue { index: 1, .. })
        ));
    }

    #[test]
    fn a_density_gives_the_shape_its_volume_times_density() {
        let ball = Shape::Sphere { radius: 0.5 }
            .mass_properties(MassSpec::Density(3.0))
            .unwrap();
        let volume = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!((ball.mass() - 3.0 * volume).abs() < 1e-15);
        assert!(matches!(
            Shape::Rod { length: 1.0 }.mass_properties(MassSpec::Density(1.0)),
            Err(BodyError::DensityWithoutVolume { kind: "rod" })
        ));
        assert!(matches!(
            Shape::Box(Vector3::new(1.0, -1.0, 1.0)).mass_properties(MassSpec::Density(1.0)),
            Err(BodyError::Inertia(InertiaError::InvalidDimension {
                name: "box side y",
                ..
            }))
        ));
        assert!(matches!(
            Shape::Sphere { radius: 1.0 }.mass_properties(MassSpec::TotalMass(-1.0)),
            Err(BodyError::Inertia(InertiaError::NonPositiveMass { .. }))
        ));
    }

    #[test]
    fn point_lists_skip_comments_and_a_header_and_name_the_bad_line() {
        let points = parse_points("# a dumbbell\nm,x,y,z\n1, -0.5, 0, 0\n\n2,0.5,0,0\n").unwrap();
        assert_eq!(points.len(), 2);
        assert_eq!(points[1].mass, 2.0);
        assert_eq!(points[0].position.x, -0.5);
        let e = parse_points("1,0,0,0\n-1,1,0,0\n").unwrap_err();
        assert_eq!(
            e,
            BodyError::PointLine {
                line: 2,
                reason: "mass -1 must be positive and finite".into()
            }
        );
        let e = parse_points("1,0,0\n").unwrap_err();
        assert!(matches!(e, BodyError::PointLine { line: 1, .. }), "{e}");
        let e = parse_points("1,0,0,zero\n").unwrap_err();
        assert!(e.to_string().contains("`zero` (z)"), "{e}");
        assert!(parse_points("# nothing\n").unwrap().is_empty());
    }

    #[test]
    fn a_mesh_in_millimetres_scales_mass_properties_by_powers_of_1e_3() {
        // The T-handle written in millimetres: with one density, read as metres its volume is
        // 1e9 times, its centre 1e3 times and its tensor 1e15 times that of the file read in
        // millimetres; scaled by 1e-3 it is the metre mesh to round-off.
        let metres = crate::THandle::STANDARD.mesh().unwrap();
        let mm = metres.scaled(1e3).unwrap();
        let back = mm.scaled(Units::Millimetre.metres()).unwrap();
        let rho = MassSpec::Density(2700.0);
        let (a, b, raw) = (
            metres.mass_properties(rho).unwrap(),
            back.mass_properties(rho).unwrap(),
            mm.mass_properties(rho).unwrap(),
        );
        let rel = |x: f64, y: f64| ((x - y) / y).abs();
        assert!(rel(b.mass(), a.mass()) < 1e-14);
        assert!(rel(raw.mass(), 1e9 * a.mass()) < 1e-14);
        assert!((b.center_of_mass() - a.center_of_mass()).norm() < 1e-17);
        assert!((raw.center_of_mass().coords - a.center_of_mass().coords * 1e3).norm() < 1e-13);
        let scale = a.inertia().norm();
        assert!((b.inertia() - a.inertia()).norm() < 1e-14 * scale);
        assert!((raw.inertia() / 1e15 - a.inertia()).norm() < 1e-14 * scale);
    }

    #[test]
    fn units_scale_to_metres() {
        assert_eq!("mm".parse::<Units>().unwrap().metres(), 1e-3);
        assert_eq!("cm".parse::<Units>().unwrap().metres(), 1e-2);
        assert_eq!("m".parse::<Units>().unwrap().metres(), 1.0);
        assert!("inch".parse::<Units>().is_err());
    }
}
