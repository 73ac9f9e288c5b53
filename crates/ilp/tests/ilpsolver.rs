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

#[test]
fn cornell_problems_solve_with_a_small_budget() {
    use invlight_ilp::{Isoc, Observer, PhotonEvaluator, Record, Search};
    use std::sync::atomic::AtomicBool;
    struct Count(u64);
    impl Observer for Count {
        fn evaluated(&mut self, _: &Record, _: &Isoc, _: bool) -> std::io::Result<()> {
            self.0 += 1;
            Ok(())
        }
    }
    for file in ["cornell-move-cone.xml", "cornell-move-light.xml"] {
        let mut problem = Problem::read(&dir().join(file)).unwrap();
        problem.max_iterations = 30;
        problem.photons = 8192;
        let mut scene = load(&problem.scene, &LoadOptions::default()).unwrap();
        let b = Binding::new(&problem, &mut scene).unwrap();
        let mut search = Search::new(&b.space, problem.settings(), &b.initial);
        let mut eval = PhotonEvaluator::new(&b, scene, problem.seed, 16);
        let mut count = Count(0);
        search
            .run(&mut eval, &mut count, &AtomicBool::new(false))
            .unwrap();
        assert_eq!(count.0, search.evaluations());
        assert!(!search.isoc().members().is_empty(), "{file}");
        let (_, photons) = eval.work();
        assert!(
            photons >= 8192,
            "{file}: the initial configuration at least"
        );
    }
}
