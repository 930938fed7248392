//! Units of a model's expressions: where parameters declare units, the dimensions (mass,
//! length, time) of every expression are inferred through the graph and checked — a sum of
//! unlike quantities, a function of a dimensional argument, a potential that is not an energy,
//! a position that is not a length are refused before any work.
//!
//! The rules are those of dimensional analysis (e.g. Bridgman, *Dimensional Analysis*, 1922):
//! sums and differences need equal dimensions; products and quotients add and subtract them;
//! `xⁿ` multiplies them by `n` (and `√x` halves them); `sin`, `exp`, `ln`, … and exponents take
//! dimensionless arguments; `atan2(y, x)` takes two alike. Angles (`rad`, `deg`) are
//! dimensionless. A parameter without a unit makes what it touches unknown, and unknown is never
//! refused; a bare number is dimensionless as a factor and takes the dimensions of what it is
//! added to (`x + 1`), so that `mass = "0.1"` or `potential = "0"` are accepted as they are
//! written.

use std::fmt;

use crate::expr::{Fun, Graph, Id, Node};
use crate::mechanics::Layout;

/// Dimensions as twice the exponents of mass, length and time (halves: `√(kg)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dim([i16; 3]);

impl Dim {
    /// A pure number.
    pub const ONE: Dim = Dim([0, 0, 0]);
    /// Mass.
    pub const MASS: Dim = Dim([2, 0, 0]);
    /// Length.
    pub const LENGTH: Dim = Dim([0, 2, 0]);
    /// Time.
    pub const TIME: Dim = Dim([0, 0, 2]);
    /// Energy, `kg m² / s²`.
    pub const ENERGY: Dim = Dim([2, 4, -4]);
    /// Acceleration, `m / s²`.
    pub const ACCELERATION: Dim = Dim([0, 2, -4]);
    /// Moment of inertia, `kg m²`.
    pub const INERTIA: Dim = Dim([2, 4, 0]);
    /// Rate, `1 / s`.
    pub const RATE: Dim = Dim([0, 0, -2]);

    fn mul(self, o: Dim) -> Dim {
        Dim([0, 1, 2].map(|i| self.0[i] + o.0[i]))
    }

    fn div(self, o: Dim) -> Dim {
        Dim([0, 1, 2].map(|i| self.0[i] - o.0[i]))
    }

    /// `self` to the power `p`, if the result has whole or half exponents.
    fn pow(self, p: f64) -> Option<Dim> {
        let mut out = [0i16; 3];
        for i in 0..3 {
            let e = f64::from(self.0[i]) * p;
            if (e - e.round()).abs() > 1e-9 || e.abs() > 1000.0 {
                return None;
            }
            out[i] = e.round() as i16;
        }
        Some(Dim(out))
    }
}

impl fmt::Display for Dim {
    /// `kg*m^2/s^2`, `1` for a pure number; half powers as `^1/2`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == Dim::ONE {
            return f.write_str("1 (a pure number)");
        }
        let power = |e: i16| -> String {
            let a = e.abs();
            match (a % 2, a / 2) {
                (0, 1) => String::new(),
                (0, p) => format!("^{p}"),
                _ => format!("^{a}/2"),
            }
        };
        let names = ["kg", "m", "s"];
        let up: Vec<String> = (0..3)
            .filter(|&i| self.0[i] > 0)
            .map(|i| format!("{}{}", names[i], power(self.0[i])))
            .collect();
        let down: Vec<String> = (0..3)
            .filter(|&i| self.0[i] < 0)
            .map(|i| format!("{}{}", names[i], power(self.0[i])))
            .collect();
        let top = if up.is_empty() {
            "1".to_string()
        } else {
            up.join("*")
        };
        if down.is_empty() {
            f.write_str(&top)
        } else {
            write!(f, "{top}/{}", down.join("/"))
        }
    }
}

