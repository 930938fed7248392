//! Stage sums with the coefficients of the built-in tables as compile-time constants.
//!
//! The generic stepper reads its table at run time: every stage sum loads its coefficients,
//! tests them for zero and loops over a run-time number of terms. For the built-in tables the
//! same sums are written out here term by term (`seq!` unrolls the stage and term indices), so
//! the coefficients are constants, zero terms vanish at compile time and each stage argument
//! is one pass over the components with its terms in registers.
//!
//! Every sum is the one the generic path takes, with the same terms in the same order
//! (`acc = w₀ x₀ + Σ_j w_j x_j`, zero weights left out, then `base + acc`), so both paths give
//! identical results bit for bit (tested in [`super`]).

use std::cell::RefCell;

use seq_macro::seq;

use super::{ExplicitRungeKutta, LANES};
use crate::problem::Ode;
use crate::state::VectorState;
use crate::tables::explicit::{DOP853, DP5, RK4};
use crate::tables::rk_pairs::{TSIT5, VERN6, VERN7, VERN8, VERN9};
use crate::tables::{ErrorEstimator, ExplicitTableau};

thread_local! {
    /// Kernels already chosen on this thread, by the address of their table.
    static CHOSEN: RefCell<Vec<(usize, Kernel)>> = const { RefCell::new(Vec::new()) };
}

/// Addresses [`CHOSEN`] remembers per thread (a program with more tables compares the rest).
const REMEMBERED: usize = 64;

impl Kernel {
    /// The unrolled kernel whose table equals `table` exactly, else [`Kernel::Generic`].
    ///
    /// A `&'static` table never changes and its memory is never reused, so the choice is
    /// remembered by address: comparing a table with the built-in ones takes longer than a
    /// short run of a cheap problem.
    pub(super) fn of<const S: usize>(table: &'static ExplicitTableau<S>) -> Self {
        let address = std::ptr::from_ref(table) as usize;
        let known = CHOSEN.with_borrow(|c| c.iter().find(|e| e.0 == address).map(|e| e.1));
        if let Some(kernel) = known {
            return kernel;
        }
        let kernel = builtin(table);
        CHOSEN.with_borrow_mut(|c| {
            if c.len() < REMEMBERED {
                c.push((address, kernel));
            }
        });
        kernel
    }
}

/// `x` and `y` are the same table: the same address, or every field that the stage and error
/// sums read equal (with the name and orders).
fn same_table<const A: usize, const B: usize>(
    x: &ExplicitTableau<A>,
    y: &ExplicitTableau<B>,
) -> bool {
    if A != B {
        return false;
    }
    if std::ptr::eq(x.a.as_ptr().cast::<f64>(), y.a.as_ptr().cast::<f64>()) {
        return true;
    }
    x.name == y.name
        && x.order == y.order
        && x.stages == y.stages
        && x.fsal == y.fsal
        && x.c[..] == y.c[..]
        && x.b[..] == y.b[..]
        && x.a.iter().zip(&y.a).all(|(p, q)| p[..] == q[..])
        && match (&x.error, &y.error) {
            (ErrorEstimator::None, ErrorEstimator::None) => true,
            (
                ErrorEstimator::Embedded { weights: w, .. },
                ErrorEstimator::Embedded { weights: v, .. },
            ) => w[..] == v[..],
            (
                ErrorEstimator::Dop853 { e5: a5, e3: a3, .. },
                ErrorEstimator::Dop853 { e5: b5, e3: b3, .. },
            ) => a5[..] == b5[..] && a3[..] == b3[..],
            _ => false,
        }
}

/// The workspace a kernel writes: stages `k`, differences `dk[j] = k[j] − k[0]`, the stage
/// argument `ytmp`, the increment `delta` and the error sums `e5`, `e3`.
pub(super) struct Work<'a, Y> {
    pub k: &'a mut [Y],
    pub dk: &'a mut [Y],
    pub ytmp: &'a mut Y,
    pub delta: &'a mut Y,
}

/// Weights of the embedded estimate (or DOP853's fifth-order difference); zeros without one.
const fn first_error_weights<const S: usize>(t: &ExplicitTableau<S>) -> [f64; S] {
    match t.error {
        ErrorEstimator::None => [0.0; S],
        ErrorEstimator::Embedded { weights, .. } => weights,
        ErrorEstimator::Dop853 { e5, .. } => e5,
    }
}

/// DOP853's third-order difference weights; zeros for other estimators.
const fn second_error_weights<const S: usize>(t: &ExplicitTableau<S>) -> [f64; S] {
    match t.error {
        ErrorEstimator::Dop853 { e3, .. } => e3,
        _ => [0.0; S],
    }
}

