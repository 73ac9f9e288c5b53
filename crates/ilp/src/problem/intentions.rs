//! What a problem asks for, in `<objectives>`: one goal (thesis §4.2.1's
//! `maximizeRadiance`, `minimizeRadiance`, `targetRadiance`; invlight's
//! `maximizeUniformity`, `minimizePower`, `maximizeDaylightFactor`) and any number of
//! `<constraint>`s, each a surface and one bound.

use super::glare::{ObserverSpec, Observers, task_glare_constraints};
use super::task::TaskSpec;
use super::{Node, Reader};
use crate::intention::{Bound, Constraint, Goal, Grid, GridValues, Side, Spacing, SurfaceRef};
use invlight_scene::Diagnostic;

const GOALS: &[&str] = &[
    "maximizeRadiance",
    "minimizeRadiance",
    "targetRadiance",
    "maximizeUniformity",
    "minimizePower",
    "maximizeDaylightFactor",
    "minimizeGlare",
];

/// What `<objectives>` asks.
pub(super) struct Intentions {
    pub goal: Goal,
    pub goal_line: u32,
    pub constraints: Vec<Constraint>,
    pub tasks: Vec<TaskSpec>,
    pub observers: Vec<ObserverSpec>,
}

impl Reader<'_, '_> {
    /// The goal of `objectives`, with its line, its constraints in file order (a
    /// `<task>`'s on its task area after the `<constraint>`s), and its `<task>`s;
    /// `workplanes` are the scene's workplane ids, which a `<task>` may default to.
    pub(super) fn intentions(
        &self,
        objectives: Node,
        workplanes: &[String],
    ) -> Result<Intentions, Diagnostic> {
        let mut goal: Option<(Goal, u32)> = None;
        let mut unknown: Option<Node> = None;
        let mut constraints = Vec::new();
        let mut tasks: Vec<TaskSpec> = Vec::new();
        let mut observers = Observers::default();
        for o in self.elements(objectives) {
            let name = o.tag_name().name();
            if name == "task" {
                tasks.push(self.task(o, workplanes)?);
                continue;
            }
            if name == "observer" {
                self.declared_observer(o, &mut observers)?;
                continue;
            }
            if name == "constraint" {
                let c = if o.attribute("maxUGR").is_some() {
                    self.ugr_constraint(o, &mut observers)?
                } else {
                    self.constraint(o)?
                };
                if let Some(first) = constraints
                    .iter()
                    .find(|d: &&Constraint| d.label() == c.label())
                {
                    return Err(self
                        .error(
                            o,
                            format!(
                                "a second {} constraint on '{}', expected one (the first is on line {})",
                                c.bound.attribute(),
                                c.surface.name,
                                first.line
                            ),
                        )
                        .with_hint("the stricter of two bounds of one kind is the one that holds"));
                }
                constraints.push(c);
                continue;
            }
            let Some(parsed) = self.goal(o, &mut observers)? else {
                self.push_warning(self.unknown_element(
                    o,
                    "objective",
                    GOALS,
                    ", <constraint>, <task> or <observer>",
                ));
                unknown.get_or_insert(o);
                continue;
            };
            if let Some((first, line)) = &goal {
                return Err(self
                    .error(
                        o,
                        format!(
                            "a second goal <{name}>, expected one (the first is <{}> on line {line})",
                            first.element()
                        ),
                    )
                    .with_hint("state other wishes as <constraint> elements"));
            }
            goal = Some((parsed, self.line(o)));
        }
        let (goal, goal_line) = goal.ok_or_else(|| match unknown {
            // The goal the author meant is most likely the element not understood.
            Some(o) => {
                let d = self.unknown_element(o, "objective", GOALS, "");
                Diagnostic {
                    message: format!(
                        "no goal in <objectives>: <{}> is not one, expected one of: {}",
                        o.tag_name().name(),
                        GOALS.join(", ")
                    ),
                    ..d
                }
            }
            None => self.error(
                objectives,
                format!(
                    "no goal in <objectives>, expected one of: {}",
                    GOALS.join(", ")
                ),
            ),
        })?;
        for t in &tasks {
            for c in t.task_constraints() {
                if let Some(first) = constraints.iter().find(|d| d.label() == c.label()) {
                    return Err(Diagnostic::at_line(
                        self.path,
                        t.line,
                        format!(
                            "<task> asks {} of '{}', which the constraint on line {} already bounds",
                            c.bound.attribute(),
                            c.surface.name,
                            first.line
                        ),
                    )
                    .with_hint("give the figure the task should ask as em=\"…\" or u0=\"…\" on <task>, and leave out the <constraint>"));
                }
                constraints.push(c);
            }
        }
        let glare = task_glare_constraints(&tasks, &observers, &constraints);
        constraints.extend(glare);
        self.warn_unrated(&observers, &goal, &constraints);
        Ok(Intentions {
            goal,
            goal_line,
            constraints,
            tasks,
            observers: observers.specs,
        })
    }

