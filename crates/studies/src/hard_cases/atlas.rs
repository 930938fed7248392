//! The atlas: every method on every hard case, at a setting chosen by one stated rule,
//! recording what happened.
//!
//! # The rule
//!
//! Each method runs a case at the step (for adaptive methods: the tolerance) that gives it an
//! error of [`TARGET`] = 1e-6 at the horizon of the case's *easy twin*, against the twin's
//! reference: starting from the scene's default step (tolerance 1e-8), the step is scaled by
//! `(1e-6/e)^(1/p)` (`p` the method's order; the tolerance by `1e-6/e`), at most 16-fold at a
//! time, for up to six runs (stopping at a run cut by the time limit: a smaller step would only
//! take longer), and the largest step (tolerance) whose error was at most 3e-6 is kept. The exact flow runs at the scene's default step. A method that cannot reach 3e-6 on
//! the easy twin is recorded as failed, with the best error it reached. So every method enters
//! a case equally accurate on its easy twin, and the atlas shows what the case, not the
//! method's order, does to it. A setting given with the method (`rk4:dt=0.05`) replaces the
//! rule.
//!
//! # What is recorded
//!
//! Per case and method ([`Entry`]): the setting and the error it gave on the easy twin; the
//! outcome — `ok` (the case's property is met), `violated` (the run finished but the property
//! is not met: which bound, by how much), `failed` (a typed error: non-convergence, a
//! non-finite state, calibration failure — with the message), `time-limit` (a run reached its
//! wall-clock limit); the final-state error against the case's reference, the largest relative
//! energy error and its growth exponent in time (`max error ∝ tᵃ` over the last two decades of
//! logarithmic time bins), the largest drift of the conserved columns, the steps and the wall
//! time of the case's run.

use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::Case;
use crate::work_precision::{
    self, EnergyHistory, FinalState, LastRow, refine_step, state_error, state_len,
};
use tumble_integrators::Flow;
use tumble_integrators::registry::{self, MethodInfo};
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{Observe, Recorder, RunPlan, RunSummary, StepControl};

/// The error every method is set to reach on a case's easy twin.
pub const TARGET: f64 = 1e-6;

/// The journal of an atlas folder.
pub const JOURNAL: &str = "atlas-journal.csv";

/// A method of the atlas and, optionally, a setting that replaces the rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Method {
    /// The integrator's registry entry.
    pub info: &'static MethodInfo,
    /// A given step or tolerance (`None`: chosen by the rule).
    pub setting: Option<StepControl>,
}

impl Method {
    /// Parses `NAME`, `NAME:dt=H` or `NAME:tol=T` (`NAME` may itself hold a colon, as a
    /// composition `TABLE:BASE` does: the setting is the part after the last colon when it
    /// holds `=`).
    ///
    /// # Errors
    /// An unknown integrator or a malformed setting.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, setting) = match spec.rsplit_once(':').filter(|(_, s)| s.contains('=')) {
            None => (spec.trim(), None),
            Some((name, setting)) => {
                let (key, value) = setting
                    .split_once('=')
                    .ok_or_else(|| format!("`{spec}`: expected NAME, NAME:dt=H or NAME:tol=T"))?;
                let x: f64 = value
                    .trim()
                    .parse()
                    .map_err(|_| format!("`{spec}`: `{}` is not a number", value.trim()))?;
                if !(x.is_finite() && x > 0.0) {
                    return Err(format!("`{spec}`: the setting must be finite and positive"));
                }
                let control = match key.trim() {
                    "dt" => StepControl::Fixed(x),
                    "tol" => StepControl::Tolerance(x),
                    other => return Err(format!("`{spec}`: `{other}` is neither dt nor tol")),
                };
                (name.trim(), Some(control))
            }
        };
        let info = registry::find(name).map_err(|e| e.to_string())?;
        match setting {
            Some(StepControl::Fixed(_)) if info.properties.adaptive => {
                return Err(format!(
                    "`{spec}`: `{}` is adaptive: give it a tolerance, {}:tol=T",
                    info.name, info.name
                ));
            }
            Some(StepControl::Tolerance(_)) if !info.properties.adaptive => {
                return Err(format!(
                    "`{spec}`: `{}` has a fixed step: give it a step, {}:dt=H",
                    info.name, info.name
                ));
            }
            Some(StepControl::Tolerance(t)) if t >= 1.0 => {
                return Err(format!(
                    "`{spec}`: the tolerance must lie strictly between 0 and 1"
                ));
            }
            _ => {}
        }
        Ok(Method { info, setting })
    }

    /// As given on the command line.
    #[must_use]
    pub fn spec(&self) -> String {
        match self.setting {
            None => self.info.name.to_string(),
            Some(StepControl::Fixed(h)) => format!("{}:dt={h}", self.info.name),
            Some(StepControl::Tolerance(t)) => format!("{}:tol={t}", self.info.name),
        }
    }
}

