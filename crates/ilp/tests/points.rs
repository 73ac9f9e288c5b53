//! The search judges a uniformity at EN 12464-1's points, not by cell means: a lamp
//! 0.9 m over the middle of a black 3 m × 1 m floor read on 1 m cells has U0 0.669 by
//! cell means and 0.562 at the cells' centres (closed forms), so `minUniformity="0.6"`
//! holds by cell means and fails at the points; the constraint's default decides it as
//! failed.

use invlight_ilp::{Bound, Constraint, Feasibility, Grid, GridValues, Side, Spacing, SurfaceRef};
use invlight_photon::{
    Components, Estimator, GridRequest, Request, SurfaceGrid, TraceSettings, measure_with,
};
use invlight_scene::{Light, LightKind, Mat4, Material, Mesh, Scene, Vec3};
use invlight_stats::Confidence;
use invlight_trace::Accel;

fn floor_under_a_lamp() -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let floor = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(3.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ],
        black,
    ));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: Vec3::new(1.5, 0.5, 0.9),
            intensity: Vec3::splat(100.0),
        },
    });
    scene
}

#[test]
fn a_layout_uniform_by_cell_means_but_not_at_the_points_is_infeasible() {
    let scene = floor_under_a_lamp();
    let accel = Accel::new(&scene);
    let floor = scene.surface("Floor").unwrap();
    let grid = SurfaceGrid::new(&scene, floor, 1.0).unwrap();
    assert_eq!((grid.columns, grid.rows), (3, 1));
    let components = Components::one(&scene);
    let z = Confidence::DEFAULT.z_one_sided();
    let judge = |values: GridValues| {
        let constraint = Constraint {
            surface: SurfaceRef {
                name: "Floor".into(),
                side: Side::Front,
            },
            bound: Bound::MinUniformity(
                0.6,
                Grid {
                    spacing: Spacing::Metres(1.0),
                    values,
                },
            ),
            line: 1,
            maintenance_factor: 1.0,
            from_task: None,
            average_over: None,
        };
        let request = Request {
            surfaces: &[floor],
            grids: vec![GridRequest {
                target: 0,
                side: Side::Front,
                grid: grid.clone(),
                values: constraint.bound.grid().unwrap().values,
            }],
            components: &components,
            estimator: Estimator::Connected,
            keep_groups: false,
            observers: Vec::new(),
        };
        let settings = TraceSettings {
            photons: 200_000,
            seed: 1,
            ..TraceSettings::default()
        };
        let m = measure_with(&scene, &accel, &request, &settings, None);
        let u0 = m.grids[0].uniformity(&[1.0]).u0;
        (u0, constraint.verdict(&u0, z))
    };
    let (points, at_points) = judge(Grid::default().values);
    let (means, by_means) = judge(GridValues::CellMeans);
    assert!((points.mean - 0.5618).abs() < 1e-3, "{points:?}");
    assert!(
        (means.mean - 0.6685).abs() < 4.0 * means.std_error,
        "{means:?}"
    );
    assert_eq!(by_means, Feasibility::Feasible, "{means:?}");
    assert_eq!(at_points, Feasibility::Infeasible, "{points:?}");
}
