//! The registry lists every method once, by a lowercase name, with order and properties.

use tumble_integrators::registry::{Family, find, methods};
use tumble_integrators::tables::composition::ALL;

#[test]
fn registry_has_every_required_name_once() {
    let required = [
        "rk4",
        "dp5",
        "dop853",
        "tsit5",
        "vern6",
        "vern7",
        "vern8",
        "vern9",
        "symplectic-euler",
        "verlet",
        "yoshida4",
        "yoshida6",
        "yoshida8",
        "suzuki4",
        "mclachlan4",
        "kahan-li6",
        "kahan-li8",
        "sofroniou-spaletta10",
        "gauss2",
        "gauss4",
        "gauss6",
        "gauss8",
        "gauss10",
        "gauss12",
    ];
    for name in required {
        assert!(find(name).is_ok(), "{name} missing");
    }
    let all = methods();
    for (i, m) in all.iter().enumerate() {
        assert_eq!(m.name, m.name.to_lowercase());
        assert!(
            all[i + 1..].iter().all(|o| o.name != m.name),
            "{} twice",
            m.name
        );
        assert!(m.order >= 1);
    }
    for t in ALL {
        let m = find(t.name).unwrap();
        assert_eq!(m.order, t.order);
        assert_eq!(m.family, Family::Composition);
        assert!(m.properties.symmetric && m.properties.symplectic && m.properties.explicit);
    }
    let g = find("gauss12").unwrap();
    assert_eq!(g.order, 12);
    assert_eq!(g.stages, 6);
    assert!(!g.properties.explicit && g.properties.symplectic);
    assert!(find("dop853").unwrap().properties.adaptive);
    for (name, order) in [
        ("tsit5", 5),
        ("vern6", 6),
        ("vern7", 7),
        ("vern8", 8),
        ("vern9", 9),
    ] {
        let m = find(name).unwrap();
        assert_eq!(m.order, order, "{name}");
        assert_eq!(m.family, Family::ExplicitRungeKutta);
        assert!(m.properties.adaptive && m.properties.dense_output && m.properties.explicit);
    }
    assert!(find("nope").is_err());
}
