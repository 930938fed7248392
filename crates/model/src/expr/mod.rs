//! Expressions as a hash-consed graph (a DAG): every distinct subexpression is stored once, so
//! that a model's kinetic energy, its derivatives and its equations of motion share their common
//! parts, and an evaluation computes each once.
//!
//! * [`Graph`] owns the nodes; [`Id`] names one. Building a node that exists returns the
//!   existing one ([hash-consing](https://en.wikipedia.org/wiki/Hash_consing)); operands of `+`
//!   and `*` are ordered so that `a + b` and `b + a` are one node; operations on constants are
//!   folded with the same `f64` operation an evaluation would perform, and the identities
//!   `x + 0`, `x · 1`, `x · 0`, `x − x`, `−(−x)` are applied as nodes are built.
//! * [`Graph::diff`] differentiates symbolically with respect to an input, memoized per input,
//!   so that second derivatives (a mass matrix) are derivatives of the first and share them.
//! * [`tape::Tape`] flattens the nodes some outputs need into a list of instructions evaluated
//!   without allocation ([`tape`]).
//! * [`parse`] reads the expression language into the graph.
//!
//! The graph is the form from which derivatives of any order (for a Taylor method: the
//! recursions of automatic differentiation, one rule per [`Node`] kind) and native code can both
//! be derived, as in heyoka (Biscani & Izzo, *Revisiting high-order Taylor methods for
//! astrodynamics and celestial mechanics*, MNRAS 504 (2021) 2614).
//!
//! `x · 0 = 0` is applied for every `x`, as in symbolic algebra: an expression that overflows
//! where it is multiplied by an exact zero evaluates to 0, not NaN.

pub mod parse;
pub mod scalar;
pub mod tape;
pub mod taylor;

use std::collections::HashMap;

/// A node of a [`Graph`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub(crate) u32);

impl Id {
    /// Its index in the graph's nodes.
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A function of one argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Fun {
    /// `√x`.
    Sqrt,
    /// `sin x`.
    Sin,
    /// `cos x`.
    Cos,
    /// `tan x`.
    Tan,
    /// `asin x`.
    Asin,
    /// `acos x`.
    Acos,
    /// `atan x`.
    Atan,
    /// `sinh x`.
    Sinh,
    /// `cosh x`.
    Cosh,
    /// `tanh x`.
    Tanh,
    /// `eˣ`.
    Exp,
    /// `ln x`.
    Log,
    /// `|x|`.
    Abs,
    /// The sign of `x` (−1, 0, 1): the derivative of `|x|`.
    Sign,
}

impl Fun {
    /// Every function by its name in the language.
    pub const ALL: [(&'static str, Fun); 14] = [
        ("sqrt", Fun::Sqrt),
        ("sin", Fun::Sin),
        ("cos", Fun::Cos),
        ("tan", Fun::Tan),
        ("asin", Fun::Asin),
        ("acos", Fun::Acos),
        ("atan", Fun::Atan),
        ("sinh", Fun::Sinh),
        ("cosh", Fun::Cosh),
        ("tanh", Fun::Tanh),
        ("exp", Fun::Exp),
        ("log", Fun::Log),
        ("abs", Fun::Abs),
        ("sign", Fun::Sign),
    ];

    /// Its value at `x` in any real scalar (as [`Fun::apply`] for `f64`; for dual numbers
    /// with the derivatives of the function, `sign` having none).
    #[must_use]
    pub fn apply_real<D: nalgebra::RealField + Copy + From<f64>>(self, x: D) -> D {
        match self {
            Fun::Sqrt => x.sqrt(),
            Fun::Sin => x.sin(),
            Fun::Cos => x.cos(),
            Fun::Tan => x.tan(),
            Fun::Asin => x.asin(),
            Fun::Acos => x.acos(),
            Fun::Atan => x.atan(),
            Fun::Sinh => x.sinh(),
            Fun::Cosh => x.cosh(),
            Fun::Tanh => x.tanh(),
            Fun::Exp => x.exp(),
            Fun::Log => x.ln(),
            Fun::Abs => x.abs(),
            Fun::Sign => {
                let zero = D::from(0.0);
                if x > zero {
                    D::from(1.0)
                } else if x < zero {
                    D::from(-1.0)
                } else {
                    x * zero
                }
            }
        }
    }

    /// Its value at `x`.
    #[must_use]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Fun::Sqrt => x.sqrt(),
            Fun::Sin => x.sin(),
            Fun::Cos => x.cos(),
            Fun::Tan => x.tan(),
            Fun::Asin => x.asin(),
            Fun::Acos => x.acos(),
            Fun::Atan => x.atan(),
            Fun::Sinh => x.sinh(),
            Fun::Cosh => x.cosh(),
            Fun::Tanh => x.tanh(),
            Fun::Exp => x.exp(),
            Fun::Log => x.ln(),
            Fun::Abs => x.abs(),
            Fun::Sign => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    // 0 at 0, and NaN stays NaN.
                    x
                }
            }
        }
    }
}

