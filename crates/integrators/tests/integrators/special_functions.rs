//! Jacobi sn, cn, dn and K(m) against tabulated values (mpmath at 60 digits, printed by
//! `tools/gen_tables.py`), and against identities.

use tumble_integrators::special::{ellip_k, jacobi_sn_cn_dn};

/// (u, m, sn, cn, dn) from mpmath.ellipfun at 60 digits (u and m are the f64 inputs).
const TABLE: &[(f64, f64, f64, f64, f64)] = &[
    (
        0.5,
        0.3,
        4.74215622711820625588596198144e-1,
        8.80408736426462429990921096660e-1,
        9.65678964745951200071222468104e-1,
    ),
    (
        1.2,
        0.5,
        8.87715488619278140844274050689e-1,
        4.60392453527896416585270366934e-1,
        7.78447561260691554619039865277e-1,
    ),
    (
        2.0,
        0.9,
        9.81615869518493796010562861308e-1,
        1.90867191286117485129401248533e-1,
        3.64399857626901666723026564141e-1,
    ),
    (
        3.7,
        0.99,
        9.99999904836395401390884254609e-1,
        -4.36265057208466549553274560878e-4,
        1.00000942115202837609450670089e-1,
    ),
    (
        4.0,
        0.998001,
        9.99733795020281750205279312690e-1,
        2.30724748205577807204755434440e-2,
        5.03018384206347833001563729243e-2,
    ),
    (
        10.0,
        0.998001,
        -7.65441738423365938152668424167e-1,
        -6.43505202060881118407724010885e-1,
        6.44414588047323513984441703740e-1,
    ),
    (
        0.1,
        0.0,
        9.98334166468281578301968678586e-2,
        9.95004165278025765541375198862e-1,
        1.0,
    ),
    (
        1.0,
        1.0,
        7.61594155955764888119458282605e-1,
        6.48054273663885399574977353226e-1,
        6.48054273663885399574977353226e-1,
    ),
    (
        -2.5,
        0.7,
        -9.71940350581748753684385769909e-1,
        -2.35227453565750537215916136596e-1,
        5.82007189335079579598815011739e-1,
    ),
    (
        7.3,
        0.2,
        6.07327261964168484356679126104e-1,
        7.94451758683374222018936135974e-1,
        9.62408810940039788671842071556e-1,
    ),
];

#[test]
fn jacobi_functions_match_tabulated_values() {
    for &(u, m, sn, cn, dn) in TABLE {
        let (s, c, d) = jacobi_sn_cn_dn(u, m).expect("valid arguments");
        for (got, want, what) in [(s, sn, "sn"), (c, cn, "cn"), (d, dn, "dn")] {
            assert!(
                (got - want).abs() <= 1e-13 * want.abs().max(1.0) * u.abs().max(1.0),
                "{what}({u} | {m}) = {got}, tabulated {want}"
            );
        }
    }
}

#[test]
fn complete_elliptic_integral_matches_tabulated_values() {
    // mpmath.ellipk at the f64 value of m (K is ill-conditioned near m = 1).
    for (m, k) in [
        (0.0, std::f64::consts::FRAC_PI_2),
        (0.5, 1.85407467730137191843385034720),
        (0.9, 2.57809211334817329268263998157),
        (0.998001, 4.49559639584215089837486535171),
        (0.999999, 8.29405146360106220189952903397),
    ] {
        let got = ellip_k(m).expect("valid m");
        assert!(
            (got - k).abs() <= 4.0 * f64::EPSILON * k,
            "K({m}) = {got}, tabulated {k}"
        );
    }
}

#[test]
fn jacobi_identities_hold() {
    for &m in &[0.1, 0.5, 0.9, 0.998001] {
        let k = ellip_k(m).expect("valid m");
        let (s, _, _) = jacobi_sn_cn_dn(k, m).expect("valid");
        assert!((s - 1.0).abs() < 1e-14, "sn(K) = 1");
        let kp = (1.0 - m).sqrt();
        let (s2, _, d2) = jacobi_sn_cn_dn(0.5 * k, m).expect("valid");
        assert!((s2 - 1.0 / (1.0 + kp).sqrt()).abs() < 1e-14, "sn(K/2)");
        assert!((d2 - kp.sqrt()).abs() < 1e-13, "dn(K/2)");
        for u in [0.3, 1.7, 5.2] {
            let (s, c, d) = jacobi_sn_cn_dn(u, m).expect("valid");
            assert!((s * s + c * c - 1.0).abs() < 1e-14);
            assert!((d * d + m * s * s - 1.0).abs() < 1e-14);
        }
    }
    assert!(jacobi_sn_cn_dn(1.0, 1.5).is_err());
    assert!(jacobi_sn_cn_dn(f64::NAN, 0.5).is_err());
    assert!(ellip_k(1.0).is_err());
}
