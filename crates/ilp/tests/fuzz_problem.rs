//! The bounded fuzz target of the problem-file reader, on mutants of the
//! repository's problem files (the mutator is the scene loaders', see
//! crates/trace/tests/fuzz/mod.rs): `Problem::parse` must not panic or hang, and a
//! problem it accepts is bound to its scene (`Binding::new`) without panic.
//!
//! `INVLIGHT_FUZZ_CASES=N` runs N cases (default 300).

#[path = "../../trace/tests/fuzz/mod.rs"]
mod fuzz;

use invlight_ilp::{Binding, Problem};
use invlight_scene::{LoadOptions, load};
use std::path::Path;

#[test]
fn fuzz_problem() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilp");
    let scene = load(&dir.join("lamp-room.gltf"), &LoadOptions::default()).unwrap();
    let samples: Vec<Vec<u8>> = ["lamp-room.xml", "appendix-d.xml"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    let path = dir.join("mutant.xml");
    fuzz::run("problem", &samples, |bytes| {
        let text = String::from_utf8_lossy(bytes);
        let Ok(problem) = Problem::parse(&path, &text) else {
            return false;
        };
        let mut scene = scene.clone();
        let _ = Binding::new(&problem, &mut scene);
        true
    });
}
