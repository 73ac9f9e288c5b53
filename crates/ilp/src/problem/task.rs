//! `<task name="office" surface="Task"/>` in `<objectives>`: a task of EN 12464-1's
//! schedule stated once, as the standard states it, instead of as constraints written
//! out by hand. It asks the task area for its maintained Ēm and its U0 (two
//! constraints, read with the file), and builds the areas the standard judges around
//! it — the immediate surrounding, the background, the walls and the ceiling
//! ([`invlight_scene::Scene::add_task_areas`]) — as calculation surfaces when the scene
//! is loaded, each with its own Ēm and U0 ([`AreaKind::required`]) as constraints of the
//! search, and where the task has an Ēz (`ez`, else the table's), the cylindrical
//! illuminance over the task area and its surrounding at a seated eye's height
//! ([`invlight_scene::Scene::add_cylindrical_area`]; `ezHeight` for another) as one
//! more. The figures are the standard's ([`invlight_scene::en12464`]); the file's
//! `maintenanceFactor` makes every Ēm a maintained value, as for any `minLux`.

use super::{Node, Problem, Reader};
use crate::Diagnostic;
use crate::intention::{Bound, Constraint, FromTask, Grid, Side, SurfaceRef};
use invlight_scene::en12464::{TASKS, Task, task};
use invlight_scene::{AreaKind, Scene, TaskArea};

/// A `<task>`: what its task area must receive and which areas around it are judged.
#[derive(Debug, Clone, PartialEq)]
pub struct TaskSpec {
    /// The task of the table, when `name` gave one.
    pub task: Option<Task>,
    /// The task area, `side` counted (default `front`: EN 12464-1's illuminance on a
    /// horizontal task area is the light arriving on its upper face).
    pub surface: SurfaceRef,
    /// Required maintained Ēm, lx: `em`, else the task's.
    pub em: Option<f64>,
    /// Required U0: `u0`, else the task's.
    pub u0: Option<f64>,
    /// The UGR limit every observer of the problem is held to: `ugrL`, else the
    /// task's UGR_L (none where the table's source gives none).
    pub ugr_l: Option<f64>,
    /// Required maintained cylindrical illuminance Ēz, lx: `ez`, else the task's
    /// (none where the table's source gives none).
    pub ez: Option<f64>,
    /// The height Ēz is asked at above the floor, m: `ezHeight`, else a seated eye's.
    pub ez_height: f64,
    /// The task area's grid for U0.
    pub grid: Grid,
    /// The areas built around it (`areas`, default all).
    pub areas: Vec<AreaKind>,
    /// The areas as [`Problem::load_scene`] built them on the scene (empty before it):
    /// `invlight map` judges these rather than building them twice.
    pub built: Vec<TaskArea>,
    /// Line of its element.
    pub line: u32,
}

impl TaskSpec {
    /// The name its constraints are credited to: the table's, or `task`.
    pub(super) fn name(&self) -> String {
        self.task.map_or("task".into(), |t| t.name.into())
    }

    fn constraint(&self, surface: SurfaceRef, bound: Bound, area: Option<AreaKind>) -> Constraint {
        Constraint {
            surface,
            bound,
            line: self.line,
            maintenance_factor: 1.0,
            from_task: Some(FromTask {
                task: self.name(),
                area,
            }),
            average_over: None,
        }
    }

    /// The task area's own constraints: Ēm (maintained, the mean of its grid's points
    /// as EN 12464-1 takes it) and U0 on that grid.
    pub(super) fn task_constraints(&self) -> Vec<Constraint> {
        let em = self.em.map(Bound::MinLux);
        let u0 = self.u0.map(|u| Bound::MinUniformity(u, self.grid));
        [em, u0]
            .into_iter()
            .flatten()
            .map(|b| Constraint {
                average_over: Some(self.grid),
                ..self.constraint(self.surface.clone(), b, None)
            })
            .collect()
    }
}

/// The `areas` words, in the order they are built.
const AREAS: [(&str, AreaKind); 5] = [
    ("surrounding", AreaKind::Surrounding),
    ("background", AreaKind::Background),
    ("walls", AreaKind::Wall),
    ("ceiling", AreaKind::Ceiling),
    ("cylindrical", AreaKind::Cylindrical),
];

