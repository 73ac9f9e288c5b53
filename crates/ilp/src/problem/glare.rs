//! Glare in `<objectives>`: the observers whose Unified Glare Rating (CIE 117) a
//! problem bounds or minimises, as EN 12464-1 bounds it by a task's UGR_L.
//!
//! - `<constraint maxUGR="19" observer="x,y,z" view="dx,dy,dz" name="pupil"?/>`: the UGR
//!   at that eye looking that way at most the limit, decided with its interval as any
//!   constraint is;
//! - `<minimizeGlare observer="x,y,z" view="dx,dy,dz" name?/>`: the goal, the least UGR
//!   there;
//! - `<observer position="x,y,z" view="dx,dy,dz" name?/>`: an observer a `<task>` holds
//!   to its UGR_L.
//!
//! A `<task>` whose row gives UGR_L (or `ugrL` on it) applies it to every observer of
//! the problem whose UGR no `maxUGR` of the file bounds already. Each observer is a
//! small calculation square at the eye facing the view, added to the scene under its
//! name when the scene is loaded ([`invlight_photon::glare::add_eye`]), on which its
//! background is traced.

use super::task::TaskSpec;
use super::{Node, Problem, Reader};
use crate::intention::{Bound, Constraint, FromTask, Goal, Side, SurfaceRef};
use invlight_photon::glare::{GlareError, Observer, add_eye, is_eye_of};
use invlight_scene::{Diagnostic, Scene, Vec3};

/// An observer of the problem: an eye, where it looks, the name its eye square takes.
#[derive(Debug, Clone, PartialEq)]
pub struct ObserverSpec {
    /// The eye square's name in the scene, and the observer's in tables.
    pub name: String,
    /// The eye and the line of sight.
    pub observer: Observer,
    /// Line of the element that first named it.
    pub line: u32,
}

impl ObserverSpec {
    /// Its eye square as an intention's surface: the front, which faces the view.
    pub fn surface(&self) -> SurfaceRef {
        SurfaceRef {
            name: self.name.clone(),
            side: Side::Front,
        }
    }
}

/// The observers read so far, each once.
#[derive(Debug, Default)]
pub(super) struct Observers {
    pub(super) specs: Vec<ObserverSpec>,
}

impl Reader<'_, '_> {
    /// Three finite numbers separated by commas, `attr` of `node`.
    fn triple(&self, node: Node, attr: &str, example: &str) -> Result<Vec3, Diagnostic> {
        let what = format!("three numbers separated by commas, e.g. {example}");
        let v = self.required(node, attr)?;
        let xs: Vec<f32> = v
            .split(',')
            .map(|x| x.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|_| {
                self.error(
                    node,
                    format!(
                        "'{attr}' of <{}> is '{v}', expected {what}",
                        node.tag_name().name()
                    ),
                )
            })?;
        match xs[..] {
            [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Vec3::new(x, y, z)),
            _ => Err(self.error(
                node,
                format!(
                    "'{attr}' of <{}> is '{v}', expected {what}",
                    node.tag_name().name()
                ),
            )),
        }
    }

    /// The observer `node` names by `at` (its eye) and `view`, and `name`: the one
    /// read before when it is the same eye looking the same way, else a new one (named
    /// `observer N` when `name` is left out).
    pub(super) fn observer_of(
        &self,
        node: Node,
        at: &str,
        observers: &mut Observers,
    ) -> Result<ObserverSpec, Diagnostic> {
        let eye = self.triple(node, at, "4.5,3.6,1.2")?;
        let view = self.triple(node, "view", "0,1,0")?;
        let observer = Observer { eye, view };
        let refused = |e: GlareError| {
            self.error(node, format!("<{}>: {e}", node.tag_name().name()))
                .with_hint("a seated eye is 1.2 m above the floor, a standing one 1.5 m; look horizontally, e.g. view=\"0,1,0\" toward +Y")
        };
        // The scene's up axis is not known yet: a view along either candidate is
        // refused when the eye square is built; here only what no axis can mend.
        if observer.view.length() == 0.0 {
            return Err(refused(GlareError::NoView));
        }
        let name = node.attribute("name").map(str::trim);
        if let Some(same) = observers.specs.iter().find(|o| o.observer == observer) {
            match name {
                Some(n) if n != same.name => {
                    return Err(self.error(
                        node,
                        format!(
                            "the observer at {at}=\"{}\" view=\"{}\" is named '{}' on line {}, and '{n}' here",
                            node.attribute(at).unwrap_or(""),
                            node.attribute("view").unwrap_or(""),
                            same.name,
                            same.line
                        ),
                    ).with_hint("leave 'name' out where the observer is named again"));
                }
                _ => return Ok(same.clone()),
            }
        }
        let name = match name {
            Some("") => return Err(self.error(node, "'name' of an observer is empty")),
            Some(n) => n.to_string(),
            None => format!("observer {}", observers.specs.len() + 1),
        };
        if let Some(other) = observers.specs.iter().find(|o| o.name == name) {
            let given = if node.attribute("name").is_some() {
                ""
            } else {
                ", the name an observer without 'name' takes by default"
            };
            return Err(self
                .error(
                    node,
                    format!(
                        "a second observer named '{name}'{given} (the first is on line {}), expected one name per eye and view",
                        other.line
                    ),
                )
                .with_hint("name each observer apart, e.g. name=\"pupil front row\""));
        }
        let spec = ObserverSpec {
            name,
            observer,
            line: self.line(node),
        };
        observers.specs.push(spec.clone());
        Ok(spec)
    }

