//! The AD Lagrangian machinery reproduces textbook equations of motion, and the hand-written
//! right-hand sides match their AD twins to 1e-12 at random states.

use nalgebra::{SVector, Vector1, Vector2};
use proptest::prelude::*;
use tumble_integrators::Ode;
use tumble_scenarios::scenes::hoop::{DrivenHoop, HoopParams, SpinningHoop};
use tumble_scenarios::{EulerLagrange, LagrangianOde, ModelError};

fn params() -> HoopParams {
    HoopParams::new(1.0, 0.2, 0.4, 9.81).unwrap()
}

proptest! {
    #![proptest_config(crate::support::proptest_config(500))]

    #[test]
    fn ad_driven_hoop_reproduces_the_textbook_equation(
        alpha in -3.2f64..3.2, alpha_dot in -10.0f64..10.0, omega in -8.0f64..8.0, t in 0.0f64..10.0
    ) {
        let scene = DrivenHoop::new(params(), omega).unwrap();
        let el = EulerLagrange::new(scene);
        let qdd = el.accelerations(t, &Vector1::new(alpha), &Vector1::new(alpha_dot)).unwrap();
        let (g, a) = (9.81, 0.4);
        let textbook = (omega * omega * alpha.cos() - g / a) * alpha.sin();
        prop_assert!((qdd[0] - textbook).abs() <= 1e-12 * (1.0 + textbook.abs()), "{} vs {}", qdd[0], textbook);
        // Mass matrix m a², momentum m a² α̇.
        let mass = el.mass_matrix(t, &Vector1::new(alpha), &Vector1::new(alpha_dot))[(0, 0)];
        prop_assert!((mass - 0.2 * 0.16).abs() < 1e-15);
    }

    #[test]
    fn hand_written_driven_hoop_matches_its_ad_twin(
        alpha in -3.2f64..3.2, alpha_dot in -10.0f64..10.0, omega in -8.0f64..8.0
    ) {
        let scene = DrivenHoop::new(params(), omega).unwrap();
        let ad = LagrangianOde::<_, 1, 2>::new(EulerLagrange::new(scene)).unwrap();
        let y = Vector2::new(alpha, alpha_dot);
        let (mut d1, mut d2) = (Vector2::zeros(), Vector2::zeros());
        scene.rhs(0.0, &y, &mut d1);
        ad.rhs(0.0, &y, &mut d2);
        prop_assert!((d1 - d2).amax() <= 1e-12 * (1.0 + d1.amax()));
    }

    #[test]
    fn hand_written_spinning_hoop_matches_its_ad_twin(
        phi in -3.2f64..3.2, alpha in -3.2f64..3.2, phi_dot in -10.0f64..10.0, alpha_dot in -10.0f64..10.0
    ) {
        let scene = SpinningHoop { hoop: params() };
        let ad = LagrangianOde::<_, 2, 4>::new(EulerLagrange::new(scene)).unwrap();
        let y = SVector::<f64, 4>::new(phi, alpha, phi_dot, alpha_dot);
        let (mut d1, mut d2) = (SVector::<f64, 4>::zeros(), SVector::<f64, 4>::zeros());
        scene.rhs(0.0, &y, &mut d1);
        ad.rhs(0.0, &y, &mut d2);
        prop_assert!((d1 - d2).amax() <= 1e-12 * (1.0 + d1.amax()), "{d1} vs {d2}");
        // Energy from the AD machinery equals the closed form.
        let q = nalgebra::Vector2::new(phi, alpha);
        let qd = nalgebra::Vector2::new(phi_dot, alpha_dot);
        let e_ad = EulerLagrange::new(scene).energy(0.0, &q, &qd);
        let e = scene.energy(alpha, phi_dot, alpha_dot);
        prop_assert!((e_ad - e).abs() <= 1e-13 * (1.0 + e.abs()));
    }
}

#[test]
fn first_order_form_rejects_a_wrong_state_size() {
    let scene = SpinningHoop { hoop: params() };
    match LagrangianOde::<_, 2, 5>::new(EulerLagrange::new(scene)) {
        Err(ModelError::Dimension {
            expected: 4,
            found: 5,
        }) => {}
        other => panic!("expected a dimension error, got {other:?}"),
    }
}

#[test]
fn bad_hoop_parameters_name_the_parameter() {
    for (args, name) in [
        ((-1.0, 0.2, 0.4, 9.81), "M"),
        ((1.0, -0.2, 0.4, 9.81), "m"),
        ((1.0, 0.2, 0.0, 9.81), "a"),
        ((1.0, 0.2, 0.4, f64::NAN), "g"),
    ] {
        let err = HoopParams::new(args.0, args.1, args.2, args.3).unwrap_err();
        assert!(err.to_string().contains(&format!("`{name}`")), "{err}");
    }
    assert!(DrivenHoop::new(params(), f64::INFINITY).is_err());
}
