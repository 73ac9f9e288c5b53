//! Reading an inverse lighting problem: ILPSolver's XML problem files, unchanged
//! (thesis §4.2.1 and appendix D, and the later form of ILPSolver's examples), plus
//! invlight's optional additions. `docs/problem-file.md` documents the format.
//!
//! Reading is forgiving where ILPSolver files differ and strict where a mistake would
//! change the answer: an unknown element or attribute is a warning naming it; a missing
//! required one, a malformed number or an unknown strategy is an error naming the file,
//! the line and what was expected. Appendix D writes `maxIterations=1000` without
//! quotes, which is not XML; such values are quoted before parsing, with a warning.
//!
//! One reader per element family: `scene.rs` (`<scene>`, its `<luminaire>`s and
//! `<output>`), `daylight.rs` (`<site>`, `<sun>`, `<sky>`), `variables.rs` (the free
//! variables of `<conditions>`), `sun_time.rs` (`<sunTime>` and where its sun stands),
//! `search.rs` (the search settings on `<objectives>`) and `intentions.rs` (the goal and
//! constraints in `<objectives>`); [`Reader::problem`] puts them together.

mod bare_attributes;
mod calculation;
mod daylight;
mod glare;
mod groups;
mod intentions;
mod scene;
mod search;
mod sun_time;
mod task;
mod variables;

pub(crate) use sun_time::SunClock;

use crate::intention::{Bound, Constraint, Goal};
use crate::vns::{Sense, Settings, Strategy};
use bare_attributes::quote_bare_attributes;
pub use glare::ObserverSpec;
pub use groups::LightGroup;
use intentions::Intentions;
use invlight_scene::daylight::{Date, Daylight, DaylightError, DaylightFlags, SunSchedule};
use invlight_scene::{Calculation, Diagnostic, LoadOptions, Luminaire, Scene, UpAxis, nearest};
use invlight_stats::Confidence;
use std::path::{Path, PathBuf};
pub use task::TaskSpec;

/// Which point of a placed object the placement point P of its rectangle stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Anchor {
    /// `anchor="vertexA"` (the default, ILPSolver's rule): the object moves by P − A, so
    /// P is where vertex A of the rectangle goes and the object keeps its authored offset
    /// from A.
    #[default]
    VertexA,
    /// `anchor="centre"`: the object's own anchor (a light's position, an object's
    /// bounding-box centre on the rectangle's plane) is put at P, wherever it was
    /// authored.
    Centre,
}

impl Anchor {
    /// The problem-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            Anchor::VertexA => "vertexA",
            Anchor::Centre => "centre",
        }
    }
}

/// Where a placement variable puts its object: a rectangle and how P relates to the
/// object.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacementSpec {
    /// The placement rectangle's name.
    pub surface: String,
    /// Indices of A, B, C, D among its distinct vertices.
    pub vertices: [usize; 4],
    /// What P stands for.
    pub anchor: Anchor,
}

