//! A check of a hand-written [`TaylorSystem`] against its right-hand side and its flow (for the
//! scenes' tests).

use nalgebra::SVector;
use tumble_integrators::TaylorSystem;

/// Checks `system`'s coefficients at `x0` against the right-hand side `f`: `x₁ = F(x₀)`,
/// `x₂ = ½ dF/dt` along the flow (a central difference), and the order-24 polynomial at
/// `h = 0.05` against 2000 RK4 steps over that step (every coefficient counts there).
pub(crate) fn check<const N: usize>(
    system: &dyn TaylorSystem,
    f: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
    x0: SVector<f64, N>,
) {
    let order = 24;
    let mut c = vec![0.0; (order + 1) * N];
    system
        .coefficients(0.0, x0.as_slice(), order, &mut c)
        .unwrap();
    let f0 = f(&x0);
    let h = 1e-5;
    let (fp, fm) = (f(&(x0 + f0 * h)), f(&(x0 - f0 * h)));
    for i in 0..N {
        assert!(
            (c[N + i] - f0[i]).abs() <= 1e-14 * (1.0 + f0[i].abs()),
            "x1[{i}]"
        );
        let x2 = (fp[i] - fm[i]) / (2.0 * h) / 2.0;
        assert!(
            (c[2 * N + i] - x2).abs() <= 1e-8 * (1.0 + x2.abs()),
            "x2[{i}]"
        );
    }
    let (h, steps) = (0.05, 2000);
    let dt = h / f64::from(steps);
    let mut y = x0;
    for _ in 0..steps {
        let k1 = f(&y);
        let k2 = f(&(y + k1 * (dt / 2.0)));
        let k3 = f(&(y + k2 * (dt / 2.0)));
        let k4 = f(&(y + k3 * dt));
        y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0);
    }
    for i in 0..N {
        let sum = (0..=order).rev().fold(0.0, |s, k| s * h + c[k * N + i]);
        assert!(
            (sum - y[i]).abs() <= 1e-13 * (1.0 + y[i].abs()),
            "x({h})[{i}]: {sum} vs {}",
            y[i]
        );
    }
}
