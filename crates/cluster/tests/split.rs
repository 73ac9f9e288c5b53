//! A trace shared by K ranks gives the same bits as one process: ranks are
//! threads here ([`Local`]), exchanging what MPI's processes would.

use invlight_cluster::Local;
use invlight_photon::{
    BLOCK_MEMORY, CHUNK, Cluster, Components, Departure, Emitters, Estimator, GridRequest,
    GridValues, Measurement, Pack, PathVisitor, PhotonTrace, Request, Side, SurfaceGrid,
    TraceSettings, measure_across, measure_more, measure_with, trace_chunks, trace_shared,
};
use invlight_scene::{Light, LightKind, Mat4, Material, Mesh, Rgb, Scene, Vec3};
use invlight_trace::{Accel, Interaction};

/// A grey floor and a grey ceiling lit by two lamps kept apart: photons bounce, reach
/// both targets on both sides, and spread over the floor's grid.
fn room() -> Scene {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.7)));
    let quad = |z: f32| {
        [
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(1.0, -1.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(-1.0, 1.0, z),
        ]
    };
    let floor = scene.add_mesh(Mesh::quad(quad(0.0), grey));
    let ceiling = scene.add_mesh(Mesh::quad(quad(2.0), grey));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene.add_instance("Ceiling", ceiling, Mat4::IDENTITY);
    for (name, x) in [("Left", -0.5), ("Right", 0.6)] {
        scene.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: name.into(),
            kind: LightKind::Point {
                position: Vec3::new(x, 0.2, 1.5),
                intensity: Vec3::ONE,
            },
        });
    }
    scene
}

