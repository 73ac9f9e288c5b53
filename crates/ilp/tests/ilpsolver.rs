//! ILPSolver's own Cornell-box problems (the thesis' §5.3.1 and §5.3.2, bundled as
//! `examples/cornell-cone` and `examples/cornell-light`) against its `cornell.dae`.

use glam::DVec3;
use invlight_ilp::{
    Binding, Comparison, Domain, Observer, PhotonEvaluator, Problem, Record, Search, Standing,
    VariableValue, compare,
};
use invlight_scene::LoadOptions;
use std::path::PathBuf;

fn problem(example: &str) -> Problem {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(example)
        .join("problem.xml");
    Problem::read(&path).unwrap()
}

/// Each problem binds with one warning — the object is authored away from vertex A, so
/// P is not where it is — and reports its anchor: at the start, where the file put it.
/// The offsets are the cone's and the panel's authored centres from vertex A
/// (`tools/check_examples.py` uses the same).
#[test]
fn cornell_problems_bind_to_cornell_dae() {
    for (example, kind, offset) in [
        (
            "cornell-cone",
            "objectInSurface",
            DVec3::new(-0.752, 0.850, 0.0),
        ),
        (
            "cornell-light",
            "lightInSurface",
            DVec3::new(2.741, -3.607, 0.0),
        ),
    ] {
        let mut problem = problem(example);
        let mut scene = problem
            .load_scene(&LoadOptions::default(), None, None, &[])
            .unwrap();
        let b = Binding::new(&problem, &mut scene).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(b.warnings.len(), 1, "{:?}", b.warnings);
        assert!(
            b.warnings[0].to_string().contains("anchor=\"centre\""),
            "{}",
            b.warnings[0]
        );
        assert_eq!(b.specs[0].kind.name(), kind);
        let VariableValue::Position { point, anchor } = b.values(&b.initial)[0] else {
            panic!("a position")
        };
        let Domain::Parallelogram(r) = &b.space.variables()[0].domain else {
            panic!("a parallelogram")
        };
        assert_eq!(point, r.a, "the initial configuration puts P at vertex A");
        let off = anchor - point;
        assert!(
            (off.x - offset.x).abs() < 2e-3 && (off.y - offset.y).abs() < 2e-3,
            "{example}: anchor − P = {off}"
        );
        assert!(b.leaves_scene(&b.initial).is_none(), "authored inside");
        assert_eq!(scene.surfaces[b.reading.surfaces[0]].name, "Cone");
    }
}

/// A small search on each problem moves from where it started to a configuration that
/// is better than the start at the problem's confidence (eq. 3.7), keeps its members
/// pairwise indistinguishable, and reports every evaluation it makes.
#[test]
fn cornell_problems_improve_on_their_start_with_a_small_budget() {
    struct Log(Vec<Record>);
    impl Observer for Log {
        fn evaluated(&mut self, r: &Record, _: Standing<'_>, _: bool) -> std::io::Result<()> {
            self.0.push(r.clone());
            Ok(())
        }
    }
    for example in ["cornell-cone", "cornell-light"] {
        let mut problem = problem(example);
        problem.max_iterations = 60;
        problem.photons = 8192;
        let mut scene = problem
            .load_scene(&LoadOptions::default(), None, None, &[])
            .unwrap();
        let b = Binding::new(&problem, &mut scene).unwrap();
        let mut search = Search::new(&b.space, problem.settings(), &b.initial);
        let mut eval = PhotonEvaluator::new(&b, scene, problem.seed, 16, problem.photons);
        let mut log = Log(Vec::new());
        search.run(&mut eval, &mut log).unwrap();
        assert_eq!(log.0.len() as u64, search.evaluations());
        let start = log.0.iter().find(|r| r.iteration == 0).unwrap();
        let z = problem.confidence.z();
        let best = search.isoc().best_first()[0];
        assert_eq!(
            compare(&best.estimate, &start.evaluation.goal, z),
            Comparison::Better,
            "{example}: best {:?} against the start {:?}",
            best.estimate,
            start.evaluation.goal
        );
        for a in search.isoc().members() {
            for m in search.isoc().members() {
                assert_eq!(
                    compare(&a.estimate, &m.estimate, z),
                    Comparison::Indistinguishable
                );
            }
        }
    }
}
