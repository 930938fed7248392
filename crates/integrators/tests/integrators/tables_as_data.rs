//! Tables are tested as data: row sums equal the nodes, order conditions (all rooted trees)
//! hold to ~10ε, Gauss–Legendre satisfies B(2s), C(s) and the symplectic condition,
//! composition coefficients sum to 1 and are symmetric.

use tumble_integrators::ExplicitRungeKutta;
use tumble_integrators::registry::{self, ExplicitVisitor, Stepping};
use tumble_integrators::tables::composition::ALL;
use tumble_integrators::tables::explicit::{DOP853, DP5};
use tumble_integrators::tables::gauss::{GAUSS2, GAUSS4, GAUSS6, GAUSS8, GAUSS10, GAUSS12};
use tumble_integrators::tables::rk_pairs::{TSIT5, VERN6, VERN7, VERN8, VERN9};
use tumble_integrators::tables::{DenseForm, ErrorEstimator, ExplicitTableau, GaussTableau};

const EPS: f64 = f64::EPSILON;

/// Rooted trees as lists of children, all trees up to `max_order`, with their orders.
fn trees(max_order: usize) -> Vec<(usize, Vec<usize>)> {
    // (order, children ids) with children ids non-decreasing; id = index in the list.
    let mut all: Vec<(usize, Vec<usize>)> = vec![(1, vec![])];
    for n in 2..=max_order {
        let existing = all.len();
        let mut new = Vec::new();
        // multisets of existing trees with total order n - 1
        fn rec(
            all: &[(usize, Vec<usize>)],
            limit: usize,
            start: usize,
            remaining: usize,
            current: &mut Vec<usize>,
            out: &mut Vec<Vec<usize>>,
        ) {
            if remaining == 0 {
                out.push(current.clone());
                return;
            }
            for id in start..limit {
                if all[id].0 <= remaining {
                    current.push(id);
                    rec(all, limit, id, remaining - all[id].0, current, out);
                    current.pop();
                }
            }
        }
        rec(&all, existing, 0, n - 1, &mut Vec::new(), &mut new);
        for children in new {
            all.push((n, children));
        }
    }
    all
}

/// Max over trees `t` with `|t| ≤ order` of `|Σᵢ wᵢ gᵢ(t) − target(|t|, γ(t))| / (10 ε · scale(t))`,
/// with `scale(t) = Σᵢ |wᵢ| |g|ᵢ(t)` (the same sums in absolute values, at least 1): the
/// elementary weight's defect in units of its own rounding error. `≤ 1` means the condition
/// holds in f64.
fn weights_defect<const S: usize>(
    a: &[[f64; S]; S],
    w: &[f64; S],
    order: usize,
    target: impl Fn(usize, f64) -> f64,
) -> f64 {
    let ts = trees(order);
    let mut g: Vec<[f64; S]> = Vec::new();
    let mut gabs: Vec<[f64; S]> = Vec::new();
    let mut gamma: Vec<f64> = Vec::new();
    let mut worst = 0.0_f64;
    for (n, children) in &ts {
        let mut v = [1.0; S];
        let mut va = [1.0; S];
        let mut gm = *n as f64;
        for &c in children {
            for i in 0..S {
                let (mut s, mut sa) = (0.0, 0.0);
                for j in 0..S {
                    s += a[i][j] * g[c][j];
                    sa += a[i][j].abs() * gabs[c][j];
                }
                v[i] *= s;
                va[i] *= sa;
            }
            gm *= gamma[c];
        }
        let phi: f64 = (0..S).map(|i| w[i] * v[i]).sum();
        let scale: f64 = (0..S).map(|i| w[i].abs() * va[i]).sum::<f64>().max(1.0);
        worst = worst.max((phi - target(*n, gm)).abs() / (10.0 * EPS * scale));
        g.push(v);
        gabs.push(va);
        gamma.push(gm);
    }
    worst
}

/// [`weights_defect`] of the order conditions `Σᵢ bᵢ gᵢ(t) = 1/γ(t)`.
fn order_condition_defect<const S: usize>(a: &[[f64; S]; S], b: &[f64; S], order: usize) -> f64 {
    weights_defect(a, b, order, |_, gamma| 1.0 / gamma)
}

/// Worst [`weights_defect`] of a polynomial interpolant `bᵢ(θ) = Σ_m d_{m,i} θ^(m+1)` of order
/// `q`: `Σᵢ bᵢ(θ) gᵢ(t) = θ^|t| / γ(t)` for `|t| ≤ q`, i.e. row `m` meets `1/γ(t)` on the
/// trees with `m + 1` nodes and `0` on the others.
fn interpolant_defect<const S: usize>(a: &[[f64; S]; S], dense: &[[f64; S]], q: usize) -> f64 {
    dense
        .iter()
        .enumerate()
        .map(|(m, row)| {
            weights_defect(
                a,
                row,
                q,
                |n, gamma| {
                    if n == m + 1 { 1.0 / gamma } else { 0.0 }
                },
            )
        })
        .fold(0.0, f64::max)
}

