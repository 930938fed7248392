//! The `[body]` table of scene files: a rigid body from a mesh, point masses and primitives
//! (the sources of `tumble inertia`), turned into the parameters of a body scene
//! ([`scenes::body`](crate::scenes::body)).
//!
//! ```toml
//! [body]
//! mesh = "t-handle.obj"       # relative to the scene file; OBJ or STL
//! units = "m"                 # of the mesh: mm, cm or m
//! mass = 0.05                 # of the mesh (or density = 2700.0, kg/m³)
//! points = "masses.csv"       # point masses, one `m, x, y, z` a line (relative path)
//! point = [[0.1, 0.0, 0.0, 0.3]]        # ... or inline
//! pivot = [0.0, 0.0, 0.0]     # heavy-top only: the fixed point, a point of the body
//!
//! [[body.shape]]              # repeatable
//! shape = "cylinder:0.1,0.01" # box:a,b,c, cylinder:r,h, sphere:r, torus:R,r, hoop:r, rod:l
//! mass = 1.0                  # or density
//! at = [0.0, 0.0, 0.2]        # where its centre goes
//! euler = [0.0, "pi/2", 0.0]  # its ZYZ turn about its centre
//! ```
//!
//! Numbers may be angle expressions as strings. Every error names the file, the line and the
//! key (`body.mesh`, `body.shape[2].mass`, …).

use std::ops::Range;
use std::path::Path;

use nalgebra::{Point3, Vector3};
use serde::Deserialize;
use toml::Spanned;
use tumble_inertia::{
    MassProperties, MassSpec, Placement, PointMass, Shape, Units, ValidationOptions, load_mesh,
    parse_points,
};
use tumble_kinematics::EulerConvention;

use crate::drawing::Part;
use crate::params::Params;
use crate::scenes::body::BodySceneKind;
use crate::toml_file::{self, Location};

/// A number as written.
type RawNumber = Spanned<toml::Value>;

/// The `[body]` table as TOML gives it (deserialized inside other files' tables, such as a
/// model's `geometry`, and read by [`read_mass_properties`]).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    mesh: Option<Spanned<String>>,
    units: Option<Spanned<String>>,
    mass: Option<RawNumber>,
    density: Option<RawNumber>,
    flip_inverted: Option<bool>,
    points: Option<Spanned<String>>,
    point: Option<Vec<Spanned<Vec<RawNumber>>>>,
    shape: Option<Vec<Spanned<RawShape>>>,
    pivot: Option<Spanned<Vec<RawNumber>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShape {
    shape: Spanned<String>,
    mass: Option<RawNumber>,
    density: Option<RawNumber>,
    at: Option<Spanned<Vec<RawNumber>>>,
    euler: Option<Spanned<Vec<RawNumber>>>,
}

impl RawBody {
    /// The sources, in words: `mesh t-handle.obj`, `2 shapes`, ….
    pub(crate) fn describe(&self) -> String {
        let mut parts = Vec::new();
        if let Some(m) = &self.mesh {
            parts.push(format!("mesh {}", m.get_ref()));
        }
        if let Some(p) = &self.points {
            parts.push(format!("points {}", p.get_ref()));
        }
        if let Some(p) = &self.point {
            parts.push(format!("{} point(s)", p.len()));
        }
        if let Some(s) = &self.shape {
            parts.push(format!("{} shape(s)", s.len()));
        }
        parts.join(", ")
    }
}

/// What is wrong with a `[body]` table: where, which key, what.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyTableError {
    /// Where the key is.
    pub at: Location,
    /// The dotted key.
    pub key: String,
    /// What is wrong.
    pub message: String,
}

/// Where the text is, to place errors.
pub(crate) struct Place<'a> {
    pub(crate) origin: &'a str,
    pub(crate) text: &'a str,
}