/// What a variable moves or changes.
#[derive(Debug, Clone, PartialEq)]
pub enum VariableKind {
    /// `objectInSurface`: an object (a named surface) placed on a rectangle.
    ObjectInSurface(PlacementSpec),
    /// `lightInSurface`: a point/spot light or an emissive object on a rectangle.
    LightInSurface(PlacementSpec),
    /// `holeInSurface`: an object that becomes an aperture, placed on a rectangle.
    HoleInSurface(PlacementSpec),
    /// `directionalLight`: the direction of a sun.
    DirectionalLight,
    /// `holeSize` (invlight): the size of an aperture, a uniform scale of its object
    /// about its centre.
    HoleSize {
        /// `minScale`, > 0.
        min: f64,
        /// `maxScale`, > `minScale`.
        max: f64,
    },
    /// `objectRotation` (invlight): the turn of an object or luminaire about its
    /// placement rectangle's normal (the scene's up without one), through its anchor.
    ObjectRotation {
        /// `min`, degrees.
        min: f64,
        /// `max`, degrees, at most 360° above `min`.
        max: f64,
    },
    /// `lightAim` (invlight): the aim of a spot or luminaire, within a cone about its
    /// authored aim.
    LightAim {
        /// `maxTilt`: the cone's half-angle, degrees, in (0, 90].
        max_tilt: f64,
    },
    /// `lightPower`: the dimming level of a light or an emissive object (its authored
    /// output × the level).
    LightPower {
        /// Lowest level.
        min: f64,
        /// Highest level.
        max: f64,
    },
    /// `sunTime` (invlight): the time of day on `date` at the problem's `<site>`, from
    /// `from` to `to` in whole steps of `step` minutes; the directional light `id`
    /// stands where NREL's SPA puts the sun then (docs/daylight.md).
    SunTime {
        /// The local date.
        date: Date,
        /// The first time, minutes after local midnight.
        from: f64,
        /// The last time, minutes after local midnight, a whole number of steps after
        /// `from`.
        to: f64,
        /// The step, minutes.
        step: f64,
    },
    /// `color`: the HSV value V of a material with fixed hue and saturation.
    Color {
        /// Hue, degrees.
        hue: f64,
        /// Saturation, 0–1.
        saturation: f64,
        /// Lowest V.
        min: f64,
        /// Highest V.
        max: f64,
    },
    /// `lightArray` (invlight): lamps set out as a regular array on a rectangle, its
    /// columns, rows and wall distances searched, the lamps beyond columns × rows off.
    LightArray(ArraySpec),
}

/// A `<lightArray id lights surface columns rows orientation continuous>`.
#[derive(Debug, Clone, PartialEq)]
pub struct ArraySpec {
    /// The lamps, in the order they fill the array (row by row).
    pub lights: Vec<String>,
    /// The placement rectangle.
    pub surface: String,
    /// Indices of A, B, C, D among its distinct vertices.
    pub vertices: [usize; 4],
    /// The least and greatest number of columns (along A→B).
    pub columns: (u32, u32),
    /// The least and greatest number of rows.
    pub rows: (u32, u32),
    /// `orientation`: degrees every lamp of the array is turned about its aim, on top
    /// of its own (`<luminaire rotation>`): 0 or 90, a linear luminaire along or across
    /// the rectangle's first edge's as authored; `None` for `search`, where the search
    /// chooses between the two ([`crate::space::ArrayDomain::turns`]).
    pub orientation: Option<f32>,
    /// `continuous="true"`: the fittings of each row laid end to end
    /// ([`crate::space::Rows`]).
    pub continuous: bool,
}

impl VariableKind {
    /// The problem-file element name.
    pub fn name(&self) -> &'static str {
        match self {
            VariableKind::ObjectInSurface(_) => "objectInSurface",
            VariableKind::LightInSurface(_) => "lightInSurface",
            VariableKind::HoleInSurface(_) => "holeInSurface",
            VariableKind::DirectionalLight => "directionalLight",
            VariableKind::LightAim { .. } => "lightAim",
            VariableKind::HoleSize { .. } => "holeSize",
            VariableKind::ObjectRotation { .. } => "objectRotation",
            VariableKind::Color { .. } => "color",
            VariableKind::LightPower { .. } => "lightPower",
            VariableKind::SunTime { .. } => "sunTime",
            VariableKind::LightArray(_) => "lightArray",
        }
    }

    /// The placement of a variable that places something on a rectangle.
    pub fn placement(&self) -> Option<&PlacementSpec> {
        match self {
            VariableKind::ObjectInSurface(p)
            | VariableKind::LightInSurface(p)
            | VariableKind::HoleInSurface(p) => Some(p),
            _ => None,
        }
    }
}

/// A free variable as written in the file.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableSpec {
    /// `id`: the object, light or material it changes.
    pub id: String,
    /// What it is.
    pub kind: VariableKind,
    /// Line of its element.
    pub line: u32,
}