#[test]
fn tree_count_matches_the_known_sequence() {
    let ts = trees(8);
    let counts: Vec<usize> = (1..=8)
        .map(|n| ts.iter().filter(|t| t.0 == n).count())
        .collect();
    assert_eq!(counts, vec![1, 1, 2, 4, 9, 20, 48, 115]);
}

fn check_explicit<const S: usize>(t: &ExplicitTableau<S>) {
    for i in 0..S {
        let row: f64 = t.a[i].iter().sum();
        let scale: f64 = t.a[i].iter().map(|x| x.abs()).sum::<f64>().max(1.0);
        assert!(
            (row - t.c[i]).abs() <= 10.0 * EPS * scale,
            "{} row {i}: sum {row} vs c {}",
            t.name,
            t.c[i]
        );
        for j in i..S {
            assert_eq!(t.a[i][j], 0.0, "{} is not explicit at ({i},{j})", t.name);
        }
    }
    assert_eq!(t.a[t.fsal], t.b, "{}: FSAL row is b", t.name);
    assert_eq!(t.c[t.fsal], 1.0);
    let defect = order_condition_defect(&t.a, &t.b, t.order as usize);
    assert!(
        defect <= 1.0,
        "{}: order conditions off by {defect} × 10ε",
        t.name
    );
}

/// Checks the table of the explicit method it visits ([`check_explicit`]) and, for an embedded
/// pair, that `b − e` has the order below the controller's exponent `q` and not `q`.
struct CheckTable;

impl ExplicitVisitor for CheckTable {
    type Output = &'static str;
    fn visit<const S: usize>(self, method: ExplicitRungeKutta<S>) -> &'static str {
        let t = method.table;
        check_explicit(t);
        if let ErrorEstimator::Embedded { weights, order } = t.error {
            let bhat: [f64; S] = std::array::from_fn(|i| t.b[i] - weights[i]);
            let q = order as usize;
            assert!(
                order_condition_defect(&t.a, &bhat, q - 1) <= 1.0,
                "{}",
                t.name
            );
            assert!(order_condition_defect(&t.a, &bhat, q) > 1e3, "{}", t.name);
        }
        t.name
    }
}

/// Every explicit table in the registry, found through its rows (a table added with its row
/// is checked with no line here).
#[test]
fn explicit_tables_have_row_sums_and_order_conditions() {
    let checked: Vec<&str> = registry::methods()
        .iter()
        .filter_map(|m| match m.stepping {
            Stepping::Explicit(e) => Some(e.visit(CheckTable)),
            _ => None,
        })
        .collect();
    for name in ["rk4", "dp5", "dop853", "tsit5", "vern9"] {
        assert!(checked.contains(&name), "{name} not checked");
    }
}

/// Tsitouras' and Verner's tables, recomputed in f64 independently of the generator: row
/// sums, explicitness, FSAL row, all order conditions of `b` (order p), of the embedded
/// `b − e` (order p − 1, and not p), and of the interpolant (order q, with `bᵢ(1) = bᵢ`).
fn check_pair<const S: usize>(t: &ExplicitTableau<S>, dense_order: usize) {
    check_explicit(t);
    let p = t.order as usize;
    let ErrorEstimator::Embedded { weights, order } = t.error else {
        panic!("{} has an embedded pair", t.name)
    };
    assert_eq!(order as usize, p, "{}: controller exponent 1/p", t.name);
    let bhat: [f64; S] = std::array::from_fn(|i| t.b[i] - weights[i]);
    let emb = order_condition_defect(&t.a, &bhat, p - 1);
    let not_p = order_condition_defect(&t.a, &bhat, p);
    assert!(
        emb <= 1.0,
        "{}: embedded conditions off by {emb} × 10ε",
        t.name
    );
    assert!(not_p > 1e3, "{}: the embedded formula has order p", t.name);
    assert_eq!(t.dense_form, DenseForm::Polynomial);
    assert_eq!(t.dense.len(), dense_order, "{}: degree = order", t.name);
    assert_eq!(t.dense_order as usize, dense_order);
    let defect = interpolant_defect(&t.a, t.dense, dense_order);
    eprintln!(
        "{}: interpolant conditions to order {dense_order} within {defect:.2} × 10ε",
        t.name
    );
    assert!(
        defect <= 1.0,
        "{}: interpolant off by {defect} × 10ε",
        t.name
    );
    for i in 0..S {
        let at_one: f64 = t.dense.iter().map(|row| row[i]).sum();
        let scale = t.dense.iter().map(|row| row[i].abs()).sum::<f64>().max(1.0);
        assert!(
            (at_one - t.b[i]).abs() <= 10.0 * EPS * scale,
            "{}: b_{i}(1) = {at_one} vs b = {}",
            t.name,
            t.b[i]
        );
    }
}

