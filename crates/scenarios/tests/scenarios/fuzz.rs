//! Fuzzing the scene-file parser: arbitrary text and mutations of the seed corpus
//! (`fuzz/corpus/scene`) give a scene file or a typed error, never a panic. CI runs a few
//! hundred cases; `PROPTEST_CASES=100000 cargo test --release fuzz_` runs many more.

use proptest::prelude::*;
use tumble_scenarios::scene_file::SceneFile;

#[path = "../../../../fuzz/support.rs"]
mod support;

use support::{corpus, edits, mutate};

const CORPUS_ROOT: &str = "../../fuzz/corpus";

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
