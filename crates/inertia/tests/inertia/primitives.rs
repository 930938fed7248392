//! Every primitive's closed form against an independent construction — point masses at the
//! centres of cells whose masses are the cells' exact masses (midpoint rule), or a fine
//! inscribed mesh — with the observed convergence rate measured (nominal 2: the midpoint rule
//! and inscribed polygons are second order).

use std::f64::consts::{PI, TAU};

use nalgebra::{Point3, Vector3};
use tumble_inertia::{InertiaError, MassProperties, MassSpec, PointMass, shapes};

use crate::common::{assert_order, rel_err};

const MASS: f64 = 2.5;

/// Relative errors of point-mass constructions at resolutions `ns` against `exact`, after
/// checking that mass and centre of mass come out right (cell masses are exact).
fn errors_against(
    exact: &MassProperties,
    ns: &[usize],
    sample: impl Fn(usize) -> Vec<PointMass>,
) -> Vec<f64> {
    ns.iter()
        .map(|&n| {
            let body = MassProperties::from_point_masses(&sample(n)).unwrap();
            assert!((body.mass() - exact.mass()).abs() <= 1e-13 * exact.mass());
            assert!((body.center_of_mass() - exact.center_of_mass()).norm() <= 1e-13);
            rel_err(body.inertia(), exact.inertia())
        })
        .collect()
}

fn hs(ns: &[usize]) -> Vec<f64> {
    ns.iter().map(|&n| 1.0 / n as f64).collect()
}

/// Midpoints and widths of `n` equal cells of `[a, b]`.
fn cells(a: f64, b: f64, n: usize) -> impl Iterator<Item = (f64, f64, f64)> + Clone {
    let h = (b - a) / n as f64;
    (0..n).map(move |k| {
        let lo = a + h * k as f64;
        let hi = if k + 1 == n { b } else { lo + h };
        (lo, hi, 0.5 * (lo + hi))
    })
}

