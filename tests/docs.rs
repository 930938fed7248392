//! The documentation is executed.
//!
//! * `documented_commands_run_as_shown`: every ```` ```console ```` block of `README.md` and of
//!   the book under `docs/` is run by `trycmd` against the `tumble` binary of this build, and
//!   the output a block shows is compared with the output the command prints (`...` stands for
//!   any lines, `[..]` for the rest of a line). Each page runs in a scratch folder of its own that
//!   sees the repository's `scenes/` and `models/`, so a page's commands build on each other
//!   (a sweep, then its plot) and write nothing into the repository.
//! * `reference_pages_are_generated_from_the_binary`: the command-line reference (every
//!   command's `--help`), the integrator table (`tumble integrators --json`) and the scene
//!   catalogue (`tumble scenes --json`) and the keys of the records tumble writes (a small run,
//!   sweep and work–precision study, made here) are rendered again and compared with the
//!   committed pages under `docs/reference/`; `TUMBLE_BLESS=1` rewrites them. A flag, a method
//!   or a record key added without its page fails here.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

const TUMBLE: &str = env!("CARGO_BIN_EXE_tumble");

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The pages whose command blocks are run: the README and every Markdown file of the book
/// except the generated reference (whose blocks are help texts, not commands).
fn executed_pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, pages: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
            .map(|entry| entry.expect("a directory entry").path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, pages);
            } else if path.extension().is_some_and(|ext| ext == "md") {
                pages.push(path);
            }
        }
    }
    let mut pages = vec![root().join("README.md")];
    walk(&root().join("docs"), &mut pages);
    pages
}

#[test]
fn documented_commands_run_as_shown() {
    // Each page becomes `NAME.md` beside a folder `NAME.in/`, which trycmd takes as the page's
    // working directory; the repository's inputs are linked into it.
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let cases = trycmd::TestCases::new();
    cases
        .register_bin("tumble", PathBuf::from(TUMBLE))
        .env("NO_COLOR", "1")
        .timeout(std::time::Duration::from_secs(300));
    for page in executed_pages() {
        let relative = page.strip_prefix(root()).expect("a page of the repository");
        let name = relative
            .to_string_lossy()
            .trim_end_matches(".md")
            .replace('/', "--");
        let workdir = scratch.path().join(format!("{name}.in"));
        std::fs::create_dir(&workdir).expect("a page's working folder");
        for input in ["scenes", "models"] {
            std::os::unix::fs::symlink(root().join(input), workdir.join(input))
                .expect("a link to the repository's inputs");
        }
        let copy = scratch.path().join(format!("{name}.md"));
        std::fs::copy(&page, &copy).expect("a copy of the page");
        cases.case(copy);
    }
    cases.run();
}

/// Runs `tumble ARGS` and returns its standard output; it must succeed.
fn tumble(args: &[&str]) -> String {
    tumble_in(Path::new("."), args)
}

