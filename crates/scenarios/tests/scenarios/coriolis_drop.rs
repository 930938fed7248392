//! `coriolis-drop`: the 2.2 cm eastward deflection, and the hand-written rotating-frame RHS
//! against the AD Lagrangian `½|ṙ + ω×r|² − g z`.

use nalgebra::SVector;
use proptest::prelude::*;
use tumble_integrators::Ode;
use tumble_kinematics::frames::{EARTH_ANGULAR_SPEED, drop_deflection_east};
use tumble_scenarios::scene::Rows;
use tumble_scenarios::scenes::coriolis::CoriolisDrop;
use tumble_scenarios::scenes::find;
use tumble_scenarios::{EulerLagrange, LagrangianOde, RunOptions};

#[test]
fn coriolis_drop_lands_2_2_cm_east() {
    let scene = find("coriolis-drop").unwrap();
    let params = scene.info().default_params();
    let mut rows = Rows::default();
    scene
        .run(&params, &RunOptions::default(), &mut rows)
        .unwrap();
    let last = rows.0.last().unwrap();
    let closed = drop_deflection_east(
        EARTH_ANGULAR_SPEED,
        std::f64::consts::FRAC_PI_2,
        100.0,
        9.81,
    );
    assert!(last[3].abs() < 1e-9, "landed at z = {}", last[3]);
    assert!(
        ((last[1] - closed) / closed).abs() < 1e-3,
        "x = {} vs {closed}",
        last[1]
    );
    assert!((last[1] - 0.022).abs() < 0.0005);
    // Landing time ≈ √(2h/g).
    assert!((last[0] - (200.0f64 / 9.81).sqrt()).abs() < 1e-6);
}

proptest! {
    #[test]
    fn rotating_frame_rhs_matches_the_ad_lagrangian(
        x in -100.0f64..100.0, y in -100.0f64..100.0, z in 0.0f64..100.0,
        vx in -50.0f64..50.0, vy in -50.0f64..50.0, vz in -50.0f64..50.0,
        colat in 0.0f64..std::f64::consts::PI, spin in 1e-5f64..1.0,
    ) {
        let model = CoriolisDrop::new(spin, colat, 9.81);
        let ad = LagrangianOde::<_, 3, 6>::new(EulerLagrange::new(model)).unwrap();
        let s = SVector::<f64, 6>::from([x, y, z, vx, vy, vz]);
        let (mut d1, mut d2) = (SVector::<f64, 6>::zeros(), SVector::<f64, 6>::zeros());
        model.rhs(0.0, &s, &mut d1);
        ad.rhs(0.0, &s, &mut d2);
        prop_assert!((d1 - d2).amax() <= 1e-12 * (1.0 + d1.amax()), "{d1} vs {d2}");
    }
}
