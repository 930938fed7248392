//! Fuzzing the OBJ and STL parsers: arbitrary bytes and mutations of the seed corpus
//! (`fuzz/corpus/obj`, `fuzz/corpus/stl`) give a mesh or a typed error, never a panic. CI runs a
//! few hundred cases; `PROPTEST_CASES=100000 cargo test --release fuzz_` runs many more.

use std::path::Path;

use proptest::prelude::*;
use tumble_inertia::{ValidationOptions, parse_obj, parse_stl};

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

fn obj(bytes: &[u8]) {
    let _ = parse_obj(bytes, Path::new("fuzz.obj"), &ValidationOptions::default());
}

fn stl(bytes: Vec<u8>) {
    let _ = parse_stl(bytes, Path::new("fuzz.stl"), &ValidationOptions::default());
}

#[test]
fn fuzz_corpus_meshes_load() {
    for seed in corpus("obj") {
        assert!(parse_obj(&seed, Path::new("seed.obj"), &ValidationOptions::default()).is_ok());
    }
    for seed in corpus("stl") {
        assert!(parse_stl(seed, Path::new("seed.stl"), &ValidationOptions::default()).is_ok());
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300))]

    #[test]
    fn fuzz_obj_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        obj(&bytes);
    }

    #[test]
    fn fuzz_obj_mutated_corpus(seed in any::<prop::sample::Index>(), edits in edits()) {
        let seeds = corpus("obj");
        obj(&mutate(&seeds[seed.index(seeds.len())], &edits));
    }

    #[test]
    fn fuzz_stl_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        stl(bytes);
    }

    #[test]
    fn fuzz_stl_mutated_corpus(seed in any::<prop::sample::Index>(), edits in edits()) {
        let seeds = corpus("stl");
        stl(mutate(&seeds[seed.index(seeds.len())], &edits));
    }
}