    /// A surface reference: `surface` and `side`.
    pub(super) fn surface_ref(&self, node: Node) -> Result<SurfaceRef, Diagnostic> {
        let side = match node.attribute("side").map(str::trim) {
            None => Side::Both,
            Some(s) => Side::parse(s).ok_or_else(|| {
                self.error(
                    node,
                    format!(
                        "'side' of <{}> is '{s}', expected front, back or both",
                        node.tag_name().name()
                    ),
                )
            })?,
        };
        Ok(SurfaceRef {
            name: self.required(node, "surface")?,
            side,
        })
    }

    /// `grid`: `auto` (EN 12464-1) or a spacing in metres; `values`: `points` (the
    /// illuminance at each cell's centre, as EN 12464-1 reads a grid) or `cell-means`.
    pub(super) fn grid(&self, node: Node) -> Result<Grid, Diagnostic> {
        let spacing = match node.attribute("grid").map(str::trim) {
            None | Some("auto") => Spacing::Auto,
            Some(_) => match self.real(node, "grid", "auto or a spacing in metres")? {
                Some(m) if m > 0.0 => Spacing::Metres(m),
                _ => {
                    return Err(self.error(
                        node,
                        format!(
                            "'grid' of <{}> is not positive, expected auto or a spacing in metres",
                            node.tag_name().name()
                        ),
                    ));
                }
            },
        };
        let values = match node.attribute("values").map(str::trim) {
            None => GridValues::Points,
            Some(v) => GridValues::parse(v).ok_or_else(|| {
                self.error(
                    node,
                    format!(
                        "'values' of <{}> is '{v}', expected points or cell-means",
                        node.tag_name().name()
                    ),
                )
                .with_hint("points: the illuminance at each grid point, as EN 12464-1 judges a grid; cell-means: the mean over each cell")
            })?,
        };
        Ok(Grid { spacing, values })
    }

    /// A positive illuminance attribute.
    pub(super) fn lux(&self, node: Node, attr: &str) -> Result<Option<f64>, Diagnostic> {
        match self.real(node, attr, "an illuminance (lx)")? {
            Some(x) if x <= 0.0 => Err(self.error(
                node,
                format!(
                    "'{attr}' of <{}> is {x}, expected a positive illuminance (lx)",
                    node.tag_name().name()
                ),
            )),
            x => Ok(x),
        }
    }

