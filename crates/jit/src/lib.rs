//! Straight-line `f64` programs compiled to native code.
//!
//! A [`Program`] is what tumble's model files become after symbolic differentiation: a flat
//! list of instructions `slot[dst] = op(slot[a], slot[b])` over a workspace of `f64` slots,
//! with no branches and no loops (the instruction tape of `tumble-model`), reading its
//! arguments from one array and writing its results to another. [`Program::run`] interprets
//! it; [`Native::compile`] turns it into one machine-code function with
//! [Cranelift](https://cranelift.dev) (the code generator of Wasmtime), so that a model's
//! right-hand side runs without an interpreter's dispatch, loads and stores between
//! instructions, or copies of its state in and out of the workspace.
//!
//! **Same numbers.** The compiled function performs the same IEEE-754 operations, in the same
//! order, on the same operands as the interpreter: `+ − × ÷`, negation, `|x|` and `√x` are
//! single correctly rounded instructions in both; Cranelift neither reassociates nor fuses
//! floating-point operations; `x^n` for an integer `n` is expanded into the multiplications of
//! binary exponentiation in the order of Rust's `f64::powi` (compiler-builtins' `__powidf2`);
//! every other function is a call of the same Rust function the interpreter calls
//! ([`Fn1`], [`Fn2`]). So every output is bit for bit the interpreter's (tested on random
//! programs, and on tumble's shipped models by their trajectories).
//!
//! **Where unsafe code is.** Compiled code is reached through a function pointer made from the
//! address Cranelift returns; that cast is the crate's one `unsafe` operation, confined to the
//! private module `native` with its safety argument. Everything else is safe code.

mod native;

use std::fmt;

pub use native::Native;

/// A function of one argument the compiled code may call (`sin`, `exp`, …): a plain Rust
/// function with the C calling convention, e.g. `extern "C" fn sin(x: f64) -> f64 { x.sin() }`.
pub type Fn1 = extern "C" fn(f64) -> f64;

/// A function of two arguments the compiled code may call (`atan2`, `x^y`, …).
pub type Fn2 = extern "C" fn(f64, f64) -> f64;

/// One operation: what an [`Instr`] computes from its operand slots `a` and `b`.
#[derive(Clone, Copy)]
pub enum Op {
    /// The constant.
    Const(f64),
    /// `a + b`.
    Add,
    /// `a − b`.
    Sub,
    /// `a · b`.
    Mul,
    /// `a / b`.
    Div,
    /// `−a`.
    Neg,
    /// `|a|`.
    Abs,
    /// `√a` (correctly rounded).
    Sqrt,
    /// `a^n` as Rust's `f64::powi` computes it.
    Powi(i32),
    /// `f(a)`.
    Call1(Fn1),
    /// `f(a, b)`.
    Call2(Fn2),
}

impl fmt::Debug for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Op::Const(c) => write!(f, "Const({c:e})"),
            Op::Add => f.write_str("Add"),
            Op::Sub => f.write_str("Sub"),
            Op::Mul => f.write_str("Mul"),
            Op::Div => f.write_str("Div"),
            Op::Neg => f.write_str("Neg"),
            Op::Abs => f.write_str("Abs"),
            Op::Sqrt => f.write_str("Sqrt"),
            Op::Powi(n) => write!(f, "Powi({n})"),
            Op::Call1(g) => write!(f, "Call1({:p})", *g as *const ()),
            Op::Call2(g) => write!(f, "Call2({:p})", *g as *const ()),
        }
    }
}

impl Op {
    /// How many operand slots the operation reads (0, 1 or 2).
    #[must_use]
    pub fn arity(self) -> usize {
        match self {
            Op::Const(_) => 0,
            Op::Neg | Op::Abs | Op::Sqrt | Op::Powi(_) | Op::Call1(_) => 1,
            Op::Add | Op::Sub | Op::Mul | Op::Div | Op::Call2(_) => 2,
        }
    }
}

/// An instruction: `slot[dst] = op(slot[a], slot[b])` (operands the operation does not read
/// are ignored).
#[derive(Debug, Clone, Copy)]
pub struct Instr {
    /// The operation.
    pub op: Op,
    /// The slot written.
    pub dst: u32,
    /// The first operand's slot.
    pub a: u32,
    /// The second operand's slot.
    pub b: u32,
}

