//! Rotating frames: transport theorem and fictitious forces against a brute-force change of
//! frame, and the Coriolis drop (2.2 cm east from 100 m at the equator).

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;
use num_dual::{Dual2_64, Dual64};
use tumble_kinematics::frames::{
    EARTH_ANGULAR_SPEED, RotatingFrame, drop_deflection_east, earth_rotation_enu, inertial_rate,
    rotating_rate,
};
use tumble_kinematics::{EulerConvention, EulerSequence};

/// Euler angles of a frame that tumbles non-uniformly: a(t) = a0 + a1 t + a2 t².
fn frame_angles<T: nalgebra::RealField + Copy>(t: T) -> Vector3<T> {
    let c = |a0: f64, a1: f64, a2: f64| {
        t * t * nalgebra::convert::<f64, T>(a2)
            + t * nalgebra::convert::<f64, T>(a1)
            + nalgebra::convert::<f64, T>(a0)
    };
    Vector3::new(c(0.3, 0.8, -0.2), c(1.0, -0.5, 0.3), c(-0.7, 2.0, 0.1))
}
fn frame_rates(t: f64) -> Vector3<f64> {
    Vector3::new(0.8 - 0.4 * t, -0.5 + 0.6 * t, 2.0 + 0.2 * t)
}
fn frame_accels() -> Vector3<f64> {
    Vector3::new(-0.4, 0.6, 0.2)
}

#[test]
fn fictitious_forces_match_a_brute_force_change_of_frame() {
    // A particle with constant inertial acceleration f (force per unit mass), seen from a frame
    // that rotates with R(t) (Euler angles above, any of several conventions). In the frame,
    // r(t) = R(t)ᵀ x(t); its second derivative must equal Rᵀ f − 2ω×ṙ − ω×(ω×r) − ω̇×r with ω, ω̇
    // in the frame's components.
    let x0 = Vector3::new(1.0, -2.0, 0.5);
    let v0 = Vector3::new(0.3, 0.1, -0.4);
    let f = Vector3::new(0.0, 0.5, -9.81);
    for conv in [
        EulerConvention::ARTICLE,
        EulerConvention::GOLDSTEIN,
        EulerConvention::extrinsic(EulerSequence::XYZ),
    ] {
        for &t in &[0.0, 0.37, 1.5, 4.0] {
            // r, ṙ, r̈ by second-order dual numbers in t.
            let td = Dual2_64::from_re(t).derivative();
            let r_t = conv.to_rotation(&frame_angles(td));
            let x_t = x0.map(Dual2_64::from_re)
                + v0.map(Dual2_64::from_re) * td
                + f.map(Dual2_64::from_re) * (td * td * 0.5);
            let r_frame = r_t.transpose() * x_t;
            let r = r_frame.map(|z| z.re);
            let rd = r_frame.map(|z| z.v1);
            let rdd = r_frame.map(|z| z.v2);
            // ω (frame components) and ω̇ by first-order duals.
            let a = frame_angles(t);
            let ad = frame_rates(t);
            let add = frame_accels();
            let ang = a.zip_map(&ad, Dual64::new);
            let rat = ad.zip_map(&add, Dual64::new);
            let w_dual = conv.omega_body(&ang, &rat);
            let frame = RotatingFrame {
                omega: w_dual.map(|z| z.re),
                omega_dot: w_dual.map(|z| z.eps),
            };
            let rot = conv.to_rotation(&a);
            let expected = frame.relative_acceleration(&(rot.transpose() * f), &r, &rd);
            assert!(
                (rdd - expected).norm() < 1e-12,
                "{conv} t={t}: {rdd} vs {expected}"
            );
            // Transport theorem: the inertial velocity R (ṙ + ω × r) = ẋ.
            let v_inertial = rot * frame.inertial_velocity(&r, &rd);
            assert!((v_inertial - (v0 + f * t)).norm() < 1e-13);
            let back = rotating_rate(&frame.omega, &r, &inertial_rate(&frame.omega, &r, &rd));
            assert!((back - rd).norm() < 1e-15);
        }
    }
}

/// The drop of a body released at rest at height `h` in a frame rotating with the Earth, by
/// classical RK4 with step `dt`; landing by cubic Hermite interpolation. Returns (east, north).
fn simulate_drop(colatitude: f64, h: f64, g: f64, dt: f64) -> (f64, f64) {
    let frame = RotatingFrame::uniform(earth_rotation_enu(EARTH_ANGULAR_SPEED, colatitude));
    // Gravity measured locally (it already contains the centrifugal term of the frame's
    // origin); the fictitious forces act on the displacement from the release point's foot.
    let gravity = Vector3::new(0.0, 0.0, -g);
    let rhs =
        |r: &Vector3<f64>, v: &Vector3<f64>| (*v, frame.relative_acceleration(&gravity, r, v));
    let (mut r, mut v) = (Vector3::new(0.0, 0.0, h), Vector3::zeros());
    loop {
        let (k1r, k1v) = rhs(&r, &v);
        let (k2r, k2v) = rhs(&(r + k1r * (dt / 2.0)), &(v + k1v * (dt / 2.0)));
        let (k3r, k3v) = rhs(&(r + k2r * (dt / 2.0)), &(v + k2v * (dt / 2.0)));
        let (k4r, k4v) = rhs(&(r + k3r * dt), &(v + k3v * dt));
        let r1 = r + (k1r + k2r * 2.0 + k3r * 2.0 + k4r) * (dt / 6.0);
        let v1 = v + (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (dt / 6.0);
        if r1.z <= 0.0 {
            // Hermite cubic on [0, dt] through (r, v) and (r1, v1); find z = 0 by bisection.
            let herm = |s: f64| {
                let (h00, h10, h01, h11) = (
                    2.0 * s.powi(3) - 3.0 * s * s + 1.0,
                    s.powi(3) - 2.0 * s * s + s,
                    -2.0 * s.powi(3) + 3.0 * s * s,
                    s.powi(3) - s * s,
                );
                r * h00 + v * (h10 * dt) + r1 * h01 + v1 * (h11 * dt)
            };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if herm(mid).z > 0.0 {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            let p = herm(0.5 * (lo + hi));
            return (p.x, p.y);
        }
        r = r1;
        v = v1;
    }
}

#[test]
fn coriolis_drop_lands_2_2_cm_east_at_the_equator() {
    let (h, g) = (100.0, 9.81);
    let closed = drop_deflection_east(EARTH_ANGULAR_SPEED, FRAC_PI_2, h, g);
    assert!((closed - 0.022).abs() < 0.0005, "closed form {closed}");
    let (east, north) = simulate_drop(FRAC_PI_2, h, g, 1e-3);
    let rel = (east - closed).abs() / closed;
    assert!(
        rel < 1e-3,
        "simulated {east} m vs closed form {closed} m (rel {rel:e})"
    );
    // No north-south deflection at the equator (to first order in Ω it vanishes exactly).
    assert!(north.abs() < 1e-9);
}

#[test]
fn coriolis_drop_scales_with_the_sine_of_the_colatitude() {
    let (h, g) = (100.0, 9.81);
    for colatitude in [0.3, 0.8, 1.2] {
        let closed = drop_deflection_east(EARTH_ANGULAR_SPEED, colatitude, h, g);
        let (east, _) = simulate_drop(colatitude, h, g, 1e-3);
        assert!(
            (east - closed).abs() / closed < 1e-3,
            "θ = {colatitude}: {east} vs {closed}"
        );
    }
}