    /// One of the goal elements, or `None` for another element.
    fn goal(&self, o: Node, observers: &mut Observers) -> Result<Option<Goal>, Diagnostic> {
        let name = o.tag_name().name();
        let goal = match name {
            "maximizeRadiance" => {
                self.check_attributes(o, &["surface", "side", "maxRadiosity"]);
                let cap = self.lux(o, "maxRadiosity").map_err(|e| {
                    e.with_hint("every lit configuration would exceed a cap of zero or less; leave the attribute out for no cap")
                })?;
                Goal::Maximize {
                    surface: self.surface_ref(o)?,
                    cap,
                }
            }
            "minimizeRadiance" => {
                self.check_attributes(o, &["surface", "side"]);
                Goal::Minimize {
                    surface: self.surface_ref(o)?,
                }
            }
            "targetRadiance" => {
                self.check_attributes(o, &["surface", "side", "lux"]);
                let lux = self.lux(o, "lux")?.ok_or_else(|| {
                    self.error(o, "<targetRadiance> needs 'lux', the illuminance to reach")
                })?;
                Goal::Target {
                    surface: self.surface_ref(o)?,
                    lux,
                }
            }
            "maximizeUniformity" => {
                self.check_attributes(o, &["surface", "side", "grid", "values"]);
                Goal::MaximizeUniformity {
                    surface: self.surface_ref(o)?,
                    grid: self.grid(o)?,
                }
            }
            "minimizePower" => {
                self.check_attributes(o, &[]);
                Goal::MinimizePower
            }
            "maximizeDaylightFactor" => {
                self.check_attributes(o, &["surface", "side"]);
                Goal::MaximizeDaylightFactor {
                    surface: self.surface_ref(o)?,
                }
            }
            "minimizeGlare" => {
                self.check_attributes(o, &["observer", "view", "name"]);
                Goal::MinimizeGlare {
                    observer: self.observer_of(o, "observer", observers)?.surface(),
                }
            }
            _ => return Ok(None),
        };
        Ok(Some(goal))
    }

    /// A `<constraint>`: a surface and exactly one bound.
    fn constraint(&self, c: Node) -> Result<Constraint, Diagnostic> {
        const BOUNDS: [&str; 5] = [
            "minLux",
            "maxLux",
            "minUniformity",
            "minPointLux",
            "minDaylightFactor",
        ];
        self.check_attributes(
            c,
            &[&["surface", "side", "grid", "values"][..], &BOUNDS].concat(),
        );
        let given: Vec<&str> = BOUNDS
            .into_iter()
            .filter(|b| c.attribute(*b).is_some())
            .collect();
        if given.len() != 1 {
            return Err(self
                .error(
                    c,
                    format!(
                        "<constraint> has {}, expected exactly one of {}",
                        if given.is_empty() {
                            "no bound".to_string()
                        } else {
                            given.join(" and ")
                        },
                        BOUNDS.join(", ")
                    ),
                )
                .with_hint("write one <constraint> element per bound"));
        }
        let bound = match given[0] {
            "minLux" => Bound::MinLux(self.lux(c, "minLux")?.unwrap_or_default()),
            "maxLux" => Bound::MaxLux(self.lux(c, "maxLux")?.unwrap_or_default()),
            "minPointLux" => Bound::MinPointLux(
                self.lux(c, "minPointLux")?.unwrap_or_default(),
                self.grid(c)?,
            ),
            "minDaylightFactor" => Bound::MinDaylightFactor(
                self.unit(c, "minDaylightFactor", 0.0, 100.0)?
                    .unwrap_or_default(),
            ),
            _ => Bound::MinUniformity(
                self.unit(c, "minUniformity", 0.0, 1.0)?.unwrap_or_default(),
                self.grid(c)?,
            ),
        };
        let gridded = c.attribute("grid").is_some() || c.attribute("values").is_some();
        let average_over = match bound {
            Bound::MinLux(_) | Bound::MaxLux(_) if gridded => Some(self.grid(c)?),
            _ => None,
        };
        if gridded && bound.grid().is_none() && average_over.is_none() {
            self.warn(
                c,
                format!(
                    "'grid' and 'values' of a {} constraint ignored: it bounds the mean",
                    bound.attribute()
                ),
            );
        }
        Ok(Constraint {
            surface: self.surface_ref(c)?,
            bound,
            line: self.line(c),
            maintenance_factor: 1.0,
            from_task: None,
            average_over,
        })
    }
}