/// Components `m … m + W − 1` of stage `I`'s argument,
/// `out = ys + ((h c_I) k₀ + Σ_{J<I} (h a_IJ) dk_J)`, accumulated in a `[f64; W]` (which the
/// compiler keeps in vector registers).
macro_rules! stage_block {
    ($t:ident, $w:tt, $i:tt, $m:ident, $h:ident, $k0:ident, $dk:ident, $ys:ident, $out:ident) => {{
        let mut acc = [0.0_f64; $w];
        for l in 0..$w {
            acc[l] = ($h * $t.c[$i]) * $k0[$m + l];
        }
        seq!(J in 1..$i {
            if $t.a[$i][J] != 0.0 {
                let c = $h * $t.a[$i][J];
                let x = &$dk[J].as_slice()[$m..$m + $w];
                for l in 0..$w {
                    acc[l] += c * x[l];
                }
            }
        });
        for l in 0..$w {
            $out[$m + l] = $ys[$m + l] + acc[l];
        }
    }};
}

/// Components `m … m + W − 1` of `delta = h k₀ + Σ_J (h b_J) dk_J`.
macro_rules! delta_block {
    ($t:ident, $w:tt, $stages:tt, $m:ident, $h:ident, $k0:ident, $dk:ident, $out:ident) => {{
        let mut acc = [0.0_f64; $w];
        for l in 0..$w {
            acc[l] = $h * $k0[$m + l];
        }
        seq!(J in 1..$stages {
            if $t.b[J] != 0.0 {
                let c = $h * $t.b[J];
                let x = &$dk[J].as_slice()[$m..$m + $w];
                for l in 0..$w {
                    acc[l] += c * x[l];
                }
            }
        });
        $out[$m..$m + $w].copy_from_slice(&acc);
    }};
}

/// Components `m … m + W − 1` of the error sums `Σ_J W5_J k_J` and `Σ_J W3_J k_J`.
macro_rules! error_block {
    ($w5:ident, $w3:ident, $w:tt, $s:tt, $m:ident, $k:ident, $o5:ident, $o3:ident) => {{
        let mut a5 = [0.0_f64; $w];
        let mut a3 = [0.0_f64; $w];
        seq!(J in 0..$s {
            if $w5[J] != 0.0 {
                let x = &$k[J].as_slice()[$m..$m + $w];
                for l in 0..$w {
                    a5[l] += $w5[J] * x[l];
                }
            }
            if $w3[J] != 0.0 {
                let x = &$k[J].as_slice()[$m..$m + $w];
                for l in 0..$w {
                    a3[l] += $w3[J] * x[l];
                }
            }
        });
        $o5[$m..$m + $w].copy_from_slice(&a5);
        $o3[$m..$m + $w].copy_from_slice(&a3);
    }};
}

macro_rules! kernel {
    ($stages_fn:ident, $error_fn:ident, $tab:path, $s:tt, $stages:tt) => {
        /// Stages `1 … stages − 1` (stage 0 in `k[0]`) and `delta = h Σ bᵢ kᵢ`; `false`
        /// (nothing done) when the workspace is not shaped for this table.
        pub(crate) fn $stages_fn<Y: VectorState, P: Ode<Y> + ?Sized>(
            problem: &P,
            t: f64,
            y: &Y,
            h: f64,
            w: Work<'_, Y>,
        ) -> bool {
            const T: ExplicitTableau<$s> = $tab;
            let Ok(k) = <&mut [Y; $s]>::try_from(w.k) else {
                return false;
            };
            let Ok(dk) = <&mut [Y; $s]>::try_from(w.dk) else {
                return false;
            };
            let n = y.dim();
            let ys = &y.as_slice()[..n];
            seq!(I in 1..$stages {
                {
                    let k0 = &k[0].as_slice()[..n];
                    let out = &mut w.ytmp.as_mut_slice()[..n];
                    let mut m = 0;
                    while m + LANES <= n {
                        stage_block!(T, LANES, I, m, h, k0, dk, ys, out);
                        m += LANES;
                    }
                    while m < n {
                        stage_block!(T, 1, I, m, h, k0, dk, ys, out);
                        m += 1;
                    }
                }
                problem.rhs(t + T.c[I] * h, w.ytmp, &mut k[I]);
                {
                    let (k0, ki) = (&k[0].as_slice()[..n], &k[I].as_slice()[..n]);
                    let d = &mut dk[I].as_mut_slice()[..n];
                    for m in 0..n {
                        d[m] = ki[m] - k0[m];
                    }
                }
            });
            let k0 = &k[0].as_slice()[..n];
            let out = &mut w.delta.as_mut_slice()[..n];
            let mut m = 0;
            while m + LANES <= n {
                delta_block!(T, LANES, $stages, m, h, k0, dk, out);
                m += LANES;
            }
            while m < n {
                delta_block!(T, 1, $stages, m, h, k0, dk, out);
                m += 1;
            }
            true
        }

        /// The error estimator's stage sums `Σ eᵢ kᵢ` into `e5` (and DOP853's `Σ e3ᵢ kᵢ`
        /// into `e3`); `false` when the workspace is not shaped for this table.
        pub(crate) fn $error_fn<Y: VectorState>(k: &[Y], e5: &mut Y, e3: &mut Y) -> bool {
            const T: ExplicitTableau<$s> = $tab;
            const W5: [f64; $s] = first_error_weights(&T);
            const W3: [f64; $s] = second_error_weights(&T);
            let Ok(k) = <&[Y; $s]>::try_from(k) else {
                return false;
            };
            let n = e5.dim();
            let o5 = &mut e5.as_mut_slice()[..n];
            let o3 = &mut e3.as_mut_slice()[..n];
            let mut m = 0;
            while m + LANES <= n {
                error_block!(W5, W3, LANES, $s, m, k, o5, o3);
                m += LANES;
            }
            while m < n {
                error_block!(W5, W3, 1, $s, m, k, o5, o3);
                m += 1;
            }
            true
        }
    };
}

