//! What the fuzz tests of the crates share: the seed corpus under `fuzz/corpus/KIND` and
//! byte-level mutations of it. Included by each crate's `tests/*/fuzz.rs` with `#[path]`.

use proptest::prelude::*;

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
pub fn corpus(kind: &str) -> Vec<Vec<u8>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
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
pub fn mutate(seed: &[u8], edits: &[(usize, u8, usize)]) -> Vec<u8> {
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
pub fn edits() -> impl Strategy<Value = Vec<(usize, u8, usize)>> {
    prop::collection::vec((any::<usize>(), any::<u8>(), any::<usize>()), 1..12)
}