impl Place<'_> {
    fn error(&self, span: &Range<usize>, key: &str, message: impl ToString) -> BodyTableError {
        BodyTableError {
            at: Location::at(self.origin, self.text, span.start),
            key: key.to_string(),
            message: message.to_string(),
        }
    }

    fn number(&self, key: &str, value: &RawNumber) -> Result<f64, BodyTableError> {
        let x = toml_file::number_or_angle(value.get_ref()).map_err(|found| {
            self.error(
                &value.span(),
                key,
                format!("must be a number, found {found}"),
            )
        })?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.error(&value.span(), key, format!("must be finite, found {x}")))
        }
    }

    fn triple(
        &self,
        key: &str,
        value: &Spanned<Vec<RawNumber>>,
    ) -> Result<Vector3<f64>, BodyTableError> {
        let list = value.get_ref();
        if list.len() != 3 {
            return Err(self.error(
                &value.span(),
                key,
                format!("must be three numbers [x, y, z], found {}", list.len()),
            ));
        }
        let mut v = Vector3::zeros();
        for (i, x) in list.iter().enumerate() {
            v[i] = self.number(key, x)?;
        }
        Ok(v)
    }

    /// `mass` or `density` (exactly one), for the key prefix `prefix`.
    fn mass_spec(
        &self,
        prefix: &str,
        span: &Range<usize>,
        mass: Option<&RawNumber>,
        density: Option<&RawNumber>,
    ) -> Result<MassSpec, BodyTableError> {
        match (mass, density) {
            (Some(m), None) => Ok(MassSpec::TotalMass(
                self.number(&format!("{prefix}mass"), m)?,
            )),
            (None, Some(d)) => Ok(MassSpec::Density(
                self.number(&format!("{prefix}density"), d)?,
            )),
            (Some(_), Some(d)) => Err(self.error(
                &d.span(),
                &format!("{prefix}density"),
                "give a mass or a density, not both",
            )),
            (None, None) => Err(self.error(
                span,
                prefix.trim_end_matches('.'),
                "needs a `mass` (kg) or a `density` (kg/m³)",
            )),
        }
    }
}

/// The body of a `[body]` table, its parts (to draw it) and, for the heavy top, its pivot.
pub(crate) struct Body {
    pub(crate) props: MassProperties,
    pub(crate) pivot: Option<Point3<f64>>,
    pub(crate) parts: Vec<Part>,
}

