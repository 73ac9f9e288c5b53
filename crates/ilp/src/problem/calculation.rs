//! A problem file's calculation surfaces: `<calculationSurface surface="…"/>` and
//! `<workplane id="…" height="…" border="…" floor="…"/>` under `<scene>`, beside
//! `<luminaire>`, read into an [`invlight_scene::Calculation`] that
//! [`super::Problem::load_scene`] puts on the scene ([`Scene::set_calculation`]): the
//! named surfaces, and the rectangles built over the floor, receive light without
//! touching it.

use super::{Node, Reader};
use crate::Diagnostic;
use invlight_scene::{Calculation, CalculationSurface, Workplane};

/// The elements of `<scene>` this file reads.
pub(super) const ELEMENTS: [&str; 2] = ["calculationSurface", "workplane"];

impl Reader<'_, '_> {
    /// `<scene>`'s `<calculationSurface>` and `<workplane>` children, in file order
    /// within each kind (the workplanes are built first, so a `<calculationSurface>`
    /// may name one).
    pub(super) fn calculation(&self, scene: Node) -> Result<Calculation, Diagnostic> {
        let mut out = Calculation::default();
        for e in self.elements(scene) {
            let origin = Some((self.path.to_path_buf(), self.line(e)));
            match e.tag_name().name() {
                "calculationSurface" => {
                    self.check_attributes(e, &["surface"]);
                    out.surfaces.push(CalculationSurface {
                        surface: self.required(e, "surface")?,
                        origin,
                    });
                }
                "workplane" => {
                    self.check_attributes(e, &["id", "height", "border", "floor"]);
                    const EXAMPLE: &str = "<workplane id=\"Task\" height=\"0.85\" border=\"0.5\"/>";
                    let height = self
                        .real(
                            e,
                            "height",
                            "a height above the floor in metres (e.g. 0.85)",
                        )?
                        .ok_or_else(|| {
                            self.error(
                                e,
                                "<workplane> needs 'height', its height above the floor in metres",
                            )
                            .with_hint(format!("for example {EXAMPLE}"))
                        })?;
                    if height <= 0.0 || height as f32 > f32::MAX {
                        return Err(self.error(
                            e,
                            format!("'height' of <workplane> is {height}, expected a positive height above the floor in metres (e.g. 0.85)"),
                        ));
                    }
                    let border = self
                        .real(e, "border", "a band along the walls in metres (e.g. 0.5)")?
                        .unwrap_or(0.0);
                    if border < 0.0 || border as f32 > f32::MAX {
                        return Err(self.error(
                            e,
                            format!("'border' of <workplane> is {border}, expected zero or more metres along the walls (e.g. 0.5)"),
                        ));
                    }
                    let floor = match e.attribute("floor") {
                        None => None,
                        Some(_) => Some(self.required(e, "floor")?),
                    };
                    out.workplanes.push(Workplane {
                        id: self.required(e, "id")?,
                        height: height as f32,
                        border: border as f32,
                        floor,
                        origin,
                    });
                }
                _ => {}
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use crate::Problem;
    use std::path::Path;

    fn problem(scene: &str) -> Result<Problem, crate::Diagnostic> {
        let text = format!(
            "<input>\n<scene path=\"room.gltf\">\n{scene}\n</scene>\n<conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"Task\"/></objectives></input>"
        );
        Problem::parse(Path::new("/p/problem.xml"), &text)
    }

    #[test]
    fn calculation_elements_are_read_with_their_lines() {
        let p = problem(
            "<calculationSurface surface=\"Desk\"/>\n<workplane id=\"Task\" height=\"0.85\" border=\"0.5\" floor=\"Floor\"/>\n<workplane id=\"Low\" height=\"0.1\"/>",
        )
        .unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        let c = &p.scene.calculation;
        assert_eq!(c.surfaces.len(), 1);
        assert_eq!(c.surfaces[0].surface, "Desk");
        assert_eq!(c.surfaces[0].origin.as_ref().unwrap().1, 3);
        assert_eq!(c.workplanes.len(), 2);
        let w = &c.workplanes[0];
        assert_eq!((w.id.as_str(), w.height, w.border), ("Task", 0.85, 0.5));
        assert_eq!(
            (w.floor.as_deref(), w.origin.as_ref().unwrap().1),
            (Some("Floor"), 4)
        );
        assert_eq!(
            (c.workplanes[1].border, c.workplanes[1].floor.as_deref()),
            (0.0, None)
        );
    }

    #[test]
    fn calculation_mistakes_name_the_line() {
        for (bad, says) in [
            ("<calculationSurface/>", "needs a non-empty 'surface'"),
            ("<workplane id=\"Task\"/>", "needs 'height'"),
            (
                "<workplane id=\"Task\" height=\"-1\"/>",
                "expected a positive height",
            ),
            (
                "<workplane id=\"Task\" height=\"0.8\" border=\"-0.1\"/>",
                "zero or more metres",
            ),
            ("<workplane height=\"0.8\"/>", "needs a non-empty 'id'"),
            (
                "<workplane id=\"T\" height=\"0.8\" floor=\"\"/>",
                "non-empty 'floor'",
            ),
        ] {
            let e = problem(bad).unwrap_err();
            assert_eq!(e.line, Some(3), "{bad}: {e}");
            assert!(e.to_string().contains(says), "{bad}: {e}");
        }
        let p = problem("<workplane id=\"T\" height=\"0.8\" hieght=\"1\"/>").unwrap();
        assert!(
            p.warnings[0].message.contains("unknown attribute 'hieght'"),
            "{:?}",
            p.warnings
        );
    }

    /// A problem over lamp-room.gltf (a 4 m × 4 m floor, Y up) with a workplane and the
    /// desk made a calculation surface, from the file at `dir`.
    fn lamp_room(dir: &Path, scene: &str) -> Problem {
        let gltf =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilp/lamp-room.gltf");
        let text = format!(
            "<input>\n<scene path=\"{}\">\n{scene}\n</scene>\n<conditions><lightInSurface id=\"Lamp\" surface=\"Ceiling__Geometry\"/></conditions><objectives><maximizeRadiance surface=\"Task\" side=\"front\"/><constraint surface=\"Desk\" minLux=\"1\"/></objectives></input>",
            gltf.display()
        );
        let path = dir.join("problem.xml");
        std::fs::write(&path, text).unwrap();
        Problem::read(&path).unwrap()
    }

    #[test]
    fn a_problem_builds_its_workplane_and_measures_it() {
        let dir = tempfile::tempdir().unwrap();
        let mut p = lamp_room(
            dir.path(),
            "<workplane id=\"Task\" height=\"0.85\" border=\"0.5\"/>\n<calculationSurface surface=\"Desk\"/>",
        );
        let mut scene = p
            .load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
            .unwrap();
        let task = scene.surface("Task").unwrap();
        let desk = scene.surface("Desk").unwrap();
        assert_eq!(scene.calculation_surfaces(), [task, desk]);
        assert!((scene.surface_area(task) - 9.0).abs() < 1e-3);
        let floor = scene.surface("Floor").unwrap();
        let level = |s: invlight_scene::SurfaceId| {
            let i = scene.surfaces[s].instances[0];
            let t = scene.world_triangles(i).next().unwrap();
            (t.corners[0].y, t.normal())
        };
        let ((task_y, up), (floor_y, _)) = (level(task), level(floor));
        assert!((task_y - floor_y - 0.85).abs() < 1e-5 && up.distance(scene.up) < 1e-6);
        let binding = crate::Binding::new(&p, &mut scene).unwrap();
        assert_eq!(binding.reading.surfaces, [task, desk]);
    }

    #[test]
    fn a_workplane_with_no_room_left_names_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let mut p = lamp_room(
            dir.path(),
            "\n<workplane id=\"Task\" height=\"0.85\" border=\"2\"/>",
        );
        let e = p
            .load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
            .unwrap_err();
        assert_eq!(e.line, Some(4), "{e}");
        assert!(e.message.contains("leaves nothing"), "{e}");
    }
}