#[test]
fn tsitouras_and_verner_tables_satisfy_their_order_conditions_in_f64() {
    check_pair(&TSIT5, 4);
    check_pair(&VERN6, 6);
    check_pair(&VERN7, 7);
    check_pair(&VERN8, 8);
    check_pair(&VERN9, 9);
}

#[test]
fn embedded_weights_have_their_orders() {
    // DP5: b̂ = b − e is of order 4 (and not 5).
    let ErrorEstimator::Embedded { weights, .. } = DP5.error else {
        panic!("DP5 has an embedded pair")
    };
    let bhat: [f64; 7] = std::array::from_fn(|i| DP5.b[i] - weights[i]);
    assert!(order_condition_defect(&DP5.a, &bhat, 4) <= 1.0);
    assert!(order_condition_defect(&DP5.a, &bhat, 5) > 1e3);
    // DOP853: b − e₅ has order 5, b − e₃ order 3.
    let ErrorEstimator::Dop853 { e5, e3, .. } = DOP853.error else {
        panic!("DOP853 has its estimator")
    };
    let b5: [f64; 16] = std::array::from_fn(|i| DOP853.b[i] - e5[i]);
    let b3: [f64; 16] = std::array::from_fn(|i| DOP853.b[i] - e3[i]);
    assert!(order_condition_defect(&DOP853.a, &b5, 5) <= 1.0);
    assert!(order_condition_defect(&DOP853.a, &b3, 3) <= 1.0);
}

fn check_gauss<const S: usize>(t: &GaussTableau<S>) {
    let tol = 10.0 * EPS;
    for i in 0..S {
        let row: f64 = t.a[i].iter().sum();
        assert!((row - t.c[i]).abs() <= tol, "{} row {i}", t.name);
    }
    // B(2s): Σ bᵢ cᵢ^{k−1} = 1/k
    for k in 1..=2 * S {
        let s: f64 = (0..S).map(|i| t.b[i] * t.c[i].powi(k as i32 - 1)).sum();
        assert!((s - 1.0 / k as f64).abs() <= tol, "{} B({k})", t.name);
    }
    // C(s): Σⱼ a_ij cⱼ^{k−1} = cᵢ^k / k
    for k in 1..=S {
        for i in 0..S {
            let s: f64 = (0..S).map(|j| t.a[i][j] * t.c[j].powi(k as i32 - 1)).sum();
            assert!(
                (s - t.c[i].powi(k as i32) / k as f64).abs() <= tol,
                "{} C({k}) row {i}",
                t.name
            );
        }
    }
    // symplectic: bᵢ a_ij + bⱼ a_ji − bᵢ bⱼ = 0
    for i in 0..S {
        for j in 0..S {
            let m = t.b[i] * t.a[i][j] + t.b[j] * t.a[j][i] - t.b[i] * t.b[j];
            assert!(m.abs() <= tol, "{} symplectic ({i},{j}): {m:e}", t.name);
        }
    }
    // symmetric nodes
    for i in 0..S {
        assert!((t.c[i] + t.c[S - 1 - i] - 1.0).abs() <= tol);
    }
    assert_eq!(t.order as usize, 2 * S);
    assert!(
        order_condition_defect(&t.a, &t.b, (2 * S).min(8)) <= 1.0,
        "{}",
        t.name
    );
}

#[test]
fn gauss_tables_are_collocation_symplectic_and_of_order_2s() {
    check_gauss(&GAUSS2);
    check_gauss(&GAUSS4);
    check_gauss(&GAUSS6);
    check_gauss(&GAUSS8);
    check_gauss(&GAUSS10);
    check_gauss(&GAUSS12);
}

#[test]
fn composition_coefficients_sum_to_one_and_are_symmetric() {
    for t in ALL {
        let m = t.gammas.len();
        let sum: f64 = t.gammas.iter().sum();
        let scale: f64 = t.gammas.iter().map(|g| g.abs()).sum();
        assert!(
            (sum - 1.0).abs() <= 10.0 * EPS * scale,
            "{}: Σγ = {sum}",
            t.name
        );
        for i in 0..m {
            assert_eq!(
                t.gammas[i],
                t.gammas[m - 1 - i],
                "{} is not symmetric",
                t.name
            );
        }
        assert_eq!(m % 2, 1, "{}: odd number of stages", t.name);
        // order 4 needs Σγ³ = 0
        let cubes: f64 = t.gammas.iter().map(|g| g * g * g).sum();
        let cscale: f64 = t.gammas.iter().map(|g| (g * g * g).abs()).sum();
        assert!(
            cubes.abs() <= 10.0 * EPS * cscale,
            "{}: Σγ³ = {cubes:e}",
            t.name
        );
        if t.order >= 6 {
            let fifth: f64 = t.gammas.iter().map(|g| g.powi(5)).sum();
            let fscale: f64 = t.gammas.iter().map(|g| g.powi(5).abs()).sum();
            assert!(
                fifth.abs() <= 10.0 * EPS * fscale,
                "{}: Σγ⁵ = {fifth:e}",
                t.name
            );
        }
    }
}
