//! A rigid body's mass properties in a model: from `geometry` (the `[body]` vocabulary: mesh,
//! points, shapes; computed once), or from `mass`, `com` and `inertia` as expressions of the
//! parameters.

use toml::Spanned;
use tumble_scenarios::body_table::read_body;

use super::ModelFileError;
use super::raw::RawBodyDef;
use super::reader::{Names, Src};
use crate::expr::{Graph, Id};
use crate::mechanics::{Algebra, Layout, M3, V3};
use tumble_scenarios::drawing::Part;

/// Mass, centre of mass (in the body's frame), inertia about the centre of mass, and the parts
/// to draw where a `geometry` gave them.
pub(super) type MassProperties = (Id, V3, M3, Option<Vec<Part>>);

/// The mass properties of the body `name` declared by `b` at `key`, its expressions in
/// `param_scope` (the parameters: a body's mass does not change in a run).
pub(super) fn mass_properties(
    src: &Src<'_>,
    key: &str,
    name: &Spanned<String>,
    b: &RawBodyDef,
    graph: &mut Graph,
    param_scope: &Names,
) -> Result<MassProperties, ModelFileError> {
    let zero = graph.constant(0.0);
    Ok(match &b.geometry {
        Some(geometry) => {
            for (k, present) in [
                ("mass", b.mass.is_some()),
                ("com", b.com.is_some()),
                ("inertia", b.inertia.is_some()),
            ] {
                if present {
                    return Err(src.invalid(
                        &geometry.span(),
                        &format!("{key}.{k}"),
                        "is computed from `geometry`; give one or the other",
                    ));
                }
            }
            let (props, parts) =
                read_body(src.origin, src.text, geometry).map_err(|e| ModelFileError::Invalid {
                    at: e.at,
                    key: format!("{key}.geometry: {}", e.key),
                    message: e.message,
                    excerpt: String::new(),
                })?;
            let c = props.center_of_mass();
            let i = props.inertia();
            let m = graph.constant(props.mass());
            let com = [c.x, c.y, c.z].map(|x| graph.constant(x));
            let mut inertia = [[zero; 3]; 3];
            for r in 0..3 {
                for s in 0..3 {
                    inertia[r][s] = graph.constant(i[(r, s)]);
                }
            }
            (m, com, inertia, Some(parts))
        }
        None => {
            let Some(mass) = &b.mass else {
                return Err(src.invalid(&name.span(), key, "needs a `mass` (with `inertia` and `com`) or a `geometry` table (the [body] vocabulary: mesh, points, shapes)"));
            };
            let mass = src.expr(&format!("{key}.mass"), mass, graph, param_scope)?;
            let com = match &b.com {
                Some(c) => src.vector(&format!("{key}.com"), c, graph, param_scope)?,
                None => [zero; 3],
            };
            let mut inertia = [[zero; 3]; 3];
            if let Some(list) = &b.inertia {
                let ik = format!("{key}.inertia");
                let v: Vec<Id> = list
                    .get_ref()
                    .iter()
                    .enumerate()
                    .map(|(k, x)| src.expr(&format!("{ik}[{}]", k + 1), x, graph, param_scope))
                    .collect::<Result<_, _>>()?;
                match v.len() {
                    3 => (0..3).for_each(|k| inertia[k][k] = v[k]),
                    6 => {
                        (0..3).for_each(|k| inertia[k][k] = v[k]);
                        for (k, (r, s)) in [(0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
                            inertia[r][s] = v[3 + k];
                            inertia[s][r] = v[3 + k];
                        }
                    }
                    found => return Err(src.invalid(&list.span(), &ik, format!("must be 3 principal moments or 6 entries [xx, yy, zz, xy, xz, yz] about the centre of mass, found {found}"))),
                }
            }
            (mass, com, inertia, None)
        }
    })
}

/// The energy of a model's masses, term by term, as they are read.
pub(super) struct Energy {
    /// Terms of the kinetic energy.
    pub(super) kinetic: Vec<Id>,
    /// Terms of the potential energy.
    pub(super) potential: Vec<Id>,
    /// Uniform gravity (model frame), if given.
    pub(super) gravity: Option<V3>,
    /// The model frame's angular velocity, if it turns.
    pub(super) frame_omega: Option<V3>,
    pub(super) layout: Layout,
}

impl Energy {
    /// ½ m |ṙ + Ω × r|² and −m g·r for a mass at r (model frame). For a mass at
    /// `r = origin + R x` carried by an orientation on SO(3) (`on_so3 = Some((ω, x, origin))`)
    /// about a fixed origin in a model frame that does not turn, |ṙ| = |ω × x + ẋ|: the same
    /// value on SO(3), written without R, so that the kinetic energy and the mass matrix do not
    /// depend on the orientation (as a body's does not).
    pub(super) fn translational(
        &mut self,
        graph: &mut Graph,
        mass: Id,
        r: V3,
        on_so3: Option<(V3, V3, V3)>,
    ) {
        let layout = self.layout;
        let mut alg = Algebra { g: graph };
        let body_frame = on_so3.filter(|(_, _, origin)| {
            self.frame_omega.is_none()
                && alg
                    .time_derivative3(*origin, layout)
                    .iter()
                    .all(|d| alg.g.as_const(*d) == Some(0.0))
        });
        let v = match body_frame {
            Some((w, x, _)) => {
                let xd = alg.time_derivative3(x, layout);
                let wx = alg.cross(w, x);
                alg.add3(wx, xd)
            }
            None => {
                let mut v = alg.time_derivative3(r, layout);
                if let Some(w) = self.frame_omega {
                    let wr = alg.cross(w, r);
                    v = alg.add3(v, wr);
                }
                v
            }
        };
        let v2 = alg.dot(v, v);
        let half = alg.g.constant(0.5);
        let hm = alg.g.mul(half, mass);
        self.kinetic.push(alg.g.mul(hm, v2));
        if let Some(g) = self.gravity {
            let gr = alg.dot(g, r);
            let mgr = alg.g.mul(mass, gr);
            self.potential.push(alg.g.neg(mgr));
        }
    }

    /// ½ ω·(I ω) of a body turning at `w` (its frame's axes) with inertia `inertia` about its
    /// centre of mass.
    pub(super) fn rotational(&mut self, graph: &mut Graph, inertia: &M3, w: V3) {
        let mut alg = Algebra { g: graph };
        let iw = alg.mat_vec(inertia, w);
        let wiw = alg.dot(w, iw);
        let half = alg.g.constant(0.5);
        self.kinetic.push(alg.g.mul(half, wiw));
    }
}