impl VariableSpec {
    /// The key of variable `i` of `specs` in `result.json`'s `variables`: its id, or
    /// `<id>.power` for a `lightPower`, `<id>.aim` for a `lightAim` and `<id>.size` for
    /// a `holeSize` whose light or hole another variable also places, dims or aims.
    pub fn key(specs: &[VariableSpec], i: usize) -> String {
        let spec = &specs[i];
        let shared = specs
            .iter()
            .enumerate()
            .any(|(j, other)| j != i && other.id == spec.id);
        if shared && matches!(spec.kind, VariableKind::LightPower { .. }) {
            format!("{}.power", spec.id)
        } else if shared && matches!(spec.kind, VariableKind::LightAim { .. }) {
            format!("{}.aim", spec.id)
        } else if shared && matches!(spec.kind, VariableKind::HoleSize { .. }) {
            format!("{}.size", spec.id)
        } else if shared && matches!(spec.kind, VariableKind::ObjectRotation { .. }) {
            format!("{}.rotation", spec.id)
        } else {
            spec.id.clone()
        }
    }
}

/// The scene a problem is posed on: `<scene path="…" scale="…" up="…"/>`, with the
/// photometric files its `<luminaire>` children give its lights.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRef {
    /// The scene file, resolved against the problem file's folder.
    pub path: PathBuf,
    /// `scale`: metres per file unit (invlight; e.g. 0.001 for a file in millimetres).
    pub scale: Option<f32>,
    /// `up`: the file's up axis when it does not say or says wrongly (invlight).
    pub up: Option<UpAxis>,
    /// `<luminaire light="…" file="…" multiplier="…"/>` children (invlight), in file
    /// order: the named point or spot light emits the file's candela table.
    pub luminaires: Vec<Luminaire>,
    /// `<luminaire size>` (invlight): the fittings' sizes as installed, in file order.
    pub sizes: Vec<FittingSize>,
    /// `<calculationSurface>` and `<workplane>` children (invlight): surfaces that
    /// receive light without touching it.
    pub calculation: Calculation,
    /// Line of its element.
    pub line: u32,
}

/// `<luminaire light size="L,W">` (invlight): a fitting's length and width as
/// installed, m, where the photometric file gives none or another (a file measured on
/// one module of a trunking row, say). It is the outline luminaires are kept apart by
/// (`binding/fittings.rs`), not the luminous area: the photometry is the file's.
#[derive(Debug, Clone, PartialEq)]
pub struct FittingSize {
    /// The light it sizes.
    pub light: String,
    /// Along the luminaire's C90–C270 axis, as EULUMDAT's length is, m.
    pub length: f64,
    /// Across it, along C0–C180, m.
    pub width: f64,
}

/// A problem file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// The problem file.
    pub path: PathBuf,
    /// The scene and how to read it.
    pub scene: SceneRef,
    /// The output folder, resolved against the problem file's folder (default `output`).
    pub output: PathBuf,
    /// Cells per dimension, used in turn (`meshSize`, default 20).
    pub cells_per_dimension: Vec<u32>,
    /// The free variables, in file order.
    pub variables: Vec<VariableSpec>,
    /// `<lightGroup>`s: lamps that share one dimming level and one aim.
    pub groups: Vec<LightGroup>,
    /// What to achieve above all.
    pub goal: Goal,
    /// Line of the goal's element.
    pub goal_line: u32,
    /// What must hold as well: the `<constraint>`s, then what each `<task>` asks of
    /// its task area, then — once [`Problem::load_scene`] has built them — of the areas
    /// around it.
    pub constraints: Vec<Constraint>,
    /// `<task>`s: EN 12464-1 tasks whose requirements are among the constraints.
    pub tasks: Vec<TaskSpec>,
    /// The observers whose glare a constraint or the goal rates, each an eye square
    /// [`crate::Binding::new`] adds to the scene under its name
    /// ([`Problem::build_eyes`]).
    pub observers: Vec<ObserverSpec>,
    /// `maxIterations` (default 1000).
    pub max_iterations: u64,
    /// `fastEvaluationQuality`, q of §4.7 (default 0.25, the thesis' value).
    pub fast_quality: f64,
    /// `strategy` (default `RACE_ISOC_ON_END`, which traced the fewest photons for an
    /// answer in the region on every bundled example).
    pub strategy: Strategy,
    /// invlight: `photons`, N (default 100 000).
    pub photons: u64,
    /// invlight: `seed` of photons and search (default 1).
    pub seed: u64,
    /// invlight: `confidence` 1 − α (default 0.95).
    pub confidence: Confidence,
    /// invlight: `maxBounces` per photon path (default: the tracer's own).
    pub max_bounces: Option<u32>,
    /// invlight: `maintenanceFactor` MF in (0, 1] (default 1). The constraints'
    /// illuminances are maintained values, as EN 12464-1 states its Em: the search
    /// holds the new installation to the file's limit ÷ MF
    /// ([`Constraint::maintained_limit`] gives the file's back). Goals are the new
    /// installation's values.
    pub maintenance_factor: f64,
    /// `<site>`, `<sun>` and `<sky>`: the daylight [`Problem::load_scene`] puts on the
    /// scene.
    pub daylight: Daylight,
    /// `<sunTime id days|date from to step dayStep objective="mean">`: the sun `id`
    /// replaced by one sun per instant with 1/K of its beam, so that every light read is
    /// the mean over the instants ([`SunSchedule::apply`]), with its line.
    pub sun_schedule: Option<(String, SunSchedule, u32)>,
    /// Warnings: unknown elements and attributes, repaired syntax.
    pub warnings: Vec<Diagnostic>,
}