/// One operation of the graph.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, by its bits (so that the node can be hashed).
    Const(u64),
    /// Input number `k` (time, a coordinate, a rate, a parameter: the caller's numbering).
    Input(u32),
    /// `a + b`.
    Add(Id, Id),
    /// `a − b`.
    Sub(Id, Id),
    /// `a · b`.
    Mul(Id, Id),
    /// `a / b`.
    Div(Id, Id),
    /// `−a`.
    Neg(Id),
    /// `aⁿ` for an integer `n`.
    Powi(Id, i32),
    /// `aᵇ`.
    Pow(Id, Id),
    /// `atan2(y, x)`.
    Atan2(Id, Id),
    /// `f(a)`.
    Call(Fun, Id),
}

impl Node {
    /// The nodes it reads.
    #[must_use]
    pub fn operands(&self) -> ([Id; 2], usize) {
        let z = Id(0);
        match *self {
            Node::Const(_) | Node::Input(_) => ([z, z], 0),
            Node::Neg(a) | Node::Powi(a, _) | Node::Call(_, a) => ([a, z], 1),
            Node::Add(a, b)
            | Node::Sub(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Pow(a, b)
            | Node::Atan2(a, b) => ([a, b], 2),
        }
    }
}

/// The graph grew beyond its limit of nodes ([`Graph::with_limit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the expressions grew beyond {limit} operations (a runaway model or its derivatives)")]
pub struct TooLarge {
    /// The limit.
    pub limit: usize,
}

/// A hash-consed expression graph.
#[derive(Debug, Clone)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    /// Derivatives computed so far: `(node, input) → node`.
    derivatives: HashMap<(Id, u32), Id>,
    limit: usize,
    overflow: bool,
}

impl Default for Graph {
    fn default() -> Self {
        Self::with_limit(1 << 22)
    }
}

/// Builds `a op b` through the graph: the methods below.
impl Graph {
    /// A graph (holding only node 0, the constant NaN) that refuses to grow beyond `limit`
    /// nodes: once reached, new nodes are the constant NaN and [`Graph::check`] reports
    /// [`TooLarge`].
    #[must_use]
    pub fn with_limit(limit: usize) -> Self {
        let nan = Node::Const(f64::NAN.to_bits());
        Graph {
            nodes: vec![nan],
            index: HashMap::from([(nan, Id(0))]),
            derivatives: HashMap::new(),
            limit: limit.max(1),
            overflow: false,
        }
    }

    /// `Err` once the graph has reached its limit.
    ///
    /// # Errors
    /// [`TooLarge`].
    pub fn check(&self) -> Result<(), TooLarge> {
        if self.overflow {
            Err(TooLarge { limit: self.limit })
        } else {
            Ok(())
        }
    }

