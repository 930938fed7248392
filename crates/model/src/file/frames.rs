//! A model file's frames: the rotations of a frame given by Euler angles or by a chain of
//! rotations, and the frames whose orientation is integrated on SO(3).

use tumble_kinematics::{EulerConvention, RotationKind};

use super::raw::RawFrame;
use super::reader::{Names, Src, axis};
use super::{ModelFileError, Orientation};
use crate::expr::{Graph, Id};
use crate::mechanics::{Algebra, Chain, Layout, M3, V3};

/// A frame's rotations about fixed axes in product order, from `angles` (three Euler angles of
/// the convention `euler`, ZYZ by default) or `rotations` (`[[axis, angle], ...]`); `None`
/// when the frame gives neither or both.
pub(super) fn read_links(
    src: &Src<'_>,
    key: &str,
    f: &RawFrame,
    graph: &mut Graph,
    scope: &Names,
) -> Result<Option<Vec<(usize, Id)>>, ModelFileError> {
    match (&f.angles, &f.rotations) {
        (Some(angles), None) => {
            let convention = match &f.euler {
                None => EulerConvention::ARTICLE,
                Some(e) => e.get_ref().parse::<EulerConvention>().map_err(|_| {
                    src.invalid(&e.span(), &format!("{key}.euler"), format!("unknown convention {:?}; write an axis sequence such as \"zyz\", \"zxz\", \"xyz\", optionally \"extrinsic-xyz\"", e.get_ref()))
                })?,
            };
            let a = src.vector(&format!("{key}.angles"), angles, graph, scope)?;
            let axes = convention.sequence.axes().map(|x| x.index());
            Ok(Some(match convention.kind {
                RotationKind::Intrinsic => vec![(axes[0], a[0]), (axes[1], a[1]), (axes[2], a[2])],
                RotationKind::Extrinsic => vec![(axes[2], a[2]), (axes[1], a[1]), (axes[0], a[0])],
            }))
        }
        (None, Some(rotations)) => {
            if let Some(e) = &f.euler {
                return Err(src.invalid(
                    &e.span(),
                    &format!("{key}.euler"),
                    "names the convention of `angles`; a frame given by `rotations` takes none",
                ));
            }
            let mut links = Vec::new();
            for (k, r) in rotations.get_ref().iter().enumerate() {
                let rk = format!("{key}.rotations[{}]", k + 1);
                let (ax, angle) = r.get_ref();
                let ax = axis(ax).ok_or_else(|| {
                    src.invalid(
                        &r.span(),
                        &rk,
                        format!("unknown axis {ax:?}; write \"x\", \"y\" or \"z\""),
                    )
                })?;
                links.push((ax, src.expr(&rk, angle, graph, scope)?));
            }
            Ok(Some(links))
        }
        _ => Ok(None),
    }
}

/// A frame integrated on SO(3): its initial orientation from `angles` (of `euler`) or
/// `rotations`, and its initial body angular velocity `omega`, both of the parameters; returns
/// its rotation and angular velocity, which are state inputs.
#[allow(clippy::too_many_arguments)]
pub(super) fn so3_frame(
    src: &Src<'_>,
    key: &str,
    f: &RawFrame,
    graph: &mut Graph,
    param_scope: &Names,
    orientations: &mut Vec<Orientation>,
    name: &str,
    layout: Layout,
) -> Result<(M3, V3), ModelFileError> {
    if let Some(p) = &f.parent {
        return Err(src.invalid(
            &p.span(),
            &format!("{key}.parent"),
            "an orientation on SO(3) turns in the model frame; leave `parent` out",
        ));
    }
    if let (Some(a), Some(_)) = (&f.angles, &f.rotations) {
        return Err(src.invalid(
            &a.span(),
            key,
            "gives its initial orientation by `angles` or by `rotations`, not both",
        ));
    }
    let links = read_links(src, key, f, graph, param_scope)?.unwrap_or_default();
    let omega = match &f.omega {
        Some(w) => src.vector(&format!("{key}.omega"), w, graph, param_scope)?,
        None => {
            let z = graph.constant(0.0);
            [z; 3]
        }
    };
    let mut alg = Algebra { g: graph };
    let initial_rotation = Chain { links }.rotation(&mut alg);
    let k = orientations.len();
    orientations.push(Orientation {
        name: name.to_string(),
        initial_rotation,
        initial_omega: omega,
    });
    Ok((layout.rotation(graph, k), layout.angular_velocity(graph, k)))
}

