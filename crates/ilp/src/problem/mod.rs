//! Reading an inverse lighting problem: ILPSolver's XML problem files, unchanged
//! (thesis §4.2.1 and appendix D, and the later form of ILPSolver's examples), plus
//! invlight's optional additions. `docs/problem-file.md` documents the format.
//!
//! Reading is forgiving where ILPSolver files differ and strict where a mistake would
//! change the answer: an unknown element or attribute is a warning naming it; a missing
//! required one, a malformed number or an unknown strategy is an error naming the file,
//! the line and what was expected. Appendix D writes `maxIterations=1000` without
//! quotes, which is not XML; such values are quoted before parsing, with a warning.

mod bare_attributes;
mod calculation;
mod daylight;

use crate::intention::{Bound, Constraint, Goal, Grid, Side, SurfaceRef};
use crate::vns::{Sense, Settings, Strategy};
use bare_attributes::quote_bare_attributes;
use invlight_scene::daylight::{
    Date, Daylight, DaylightError, DaylightFlags, SkyKind, SunSchedule, TimeOfDay,
};
use invlight_scene::{Calculation, Diagnostic, LoadOptions, Luminaire, Scene, UpAxis};
use invlight_stats::Confidence;
use std::path::{Path, PathBuf};

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
    /// `<calculationSurface>` and `<workplane>` children (invlight): surfaces that
    /// receive light without touching it.
    pub calculation: Calculation,
    /// Line of its element.
    pub line: u32,
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
    /// What to achieve above all.
    pub goal: Goal,
    /// Line of the goal's element.
    pub goal_line: u32,
    /// What must hold as well.
    pub constraints: Vec<Constraint>,
    /// `maxIterations` (default 1000).
    pub max_iterations: u64,
    /// `fastEvaluationQuality`, q of §4.7 (default 0.25, the thesis' value).
    pub fast_quality: f64,
    /// `strategy` (default `REFINE_ISOC_ON_INTERSECTION`).
    pub strategy: Strategy,
    /// invlight: `photons`, N (default 100 000).
    pub photons: u64,
    /// invlight: `seed` of photons and search (default 1).
    pub seed: u64,
    /// invlight: `confidence` 1 − α (default 0.95).
    pub confidence: Confidence,
    /// invlight: `maxBounces` per photon path (default: the tracer's own).
    pub max_bounces: Option<u32>,
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
const GOALS: &[&str] = &[
    "maximizeRadiance",
    "minimizeRadiance",
    "targetRadiance",
    "maximizeUniformity",
    "minimizePower",
    "maximizeDaylightFactor",
];
const VARIABLES: &[&str] = &[
    "objectInSurface",
    "lightInSurface",
    "holeInSurface",
    "holeSize",
    "objectRotation",
    "directionalLight",
    "lightAim",
    "color",
    "lightPower",
    "sunTime",
];
const VERTEX_ATTRS: [&str; 4] = [
    "vertexAIndex",
    "vertexBIndex",
    "vertexCIndex",
    "vertexDIndex",
];

