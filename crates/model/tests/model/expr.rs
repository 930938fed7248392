//! The expression language and graph: values, exact derivatives, sharing, errors.

use tumble_model::expr::parse::{Scope, parse};
use tumble_model::expr::tape::Tape;
use tumble_model::expr::{Graph, Id};
use tumble_model::mechanics::{Algebra, Chain, Layout};

/// Names `x`, `y`, `z` as inputs 0, 1, 2.
struct Xyz;

impl Scope for Xyz {
    fn resolve(&self, name: &str, graph: &mut Graph) -> Option<Id> {
        ["x", "y", "z"]
            .iter()
            .position(|n| *n == name)
            .map(|k| graph.input(k as u32))
    }
    fn names(&self) -> Vec<String> {
        vec!["x".into(), "y".into(), "z".into()]
    }
}

fn value(text: &str, at: [f64; 3]) -> f64 {
    let mut g = Graph::default();
    let id = parse(text, &mut g, &Xyz).unwrap();
    g.eval(id, &at)
}

#[test]
fn precedence_and_functions_follow_the_grammar() {
    let at = [0.3, -1.2, 2.0];
    let (x, y, z) = (0.3f64, -1.2f64, 2.0f64);
    assert_eq!(value("-x^2", at), -(x * x));
    assert_eq!(value("2^-1", at), 0.5);
    assert_eq!(value("z^3^2", at), z.powi(9));
    assert_eq!(value("x - y - z", at), x - y - z);
    assert_eq!(value("x / y / z", at), x / y / z);
    assert_eq!(value("1 + 2*3", at), 7.0);
    assert_eq!(value("atan2(y, x)", at), y.atan2(x));
    assert_eq!(value("sqrt(z)*pi", at), z.sqrt() * std::f64::consts::PI);
    assert_eq!(value("pow(z, x)", at), z.powf(x));
    assert_eq!(value("1e-3*exp(log(z))", at), 1e-3 * z.ln().exp());
    assert_eq!(value("abs(y)*sign(y)", at), -y.abs());
}

