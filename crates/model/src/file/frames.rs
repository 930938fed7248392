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