/// The built-in tables with unrolled kernels: for each, its variant of [`Kernel`], its
/// constructor, its `const` table, the table's size `S` and its stages per attempt. Generates
/// [`Kernel`], the kernels, `builtin` (the variant of the first table a test accepts) and the
/// dispatchers [`stages`] and [`error_sums`].
macro_rules! builtin_kernels {
    ($($variant:ident: $ctor:ident, $tab:path, $s:tt, $stages:tt;)*) => {
        /// Which stage sums a stepper uses: the generic loops, or one of the unrolled kernels.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub(super) enum Kernel {
            Generic,
            $($variant,)*
        }

        /// Stage and error kernels, one module per table.
        #[allow(non_snake_case)]
        mod unrolled {
            use super::*;
            $(
                pub(super) mod $variant {
                    use super::*;
                    kernel!(stages, error, $tab, $s, $stages);
                }
            )*
        }

        /// The variant of the built-in table equal to `table` (the constructors' tables
        /// first: the same reference, so the pointer test settles it); [`Kernel::Generic`]
        /// when none is.
        fn builtin<const S: usize>(table: &ExplicitTableau<S>) -> Kernel {
            $(
                if same_table(table, ExplicitRungeKutta::$ctor().table) {
                    return Kernel::$variant;
                }
            )*
            Kernel::Generic
        }

        /// Runs the unrolled stages of `kernel`; `false` for [`Kernel::Generic`] or a
        /// workspace not shaped for it (the caller then takes the generic path).
        #[inline]
        pub(super) fn stages<Y: VectorState, P: Ode<Y> + ?Sized>(
            kernel: Kernel,
            problem: &P,
            t: f64,
            y: &Y,
            h: f64,
            w: Work<'_, Y>,
        ) -> bool {
            match kernel {
                Kernel::Generic => false,
                $(Kernel::$variant => unrolled::$variant::stages(problem, t, y, h, w),)*
            }
        }

        /// The error sums of `kernel` (see `error` of each kernel); `false` as for [`stages`].
        #[inline]
        pub(super) fn error_sums<Y: VectorState>(
            kernel: Kernel,
            k: &[Y],
            e5: &mut Y,
            e3: &mut Y,
        ) -> bool {
            match kernel {
                Kernel::Generic => false,
                $(Kernel::$variant => unrolled::$variant::error(k, e5, e3),)*
            }
        }
    };
}

builtin_kernels! {
    Rk4: rk4, RK4, 5, 4;
    Dp5: dp5, DP5, 7, 7;
    Tsit5: tsit5, TSIT5, 7, 7;
    Dop853: dop853, DOP853, 16, 12;
    Vern6: vern6, VERN6, 12, 9;
    Vern7: vern7, VERN7, 16, 10;
    Vern8: vern8, VERN8, 21, 13;
    Vern9: vern9, VERN9, 26, 16;
}

#[cfg(test)]
mod tests {
    use nalgebra::{DVector, SVector};

    use super::Kernel;
    use crate::explicit::ExplicitRungeKutta;
    use crate::stepper::{AdaptiveStepper, DenseOutput, Stepper, Tolerances};
    use crate::{Driver, NoObserver, Ode, VectorState};