/// Symbolic derivatives agree with central differences for expressions using every function.
#[test]
fn symbolic_derivatives_match_finite_differences() {
    let texts = [
        "sin(x)*cos(y)^2 + tan(z/3)",
        "sqrt(x^2 + y^2 + z^2) * exp(-x*y)",
        "atan2(y, x) + log(z) * asin(x/2) - acos(x/3)",
        "pow(z, x) + sinh(x)*cosh(y) + tanh(z) + atan(x*y)",
        "(x + y)/(z - x) * abs(y)",
    ];
    let at = [0.3, -1.2, 2.0];
    for text in texts {
        let mut g = Graph::default();
        let f = parse(text, &mut g, &Xyz).unwrap();
        for k in 0..3u32 {
            let d = g.diff(f, k);
            let exact = g.eval(d, &at);
            let h = 1e-6;
            let mut p = at;
            let mut m = at;
            p[k as usize] += h;
            m[k as usize] -= h;
            let fd = (g.eval(f, &p) - g.eval(f, &m)) / (2.0 * h);
            assert!(
                (exact - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                "d/d{k} of {text}: symbolic {exact}, differences {fd}"
            );
        }
    }
}

#[test]
fn shared_subexpressions_are_stored_once() {
    let mut g = Graph::default();
    let a = parse("sin(x*y) + sin(x*y)^2", &mut g, &Xyz).unwrap();
    let before = g.len();
    let b = parse("sin(y*x)", &mut g, &Xyz).unwrap();
    assert_eq!(
        g.len(),
        before,
        "sin(y*x) is the node sin(x*y) already holds"
    );
    // NaN (node 0), x, y, x*y, sin, the constant 2, sin^2, +: 8.
    assert_eq!(before, 8);
    let tape = Tape::new(&g, &[a, b]);
    // The exponent is part of the instruction: x*y, sin, ^2, + once each.
    assert_eq!(tape.len() + tape.prelude_len(), 4);
}

#[test]
fn parameters_are_hoisted_into_the_prelude() {
    let mut g = Graph::default();
    // Inputs 0, 1 vary, 2 is fixed: z*z/2 is computed once per run.
    let f = parse("z*z/2*x + y", &mut g, &Xyz).unwrap();
    let tape = Tape::with_fixed(&g, &[f], &|k| k == 2);
    let mut w = tape.workspace();
    w[2] = 3.0;
    tape.run_prelude(&mut w);
    w[0] = 2.0;
    w[1] = 1.0;
    tape.run(&mut w);
    assert_eq!(tape.output(&w, 0), 2.0 * 3.0 * 3.0 / 2.0 + 1.0);
    assert_eq!(tape.prelude_len(), 3, "z*z, 2 and /2 in the prelude");
    assert_eq!(tape.len(), 2, "*x and +y per evaluation");
}

#[test]
fn errors_say_where_and_what() {
    let mut g = Graph::default();
    let e = parse("x + sin(yy)", &mut g, &Xyz).unwrap_err();
    assert_eq!((e.offset, e.len), (8, 2));
    assert!(e.message.contains("unknown name `yy`"), "{}", e.message);
    assert!(e.message.contains("x, y, z, pi"), "{}", e.message);
    assert_eq!(e.excerpt("x + sin(yy)"), "    x + sin(yy)\n            ^^");
    for (text, words) in [
        ("x +", "expected a number"),
        ("(x + y", "not closed"),
        ("x y", "missing operator"),
        ("sin(x, y)", "takes 1 argument"),
        ("foo(x)", "unknown function"),
        ("x $ y", "not part of the expression language"),
        ("1e999", "not a finite number"),
        ("", "empty expression"),
        ("sin + 1", "is a function"),
    ] {
        let e = parse(text, &mut g, &Xyz).unwrap_err();
        assert!(e.message.contains(words), "{text}: {}", e.message);
    }
}

#[test]
fn runaway_expressions_are_refused_before_work() {
    let mut g = Graph::default();
    let deep = format!("{}x{}", "(".repeat(100), ")".repeat(100));
    assert!(
        parse(&deep, &mut g, &Xyz)
            .unwrap_err()
            .message
            .contains("nested more than")
    );
    let minus = format!("{}x", "-".repeat(100));
    assert!(
        parse(&minus, &mut g, &Xyz)
            .unwrap_err()
            .message
            .contains("nested more than")
    );
    let long = "x+".repeat(6000) + "x";
    assert!(
        parse(&long, &mut g, &Xyz)
            .unwrap_err()
            .message
            .contains("bytes long")
    );
    let mut small = Graph::with_limit(10);
    let _ = parse("sin(x)+cos(y)*tan(z)+exp(x*y*z)", &mut small, &Xyz).unwrap();
    assert!(small.check().is_err());
}

/// A chain of three rotations is each Euler convention's rotation, and its body angular
/// velocity is tumble-kinematics' `omega_body`, for all 24 conventions.
#[test]
fn euler_chains_match_the_kinematics_crate() {
    use nalgebra::Vector3;
    use tumble_kinematics::{EulerConvention, RotationKind};
    let angles = Vector3::new(0.4, 1.1, -0.7);
    let rates = Vector3::new(0.3, -0.8, 1.9);
    for conv in EulerConvention::all() {
        let mut g = Graph::default();
        let layout = Layout { n: 3, so3: 0 };
        let a: Vec<Id> = (0..3).map(|i| g.input(layout.q(i))).collect();
        let axes = conv.sequence.axes().map(|x| x.index());
        let links = match conv.kind {
            RotationKind::Intrinsic => vec![(axes[0], a[0]), (axes[1], a[1]), (axes[2], a[2])],
            RotationKind::Extrinsic => vec![(axes[2], a[2]), (axes[1], a[1]), (axes[0], a[0])],
        };
        let chain = Chain { links };
        let mut alg = Algebra { g: &mut g };
        let r = chain.rotation(&mut alg);
        let w = chain.omega_body(&mut alg, layout);
        let inputs = [0.0, angles.x, angles.y, angles.z, rates.x, rates.y, rates.z];
        let expected_r = conv.to_rotation(&angles);
        let expected_w = conv.omega_body(&angles, &rates);
        for i in 0..3 {
            for j in 0..3 {
                let v = g.eval(r[i][j], &inputs);
                assert!(
                    (v - expected_r[(i, j)]).abs() < 1e-15,
                    "{conv}: R[{i}][{j}]"
                );
            }
            let v = g.eval(w[i], &inputs);
            assert!(
                (v - expected_w[i]).abs() < 1e-14,
                "{conv}: omega[{i}] {v} vs {}",
                expected_w[i]
            );
        }
    }
}