/// How an entry ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// The case's property is met.
    Ok,
    /// The run finished; the property is not met.
    Violated,
    /// A typed error (or the rule found no setting).
    Failed,
    /// A run reached its wall-clock limit.
    TimeLimit,
}

impl Status {
    /// As written in `atlas.csv`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Violated => "violated",
            Status::Failed => "failed",
            Status::TimeLimit => "time-limit",
        }
    }
}

/// One method on one case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    /// The case.
    pub case: String,
    /// A fingerprint of the case's definition: a resumed atlas reuses an entry only for the
    /// same case.
    pub case_key: String,
    /// The method as given (`rk4`, `rk4:dt=0.05`).
    pub method: String,
    /// `dt` of the case's run (fixed-step methods).
    pub dt: Option<f64>,
    /// `tol` of the case's run (adaptive methods).
    pub tol: Option<f64>,
    /// How the setting was chosen: `rule`, `given`, `exact`.
    pub chosen_by: String,
    /// The error of that setting on the easy twin.
    pub easy_error: Option<f64>,
    /// How the case's run ended.
    pub status: Status,
    /// Why it is not ok (empty when ok).
    pub reason: String,
    /// Final-state error against the reference.
    pub error: Option<f64>,
    /// Largest relative energy error.
    pub energy: Option<f64>,
    /// Growth exponent of the energy error in time.
    pub energy_growth: Option<f64>,
    /// Largest drift of the conserved columns.
    pub drift: Option<f64>,
    /// Steps of the case's run.
    pub steps: Option<u64>,
    /// Wall time of the case's run (s).
    pub seconds: Option<f64>,
}

impl Entry {
    /// The entry of `method` on `case` before anything ran (status `failed`, no reason yet).
    fn blank(case: &Case, method: &Method) -> Self {
        Entry {
            case: case.name.clone(),
            case_key: case.key(),
            method: method.spec(),
            dt: None,
            tol: None,
            chosen_by: String::new(),
            easy_error: None,
            status: Status::Failed,
            reason: String::new(),
            error: None,
            energy: None,
            energy_growth: None,
            drift: None,
            steps: None,
            seconds: None,
        }
    }

    /// The entry ended by `reason`: `time-limit` when a run reached its wall-clock limit
    /// ([`tumble_integrators::Error::TimeLimit`]), `failed` otherwise.
    fn failing(mut self, reason: String) -> Self {
        self.status = if reason.contains("time limit") {
            Status::TimeLimit
        } else {
            Status::Failed
        };
        self.reason = reason;
        self
    }
}

/// A case's references: the final state of the case and of its easy twin.
#[derive(Debug, Clone)]
pub struct References {
    /// The case's (`None` when the case has no reference).
    pub case: Option<FinalState>,
    /// The easy twin's.
    pub easy: FinalState,
    /// How they were computed.
    pub method: String,
}