/// A straight-line program over a workspace of `slots` values, run on an argument array `x`
/// and a result array `out`: slot `args[i]` is set to `x[i]`, the instructions run in order,
/// then `out[i]` is set to slot `results[i]`, and the `outputs` slots of the workspace hold
/// their values. Slots that no instruction writes before reading them and that are no
/// argument are inputs read from the workspace (values set once, as a run's parameters).
#[derive(Debug, Clone, Copy)]
pub struct Program<'a> {
    /// Size of the workspace.
    pub slots: usize,
    /// The instructions, in order.
    pub code: &'a [Instr],
    /// The slot each argument is written to, before the instructions run.
    pub args: &'a [u32],
    /// The slots copied to the result array, in order, after the instructions run.
    pub results: &'a [u32],
    /// The slots whose values the workspace holds after a run.
    pub outputs: &'a [u32],
}

/// Why a program was not compiled.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum JitError {
    /// A slot index at or beyond the workspace.
    #[error("instruction {instr} names slot {slot}, beyond the workspace of {slots} slots")]
    SlotOutOfRange {
        /// The instruction (its position in the code; the number of instructions for an
        /// argument, a result or an output).
        instr: usize,
        /// The slot named.
        slot: u32,
        /// The workspace size.
        slots: usize,
    },
    /// The workspace (or the argument or result array) is too large to address with 32-bit
    /// offsets.
    #[error("a workspace, argument or result array of {0} values is too large to compile")]
    TooLarge(usize),
    /// The machine this runs on is not one Cranelift generates code for.
    #[error("no native code generator for this machine: {0}")]
    Host(String),
    /// Cranelift refused the function.
    #[error("code generation failed: {0}")]
    Codegen(String),
}

impl Program<'_> {
    /// Checks every slot index against the workspace: the condition under which the compiled
    /// code touches only the workspace and the arrays it is given.
    ///
    /// # Errors
    /// [`JitError::SlotOutOfRange`] for the first index beyond the workspace,
    /// [`JitError::TooLarge`] for a workspace or an array beyond 32-bit byte offsets.
    pub fn validate(&self) -> Result<(), JitError> {
        for len in [self.slots, self.args.len(), self.results.len()] {
            if len > (i32::MAX as usize) / 8 {
                return Err(JitError::TooLarge(len));
            }
        }
        let check = |instr: usize, slot: u32| {
            if (slot as usize) < self.slots {
                Ok(())
            } else {
                Err(JitError::SlotOutOfRange {
                    instr,
                    slot,
                    slots: self.slots,
                })
            }
        };
        for (i, ins) in self.code.iter().enumerate() {
            check(i, ins.dst)?;
            let arity = ins.op.arity();
            if arity > 0 {
                check(i, ins.a)?;
            }
            if arity > 1 {
                check(i, ins.b)?;
            }
        }
        for &o in self.args.iter().chain(self.results).chain(self.outputs) {
            check(self.code.len(), o)?;
        }
        Ok(())
    }

    /// Runs the program by interpretation on the workspace `w`, the arguments `x` and the
    /// results `out`: the reference semantics of [`Native`].
    ///
    /// # Panics
    /// If a slot index is beyond `w` (a program that passes [`Program::validate`] and a
    /// workspace of at least `slots` values never does), or `x` or `out` is shorter than
    /// `args` or `results`.
    pub fn run(&self, w: &mut [f64], x: &[f64], out: &mut [f64]) {
        for (&s, &v) in self.args.iter().zip(&x[..self.args.len()]) {
            w[s as usize] = v;
        }
        for ins in self.code {
            let x = w[ins.a as usize];
            let y = w[ins.b as usize];
            w[ins.dst as usize] = match ins.op {
                Op::Const(c) => c,
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
                Op::Div => x / y,
                Op::Neg => -x,
                Op::Abs => x.abs(),
                Op::Sqrt => x.sqrt(),
                Op::Powi(n) => x.powi(n),
                Op::Call1(f) => f(x),
                Op::Call2(f) => f(x, y),
            };
        }
        for (o, &s) in out[..self.results.len()].iter_mut().zip(self.results) {
            *o = w[s as usize];
        }
    }
}