const TOP: &[&str] = &[
    "scene",
    "output",
    "conditions",
    "objectives",
    "site",
    "sun",
    "sky",
];

impl Problem {
    /// The `<lightGroup>`s and, as groups of their own, the `<lightArray>`s: a
    /// `<lightPower>` or `<lightAim>` of an array's id dims or aims all its lamps as
    /// one, as of a group's.
    pub fn lamp_groups(&self) -> Vec<LightGroup> {
        let mut out = self.groups.clone();
        for v in &self.variables {
            if let VariableKind::LightArray(a) = &v.kind {
                out.push(LightGroup {
                    id: v.id.clone(),
                    lights: a.lights.clone(),
                    line: v.line,
                });
            }
        }
        out
    }

    /// Reads a problem file.
    pub fn read(path: &Path) -> Result<Problem, Diagnostic> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Diagnostic::new(path, format!("cannot read the problem file: {e}")))?;
        Problem::parse(path, &text)
    }

    /// Loads the problem's scene with `base`'s options and `<scene>`'s `scale` and `up`
    /// unless `scale` and `up` (the command line's) say otherwise, its lights given
    /// their `<luminaire>` files (relative to the problem file) and then `luminaires`
    /// (the command line's, which thus win), and puts the file's daylight on it
    /// ([`Problem::daylight`]; its warnings were given when the file was read), its sun
    /// placed at the middle of a `<sunTime>`'s range, or spread over the instants of a
    /// `<sunTime objective="mean">` ([`Problem::sun_schedule`]). A missing file is named with the problem file's
    /// line: its path is relative to the problem file, not to the current directory.
    /// Each `<task>`'s areas are built on the scene and their requirements join the
    /// constraints ([`Problem::tasks`]), which is why the problem is changed.
    pub fn load_scene(
        &mut self,
        base: &LoadOptions,
        scale: Option<f32>,
        up: Option<UpAxis>,
        luminaires: &[Luminaire],
    ) -> Result<Scene, Diagnostic> {
        let path = &self.scene.path.clone();
        if !path.exists() {
            let dir = self.path.parent().unwrap_or(Path::new("."));
            return Err(Diagnostic::at_line(
                &self.path,
                self.scene.line,
                format!("the scene file {} does not exist", path.display()),
            )
            .with_hint(format!(
                "a <scene path> is relative to the problem file's folder, {}",
                if dir.as_os_str().is_empty() {
                    Path::new(".").display()
                } else {
                    dir.display()
                }
            )));
        }
        let mut options = *base;
        options.scale = scale.or(self.scene.scale).unwrap_or(1.0);
        options.up = up.or(self.scene.up);
        let mut scene = invlight_scene::load_with(path, &options, &self.scene.luminaires)?;
        scene.set_luminaires(path, luminaires, &options)?;
        self.turn_arrays(&mut scene);
        scene.set_calculation(path, &self.scene.calculation)?;
        self.build_task_areas(&mut scene)?;
        // A sun below the horizon was warned of with its line when the file was read.
        let daylight = |e: DaylightError| Diagnostic::new(&self.path, format!("daylight: {e}"));
        self.daylight.apply_sun(&mut scene).map_err(daylight)?;
        let mut sky_drawn = false;
        for spec in &self.variables {
            if matches!(spec.kind, VariableKind::SunTime { .. }) {
                let clock = SunClock::place(self, spec, &mut scene)
                    .map_err(|e| Diagnostic::at_line(&self.path, spec.line, e.to_string()))?;
                sky_drawn |= clock.draws_sky();
            }
        }
        if let (Some((id, schedule, line)), Some(site)) = (&self.sun_schedule, self.daylight.site) {
            let lux = self.daylight.sun.and_then(|s| s.illuminance);
            schedule
                .apply(id, &site, lux, &mut scene)
                .map_err(|e| Diagnostic::at_line(&self.path, *line, format!("<sunTime>: {e}")))?;
        }
        // A clear sky follows a sunTime's sun, which drew it above; any other sky is put
        // on after the suns, so that a clear one finds the sun it is drawn about.
        if !sky_drawn {
            self.daylight.apply_sky(&mut scene).map_err(daylight)?;
        }
        Ok(scene)
    }

    /// Puts the command line's daylight over this problem's own
    /// ([`DaylightFlags::over`]): what its scene is lit by, once, in
    /// [`Problem::load_scene`], and what its search's suns follow. Returns what the
    /// flags' daylight is worth a warning for (the file's own was warned of when read).
    pub fn lit_by(&mut self, flags: &DaylightFlags) -> Result<Vec<String>, DaylightError> {
        let daylight = flags.over(&self.daylight)?;
        let warnings = if daylight == self.daylight {
            Vec::new()
        } else {
            daylight.warnings()
        };
        self.daylight = daylight;
        Ok(warnings)
    }

    /// The bounce cap of its photon paths: `maxBounces`, else the tracer's own.
    pub fn bounces(&self) -> u32 {
        self.max_bounces
            .unwrap_or(invlight_photon::DEFAULT_MAX_BOUNCES)
    }

    /// The line of the first intention that asks for a daylight factor
    /// (`<maximizeDaylightFactor>`, `minDaylightFactor`), if one does: such a problem
    /// is measured under the overcast sky alone ([`crate::Binding::new`]).
    pub fn daylight_factor_line(&self) -> Option<u32> {
        let goal = matches!(self.goal, Goal::MaximizeDaylightFactor { .. });
        goal.then_some(self.goal_line).or_else(|| {
            self.constraints
                .iter()
                .find(|c| matches!(c.bound, Bound::MinDaylightFactor(_)))
                .map(|c| c.line)
        })
    }

    /// The search settings the file asks for.
    pub fn settings(&self) -> Settings {
        Settings {
            max_iterations: self.max_iterations,
            photons: self.photons,
            fast_quality: self.fast_quality,
            strategy: self.strategy,
            confidence: self.confidence,
            cap: match self.goal {
                Goal::Maximize { cap, .. } => cap,
                _ => None,
            },
            sense: match self.goal {
                Goal::Maximize { .. }
                | Goal::MaximizeUniformity { .. }
                | Goal::MaximizeDaylightFactor { .. } => Sense::Maximize,
                Goal::Minimize { .. } | Goal::MinimizePower | Goal::MinimizeGlare { .. } => {
                    Sense::Minimize
                }
                Goal::Target { lux, .. } => Sense::Target(lux),
            },
            constraints: self.constraints.iter().map(|c| c.bound).collect(),
            seed: self.seed,
            tries_per_radius: None,
        }
    }

    /// Parses problem-file text; `path` names it in messages and anchors relative paths.
    pub fn parse(path: &Path, text: &str) -> Result<Problem, Diagnostic> {
        let mut warnings = Vec::new();
        let fixed = quote_bare_attributes(text, path, &mut warnings);
        let doc = roxmltree::Document::parse(&fixed).map_err(|e| {
            let pos = e.pos();
            Diagnostic::at_line(path, pos.row, format!("not well-formed XML: {e}"))
        })?;
        let r = Reader {
            path,
            doc: &doc,
            warnings: std::cell::RefCell::new(warnings),
        };
        let problem = r.problem()?;
        Ok(Problem {
            warnings: r.warnings.into_inner(),
            ..problem
        })
    }
}