/// Computes a case's references ([`work_precision::reference_within`]), each run limited to
/// `seconds`.
///
/// # Errors
/// The reference runs' error, as text.
pub fn references(case: &Case, seconds: f64) -> Result<References, String> {
    let easy =
        work_precision::reference_within(case.scene, &case.easy, case.easy_t_end, Some(seconds))
            .map_err(|e| format!("the easy twin's reference: {e}"))?;
    let hard = if case.reference {
        Some(
            work_precision::reference_within(case.scene, &case.params, case.t_end, Some(seconds))
                .map_err(|e| format!("the reference: {e}"))?,
        )
    } else {
        None
    };
    Ok(References {
        method: hard.as_ref().unwrap_or(&easy).method.clone(),
        case: hard.map(|r| r.state),
        easy: easy.state,
    })
}

/// The plan of `method` at `control` over `[0, t_end]`, limited to `seconds`.
fn plan(
    case: &Case,
    method: &MethodInfo,
    control: StepControl,
    t_end: f64,
    seconds: f64,
) -> Result<RunPlan, String> {
    let control = match control {
        StepControl::Fixed(h) => StepControl::Fixed(refine_step(h, t_end)),
        tol => tol,
    };
    work_precision::plan(
        case.scene.info(),
        method.name,
        control,
        t_end,
        Observe::Ends,
    )
    .map(|p| p.with_deadline(seconds))
    .map_err(|e| e.to_string())
}

/// The setting of `method` on `case` by the rule (module doc), with its easy-twin error.
///
/// # Errors
/// No setting reaches the target (the best error reached, or the last run's error).
pub fn calibrate(
    case: &Case,
    method: &MethodInfo,
    easy: &FinalState,
    seconds: f64,
) -> Result<(StepControl, f64), String> {
    let info = case.scene.info();
    let t = case.easy_t_end;
    let run = |control: StepControl| -> Result<f64, String> {
        let plan = plan(case, method, control, t, seconds)?;
        let (state, _) = work_precision::final_state(case.scene, &case.easy, &plan)
            .map_err(|e| e.to_string())?;
        Ok(state_error(info, &state, easy))
    };
    if method.properties.exact {
        let control = StepControl::Fixed(info.default_step.min(t));
        return run(control).map(|e| (control, e));
    }
    let adaptive = method.properties.adaptive;
    let p = f64::from(method.order.value().unwrap_or(2).max(1));
    let mut control = if adaptive {
        StepControl::Tolerance(1e-8)
    } else {
        StepControl::Fixed(info.default_step.min(t / 4.0))
    };
    let size = |c: StepControl| match c {
        StepControl::Fixed(h) | StepControl::Tolerance(h) => h,
    };
    let mut best: Option<(StepControl, f64)> = None;
    let mut last = String::new();
    for _ in 0..6 {
        let factor = match run(control) {
            Ok(e) if e <= 3.0 * TARGET => {
                if best.is_none_or(|(b, _)| size(control) > size(b)) {
                    best = Some((control, e));
                }
                if e >= TARGET / 3.0 {
                    break;
                }
                last = format!("error {e:.1e} at {}", words(control));
                if e > 0.0 { TARGET / e } else { f64::INFINITY }
            }
            Ok(e) => {
                last = format!("error {e:.1e} at {}", words(control));
                if e.is_finite() { TARGET / e } else { 0.0 }
            }
            // A smaller step (tighter tolerance) would only take longer: stop at the first run
            // the time limit cuts, keeping the best setting if one was found.
            Err(reason) if reason.contains("time limit") => {
                if best.is_none() {
                    last = format!("{reason} at {}", words(control));
                }
                break;
            }
            Err(reason) => {
                last = format!("{reason} at {}", words(control));
                0.0
            }
        };
        let next = if adaptive {
            StepControl::Tolerance((size(control) * factor.clamp(1e-3, 1e3)).clamp(1e-14, 1e-3))
        } else {
            let scale = factor.powf(1.0 / p).clamp(1.0 / 16.0, 16.0);
            StepControl::Fixed((size(control) * scale).clamp(t * 1e-7, t / 4.0))
        };
        if size(next) == size(control) {
            break;
        }
        control = next;
    }
    best.ok_or_else(|| {
        format!("no setting reaches an error of {TARGET:e} on the easy twin (last: {last})")
    })
}

/// `dt = H s` or `tol = T`.
fn words(c: StepControl) -> String {
    match c {
        StepControl::Fixed(h) => format!("dt = {h:.3e} s"),
        StepControl::Tolerance(t) => format!("tol = {t:.1e}"),
    }
}

