//! ILPSolver's own Cornell-box problems against its `cornell.dae` (shared/scenes).

use invlight_ilp::{Binding, Problem, Value};
use invlight_scene::{LoadOptions, load};
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/ilpsolver")
}

#[test]
fn cornell_problems_bind_to_cornell_dae() {
    for (file, kind) in [
        ("cornell-move-cone.xml", "objectInSurface"),
        ("cornell-move-light.xml", "lightInSurface"),
    ] {
        let problem = Problem::read(&dir().join(file)).unwrap();
        let mut scene = load(&problem.scene, &LoadOptions::default()).unwrap();
        let b = Binding::new(&problem, &mut scene).unwrap_or_else(|e| panic!("{e}"));
        assert!(b.warnings.is_empty(), "{:?}", b.warnings);
        assert_eq!(b.kinds, vec![kind]);
        // The initial configuration puts the reference point at vertex A.
        let Value::Position(p) = b.values(&b.initial)[0] else {
            panic!("a position")
        };
        let a = b.space.variables()[0].clone();
        let invlight_ilp::Domain::Rectangle(r) = a.domain else {
            panic!("a rectangle")
        };
        assert_eq!(p, r.a);
        assert_eq!(scene.surfaces[b.objective as usize].name, "Cone");
    }
}
