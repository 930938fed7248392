//! Fuzzing the model parser and the expression parser: arbitrary text and mutations of the
//! seed corpus (`fuzz/corpus/model`) give a model or a typed error, never a panic. CI runs a few
//! hundred cases; `PROPTEST_CASES=100000 cargo test --release -p tumble-model fuzz_` runs more.

use std::path::Path;

use proptest::prelude::*;
use tumble_model::Model;
use tumble_model::expr::Graph;
use tumble_model::expr::parse::{Scope, parse};

#[path = "../../../../fuzz/support.rs"]
mod support;

use support::{corpus, edits, mutate};

fn origin() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus/model/fuzz.toml")
        .display()
        .to_string()
}

fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig::with_cases(cases)
}

struct Any;

impl Scope for Any {
    fn resolve(&self, name: &str, graph: &mut Graph) -> Option<tumble_model::expr::Id> {
        (name.len() == 1).then(|| graph.input(u32::from(name.as_bytes()[0] % 8)))
    }
    fn names(&self) -> Vec<String> {
        vec!["a single letter".into()]
    }
}

#[test]
fn fuzz_corpus_models_parse() {
    for seed in corpus("model") {
        let text = String::from_utf8(seed).unwrap();
        if let Err(e) = Model::parse(&text, &origin()) {
            panic!("{e}\n{text}");
        }
    }
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn fuzz_model_arbitrary_text(text in "\\PC{0,300}") {
        let _ = Model::parse(&text, &origin());
    }

    #[test]
    fn fuzz_model_mutated_corpus(seed in any::<prop::sample::Index>(), edits in edits()) {
        let seeds = corpus("model");
        let bytes = mutate(&seeds[seed.index(seeds.len())], &edits);
        if let Ok(model) = Model::parse(&String::from_utf8_lossy(&bytes), &origin()) {
            let _ = tumble_model::ModelScene::new(model);
        }
    }

    #[test]
    fn fuzz_expression_arbitrary_text(text in "[-+*/^(),.0-9a-z ]{0,200}") {
        let mut g = Graph::default();
        if let Ok(id) = parse(&text, &mut g, &Any) {
            let _ = g.eval(id, &[0.5; 8]);
            let _ = g.diff(id, 0);
        }
    }
}