/// The units a parameter may declare, by name.
const UNITS: [(&str, Dim); 19] = [
    ("kg", Dim::MASS),
    ("g", Dim::MASS),
    ("m", Dim::LENGTH),
    ("cm", Dim::LENGTH),
    ("mm", Dim::LENGTH),
    ("km", Dim::LENGTH),
    ("s", Dim::TIME),
    ("ms", Dim::TIME),
    ("min", Dim::TIME),
    ("h", Dim::TIME),
    ("rad", Dim::ONE),
    ("deg", Dim::ONE),
    ("rev", Dim::ONE),
    ("1", Dim::ONE),
    ("N", Dim([2, 2, -4])),
    ("J", Dim::ENERGY),
    ("W", Dim([2, 4, -6])),
    ("Hz", Dim::RATE),
    ("Pa", Dim([2, -2, -4])),
];

/// The dimensions of a unit written as products and quotients of known units with integer
/// powers: `kg*m^2/s^2`, `rad/s`, `N*m`. An empty unit is unknown (`None`).
///
/// # Errors
/// A message naming the unknown part and the units known.
pub fn parse_unit(text: &str) -> Result<Option<Dim>, String> {
    let text = text.trim();
    if text.is_empty() {
        return Ok(None);
    }
    let mut dim = Dim::ONE;
    let mut rest = text;
    let mut divide = false;
    loop {
        let end = rest.find(['*', '/']).unwrap_or(rest.len());
        let term = rest[..end].trim();
        let (name, power) = match term.split_once('^') {
            Some((n, p)) => (
                n.trim(),
                p.trim().parse::<i16>().map_err(|_| {
                    format!(
                        "`{term}` in unit {text:?}: a power is a whole number, such as m^2 or s^-1"
                    )
                })?,
            ),
            None => (term, 1),
        };
        let Some((_, d)) = UNITS.iter().find(|(n, _)| *n == name) else {
            let known: Vec<&str> = UNITS.iter().map(|(n, _)| *n).collect();
            return Err(format!(
                "unknown unit `{name}` in {text:?}; a unit is a product or quotient of {} with whole powers, such as \"kg*m^2/s^2\" or \"rad/s\"",
                known.join(", ")
            ));
        };
        let d = d.pow(f64::from(power)).unwrap_or(Dim::ONE);
        dim = if divide { dim.div(d) } else { dim.mul(d) };
        if end == rest.len() {
            return Ok(Some(dim));
        }
        divide = rest.as_bytes()[end] == b'/';
        rest = &rest[end + 1..];
    }
}

/// What is known of a node's dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Known {
    /// Dimensions.
    Dim(Dim),
    /// A bare number: dimensionless as a factor, alike with what it is added to.
    Number,
    /// Unknown (it depends on a parameter or coordinate without units).
    Unknown,
}

/// Dimensions of the nodes of a graph, inferred from its inputs'.
pub struct Inference<'g> {
    graph: &'g Graph,
    inputs: Vec<Option<Dim>>,
    memo: Vec<Option<Known>>,
}

/// An inconsistency: the message, for the expression that holds it.
pub type Inconsistent = String;

impl<'g> Inference<'g> {
    /// Inference over `graph` with inputs numbered as the model's `layout`: time in seconds,
    /// the parameters' units as declared, coordinates as their initial values (or, for a
    /// coordinate whose initial value is a bare number, its initial rate times a time), rates
    /// as their coordinates per second, an SO(3) orientation's matrix dimensionless and its
    /// angular velocity per second.
    #[must_use]
    pub fn new(
        graph: &'g Graph,
        layout: Layout,
        params: &[Option<Dim>],
        initial: &[Id],
        initial_rates: &[Id],
    ) -> Self {
        let count = layout.param(params.len()) as usize;
        let mut inputs = vec![None; count];
        inputs[Layout::T as usize] = Some(Dim::TIME);
        for (j, d) in params.iter().enumerate() {
            inputs[layout.param(j) as usize] = *d;
        }
        let mut me = Inference {
            graph,
            inputs,
            memo: vec![None; graph.len()],
        };
        for i in 0..layout.n {
            let q = match me.dims(initial[i]) {
                Ok(Known::Dim(d)) => Some(d),
                _ => match me.dims(initial_rates[i]) {
                    Ok(Known::Dim(d)) => Some(d.mul(Dim::TIME)),
                    _ => None,
                },
            };
            me.inputs[layout.q(i) as usize] = q;
            me.inputs[layout.qd(i) as usize] = q.map(|d| d.div(Dim::TIME));
        }
        // An orientation on SO(3): a dimensionless rotation matrix turning at a rate.
        for f in 0..layout.so3 {
            for a in 0..3 {
                for b in 0..3 {
                    me.inputs[layout.rot(f, a, b) as usize] = Some(Dim::ONE);
                }
                me.inputs[layout.omega(f, a) as usize] = Some(Dim::RATE);
            }
        }
        // The coordinates' dimensions are now known: forget what was inferred without them.
        me.memo.fill(None);
        me
    }