struct Reader<'a, 'i> {
    path: &'a Path,
    doc: &'a roxmltree::Document<'i>,
    warnings: std::cell::RefCell<Vec<Diagnostic>>,
}

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

impl<'a, 'i> Reader<'a, 'i> {
    fn line(&self, node: Node) -> u32 {
        self.doc.text_pos_at(node.range().start).row
    }

    fn error(&self, node: Node, message: impl Into<String>) -> Diagnostic {
        Diagnostic::at_line(self.path, self.line(node), message)
    }

    fn warn(&self, node: Node, message: String) {
        self.push_warning(self.error(node, message));
    }

    fn push_warning(&self, w: Diagnostic) {
        self.warnings.borrow_mut().push(w);
    }

    /// Warns about attributes of `node` not in `known`.
    fn check_attributes(&self, node: Node, known: &[&str]) {
        for a in node.attributes() {
            if !known.contains(&a.name()) {
                let w = self.error(
                    node,
                    format!(
                        "unknown attribute '{}' of <{}> ignored (expected one of: {})",
                        a.name(),
                        node.tag_name().name(),
                        known.join(", ")
                    ),
                );
                self.push_warning(match nearest(a.name(), known) {
                    Some(k) => w.with_hint(format!("did you mean '{k}'?")),
                    None => w,
                });
            }
        }
    }

