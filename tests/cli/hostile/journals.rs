//! Damaged, truncated and foreign journals in a sweep folder, then `--resume` or `merge`.

use std::path::Path;

use super::Content::Text;
use super::{Case, run_in, run_table};

/// A three-point sweep, fast.
pub const SWEEP: &str = "scene = \"free-hoop\"\n[run]\nintegrator = \"gauss8\"\ndt = 0.01\n\
t_end = 0.1\n[[axes]]\nparameter = \"omega0\"\nvalues = [1.0, 2.0, 3.0]\n[metrics]\n\
record = [\"max_tilt\"]\n";

const FILES: &[(&str, super::Content)] = &[("s.sweep.toml", Text(SWEEP))];

/// Runs the sweep into `sw`.
fn finished(dir: &Path) {
    let (code, err) = run_in(
        dir,
        &["sweep", "s.sweep.toml", "-o", "sw", "--check", "off"],
    );
    assert_eq!(code, Some(0), "{err}");
}

fn journal(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("sw/journal.csv")).unwrap()
}

/// `sw` finished, its results gone (so `--resume` reads the journal), the journal replaced by
/// `damage` of it.
fn damaged(dir: &Path, damage: impl Fn(&str) -> String) {
    finished(dir);
    std::fs::remove_file(dir.join("sw/results.csv")).unwrap();
    let text = damage(&journal(dir));
    std::fs::write(dir.join("sw/journal.csv"), text).unwrap();
}

fn first_line(text: &str) -> &str {
    text.lines().next().unwrap()
}