    /// What is known of `id`'s dimensions.
    fn dims(&mut self, id: Id) -> Result<Known, Inconsistent> {
        if let Some(k) = self.memo[id.index()] {
            return Ok(k);
        }
        let node = self.graph.node(id);
        let (ops, count) = node.operands();
        let mut args = [Known::Unknown; 2];
        for k in 0..count {
            args[k] = self.dims(ops[k])?;
        }
        let [a, b] = args;
        let alike = |what: &str| -> Result<Known, Inconsistent> {
            match (a, b) {
                (Known::Dim(x), Known::Dim(y)) if x != y => Err(format!("{what} of {x} and {y}")),
                (Known::Dim(x), _) | (_, Known::Dim(x)) => Ok(Known::Dim(x)),
                (Known::Number, Known::Number) => Ok(Known::Number),
                _ => Ok(Known::Unknown),
            }
        };
        let as_factor = |k: Known| match k {
            Known::Dim(d) => Some(d),
            Known::Number => Some(Dim::ONE),
            Known::Unknown => None,
        };
        let dimensionless = |k: Known, what: &str| -> Result<(), Inconsistent> {
            match k {
                Known::Dim(d) if d != Dim::ONE => Err(format!("{what} of a quantity in {d}")),
                _ => Ok(()),
            }
        };
        let number_or = |k: Known, f: &dyn Fn(Dim) -> Option<Dim>| match k {
            Known::Number => Known::Number,
            Known::Dim(d) => f(d).map_or(Known::Unknown, Known::Dim),
            Known::Unknown => Known::Unknown,
        };
        let known = match node {
            Node::Const(bits) => {
                if f64::from_bits(bits) == 0.0 {
                    // Zero is alike with everything.
                    Known::Unknown
                } else {
                    Known::Number
                }
            }
            Node::Input(k) => self
                .inputs
                .get(k as usize)
                .copied()
                .flatten()
                .map_or(Known::Unknown, Known::Dim),
            Node::Add(..) => alike("a sum")?,
            Node::Sub(..) => alike("a difference")?,
            Node::Mul(..) | Node::Div(..) => match (a, b) {
                (Known::Number, Known::Number) => Known::Number,
                _ => match (as_factor(a), as_factor(b)) {
                    (Some(x), Some(y)) => Known::Dim(if matches!(node, Node::Mul(..)) {
                        x.mul(y)
                    } else {
                        x.div(y)
                    }),
                    _ => Known::Unknown,
                },
            },
            Node::Neg(_) => a,
            Node::Powi(_, n) => number_or(a, &|d| d.pow(f64::from(n))),
            Node::Pow(_, e) => {
                dimensionless(b, "an exponent")?;
                match self.graph.as_const(e) {
                    Some(p) => number_or(a, &|d| d.pow(p)),
                    None => {
                        dimensionless(a, "a power with a variable exponent")?;
                        number_or(a, &|_| Some(Dim::ONE))
                    }
                }
            }
            Node::Atan2(..) => {
                alike("atan2")?;
                Known::Dim(Dim::ONE)
            }
            Node::Call(f, _) => match f {
                Fun::Sqrt => number_or(a, &|d| d.pow(0.5)),
                Fun::Abs => a,
                Fun::Sign => Known::Dim(Dim::ONE),
                _ => {
                    dimensionless(a, &format!("{}()", fun_name(f)))?;
                    number_or(a, &|_| Some(Dim::ONE))
                }
            },
        };
        self.memo[id.index()] = Some(known);
        Ok(known)
    }