    /// The diagnostic for an element `node` not in `known`, "unknown {what} <name> …
    /// (expected one of: …)", with the nearest known element as its hint.
    fn unknown_element(&self, node: Node, what: &str, known: &[&str], more: &str) -> Diagnostic {
        let name = node.tag_name().name();
        let d = self.error(
            node,
            format!(
                "unknown {what} <{name}> ignored (expected one of: {}{more})",
                known.join(", ")
            ),
        );
        match nearest(name, known) {
            Some(k) => d.with_hint(format!("did you mean <{k}>?")),
            None => d,
        }
    }

    fn elements(&self, node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
        node.children().filter(|c| c.is_element())
    }

    fn required(&self, node: Node, attr: &str) -> Result<String, Diagnostic> {
        match node.attribute(attr) {
            Some(v) if !v.trim().is_empty() => Ok(v.trim().to_string()),
            _ => Err(self.error(
                node,
                format!(
                    "<{}> needs a non-empty '{attr}' attribute",
                    node.tag_name().name()
                ),
            )),
        }
    }

    fn number<T: std::str::FromStr>(
        &self,
        node: Node,
        attr: &str,
        what: &str,
    ) -> Result<Option<T>, Diagnostic> {
        match node.attribute(attr) {
            None => Ok(None),
            Some(v) => v.trim().parse().map(Some).map_err(|_| {
                self.error(
                    node,
                    format!(
                        "'{attr}' of <{}> is '{v}', expected {what}",
                        node.tag_name().name()
                    ),
                )
            }),
        }
    }

    /// A finite real number: `NaN` and `inf` parse as f64 but mean nothing here.
    fn real(&self, node: Node, attr: &str, what: &str) -> Result<Option<f64>, Diagnostic> {
        match self.number::<f64>(node, attr, what)? {
            Some(x) if !x.is_finite() => Err(self.error(
                node,
                format!(
                    "'{attr}' of <{}> is {x}, expected {what}",
                    node.tag_name().name()
                ),
            )),
            x => Ok(x),
        }
    }

