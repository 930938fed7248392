//! The Lie-group Runge–Kutta methods on the product `SO(3)ᴹ × ℝᴺ` act factor by factor: on two
//! uncoupled bodies (a heavy top and a free asymmetric body) side by side, `product_rkmk4` and
//! `product_cg3` give, bit for bit, what `rkmk4` and `cg3` give on each body alone, and each
//! rotation stays on SO(3) to round-off.

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::rigid::{
    EulerEquations, GroupState, LieVectorField, ProductState, ProductVectorField, cg3, product_cg3,
    product_rkmk4, rkmk4,
};
use tumble_integrators::{NoObserver, Stepper};
use tumble_kinematics::so3::{exp, orthogonality_defect};

use crate::rigid_support::*;

/// Two bodies' Euler equations side by side on `SO(3)² × ℝ⁶` (`y = (m₁, m₂)`).
struct SideBySide<A, B>(A, B);

impl<A: LieVectorField<3>, B: LieVectorField<3>> ProductVectorField<2, 6> for SideBySide<A, B> {
    fn eval(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; 2],
        y: &SVector<f64, 6>,
    ) -> ([Vector3<f64>; 2], SVector<f64, 6>) {
        let (xi1, f1) = self
            .0
            .eval(t, &rotations[0], &y.fixed_rows::<3>(0).into_owned());
        let (xi2, f2) = self
            .1
            .eval(t, &rotations[1], &y.fixed_rows::<3>(3).into_owned());
        let mut f = SVector::<f64, 6>::zeros();
        f.fixed_rows_mut::<3>(0).copy_from(&f1);
        f.fixed_rows_mut::<3>(3).copy_from(&f2);
        ([xi1, xi2], f)
    }
}

#[test]
fn product_methods_step_each_factor_as_the_single_body_methods_do() {
    let (top, free) = (asymmetric_top(), asymmetric_body());
    let (f1, f2) = (EulerEquations(&top), EulerEquations(&free));
    let field = SideBySide(f1, f2);
    let s1 = GroupState::<3>::from(initial_state());
    let s2 = GroupState {
        rotation: *exp(&Vector3::new(-0.5, 0.8, 0.2)).matrix(),
        vector: Vector3::new(-0.4, 1.2, 0.6),
    };
    let (h, steps, t_end) = (0.01, 5000u32, 50.0);
    for name in ["rkmk4", "cg3"] {
        let start = ProductState {
            rotations: [s1.rotation, s2.rotation],
            vector: SVector::<f64, 6>::from_fn(|i, _| {
                if i < 3 {
                    s1.vector[i]
                } else {
                    s2.vector[i - 3]
                }
            }),
        };
        let product;
        let (a, b) = if name == "rkmk4" {
            product = run(
                &mut product_rkmk4::<2, 6>(),
                &field,
                start,
                t_end,
                h,
                &mut NoObserver,
            )
            .unwrap();
            (
                run(&mut rkmk4::<3>(), &f1, s1, t_end, h, &mut NoObserver).unwrap(),
                run(&mut rkmk4::<3>(), &f2, s2, t_end, h, &mut NoObserver).unwrap(),
            )
        } else {
            product = run(
                &mut product_cg3::<2, 6>(),
                &field,
                start,
                t_end,
                h,
                &mut NoObserver,
            )
            .unwrap();
            (
                run(&mut cg3::<3>(), &f1, s1, t_end, h, &mut NoObserver).unwrap(),
                run(&mut cg3::<3>(), &f2, s2, t_end, h, &mut NoObserver).unwrap(),
            )
        };
        assert_eq!(product.rotations[0], a.rotation, "{name}");
        assert_eq!(product.rotations[1], b.rotation, "{name}");
        assert_eq!(product.vector.fixed_rows::<3>(0), a.vector, "{name}");
        assert_eq!(product.vector.fixed_rows::<3>(3), b.vector, "{name}");
        let defect = product.orthogonality_defect();
        let bound = 10.0 * f64::EPSILON * f64::from(steps).sqrt();
        eprintln!("{name}: {steps} steps on SO(3)² × R⁶, max ‖RᵀR − 𝟙‖ = {defect:.2e}");
        assert!(defect < bound, "{name}: {defect:e}");
        assert!(defect == orthogonality_defect(&a.rotation).max(orthogonality_defect(&b.rotation)));
    }
    // A stepper restarted at the same state repeats its step (its carries are reset).
    let mut stepper = product_rkmk4::<2, 6>();
    let start = ProductState {
        rotations: [s1.rotation, s2.rotation],
        vector: SVector::<f64, 6>::repeat(0.3),
    };
    let (mut x, mut y) = (start, start);
    stepper.step(&field, 0.0, &mut x, h).unwrap();
    stepper.step(&field, 0.0, &mut y, h).unwrap();
    assert_eq!(x, y);
}
