//! Merging the folders of a sharded sweep into the folder an unsharded run writes.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

use super::compute::ComputeRecord;
use super::definition::SweepDefinition;
use super::engine::{SweepReport, first_difference, open_folder};
use super::journal::{self, DEFINITION, JOURNAL, PointRow};
use super::refine::{self, Lattice};
use super::{Shard, SweepError};

/// A shard a merge found unfinished.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnfinishedShard {
    /// The shard.
    pub shard: Shard,
    /// The folder that holds it (`None`: none of the folders given does).
    pub dir: Option<PathBuf>,
    /// Its points in that folder's journal.
    pub finished: u64,
    /// Its points.
    pub points: u64,
}

/// The shards of a sweep a merge found unfinished, and how to finish them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unfinished {
    /// Unfinished shards (missing ones included), by shard number.
    pub shards: Vec<UnfinishedShard>,
    /// Shards in all.
    pub count: u64,
    /// A `sweep.toml` of the sweep, to run the shards from.
    pub definition: PathBuf,
    /// Folders given that hold no sweep yet (a shard that never started).
    pub empty: Vec<PathBuf>,
}

impl fmt::Display for Unfinished {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let list: Vec<String> = self.shards.iter().map(|u| u.shard.to_string()).collect();
        writeln!(
            f,
            "{} of {} shards not finished: {}",
            self.shards.len(),
            self.count,
            list.join(", ")
        )?;
        for u in &self.shards {
            match &u.dir {
                Some(dir) => writeln!(
                    f,
                    "  shard {}: {} of {} points in {}; finish it with `tumble sweep {} \
                     --shard {} --resume -o {}`",
                    u.shard,
                    u.finished,
                    u.points,
                    dir.display(),
                    self.definition.display(),
                    u.shard,
                    dir.display()
                )?,
                None => writeln!(
                    f,
                    "  shard {}: no folder given holds it; run it with `tumble sweep {} \
                     --shard {} --resume -o FOLDER`",
                    u.shard,
                    self.definition.display(),
                    u.shard
                )?,
            }
        }
        for dir in &self.empty {
            writeln!(f, "  {}: holds no sweep yet", dir.display())?;
        }
        write!(f, "then merge again")
    }
}

/// Reads a folder's `sweep.toml`; `None` when the folder holds no sweep yet.
fn read_definition(dir: &Path) -> Result<Option<String>, SweepError> {
    let path = dir.join(DEFINITION);
    match std::fs::read_to_string(&path) {
        Ok(text) if dir.join(JOURNAL).exists() => Ok(Some(text)),
        Ok(_) => Ok(None),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(source) => Err(SweepError::Io {
            path,
            what: "cannot read the sweep's definition",
            source,
        }),
    }
}

