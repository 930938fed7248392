//! A flat instruction tape: the nodes some outputs of a [`Graph`] need, in dependency order,
//! each writing one slot of a workspace allocated once. Evaluating it allocates nothing.
//!
//! Inputs split into *fixed* ones (a run's parameters) and *varying* ones (time, coordinates,
//! rates): the nodes that depend on fixed inputs only (a moment of inertia `M a²/2`, `g/a`)
//! form the tape's prelude, evaluated once per run by [`Tape::run_prelude`]; the rest, the body
//! run per evaluation by [`Tape::run`].

use super::scalar::TapeScalar;
use super::{Fun, Graph, Id, Node};
use tumble_jit::{Fn1, Fn2, JitError, Native, Program};

/// One operation of a tape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Op {
    Const(f64),
    Add,
    Sub,
    Mul,
    Div,
    Neg,
    Powi(i32),
    Pow,
    Atan2,
    Call(Fun),
}

/// An instruction: `slot[dst] = op(slot[a], slot[b])`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Instr {
    pub(super) op: Op,
    pub(super) dst: u32,
    pub(super) a: u32,
    pub(super) b: u32,
}

/// Outputs of a graph as instructions.
#[derive(Debug, Clone, PartialEq)]
pub struct Tape {
    pub(super) inputs: usize,
    pub(super) slots: usize,
    pub(super) prelude: Vec<Instr>,
    pub(super) body: Vec<Instr>,
    pub(super) outputs: Vec<u32>,
}

impl Tape {
    /// The tape of `outputs`, every input varying (no prelude); inputs are numbered as in the
    /// graph's [`Node::Input`] and the workspace has a slot for each up to the largest.
    #[must_use]
    pub fn new(graph: &Graph, outputs: &[Id]) -> Self {
        Self::with_fixed(graph, outputs, &|_| false)
    }

    /// The tape of `outputs`, with the nodes that depend only on constants and on inputs for
    /// which `fixed` holds in the prelude.
    #[must_use]
    pub fn with_fixed(graph: &Graph, outputs: &[Id], fixed: &dyn Fn(u32) -> bool) -> Self {
        let n = graph.len();
        let mut needed = vec![false; n];
        let mut stack: Vec<Id> = outputs.to_vec();
        let mut inputs = 0usize;
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut needed[id.index()], true) {
                continue;
            }
            let node = graph.node(id);
            if let Node::Input(k) = node {
                inputs = inputs.max(k as usize + 1);
            }
            let (ops, count) = node.operands();
            stack.extend_from_slice(&ops[..count]);
        }
        // Node ids are topological: operands are built before the nodes that read them.
        let mut slot = vec![u32::MAX; n];
        let mut varying = vec![false; n];
        let mut next = inputs;
        let (mut prelude, mut body) = (Vec::new(), Vec::new());
        for i in 0..n {
            if !needed[i] {
                continue;
            }
            let node = graph.node(Id(i as u32));
            let (ops, count) = node.operands();
            let [a, b] = [ops[0], ops[1]].map(|o| slot[o.index()]);
            let op = match node {
                Node::Input(k) => {
                    slot[i] = k;
                    varying[i] = !fixed(k);
                    continue;
                }
                Node::Const(bits) => Op::Const(f64::from_bits(bits)),
                Node::Add(..) => Op::Add,
                Node::Sub(..) => Op::Sub,
                Node::Mul(..) => Op::Mul,
                Node::Div(..) => Op::Div,
                Node::Neg(_) => Op::Neg,
                Node::Powi(_, m) => Op::Powi(m),
                Node::Pow(..) => Op::Pow,
                Node::Atan2(..) => Op::Atan2,
                Node::Call(f, _) => Op::Call(f),
            };
            varying[i] = ops[..count].iter().any(|o| varying[o.index()]);
            slot[i] = next as u32;
            let instr = Instr {
                op,
                dst: next as u32,
                a: if count > 0 { a } else { 0 },
                b: if count > 1 { b } else { 0 },
            };
            next += 1;
            if varying[i] {
                body.push(instr);
            } else {
                prelude.push(instr);
            }
        }
        Tape {
            inputs,
            slots: next,
            prelude,
            body,
            outputs: outputs.iter().map(|o| slot[o.index()]).collect(),
        }
    }

    /// A workspace for this tape (the one allocation).
    #[must_use]
    pub fn workspace(&self) -> Vec<f64> {
        vec![0.0; self.slots]
    }

    /// Number of input slots (the largest input number read, plus one).
    #[must_use]
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// Instructions run per evaluation.
    #[must_use]
    pub fn len(&self) -> usize {
        self.body.len()
    }

    /// Whether the body is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.body.is_empty()
    }

    /// Instructions of the prelude.
    #[must_use]
    pub fn prelude_len(&self) -> usize {
        self.prelude.len()
    }

    #[inline]
    fn exec<S: TapeScalar>(code: &[Instr], w: &mut [S]) {
        for ins in code {
            let x = w[ins.a as usize];
            let y = w[ins.b as usize];
            w[ins.dst as usize] = match ins.op {
                Op::Const(c) => S::of(c),
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
                Op::Div => x.quotient(y),
                Op::Neg => -x,
                Op::Powi(m) => x.int_pow(m),
                Op::Pow => x.real_pow(y),
                Op::Atan2 => x.atan2_with(y),
                Op::Call(f) => x.fun(f),
            };
        }
    }

    /// Runs the prelude in the scalar `S` (for `f64`, as [`Tape::run_prelude`]).
    pub fn run_prelude_in<S: TapeScalar>(&self, w: &mut [S]) {
        Self::exec(&self.prelude, w);
    }

    /// The body compiled to native code ([`tumble_jit`]), reading the inputs `args[i]` from
    /// its argument array and writing its first `results` outputs to its result array: run on
    /// a workspace prepared as for [`Tape::run`] (the other inputs set, prelude run), with
    /// arguments `x`, it writes `out[i]` as [`Tape::output`] `i` after setting input
    /// `args[k]` to `x[k]` and running [`Tape::run`], bit for bit, and leaves the other
    /// outputs in the workspace. Square roots and absolute values are single instructions,
    /// integer powers the multiplications of `f64::powi`, and the other functions calls of
    /// the same Rust functions the interpreter calls ([`Fun::apply`]), so nothing is computed
    /// differently.
    ///
    /// # Errors
    /// [`JitError`] where the machine has no code generator (the interpreter then serves).
    pub fn compile(&self, args: &[u32], results: usize) -> Result<Native, JitError> {
        let code: Vec<tumble_jit::Instr> = self
            .body
            .iter()
            .map(|ins| tumble_jit::Instr {
                op: native_op(ins.op),
                dst: ins.dst,
                a: ins.a,
                b: ins.b,
            })
            .collect();
        let results = results.min(self.outputs.len());
        Native::compile(&Program {
            slots: self.slots,
            code: &code,
            args,
            results: &self.outputs[..results],
            outputs: &self.outputs[results..],
        })
    }

    /// Runs the prelude: after the fixed inputs are set in `w` (`w[k]` for input `k`).
    pub fn run_prelude(&self, w: &mut [f64]) {
        Self::exec(&self.prelude, w);
    }

    /// Runs the body: after the varying inputs are set in `w`.
    pub fn run(&self, w: &mut [f64]) {
        Self::exec(&self.body, w);
    }

    /// Sets every input from `inputs` and runs prelude and body.
    pub fn run_all(&self, w: &mut [f64], inputs: &[f64]) {
        let n = self.inputs.min(inputs.len());
        w[..n].copy_from_slice(&inputs[..n]);
        self.run_prelude(w);
        self.run(w);
    }

    /// Every output at `inputs` (`inputs[k]` for input `k`, missing ones zero) in any real
    /// scalar: `f64`, or the dual numbers of `num-dual`, whose derivatives then come by
    /// automatic differentiation through the same instructions. Allocates its workspace on
    /// each call: for checks and generic callers, not for a step (use [`Tape::run`]).
    #[must_use]
    pub fn eval<D: nalgebra::RealField + Copy + From<f64>>(&self, inputs: &[D]) -> Vec<D> {
        let zero = D::from(0.0);
        let mut w = vec![zero; self.slots];
        let n = self.inputs.min(inputs.len());
        w[..n].copy_from_slice(&inputs[..n]);
        for ins in self.prelude.iter().chain(&self.body) {
            let x = w[ins.a as usize];
            let y = w[ins.b as usize];
            w[ins.dst as usize] = match ins.op {
                Op::Const(c) => D::from(c),
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
                Op::Div => x / y,
                Op::Neg => -x,
                Op::Powi(m) => x.powi(m),
                Op::Pow => x.powf(y),
                Op::Atan2 => x.atan2(y),
                Op::Call(f) => f.apply_real(x),
            };
        }
        self.outputs.iter().map(|&o| w[o as usize]).collect()
    }

    /// Output `i` after a run.
    #[must_use]
    #[inline]
    pub fn output(&self, w: &[f64], i: usize) -> f64 {
        w[self.outputs[i] as usize]
    }

    /// Number of outputs.
    #[must_use]
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }
}