/// The recorder of a case's run: its last row, its energy history and the drift of the
/// conserved columns.
struct Watch {
    last: LastRow,
    history: EnergyHistory,
    columns: Vec<usize>,
    initial: Vec<f64>,
    drift: f64,
}

impl Recorder for Watch {
    fn row(&mut self, values: &[f64]) -> Flow {
        self.last.row(values);
        self.history.row(values);
        if self.initial.is_empty() {
            self.initial = self.columns.iter().map(|&c| values[c]).collect();
        } else {
            for (&c, &v0) in self.columns.iter().zip(&self.initial) {
                self.drift = self.drift.max((values[c] - v0).abs());
            }
        }
        Flow::Continue
    }
}

/// Runs `method` on `case` (calibrating it unless it has a setting), each run limited to
/// `seconds`; never fails: whatever happens is the entry.
#[must_use]
pub fn run_entry(case: &Case, refs: &References, method: &Method, seconds: f64) -> Entry {
    let info = case.scene.info();
    let mut entry = Entry::blank(case, method);
    let (control, chosen_by) = match method.setting {
        Some(c) => (c, "given"),
        None => match calibrate(case, method.info, &refs.easy, seconds) {
            Ok((c, e)) => {
                entry.easy_error = Some(e);
                (
                    c,
                    if method.info.properties.exact {
                        "exact"
                    } else {
                        "rule"
                    },
                )
            }
            Err(reason) => return entry.failing(format!("calibration: {reason}")),
        },
    };
    entry.chosen_by = chosen_by.into();
    let plan = match plan(case, method.info, control, case.t_end, seconds) {
        Ok(p) => p.observing(Observe::EveryStep),
        Err(reason) => {
            entry.reason = reason;
            return entry;
        }
    };
    match plan.step {
        StepControl::Fixed(h) => entry.dt = Some(h),
        StepControl::Tolerance(t) => entry.tol = Some(t),
    }
    let columns = info.columns();
    let index = |name: &str| columns.iter().position(|c| c == name);
    let mut watch = Watch {
        last: LastRow::default(),
        history: EnergyHistory::new(
            case.t_end / 1e3,
            case.t_end,
            30,
            index("energy_rel_err").unwrap_or(usize::MAX),
        ),
        columns: case
            .property
            .conserved
            .iter()
            .filter_map(|c| index(c))
            .collect(),
        initial: Vec::new(),
        drift: 0.0,
    };
    let start = Instant::now();
    let outcome = case.scene.simulate(&case.params, &plan, &mut watch);
    entry.seconds = Some(start.elapsed().as_secs_f64());
    let summary: RunSummary = match outcome {
        Ok(s) => s,
        Err(e) => return entry.failing(e.to_string()),
    };
    entry.steps = Some(summary.steps);
    entry.energy = Some(summary.max_energy_rel_err);
    entry.energy_growth = watch.history.growth_exponent(2.0);
    if !watch.columns.is_empty() {
        let scale = watch
            .initial
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        entry.drift = Some(watch.drift / scale);
    }
    if let Some(reference) = &refs.case {
        let n = state_len(info);
        let state = FinalState {
            t: watch.last.last.first().copied().unwrap_or(f64::NAN),
            values: watch
                .last
                .last
                .get(1..=n)
                .map(<[f64]>::to_vec)
                .unwrap_or_default(),
        };
        entry.error = Some(state_error(info, &state, reference));
    }
    let mut broken = Vec::new();
    let mut check = |what: &str, value: Option<f64>, bound: Option<f64>| {
        if let (Some(v), Some(b)) = (value, bound)
            && !(v <= b)
        {
            broken.push(format!("{what} {v:.2e} > {b:.0e}"));
        }
    };
    check("error", entry.error, case.property.error);
    check("energy error", entry.energy, case.property.energy);
    check("drift", entry.drift, case.property.drift);
    if broken.is_empty() {
        entry.status = Status::Ok;
    } else {
        entry.status = Status::Violated;
        entry.reason = broken.join("; ");
    }
    entry
}

