//! exploratory
use crate::rigid_support::*;

#[test]
fn explore_orders() {
    let body = if std::env::var("DIAG").is_ok() { diagonal_body() } else { asymmetric_body() };
    let s0 = initial_state();
    let t_end = 5.0;
    let ex = exact_state(&body, &s0, t_end);
    let scale = s0.momentum.norm();
    for name in ["lgvi","rkmk4","cg3","split2","split4","split6","split8","split-exact2","dmv","exact"] {
        let mut line = format!("{name:>12}:");
        for k in 0..9 {
            let n = 10usize << k;
            let h = t_end / n as f64;
            let s = solve_free(name, &body, &s0, t_end, h).unwrap();
            line += &format!(" {:.2e}", state_error(&s, &ex, scale));
        }
        eprintln!("{line}");
    }
}