    /// `<constraint maxUGR observer view name?>`.
    pub(super) fn ugr_constraint(
        &self,
        c: Node,
        observers: &mut Observers,
    ) -> Result<Constraint, Diagnostic> {
        self.check_attributes(c, &["maxUGR", "observer", "view", "name"]);
        let limit = self
            .real(c, "maxUGR", "a UGR limit (CIE 117's scale: 10 to 30)")?
            .unwrap_or_default();
        if !(limit > 0.0 && limit <= 40.0) {
            return Err(self
                .error(
                    c,
                    format!("'maxUGR' of <constraint> is {limit}, expected a UGR limit in (0, 40] (CIE 117's scale runs from 10 to 30)"),
                )
                .with_hint("EN 12464-1's UGR_L: 16 for technical drawing, 19 for offices and classrooms, 22 for industry"));
        }
        let spec = self.observer_of(c, "observer", observers)?;
        Ok(Constraint {
            surface: spec.surface(),
            bound: Bound::MaxUgr(limit),
            line: self.line(c),
            maintenance_factor: 1.0,
            from_task: None,
            average_over: None,
        })
    }

    /// Warns of each observer that neither the goal nor a limit rates: an `<observer>`
    /// whose tasks give no UGR_L.
    pub(super) fn warn_unrated(
        &self,
        observers: &Observers,
        goal: &Goal,
        constraints: &[Constraint],
    ) {
        for o in &observers.specs {
            let rated = constraints
                .iter()
                .any(|c| matches!(c.bound, Bound::MaxUgr(_)) && c.surface.name == o.name)
                || matches!(goal, Goal::MinimizeGlare { observer } if observer.name == o.name);
            if !rated {
                self.push_warning(
                    Diagnostic::at_line(
                        self.path,
                        o.line,
                        format!(
                            "the observer '{}' is rated by no limit: no <task> gives a UGR_L (invlight's table gives one only where its cited source does)",
                            o.name
                        ),
                    )
                    .with_hint("give the limit on the task, e.g. <task name=\"office\" ugrL=\"19\"/>, or a <constraint maxUGR=\"19\" observer=… view=…/>"),
                );
            }
        }
    }

    /// `<observer position view name?>`: an observer a `<task>`'s UGR_L bounds.
    pub(super) fn declared_observer(
        &self,
        o: Node,
        observers: &mut Observers,
    ) -> Result<(), Diagnostic> {
        self.check_attributes(o, &["position", "view", "name"]);
        self.observer_of(o, "position", observers).map(|_| ())
    }
}

/// What each `<task>` with a UGR_L asks of the observers no `maxUGR` of the file bounds:
/// the UGR at most UGR_L, credited to the task. A task without UGR_L asks nothing of
/// them.
pub(super) fn task_glare_constraints(
    tasks: &[TaskSpec],
    observers: &Observers,
    constraints: &[Constraint],
) -> Vec<Constraint> {
    let bounded = |name: &str| {
        constraints
            .iter()
            .any(|c| matches!(c.bound, Bound::MaxUgr(_)) && c.surface.name == name)
    };
    let mut out: Vec<Constraint> = Vec::new();
    for t in tasks {
        let Some(limit) = t.ugr_l else { continue };
        for o in observers.specs.iter().filter(|o| !bounded(&o.name)) {
            // Of two tasks, the stricter limit holds.
            if let Some(c) = out.iter_mut().find(|c| c.surface.name == o.name) {
                if limit < c.bound.limit() {
                    c.bound = Bound::MaxUgr(limit);
                }
                continue;
            }
            out.push(Constraint {
                surface: o.surface(),
                bound: Bound::MaxUgr(limit),
                line: t.line,
                maintenance_factor: 1.0,
                from_task: Some(FromTask {
                    task: t.name(),
                    area: None,
                }),
                average_over: None,
            });
        }
    }
    out
}