/// How to run an atlas.
#[derive(Debug, Clone, Copy)]
pub struct AtlasConfig<'a> {
    /// Worker threads.
    pub threads: usize,
    /// Wall-clock limit of each run (s).
    pub run_seconds: f64,
    /// Wall-clock budget of the whole atlas (s): no entry starts after it.
    pub budget: f64,
    /// Continue the atlas in the folder.
    pub resume: bool,
    /// Set to stop starting entries.
    pub cancel: Option<&'a AtomicBool>,
}

/// What an atlas run produced.
#[derive(Debug, Clone)]
pub struct AtlasReport {
    /// Every finished entry, in case order then method order.
    pub entries: Vec<Entry>,
    /// Entries of the atlas in all.
    pub total: usize,
    /// Entries found in the journal.
    pub resumed: usize,
    /// How each case's reference was computed (`case → method`, or why it failed).
    pub references: BTreeMap<String, String>,
    /// Wall time (s).
    pub seconds: f64,
}

impl AtlasReport {
    /// Whether every entry finished.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.entries.len() == self.total
    }
}

/// The pairs of an atlas: each case with each method that runs its scene, each pair once (a
/// case or method given twice is run, journalled and counted once).
#[must_use]
pub fn pairs<'a>(cases: &'a [Case], methods: &'a [Method]) -> Vec<(&'a Case, &'a Method)> {
    let mut seen = std::collections::BTreeSet::new();
    cases
        .iter()
        .flat_map(|c| {
            methods
                .iter()
                .filter(|m| c.scene.info().kind_for(m.info).is_some())
                .map(move |m| (c, m))
        })
        .filter(|(c, m)| seen.insert((c.name.clone(), m.spec())))
        .collect()
}

/// Cuts the last line of the journal at `path` when an interrupted write (a kill, a full disk)
/// left it without its newline: that entry is run again, and the next one starts on a line of
/// its own.
fn cut_torn_line(path: &Path) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let keep = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    if keep < bytes.len() {
        OpenOptions::new()
            .write(true)
            .open(path)
            .and_then(|f| f.set_len(keep as u64))
            .map_err(|e| format!("{}: cannot cut its torn last line: {e}", path.display()))?;
    }
    Ok(())
}

