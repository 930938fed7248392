//! Compiled programs against the interpreter, their reference semantics.

use proptest::prelude::*;
use tumble_jit::{Fn1, Fn2, Instr, JitError, Native, Op, Program};

extern "C" fn sin(x: f64) -> f64 {
    x.sin()
}
extern "C" fn exp(x: f64) -> f64 {
    x.exp()
}
extern "C" fn atan2(y: f64, x: f64) -> f64 {
    y.atan2(x)
}
extern "C" fn powf(x: f64, y: f64) -> f64 {
    x.powf(y)
}

const CALL1: [Fn1; 2] = [sin, exp];
const CALL2: [Fn2; 2] = [atan2, powf];

/// Equal bits, or both NaN (NaN payloads are not part of the contract).
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Runs `program` both ways from the same workspace and arguments `x` and compares every
/// result and every output.
fn agree(program: &Program<'_>, w0: &[f64], x: &[f64]) -> Result<(), String> {
    let native = Native::compile(program).map_err(|e| e.to_string())?;
    let (mut wi, mut wn) = (w0.to_vec(), w0.to_vec());
    let r = program.results.len();
    let (mut oi, mut on) = (vec![-7.0; r], vec![-7.0; r]);
    program.run(&mut wi, x, &mut oi);
    native.run(&mut wn, x, &mut on);
    for (k, (&i, &n)) in oi.iter().zip(&on).enumerate() {
        if !same(i, n) {
            return Err(format!("result {k}: interpreter {i:e}, native {n:e}"));
        }
    }
    for &o in program.outputs {
        let (i, n) = (wi[o as usize], wn[o as usize]);
        if !same(i, n) {
            return Err(format!("slot {o}: interpreter {i:e}, native {n:e}"));
        }
    }
    Ok(())
}