/// Reads every source of the table (files relative to the scene file's directory) and combines
/// them.
pub(crate) fn read(
    place: &Place<'_>,
    table: &Spanned<RawBody>,
    kind: BodySceneKind,
) -> Result<Body, BodyTableError> {
    let span = table.span();
    let raw = table.get_ref();
    let dir = Path::new(place.origin).parent().unwrap_or(Path::new(""));
    let mut parts = Vec::new();
    let mut drawn = Vec::new();
    if let Some(mesh) = &raw.mesh {
        let units = match &raw.units {
            None => Units::Metre,
            Some(u) => u
                .get_ref()
                .parse::<Units>()
                .map_err(|e| place.error(&u.span(), "body.units", e))?,
        };
        let options = ValidationOptions {
            flip_inverted: raw.flip_inverted.unwrap_or(false),
            ..ValidationOptions::default()
        };
        let path = dir.join(mesh.get_ref());
        let loaded = load_mesh(&path, &options)
            .map_err(|e| place.error(&mesh.span(), "body.mesh", chain(&e)))?
            .scaled(units.metres())
            .map_err(|e| place.error(&mesh.span(), "body.mesh", e))?;
        let spec = place.mass_spec("body.", &span, raw.mass.as_ref(), raw.density.as_ref())?;
        let props = loaded.mass_properties(spec).map_err(|e| {
            let key = match spec {
                MassSpec::TotalMass(_) => "body.mass",
                MassSpec::Density(_) => "body.density",
            };
            let at = raw
                .mass
                .as_ref()
                .or(raw.density.as_ref())
                .map_or(span.clone(), Spanned::span);
            place.error(&at, key, e)
        })?;
        parts.push(props);
        drawn.push(Part::Mesh(loaded));
    } else if let Some(u) = &raw.units {
        return Err(place.error(
            &u.span(),
            "body.units",
            "gives the unit of a mesh, and there is no `mesh`",
        ));
    } else if let Some(m) = raw.mass.as_ref().or(raw.density.as_ref()) {
        return Err(place.error(
            &m.span(),
            if raw.mass.is_some() {
                "body.mass"
            } else {
                "body.density"
            },
            "gives the mass of a mesh, and there is no `mesh` (shapes take their own)",
        ));
    }
    let mut points: Vec<PointMass> = Vec::new();
    if let Some(file) = &raw.points {
        let path = dir.join(file.get_ref());
        let text = std::fs::read_to_string(&path).map_err(|e| {
            place.error(
                &file.span(),
                "body.points",
                format!("{}: cannot read: {e}", path.display()),
            )
        })?;
        let read = parse_points(&text).map_err(|e| {
            place.error(
                &file.span(),
                "body.points",
                format!("{}: {e}", path.display()),
            )
        })?;
        if read.is_empty() {
            return Err(place.error(
                &file.span(),
                "body.points",
                format!(
                    "{}: no point masses (one `m, x, y, z` a line)",
                    path.display()
                ),
            ));
        }
        points.extend(read);
    }
    for (k, p) in raw.point.iter().flatten().enumerate() {
        let key = format!("body.point[{}]", k + 1);
        let list = p.get_ref();
        if list.len() != 4 {
            return Err(place.error(
                &p.span(),
                &key,
                format!("must be four numbers [m, x, y, z], found {}", list.len()),
            ));
        }
        let v: Vec<f64> = list
            .iter()
            .map(|x| place.number(&key, x))
            .collect::<Result<_, _>>()?;
        if !(v[0] > 0.0) {
            return Err(place.error(&p.span(), &key, format!("mass {} must be positive", v[0])));
        }
        points.push(PointMass::new(v[0], Point3::new(v[1], v[2], v[3])));
    }
    if let Some(list) = &raw.point
        && list.is_empty()
    {
        return Err(place.error(&span, "body.point", "is an empty list: no point masses"));
    }
    if !points.is_empty() {
        let props = MassProperties::from_point_masses(&points)
            .map_err(|e| place.error(&span, "body.point", e))?;
        parts.push(props);
        drawn.push(Part::Points(points));
    }
    for (k, s) in raw.shape.iter().flatten().enumerate() {
        let prefix = format!("body.shape[{}].", k + 1);
        let raw_shape = s.get_ref();
        let shape = Shape::parse(raw_shape.shape.get_ref())
            .map_err(|e| place.error(&raw_shape.shape.span(), &format!("{prefix}shape"), e))?;
        let spec = place.mass_spec(
            &prefix,
            &s.span(),
            raw_shape.mass.as_ref(),
            raw_shape.density.as_ref(),
        )?;
        let props = shape.mass_properties(spec).map_err(|e| {
            use tumble_inertia::{BodyError, InertiaError};
            let (key, span) = match (&e, spec) {
                (
                    BodyError::Inertia(
                        InertiaError::NonPositiveMass { .. } | InertiaError::NonFiniteMass { .. },
                    ),
                    MassSpec::TotalMass(_),
                ) => ("mass", raw_shape.mass.as_ref().map(Spanned::span)),
                (
                    BodyError::Inertia(InertiaError::InvalidDensity { .. })
                    | BodyError::DensityWithoutVolume { .. },
                    _,
                ) => ("density", raw_shape.density.as_ref().map(Spanned::span)),
                _ => ("shape", Some(raw_shape.shape.span())),
            };
            place.error(&span.unwrap_or(s.span()), &format!("{prefix}{key}"), e)
        })?;
        let placement = Placement {
            at: raw_shape
                .at
                .as_ref()
                .map(|v| place.triple(&format!("{prefix}at"), v))
                .transpose()?
                .unwrap_or_default(),
            euler: raw_shape
                .euler
                .as_ref()
                .map(|v| place.triple(&format!("{prefix}euler"), v))
                .transpose()?
                .unwrap_or_default(),
        };
        parts.push(placement.place(&props));
        drawn.push(Part::Shape(shape, placement));
    }
    if parts.is_empty() {
        return Err(place.error(
            &span,
            "body",
            "has no mass: give a `mesh`, `points`, `point` or `[[body.shape]]`",
        ));
    }
    let props = MassProperties::combine_all(&parts).map_err(|e| place.error(&span, "body", e))?;
    let pivot = match (&raw.pivot, kind) {
        (Some(p), BodySceneKind::HeavyTop) => Some(Point3::from(place.triple("body.pivot", p)?)),
        (None, BodySceneKind::HeavyTop) => {
            return Err(place.error(
                &span,
                "body.pivot",
                "the heavy top needs its fixed point: pivot = [x, y, z]",
            ));
        }
        (Some(p), _) => {
            return Err(place.error(
                &p.span(),
                "body.pivot",
                "only the heavy top has a pivot; a free body turns about its centre of mass",
            ));
        }
        (None, _) => None,
    };
    Ok(Body {
        props,
        pivot,
        parts: drawn,
    })
}