/// Runs `tumble ARGS` in `dir` and returns its standard output; it must succeed.
fn tumble_in(dir: &Path, args: &[&str]) -> String {
    let output = Command::new(TUMBLE)
        .current_dir(dir)
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("tumble runs");
    assert!(
        output.status.success(),
        "tumble {} failed: {}",
        args.join(" "),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8 output")
}

/// The subcommands listed in the `Commands:` section of a help text (`help` left out).
fn subcommands(help: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut in_commands = false;
    for line in help.lines() {
        if line == "Commands:" {
            in_commands = true;
        } else if in_commands {
            if line.is_empty() || !line.starts_with(' ') {
                break;
            }
            // A command's line is indented by two spaces; its wrapped description by more.
            if let Some(rest) = line.strip_prefix("  ")
                && !rest.starts_with(' ')
            {
                let name = rest.split_whitespace().next().expect("a command name");
                if name != "help" {
                    names.push(name.to_string());
                }
            }
        }
    }
    names
}

/// The command-line reference: every command's `--help`, walked from `tumble --help` down.
fn cli_reference() -> String {
    fn visit(path: &mut Vec<String>, page: &mut String) {
        let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
        args.push("--help");
        let help = tumble(&args);
        let title = if path.is_empty() {
            "tumble".to_string()
        } else {
            format!("tumble {}", path.join(" "))
        };
        let depth = if path.is_empty() { 2 } else { 1 + path.len() };
        let _ = write!(
            page,
            "{} `{title}`\n\n```text\n{}\n```\n\n",
            "#".repeat(depth.min(4)),
            help.trim_end()
        );
        for name in subcommands(&help) {
            path.push(name);
            visit(path, page);
            path.pop();
        }
    }
    let mut page = String::from(
        "# Command-line reference\n\n\
         Generated from the `tumble` binary's own help (`tumble COMMAND --help` for every \
         command and subcommand) by `cargo test --test docs`, which fails when this page differs \
         from what the binary prints; `TUMBLE_BLESS=1 cargo test --test docs` rewrites it. Exit \
         codes and what tumble checks before it runs: [guarantees](../explanation/guarantees.md).\n\n",
    );
    visit(&mut Vec::new(), &mut page);
    page.trim_end().to_string() + "\n"
}

/// A table cell: pipes escaped, newlines folded.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

fn names(list: &Value) -> String {
    list.as_array()
        .map(|items| {
            items
                .iter()
                .map(|item| format!("`{}`", item.as_str().unwrap_or_default()))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default()
}

fn text(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Null => "—".to_string(),
        other => other.to_string(),
    }
}

/// The measurements of a recommendation (`to_error` or `long_run` in `tumble scenes --json`):
/// each method's time to the band's finest error, or its largest relative energy error over
/// the long run.
fn measured(entry: &Value) -> String {
    let time = |s: f64| {
        if s < 1e-3 {
            format!("{:.1} µs", 1e6 * s)
        } else if s < 1.0 {
            format!("{:.2} ms", 1e3 * s)
        } else {
            format!("{s:.3} s")
        }
    };
    let methods = |v: &Value| v["method"].as_array().cloned().unwrap_or_default();
    if let Some(band) = entry.get("to_error") {
        let items: Vec<String> = methods(band)
            .iter()
            .map(|m| match m["seconds"].as_f64() {
                Some(s) => format!("{} {}", text(&m["integrator"]), time(s)),
                None => format!(
                    "{} not reached (best {:.1e})",
                    text(&m["integrator"]),
                    m["best_error"].as_f64().unwrap_or(f64::NAN)
                ),
            })
            .collect();
        return format!(
            "to {:.0e}: {}",
            band["target_error"].as_f64().unwrap_or(f64::NAN),
            items.join(", ")
        );
    }
    if let Some(long) = entry.get("long_run") {
        let items: Vec<String> = methods(long)
            .iter()
            .map(|m| match m["max_energy_rel_err"].as_f64() {
                Some(e) => format!(
                    "{} ({}) {e:.1e}",
                    text(&m["integrator"]),
                    text(&m["control"])
                ),
                None => format!("{} failed: {}", text(&m["integrator"]), text(&m["failed"])),
            })
            .collect();
        return format!("{} steps: {}", text(&long["steps"]), items.join(", "));
    }
    String::new()
}

/// The integrator reference, from `tumble integrators --json`.
fn integrators_reference() -> String {
    let list: Value = serde_json::from_str(&tumble(&["integrators", "--json"])).expect("JSON");
    let list = list.as_array().expect("a list of integrators");
    let mut page = String::from(
        "# Integrators\n\n\
         Generated from the integrator registry (`tumble integrators --json`) by \
         `cargo test --test docs`; `TUMBLE_BLESS=1 cargo test --test docs` rewrites it. \
         `TABLE:BASE` composes any symmetric order-2 base a scene offers (see \
         [choosing an integrator](../tutorials/integrators.md)).\n\n",
    );
    let _ = writeln!(page, "{} methods.\n", list.len());
    page.push_str(
        "| name | order | family | stages | explicit | symplectic | symmetric | adaptive | \
         dense output | Lie group | problem | what it is |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let flag = |method: &Value, key: &str| {
        if method["properties"][key].as_bool() == Some(true) {
            "yes"
        } else {
            ""
        }
    };
    for method in list {
        let _ = writeln!(
            page,
            "| `{}` | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            text(&method["name"]),
            text(&method["order"]),
            text(&method["family"]),
            text(&method["stages"]),
            flag(method, "explicit"),
            flag(method, "symplectic"),
            flag(method, "symmetric"),
            flag(method, "adaptive"),
            flag(method, "dense_output"),
            flag(method, "lie_group"),
            cell(&text(&method["problem"])),
            cell(&text(&method["summary"])),
        );
    }
    page.push_str("\n## Scenes each method runs\n\n| name | scenes |\n|---|---|\n");
    for method in list {
        let _ = writeln!(
            page,
            "| `{}` | {} |",
            text(&method["name"]),
            names(&method["scenes"])
        );
    }
    page
}

/// The scene catalogue, from `tumble scenes --json`.
fn scenes_reference() -> String {
    let list: Value = serde_json::from_str(&tumble(&["scenes", "--json"])).expect("JSON");
    let list = list.as_array().expect("a list of scenes");
    let mut page = String::from(
        "# Scenes\n\n\
         Generated from the scene catalogue (`tumble scenes --json`) by `cargo test --test docs`; \
         `TUMBLE_BLESS=1 cargo test --test docs` rewrites it. Every parameter can be set with \
         `--set NAME=VALUE` (`simulate`, `animate`, `view`), under `[parameters]` in a scene or \
         sweep file, or as `params={...}` from Python.\n\n\
         | scene | what it is | default run | error of the default run at t_end |\n\
         |---|---|---|---|\n",
    );
    for scene in list {
        let name = text(&scene["name"]);
        let setting = if scene["default_dt"].is_null() {
            String::new()
        } else {
            format!(", dt = {}", text(&scene["default_dt"]))
        };
        let _ = writeln!(
            page,
            "| [`{name}`](#{name}) | {} | {}{setting}, t_end = {} | {} |",
            cell(&text(&scene["summary"])),
            text(&scene["default_integrator"]),
            text(&scene["default_t_end"]),
            text(&scene["default_error"]),
        );
    }
    for scene in list {
        let name = text(&scene["name"]);
        let _ = write!(
            page,
            "\n## {name}\n\n{}.\n\n\
             - coordinates: {}\n- CSV columns: {}\n- conserved: {}\n- oracle of its tests: {}\n\
             - problem kinds: {}\n- default: {}",
            text(&scene["summary"]),
            names(&scene["coordinates"]),
            names(&scene["columns"]),
            scene["conserved"]
                .as_array()
                .map(|c| c.iter().map(text).collect::<Vec<_>>().join("; "))
                .unwrap_or_default(),
            cell(&text(&scene["oracle"])),
            names(&scene["problems"]),
            text(&scene["default_integrator"]),
        );
        if !scene["default_dt"].is_null() {
            let _ = write!(page, ", dt = {}", text(&scene["default_dt"]));
        }
        let _ = writeln!(page, ", t_end = {}\n", text(&scene["default_t_end"]));
        page.push_str("| parameter | default | unit | domain | meaning |\n|---|---|---|---|---|\n");
        for parameter in scene["parameters"].as_array().into_iter().flatten() {
            let _ = writeln!(
                page,
                "| `{}` | {} | {} | {} | {} |",
                text(&parameter["name"]),
                text(&parameter["default"]),
                cell(&text(&parameter["unit"])),
                cell(&text(&parameter["domain"])),
                cell(&text(&parameter["description"])),
            );
        }
        if let Some(recommended) = scene["recommended"].as_array()
            && !recommended.is_empty()
        {
            page.push_str(
                "\n| recommended for | methods | why | compared with | measured |\n\
                 |---|---|---|---|---|\n",
            );
            for entry in recommended {
                let _ = writeln!(
                    page,
                    "| {} | {} | {} | {} | {} |",
                    cell(&text(&entry["purpose"])),
                    names(&entry["integrators"]),
                    cell(&text(&entry["reason"])),
                    names(&entry["compared_with"]),
                    cell(&measured(entry)),
                );
            }
            let by = &scene["measured_by"];
            if !by.is_null() {
                let _ = writeln!(
                    page,
                    "\nMeasured by `{}` (tumble {}, {}) on {}: {}, {} cores, load average {}; \
                     errors against {}.",
                    text(&by["command"]),
                    text(&by["tumble_version"]),
                    text(&by["git_commit"]),
                    text(&by["date"]),
                    text(&by["cpu"]),
                    text(&by["cores"]),
                    text(&by["load_average"]),
                    text(&scene["measured_against"]),
                );
            }
        }
        let _ = writeln!(
            page,
            "\nIntegrators that run it: {}.",
            names(&scene["integrators"])
        );
    }
    page
}

/// The keys of a JSON record, nested ones as `a.b`, those of a list's objects as `a[].b`; the
/// keys of a table of names (parameters, metrics, integrators) are left out, since they are the
/// names, not the format.
fn keys(value: &Value, prefix: &str, out: &mut Vec<String>) {
    const NAMED: [&str; 4] = ["parameters", "metrics", "largest_change", "integrators"];
    match value {
        Value::Object(map) => {
            for (key, child) in map {
                let path = if prefix.is_empty() {
                    key.clone()
                } else {
                    format!("{prefix}.{key}")
                };
                out.push(path.clone());
                if !NAMED.contains(&key.as_str()) {
                    keys(child, &path, out);
                }
            }
        }
        Value::Array(items) => {
            if let Some(first) = items.iter().find(|item| item.is_object()) {
                keys(first, &format!("{prefix}[]"), out);
            }
        }
        _ => {}
    }
}

/// The record keys page: the sidecar of a run, the manifest of a sweep and of a work–precision
/// study, and the headers of a sweep's journal and compute record, from small runs made here.
fn records_reference() -> String {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let dir = scratch.path();
    tumble_in(
        dir,
        &["simulate", "free-hoop", "--t-end", "0.5", "-o", "run.csv"],
    );
    tumble_in(
        dir,
        &[
            "sweep",
            "--set",
            "axes.omega0.count=2",
            "--set",
            "axes.alpha0.count=2",
            "-o",
            "sweep",
        ],
    );
    tumble_in(
        dir,
        &[
            "work-precision",
            "free-body",
            "--integrators",
            "dop853",
            "--t-end",
            "1",
            "-o",
            "wp",
        ],
    );
    let read = |file: &str| {
        std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("reading {file}: {e}"))
    };
    let mut page = String::from(
        "# Record keys\n\n\
         Generated by `cargo test --test docs` from records it makes (`tumble simulate free-hoop \
         --t-end 0.5 -o run.csv`, a 2 × 2 `tumble sweep`, a one-method `tumble work-precision \
         free-body`); `TUMBLE_BLESS=1 cargo test --test docs` rewrites it. Nested keys are written \
         `a.b`, the keys of a list's entries `a[].b`; the names under `parameters`, `metrics`, \
         `integrators` and `largest_change` are those of the scene and the study. What the files \
         are: [file formats](file-formats.md).\n",
    );
    for (title, file) in [
        ("A run's sidecar, `FILE.csv.json`", "run.csv.json"),
        ("A sweep's `manifest.json`", "sweep/manifest.json"),
        (
            "A work–precision study's `manifest.json`",
            "wp/manifest.json",
        ),
    ] {
        let record: Value = serde_json::from_str(&read(file)).expect("a JSON record");
        let mut list = Vec::new();
        keys(&record, "", &mut list);
        let _ = write!(page, "\n## {title}\n\n");
        for key in list {
            let _ = writeln!(page, "- `{key}`");
        }
    }
    let journal = read("sweep/journal.csv");
    let mut lines = journal.lines();
    let first = lines.next().unwrap_or_default();
    let header = lines.next().unwrap_or_default();
    // The first line names the sweep's definition by its hash, which depends on the sweep.
    let first = first.split(", definition").next().unwrap_or(first);
    let _ = write!(
        page,
        "\n## A sweep's `journal.csv`\n\nA first line `{first}, definition fnv1a64:HASH` (the hash \
         of the resolved definition, so that a journal of another sweep is refused), then the \
         columns of `results.csv`, here those of the built-in map:\n\n```text\n{header}\n```\n"
    );
    let compute = read("sweep/compute.csv");
    let _ = write!(
        page,
        "\n## A sweep's `compute.csv`\n\n```text\n{}\n```\n",
        compute.lines().next().unwrap_or_default()
    );
    page
}

#[test]
fn reference_pages_are_generated_from_the_binary() {
    let bless = std::env::var_os("TUMBLE_BLESS").is_some_and(|v| v == "1");
    let mut stale = Vec::new();
    for (file, generated) in [
        ("docs/reference/cli.md", cli_reference()),
        ("docs/reference/integrators.md", integrators_reference()),
        ("docs/reference/scenes.md", scenes_reference()),
        ("docs/reference/records.md", records_reference()),
    ] {
        let path = root().join(file);
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        if committed != generated {
            if bless {
                std::fs::write(&path, &generated)
                    .unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
            } else {
                let first = committed
                    .lines()
                    .zip(generated.lines())
                    .position(|(a, b)| a != b)
                    .unwrap_or(committed.lines().count().min(generated.lines().count()));
                stale.push(format!(
                    "{file}: differs from what the binary generates, from line {}:\n  committed: {}\n  generated: {}",
                    first + 1,
                    committed.lines().nth(first).unwrap_or("(end of file)"),
                    generated.lines().nth(first).unwrap_or("(end of file)"),
                ));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "{}\nrun `TUMBLE_BLESS=1 cargo test --test docs` and commit the pages",
        stale.join("\n")
    );
}