/// The compiled form of an operation: the same arithmetic, or a call of the function the
/// interpreter applies.
fn native_op(op: Op) -> tumble_jit::Op {
    use tumble_jit::Op as N;
    match op {
        Op::Const(c) => N::Const(c),
        Op::Add => N::Add,
        Op::Sub => N::Sub,
        Op::Mul => N::Mul,
        Op::Div => N::Div,
        Op::Neg => N::Neg,
        Op::Powi(m) => N::Powi(m),
        Op::Pow => N::Call2(pow as Fn2),
        Op::Atan2 => N::Call2(atan2 as Fn2),
        Op::Call(Fun::Sqrt) => N::Sqrt,
        Op::Call(Fun::Abs) => N::Abs,
        Op::Call(f) => N::Call1(match f {
            Fun::Sin => sin as Fn1,
            Fun::Cos => cos,
            Fun::Tan => tan,
            Fun::Asin => asin,
            Fun::Acos => acos,
            Fun::Atan => atan,
            Fun::Sinh => sinh,
            Fun::Cosh => cosh,
            Fun::Tanh => tanh,
            Fun::Exp => exp,
            Fun::Log => log,
            Fun::Sign => sign,
            Fun::Sqrt => sqrt,
            Fun::Abs => abs,
        }),
    }
}

/// The functions compiled code calls: each is [`Fun::apply`] of its function, with the C ABI.
macro_rules! c_functions {
    ($($name:ident => $fun:ident),* $(,)?) => {
        $(
            extern "C" fn $name(x: f64) -> f64 {
                Fun::$fun.apply(x)
            }
        )*
    };
}

c_functions!(
    sin => Sin, cos => Cos, tan => Tan, asin => Asin, acos => Acos, atan => Atan,
    sinh => Sinh, cosh => Cosh, tanh => Tanh, exp => Exp, log => Log, sign => Sign,
    sqrt => Sqrt, abs => Abs,
);

extern "C" fn pow(x: f64, y: f64) -> f64 {
    x.powf(y)
}

extern "C" fn atan2(a: f64, b: f64) -> f64 {
    a.atan2(b)
}