/// The mass properties of a `[body]` table written inside another file (`origin`, its `text`):
/// every source combined, in the table's own frame; files are relative to `origin`'s directory.
/// A `pivot` is refused (it belongs to the heavy-top scene).
///
/// # Errors
/// As the scene file's `[body]` table: the key, its place and what is wrong.
pub fn read_mass_properties(
    origin: &str,
    text: &str,
    table: &Spanned<RawBody>,
) -> Result<MassProperties, BodyTableError> {
    read_body(origin, text, table).map(|(props, _)| props)
}

/// As [`read_mass_properties`], with the parts that draw the body (in the table's frame).
///
/// # Errors
/// As [`read_mass_properties`].
pub fn read_body(
    origin: &str,
    text: &str,
    table: &Spanned<RawBody>,
) -> Result<(MassProperties, Vec<crate::drawing::Part>), BodyTableError> {
    let place = Place { origin, text };
    read(&place, table, BodySceneKind::Free).map(|body| (body.props, body.parts))
}

/// An error and its sources, on one line.
fn chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// Sets the body's parameters: principal moments (about the centre of mass, or the pivot for
/// the top), the principal axes as ZYZ angles, and for the top the mass and the centre of mass
/// from the pivot.
///
/// # Errors
/// A message for a body with a zero principal moment (a thin rod, collinear points: a rigid-body
/// scene needs three positive moments) or moments a scene refuses.
pub(crate) fn set_params(body: &Body, params: &mut Params) -> Result<(), String> {
    let tensor = match body.pivot {
        Some(p) => body.props.inertia_about(&p),
        None => *body.props.inertia(),
    };
    // Checked as a possibly idealized body first, so that a zero moment gets the message below.
    let reference = body.pivot.unwrap_or(body.props.center_of_mass());
    let checked = MassProperties::try_new_idealized(body.props.mass(), reference, tensor)
        .map_err(|e| e.to_string())?;
    let principal = checked.principal();
    let moments = principal.moments;
    let about = if body.pivot.is_some() {
        "about the pivot"
    } else {
        "about the centre of mass"
    };
    if !(moments[0] > 1e-12 * moments[2]) {
        return Err(format!(
            "the body's principal moments {about} are ({:e}, {:e}, {:e}) kg·m²: one is zero (a \
             thin rod along its axis, collinear point masses, or a pivot on that axis), and a \
             rigid-body scene needs three positive moments",
            moments[0], moments[1], moments[2]
        ));
    }
    let angles = EulerConvention::ARTICLE
        .from_rotation(&principal.axes)
        .angles;
    let values = [
        ("I1", moments[0]),
        ("I2", moments[1]),
        ("I3", moments[2]),
        ("frame_phi", angles[0]),
        ("frame_theta", angles[1]),
        ("frame_psi", angles[2]),
    ];
    for (name, value) in values {
        params.set(name, value).map_err(|e| e.to_string())?;
    }
    if let Some(pivot) = body.pivot {
        let c = body.props.center_of_mass() - pivot;
        params
            .set("mass", body.props.mass())
            .map_err(|e| e.to_string())?;
        for (name, value) in [("cx", c.x), ("cy", c.y), ("cz", c.z)] {
            params.set(name, value).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