/// Runs the atlas of `cases` × `methods` (those that run each case's scene) into `dir`'s
/// journal, in parallel, under the budget; returns what finished.
///
/// # Errors
/// The folder or journal cannot be read or written; a journal of another atlas; the worker
/// threads cannot be started.
pub fn run(
    cases: &[Case],
    methods: &[Method],
    dir: &Path,
    config: &AtlasConfig<'_>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<AtlasReport, String> {
    let start = Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(JOURNAL);
    let mut done: BTreeMap<(String, String), Entry> = BTreeMap::new();
    if path.exists() {
        if !config.resume {
            return Err(format!(
                "{}: the folder already holds an atlas; pass --resume to continue it, or \
                 choose another output folder",
                dir.display()
            ));
        }
        cut_torn_line(&path)?;
        let mut reader = csv::Reader::from_path(&path).map_err(|e| e.to_string())?;
        for (k, row) in reader.deserialize::<Entry>().enumerate() {
            let entry = row.map_err(|e| format!("{}:{}: {e}", path.display(), k + 2))?;
            // An entry of a case since changed is computed again.
            if cases
                .iter()
                .any(|c| c.name == entry.case && c.key() == entry.case_key)
            {
                done.insert((entry.case.clone(), entry.method.clone()), entry);
            }
        }
    }
    let all = pairs(cases, methods);
    let total = all.len();
    let resumed = all
        .iter()
        .filter(|(c, m)| done.contains_key(&(c.name.clone(), m.spec())))
        .count();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(config.threads.clamp(1, total.max(1)))
        .build()
        .map_err(|e| e.to_string())?;
    // The references of the cases that still have entries to run.
    let todo: Vec<&Case> = cases
        .iter()
        .filter(|c| {
            all.iter()
                .any(|(k, m)| k.name == c.name && !done.contains_key(&(c.name.clone(), m.spec())))
        })
        .collect();
    // Each case's references are computed by the first of its entries that starts, within
    // the budget left then (an atlas out of budget computes none).
    // With them, whether the budget shortened their time limit.
    type Cell = OnceLock<(Result<References, String>, bool)>;
    let refs: BTreeMap<String, Cell> = todo
        .iter()
        .map(|c| (c.name.clone(), OnceLock::new()))
        .collect();
    let file = OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    // The header goes first into an empty journal only.
    let empty = file.metadata().map_or(true, |m| m.len() == 0);
    let journal = Mutex::new(
        csv::WriterBuilder::new()
            .has_headers(empty)
            .from_writer(file),
    );
    let fresh: Mutex<Vec<Entry>> = Mutex::new(Vec::new());
    let finished = std::sync::atomic::AtomicUsize::new(resumed);
    let failure: Mutex<Option<String>> = Mutex::new(None);
    progress(resumed, total);
    pool.install(|| {
        all.par_iter().with_max_len(1).for_each(|(case, method)| {
            let key = (case.name.clone(), method.spec());
            if done.contains_key(&key)
                || config.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
                || failure.lock().map_or(true, |f| f.is_some())
            {
                return;
            }
            let left = config.budget - start.elapsed().as_secs_f64();
            if left <= 0.0 {
                return;
            }
            let seconds = config.run_seconds.min(left);
            let reference = refs.get(&case.name).map(|cell| {
                cell.get_or_init(|| {
                    let full = config.run_seconds * 4.0;
                    (references(case, full.min(left)), left < full)
                })
            });
            // A reference the budget cut short is no result: its entries are left to a resume.
            if let Some((Err(reason), true)) = reference
                && reason.contains("time limit")
            {
                return;
            }
            let entry = match reference.map(|(r, _)| r) {
                Some(Ok(r)) => run_entry(case, r, method, seconds),
                Some(Err(reason)) => {
                    Entry::blank(case, method).failing(format!("no reference: {reason}"))
                }
                None => return,
            };
            // An entry cut short by the end of the budget is not a result: left to a resume.
            if entry.status == Status::TimeLimit && seconds < config.run_seconds {
                return;
            }
            let written = journal.lock().map_err(|e| e.to_string()).and_then(|mut w| {
                w.serialize(&entry).map_err(|e| e.to_string())?;
                w.flush().map_err(|e| e.to_string())
            });
            if let Err(e) = written {
                if let Ok(mut f) = failure.lock() {
                    f.get_or_insert(format!("{}: {e}", path.display()));
                }
                return;
            }
            if let Ok(mut f) = fresh.lock() {
                f.push(entry);
            }
            progress(finished.fetch_add(1, Ordering::Relaxed) + 1, total);
        });
    });
    if let Some(e) = failure.into_inner().ok().flatten() {
        return Err(e);
    }
    for entry in fresh.into_inner().unwrap_or_default() {
        done.insert((entry.case.clone(), entry.method.clone()), entry);
    }
    let entries = all
        .iter()
        .filter_map(|(c, m)| done.get(&(c.name.clone(), m.spec())).cloned())
        .collect();
    Ok(AtlasReport {
        entries,
        total,
        resumed,
        references: refs
            .into_iter()
            .filter_map(|(k, cell)| {
                cell.into_inner()
                    .map(|(r, _)| (k, r.map_or_else(|e| e, |r| r.method)))
            })
            .collect(),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// `atlas.csv`: the entries (in atlas order) as CSV.
///
/// # Errors
/// Never in practice (writing to memory).
pub fn atlas_csv(entries: &[Entry]) -> Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for e in entries {
        w.serialize(e).map_err(|e| e.to_string())?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

/// The parameters of `case` that differ from its scene's defaults, as `name = value` text.
#[must_use]
pub fn parameters_text(case: &Case) -> String {
    let defaults: Params = case.scene.info().default_params();
    case.params
        .iter()
        .filter(|(n, v)| defaults.get(n).map_or(true, |d| d.to_bits() != v.to_bits()))
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}