impl Problem {
    /// Adds each observer's eye square to `scene` under its name ([`add_eye`]); one
    /// already there as a calculation surface (a scene bound before) is kept.
    pub fn build_eyes(&self, scene: &mut Scene) -> Result<(), Diagnostic> {
        let bounds = scene.bounds();
        for o in &self.observers {
            let eye = o.observer.eye;
            if let Some((lo, hi)) =
                bounds.filter(|(lo, hi)| eye.cmplt(*lo).any() || eye.cmpgt(*hi).any())
            {
                return Err(Diagnostic::at_line(
                    &self.path,
                    o.line,
                    format!(
                        "the observer '{}' at ({}, {}, {}) is outside the scene, whose bounds are ({}, {}, {}) to ({}, {}, {})",
                        o.name, eye.x, eye.y, eye.z, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
                    ),
                )
                .with_hint("give the eye inside the room, in the scene's metres (EN 12464-1: 1.2 m above the floor seated)"));
            }
            if let Some(s) = scene.surface(&o.name) {
                if is_eye_of(scene, s, &o.observer) {
                    continue;
                }
                return Err(Diagnostic::at_line(
                    &self.path,
                    o.line,
                    format!(
                        "the observer '{}' has the name of a surface of the scene, expected a name of its own",
                        o.name
                    ),
                )
                .with_hint("give the observer another name=\"…\" (a surface, a workplane and a calculation surface name theirs)"));
            }
            add_eye(scene, &o.observer, &o.name).map_err(|e| {
                Diagnostic::at_line(&self.path, o.line, format!("observer '{}': {e}", o.name))
                    .with_hint("look horizontally or at a slant: UGR's position index needs a vertical plane through the line of sight")
            })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn parse(objectives: &str) -> Result<Problem, Diagnostic> {
        let text = format!(
            "<input><scene path=\"built-in-code.gltf\"><workplane id=\"Task\" height=\"0.8\"/></scene><conditions/><objectives><minimizePower/>{objectives}</objectives></input>"
        );
        Problem::parse(Path::new("/tests/problem.xml"), &text)
    }

    const PUPIL: &str = "position=\"2,1,1.2\" view=\"0,1,0\" name=\"pupil\"";

    #[test]
    fn a_tasks_ugr_limit_bounds_every_observer_no_constraint_bounds() {
        let p = parse(&format!(
            "<task name=\"office\" ugrL=\"19\"/><observer {PUPIL}/>
             <observer position=\"4,1,1.2\" view=\"0,1,0\"/>
             <constraint maxUGR=\"16\" observer=\"4,1,1.2\" view=\"0,1,0\"/>"
        ))
        .unwrap();
        let ugr: Vec<(String, f64, Option<String>)> = p
            .constraints
            .iter()
            .filter(|c| matches!(c.bound, Bound::MaxUgr(_)))
            .map(|c| (c.label(), c.bound.limit(), c.standard_name()))
            .collect();
        assert_eq!(
            ugr,
            [
                ("observer 2.maxUGR".to_string(), 16.0, None),
                (
                    "pupil.maxUGR".to_string(),
                    19.0,
                    Some("EN 12464-1 office: UGR_L".to_string())
                ),
            ]
        );
        assert_eq!(p.observers.len(), 2);
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    #[test]
    fn an_observer_no_limit_rates_is_warned_of() {
        let p = parse(&format!("<task name=\"office\"/><observer {PUPIL}/>")).unwrap();
        assert!(
            p.constraints
                .iter()
                .all(|c| !matches!(c.bound, Bound::MaxUgr(_)))
        );
        let w = &p.warnings[0];
        assert!(w.message.contains("'pupil' is rated by no limit"), "{w}");
        assert!(w.hint.as_deref().unwrap_or("").contains("ugrL"), "{w}");
    }

    #[test]
    fn bad_observers_are_refused_with_what_was_expected() {
        let cases = [
            (
                "<constraint maxUGR=\"19\" observer=\"1,2\" view=\"0,1,0\"/>",
                "'observer' of <constraint> is '1,2', expected three numbers",
            ),
            (
                "<constraint maxUGR=\"19\" observer=\"1,2,1.2\" view=\"0,0,0\"/>",
                "the view direction has no length",
            ),
            (
                "<constraint maxUGR=\"19\" observer=\"1,2,1.2\"/>",
                "needs a non-empty 'view'",
            ),
            (
                "<constraint maxUGR=\"55\" observer=\"1,2,1.2\" view=\"0,1,0\"/>",
                "expected a UGR limit in (0, 40]",
            ),
            (
                "<observer position=\"1,2,1.2\" view=\"0,1,0\" name=\"a\"/><observer position=\"1,3,1.2\" view=\"0,1,0\" name=\"a\"/>",
                "a second observer named 'a'",
            ),
            (
                "<observer position=\"1,2,1.2\" view=\"0,1,0\"/><observer position=\"1,3,1.2\" view=\"0,1,0\" name=\"observer 1\"/>",
                "a second observer named 'observer 1'",
            ),
            (
                "<observer position=\"1,3,1.2\" view=\"0,1,0\" name=\"observer 2\"/><observer position=\"1,2,1.2\" view=\"0,1,0\"/>",
                "the name an observer without 'name' takes by default",
            ),
            (
                "<task name=\"office\" ugrL=\"-3\"/>",
                "'ugrL' of <task> is -3, expected a UGR limit in (0, 40]",
            ),
        ];
        for (xml, want) in cases {
            let e = parse(xml).unwrap_err();
            assert!(e.message.contains(want), "{xml}: {e}");
        }
    }
}