    fn unit(&self, node: Node, attr: &str, lo: f64, hi: f64) -> Result<Option<f64>, Diagnostic> {
        let v = self.real(node, attr, &format!("a number in [{lo}, {hi}]"))?;
        match v {
            Some(x) if !(lo..=hi).contains(&x) => Err(self.error(
                node,
                format!(
                    "'{attr}' of <{}> is {x}, expected a number in [{lo}, {hi}]",
                    node.tag_name().name()
                ),
            )),
            _ => Ok(v),
        }
    }

    /// The one child `name` of `parent`, if any; a second is an error.
    fn only(&self, parent: Node<'a, 'i>, name: &str) -> Result<Option<Node<'a, 'i>>, Diagnostic> {
        let mut found = self
            .elements(parent)
            .filter(|e| e.tag_name().name() == name);
        let first = found.next();
        if let Some(second) = found.next() {
            return Err(self.error(second, format!("a second <{name}>, expected one")));
        }
        Ok(first)
    }

    /// The whole problem: `<input>`'s element families read in turn (scene, daylight,
    /// output, conditions, objectives), then the checks that span two of them.
    fn problem(&self) -> Result<Problem, Diagnostic> {
        let root = self.doc.root_element();
        if root.tag_name().name() != "input" {
            return Err(self.error(
                root,
                format!(
                    "the root element is <{}>, expected <input>",
                    root.tag_name().name()
                ),
            ));
        }
        self.check_attributes(root, &[]);
        for e in self.elements(root) {
            if !TOP.contains(&e.tag_name().name()) {
                self.push_warning(self.unknown_element(e, "element", TOP, ""));
            }
        }
        let dir = self.path.parent().unwrap_or(Path::new("."));
        let scene = self.scene_ref(root, dir)?;
        let daylight = self.daylight(
            self.only(root, "site")?,
            self.only(root, "sun")?,
            self.only(root, "sky")?,
        )?;
        let output = self.output(root, dir)?;
        let conditions = self.conditions(root)?;
        self.check_sun_times(&conditions, &daylight)?;

        let objectives = self.only(root, "objectives")?.ok_or_else(|| {
            self.error(
                root,
                "no <objectives>, expected one with <maximizeRadiance surface=\"…\"/>",
            )
        })?;
        let search = self.search(objectives)?;
        let workplanes: Vec<String> = scene
            .calculation
            .workplanes
            .iter()
            .map(|w| w.id.clone())
            .collect();
        let Intentions {
            goal,
            goal_line,
            constraints,
            tasks,
            observers,
        } = self.intentions(objectives, &workplanes)?;
        let constraints: Vec<Constraint> = constraints
            .into_iter()
            .map(|c| c.maintained(search.maintenance_factor))
            .collect();

        let df = matches!(goal, Goal::MaximizeDaylightFactor { .. })
            || constraints
                .iter()
                .any(|c: &Constraint| matches!(c.bound, Bound::MinDaylightFactor(_)));
        if let (true, Some((_, _, line))) = (df, &conditions.sun_schedule) {
            return Err(Diagnostic::at_line(
                self.path,
                *line,
                "<sunTime objective=\"mean\"> in a daylight-factor problem: the factor is the overcast sky's light alone, with no sun",
            ));
        }

        Ok(Problem {
            path: self.path.to_path_buf(),
            scene,
            output,
            cells_per_dimension: conditions.cells_per_dimension,
            variables: conditions.variables,
            groups: conditions.groups,
            goal,
            goal_line,
            constraints,
            tasks,
            observers,
            max_iterations: search.max_iterations,
            fast_quality: search.fast_quality,
            strategy: search.strategy,
            photons: search.photons,
            seed: search.seed,
            confidence: search.confidence,
            max_bounces: search.max_bounces,
            maintenance_factor: search.maintenance_factor,
            daylight,
            sun_schedule: conditions.sun_schedule,
            warnings: Vec::new(),
        })
    }
}

#[cfg(test)]
mod tests;