/// Runs `each` on every rank of a K-rank [`Local`] job, each on its own thread, and
/// returns what each gave, rank 0 first, with the words the ranks sent.
fn on_ranks<T: Send>(k: usize, each: impl Fn(&Local) -> T + Sync) -> (Vec<T>, u64) {
    let ranks = Local::ranks(k);
    let each = &each;
    let out = std::thread::scope(|s| {
        let handles: Vec<_> = ranks.iter().map(|r| s.spawn(move || each(r))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    (out, ranks[0].words_sent())
}

#[test]
fn a_measurement_shared_by_k_ranks_has_the_bits_of_one_process() {
    let scene = room();
    let accel = Accel::new(&scene);
    let targets = [
        scene.surface("Floor").unwrap(),
        scene.surface("Ceiling").unwrap(),
    ];
    let mut components = Components::new(&scene, 2);
    components.set_light(scene.light("Right").unwrap(), 1);
    let grid = SurfaceGrid::new(&scene, targets[0], 0.5).unwrap();
    let request = Request {
        surfaces: &targets,
        grids: vec![GridRequest {
            target: 0,
            side: Side::Front,
            grid,
            values: GridValues::Points,
        }],
        components: &components,
        estimator: Estimator::Connected,
        keep_groups: true,
        observers: Vec::new(),
    };
    // Seven whole chunks and a part of one: the ranks' shares are uneven, and with eight
    // ranks some trace nothing.
    let settings = TraceSettings {
        photons: 7 * CHUNK + 640,
        seed: 11,
        ..TraceSettings::default()
    };
    let alone = measure_with(&scene, &accel, &request, &settings, None);
    assert!(alone.hits.iter().all(|&h| h > 1000), "{:?}", alone.hits);
    assert!(alone.group_means(1, Side::Both, &[1.0, 1.0]).len() == 458);
    for k in [1, 2, 3, 8] {
        let (shared, words): (Vec<Measurement>, _) = on_ranks(k, |r| {
            measure_across(&scene, &accel, &request, &settings, None, r)
        });
        for (rank, m) in shared.iter().enumerate() {
            // Measurement's PartialEq compares every f64, so equal means the same bits
            // here (no NaN in a measurement).
            assert!(m == &alone, "rank {rank} of {k} differs from one process");
        }
        assert_eq!(words == 0, k == 1, "K = {k}: {words} words");
    }
}

/// The search refines a candidate from n to N photons by tracing the N − n more
/// (`measure_more`); shared by K ranks, the continuation has one process's bits too,
/// from a chunk boundary and from inside a chunk.
#[test]
fn a_continued_measurement_shared_by_k_ranks_has_the_bits_of_one_process() {
    let scene = room();
    let accel = Accel::new(&scene);
    let targets = [scene.surface("Floor").unwrap()];
    let components = Components::new(&scene, 1);
    let request = Request {
        surfaces: &targets,
        grids: Vec::new(),
        components: &components,
        estimator: Estimator::Connected,
        keep_groups: true,
        observers: Vec::new(),
    };
    let settings = |photons| TraceSettings {
        photons,
        seed: 3,
        ..TraceSettings::default()
    };
    let whole = measure_with(&scene, &accel, &request, &settings(6 * CHUNK), None);
    for first in [2 * CHUNK, CHUNK + 640] {
        let previous = measure_with(&scene, &accel, &request, &settings(first), None);
        // A continuation casts the rays of the chunks from the boundary on, counted
        // beside the previous measurement's (a chunk's rays are its own, whoever traces it).
        let before = previous.resumable_photons();
        let skipped = measure_with(&scene, &accel, &request, &settings(before), None).rays;
        let rays = previous.rays + whole.rays - skipped;
        for k in [1, 2, 3] {
            let (continued, words): (Vec<Measurement>, _) = on_ranks(k, |r| {
                measure_more(
                    &scene,
                    &accel,
                    &request,
                    &settings(6 * CHUNK),
                    None,
                    &previous,
                    r,
                )
            });
            for (rank, mut m) in continued.into_iter().enumerate() {
                assert_eq!(m.rays, rays, "rank {rank} of {k}, from {first} photons");
                m.rays = whole.rays;
                assert!(
                    m == whole,
                    "rank {rank} of {k}, from {first} photons, differs"
                );
            }
            assert_eq!(words == 0, k == 1, "K = {k}: {words} words");
        }
    }
}

/// Ranks that trace whole candidates exchange their measurements as words: read back,
/// a measurement is the same bit for bit, its grid, its kept groups and the boundary a
/// continuation starts from (a trace ending inside a chunk) included.
#[test]
fn a_packed_measurement_reads_back_the_same() {
    let scene = room();
    let accel = Accel::new(&scene);
    let targets = [
        scene.surface("Floor").unwrap(),
        scene.surface("Ceiling").unwrap(),
    ];
    let mut components = Components::new(&scene, 2);
    components.set_light(scene.light("Right").unwrap(), 1);
    let grid = SurfaceGrid::new(&scene, targets[0], 0.5).unwrap();
    for keep_groups in [true, false] {
        let request = Request {
            surfaces: &targets,
            grids: vec![GridRequest {
                target: 0,
                side: Side::Back,
                grid: grid.clone(),
                values: GridValues::Points,
            }],
            components: &components,
            estimator: Estimator::Connected,
            keep_groups,
            observers: Vec::new(),
        };
        for photons in [2 * CHUNK, 2 * CHUNK + 640] {
            let settings = TraceSettings {
                photons,
                seed: 4,
                ..TraceSettings::default()
            };
            let m = measure_with(&scene, &accel, &request, &settings, None);
            let mut words = Vec::new();
            m.pack(&mut words);
            let mut words = words.into_iter();
            let back = Measurement::unpack(&request, &mut words);
            assert!(back == m, "{photons} photons, groups kept: {keep_groups}");
            assert_eq!(words.next(), None, "every word read");
            assert_eq!(back.resumable_photons(), m.resumable_photons());
        }
    }
}

/// A visitor that says it is large, so that a block holds one chunk per rank and a
/// trace takes many exchanges, and that records the order the fold sees its chunks in.
#[derive(Default)]
struct Large {
    arrivals: u64,
    lumens: f64,
    groups: u64,
}

impl PathVisitor for Large {
    fn arrive(&mut self, _: &Interaction, _: Vec3, power: Rgb, _: u32, _: &Departure) {
        self.arrivals += 1;
        self.lumens += power.x as f64;
    }
    fn escape(&mut self, _: Rgb) {}
    fn end_group(&mut self) {
        self.groups += 1;
    }
    fn bytes(&self) -> usize {
        BLOCK_MEMORY
    }
}

impl Pack for Large {
    fn pack(&self, out: &mut Vec<u64>) {
        out.extend([self.arrivals, self.lumens.to_bits(), self.groups]);
    }
    fn unpack(&mut self, words: &mut dyn Iterator<Item = u64>) {
        self.arrivals = words.next().unwrap();
        self.lumens = f64::from_bits(words.next().unwrap());
        self.groups = words.next().unwrap();
    }
}

#[test]
fn chunks_reach_the_fold_in_chunk_order_over_many_exchanges() {
    let scene = room();
    let accel = Accel::new(&scene);
    let emitters = Emitters::new(&scene);
    let settings = TraceSettings {
        photons: 10 * CHUNK + 100,
        seed: 3,
        ..TraceSettings::default()
    };
    let mut alone = Vec::new();
    let trace = PhotonTrace {
        scene: &scene,
        accel: &accel,
        emitters: &emitters,
        settings: &settings,
    };
    let alone_rays = trace_chunks(
        trace,
        Large::default,
        |v| alone.push((v.arrivals, v.lumens.to_bits(), v.groups)),
        None,
    );
    assert_eq!(alone.len(), 11);
    assert_eq!(alone.last().unwrap().2, 2, "100 photons end two groups");
    let shown = std::sync::Mutex::new(Vec::new());
    for k in [2, 3, 4] {
        let (folds, _) = on_ranks(k, |r| {
            let mut seen = Vec::new();
            let report = |done: u64| {
                if r.rank() == 0 {
                    shown.lock().unwrap().push(done);
                }
            };
            let rays = trace_shared(
                trace,
                Large::default,
                |v| seen.push((v.arrivals, v.lumens.to_bits(), v.groups)),
                Some(&report),
                r,
            );
            (seen, rays)
        });
        for (rank, (seen, rays)) in folds.iter().enumerate() {
            assert_eq!(seen, &alone, "rank {rank} of {k}");
            assert_eq!(*rays, alone_rays, "rank {rank} of {k}");
        }
        // One exchange per block of K chunks; progress after each, to the last photon.
        let shown = std::mem::take(&mut *shown.lock().unwrap());
        assert_eq!(shown.len() as u64, 11u64.div_ceil(k as u64), "K = {k}");
        assert_eq!(shown.last(), Some(&settings.photons));
    }
}