fn op(kind: u8, c: f64, n: i32) -> Op {
    match kind % 11 {
        0 => Op::Const(c),
        1 => Op::Add,
        2 => Op::Sub,
        3 => Op::Mul,
        4 => Op::Div,
        5 => Op::Neg,
        6 => Op::Abs,
        7 => Op::Sqrt,
        8 => Op::Powi(n),
        9 => Op::Call1(CALL1[(n & 1) as usize]),
        _ => Op::Call2(CALL2[(n & 1) as usize]),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random straight-line programs (every operation, slots written in any order, inputs and
    /// arguments read several times, slots overwritten, arguments anywhere, results and
    /// outputs anywhere) give the interpreter's bits.
    #[test]
    fn compiled_programs_give_the_interpreters_bits(
        inputs in prop::collection::vec(-3.0f64..3.0, 1..6),
        extra in 1usize..30,
        code in prop::collection::vec((any::<u8>(), -2.0f64..2.0, -9i32..9, any::<u32>(), any::<u32>(), any::<u32>()), 1..120),
        outs in prop::collection::vec(any::<u32>(), 1..8),
        x in prop::collection::vec((-3.0f64..3.0, any::<u32>()), 0..8),
        res in prop::collection::vec(any::<u32>(), 0..8),
    ) {
        let slots = inputs.len() + extra;
        let s = |k: u32| k % slots as u32;
        let code: Vec<Instr> = code
            .iter()
            .map(|&(kind, c, n, d, a, b)| Instr { op: op(kind, c, n), dst: s(d), a: s(a), b: s(b) })
            .collect();
        let outputs: Vec<u32> = outs.iter().map(|&o| s(o)).collect();
        let results: Vec<u32> = res.iter().map(|&o| s(o)).collect();
        let args: Vec<u32> = x.iter().map(|&(_, a)| s(a)).collect();
        let x: Vec<f64> = x.iter().map(|&(v, _)| v).collect();
        let mut w0 = vec![0.5; slots];
        w0[..inputs.len()].copy_from_slice(&inputs);
        let program = Program { slots, code: &code, args: &args, results: &results, outputs: &outputs };
        prop_assert_eq!(agree(&program, &w0, &x), Ok(()));
    }

    /// `x^n` is Rust's `f64::powi`, bit for bit, for exponents across the `i32` range and
    /// bases from tiny to huge (overflow to ∞ and underflow to 0 included).
    #[test]
    fn powi_is_rusts_powi_bit_for_bit(x in prop::num::f64::ANY, n in any::<i32>(), small in -70i32..70) {
        for n in [n, small] {
            let code = [Instr { op: Op::Powi(n), dst: 1, a: 0, b: 0 }];
            let program = Program { slots: 2, code: &code, args: &[], results: &[], outputs: &[1] };
            let native = Native::compile(&program).unwrap();
            let mut w = [x, 0.0];
            native.run(&mut w, &[], &mut []);
            prop_assert!(same(w[1], x.powi(n)), "{x:e}^{n}: {:e} vs {:e}", w[1], x.powi(n));
        }
    }
}

/// The special values of every operation: ±0, ±∞, NaN, subnormals, through each instruction.
#[test]
fn special_values_go_through_every_operation_as_interpreted() {
    let specials = [
        0.0,
        -0.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        f64::MIN_POSITIVE / 4.0,
        -1.0,
        1e308,
    ];
    for kind in 0..11u8 {
        for n in [-3, 0, 1, 2, 7] {
            for &x in &specials {
                for &y in &specials {
                    let code = [Instr {
                        op: op(kind, 0.25, n),
                        dst: 2,
                        a: 0,
                        b: 1,
                    }];
                    let program = Program {
                        slots: 3,
                        code: &code,
                        args: &[0],
                        results: &[2],
                        outputs: &[],
                    };
                    assert_eq!(
                        agree(&program, &[0.5, y, 0.0], &[x]),
                        Ok(()),
                        "{kind} {n} {x} {y}"
                    );
                }
            }
        }
    }
}

/// A slot beyond the workspace is refused before any code is generated: compiled code can
/// only touch the workspace it is given.
#[test]
fn a_slot_beyond_the_workspace_is_refused_before_any_code_exists() {
    let add = |dst, a, b| Instr {
        op: Op::Add,
        dst,
        a,
        b,
    };
    for (code, args, results, outputs, bad) in [
        (vec![add(3, 0, 1)], vec![], vec![], vec![2], (0, 3)),
        (vec![add(2, 0, 7)], vec![], vec![], vec![2], (0, 7)),
        (
            vec![add(2, 0, 1), add(2, 9, 1)],
            vec![],
            vec![],
            vec![2],
            (1, 9),
        ),
        (vec![add(2, 0, 1)], vec![], vec![], vec![5], (1, 5)),
        (vec![add(2, 0, 1)], vec![0, 4], vec![2], vec![], (1, 4)),
        (vec![add(2, 0, 1)], vec![0], vec![2, 3], vec![], (1, 3)),
    ] {
        let program = Program {
            slots: 3,
            code: &code,
            args: &args,
            results: &results,
            outputs: &outputs,
        };
        assert_eq!(
            Native::compile(&program).unwrap_err(),
            JitError::SlotOutOfRange {
                instr: bad.0,
                slot: bad.1,
                slots: 3
            }
        );
    }
    // The unread operand of a one-argument operation is not a slot.
    let neg = [Instr {
        op: Op::Neg,
        dst: 1,
        a: 0,
        b: u32::MAX,
    }];
    let program = Program {
        slots: 2,
        code: &neg,
        args: &[],
        results: &[],
        outputs: &[1],
    };
    assert!(Native::compile(&program).is_ok());
}

/// Outputs the program never writes keep the workspace's values (an input passed through, a
/// value left in the workspace), and slots the program only reads are not changed.
#[test]
fn slots_the_program_does_not_write_keep_their_values() {
    let code = [Instr {
        op: Op::Mul,
        dst: 2,
        a: 0,
        b: 1,
    }];
    let program = Program {
        slots: 4,
        code: &code,
        args: &[],
        results: &[],
        outputs: &[2, 0, 3],
    };
    let native = Native::compile(&program).unwrap();
    let mut w = [3.0, 4.0, 0.0, 9.5];
    native.run(&mut w, &[], &mut []);
    assert_eq!(w, [3.0, 4.0, 12.0, 9.5]);
}

/// Arguments come from the argument array and results go to the result array, results that
/// are arguments or inputs passed through; an argument named as an output is left in the
/// workspace as the interpreter leaves it, and the result array's other entries and the
/// workspace's other slots are not touched.
#[test]
fn arguments_and_results_go_through_their_arrays() {
    let code = [Instr {
        op: Op::Sub,
        dst: 3,
        a: 1,
        b: 0,
    }];
    let program = Program {
        slots: 5,
        code: &code,
        args: &[1, 2],
        results: &[3, 2, 0],
        outputs: &[2],
    };
    let native = Native::compile(&program).unwrap();
    let mut w = [1.5, -1.0, -1.0, -1.0, 7.0];
    let mut out = [0.0; 4];
    native.run(&mut w, &[10.0, 20.0, 30.0], &mut out);
    assert_eq!(out, [8.5, 20.0, 1.5, 0.0]);
    assert_eq!(w, [1.5, -1.0, 20.0, -1.0, 7.0]);
    let (mut wi, mut oi) = ([1.5, -1.0, -1.0, -1.0, 7.0], [0.0; 4]);
    program.run(&mut wi, &[10.0, 20.0, 30.0], &mut oi);
    assert_eq!(oi, out);
    assert_eq!(wi[2], w[2]);
}

/// One compiled function serves several threads at once, each with its own workspace.
#[test]
fn one_compiled_function_serves_several_threads_at_once() {
    let code = [
        Instr {
            op: Op::Call1(sin),
            dst: 1,
            a: 0,
            b: 0,
        },
        Instr {
            op: Op::Powi(3),
            dst: 2,
            a: 1,
            b: 0,
        },
    ];
    let program = Program {
        slots: 3,
        code: &code,
        args: &[0],
        results: &[2],
        outputs: &[],
    };
    let native = Native::compile(&program).unwrap();
    std::thread::scope(|s| {
        for t in 0..4 {
            s.spawn(move || {
                for k in 0..10_000 {
                    let x = f64::from(t * 10_000 + k) * 1e-3;
                    let mut w = [0.0; 3];
                    let mut out = [0.0];
                    native.run(&mut w, &[x, 5.0], &mut out);
                    assert_eq!(out[0].to_bits(), x.sin().powi(3).to_bits());
                }
            });
        }
    });
}