impl Problem {
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
    pub fn load_scene(
        &self,
        base: &LoadOptions,
        scale: Option<f32>,
        up: Option<UpAxis>,
        luminaires: &[Luminaire],
    ) -> Result<Scene, Diagnostic> {
        let path = &self.scene.path;
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
        scene.set_calculation(path, &self.scene.calculation)?;
        // A sun below the horizon was warned of with its line when the file was read.
        self.daylight
            .apply(&mut scene)
            .map_err(|e| Diagnostic::new(&self.path, format!("daylight: {e}")))?;
        for spec in &self.variables {
            if matches!(spec.kind, VariableKind::SunTime { .. }) {
                crate::binding::place_sun_time(self, spec, &mut scene)
                    .map_err(|e| Diagnostic::at_line(&self.path, spec.line, e))?;
            }
        }
        if let (Some((id, schedule, line)), Some(site)) = (&self.sun_schedule, self.daylight.site) {
            let lux = self.daylight.sun.and_then(|s| s.illuminance);
            schedule
                .apply(id, &site, lux, &mut scene)
                .map_err(|e| Diagnostic::at_line(&self.path, *line, format!("<sunTime>: {e}")))?;
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
                Goal::Minimize { .. } | Goal::MinimizePower => Sense::Minimize,
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
        let w = Diagnostic::at_line(self.path, self.line(node), message);
        self.warnings.borrow_mut().push(w);
    }

    /// Warns about attributes of `node` not in `known`.
    fn check_attributes(&self, node: Node, known: &[&str]) {
        for a in node.attributes() {
            if !known.contains(&a.name()) {
                self.warn(
                    node,
                    format!(
                        "unknown attribute '{}' of <{}> ignored (expected one of: {})",
                        a.name(),
                        node.tag_name().name(),
                        known.join(", ")
                    ),
                );
            }
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

    /// `<scene>`'s `<luminaire light file multiplier>` children; the file is kept as
    /// written and resolved when the scene is loaded ([`Scene::set_luminaires`]), under
    /// the folder rule of the problem file.
    fn luminaires(&self, scene: Node) -> Result<Vec<Luminaire>, Diagnostic> {
        let mut out = Vec::new();
        for e in self.elements(scene) {
            if e.tag_name().name() != "luminaire" {
                if !calculation::ELEMENTS.contains(&e.tag_name().name()) {
                    self.warn(
                        e,
                        format!(
                            "unknown element <{}> in <scene> ignored (expected luminaire, calculationSurface or workplane)",
                            e.tag_name().name()
                        ),
                    );
                }
                continue;
            }
            self.check_attributes(e, &["light", "file", "multiplier"]);
            let what = "a positive factor on the file's candela";
            let multiplier = match self.real(e, "multiplier", what)? {
                Some(m) if m <= 0.0 || m as f32 > f32::MAX => {
                    return Err(self.error(
                        e,
                        format!("'multiplier' of <luminaire> is {m}, expected {what}"),
                    ));
                }
                m => m.unwrap_or(1.0) as f32,
            };
            out.push(Luminaire {
                light: self.required(e, "light")?,
                file: PathBuf::from(self.required(e, "file")?),
                multiplier,
                origin: Some((self.path.to_path_buf(), self.line(e))),
            });
        }
        Ok(out)
    }

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
                self.warn(
                    e,
                    format!(
                        "unknown element <{}> ignored (expected one of: {})",
                        e.tag_name().name(),
                        TOP.join(", ")
                    ),
                );
            }
        }
        let only = |name: &str| -> Result<Option<Node<'a, 'i>>, Diagnostic> {
            let mut found = self.elements(root).filter(|e| e.tag_name().name() == name);
            let first = found.next();
            if let Some(second) = found.next() {
                return Err(self.error(second, format!("a second <{name}>, expected one")));
            }
            Ok(first)
        };
        let dir = self.path.parent().unwrap_or(Path::new("."));

        let scene_el = only("scene")?
            .ok_or_else(|| self.error(root, "no <scene path=\"…\"/>, expected one in <input>"))?;
        self.check_attributes(scene_el, &["path", "scale", "up"]);
        let scale = match self.real(scene_el, "scale", "metres per file unit (e.g. 0.001)")? {
            Some(s) if s <= 0.0 => {
                return Err(self.error(
                    scene_el,
                    format!("'scale' of <scene> is {s}, expected a positive number of metres per file unit (e.g. 0.001 for millimetres)"),
                ));
            }
            s => s.map(|s| s as f32),
        };
        let up = match scene_el.attribute("up").map(str::trim) {
            None => None,
            Some("y" | "Y") => Some(UpAxis::Y),
            Some("z" | "Z") => Some(UpAxis::Z),
            Some(other) => {
                return Err(self.error(
                    scene_el,
                    format!("'up' of <scene> is '{other}', expected y or z"),
                ));
            }
        };
        let scene = SceneRef {
            path: dir.join(self.required(scene_el, "path")?),
            scale,
            up,
            luminaires: self.luminaires(scene_el)?,
            calculation: self.calculation(scene_el)?,
            line: self.line(scene_el),
        };

        let daylight = self.daylight(only("site")?, only("sun")?, only("sky")?)?;

        let output = match only("output")? {
            Some(o) => {
                self.check_attributes(o, &["path"]);
                dir.join(self.required(o, "path")?)
            }
            None => dir.join("output"),
        };

        let conditions = only("conditions")?.ok_or_else(|| {
            self.error(
                root,
                "no <conditions>, expected one with the free variables",
            )
        })?;
        self.check_attributes(conditions, &["meshSize"]);
        let cells_per_dimension = match conditions.attribute("meshSize") {
            None => vec![20],
            Some(m) => parse_mesh(m).ok_or_else(|| {
                self.error(
                    conditions,
                    format!(
                        "meshSize is '{m}', expected cells per dimension: a positive integer or several joined by 'x' (\"20\", \"20x6\")"
                    ),
                )
            })?,
        };
        let mut variables = Vec::new();
        let mut sun_schedule = None;
        for v in self.elements(conditions) {
            if v.tag_name().name() == "sunTime" && v.attribute("objective").is_some() {
                if sun_schedule.is_some() {
                    return Err(
                        self.error(v, "a second <sunTime objective=\"mean\">, expected one")
                    );
                }
                let id = self.required(v, "id")?.to_string();
                sun_schedule = Some((id, self.sun_schedule(v)?, self.line(v)));
                continue;
            }
            if let Some(spec) = self.variable(v)? {
                // A light may be placed, dimmed and aimed: one lightInSurface, one
                // lightPower and one lightAim of the same id; a hole placed and sized:
                // one holeInSurface and one holeSize; any of them, or an
                // objectInSurface, turned by one objectRotation (a luminaire's turn and
                // its aim are one frame, so not with lightAim). Any other repeat is a
                // mistake.
                let turned =
                    |w: &VariableSpec| matches!(w.kind, VariableKind::ObjectRotation { .. });
                let aimed = |w: &VariableSpec| matches!(w.kind, VariableKind::LightAim { .. });
                let light_part = |w: &VariableSpec| match w.kind {
                    VariableKind::LightInSurface(_) => Some((0, 0)),
                    VariableKind::LightPower { .. } => Some((0, 1)),
                    VariableKind::LightAim { .. } => Some((0, 2)),
                    VariableKind::HoleInSurface(_) => Some((1, 0)),
                    VariableKind::HoleSize { .. } => Some((1, 1)),
                    _ => None,
                };
                let group = |w: &VariableSpec| light_part(w).map(|(g, _)| g);
                let allowed = variables
                    .iter()
                    .filter(|w: &&VariableSpec| w.id == spec.id)
                    .all(|w| {
                        let (a, b) = (w, &spec);
                        if turned(a) || turned(b) {
                            let other = if turned(a) { b } else { a };
                            !turned(other) && !aimed(other)
                        } else {
                            light_part(a).is_some()
                                && group(a) == group(b)
                                && light_part(a) != light_part(b)
                        }
                    });
                if !allowed {
                    return Err(self.error(
                        v,
                        format!(
                            "a second variable with id '{}', expected distinct ids",
                            spec.id
                        ),
                    ));
                }
                variables.push(spec);
            }
        }
        if variables.is_empty() {
            return Err(self
                .error(
                    conditions,
                    "no variables in <conditions>, expected at least one",
                )
                .with_hint(format!("variables are: {}", VARIABLES.join(", "))));
        }
        // A sun by the time of day needs the place it shines on; a clear sky is drawn
        // about one sun, and would not follow it.
        let timed = variables
            .iter()
            .filter(|s| matches!(s.kind, VariableKind::SunTime { .. }))
            .map(|s| s.line);
        for line in timed.chain(sun_schedule.as_ref().map(|s| s.2)) {
            let at = |msg: &str| Diagnostic::at_line(self.path, line, msg);
            if daylight.site.is_none() {
                return Err(at("<sunTime> moves the sun over a day at a place, and the problem has no <site>")
                    .with_hint("add <site latitude=\"-34.9\" longitude=\"-56.2\" timezone=\"-3\"/> under <input>"));
            }
            if daylight.sky.is_some_and(|s| s.kind == SkyKind::CieClear) {
                return Err(at("<sunTime> with a cie-clear <sky> is not supported: the clear sky is drawn about one sun and would not follow it")
                    .with_hint("use the cie-overcast sky, or no sky"));
            }
        }

        let objectives = only("objectives")?.ok_or_else(|| {
            self.error(
                root,
                "no <objectives>, expected one with <maximizeRadiance surface=\"…\"/>",
            )
        })?;
        self.check_attributes(
            objectives,
            &[
                "maxIterations",
                "fastEvaluationQuality",
                "strategy",
                "photons",
                "seed",
                "confidence",
                "maxBounces",
            ],
        );
        let max_iterations = self
            .number(objectives, "maxIterations", "a non-negative integer")?
            .unwrap_or(1000);
        let fast_quality =
            match self.real(objectives, "fastEvaluationQuality", "a number in (0, 1]")? {
                Some(q) if !(q > 0.0 && q <= 1.0) => {
                    return Err(self.error(
                        objectives,
                        format!("fastEvaluationQuality is {q}, expected a number in (0, 1]"),
                    ));
                }
                q => q.unwrap_or(0.25),
            };
        let strategy = match objectives.attribute("strategy") {
            None => Strategy::RefineOnIntersection,
            Some(s) => Strategy::parse(s.trim()).ok_or_else(|| {
                self.error(
                    objectives,
                    format!("strategy is '{s}', expected {}", Strategy::names()),
                )
            })?,
        };
        let photons = match self.number::<u64>(objectives, "photons", "a positive integer")? {
            Some(0) => {
                return Err(self.error(objectives, "photons is 0, expected a positive integer"));
            }
            p => p.unwrap_or(100_000),
        };
        let seed = self
            .number(objectives, "seed", "a non-negative integer")?
            .unwrap_or(1);
        let confidence = match self.real(objectives, "confidence", "a number in (0, 1)")? {
            None => Confidence::DEFAULT,
            Some(c) => Confidence::new(c).map_err(|e| self.error(objectives, e.to_string()))?,
        };
        let max_bounces = self.number(objectives, "maxBounces", "a non-negative integer")?;
        let mut goal: Option<(Goal, u32)> = None;
        let mut constraints = Vec::new();
        for o in self.elements(objectives) {
            let name = o.tag_name().name();
            if name == "constraint" {
                let c = self.constraint(o)?;
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
            let Some(parsed) = self.goal(o)? else {
                self.warn(
                    o,
                    format!(
                        "unknown objective <{name}> ignored (expected one of: {}, or <constraint>)",
                        GOALS.join(", ")
                    ),
                );
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
        let (goal, goal_line) = goal.ok_or_else(|| {
            self.error(
                objectives,
                format!(
                    "no goal in <objectives>, expected one of: {}",
                    GOALS.join(", ")
                ),
            )
        })?;

        let df = matches!(goal, Goal::MaximizeDaylightFactor { .. })
            || constraints
                .iter()
                .any(|c: &Constraint| matches!(c.bound, Bound::MinDaylightFactor(_)));
        if let (true, Some((_, _, line))) = (df, &sun_schedule) {
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
            cells_per_dimension,
            variables,
            goal,
            goal_line,
            constraints,
            max_iterations,
            fast_quality,
            strategy,
            photons,
            seed,
            confidence,
            max_bounces,
            daylight,
            sun_schedule,
            warnings: Vec::new(),
        })
    }

    /// A surface reference: `surface` and `side`.
    fn surface_ref(&self, node: Node) -> Result<SurfaceRef, Diagnostic> {
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

    /// `grid`: `auto` (EN 12464-1) or a spacing in metres.
    fn grid(&self, node: Node) -> Result<Grid, Diagnostic> {
        match node.attribute("grid").map(str::trim) {
            None | Some("auto") => Ok(Grid::Auto),
            Some(_) => match self.real(node, "grid", "auto or a spacing in metres")? {
                Some(m) if m > 0.0 => Ok(Grid::Spacing(m)),
                _ => Err(self.error(
                    node,
                    format!(
                        "'grid' of <{}> is not positive, expected auto or a spacing in metres",
                        node.tag_name().name()
                    ),
                )),
            },
        }
    }

    /// A positive illuminance attribute.
    fn lux(&self, node: Node, attr: &str) -> Result<Option<f64>, Diagnostic> {
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
    fn goal(&self, o: Node) -> Result<Option<Goal>, Diagnostic> {
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
                self.check_attributes(o, &["surface", "side", "grid"]);
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
        self.check_attributes(c, &[&["surface", "side", "grid"][..], &BOUNDS].concat());
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
        if c.attribute("grid").is_some() && bound.grid().is_none() {
            self.warn(
                c,
                format!(
                    "'grid' of a {} constraint ignored: it bounds the mean",
                    bound.attribute()
                ),
            );
        }
        Ok(Constraint {
            surface: self.surface_ref(c)?,
            bound,
            line: self.line(c),
        })
    }

    /// `<sunTime id days|date from to [step] [dayStep] objective="mean">`: the instants
    /// of [`SunSchedule`], `days="2026-01-01..2026-12-31"` (or one `date`) every
    /// `dayStep` days (default 1), each at the times of [`Reader::sun_time`].
    fn sun_schedule(&self, v: Node) -> Result<SunSchedule, Diagnostic> {
        const EXAMPLE: &str = "<sunTime id=\"Sun\" days=\"2026-01-01..2026-12-31\" dayStep=\"7\" from=\"08:00\" to=\"18:00\" step=\"60\" objective=\"mean\"/>";
        self.check_attributes(
            v,
            &[
                "id",
                "days",
                "date",
                "from",
                "to",
                "step",
                "dayStep",
                "objective",
            ],
        );
        let objective = self.required(v, "objective")?;
        if objective != "mean" {
            return Err(self
                .error(
                    v,
                    format!("'objective' of <sunTime> is '{objective}', expected mean"),
                )
                .with_hint(format!("for example {EXAMPLE}")));
        }
        let bad = |e| self.sun_time_error(v, e, EXAMPLE);
        let (first, last): (Date, Date) = match (v.attribute("days"), v.attribute("date")) {
            (Some(days), None) => {
                let (a, b) = days.split_once("..").ok_or_else(|| {
                    self.error(
                        v,
                        format!("'days' of <sunTime> is '{days}', expected FIRST..LAST"),
                    )
                    .with_hint(format!("for example {EXAMPLE}"))
                })?;
                (
                    a.trim().parse().map_err(bad)?,
                    b.trim().parse().map_err(bad)?,
                )
            }
            (None, Some(date)) => {
                let d: Date = date.parse().map_err(bad)?;
                (d, d)
            }
            _ => {
                return Err(self
                    .error(
                        v,
                        "<sunTime objective=\"mean\"> needs 'days' or 'date', not both",
                    )
                    .with_hint(format!("for example {EXAMPLE}")));
            }
        };
        if last < first {
            return Err(self.error(v, format!("'days' of <sunTime> runs from {first} back to {last}, expected the first day first")));
        }
        let day_step = match self.number(v, "dayStep", "a whole number of days")? {
            None => 1,
            Some(0) => {
                return Err(self.error(v, "'dayStep' of <sunTime> is 0, expected at least 1 day"));
            }
            Some(n) => n as u32,
        };
        let (from, to, step) = self.sun_times(v, EXAMPLE)?;
        let schedule = SunSchedule {
            first,
            last,
            day_step,
            from,
            to,
            step,
        };
        let n = schedule.instants().len();
        if n > 20_000 {
            return Err(self.error(v, format!("<sunTime> has {n} instants, expected at most 20 000 (one sun each): take a longer step or dayStep")));
        }
        Ok(schedule)
    }

    /// `<sunTime id date from to [step]>`: the time of day as a variable, on `date`.
    fn sun_time(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        const EXAMPLE: &str =
            "<sunTime id=\"Sun\" date=\"2026-12-21\" from=\"08:00\" to=\"18:00\" step=\"10\"/>";
        self.check_attributes(v, &["id", "date", "from", "to", "step"]);
        let date: Date = self
            .required(v, "date")?
            .parse()
            .map_err(|e| self.sun_time_error(v, e, EXAMPLE))?;
        let (from, to, step) = self.sun_times(v, EXAMPLE)?;
        Ok(VariableKind::SunTime {
            date,
            from,
            to,
            step,
        })
    }

    /// A daylight error of `<sunTime>` `v`, with what the element looks like.
    fn sun_time_error(
        &self,
        v: Node,
        e: invlight_scene::daylight::DaylightError,
        example: &str,
    ) -> Diagnostic {
        self.error(v, format!("<sunTime>: {e}"))
            .with_hint(format!("for example {example}"))
    }

    /// A `<sunTime>`'s `from`, `to` (minutes after local midnight) and `step` (minutes,
    /// 10 by default): whole steps from `from` to `to` within one day.
    fn sun_times(&self, v: Node, example: &str) -> Result<(f64, f64, f64), Diagnostic> {
        let minutes = |attr: &str| -> Result<f64, Diagnostic> {
            let t: TimeOfDay = self
                .required(v, attr)?
                .parse()
                .map_err(|e| self.sun_time_error(v, e, example))?;
            Ok(t.seconds_of_day() / 60.0)
        };
        let (from, to) = (minutes("from")?, minutes("to")?);
        let step = match self.real(v, "step", "minutes")? {
            None => 10.0,
            Some(s) if s > 0.0 && s <= 1440.0 => s,
            Some(s) => {
                return Err(self.error(
                    v,
                    format!("'step' of <sunTime> is {s}, expected minutes in (0, 1440]"),
                ));
            }
        };
        let steps = (to - from) / step;
        if !(from < to && (steps - steps.round()).abs() < 1e-6) {
            return Err(self
                .error(
                    v,
                    format!("<sunTime> runs from {from} to {to} minutes after midnight in steps of {step}, expected from before to and a whole number of steps between them"),
                )
                .with_hint(format!("for example {example}")));
        }
        Ok((from, to, step))
    }

    fn vertices(&self, v: Node) -> Result<[usize; 4], Diagnostic> {
        let mut out = [0, 1, 2, 3];
        for (k, attr) in VERTEX_ATTRS.iter().enumerate() {
            if let Some(i) = self.number(v, attr, "a vertex index (0, 1, 2, …)")? {
                out[k] = i;
            }
        }
        Ok(out)
    }

    fn variable(&self, v: Node) -> Result<Option<VariableSpec>, Diagnostic> {
        let name = v.tag_name().name();
        let kind = match name {
            "objectInSurface" | "lightInSurface" | "holeInSurface" => {
                let mut known = vec!["id", "surface", "anchor"];
                known.extend(VERTEX_ATTRS);
                self.check_attributes(v, &known);
                let anchor = match v.attribute("anchor").map(str::trim) {
                    None | Some("vertexA") => Anchor::VertexA,
                    Some("centre" | "center") => Anchor::Centre,
                    Some(other) => {
                        return Err(self.error(
                            v,
                            format!("'anchor' of <{name}> is '{other}', expected vertexA (P is where vertex A goes, ILPSolver's rule) or centre (P is where the object's own centre or the light goes)"),
                        ));
                    }
                };
                let spec = PlacementSpec {
                    surface: self.required(v, "surface")?,
                    vertices: self.vertices(v)?,
                    anchor,
                };
                match name {
                    "objectInSurface" => VariableKind::ObjectInSurface(spec),
                    "lightInSurface" => VariableKind::LightInSurface(spec),
                    _ => VariableKind::HoleInSurface(spec),
                }
            }
            "directionalLight" => {
                self.check_attributes(v, &["id"]);
                VariableKind::DirectionalLight
            }
            "holeSize" => {
                self.check_attributes(v, &["id", "minScale", "maxScale"]);
                let what = "a positive scale of the hole (1 is its authored size)";
                let scale = |attr: &str, default: f64| -> Result<f64, Diagnostic> {
                    match self.real(v, attr, what)? {
                        Some(x) if x <= 0.0 => Err(self
                            .error(v, format!("'{attr}' of <holeSize> is {x}, expected {what}"))),
                        x => Ok(x.unwrap_or(default)),
                    }
                };
                let (min, max) = (scale("minScale", 0.5)?, scale("maxScale", 2.0)?);
                if min >= max {
                    return Err(self.error(
                        v,
                        format!("<holeSize> has minScale {min} ≥ maxScale {max}, expected minScale < maxScale"),
                    ));
                }
                VariableKind::HoleSize { min, max }
            }
            "sunTime" => self.sun_time(v)?,
            "objectRotation" => {
                self.check_attributes(v, &["id", "min", "max"]);
                let what = "an angle in degrees";
                let min = self.real(v, "min", what)?.unwrap_or(0.0);
                let max = self.real(v, "max", what)?.unwrap_or(360.0);
                if !(min < max && max - min <= 360.0) {
                    return Err(self.error(
                        v,
                        format!("<objectRotation> has min {min}° and max {max}°, expected min < max ≤ min + 360°"),
                    ));
                }
                VariableKind::ObjectRotation { min, max }
            }
            "lightAim" => {
                self.check_attributes(v, &["id", "maxTilt"]);
                let what = "the largest tilt from the authored aim, degrees in (0, 90]";
                match self.real(v, "maxTilt", what)? {
                    Some(t) if t > 0.0 && t <= 90.0 => VariableKind::LightAim { max_tilt: t },
                    Some(t) => {
                        return Err(self.error(
                            v,
                            format!("'maxTilt' of <lightAim> is {t}, expected {what}"),
                        ));
                    }
                    None => {
                        return Err(self.error(v, format!("<lightAim> needs 'maxTilt', {what}")));
                    }
                }
            }
            "color" => {
                self.check_attributes(v, &["id", "hue", "saturation", "min", "max"]);
                let need = |attr: &str, lo: f64, hi: f64| -> Result<f64, Diagnostic> {
                    self.unit(v, attr, lo, hi)?.ok_or_else(|| {
                        self.error(
                            v,
                            format!("<color> needs '{attr}', a number in [{lo}, {hi}]"),
                        )
                    })
                };
                let hue = need("hue", 0.0, 360.0)?;
                let saturation = need("saturation", 0.0, 1.0)?;
                let min = self.unit(v, "min", 0.0, 1.0)?.unwrap_or(0.0);
                let max = self.unit(v, "max", 0.0, 1.0)?.unwrap_or(1.0);
                if min >= max {
                    return Err(self.error(
                        v,
                        format!("<color> has min {min} ≥ max {max}, expected min < max"),
                    ));
                }
                VariableKind::Color {
                    hue,
                    saturation,
                    min,
                    max,
                }
            }
            "lightPower" => {
                self.check_attributes(v, &["id", "min", "max"]);
                let level = |attr: &str, default: f64| -> Result<f64, Diagnostic> {
                    match self.real(v, attr, "a level (1 is the authored output)")? {
                        Some(x) if x < 0.0 => Err(self.error(
                            v,
                            format!("'{attr}' of <lightPower> is {x}, expected a level ≥ 0 (1 is the authored output)"),
                        )),
                        x => Ok(x.unwrap_or(default)),
                    }
                };
                let (min, max) = (level("min", 0.0)?, level("max", 1.0)?);
                if min >= max {
                    return Err(self.error(
                        v,
                        format!("<lightPower> has min {min} ≥ max {max}, expected min < max"),
                    ));
                }
                VariableKind::LightPower { min, max }
            }
            other => {
                self.warn(
                    v,
                    format!(
                        "unknown variable <{other}> ignored (expected one of: {})",
                        VARIABLES.join(", ")
                    ),
                );
                return Ok(None);
            }
        };
        Ok(Some(VariableSpec {
            id: self.required(v, "id")?,
            kind,
            line: self.line(v),
        }))
    }
}

/// `"20"` → [20]; `"20x6"` → [20, 6].
fn parse_mesh(s: &str) -> Option<Vec<u32>> {
    let v: Option<Vec<u32>> = s
        .trim()
        .split(['x', 'X'])
        .map(|p| p.trim().parse().ok().filter(|&n| n > 0))
        .collect();
    v.filter(|v| !v.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Problem, Diagnostic> {
        Problem::parse(Path::new("/p/problem.xml"), text)
    }

    /// `<site>`, `<sun>` and `<sky>` read into the problem's daylight; mistakes name
    /// their line and show the element's form.
    #[test]
    fn daylight_elements() {
        use invlight_scene::daylight::SkyKind;
        let body = "<scene path=\"s.gltf\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives>";
        let with = |extra: &str| parse(&format!("<input>{body}\n{extra}</input>"));
        let p = with(
            r#"<site latitude="-34.9" longitude="-56.2" timezone="-3" north="30"/>
<sun date="2025-12-21" time="10:00"/><sky type="cie-overcast" horizontalLux="10000"/>"#,
        )
        .unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        let site = p.daylight.site.unwrap();
        assert_eq!((site.latitude(), site.north()), (-34.9, 30.0));
        assert_eq!(p.daylight.sun.unwrap().time.hour(), 10);
        let sky = p.daylight.sky.unwrap();
        assert_eq!(
            (sky.kind, sky.horizontal_lux),
            (SkyKind::CieOvercast, 10_000.0)
        );
        assert!(with("").unwrap().daylight.is_empty());
        let night = with(
            r#"<site latitude="-34.9" longitude="-56.2" timezone="-3"/>
<sun date="2025-12-21" time="23:00"/>"#,
        )
        .unwrap();
        assert_eq!(night.warnings.len(), 1, "{:?}", night.warnings);
        assert_eq!(night.warnings[0].line, Some(3));
        assert!(night.warnings[0].to_string().contains("below the horizon"));
        for (extra, what) in [
            (r#"<sun date="2025-12-21" time="10:00"/>"#, "needs the site"),
            (
                r#"<sky type="cie-sunny" horizontalLux="5"/>"#,
                "cie-overcast or cie-clear",
            ),
            (r#"<sky type="cie-overcast"/>"#, "horizontalLux"),
            (
                r#"<site latitude="-94" longitude="0" timezone="0"/>"#,
                "latitude",
            ),
            (r#"<site latitude="10" timezone="0"/>"#, "longitude"),
        ] {
            let e = with(extra).unwrap_err();
            assert_eq!(e.line, Some(2), "{extra}: {e}");
            assert!(e.to_string().contains(what), "{extra}: {e}");
        }
    }

    /// `<sunTime>`: whole steps between two clock times of one date, at the problem's
    /// site; mistakes name their line.
    #[test]
    fn sun_time_variable() {
        let with = |site: &str, sky: &str, var: &str| {
            parse(&format!(
                "<input><scene path=\"s.gltf\"/>{site}{sky}\n<conditions>{var}</conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>"
            ))
        };
        let site = r#"<site latitude="0" longitude="0" timezone="0"/>"#;
        let var = r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="18:00" step="30"/>"#;
        let p = with(site, "", var).unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        let VariableKind::SunTime {
            date,
            from,
            to,
            step,
        } = &p.variables[0].kind
        else {
            panic!("{:?}", p.variables);
        };
        assert_eq!((date.day(), *from, *to, *step), (21, 480.0, 1080.0, 30.0));
        let default_step = r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="09:00"/>"#;
        let p = with(site, "", default_step).unwrap();
        assert!(matches!(
            p.variables[0].kind,
            VariableKind::SunTime { step: 10.0, .. }
        ));
        let clear =
            r#"<sun date="2026-12-21" time="12:00"/><sky type="cie-clear" horizontalLux="9000"/>"#;
        let mean = r#"<color id="W" hue="0" saturation="0"/><sunTime id="Sun" days="2026-01-01..2026-12-31" dayStep="7" from="08:00" to="18:00" step="60" objective="mean"/>"#;
        let p = with(site, "", mean).unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        assert_eq!(p.variables.len(), 1);
        let (id, schedule, line) = p.sun_schedule.as_ref().unwrap();
        assert_eq!((id.as_str(), *line), ("Sun", 2));
        assert_eq!(schedule.instants().len(), 53 * 11);
        let df = parse(&format!(
            "<input><scene path=\"s.gltf\"/>{site}\n<conditions>{mean}</conditions><objectives><maximizeDaylightFactor surface=\"F\"/></objectives></input>"
        ))
        .unwrap_err();
        assert!(df.to_string().contains("daylight-factor"), "{df}");
        for (site, sky, var, what) in [
            ("", "", mean, "no <site>"),
            (site, "", &mean.replace("..", "/"), "FIRST..LAST"),
            (
                site,
                "",
                &mean.replace("\"mean\"", "\"max\""),
                "expected mean",
            ),
            (
                site,
                "",
                &mean.replace("days=", "date=\"2026-01-01\" days="),
                "not both",
            ),
            (
                site,
                "",
                &mean.replace("dayStep=\"7\"", "dayStep=\"0\""),
                "dayStep",
            ),
            (
                site,
                "",
                &mean.replace("2026-12-31", "2025-12-31"),
                "first day first",
            ),
            ("", "", var, "no <site>"),
            (site, clear, var, "cie-clear"),
            (
                site,
                "",
                r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="18:05" step="30"/>"#,
                "whole number of steps",
            ),
            (
                site,
                "",
                r#"<sunTime id="Sun" date="2026-12-21" from="18:00" to="08:00"/>"#,
                "from before to",
            ),
            (
                site,
                "",
                r#"<sunTime id="Sun" date="2026-02-30" from="08:00" to="09:00"/>"#,
                "28 days",
            ),
            (
                site,
                "",
                r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="24:00"/>"#,
                "24:00",
            ),
            (
                site,
                "",
                r#"<sunTime id="Sun" date="2026-12-21" from="08:00" to="09:00" step="0"/>"#,
                "step",
            ),
        ] {
            let e = with(site, sky, var).unwrap_err();
            assert_eq!(e.line, Some(2), "{var}: {e}");
            assert!(e.to_string().contains(what), "{var}: {e}");
        }
    }

    /// `<maximizeDaylightFactor>` and `minDaylightFactor` read as the goal and bound of
    /// that name, in per cent, with the line a daylight-factor problem reports.
    #[test]
    fn daylight_factor_intentions() {
        let p = parse(
            r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeDaylightFactor surface="Desk" side="front"/>
<constraint surface="Floor" minDaylightFactor="2"/></objectives></input>"#,
        )
        .unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        assert_eq!(p.goal.element(), "maximizeDaylightFactor");
        assert_eq!(p.goal.unit(), "DF %");
        assert_eq!(p.goal.surface().unwrap().side, Side::Front);
        assert_eq!(p.settings().sense, Sense::Maximize);
        assert_eq!(p.constraints[0].bound, Bound::MinDaylightFactor(2.0));
        assert_eq!(p.constraints[0].label(), "Floor.minDaylightFactor");
        assert_eq!(p.daylight_factor_line(), Some(2));
        let lux = parse(
            r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeRadiance surface="Desk"/>
<constraint surface="Floor" minDaylightFactor="2"/></objectives></input>"#,
        )
        .unwrap();
        assert_eq!(lux.daylight_factor_line(), Some(3));
        let e = parse(
            r#"<input><scene path="s.gltf"/><conditions><holeSize id="H"/></conditions>
<objectives><maximizeRadiance surface="Desk"/>
<constraint surface="Floor" minDaylightFactor="120"/></objectives></input>"#,
        )
        .unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.to_string().contains("[0, 100]"), "{e}");
    }

    #[test]
    fn later_form_with_everything() {
        let p = parse(
            r#"<?xml version="1.0"?>
<input>
  <scene path="room.gltf" scale="0.001" up="z"/>
  <output path="out"/>
  <conditions meshSize="20x6">
    <objectInSurface id="Cone" surface="Cone__Geometry" vertexAIndex="3" vertexBIndex="0" vertexCIndex="2" vertexDIndex="1"/>
    <lightInSurface id="Lamp" surface="Ceiling" anchor="centre"/>
    <holeInSurface id="Hole" surface="Roof"/>
    <directionalLight id="Sun"/>
    <color id="Walls" hue="39" saturation="0.23" max="0.9"/>
  </conditions>
  <objectives maxIterations="50" fastEvaluationQuality="0.0078125" strategy="REFINE_ISOC_ON_END" photons="5000" seed="3" confidence="0.9" maxBounces="4">
    <maximizeRadiance surface="Floor" maxRadiosity="300"/>
  </objectives>
</input>"#,
        )
        .unwrap();
        assert_eq!(p.scene.path, Path::new("/p/room.gltf"));
        assert_eq!((p.scene.scale, p.scene.up), (Some(0.001), Some(UpAxis::Z)));
        assert_eq!(p.output, Path::new("/p/out"));
        assert_eq!(p.cells_per_dimension, vec![20, 6]);
        assert_eq!(p.variables.len(), 5);
        assert_eq!(
            p.variables[0].kind,
            VariableKind::ObjectInSurface(PlacementSpec {
                surface: "Cone__Geometry".into(),
                vertices: [3, 0, 2, 1],
                anchor: Anchor::VertexA,
            })
        );
        assert_eq!(
            p.variables[1].kind.placement().map(|p| p.anchor),
            Some(Anchor::Centre)
        );
        assert_eq!(p.variables[0].line, 6);
        assert_eq!(
            p.variables[4].kind,
            VariableKind::Color {
                hue: 39.0,
                saturation: 0.23,
                min: 0.0,
                max: 0.9
            }
        );
        assert!(matches!(
            p.goal,
            Goal::Maximize {
                cap: Some(300.0),
                ..
            }
        ));
        assert_eq!(p.strategy, Strategy::RefineOnEnd);
        assert_eq!(
            (p.photons, p.seed, p.max_bounces, p.max_iterations),
            (5000, 3, Some(4), 50)
        );
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    #[test]
    fn thesis_form_with_bare_attribute() {
        let p = parse(
            "<input>\n<scene path=\"cube.dae\"/>\n<conditions>\n<directionalLight id=\"Sun\"/>\n</conditions>\n<objectives maxIterations=1000>\n<maximizeRadiance surface=\"S\"/>\n</objectives>\n</input>",
        )
        .unwrap();
        assert_eq!(p.max_iterations, 1000);
        assert_eq!(p.cells_per_dimension, vec![20]);
        assert_eq!(p.warnings.len(), 1);
        assert_eq!(p.warnings[0].line, Some(6));
        assert_eq!(p.strategy, Strategy::RefineOnIntersection);
        assert_eq!((p.photons, p.confidence), (100_000, Confidence::DEFAULT));
    }

    #[test]
    fn unknown_things_are_warnings() {
        let p = parse(
            "<input><scene path=\"s.obj\" units=\"mm\"/><camera/>\n<conditions meshSize=\"4\"><color id=\"W\" hue=\"0\" saturation=\"0\"/><spin id=\"x\"/></conditions>\n<objectives><maximizeRadiance surface=\"F\"/><minimizeGlare/></objectives></input>",
        )
        .unwrap();
        let msgs: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
        assert_eq!(msgs.len(), 4, "{msgs:?}");
        assert!(
            msgs.iter()
                .any(|m| m.contains("'units'") && m.starts_with("/p/problem.xml:1:"))
        );
        assert!(msgs.iter().any(|m| m.contains("<camera>")));
        assert!(
            msgs.iter()
                .any(|m| m.contains("<spin>") && m.contains(":2:"))
        );
        assert!(
            msgs.iter()
                .any(|m| m.contains("<minimizeGlare>") && m.contains(":3:"))
        );
    }

    #[test]
    fn nonsense_values_are_errors() {
        for (objectives, what) in [
            (
                "<maximizeRadiance surface=\"F\" maxRadiosity=\"NaN\"/>",
                "maxRadiosity",
            ),
            (
                "<maximizeRadiance surface=\"F\" maxRadiosity=\"0\"/>",
                "positive",
            ),
            (
                "<maximizeRadiance surface=\"F\" maxRadiosity=\"-3\"/>",
                "positive",
            ),
        ] {
            let e = parse(&format!("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n<objectives>{objectives}</objectives></input>")).unwrap_err();
            assert_eq!(e.line, Some(2), "{e}");
            assert!(e.to_string().contains(what), "{e}");
        }
        let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions><objectives confidence=\"inf\"><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert!(e.message.contains("confidence"), "{e}");
        let e = parse("<input><scene path=\"s.obj\" scale=\"-1\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert!(e.message.contains("scale"), "{e}");
        let e = parse("<input><scene path=\"s.obj\" up=\"x\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert!(e.message.contains("'up'"), "{e}");
        let e = parse("<input><scene path=\"s.obj\"/><conditions><lightInSurface id=\"L\" surface=\"C\" anchor=\"middle\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert!(e.message.contains("centre"), "{e}");
    }

    /// Every intention element reads, with its sides and grids; mistakes are errors on
    /// their line.
    #[test]
    fn intentions_read_and_their_mistakes_are_errors() {
        let wrap = |objectives: &str| {
            format!(
                "<input><scene path=\"s.obj\"/><conditions><lightPower id=\"L\" min=\"0.2\"/><lightInSurface id=\"L\" surface=\"C\"/></conditions>\n<objectives>{objectives}</objectives></input>"
            )
        };
        let p = parse(&wrap(
            "<minimizePower/><constraint surface=\"Desk\" side=\"front\" minLux=\"500\"/><constraint surface=\"Desk\" side=\"front\" minUniformity=\"0.6\"/><constraint surface=\"Screen\" maxLux=\"300\"/><constraint surface=\"Desk\" minPointLux=\"300\" grid=\"0.25\"/>",
        ))
        .unwrap();
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        assert_eq!(p.goal, Goal::MinimizePower);
        let labels: Vec<String> = p.constraints.iter().map(Constraint::label).collect();
        assert_eq!(
            labels,
            [
                "Desk.front.minLux",
                "Desk.front.minUniformity",
                "Screen.maxLux",
                "Desk.minPointLux"
            ]
        );
        assert_eq!(
            p.constraints[1].bound,
            Bound::MinUniformity(0.6, Grid::Auto)
        );
        assert_eq!(
            p.constraints[3].bound,
            Bound::MinPointLux(300.0, Grid::Spacing(0.25))
        );
        assert_eq!(
            p.variables[0].kind,
            VariableKind::LightPower { min: 0.2, max: 1.0 }
        );
        assert_eq!(VariableSpec::key(&p.variables, 0), "L.power");
        assert_eq!(VariableSpec::key(&p.variables, 1), "L");
        let settings = p.settings();
        assert_eq!(settings.sense, Sense::Minimize);
        assert_eq!(settings.constraints.len(), 4);
        for (goal, sense) in [
            (
                "<targetRadiance surface=\"D\" lux=\"500\"/>",
                Sense::Target(500.0),
            ),
            (
                "<minimizeRadiance surface=\"D\" side=\"back\"/>",
                Sense::Minimize,
            ),
            (
                "<maximizeUniformity surface=\"D\" grid=\"auto\"/>",
                Sense::Maximize,
            ),
        ] {
            assert_eq!(
                parse(&wrap(goal)).unwrap().settings().sense,
                sense,
                "{goal}"
            );
        }
        for (objectives, what) in [
            ("", "no goal"),
            ("<minimizePower/><minimizePower/>", "a second goal"),
            ("<targetRadiance surface=\"D\"/>", "'lux'"),
            ("<targetRadiance surface=\"D\" lux=\"-5\"/>", "positive"),
            ("<minimizePower/><constraint surface=\"D\"/>", "no bound"),
            (
                "<minimizePower/><constraint surface=\"D\" minLux=\"1\" maxLux=\"2\"/>",
                "exactly one",
            ),
            (
                "<minimizePower/><constraint surface=\"D\" minUniformity=\"1.5\"/>",
                "minUniformity",
            ),
            (
                "<minimizePower/><constraint surface=\"D\" minLux=\"5\" side=\"top\"/>",
                "front, back or both",
            ),
            (
                "<minimizePower/><constraint surface=\"D\" minPointLux=\"5\" grid=\"-1\"/>",
                "grid",
            ),
            (
                "<minimizePower/><constraint surface=\"D\" minLux=\"5\"/><constraint surface=\"D\" minLux=\"7\"/>",
                "a second minLux",
            ),
        ] {
            let e = parse(&wrap(objectives)).unwrap_err();
            assert!(e.to_string().contains(what), "{objectives}: {e}");
            assert!(e.line.is_some(), "{e}");
        }
        for (conditions, what) in [
            (
                "<lightPower id=\"L\" min=\"0.5\" max=\"0.5\"/>",
                "min < max",
            ),
            ("<lightPower id=\"L\" min=\"-1\"/>", "≥ 0"),
            (
                "<lightPower id=\"L\"/><lightPower id=\"L\"/>",
                "a second variable",
            ),
            (
                "<color id=\"L\" hue=\"0\" saturation=\"0\"/><lightPower id=\"L\"/>",
                "a second variable",
            ),
        ] {
            let text = format!(
                "<input><scene path=\"s.obj\"/><conditions>{conditions}</conditions><objectives><minimizePower/></objectives></input>"
            );
            let e = parse(&text).unwrap_err();
            assert!(e.to_string().contains(what), "{conditions}: {e}");
        }
        // 'grid' on a bound of the mean is ignored with a warning.
        let p = parse(&wrap(
            "<minimizePower/><constraint surface=\"D\" minLux=\"5\" grid=\"1\"/>",
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    }

    /// A scene path that does not exist is named with the problem file's line and the
    /// folder it is relative to.
    #[test]
    fn a_missing_scene_says_where_paths_are_relative_to() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("problem.xml");
        std::fs::write(&path, "<input>\n<scene path=\"nowhere.gltf\"/><conditions><directionalLight id=\"S\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap();
        let p = Problem::read(&path).unwrap();
        let e = p
            .load_scene(&LoadOptions::default(), None, None, &[])
            .unwrap_err();
        assert_eq!(e.line, Some(2));
        let text = e.to_string();
        assert!(
            text.contains("nowhere.gltf") && text.contains("relative to the problem file"),
            "{text}"
        );
        assert!(text.contains(&dir.path().display().to_string()), "{text}");
    }

    #[test]
    fn errors_name_line_and_expectation() {
        let e = parse("<input>\n<scene path=\"s.obj\"/>\n<conditions>\n<lightInSurface id=\"L\"/>\n</conditions>\n<objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("'surface'"), "{e}");
        let e = parse("<input>\n<scene path=\"s.obj\"/>\n<conditions meshSize=\"20y\"><directionalLight id=\"S\"/></conditions>\n<objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(e.message.contains("meshSize"), "{e}");
        let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions>\n\n<objectives strategy=\"FAST\"><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(e.message.contains("REFINE_ISOC_ON_END"), "{e}");
        let e = parse("<input><scene path=\"s.obj\"/><conditions><directionalLight id=\"S\"/></conditions></input>").unwrap_err();
        assert!(e.message.contains("<objectives>"), "{e}");
        let e = parse("<input><scene path=\"s.obj\"/>\n<conditions><color id=\"W\" hue=\"400\" saturation=\"0.2\"/></conditions><objectives><maximizeRadiance surface=\"F\"/></objectives></input>").unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("[0, 360]"), "{e}");
        let e = parse("<input><scene path=\"s.obj\"></input>").unwrap_err();
        assert!(e.message.contains("XML"), "{e}");
    }

    #[test]
    fn mesh_sizes() {
        assert_eq!(parse_mesh("20"), Some(vec![20]));
        assert_eq!(parse_mesh(" 20x6 "), Some(vec![20, 6]));
        assert_eq!(parse_mesh("0"), None);
        assert_eq!(parse_mesh("x"), None);
    }
}

#[cfg(test)]
mod files {
    use super::*;

    #[test]
    fn ilpsolver_examples_parse() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilpsolver");
        let mut n = 0;
        for entry in std::fs::read_dir(&dir).expect("tests/data/ilpsolver") {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "xml") {
                let p = Problem::read(&path).unwrap_or_else(|e| panic!("{e}"));
                assert!(p.warnings.is_empty(), "{:?}", p.warnings);
                assert!(!p.variables.is_empty());
                n += 1;
            }
        }
        assert_eq!(n, 7);
        let cone = Problem::read(&dir.join("cornell-move-cone.xml")).unwrap();
        assert_eq!(cone.cells_per_dimension, vec![200]);
        assert_eq!(cone.strategy, Strategy::RefineOnEnd);
        assert_eq!(cone.fast_quality, 0.00390625);
        let color = Problem::read(&dir.join("sponza-color.xml")).unwrap();
        assert!(matches!(
            color.goal,
            Goal::Maximize {
                cap: Some(0.0003),
                ..
            }
        ));
    }

    #[test]
    fn thesis_appendix_d_parses() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/ilp/appendix-d.xml");
        let p = Problem::read(&path).unwrap();
        let kinds: Vec<&str> = p.variables.iter().map(|v| v.kind.name()).collect();
        assert_eq!(
            kinds,
            [
                "holeInSurface",
                "directionalLight",
                "lightInSurface",
                "objectInSurface",
                "color"
            ]
        );
        assert_eq!(p.max_iterations, 1000);
        assert_eq!(p.warnings.len(), 1, "the unquoted maxIterations");
        assert_eq!(p.warnings[0].line, Some(28));
        assert_eq!(p.goal.surface().unwrap().name, "Suzzane");
    }
}