/// Joins the folders of the `N` shards of one sweep into `out` as an unsharded run would
/// have written it (`sweep.toml`, a complete journal, the compute records of every shard);
/// returns the definition and every row in index order.
///
/// A folder given that does not exist or holds no sweep yet counts as a shard that has not
/// started.
///
/// # Errors
/// [`SweepError::Unfinished`] listing every shard that is missing or incomplete (with the
/// command to finish each); [`SweepError::Merge`] when the folders hold different sweeps or
/// a shard twice; errors reading them; `out` already holding a sweep.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<(SweepDefinition, SweepReport), SweepError> {
    let start = Instant::now();
    if dirs.is_empty() {
        return Err(SweepError::Merge("no folders to merge".into()));
    }
    let mut texts = Vec::with_capacity(dirs.len());
    for dir in dirs {
        texts.push(read_definition(dir)?);
    }
    let Some((first, text)) = dirs
        .iter()
        .zip(&texts)
        .find_map(|(d, t)| t.as_ref().map(|t| (d, t.clone())))
    else {
        return Err(SweepError::Merge(format!(
            "none of the {} folders holds a sweep (sweep.toml and journal.csv)",
            dirs.len()
        )));
    };
    let def = SweepDefinition::parse(&text, &first.join(DEFINITION).display().to_string(), &[])?;
    if def.to_toml() != text {
        return Err(SweepError::DifferentSweep {
            dir: first.clone(),
            reason: "its sweep.toml is not the resolved form tumble writes (edited by hand?)"
                .into(),
        });
    }
    let mut rows: BTreeMap<u64, PointRow> = BTreeMap::new();
    let mut seen: BTreeMap<u64, (PathBuf, u64)> = BTreeMap::new();
    let mut count = None;
    let mut empty = Vec::new();
    let mut compute = ComputeRecord::default();
    for (dir, other) in dirs.iter().zip(&texts) {
        let Some(other) = other else {
            empty.push(dir.clone());
            continue;
        };
        if *other != text {
            return Err(SweepError::Merge(format!(
                "{} and {} hold different sweeps: {}",
                first.display(),
                dir.display(),
                first_difference(&text, other)
            )));
        }
        let contents = journal::read(&dir.join(JOURNAL), &def, &text)?;
        let shard = contents.shard;
        let n = *count.get_or_insert(shard.count);
        if shard.count != n {
            return Err(SweepError::Merge(format!(
                "{} is shard {shard}, but {} is one of {n} shards",
                dir.display(),
                first.display()
            )));
        }
        if let Some((previous, _)) = seen.get(&shard.index) {
            return Err(SweepError::Merge(format!(
                "{} and {} are both shard {shard}",
                previous.display(),
                dir.display()
            )));
        }
        seen.insert(shard.index, (dir.clone(), contents.rows.len() as u64));
        compute.runs.extend(ComputeRecord::read(dir)?.runs);
        for (index, row) in contents.rows {
            // Shards of a refined sweep share the points on the faces between their cells.
            if let Some(other) = rows.get(&index)
                && *other != row
            {
                return Err(SweepError::Merge(format!(
                    "point {index} has different results in {} and another shard's folder",
                    dir.display()
                )));
            }
            rows.insert(index, row);
        }
    }
    let count = count.unwrap_or(1);
    let lattice = Lattice::of(&def);
    // Shards beyond the points (a refined sweep: beyond its coarse cells) have none: nothing
    // to merge from them, present or not.
    let parts = lattice.as_ref().map_or(def.points(), Lattice::coarse_cells);
    let mut needed = BTreeSet::new();
    let unfinished: Vec<UnfinishedShard> = (1..=count.min(parts))
        .filter_map(|k| {
            let shard = Shard::new(k, count).ok()?;
            // A refined shard's points follow from its results: walk its refinement over the
            // rows at hand; it is finished when no level lacks a point.
            let (points, done) = match &lattice {
                Some(lattice) => {
                    let walked =
                        refine::walk::<()>(lattice, shard, &mut rows, &mut |_, _, _| Ok(()))
                            .ok()?;
                    let n = walked.needed.len() as u64;
                    needed.extend(walked.needed);
                    (n, walked.complete)
                }
                None => {
                    let points = shard.size(def.points());
                    (points, seen.get(&k).is_some_and(|(_, f)| *f == points))
                }
            };
            match seen.get(&k) {
                Some(_) if done => None,
                Some((dir, finished)) => Some(UnfinishedShard {
                    shard,
                    dir: Some(dir.clone()),
                    finished: *finished,
                    points,
                }),
                None => Some(UnfinishedShard {
                    shard,
                    dir: None,
                    finished: 0,
                    points,
                }),
            }
        })
        .collect();
    if !unfinished.is_empty() || !empty.is_empty() {
        return Err(SweepError::Unfinished(Unfinished {
            shards: unfinished,
            count,
            definition: first.join(DEFINITION),
            empty,
        }));
    }
    // Write the merged folder: definition, then a complete journal in index order, and the
    // compute records of every shard.
    let (mut writer, _) = open_folder(&def, out, Shard::ALL, false)?;
    if lattice.is_some() {
        rows.retain(|i, _| needed.contains(i));
    }
    let rows: Vec<PointRow> = rows.into_values().collect();
    for row in &rows {
        writer.push(&def, row)?;
    }
    writer.flush()?;
    compute.write(out)?;
    let total = rows.len() as u64;
    let totals = compute.totals();
    Ok((
        def,
        SweepReport {
            rows,
            total,
            computed: totals.computed,
            resumed: total,
            elapsed: start.elapsed(),
            threads: totals.max_threads,
            compute,
        },
    ))
}
