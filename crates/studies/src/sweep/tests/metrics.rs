//! Metrics on real scenes, against the trajectory they summarise.

use super::*;

#[test]
fn hoop_metrics_agree_with_the_trajectory() {
    let def = small();
    let row = run_point(&def, 5);
    assert_eq!(row.status, Status::Ok, "{}", row.reason);
    // The same run, every row kept.
    let scene = find("free-hoop").unwrap();
    let mut params = def.params.clone();
    params.set("omega0", 5.0).unwrap();
    params.set("alpha0", 2.0).unwrap();
    let mut rows = Rows::default();
    let summary = scene.simulate(&params, &def.plan, &mut rows).unwrap();
    let tilt = scene
        .info()
        .columns()
        .iter()
        .position(|c| c == "tilt")
        .unwrap();
    let samples: Vec<f64> = rows.0.iter().map(|r| r[tilt]).collect();
    let sampled_max = samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let [max, last, crossing, energy] = row.metrics[..] else {
        panic!("{:?}", row.metrics)
    };
    let max = max.unwrap();
    // The interpolated maximum is at least the largest sample, and close to it.
    assert!(
        max >= sampled_max && max - sampled_max < 1e-4,
        "{max} {sampled_max}"
    );
    assert_eq!(last, Some(*samples.last().unwrap()));
    // The sweep runs the Euler–Poisson reduction (its metrics read only the tilt, the bead and
    // the energy), whose energy is summed from other numbers than the full model's: the two
    // largest relative errors agree to round-off, not bit for bit.
    assert!(def.reduction().is_some());
    let energy = energy.unwrap();
    assert!(
        energy < 1e-14 && (energy - summary.max_energy_rel_err).abs() < 1e-15,
        "{energy:e} {:e}",
        summary.max_energy_rel_err
    );
    // The crossing lies between the samples that cross the threshold.
    let t = crossing.unwrap();
    let k = samples.iter().position(|&s| s > 0.01).unwrap();
    assert!(rows.0[k - 1][0] <= t && t <= rows.0[k][0], "{t}");
}

#[test]
fn flips_of_the_t_handle_are_counted() {
    let def = parse(
        "scene = \"dzhanibekov\"\n[run]\nintegrator = \"split8\"\ndt = 0.001\nt_end = 10.0\n\
         [[axes]]\nparameter = \"spin\"\nvalues = [20.0]\n\
         [metrics]\nrecord = [\"flips\", \"max_energy_rel_err\"]\n",
    )
    .unwrap();
    let row = run_point(&def, 0);
    assert_eq!(row.status, Status::Ok, "{}", row.reason);
    // The scene's test sees at least 4 flips in 10 s at the default spin of 20 rad/s.
    let flips = row.metrics[0].unwrap();
    assert!(flips >= 4.0 && flips.fract() == 0.0, "{flips}");
    // A symmetric body has no intermediate axis: that point fails, with the reason.
    let def = parse(
        "scene = \"free-body\"\n[parameters]\nI1 = 1.0\nI2 = 2.0\n[run]\nt_end = 1.0\n\
         [[axes]]\nparameter = \"I3\"\nvalues = [3.0, 2.0]\n\
         [metrics]\nrecord = [\"flips\"]\n",
    )
    .unwrap();
    assert_eq!(run_point(&def, 0).status, Status::Ok);
    let symmetric = run_point(&def, 1);
    assert_eq!(symmetric.status, Status::Failed);
    assert!(
        symmetric.reason.contains("intermediate axis"),
        "{}",
        symmetric.reason
    );
    assert_eq!(symmetric.metrics, vec![None]);
}
