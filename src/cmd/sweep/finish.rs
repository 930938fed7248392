//! The end of a sweep or a merge: `results.csv` (or Parquet), the map and slices,
//! `manifest.json`, the self-check and the summary.

use super::*;

/// Writes `results.csv`, the plots and `manifest.json`, prints the summary, and turns failed
/// points into [`PointsFailed`].
pub(super) fn finish(
    def: &SweepDefinition,
    dir: &Path,
    report: &SweepReport,
    shard: Shard,
    (command, format): (&str, Format),
    check: CheckSettings,
    figure_options: &plot::FigureOptions,
) -> Result<()> {
    if !report.complete() {
        bail!(
            "{}: the sweep stopped with {} of {} points finished; run it again with --resume",
            dir.display(),
            report.rows.len(),
            report.total
        );
    }
    let results = dir.join("results.csv");
    output::write_whole(&results, &sweep::results_csv(def, &report.rows)?)?;
    let plots = if shard == Shard::ALL {
        plot::sweep::draw_plots(def, dir, &report.rows, figure_options)?
    } else {
        Vec::new()
    };
    let tolerance = check.tolerance(def);
    // The self-check of a whole sweep: chosen points again at a tighter setting.
    let self_check = if shard == Shard::ALL {
        quiet_point_panics(|| sweep::check_sweep(def, &report.rows, check.size, check.threads))?
    } else {
        None
    };
    let text = manifest::to_text(&SweepRecord::new(
        crate::provenance::now(report.threads),
        def,
        report,
        shard,
        command,
        &plots,
        self_check.as_ref().map(|c| (c, tolerance)),
    ))?;
    if format == Format::Parquet {
        let metadata = vec![(crate::cmd::simulate::METADATA_KEY.to_string(), text.clone())];
        let table = sweep::results_table(def, &report.rows, metadata);
        output::write_whole(&dir.join(RESULTS_PARQUET), &table.to_parquet()?)?;
    }
    output::write_whole(&dir.join("manifest.json"), text.as_bytes())?;

    let failed = report.failures().count();
    let info = def.scene.info();
    eprintln!(
        "sweep        {} ({}), {} points{}",
        info.name,
        def.origin,
        def.points(),
        if shard == Shard::ALL {
            String::new()
        } else {
            format!(", shard {shard}: {} of them", report.total)
        }
    );
    if let (Some(r), Some(levels)) = (
        &def.refine,
        sweep::refine::points_by_level(def, &report.rows),
    ) {
        let per_level: Vec<String> = levels.iter().map(u64::to_string).collect();
        eprintln!(
            "refined      {} levels where {} changes by more than {:?}: {} points, {:.1} % of the \
             grid (by level: {})",
            r.levels,
            r.metric,
            r.threshold,
            report.rows.len(),
            100.0 * report.rows.len() as f64 / def.points() as f64,
            per_level.join(", ")
        );
    }
    eprintln!(
        "integrator   {}, {}, t in [0, {}] s",
        def.plan.integrator(),
        plot::sweep::step_words(def.plan.step),
        def.plan.t_end
    );
    match def.reduction() {
        Some(r) => eprintln!("model        {}: {}", r.name, r.summary),
        None => eprintln!("model        full ({})", def.scene.info().name),
    }
    if command == "merge" {
        let t = report.compute.totals();
        eprintln!("merged       {} points", report.rows.len());
        eprintln!(
            "compute      {} points computed in {} runs on {} host{}, {} wall in total, {:.1} \
             thread-s",
            t.computed,
            t.runs,
            t.hosts.len(),
            if t.hosts.len() == 1 { "" } else { "s" },
            seconds(t.wall_time),
            t.thread_seconds
        );
    } else {
        let rate = report
            .points_per_second()
            .map_or_else(String::new, |r| format!(", {r:.1} points/s"));
        eprintln!(
            "work         {} points computed, {} resumed, {} threads, {}{rate}",
            report.computed,
            report.resumed,
            report.threads,
            seconds(report.elapsed)
        );
    }
    eprintln!(
        "status       {} ok, {failed} failed",
        report.rows.len() - failed
    );
    let converged = match &self_check {
        Some(c) => {
            let ok = c.converged(tolerance);
            let at = c
                .physical_largest()
                .and_then(|m| Some((m.metric.name(), m.index?)))
                .map_or_else(String::new, |(name, i)| {
                    let values: Vec<String> = def
                        .axes
                        .iter()
                        .zip(def.point(i))
                        .map(|(a, v)| format!("{} = {v}", a.parameter))
                        .collect();
                    format!(" ({name} at point {i}: {})", values.join(", "))
                });
            let chosen = c.screen.map_or_else(
                || "an even spread, the corners".to_string(),
                |s| {
                    format!(
                        "the most sensitive at {}, an even spread, the corners",
                        plot::sweep::step_words(s)
                    )
                },
            );
            eprintln!(
                "self-check   largest change {:.1e}{at} over {} check points ({chosen}) at {}: {}",
                c.largest(),
                c.points.len(),
                plot::sweep::step_words(c.setting),
                if ok {
                    format!("within the tolerance {tolerance:.1e}")
                } else {
                    format!("more than the tolerance {tolerance:.1e}")
                }
            );
            for m in &c.changes {
                if m.metric != Metric::MaxEnergyRelErr
                    && (m.max_change > tolerance || m.undefined_in_one > 0)
                {
                    eprintln!(
                        "warning      {}: changed by {:.2e}{}{}",
                        m.metric,
                        m.max_change,
                        m.index
                            .map_or_else(String::new, |i| format!(" at point {i}")),
                        if m.undefined_in_one > 0 {
                            format!(", defined in one run only at {} points", m.undefined_in_one)
                        } else {
                            String::new()
                        }
                    );
                }
            }
            if !c.status_changed.is_empty() {
                eprintln!(
                    "warning      {} check points failed at one setting only: {:?}",
                    c.status_changed.len(),
                    c.status_changed
                );
            }
            ok.then_some(()).ok_or(c.largest())
        }
        None => {
            if shard == Shard::ALL {
                eprintln!("self-check   off");
            }
            Ok(())
        }
    };
    eprintln!("output       {}", dir.display());
    for p in &plots {
        eprintln!("plot         {}", dir.join(p).display());
    }
    if failed > 0 {
        return Err(PointsFailed {
            failed,
            total: report.total,
            results,
        }
        .into());
    }
    if let Err(largest) = converged {
        return Err(NotConverged { largest, tolerance }.into());
    }
    Ok(())
}