impl Reader<'_, '_> {
    /// A `<task>`; `workplanes` are the ids of the scene's `<workplane>`s, the only one
    /// of which is the task area when `surface` is left out.
    pub(super) fn task(&self, t: Node, workplanes: &[String]) -> Result<TaskSpec, Diagnostic> {
        self.check_attributes(
            t,
            &[
                "name", "surface", "side", "em", "u0", "ugrL", "ez", "ezHeight", "grid", "areas",
            ],
        );
        const EXAMPLE: &str = "<task name=\"office\" surface=\"Task\"/>";
        let names = || TASKS.iter().map(|t| t.name).collect::<Vec<_>>().join(", ");
        let named = match t.attribute("name").map(str::trim) {
            None => None,
            Some(n) => Some(*task(n).ok_or_else(|| {
                self.error(
                    t,
                    format!(
                        "'name' of <task> is '{n}', expected a task of EN 12464-1's table: {}",
                        names()
                    ),
                )
                .with_hint("for another task give its figures: em=\"…\" u0=\"…\"")
            })?),
        };
        let em = self.lux(t, "em")?.or(named.map(|n| n.em));
        let u0 = self.unit(t, "u0", 0.0, 1.0)?.or(named.map(|n| n.u0));
        let ugr_l = match self.real(t, "ugrL", "a UGR limit (CIE 117's scale: 10 to 30)")? {
            Some(u) if !(u > 0.0 && u <= 40.0) => {
                return Err(self.error(
                    t,
                    format!("'ugrL' of <task> is {u}, expected a UGR limit in (0, 40] (CIE 117's scale runs from 10 to 30)"),
                ));
            }
            u => u.or(named.and_then(|n| n.ugr_l)),
        };
        let ez = self.lux(t, "ez")?.or(named.and_then(|n| n.ez));
        let ez_height = match self.real(t, "ezHeight", "a height above the floor in metres")? {
            Some(h) if !(h > 0.0 && h < 10.0) => {
                return Err(self
                    .error(t, format!("'ezHeight' of <task> is {h}, expected a height above the floor in metres"))
                    .with_hint("EN 12464-1 asks Ez 1.2 m above the floor for seated people, 1.6 m for standing ones"));
            }
            h => h.unwrap_or(invlight_scene::SEATED),
        };
        if named.is_none() && em.is_none() && u0.is_none() {
            return Err(self
                .error(t, format!("<task> needs 'name', a task of EN 12464-1's table ({}), or its figures 'em' and 'u0'", names()))
                .with_hint(format!("for example {EXAMPLE}")));
        }
        let name = match (t.attribute("surface"), workplanes) {
            (Some(_), _) => self.required(t, "surface")?,
            (None, [only]) => only.clone(),
            (None, _) => {
                return Err(self
                    .error(t, "<task> needs 'surface', the task area it asks for")
                    .with_hint(format!(
                        "a <workplane> in <scene> builds one; with a single workplane 'surface' may be left out (for example {EXAMPLE})"
                    )));
            }
        };
        let side = match t.attribute("side") {
            None => Side::Front,
            Some(_) => self.surface_ref(t)?.side,
        };
        let areas = match t.attribute("areas").map(str::trim) {
            None | Some("all") => AREAS.iter().map(|&(_, k)| k).collect(),
            Some("none") => Vec::new(),
            Some(list) => {
                let mut kinds = Vec::new();
                for word in list.split_whitespace() {
                    let Some(&(_, kind)) = AREAS.iter().find(|(w, _)| *w == word) else {
                        let words: Vec<&str> = AREAS.iter().map(|(w, _)| *w).collect();
                        return Err(self.error(
                            t,
                            format!(
                                "'areas' of <task> names '{word}', expected all, none, or some of: {}",
                                words.join(", ")
                            ),
                        ));
                    };
                    if !kinds.contains(&kind) {
                        kinds.push(kind);
                    }
                }
                AREAS
                    .iter()
                    .map(|&(_, k)| k)
                    .filter(|k| kinds.contains(k))
                    .collect()
            }
        };
        Ok(TaskSpec {
            task: named,
            surface: SurfaceRef { name, side },
            em,
            u0,
            ugr_l,
            ez,
            ez_height,
            grid: self.grid(t)?,
            areas,
            built: Vec::new(),
            line: self.line(t),
        })
    }
}