/// Where a frame is: its rotation (body → model frame), its angular velocity in its own axes
/// and its origin in the model frame; and, for a frame that turns with an orientation on SO(3)
/// (that orientation itself, or a frame carried by it through `parent`), the same relative to
/// that orientation.
#[derive(Debug, Clone, Copy)]
pub(super) struct Placed {
    /// `R`, body → model frame.
    pub(super) rotation: M3,
    /// `ω` in the frame's own axes.
    pub(super) omega: V3,
    /// The frame's origin in the model frame.
    pub(super) origin: V3,
    /// The rotation relative to the frame's root (the model frame, or the orientation on SO(3)
    /// that carries it): `R = R_root · rotation_in_root`.
    pub(super) rotation_in_root: M3,
    /// The origin in the root's axes, from the root's origin.
    pub(super) origin_in_root: V3,
    /// The orientation on SO(3) that carries the frame: its angular velocity and its origin.
    pub(super) root: Option<Root>,
}

/// An orientation on SO(3) as the root of the frames it carries.
#[derive(Debug, Clone, Copy)]
pub(super) struct Root {
    /// Its rotation (state inputs).
    pub(super) rotation: M3,
    /// Its body angular velocity (state inputs).
    pub(super) omega: V3,
    /// Its origin in the model frame.
    pub(super) origin: V3,
}

impl Placed {
    /// An orientation on SO(3) with its rotation `r`, angular velocity `w` and origin.
    pub(super) fn on_so3(alg: &mut Algebra<'_>, r: M3, w: V3, origin: V3) -> Self {
        Self {
            rotation: r,
            omega: w,
            origin,
            rotation_in_root: alg.identity(),
            origin_in_root: alg.zero3(),
            root: Some(Root {
                rotation: r,
                omega: w,
                origin,
            }),
        }
    }

    /// A frame turned from `parent` (or from the model frame) by the rotations `own` (product
    /// order), its origin at `offset` in the parent's axes from the parent's origin. `links`
    /// are the parent's rotations relative to its root, extended by `own`: the frame's chain
    /// from its root, whose rotation and angular velocity are those of the chain
    /// ([`Chain::rotation`], [`Chain::omega_body`]) composed with the root's:
    /// `R = R_root R_c`, `ω = R_cᵀ ω_root + ω_c`.
    pub(super) fn chained(
        alg: &mut Algebra<'_>,
        parent: Option<&Placed>,
        chain: &Chain,
        offset: V3,
        layout: Layout,
    ) -> Self {
        let rel = chain.rotation(alg);
        let w_rel = chain.omega_body(alg, layout);
        let origin_in_root = match parent {
            None => offset,
            Some(p) => {
                let turned = alg.mat_vec(&p.rotation_in_root, offset);
                alg.add3(p.origin_in_root, turned)
            }
        };
        let root = parent.and_then(|p| p.root);
        let (rotation, omega, origin) = match root {
            None => (rel, w_rel, origin_in_root),
            Some(root) => {
                let rotation = alg.mat_mul(&root.rotation, &rel);
                let carried = alg.mat_t_vec(&rel, root.omega);
                let omega = alg.add3(carried, w_rel);
                let turned = alg.mat_vec(&root.rotation, origin_in_root);
                (rotation, omega, alg.add3(root.origin, turned))
            }
        };
        Self {
            rotation,
            omega,
            origin,
            rotation_in_root: rel,
            origin_in_root,
            root,
        }
    }

    /// For a position `local` in this frame: on an orientation on SO(3), that orientation's
    /// angular velocity, the position in its axes (from its origin) and its origin
    /// (`r = origin + R_root x`), so that the velocity is written `ω_root × x + ẋ` without the
    /// rotation; `None` for a frame no such orientation carries.
    pub(super) fn in_root(&self, alg: &mut Algebra<'_>, local: V3) -> Option<(V3, V3, V3)> {
        let root = self.root?;
        let turned = alg.mat_vec(&self.rotation_in_root, local);
        let x = alg.add3(self.origin_in_root, turned);
        Some((root.omega, x, root.origin))
    }
}

/// The names of `frames`, sorted and joined (`none` when there are none), for a message.
pub(super) fn frame_names(frames: &std::collections::HashMap<String, Placed>) -> String {
    let mut known: Vec<&str> = frames.keys().map(String::as_str).collect();
    known.sort_unstable();
    if known.is_empty() {
        "none".to_string()
    } else {
        known.join(", ")
    }
}
