//! Principal moments and axes, and the physical-realizability check.
//!
//! The eigendecomposition is faer's self-adjoint one (`Mat::self_adjoint_eigen`), which returns
//! eigenvalues in non-decreasing order and orthonormal eigenvectors even for repeated
//! eigenvalues. Its eigenvectors are then put in a canonical form (below), so that the same
//! tensor always gives the same frame and an already diagonal tensor gives a signed permutation
//! of the identity.

use faer::{Mat, Side};
use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::error::InertiaError;

/// Relative tolerance of the realizability checks: `64 ε ≈ 1.4e-14`, measured against the
/// largest principal moment (or, for symmetry, the largest entry).
///
/// It only absorbs round-off: the eigenvalues of a symmetric 3×3 matrix are computed to a few
/// `ε ‖I‖`, so a thin hoop's exact `I1 + I2 = I3` may come out a few ulps short, and the
/// exactly-zero axial moment of a thin rod a few ulps negative. A genuine violation (a tensor
/// no mass distribution has) is larger than this by orders of magnitude.
pub const REALIZABILITY_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// Principal moments and principal axes of an inertia tensor: `I = Q diag(I1, I2, I3) Qᵀ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalAxes {
    /// `(I1, I2, I3)`, ascending (kg·m²).
    pub moments: Vector3<f64>,
    /// `Q`: a proper rotation (right-handed frame) whose column `k` is the axis of moment `Iₖ₊₁`,
    /// expressed in the frame of the tensor. It maps principal-frame components to body-frame
    /// components: `I = Q diag(moments) Qᵀ`, `Qᵀ I Q = diag(moments)`.
    ///
    /// For repeated moments (a sphere, a symmetric cylinder) the axes within the degenerate
    /// eigenspace are not unique; `Q` is then one valid orthonormal right-handed choice.
    pub axes: Rotation3<f64>,
}

/// Whether every off-diagonal entry is exactly zero.
fn is_diagonal(m: &Matrix3<f64>) -> bool {
    (0..3).all(|i| (0..3).all(|j| i == j || m[(i, j)] == 0.0))
}

/// Whether a tensor must be positive definite or may be semi-definite (idealized bodies).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Definiteness {
    Positive,
    SemiDefinite,
}

/// Principal moments (ascending) and right-handed principal axes of a symmetric 3×3 tensor.
///
/// No physical check is made (see [`realizable_principal_axes`] for that); the tensor must be
/// finite and symmetric to round-off.
///
/// Canonical form: the first two axes are signed so that their component of largest magnitude
/// is positive (the first such component on ties), and the third is their cross product, which
/// makes the frame right-handed. An exactly diagonal tensor is already in its principal frame:
/// its axes are the frame's own, sorted by moment (stably, so equal moments keep the order
/// x, y, z), without calling the eigensolver.
///
/// # Errors
/// [`InertiaError::NonFiniteInertia`], [`InertiaError::NotSymmetric`] (beyond
/// [`REALIZABILITY_TOLERANCE`] × the largest entry), [`InertiaError::EigenNoConvergence`].
pub fn principal_axes(inertia: &Matrix3<f64>) -> Result<PrincipalAxes, InertiaError> {
    for row in 0..3 {
        for col in 0..3 {
            let value = inertia[(row, col)];
            if !value.is_finite() {
                return Err(InertiaError::NonFiniteInertia { row, col, value });
            }
        }
    }
    let scale = inertia.amax();
    for (row, col) in [(0, 1), (0, 2), (1, 2)] {
        let (upper, lower) = (inertia[(row, col)], inertia[(col, row)]);
        if (upper - lower).abs() > REALIZABILITY_TOLERANCE * scale {
            return Err(InertiaError::NotSymmetric {
                row,
                col,
                upper,
                lower,
            });
        }
    }
    let (moments, mut columns) = if is_diagonal(inertia) {
        // Already principal (every primitive, every symmetric body in its symmetry frame):
        // sort the frame's own axes, stably, so equal moments keep x, y, z order.
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| inertia[(i, i)].total_cmp(&inertia[(j, j)]));
        (
            Vector3::from_fn(|k, _| inertia[(order[k], order[k])]),
            order.map(|i| Vector3::from_fn(|r, _| if r == i { 1.0 } else { 0.0 })),
        )
    } else {
        let a = Mat::<f64>::from_fn(3, 3, |i, j| 0.5 * (inertia[(i, j)] + inertia[(j, i)]));
        let evd = a
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| InertiaError::EigenNoConvergence)?;
        let s = evd.S().column_vector();
        let u = evd.U();
        (
            Vector3::new(s[0], s[1], s[2]),
            [0, 1, 2].map(|k| Vector3::new(u[(0, k)], u[(1, k)], u[(2, k)])),
        )
    };
    for column in columns.iter_mut().take(2) {
        if column[column.iamax()] < 0.0 {
            *column = -*column;
        }
    }
    columns[2] = columns[0].cross(&columns[1]);
    let q = Matrix3::from_columns(&columns);
    Ok(PrincipalAxes {
        moments,
        axes: Rotation3::from_matrix_unchecked(q),
    })
}

/// Principal axes of a tensor that a rigid body can have: symmetric, all principal moments
/// positive, and `Iᵢ + Iⱼ ≥ Iₖ` for every permutation (each up to [`REALIZABILITY_TOLERANCE`]
/// × the largest moment). Returns them on success.
///
/// The triangle inequality holds for every mass distribution because
/// `Iᵢ + Iⱼ − Iₖ = 2 ∫ rₖ² dm ≥ 0` in the principal frame; equality means the mass lies in a
/// plane (a thin hoop, a thin disk).
///
/// # Errors
/// As [`principal_axes`], plus [`InertiaError::NotPositiveDefinite`] (a moment not above the
/// tolerance) and [`InertiaError::TriangleInequality`].
///
/// ```
/// use nalgebra::Matrix3;
/// use tumble_inertia::{realizable_principal_axes, InertiaError};
///
/// assert!(realizable_principal_axes(&Matrix3::from_diagonal_element(1.0)).is_ok());
/// // No body has moments 1, 1, 3: the mass would have to lie "beyond" a plane.
/// let bad = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, 3.0));
/// assert!(matches!(realizable_principal_axes(&bad), Err(InertiaError::TriangleInequality { .. })));
/// ```
pub fn realizable_principal_axes(inertia: &Matrix3<f64>) -> Result<PrincipalAxes, InertiaError> {
    realizable_principal_axes_with(inertia, Definiteness::Positive)
}

/// Whether moments (ascending) are all positive beyond round-off.
pub(crate) fn is_positive_definite(moments: &Vector3<f64>) -> bool {
    moments[0] > REALIZABILITY_TOLERANCE * moments.amax()
}

pub(crate) fn realizable_principal_axes_with(
    inertia: &Matrix3<f64>,
    definiteness: Definiteness,
) -> Result<PrincipalAxes, InertiaError> {
    let principal = principal_axes(inertia)?;
    let m = principal.moments;
    let tolerance = REALIZABILITY_TOLERANCE * m.amax();
    let definite = match definiteness {
        Definiteness::Positive => is_positive_definite(&m),
        Definiteness::SemiDefinite => m[0] >= -tolerance,
    };
    if !definite {
        return Err(InertiaError::NotPositiveDefinite { moments: m });
    }
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        if m[i] + m[j] < m[k] - tolerance {
            return Err(InertiaError::TriangleInequality { moments: m });
        }
    }
    Ok(principal)
}