impl Problem {
    /// Builds each `<task>`'s areas on `scene` as calculation surfaces and states their
    /// requirements as constraints, after the file's own (those of an earlier load are
    /// replaced). Called by [`Problem::load_scene`], so a loaded problem's constraints
    /// are the whole statement its search and its outputs read.
    pub(super) fn build_task_areas(&mut self, scene: &mut Scene) -> Result<(), Diagnostic> {
        self.constraints
            .retain(|c| c.from_task.as_ref().is_none_or(|t| t.area.is_none()));
        for spec in self.tasks.iter_mut().filter(|t| !t.areas.is_empty()) {
            let at = |message: String| Diagnostic::at_line(&self.path, spec.line, message);
            let name = &spec.surface.name;
            let Some(surface) = scene.surface(name) else {
                return Err(at(format!(
                    "<task>: no surface named '{name}', expected the task area"
                ))
                .with_hint(invlight_scene::known_names(
                    scene.surfaces.iter().map(|s| s.name.as_str()),
                    "surfaces",
                )));
            };
            let planar: Vec<AreaKind> = spec
                .areas
                .iter()
                .copied()
                .filter(|&k| k != AreaKind::Cylindrical)
                .collect();
            let mut areas = scene
                .add_task_areas(&self.scene.path, surface, &planar)
                .map_err(|e| {
                    at(format!("<task>: {}", e.message)).with_hint(
                        "make the task area one horizontal plane (a <workplane>), or give areas=\"none\" to ask the task area alone",
                    )
                })?;
            let cylindrical = match spec.ez {
                Some(ez) if spec.areas.contains(&AreaKind::Cylindrical) => Some(ez),
                _ => None,
            };
            let ez = match cylindrical {
                Some(ez) => {
                    let area = scene
                        .add_cylindrical_area(&self.scene.path, surface, spec.ez_height)
                        .map_err(|e| {
                            at(format!("<task>: {}", e.message)).with_hint(
                                "give ezHeight, the eye's height above the floor (1.2 m seated, 1.6 m standing), or leave 'cylindrical' out of areas (areas=\"surrounding background walls ceiling\")",
                            )
                        })?;
                    let surface = SurfaceRef {
                        name: area.name.clone(),
                        side: Side::Front,
                    };
                    let lux = spec.constraint(surface, Bound::MinLux(ez), Some(area.kind));
                    areas.push(area);
                    Some(lux.maintained(self.maintenance_factor))
                }
                None => None,
            };
            spec.built = areas.clone();
            for a in areas {
                let Some((em, u0)) = a.kind.required(spec.em, spec.task.as_ref()) else {
                    continue;
                };
                let surface = SurfaceRef {
                    name: a.name,
                    side: Side::Front,
                };
                let grid = a.kind.spacing().map_or(Grid::AUTO, Grid::metres);
                let mut lux = spec.constraint(surface.clone(), Bound::MinLux(em), Some(a.kind));
                lux.average_over = Some(grid);
                let lux = lux.maintained(self.maintenance_factor);
                let even = spec.constraint(surface, Bound::MinUniformity(u0, grid), Some(a.kind));
                self.constraints.extend([lux, even]);
            }
            self.constraints.extend(ez);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The test room with one workplane, `objectives` inside `<objectives>`.
    fn problem(dir: &Path, objectives: &str) -> Result<Problem, Diagnostic> {
        let gltf =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilp/lamp-room.gltf");
        let text = format!(
            "<input>\n<scene path=\"{}\">\n<workplane id=\"Task\" height=\"0.85\" border=\"0.5\"/>\n</scene>\n<conditions><lightInSurface id=\"Lamp\" surface=\"Ceiling__Geometry\"/></conditions>\n<objectives maintenanceFactor=\"0.8\">\n<minimizePower/>\n{objectives}\n</objectives></input>",
            gltf.display()
        );
        let path = dir.join("problem.xml");
        std::fs::write(&path, text).unwrap();
        Problem::read(&path)
    }

    fn load(p: &mut Problem) -> Scene {
        p.load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
            .unwrap()
    }

    #[test]
    fn a_named_task_asks_every_area_what_the_standard_does() {
        let dir = tempfile::tempdir().unwrap();
        // The test room is 1.2 m high: Ēz at 0.9 m.
        let mut p = problem(dir.path(), "<task name=\"office\" ezHeight=\"0.9\"/>").unwrap();
        // Read: the task area's own two, on the only workplane.
        assert_eq!(p.constraints.len(), 2);
        let scene = load(&mut p);
        let asked: Vec<(String, &'static str, f64)> = p
            .constraints
            .iter()
            .map(|c| {
                let what = match c.bound {
                    Bound::MinUniformity(..) => "U0",
                    _ => "Em",
                };
                let limit = match c.bound {
                    Bound::MinUniformity(u, _) => u,
                    _ => c.maintained_limit(),
                };
                (c.surface.name.clone(), what, limit)
            })
            .collect();
        let has = |name: &str, what: &str, limit: f64| {
            asked
                .iter()
                .any(|(n, w, l)| n == name && *w == what && (l - limit).abs() < 1e-9)
        };
        assert!(
            has("Task", "Em", 500.0) && has("Task", "U0", 0.6),
            "{asked:?}"
        );
        assert!(has("immediate surrounding", "Em", 300.0), "{asked:?}");
        assert!(has("immediate surrounding", "U0", 0.4), "{asked:?}");
        assert!(
            has("ceiling", "Em", 50.0) && has("ceiling", "U0", 0.1),
            "{asked:?}"
        );
        // Each wall named for the model's wall it stands in front of.
        for w in ["WallW", "WallN", "WallE", "WallS"] {
            assert!(has(&format!("{w} (EN 12464-1)"), "Em", 75.0), "{asked:?}");
        }
        // The office's Ēz 150 lx, over the prisms' mean: no grid, no U0.
        assert!(has("cylindrical illuminance", "Em", 150.0), "{asked:?}");
        assert!(!has("cylindrical illuminance", "U0", 0.1), "{asked:?}");
        // Every illuminance is maintained: the search holds the new installation to ÷ MF;
        // and every Ēm is the mean of its grid's points, as EN 12464-1 takes it.
        for c in p
            .constraints
            .iter()
            .filter(|c| c.bound.attribute() == "minLux")
        {
            assert!((c.bound.limit() - c.maintained_limit() / 0.8).abs() < 1e-9);
            if c.surface.name == "cylindrical illuminance" {
                assert_eq!(c.average_over, None);
                assert_eq!(
                    c.standard_name().unwrap(),
                    "EN 12464-1 office: cylindrical illuminance Ēz"
                );
                continue;
            }
            let grid = c.average_over.expect("Em over a grid");
            assert_eq!(grid.values, crate::GridValues::Points, "{}", c.surface.name);
        }
        // Each area is a calculation surface of the scene the search traces.
        for c in &p.constraints {
            let id = scene.surface(&c.surface.name).expect("built");
            assert!(
                scene.calculation_surfaces().contains(&id),
                "{}",
                c.surface.name
            );
        }
        let named = p.constraints[2].standard_name().unwrap();
        assert_eq!(named, "EN 12464-1 office: immediate surrounding Ēm");
        assert_eq!(
            p.constraints[1].standard_name().unwrap(),
            "EN 12464-1 office: task area U0"
        );
        // A second load states the areas once, not twice.
        let before = p.constraints.len();
        load(&mut p);
        assert_eq!(p.constraints.len(), before);
    }

    #[test]
    fn a_task_given_by_its_figures_and_no_areas_asks_the_task_area_alone() {
        let dir = tempfile::tempdir().unwrap();
        let mut p = problem(
            dir.path(),
            "<task surface=\"Task\" em=\"200\" u0=\"0.4\" areas=\"none\"/>",
        )
        .unwrap();
        load(&mut p);
        assert_eq!(p.constraints.len(), 2);
        assert_eq!(
            p.constraints[0].standard_name().unwrap(),
            "EN 12464-1 task: task area Ēm"
        );
        assert_eq!(p.constraints[1].surface.side, Side::Front);
    }

    #[test]
    fn a_tasks_cylindrical_illuminance_is_asked_where_it_has_an_ez() {
        let dir = tempfile::tempdir().unwrap();
        // The test room is 1.2 m high: Ēz at 0.9 m.
        let ez = |objectives: &str| {
            let objectives = objectives.replace("/>", " ezHeight=\"0.9\"/>");
            let mut p = problem(dir.path(), &objectives).unwrap();
            load(&mut p);
            p.constraints
                .iter()
                .find(|c| c.surface.name == "cylindrical illuminance")
                .map(Constraint::maintained_limit)
        };
        // The table's row, the file's own figure, and none where neither gives one or
        // the areas asked leave it out.
        assert_eq!(ez("<task name=\"classroom\"/>"), Some(150.0));
        assert_eq!(ez("<task name=\"classroom\" ez=\"200\"/>"), Some(200.0));
        assert_eq!(ez("<task name=\"filing\"/>"), None);
        assert_eq!(ez("<task name=\"office\" areas=\"walls\"/>"), None);
        assert_eq!(
            ez("<task name=\"filing\" ez=\"50\" areas=\"cylindrical\"/>"),
            Some(50.0)
        );
        // A height outside the room is refused with the line and what the standard asks.
        let mut p = problem(dir.path(), "<task name=\"office\" ezHeight=\"9\"/>").unwrap();
        let e = p
            .load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
            .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains(":8:") && text.contains("not inside the room"),
            "{text}"
        );
        assert!(
            text.contains("1.2 m") && text.contains("leave 'cylindrical' out"),
            "{text}"
        );
        let e = problem(dir.path(), "<task name=\"office\" ezHeight=\"-1\"/>").unwrap_err();
        assert!(e.to_string().contains("'ezHeight'"), "{e}");
    }

    #[test]
    fn a_task_refuses_an_unknown_name_a_bound_twice_and_an_unknown_area() {
        let dir = tempfile::tempdir().unwrap();
        let e = problem(dir.path(), "<task name=\"ofice\"/>").unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains(":8:") && text.contains("office, filing"),
            "{text}"
        );
        let e = problem(
            dir.path(),
            "<constraint surface=\"Task\" side=\"front\" minLux=\"400\"/>\n<task name=\"office\"/>",
        )
        .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("already bounds") && text.contains("line 8"),
            "{text}"
        );
        let e = problem(dir.path(), "<task name=\"office\" areas=\"walls floor\"/>").unwrap_err();
        assert!(e.to_string().contains("'floor'"), "{e}");
    }
}