    /// Lotka–Volterra and Hairer's forced rigid body side by side (dimension 5, so the
    /// blocks of the generic path have a remainder).
    struct Mixed;

    impl<Y: VectorState> Ode<Y> for Mixed {
        fn rhs(&self, t: f64, y: &Y, dy: &mut Y) {
            let (y, dy) = (y.as_slice(), dy.as_mut_slice());
            dy[0] = y[0] * (1.0 - y[1]);
            dy[1] = y[1] * (y[0] - 1.0);
            dy[2] = (-2.0 + 0.5 / 0.75) * y[3] * y[4];
            dy[3] = (1.25 - 0.5 / 0.75) * y[2] * y[4];
            dy[4] = -0.5 * y[2] * y[3] + 0.25 * (3.0 * t).sin();
        }
    }

    /// Runs `method` adaptively to `t = 20` with the unrolled kernel and with the generic
    /// loops forced, then interpolates in the last step: every number must agree bit for bit.
    fn same_bits<const S: usize, Y: VectorState + PartialEq + std::fmt::Debug>(
        method: ExplicitRungeKutta<S>,
        y0: &Y,
        expect: Kernel,
    ) {
        let tol = Tolerances::new(1e-9, 1e-9).expect("tolerances");
        let run = |generic: bool| {
            let mut y = y0.clone();
            let mut st = method.stepper(&y);
            assert_eq!(st.kernel, expect, "{}", method.table.name);
            if generic {
                st.kernel = Kernel::Generic;
            }
            let report = Driver::new(0.0, 20.0)
                .expect("driver")
                .run_adaptive(&mut st, &Mixed, &mut y, &tol, &mut [], &mut NoObserver)
                .expect("run");
            // a fixed step and an attempt after the run exercise both entry points again
            let mut z = y.clone();
            st.step(&Mixed, 20.0, &mut z, 0.3).expect("step");
            let err = st.attempt(&Mixed, 20.3, &z, 0.2, &tol).expect("attempt");
            st.accept(&Mixed, 20.3, &mut z, 0.2);
            let mut mid = y.clone();
            st.interpolate(&Mixed, 20.37, &mut mid);
            (y, report.steps, report.rejected, z, err.to_bits(), mid)
        };
        let (fast, generic) = (run(false), run(true));
        assert!(fast.1 > 20, "{}: only {} steps", method.table.name, fast.1);
        assert_eq!(fast, generic, "{}", method.table.name);
    }

    #[test]
    fn unrolled_kernels_give_the_generic_stage_sums_bit_for_bit() {
        let y = SVector::<f64, 5>::from([1.2, 0.8, 1.0, 0.1, 0.9]);
        let d = DVector::from_column_slice(y.as_slice());
        macro_rules! both {
            ($m:expr, $k:expr) => {
                same_bits($m, &y, $k);
                same_bits($m, &d, $k);
            };
        }
        both!(ExplicitRungeKutta::dp5(), Kernel::Dp5);
        both!(ExplicitRungeKutta::tsit5(), Kernel::Tsit5);
        both!(ExplicitRungeKutta::dop853(), Kernel::Dop853);
        both!(ExplicitRungeKutta::vern6(), Kernel::Vern6);
        both!(ExplicitRungeKutta::vern7(), Kernel::Vern7);
        both!(ExplicitRungeKutta::vern8(), Kernel::Vern8);
        both!(ExplicitRungeKutta::vern9(), Kernel::Vern9);
    }

    #[test]
    fn rk4_kernel_gives_the_generic_fixed_steps_bit_for_bit() {
        let y0 = SVector::<f64, 5>::from([1.2, 0.8, 1.0, 0.1, 0.9]);
        let run = |generic: bool| {
            let mut y = y0;
            let mut st = ExplicitRungeKutta::rk4().stepper(&y);
            assert_eq!(st.kernel, Kernel::Rk4);
            if generic {
                st.kernel = Kernel::Generic;
            }
            for i in 0..400 {
                st.step(&Mixed, 0.05 * f64::from(i), &mut y, 0.05)
                    .expect("step");
            }
            y
        };
        assert_eq!(run(false), run(true));
    }

    #[test]
    fn a_table_that_differs_from_a_built_in_one_takes_the_generic_path() {
        let mut table = crate::tables::rk_pairs::VERN8;
        table.a[5][2] = f64::from_bits(table.a[5][2].to_bits() + 1);
        let leaked: &'static _ = Box::leak(Box::new(table));
        let method = ExplicitRungeKutta {
            table: leaked,
            controller: ExplicitRungeKutta::vern8().controller,
        };
        let st = method.stepper(&SVector::<f64, 5>::zeros());
        assert_eq!(st.kernel, Kernel::Generic);
    }
}
