//! Fuzzing the OBJ and STL parsers: arbitrary bytes and mutations of the seed corpus
//! (`fuzz/corpus/obj`, `fuzz/corpus/stl`) give a mesh or a typed error, never a panic. CI runs a
//! few hundred cases; `PROPTEST_CASES=100000 cargo test --release fuzz_` runs many more.

use std::path::Path;

use proptest::prelude::*;
use tumble_inertia::{ValidationOptions, parse_obj, parse_stl};

#[path = "../../../../fuzz/support.rs"]
mod support;

use support::{corpus, edits, mutate};

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
