//! Fuzzing the sweep-file parser: arbitrary text and mutations of the seed corpus
//! (`fuzz/corpus/sweep`) give a definition or a typed error, never a panic. CI runs a few
//! hundred cases; `PROPTEST_CASES=100000 cargo test --release fuzz_` runs many more.

use proptest::prelude::*;
use tumble_studies::sweep::SweepDefinition;

#[path = "../../../../fuzz/support.rs"]
mod support;

use support::{corpus, edits, mutate};

/// Proptest settings: `default_cases` cases, or `PROPTEST_CASES` when set.
fn proptest_config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig::with_cases(cases)
}

#[test]
fn fuzz_corpus_sweep_files_parse() {
    for seed in corpus("sweep") {
        let text = String::from_utf8(seed).unwrap();
        if let Err(e) = SweepDefinition::parse(&text, "seed.sweep.toml", &[]) {
            panic!("{e}\n{text}");
        }
    }
}

proptest! {
    #![proptest_config(proptest_config(300))]

    #[test]
    fn fuzz_sweep_file_arbitrary_text(text in "\\PC{0,300}") {
        let _ = SweepDefinition::parse(&text, "fuzz.sweep.toml", &[]);
    }

    #[test]
    fn fuzz_sweep_file_mutated_corpus(seed in any::<prop::sample::Index>(), edits in edits()) {
        let seeds = corpus("sweep");
        let bytes = mutate(&seeds[seed.index(seeds.len())], &edits);
        let _ = SweepDefinition::parse(&String::from_utf8_lossy(&bytes), "fuzz.sweep.toml", &[]);
    }
}