#[test]
fn thin_rod_matches_midpoint_point_masses_at_second_order() {
    let length = 1.7;
    let exact = MassProperties::thin_rod(MASS, length).unwrap();
    let ns = [4, 8, 16, 32, 64];
    let errors = errors_against(&exact, &ns, |n| {
        cells(-length / 2.0, length / 2.0, n)
            .map(|(_, _, z)| PointMass::new(MASS / n as f64, Point3::new(0.0, 0.0, z)))
            .collect()
    });
    assert_order("thin rod vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn thin_hoop_equals_three_or_more_equally_spaced_point_masses_exactly() {
    // Σ cos² φₖ = Σ sin² φₖ = n/2 and Σ cos φₖ sin φₖ = 0 for n ≥ 3 equally spaced angles, so the
    // sampling is exact from n = 3 on: the expected "rate" is exactness, to round-off.
    let radius = 0.8;
    let exact = MassProperties::thin_hoop(MASS, radius).unwrap();
    for n in 3..=40 {
        let points: Vec<PointMass> = (0..n)
            .map(|k| {
                let phi = TAU * (k as f64 + 0.3) / n as f64;
                PointMass::new(
                    MASS / n as f64,
                    Point3::new(radius * phi.cos(), radius * phi.sin(), 0.0),
                )
            })
            .collect();
        let body = MassProperties::from_point_masses(&points).unwrap();
        let err = rel_err(body.inertia(), exact.inertia());
        assert!(err <= 1e-14, "n = {n}: relative error {err:e}");
    }
    // Two points are not enough: they form a rod, with one moment zero.
    let two = [
        PointMass::new(MASS / 2.0, Point3::new(radius, 0.0, 0.0)),
        PointMass::new(MASS / 2.0, Point3::new(-radius, 0.0, 0.0)),
    ];
    let rod = MassProperties::from_point_masses(&two).unwrap();
    assert!(rel_err(rod.inertia(), exact.inertia()) > 0.1);
}

#[test]
fn thin_disk_matches_polar_cell_point_masses_at_second_order() {
    let radius = 0.9;
    let exact = MassProperties::thin_disk(MASS, radius).unwrap();
    let area = PI * radius * radius;
    let ns = [4, 8, 16, 32, 64];
    let errors = errors_against(&exact, &ns, |n| {
        let mut points = Vec::new();
        for (r0, r1, r) in cells(0.0, radius, n) {
            for (p0, p1, phi) in cells(0.0, TAU, 2 * n) {
                let cell_area = 0.5 * (r1 * r1 - r0 * r0) * (p1 - p0);
                points.push(PointMass::new(
                    MASS * cell_area / area,
                    Point3::new(r * phi.cos(), r * phi.sin(), 0.0),
                ));
            }
        }
        points
    });
    assert_order("thin disk vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn solid_cylinder_matches_cylindrical_cell_point_masses_at_second_order() {
    let (radius, height) = (0.6, 1.9);
    let exact = MassProperties::solid_cylinder(MASS, radius, height).unwrap();
    let volume = PI * radius * radius * height;
    let ns = [4, 8, 16, 32];
    let errors = errors_against(&exact, &ns, |n| {
        let mut points = Vec::new();
        for (r0, r1, r) in cells(0.0, radius, n) {
            for (p0, p1, phi) in cells(0.0, TAU, 3) {
                for (z0, z1, z) in cells(-height / 2.0, height / 2.0, n) {
                    let v = 0.5 * (r1 * r1 - r0 * r0) * (p1 - p0) * (z1 - z0);
                    points.push(PointMass::new(
                        MASS * v / volume,
                        Point3::new(r * phi.cos(), r * phi.sin(), z),
                    ));
                }
            }
        }
        points
    });
    assert_order("solid cylinder vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn solid_cylinder_matches_inscribed_prism_meshes_at_second_order() {
    let (radius, height) = (0.6, 1.9);
    let exact = MassProperties::solid_cylinder(MASS, radius, height).unwrap();
    let ns = [8, 16, 32, 64, 128];
    let errors: Vec<f64> = ns
        .iter()
        .map(|&n| {
            let mesh = shapes::cylinder_mesh(radius, height, n).unwrap();
            let body = mesh.mass_properties(MassSpec::TotalMass(MASS)).unwrap();
            assert!(body.center_of_mass().coords.norm() <= 1e-15);
            rel_err(body.inertia(), exact.inertia())
        })
        .collect();
    assert_order("solid cylinder vs prism meshes", &hs(&ns), &errors, 2.0);
}

#[test]
fn solid_sphere_matches_spherical_cell_point_masses_at_second_order() {
    let radius = 0.75;
    let exact = MassProperties::solid_sphere(MASS, radius).unwrap();
    let volume = 4.0 / 3.0 * PI * radius.powi(3);
    let ns = [4, 8, 16, 32];
    let errors = errors_against(&exact, &ns, |n| {
        let mut points = Vec::new();
        for (r0, r1, r) in cells(0.0, radius, n) {
            for (t0, t1, theta) in cells(0.0, PI, n) {
                for (p0, p1, phi) in cells(0.0, TAU, 4) {
                    let v = (r1.powi(3) - r0.powi(3)) / 3.0 * (t0.cos() - t1.cos()) * (p1 - p0);
                    points.push(PointMass::new(
                        MASS * v / volume,
                        Point3::new(
                            r * theta.sin() * phi.cos(),
                            r * theta.sin() * phi.sin(),
                            r * theta.cos(),
                        ),
                    ));
                }
            }
        }
        points
    });
    assert_order("solid sphere vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn hollow_sphere_matches_surface_cell_point_masses_at_second_order() {
    let radius = 1.3;
    let exact = MassProperties::hollow_sphere(MASS, radius).unwrap();
    let ns = [4, 8, 16, 32, 64];
    let errors = errors_against(&exact, &ns, |n| {
        let mut points = Vec::new();
        for (t0, t1, theta) in cells(0.0, PI, n) {
            for (p0, p1, phi) in cells(0.0, TAU, 4) {
                // Area fraction of the cell: (cos t0 − cos t1) Δφ / 4π.
                let fraction = (t0.cos() - t1.cos()) * (p1 - p0) / (4.0 * PI);
                points.push(PointMass::new(
                    MASS * fraction,
                    Point3::new(
                        radius * theta.sin() * phi.cos(),
                        radius * theta.sin() * phi.sin(),
                        radius * theta.cos(),
                    ),
                ));
            }
        }
        points
    });
    assert_order("hollow sphere vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn solid_box_matches_grid_point_masses_at_second_order() {
    let sides = Vector3::new(0.4, 1.1, 2.3);
    let exact = MassProperties::solid_box(MASS, &sides).unwrap();
    let ns = [4, 8, 16, 32];
    let errors = errors_against(&exact, &ns, |n| {
        let m = MASS / (n * n * n) as f64;
        let mut points = Vec::new();
        for (_, _, x) in cells(-sides.x / 2.0, sides.x / 2.0, n) {
            for (_, _, y) in cells(-sides.y / 2.0, sides.y / 2.0, n) {
                for (_, _, z) in cells(-sides.z / 2.0, sides.z / 2.0, n) {
                    points.push(PointMass::new(m, Point3::new(x, y, z)));
                }
            }
        }
        points
    });
    assert_order("solid box vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn solid_torus_matches_tube_cell_point_masses_at_second_order() {
    let (big, small) = (1.0, 0.35);
    let exact = MassProperties::solid_torus(MASS, big, small).unwrap();
    let volume = 2.0 * PI * PI * big * small * small;
    let ns = [4, 8, 16, 32];
    let errors = errors_against(&exact, &ns, |n| {
        let mut points = Vec::new();
        // Tube coordinates: x = (R + ρ cos α) cos φ, y = (R + ρ cos α) sin φ, z = ρ sin α,
        // dV = ρ (R + ρ cos α) dρ dα dφ, integrated exactly over each cell.
        for (r0, r1, rho) in cells(0.0, small, n) {
            for (a0, a1, alpha) in cells(0.0, TAU, n) {
                for (p0, p1, phi) in cells(0.0, TAU, 4) {
                    let v = (p1 - p0)
                        * (big * 0.5 * (r1 * r1 - r0 * r0) * (a1 - a0)
                            + (r1.powi(3) - r0.powi(3)) / 3.0 * (a1.sin() - a0.sin()));
                    let s = big + rho * alpha.cos();
                    points.push(PointMass::new(
                        MASS * v / volume,
                        Point3::new(s * phi.cos(), s * phi.sin(), rho * alpha.sin()),
                    ));
                }
            }
        }
        points
    });
    assert_order("solid torus vs point masses", &hs(&ns), &errors, 2.0);
}

#[test]
fn primitives_are_diagonal_with_the_symmetry_axis_along_z() {
    let hoop = MassProperties::thin_hoop(2.0, 0.5).unwrap();
    assert_eq!(hoop.inertia().diagonal(), Vector3::new(0.25, 0.25, 0.5));
    let rod = MassProperties::thin_rod(3.0, 2.0).unwrap();
    assert_eq!(rod.inertia().diagonal(), Vector3::new(1.0, 1.0, 0.0));
    assert!(!rod.is_positive_definite());
    let cylinder = MassProperties::solid_cylinder(12.0, 1.0, 2.0).unwrap();
    assert_eq!(cylinder.inertia().diagonal(), Vector3::new(7.0, 7.0, 6.0));
    let torus = MassProperties::solid_torus(8.0, 1.0, 0.5).unwrap();
    assert_eq!(torus.inertia().diagonal(), Vector3::new(5.25, 5.25, 9.5));
    for body in [&hoop, &cylinder, &torus] {
        assert!(body.is_positive_definite());
        assert_eq!(body.center_of_mass(), Point3::origin());
    }
}

#[test]
fn primitives_reject_invalid_dimensions_and_masses() {
    assert!(matches!(
        MassProperties::thin_hoop(1.0, 0.0),
        Err(InertiaError::InvalidDimension { name: "radius", .. })
    ));
    assert!(matches!(
        MassProperties::solid_cylinder(1.0, 1.0, f64::NAN),
        Err(InertiaError::InvalidDimension { name: "height", .. })
    ));
    assert!(matches!(
        MassProperties::solid_box(1.0, &Vector3::new(1.0, -1.0, 1.0)),
        Err(InertiaError::InvalidDimension {
            name: "box side y",
            ..
        })
    ));
    assert!(matches!(
        MassProperties::solid_sphere(-1.0, 1.0),
        Err(InertiaError::NonPositiveMass { .. })
    ));
    assert!(matches!(
        MassProperties::hollow_sphere(f64::INFINITY, 1.0),
        Err(InertiaError::NonFiniteMass { .. })
    ));
    assert!(matches!(
        MassProperties::solid_torus(1.0, 1.0, 1.5),
        Err(InertiaError::SelfIntersectingTorus { .. })
    ));
    assert!(matches!(
        MassProperties::thin_rod(1.0, f64::INFINITY),
        Err(InertiaError::InvalidDimension { name: "length", .. })
    ));
}
