//! Built-in scenes: each documents its coordinates, parameters, conserved quantities and the
//! oracle its tests use.

pub mod body;
pub mod coriolis;
pub mod euler_poisson;
pub mod free_hoop;
pub mod hoop;
pub mod rigid;
pub mod top;

#[cfg(test)]
pub(crate) mod taylor_check;

use crate::error::SceneError;
use crate::scene::Scene;

/// Every built-in scene, in the order `tumble scenes` lists them.
#[must_use]
pub fn builtin() -> &'static [&'static dyn Scene] {
    &[
        &hoop::DrivenHoopScene,
        &hoop::SpinningHoopScene,
        &free_hoop::FreeHoopScene,
        &rigid::FreeBodyScene,
        &rigid::DzhanibekovScene,
        &rigid::HeavyTopScene,
        &coriolis::CoriolisDropScene,
    ]
}

/// The built-in scene called `name`.
///
/// # Errors
/// [`SceneError::UnknownScene`] listing the built-in names.
pub fn find(name: &str) -> Result<&'static dyn Scene, SceneError> {
    builtin()
        .iter()
        .copied()
        .find(|s| s.info().name == name)
        .ok_or_else(|| SceneError::UnknownScene {
            name: name.to_string(),
            known: builtin()
                .iter()
                .map(|s| s.info().name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// `Σⱼ₌₀ᵏ aⱼ bₖ₋ⱼ` (a multiply and an add: `f64::mul_add` is a library call on an x86-64
/// target without FMA, which the binary is built for).
#[inline]
pub(crate) fn cauchy(a: &[f64], b: &[f64], k: usize) -> f64 {
    a[..=k]
        .iter()
        .zip(b[..=k].iter().rev())
        .fold(0.0, |s, (x, y)| s + x * y)
}
