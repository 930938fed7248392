//! Fuzzing the scene-file parser: arbitrary text and mutations of the seed corpus
//! (`fuzz/corpus/scene`) give a scene file or a typed error, never a panic. CI runs a few
//! hundred cases; `PROPTEST_CASES=100000 cargo test --release fuzz_` runs many more.

use proptest::prelude::*;
use tumble_scenarios::scene_file::SceneFile;

const CORPUS_ROOT: &str = "../../fuzz/corpus";

/// Tokens a mutation may insert: numbers out of range, TOML and expression punctuation.
const TOKENS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-0",
    "0",
    "-1",
    "18446744073709551616",
    "\"",
    "[",
    "]",
    "[[",
    "=",
    ",",
    ".",
    "\n",
    "#",
    "/",
    "*",
    "pi",
    "e",
    "{",
    "}",
    "'''",
    "\\u0000",
    "v ",
    "f ",
    "facet normal",
    "vertex",
    "endloop",
    "solid",
    "\u{feff}",
    "é",
];

/// The files of the seed corpus `fuzz/corpus/KIND`.
fn corpus(kind: &str) -> Vec<Vec<u8>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(CORPUS_ROOT)
        .join(kind);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// `seed` after `edits`: each `(position, operation, pick)` replaces, inserts or deletes a byte
/// or inserts one of [`TOKENS`].
fn mutate(seed: &[u8], edits: &[(usize, u8, usize)]) -> Vec<u8> {
    let mut out = seed.to_vec();
    for &(pos, op, pick) in edits {
        let at = pos % (out.len() + 1);
        match op % 4 {
            0 if at < out.len() => out[at] = pick as u8,
            1 => out.insert(at, pick as u8),
            2 if at < out.len() => {
                out.remove(at);
            }
            3 => {
                let token = TOKENS[pick % TOKENS.len()];
                out.splice(at..at, token.bytes());
            }
            _ => {}
        }
    }
    out
}

/// Edits for [`mutate`].
fn edits() -> impl Strategy<Value = Vec<(usize, u8, usize)>> {
    prop::collection::vec((any::<usize>(), any::<u8>(), any::<usize>()), 1..12)
}

fn origin() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(CORPUS_ROOT)
        .join("scene/fuzz.toml")
        .display()
        .to_string()
}

use std::path::Path;

#[test]
fn fuzz_corpus_scene_files_parse() {
    for seed in corpus("scene") {
        let text = String::from_utf8(seed).unwrap();
        if let Err(e) = SceneFile::parse(&text, &origin()) {
            panic!("{e}\n{text}");
        }
    }
}

proptest! {
    #![proptest_config(crate::support::proptest_config(300))]

    #[test]
    fn fuzz_scene_file_arbitrary_text(text in "\\PC{0,300}") {
        let _ = SceneFile::parse(&text, &origin());
    }

    #[test]
    fn fuzz_scene_file_mutated_corpus(seed in any::<prop::sample::Index>(), edits in edits()) {
        let seeds = corpus("scene");
        let bytes = mutate(&seeds[seed.index(seeds.len())], &edits);
        let _ = SceneFile::parse(&String::from_utf8_lossy(&bytes), &origin());
    }
}