    /// Checks the expression `id`: consistent throughout, and of dimensions `expected` where
    /// both are known. Returns what is wrong.
    ///
    /// # Errors
    /// A message: the inconsistency inside, or the dimensions found and expected.
    pub fn check(&mut self, id: Id, expected: Option<(Dim, &str)>) -> Result<(), Inconsistent> {
        let found = self.dims(id)?;
        if let (Known::Dim(d), Some((e, what))) = (found, expected)
            && d != e
        {
            return Err(format!("has units {d}, not {what} ({e})"));
        }
        Ok(())
    }
}

fn fun_name(f: Fun) -> &'static str {
    match f {
        Fun::Sqrt => "sqrt",
        Fun::Sin => "sin",
        Fun::Cos => "cos",
        Fun::Tan => "tan",
        Fun::Asin => "asin",
        Fun::Acos => "acos",
        Fun::Atan => "atan",
        Fun::Sinh => "sinh",
        Fun::Cosh => "cosh",
        Fun::Tanh => "tanh",
        Fun::Exp => "exp",
        Fun::Log => "ln",
        Fun::Abs => "abs",
        Fun::Sign => "sign",
    }
}

/// The dimensions an expression at `key` must have, by what the key declares: energies,
/// gravity, positions, masses, inertia, angles, a frame's rate of turn.
#[must_use]
pub fn expected(key: &str) -> Option<(Dim, &'static str)> {
    let last = key.rsplit('.').next().unwrap_or(key);
    let field = last.split('[').next().unwrap_or(last);
    let top = key.split('.').next().unwrap_or(key);
    Some(match (top, field) {
        ("lagrangian", "potential" | "kinetic") => (Dim::ENERGY, "an energy"),
        ("lagrangian", "gravity") => (Dim::ACCELERATION, "an acceleration"),
        ("points" | "bodies", "position" | "origin" | "com") => (Dim::LENGTH, "a length"),
        ("points" | "bodies", "mass") => (Dim::MASS, "a mass"),
        ("bodies", "inertia") => (Dim::INERTIA, "a moment of inertia"),
        ("frames", "angles" | "rotations") => (Dim::ONE, "an angle"),
        ("rotating_frame" | "frames", "omega") => (Dim::RATE, "a rate of turn"),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_parse_to_their_dimensions() {
        assert_eq!(parse_unit("kg*m^2/s^2"), Ok(Some(Dim::ENERGY)));
        assert_eq!(parse_unit("N*m"), Ok(Some(Dim::ENERGY)));
        assert_eq!(parse_unit("J"), Ok(Some(Dim::ENERGY)));
        assert_eq!(parse_unit("rad/s"), Ok(Some(Dim::RATE)));
        assert_eq!(parse_unit("m/s^2"), Ok(Some(Dim::ACCELERATION)));
        assert_eq!(parse_unit("s^-1"), Ok(Some(Dim::RATE)));
        assert_eq!(parse_unit("rad"), Ok(Some(Dim::ONE)));
        assert_eq!(parse_unit(""), Ok(None));
        assert!(
            parse_unit("furlong")
                .unwrap_err()
                .contains("unknown unit `furlong`")
        );
        assert!(parse_unit("m^x").unwrap_err().contains("whole number"));
    }

    #[test]
    fn dimensions_print_as_units() {
        assert_eq!(Dim::ENERGY.to_string(), "kg*m^2/s^2");
        assert_eq!(Dim::RATE.to_string(), "1/s");
        assert_eq!(Dim::LENGTH.pow(0.5).unwrap().to_string(), "m^1/2");
    }
}
