//! Which methods run a scene, and why one does not: the `TABLE:BASE` compositions of the
//! scene's symmetric order-2 bases ([`registry::BASES`]) and the error for a method that cannot
//! run it, saying what the method needs, what the scene offers and which names run it.

use tumble_integrators::ProblemKind;
use tumble_integrators::registry::{self, Family};
use tumble_integrators::tables::composition;

use crate::error::SceneError;
use crate::scene::SceneInfo;

impl SceneInfo {
    /// The symmetric order-2 bases whose `TABLE:BASE` compositions run this scene
    /// ([`registry::BASES`]).
    #[must_use]
    pub fn composition_bases(&self) -> Vec<&'static str> {
        registry::BASES
            .iter()
            .filter(|b| self.problems.iter().any(|k| b.problems.contains(k)))
            .filter(|b| !self.needs_dense_output || b.properties.dense_output)
            .map(|b| b.name)
            .collect()
    }

    /// [`Self::integrators`] and, in words, the `TABLE:BASE` compositions that run this scene.
    #[must_use]
    pub fn applicable(&self) -> String {
        let mut out = self.integrators().join(", ");
        let bases = self.composition_bases();
        if !bases.is_empty() {
            out += &format!(
                "; and TABLE:BASE with BASE one of {} and TABLE one of {}",
                bases.join(", "),
                composition::ALL.map(|t| t.name).join(", ")
            );
        }
        out
    }

    /// Whether the method called `name` runs this scene.
    #[must_use]
    pub fn runs(&self, name: &str) -> bool {
        registry::find(name).is_ok_and(|m| self.kind_for(m).is_some())
    }

    /// The error for a method called `name` that does not run this scene: why not (an unknown
    /// name; what the method needs and what the scene offers; for a composition table named
    /// alone, the `TABLE:BASE` names that compose this scene's symmetric base) and the methods
    /// that do run it.
    #[must_use]
    pub fn unsupported(&self, name: &str) -> SceneError {
        let kinds = |ks: &[ProblemKind]| ks.iter().map(|k| k.name()).collect::<Vec<_>>().join(", ");
        let reason = match registry::find(name) {
            Err(_) => match name.split_once(':') {
                Some(_) => format!(
                    "no such composition: TABLE:BASE takes a table of {} and a base of {}",
                    composition::ALL.map(|t| t.name).join(", "),
                    registry::BASES.map(|b| b.name).join(", ")
                ),
                None => "no integrator has this name (`tumble integrators` lists them)".into(),
            },
            Ok(m) if self.needs_dense_output && !m.properties.dense_output => {
                "its runs locate events, and the method has no dense output".into()
            }
            Ok(m) => {
                let mut why = format!(
                    "it needs a {} (problem kinds: {}), and the scene offers {}",
                    m.problem,
                    kinds(m.problems),
                    kinds(self.problems)
                );
                let bases: Vec<String> = self
                    .composition_bases()
                    .iter()
                    .map(|b| format!("{name}:{b}"))
                    .collect();
                let on_group = [
                    ProblemKind::RigidBody,
                    ProblemKind::FreeRigidBody,
                    ProblemKind::LieVectorField,
                    ProblemKind::ProductVectorField,
                    ProblemKind::ProductLagrangian,
                    ProblemKind::CoupledRigidBody,
                ];
                if !self.not_on_group.is_empty() && m.problems.iter().all(|k| on_group.contains(k))
                {
                    why += &format!("; {}", self.not_on_group);
                }
                if m.family == Family::Composition
                    && registry::composed(name).is_none()
                    && !bases.is_empty()
                {
                    why += &format!(
                        "; the same table composes this scene's symmetric order-2 bases as {}",
                        bases.join(", ")
                    );
                }
                why
            }
        };
        SceneError::UnsupportedIntegrator {
            scene: self.name.to_string(),
            name: name.to_string(),
            reason,
            applicable: self.applicable(),
        }
    }
}