    /// Number of nodes.
    #[must_use]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether it has no node.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node `id`.
    #[must_use]
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.index()]
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        if self.nodes.len() >= self.limit {
            self.overflow = true;
            // Node 0 is the constant NaN ([`Self::with_limit`]).
            return Id(0);
        }
        let id = Id(u32::try_from(self.nodes.len()).unwrap_or(u32::MAX));
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// The constant `x`.
    pub fn constant(&mut self, x: f64) -> Id {
        // One zero: −0 and 0 are the same constant for the identities below.
        let x = if x == 0.0 { 0.0 } else { x };
        self.intern(Node::Const(x.to_bits()))
    }

    /// Input `k`.
    pub fn input(&mut self, k: u32) -> Id {
        self.intern(Node::Input(k))
    }

    /// The value of `id` when it is a constant.
    #[must_use]
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.nodes[id.index()] {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn is(&self, id: Id, x: f64) -> bool {
        self.as_const(id) == Some(x)
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x + y);
        }
        if self.is(a, 0.0) {
            return b;
        }
        if self.is(b, 0.0) {
            return a;
        }
        if let Node::Neg(c) = self.nodes[b.index()] {
            return self.sub(a, c);
        }
        if let Node::Neg(c) = self.nodes[a.index()] {
            return self.sub(b, c);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// `a − b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x - y);
        }
        if a == b {
            return self.constant(0.0);
        }
        if self.is(b, 0.0) {
            return a;
        }
        if self.is(a, 0.0) {
            return self.neg(b);
        }
        if let Node::Neg(c) = self.nodes[b.index()] {
            return self.add(a, c);
        }
        self.intern(Node::Sub(a, b))
    }

    /// `a · b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x * y);
        }
        if self.is(a, 0.0) || self.is(b, 0.0) {
            return self.constant(0.0);
        }
        if self.is(a, 1.0) {
            return b;
        }
        if self.is(b, 1.0) {
            return a;
        }
        if self.is(a, -1.0) {
            return self.neg(b);
        }
        if self.is(b, -1.0) {
            return self.neg(a);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    /// `a / b`.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x / y);
        }
        if self.is(a, 0.0) {
            return self.constant(0.0);
        }
        if self.is(b, 1.0) {
            return a;
        }
        if a == b {
            return self.constant(1.0);
        }
        self.intern(Node::Div(a, b))
    }

    /// `−a`.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(-x);
        }
        if let Node::Neg(b) = self.nodes[a.index()] {
            return b;
        }
        self.intern(Node::Neg(a))
    }

    /// `aⁿ`.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.powi(n));
        }
        match n {
            0 => self.constant(1.0),
            1 => a,
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    /// `aᵇ` (an integer constant exponent becomes [`Node::Powi`]).
    pub fn pow(&mut self, a: Id, b: Id) -> Id {
        if let Some(y) = self.as_const(b)
            && y.fract() == 0.0
            && y.abs() <= 64.0
        {
            return self.powi(a, y as i32);
        }
        if let Some(y) = self.as_const(b)
            && y == 0.5
        {
            return self.call(Fun::Sqrt, a);
        }
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x.powf(y));
        }
        self.intern(Node::Pow(a, b))
    }

    /// `atan2(y, x)`.
    pub fn atan2(&mut self, y: Id, x: Id) -> Id {
        if let (Some(a), Some(b)) = (self.as_const(y), self.as_const(x)) {
            return self.constant(a.atan2(b));
        }
        self.intern(Node::Atan2(y, x))
    }

    /// `f(a)`.
    pub fn call(&mut self, f: Fun, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(f.apply(x));
        }
        self.intern(Node::Call(f, a))
    }

    /// `Σ terms` (0 for none).
    pub fn sum(&mut self, terms: &[Id]) -> Id {
        let mut acc = self.constant(0.0);
        for &t in terms {
            acc = self.add(acc, t);
        }
        acc
    }

    /// Whether `id` depends on any input for which `pred` holds.
    #[must_use]
    pub fn depends_on(&self, id: Id, pred: &dyn Fn(u32) -> bool) -> bool {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![id];
        while let Some(n) = stack.pop() {
            if std::mem::replace(&mut seen[n.index()], true) {
                continue;
            }
            let node = self.nodes[n.index()];
            if let Node::Input(k) = node
                && pred(k)
            {
                return true;
            }
            let (ops, count) = node.operands();
            stack.extend_from_slice(&ops[..count]);
        }
        false
    }

    /// `∂id/∂(input k)`, symbolically, memoized.
    pub fn diff(&mut self, id: Id, k: u32) -> Id {
        if let Some(&d) = self.derivatives.get(&(id, k)) {
            return d;
        }
        // Iterative post-order so that deep expressions do not exhaust the stack.
        let mut stack = vec![(id, false)];
        while let Some((n, ready)) = stack.pop() {
            if self.derivatives.contains_key(&(n, k)) {
                continue;
            }
            let node = self.nodes[n.index()];
            let (ops, count) = node.operands();
            if !ready {
                stack.push((n, true));
                for &o in &ops[..count] {
                    if !self.derivatives.contains_key(&(o, k)) {
                        stack.push((o, false));
                    }
                }
                continue;
            }
            let d = self.diff_node(n, node, k);
            self.derivatives.insert((n, k), d);
        }
        self.derivatives[&(id, k)]
    }

    /// The derivative of node `n` (= `node`) given its operands' derivatives.
    fn diff_node(&mut self, n: Id, node: Node, k: u32) -> Id {
        let d = |g: &Self, a: Id| g.derivatives[&(a, k)];
        match node {
            Node::Const(_) => self.constant(0.0),
            Node::Input(j) => self.constant(if j == k { 1.0 } else { 0.0 }),
            Node::Add(a, b) => {
                let (da, db) = (d(self, a), d(self, b));
                self.add(da, db)
            }
            Node::Sub(a, b) => {
                let (da, db) = (d(self, a), d(self, b));
                self.sub(da, db)
            }
            Node::Mul(a, b) => {
                let (da, db) = (d(self, a), d(self, b));
                let x = self.mul(da, b);
                let y = self.mul(a, db);
                self.add(x, y)
            }
            Node::Div(a, b) => {
                // (a/b)' = (a' − (a/b) b') / b
                let (da, db) = (d(self, a), d(self, b));
                let x = self.mul(n, db);
                let y = self.sub(da, x);
                self.div(y, b)
            }
            Node::Neg(a) => {
                let da = d(self, a);
                self.neg(da)
            }
            Node::Powi(a, m) => {
                let da = d(self, a);
                if self.is(da, 0.0) {
                    return da;
                }
                let c = self.constant(f64::from(m));
                let p = self.powi(a, m - 1);
                let cp = self.mul(c, p);
                self.mul(cp, da)
            }
            Node::Pow(a, b) => {
                // (aᵇ)' = aᵇ (b' ln a + b a'/a)
                let (da, db) = (d(self, a), d(self, b));
                let ln = self.call(Fun::Log, a);
                let x = self.mul(db, ln);
                let ba = self.mul(b, da);
                let y = self.div(ba, a);
                let s = self.add(x, y);
                self.mul(n, s)
            }
            Node::Atan2(y, x) => {
                // (x y' − y x') / (x² + y²)
                let (dy, dx) = (d(self, y), d(self, x));
                let a = self.mul(x, dy);
                let b = self.mul(y, dx);
                let num = self.sub(a, b);
                let x2 = self.powi(x, 2);
                let y2 = self.powi(y, 2);
                let den = self.add(x2, y2);
                self.div(num, den)
            }
            Node::Call(f, a) => {
                let da = d(self, a);
                if self.is(da, 0.0) {
                    return da;
                }
                let one = self.constant(1.0);
                let factor = match f {
                    Fun::Sqrt => {
                        let two = self.constant(2.0);
                        let t = self.mul(two, n);
                        self.div(one, t)
                    }
                    Fun::Sin => self.call(Fun::Cos, a),
                    Fun::Cos => {
                        let s = self.call(Fun::Sin, a);
                        self.neg(s)
                    }
                    Fun::Tan => {
                        let t2 = self.powi(n, 2);
                        self.add(one, t2)
                    }
                    Fun::Asin | Fun::Acos => {
                        let a2 = self.powi(a, 2);
                        let r = self.sub(one, a2);
                        let s = self.call(Fun::Sqrt, r);
                        let inv = self.div(one, s);
                        if f == Fun::Asin { inv } else { self.neg(inv) }
                    }
                    Fun::Atan => {
                        let a2 = self.powi(a, 2);
                        let r = self.add(one, a2);
                        self.div(one, r)
                    }
                    Fun::Sinh => self.call(Fun::Cosh, a),
                    Fun::Cosh => self.call(Fun::Sinh, a),
                    Fun::Tanh => {
                        let t2 = self.powi(n, 2);
                        self.sub(one, t2)
                    }
                    Fun::Exp => n,
                    Fun::Log => self.div(one, a),
                    Fun::Abs => self.call(Fun::Sign, a),
                    Fun::Sign => return self.constant(0.0),
                };
                self.mul(factor, da)
            }
        }
    }

    /// The value of `id` with inputs `inputs` (by recursion over the graph, memoized: for tests
    /// and one-off values; runs use a [`tape::Tape`]).
    #[must_use]
    pub fn eval(&self, id: Id, inputs: &[f64]) -> f64 {
        let t = tape::Tape::new(self, &[id]);
        let mut w = t.workspace();
        t.run_all(&mut w, inputs);
        t.output(&w, 0)
    }

    /// The expression `id` as text (for messages and tests).
    #[must_use]
    pub fn display(&self, id: Id, names: &dyn Fn(u32) -> String) -> String {
        match self.nodes[id.index()] {
            Node::Const(b) => format!("{}", f64::from_bits(b)),
            Node::Input(k) => names(k),
            Node::Add(a, b) => format!("({} + {})", self.display(a, names), self.display(b, names)),
            Node::Sub(a, b) => format!("({} - {})", self.display(a, names), self.display(b, names)),
            Node::Mul(a, b) => format!("{} * {}", self.display(a, names), self.display(b, names)),
            Node::Div(a, b) => format!("{} / ({})", self.display(a, names), self.display(b, names)),
            Node::Neg(a) => format!("-({})", self.display(a, names)),
            Node::Powi(a, n) => format!("({})^{n}", self.display(a, names)),
            Node::Pow(a, b) => format!("({})^({})", self.display(a, names), self.display(b, names)),
            Node::Atan2(a, b) => {
                format!(
                    "atan2({}, {})",
                    self.display(a, names),
                    self.display(b, names)
                )
            }
            Node::Call(f, a) => {
                let name = Fun::ALL
                    .iter()
                    .find(|(_, g)| *g == f)
                    .map_or("?", |(n, _)| n);
                format!("{name}({})", self.display(a, names))
            }
        }
    }
}