fn empty(dir: &Path) {
    damaged(dir, |_| String::new());
}
fn foreign_first_line(dir: &Path) {
    damaged(dir, |t| {
        t.replacen(first_line(t), "index,omega0,max_tilt", 1)
    });
}
fn no_header(dir: &Path) {
    damaged(dir, |t| format!("{}\n", first_line(t)));
}
fn wrong_header(dir: &Path) {
    damaged(dir, |t| {
        let mut lines: Vec<&str> = t.lines().collect();
        lines[1] = "index,colour,flavour";
        lines.join("\n") + "\n"
    });
}
fn other_fingerprint(dir: &Path) {
    damaged(dir, |t| {
        let line = first_line(t);
        let (head, _) = line.split_once("fnv1a64:").unwrap();
        t.replacen(line, &format!("{head}fnv1a64:0123456789abcdef"), 1)
    });
}
fn binary(dir: &Path) {
    finished(dir);
    std::fs::remove_file(dir.join("sw/results.csv")).unwrap();
    std::fs::write(dir.join("sw/journal.csv"), b"\xff\xfe\x00\x01\n\x80\x81\n").unwrap();
}
fn garbage_row(dir: &Path) {
    damaged(dir, |t| format!("{t}banana,split,yes,no,maybe\n"));
}
fn point_out_of_range(dir: &Path) {
    damaged(dir, |t| {
        let last = t.lines().last().unwrap();
        let (_, rest) = last.split_once(',').unwrap();
        format!("{t}99,{rest}\n")
    });
}
fn point_twice(dir: &Path) {
    damaged(dir, |t| {
        let row = t.lines().nth(2).unwrap();
        let changed = row.replacen(",ok,", ",failed,", 1).replacen("0.", "7.", 1);
        format!("{t}{changed}\n")
    });
}
/// A journal whose first line claims shard 1 of 4·10¹² (the definition's fingerprint kept).
fn huge_shard_count(dir: &Path) {
    damaged(dir, |t| {
        let lines: Vec<&str> = t.lines().collect();
        let first = lines[0].replacen("shard 1/1,", "shard 1/4000000000000,", 1);
        format!("{first}\n{}\n{}\n", lines[1], lines[2])
    });
}
fn shard_zero(dir: &Path) {
    damaged(dir, |t| t.replacen("shard 1/1,", "shard 0/0,", 1));
}
fn no_journal(dir: &Path) {
    finished(dir);
    std::fs::remove_file(dir.join("sw/journal.csv")).unwrap();
}
fn edited_definition(dir: &Path) {
    finished(dir);
    let path = dir.join("sw/sweep.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(path, text.replacen("0.1", "0.2", 1)).unwrap();
}
fn journal_a_folder(dir: &Path) {
    finished(dir);
    std::fs::remove_file(dir.join("sw/results.csv")).unwrap();
    std::fs::remove_file(dir.join("sw/journal.csv")).unwrap();
    std::fs::create_dir(dir.join("sw/journal.csv")).unwrap();
}
fn two_copies(dir: &Path) {
    finished(dir);
    let (code, err) = run_in(
        dir,
        &["sweep", "s.sweep.toml", "-o", "sw2", "--check", "off"],
    );
    assert_eq!(code, Some(0), "{err}");
}
fn foreign_results(dir: &Path) {
    two_copies(dir);
    std::fs::write(dir.join("sw2/results.csv"), "a,b,c\n1,2,3\n").unwrap();
}
fn incomplete_shard(dir: &Path) {
    let (code, err) = run_in(
        dir,
        &[
            "sweep",
            "s.sweep.toml",
            "-o",
            "k1",
            "--shard",
            "1/2",
            "--check",
            "off",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    let path = dir.join("k1/journal.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    std::fs::write(path, format!("{}\n{}\n", lines[0], lines[1])).unwrap();
}

const RESUME: &[&str] = &[
    "sweep",
    "s.sweep.toml",
    "-o",
    "sw",
    "--resume",
    "--check",
    "off",
];
const MERGE: &[&str] = &["sweep", "merge", "sw", "-o", "merged", "--check", "off"];

macro_rules! journal_cases {
    ($($name:expr, $setup:expr, [$($fragment:expr),+];)+) => {
        &[$(
            Case::new(concat!($name, ", then --resume"), RESUME, 1, &[$($fragment),+])
                .files(FILES)
                .setup($setup),
            Case::new(concat!($name, ", then merge"), MERGE, 1, &[$($fragment),+])
                .files(FILES)
                .setup($setup),
        )+]
    };
}

const DAMAGED: &[Case] = journal_cases![
    "journal empty", empty, ["journal.csv:1"];
    "journal without its first line", foreign_first_line, ["journal.csv:1", "not a tumble sweep journal"];
    "journal without a header", no_header, ["journal.csv:2"];
    "journal of other columns", wrong_header, ["journal.csv:2", "colour"];
    "journal of another definition", other_fingerprint, ["another definition"];
    "journal binary", binary, ["journal.csv", "UTF-8"];
    "journal with a garbage row", garbage_row, ["journal.csv:6"];
    "journal with a point out of range", point_out_of_range, ["journal.csv", "99"];
    "journal with a point twice", point_twice, ["journal.csv", "twice"];
    "journal of shard 1/4000000000000", huge_shard_count, ["4000000000000"];
    "journal of shard 0/0", shard_zero, ["journal.csv:1"];
    "journal missing", no_journal, ["journal"];
    "journal a folder", journal_a_folder, ["journal"];
];

const OTHERS: &[Case] = &[
    Case::new(
        "sweep definition edited, then merge",
        MERGE,
        1,
        &["sw", "different sweep", "another definition"],
    )
    .files(FILES)
    .setup(edited_definition),
    Case::new(
        "one folder twice in a merge",
        &["sweep", "merge", "sw", "sw", "-o", "merged"],
        1,
        &["both shard 1/1"],
    )
    .files(FILES)
    .setup(finished),
    Case::new(
        "two copies of shard 1/1 in a merge",
        &["sweep", "merge", "sw", "sw2", "-o", "merged"],
        1,
        &["both shard 1/1"],
    )
    .files(FILES)
    .setup(two_copies),
    Case::new(
        "an incomplete shard in a merge",
        &["sweep", "merge", "k1", "-o", "merged"],
        1,
        &["1/2"],
    )
    .files(FILES)
    .setup(incomplete_shard),
    Case::new(
        "diff against foreign results",
        &["sweep", "diff", "sw", "sw2"],
        1,
        &["results.csv"],
    )
    .files(FILES)
    .setup(foreign_results),
    Case::new(
        "resume into a folder of another sweep",
        &["sweep", "-o", "sw", "--resume", "--check", "off"],
        1,
        &["sw"],
    )
    .files(FILES)
    .setup(finished),
];

pub const CASES: &[Case] = DAMAGED;

/// The cases that are not pairs.
pub const MORE: &[Case] = OTHERS;

#[test]
fn hostile_journals() {
    run_table(CASES);
    run_table(MORE);
}
