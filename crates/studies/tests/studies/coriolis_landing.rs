//! The Coriolis drop's landing offset as a sweep metric, `final:x`: a run that ends at the
//! scene's terminal event (the landing) is a complete point, and its final row is the landing.
//! Against the first-order closed form `x = Ω sin(colatitude) (2h)^{3/2} / (3 √g)` the offset
//! agrees to the size of the neglected second-order terms, `(Ω t)² ≈ 1e-7` relative.

use tumble_studies::sweep::{Status, SweepDefinition, run_point};

#[test]
fn a_sweep_reports_the_landing_offset_of_the_coriolis_drop() {
    let text = r#"
scene = "coriolis-drop"
[[axes]]
parameter = "h"
values = [20.0, 50.0, 100.0, 200.0]
[metrics]
record = ["final:x", "min:z"]
"#;
    let def = SweepDefinition::parse(text, "landing", &[]).unwrap();
    let omega: f64 = def.params.get("omega_earth").unwrap();
    let colatitude: f64 = def.params.get("colatitude").unwrap();
    let g: f64 = def.params.get("g").unwrap();
    for i in 0..def.points() {
        let row = run_point(&def, i);
        assert_eq!(row.status, Status::Ok, "{}", row.reason);
        let h = row.values[0];
        let first_order = omega * colatitude.sin() * (2.0 * h).powf(1.5) / (3.0 * g.sqrt());
        let x = row.metrics[0].unwrap();
        let relative = (x - first_order).abs() / first_order;
        eprintln!("h = {h}: x = {x:.12e}, first order {first_order:.12e}, relative {relative:.1e}");
        assert!(relative < 2e-7, "h = {h}: {relative:e}");
        // The run ends on the ground: the lowest height is 0 to round-off.
        assert!(row.metrics[1].unwrap().abs() < 1e-12 * h);
    }
}
