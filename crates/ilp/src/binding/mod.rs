//! Binding a problem's variables to a scene, and applying configurations to it (thesis
//! §4.5). Applying changes only what moved, as OptiX transform nodes did for ILPSolver:
//! instance transforms (so the acceleration structure rebuilds only its top level),
//! light positions and directions, material K_d.
//!
//! One binder per variable kind finds what a variable changes and its domain:
//! `placement.rs` (`objectInSurface`, `lightInSurface`), `hole.rs` (`holeInSurface`,
//! `holeSize`), `sun.rs` (`directionalLight`, `sunTime`), `aim.rs`, `rotation.rs`,
//! `power.rs` and `colour.rs`; `value.rs` turns a configuration into world values and
//! back, `layout.rs` reads interchangeable lamps as the array a designer would draw.

mod aim;
mod array;
mod colour;
mod conflicts;
mod exchangeable;
mod fittings;
mod hole;
mod layout;
mod placement;
mod power;
mod refusal;
mod rotation;
mod solved;
mod sun;
mod value;

pub use colour::hsv_to_rgb;
pub use layout::{ArrayLayout, Layout, regular_array};
pub use placement::Bounds;
pub use value::{ConfigurationError, VariableValue};

use crate::intention::{Constraint, Goal};
use crate::problem::{Problem, SunClock, VariableKind, VariableSpec};
use crate::reading::Reading;
use crate::space::{Configuration, Domain, Space, Variable};
use glam::{DVec3, Mat3, Mat4, Vec3};
use invlight_photon::{Components, Emitters, SourceOrigin};
use invlight_scene::daylight::daylight_factor_scene;
use invlight_scene::{
    Diagnostic, InstanceId, LightId, LightKind, MaterialId, Scene, SurfaceId, known_names,
};
use placement::instance_bounds;
use power::Dimmed;

/// What a placement moves, and how P turns into a translation.
#[derive(Debug, Clone)]
struct Moved {
    instances: Vec<(InstanceId, Mat4)>,
    lights: Vec<(LightId, Vec3)>,
    /// The point P stands for as authored: vertex A (ILPSolver's rule) or the anchor.
    reference: DVec3,
    /// The anchor as authored.
    anchor: DVec3,
    /// What moves, as authored (instances' boxes and light positions).
    bounds: Bounds,
}

/// What a variable changes in the scene, with the state it started from.
#[derive(Debug, Clone)]
enum Target {
    /// Instances and point/spot lights translated by P − reference.
    Move(Moved),
    /// A directional light's direction.
    Sun { light: LightId },
    /// The aim of a spot or goniometric light, or of a `<lightGroup>`'s lamps: each
    /// light with its authored aim `axis` and `frame`, all turned by the shortest
    /// rotation from the first one's axis to the aim (a luminaire's authored frame
    /// turns with it, C0 included).
    Aim { lights: Vec<(LightId, Vec3, Mat3)> },
    /// Materials' K_d.
    Colour {
        materials: Vec<MaterialId>,
        hue: f64,
        saturation: f64,
    },
    /// A light's or emissive object's output, kept apart as component `component`.
    Power { dimmed: Dimmed, component: usize },
    /// A hole's instances, with their authored transforms, scaled uniformly about
    /// `centre`, their box's centre as authored.
    Scale {
        instances: Vec<(InstanceId, Mat4)>,
        centre: Vec3,
    },
    /// A directional light set where the sun stands at a time.
    SunTime(SunClock),
    /// A `<lightArray>`'s lamps, set out as its shape and the rest off.
    Array(array::Lamps),
    /// An object's instances, or a light as authored, turned about `axis` (unit)
    /// through `centre` (the box's centre, the light's position).
    Rotate {
        instances: Vec<(InstanceId, Mat4)>,
        light: Option<(LightId, LightKind)>,
        axis: Vec3,
        centre: Vec3,
    },
}

/// A problem bound to a scene: the search space, where it starts, the objective and the
/// means to apply a configuration.
#[derive(Debug, Clone)]
pub struct Binding {
    /// The variables' space.
    pub space: Space,
    /// The scene as authored, as a configuration; where it is refused and an array is
    /// searched, the first of the structured starts that is not.
    pub initial: Configuration,
    /// What the goal and constraints measure.
    pub reading: Reading,
    /// The goal.
    pub goal: Goal,
    /// The constraints, in the problem's order.
    pub constraints: Vec<Constraint>,
    /// The problem file's variables, in the space's order.
    pub specs: Vec<VariableSpec>,
    /// Warnings found while binding (e.g. a `lightInSurface` object that emits nothing).
    pub warnings: Vec<Diagnostic>,
    targets: Vec<Target>,
    /// Where placed things may go: everything no variable moves, and every moved thing
    /// as authored.
    bounds: Option<Bounds>,
    /// The electric lights' authored power per component, in `power_unit` (daylight
    /// costs nothing).
    electric_power: Vec<f64>,
    /// Each light's own share of `electric_power`, by light index: what an array's
    /// lamp left off does not draw.
    light_power: Vec<f64>,
    /// What `electric_power` and [`Binding::power`] count.
    pub power_unit: PowerUnit,
    /// The lights that emit a photometric file's table (`--luminaire`, `<luminaire>`,
    /// `EXT_lights_ies`), in the scene's order: a run's numbers depend on them, so
    /// `run.json` records them and `--resume` checks them.
    pub luminaires: Vec<LuminaireUse>,
    /// The least-power levels' program and the variables it chooses, when the
    /// evaluator solves the dimming instead of the search ([`Binding::level_solver`]).
    level_solver: Option<(Vec<usize>, crate::dimming::LevelSolver)>,
    /// How many lights the scene has, and whether anything else emits (an emissive
    /// surface, a sky): what [`Binding::lit_only_by`] asks.
    sources: (usize, bool),
    /// The scene's lights' names, by light index.
    light_names: Vec<String>,
    /// The moved luminaires' outlines, which no candidate may overlap.
    fittings: Vec<fittings::Fitting>,
}

/// A light that emits a photometric file's candela table, as a run used it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LuminaireUse {
    /// The light's name.
    pub light: String,
    /// The IES or EULUMDAT file as it was given (`--luminaire`, `<luminaire file>`, a
    /// glTF `uri`); its name alone for a profile inside a glTF, and in folders written
    /// before the path was recorded.
    pub file: String,
    /// The file read, canonical; `None` for a profile inside a glTF and in folders
    /// written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<std::path::PathBuf>,
    /// The factor on the file's candela as authored (a problem file's `multiplier`, a
    /// glTF light's colour × intensity); `None` in folders written before it was
    /// recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplier: Option<f64>,
    /// The light's flux as authored (the table's times its multiplier), lm.
    pub lm: f64,
    /// Degrees a problem file turned it about its aim as loaded (`<luminaire rotation>`
    /// and a fixed `<lightArray orientation>`); `None` when not turned.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<f64>,
    /// Its length and width as installed (`<luminaire size>`), m; `None` when the
    /// file's stand.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 2]>,
}

/// What `minimizePower` minimises: electrical watts when every electric light's
/// photometric file gives them, else luminous flux — a designer's "least power" is
/// the meter's, but a point light or an emissive surface has no watts, and a sum of
/// some lamps' watts with other lamps' lumens would mean nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PowerUnit {
    /// Electrical power, W ([`LightKind::watts`]: the IES input watts, EULUMDAT's
    /// wattage with ballast).
    Watts,
    /// Luminous flux, lm.
    Lumens,
}

impl PowerUnit {
    /// `W` or `lm`.
    pub fn symbol(self) -> &'static str {
        match self {
            PowerUnit::Watts => "W",
            PowerUnit::Lumens => "lm",
        }
    }
}

impl Binding {
    /// Binds `problem` to `scene`. The scene is changed once here: the objects of
    /// `holeInSurface` variables get a hole material on a copy of their meshes, and a
    /// problem that asks for a daylight factor ([`Problem::daylight_factor_line`]) has
    /// its lights and emission turned off under its overcast sky, or one of 10 000 lx
    /// ([`daylight_factor_scene`]): the factor is that sky's light alone.
    pub fn new(problem: &Problem, scene: &mut Scene) -> Result<Binding, Diagnostic> {
        let path = problem.path.as_path();
        if let Some(line) = problem.daylight_factor_line() {
            daylight_factor_scene(scene).map_err(|e| {
                Diagnostic::at_line(path, line, e.to_string())
                    .with_hint("a daylight factor is measured under the CIE overcast sky alone, every light off")
            })?;
        }
        problem.build_eyes(scene)?;
        conflicts::framed_once(&problem.variables, path)?;
        let mut variables = Vec::new();
        let mut targets = Vec::new();
        let mut initial = Vec::new();
        let mut warnings = Vec::new();
        // Each sunTime's variable index and its cells: one per step, centred on it.
        let mut steps = Vec::new();
        for spec in &problem.variables {
            let err = |msg: String| Diagnostic::at_line(path, spec.line, msg);
            let (domain, target) = bind(problem, spec, scene, &targets, &err, &mut warnings)?;
            match spec.kind {
                VariableKind::SunTime { from, to, step, .. } => {
                    steps.push((variables.len(), ((to - from) / step).round() as u32 + 1));
                }
                // A level fixed by equal min and max is one cell: nothing to search.
                VariableKind::LightPower { min, max } if min == max => {
                    steps.push((variables.len(), 1));
                }
                _ => {}
            }
            initial.extend(initial_coords(scene, &domain, &target));
            if let Target::Power { dimmed, .. } = &target
                && let Some(first) = targets
                    .iter()
                    .position(|t| matches!(t, Target::Power { dimmed: d, .. } if d.same(dimmed)))
            {
                return Err(err(format!(
                    "a second <lightPower> of '{}', expected one per light (the first is '{}')",
                    spec.id, problem.variables[first].id
                )));
            }
            variables.push(Variable {
                id: spec.id.clone(),
                domain,
            });
            targets.push(target);
        }
        conflicts::placed_once(&targets, &problem.variables, scene, path)?;
        let reading = Reading::new(problem, scene)?;
        let bounds = reachable_bounds(scene, &targets);
        let cheap: Vec<usize> = targets
            .iter()
            .enumerate()
            .filter(|(_, t)| matches!(t, Target::Power { .. }))
            .map(|(i, _)| i)
            .collect();
        let exchangeable = exchangeable::exchangeable(scene, &problem.variables, &targets);
        let mut space = Space::new(variables, &problem.cells_per_dimension)
            .with_exchangeable(exchangeable)
            .with_cheap(&cheap);
        for (v, cells) in steps {
            space = space.with_cells(v, cells);
        }
        let mut binding = Binding {
            initial: Configuration { coords: initial },
            space,
            reading,
            goal: problem.goal.clone(),
            constraints: problem.constraints.clone(),
            specs: problem.variables.clone(),
            warnings,
            targets,
            bounds,
            electric_power: Vec::new(),
            light_power: Vec::new(),
            power_unit: PowerUnit::Lumens,
            luminaires: scene
                .lights
                .iter()
                .filter_map(|l| match &l.kind {
                    LightKind::Goniometric {
                        photometry,
                        multiplier,
                        ..
                    } => Some(LuminaireUse {
                        light: l.name.clone(),
                        file: match &photometry.source {
                            Some(s) => s.given.clone(),
                            None => photometry.file.clone(),
                        },
                        path: photometry.source.as_ref().map(|s| s.path.clone()),
                        multiplier: Some(f64::from(invlight_scene::luminance(*multiplier))),
                        lm: f64::from(invlight_scene::luminance(l.kind.flux())),
                        rotation: problem.turn_as_installed(&l.name),
                        size: problem.size_as_installed(&l.name),
                    }),
                    _ => None,
                })
                .collect(),
            level_solver: None,
            light_names: scene.lights.iter().map(|l| l.name.clone()).collect(),
            fittings: Vec::new(),
            sources: (
                scene.lights.len(),
                scene.sky.is_some() || scene.materials.iter().any(|m| m.is_emissive()),
            ),
        };
        (
            binding.electric_power,
            binding.light_power,
            binding.power_unit,
        ) = binding.component_power(scene);
        binding.fittings = fittings::fittings(scene, &binding.targets, &problem.scene.sizes);
        binding.initial = binding.first_start(binding.initial.clone());
        binding.solve_levels(problem.confidence);
        Ok(binding)
    }

    /// Whether the scene's light comes from `lamps` lights alone (no other light, no
    /// emissive surface, no sky): then a count of them is a count of all its lamps.
    pub fn lit_only_by(&self, lamps: usize) -> bool {
        self.sources == (lamps, false)
    }

    /// The number of components the lights' light is kept apart in: one for the lights
    /// no variable dims, one per `lightPower` variable.
    pub fn component_count(&self) -> usize {
        1 + self
            .targets
            .iter()
            .filter(|t| matches!(t, Target::Power { .. }))
            .count()
    }

    /// Which component each light and emissive instance of `scene` is in.
    pub fn components(&self, scene: &Scene) -> Components {
        let mut c = Components::new(scene, self.component_count());
        for t in &self.targets {
            if let Target::Power { dimmed, component } = t {
                match dimmed {
                    Dimmed::Light { light, .. } => c.set_light(*light, *component),
                    Dimmed::Group(lights) => {
                        lights.iter().for_each(|&(l, _)| c.set_light(l, *component))
                    }
                    Dimmed::Emissive { instances, .. } => instances
                        .iter()
                        .for_each(|&i| c.set_instance(i, *component)),
                }
            }
        }
        c
    }

    /// Each component's electric power as authored, every light but the sun: watts
    /// when every electric light has them ([`PowerUnit`]), else lumens.
    fn component_power(&self, scene: &Scene) -> (Vec<f64>, Vec<f64>, PowerUnit) {
        let emitters = Emitters::new(scene);
        let components = self.components(scene);
        let (mut flux, mut watts) = (
            vec![0.0; self.component_count()],
            Some(vec![0.0; self.component_count()]),
        );
        let (mut light_flux, mut light_watts) =
            (vec![0.0; scene.lights.len()], vec![0.0; scene.lights.len()]);
        let mut counted = vec![false; scene.lights.len()];
        let of = components.of_sources(&emitters);
        for (s, &k) in of.iter().enumerate() {
            let s = s as u32;
            let k = k as usize;
            match emitters.origin(s) {
                SourceOrigin::Light(l) if power::is_daylight(&scene.lights[l].kind) => continue,
                SourceOrigin::Light(l) => {
                    // A light drawn as several sources draws its watts once.
                    if !std::mem::replace(&mut counted[l.index()], true) {
                        match (scene.lights[l].kind.watts(), &mut watts) {
                            (Some(w), Some(sum)) => {
                                sum[k] += w;
                                light_watts[l.index()] = w;
                            }
                            _ => watts = None,
                        }
                    }
                    light_flux[l.index()] += emitters.flux(s);
                }
                SourceOrigin::Instance(_) => watts = None,
                // Daylight costs no power.
                SourceOrigin::Sky => continue,
            }
            flux[k] += emitters.flux(s);
        }
        match watts {
            Some(w) if counted.iter().any(|&c| c) => (w, light_watts, PowerUnit::Watts),
            _ => (flux, light_flux, PowerUnit::Lumens),
        }
    }

    /// The goal's unit: [`Goal::unit`], and for `minimizePower` what
    /// [`Binding::power`] counts.
    pub fn goal_unit(&self) -> &'static str {
        match self.goal {
            Goal::MinimizePower => self.power_unit.symbol(),
            _ => self.goal.unit(),
        }
    }

    /// The weight of each component at `config`: 1 for the undimmed lights, each
    /// `lightPower` variable's level for its own.
    pub fn levels(&self, config: &Configuration) -> Vec<f64> {
        self.levels_and_off(config).0
    }

    /// [`Binding::levels`] and the lamps the arrays leave off, found once for both.
    fn levels_and_off(&self, config: &Configuration) -> (Vec<f64>, Vec<LightId>) {
        let mut w = vec![1.0; self.component_count()];
        for (i, (t, v)) in self.targets.iter().zip(self.space.variables()).enumerate() {
            if let (Target::Power { component, .. }, Domain::Segment { min, max }) = (t, &v.domain)
            {
                w[*component] = min + self.space.slice(config, i)[0] * (max - min);
            }
        }
        // A lamp an array leaves off and that has a level of its own is at 0.
        let off = self.lamps_off(config);
        for t in &self.targets {
            if let Target::Power {
                dimmed: Dimmed::Light { light, .. },
                component,
            } = t
                && off.contains(light)
            {
                w[*component] = 0.0;
            }
        }
        (w, off)
    }

    /// The electric lights' power at `config` in [`Binding::power_unit`]: each
    /// component's authored power times its level (exact for flux; for watts, a lamp
    /// dimmed to a level is taken to draw that share, as a driver's rated curve is not
    /// in the file; daylight is not counted).
    pub fn power(&self, config: &Configuration) -> f64 {
        let (w, off) = self.levels_and_off(config);
        let on: f64 = w.iter().zip(&self.electric_power).map(|(w, f)| w * f).sum();
        let off: f64 = off
            .into_iter()
            .map(|l| w[self.component_of(l)] * self.light_power[l.index()])
            .sum();
        on - off
    }

    /// The part of `config` that changes the scene's geometry or materials (everything
    /// but the dimming levels, which one trace serves for all): configurations with the
    /// same arrangement share a trace.
    pub fn arrangement(&self, config: &Configuration) -> Vec<u64> {
        let mut out = Vec::new();
        for (i, t) in self.targets.iter().enumerate() {
            if !matches!(t, Target::Power { .. }) {
                out.extend(self.space.slice(config, i).iter().map(|x| x.to_bits()));
            }
        }
        out
    }

    /// Whether no variable changes the arrangement: a problem of dimming levels alone,
    /// which one trace answers.
    pub fn dimming_only(&self) -> bool {
        self.targets
            .iter()
            .all(|t| matches!(t, Target::Power { .. }))
    }

    /// The instances a configuration may move (objects, emissive objects and holes
    /// placed on rectangles), in variable order: the acceleration structure keeps them
    /// separate and bakes everything else into one tree.
    pub fn movable_instances(&self) -> Vec<InstanceId> {
        let mut out: Vec<InstanceId> = Vec::new();
        for t in &self.targets {
            let ids = match t {
                Target::Move(m) => &m.instances,
                Target::Scale { instances, .. } | Target::Rotate { instances, .. } => instances,
                _ => continue,
            };
            for &(i, _) in ids {
                if !out.contains(&i) {
                    out.push(i);
                }
            }
        }
        out
    }

    /// Applies a configuration, dimming levels included (what `render`, `measure` and
    /// `map --config` show); returns whether any instance transform changed (then the
    /// caller refits the acceleration structure's top level).
    pub fn apply(&self, scene: &mut Scene, config: &Configuration) -> bool {
        self.apply_parts(scene, config, true)
    }

    /// Applies a configuration's arrangement and leaves every light at its authored
    /// output: the scene the photon evaluator traces, weighing each dimmed light's
    /// light by its level afterwards ([`Binding::levels`]).
    pub fn apply_arrangement(&self, scene: &mut Scene, config: &Configuration) -> bool {
        self.apply_parts(scene, config, false)
    }

    fn apply_parts(&self, scene: &mut Scene, config: &Configuration, dim: bool) -> bool {
        let mut moved = false;
        let values = self.values(config);
        let local = self.local_transforms(&values);
        let scale_of = |i: InstanceId| {
            local
                .iter()
                .find(|(j, _)| *j == i)
                .map_or(Mat4::IDENTITY, |&(_, s)| s)
        };
        let placed = |i: InstanceId| {
            self.targets
                .iter()
                .any(|t| matches!(t, Target::Move(m) if m.instances.iter().any(|&(j, _)| j == i)))
        };
        for (&value, target) in values.iter().zip(&self.targets) {
            match (value, target) {
                (
                    VariableValue::Angle(a),
                    Target::Rotate {
                        light: Some((light, authored)),
                        axis,
                        ..
                    },
                ) => rotation::turn_light(scene, *light, authored, *axis, a),
                (
                    VariableValue::Scale(_) | VariableValue::Angle(_),
                    Target::Scale { instances, .. } | Target::Rotate { instances, .. },
                ) => {
                    for &(inst, original) in instances.iter().filter(|&&(i, _)| !placed(i)) {
                        let t = scale_of(inst) * original;
                        let slot = &mut scene.instances[inst].transform;
                        if *slot != t {
                            *slot = t;
                            moved = true;
                        }
                    }
                }
                (VariableValue::Position { point, .. }, Target::Move(m)) => {
                    let delta = (point - m.reference).as_vec3();
                    let shift = Mat4::from_translation(delta);
                    for &(inst, original) in &m.instances {
                        let t = shift * scale_of(inst) * original;
                        let slot = &mut scene.instances[inst].transform;
                        if *slot != t {
                            *slot = t;
                            moved = true;
                        }
                    }
                    for &(light, original) in &m.lights {
                        if let Some(position) = scene.lights[light].kind.position_mut() {
                            *position = original + delta;
                        }
                    }
                }
                (VariableValue::Time { minutes, .. }, Target::SunTime(clock)) => {
                    if let (
                        Ok((d, lux)),
                        LightKind::Directional {
                            direction,
                            illuminance,
                        },
                    ) = (clock.at(minutes), &mut scene.lights[clock.light].kind)
                    {
                        *direction = d.as_vec3();
                        *illuminance = Vec3::splat(lux as f32);
                        clock.draw_sky(scene, d);
                    }
                }
                (VariableValue::Direction(d), Target::Sun { light }) => {
                    if let LightKind::Directional { direction, .. } = &mut scene.lights[*light].kind
                    {
                        *direction = d.as_vec3().normalize();
                    }
                }
                (VariableValue::Direction(d), Target::Aim { lights }) => {
                    aim::apply(scene, lights, d);
                }
                (VariableValue::Colour { rgb, .. }, Target::Colour { materials, .. }) => {
                    for &m in materials {
                        scene.materials[m].diffuse =
                            Vec3::new(rgb[0] as f32, rgb[1] as f32, rgb[2] as f32);
                    }
                }
                (VariableValue::Power(level), Target::Power { dimmed, .. }) => {
                    power::apply(scene, dimmed, if dim { level } else { 1.0 });
                }
                _ => {}
            }
        }
        // After the levels: an array's lamps beyond its shape are off whatever their
        // level.
        for (value, target) in values.iter().zip(&self.targets) {
            if let (VariableValue::Array(shape), Target::Array(lamps)) = (value, target) {
                array::apply(scene, lamps, shape, self);
            }
        }
        moved
    }

    /// The transform each sized or turned instance gets at `values` before a placement
    /// moves it: an object sized or turned is scaled and turned about its authored
    /// centre (the two commute: the scale is uniform and both are about the box's
    /// centre), then moved.
    fn local_transforms(&self, values: &[VariableValue]) -> Vec<(InstanceId, Mat4)> {
        let mut local: Vec<(InstanceId, Mat4)> = Vec::new();
        for (value, target) in values.iter().zip(&self.targets) {
            let (about, instances) = match (value, target) {
                (VariableValue::Scale(k), Target::Scale { instances, centre }) => (
                    Mat4::from_translation(*centre)
                        * Mat4::from_scale(Vec3::splat(*k as f32))
                        * Mat4::from_translation(-*centre),
                    instances,
                ),
                (
                    VariableValue::Angle(a),
                    Target::Rotate {
                        instances,
                        axis,
                        centre,
                        ..
                    },
                ) => (
                    Mat4::from_translation(*centre)
                        * Mat4::from_axis_angle(*axis, a.to_radians() as f32)
                        * Mat4::from_translation(-*centre),
                    instances,
                ),
                _ => continue,
            };
            for &(i, _) in instances {
                match local.iter_mut().find(|(j, _)| *j == i) {
                    Some((_, m)) => *m = about * *m,
                    None => local.push((i, about)),
                }
            }
        }
        local
    }
}

/// The domain and target of variable `spec`, from the binder of its kind; `targets`
/// are the earlier variables'.
fn bind(
    problem: &Problem,
    spec: &VariableSpec,
    scene: &mut Scene,
    targets: &[Target],
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    match &spec.kind {
        VariableKind::ObjectInSurface(p) => placement::object(scene, spec, p, err, warnings),
        VariableKind::HoleInSurface(p) => hole::placement(scene, spec, p, err, warnings),
        VariableKind::LightInSurface(p) => placement::light(scene, spec, p, err, warnings),
        VariableKind::DirectionalLight => sun::direction(scene, spec, err),
        VariableKind::SunTime { from, to, step, .. } => {
            sun::time(problem, spec, scene, *from, *to, *step, err)
        }
        VariableKind::HoleSize { min, max } => hole::size(scene, spec, *min, *max, err),
        VariableKind::ObjectRotation { min, max } => {
            rotation::variable(problem, scene, spec, *min, *max, err)
        }
        VariableKind::LightAim { max_tilt } => {
            aim::variable(scene, spec, *max_tilt, &problem.lamp_groups(), err)
        }
        VariableKind::LightPower { min, max } => power::variable(
            scene,
            spec,
            (*min, *max),
            targets,
            &problem.lamp_groups(),
            err,
        ),
        VariableKind::LightArray(a) => {
            if let Some(g) = problem.groups.iter().find(|g| g.id == spec.id) {
                return Err(err(format!(
                    "<lightArray id=\"{}\"> has the id of the <lightGroup> on line {}, expected an id of its own",
                    spec.id, g.line
                )));
            }
            array::variable(scene, spec, a, &problem.scene.sizes, err)
        }
        VariableKind::Color {
            hue,
            saturation,
            min,
            max,
        } => colour::variable(
            scene,
            spec,
            (*hue, *saturation),
            (*min, *max),
            err,
            warnings,
        ),
    }
}

/// The surface `name` a variable changes, or an error listing the scene's surfaces.
fn find_surface(
    scene: &Scene,
    name: &str,
    spec: &VariableSpec,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<SurfaceId, Diagnostic> {
    scene.surface(name).ok_or_else(|| {
        err(format!(
            "no surface named '{name}' in the scene, expected the object that <{}> moves",
            spec.kind.name()
        ))
        .with_hint(known_names(
            scene.surfaces.iter().map(|s| s.name.as_str()),
            "surfaces",
        ))
    })
}

/// The distinct materials of a surface's triangles, in order.
fn surface_materials(scene: &Scene, s: SurfaceId) -> Vec<MaterialId> {
    let mut out = Vec::new();
    for &i in &scene.surfaces[s].instances {
        for &m in &scene.meshes[scene.instances[i].mesh].materials {
            if !out.contains(&m) {
                out.push(m);
            }
        }
    }
    out
}

/// The box everything may occupy: the scene's instances no variable moves, the lights
/// no placement moves, and each moved thing as authored (`None` for an empty scene).
fn reachable_bounds(scene: &Scene, targets: &[Target]) -> Option<Bounds> {
    let mut moved_instances = vec![false; scene.instances.len()];
    let mut moved_lights = vec![false; scene.lights.len()];
    let mut out: Option<Bounds> = None;
    let mut add = |b: Bounds| out = Some(out.map_or(b, |o: Bounds| o.union(b)));
    for t in targets {
        match t {
            Target::Move(m) => {
                m.instances
                    .iter()
                    .for_each(|&(i, _)| moved_instances[i.index()] = true);
                m.lights
                    .iter()
                    .for_each(|&(l, _)| moved_lights[l.index()] = true);
                add(m.bounds);
            }
            Target::Array(lamps) => {
                lamps
                    .lamps
                    .iter()
                    .for_each(|&(l, _, _)| moved_lights[l.index()] = true);
                if let Some(b) = lamps.bounds() {
                    add(b);
                }
            }
            _ => {}
        }
    }
    let fixed: Vec<InstanceId> = (0..scene.instances.len())
        .map(InstanceId::from_index)
        .filter(|&i| !moved_instances[i.index()])
        .collect();
    if let Some(b) = instance_bounds(scene, &fixed) {
        add(b);
    }
    for (l, light) in scene.lights.iter().enumerate() {
        if let (false, Some(p)) = (moved_lights[l], light.kind.position()) {
            add(Bounds::point(p.as_dvec3()));
        }
    }
    out
}

/// The normalised coordinates of the scene as authored.
fn initial_coords(scene: &Scene, domain: &Domain, target: &Target) -> Vec<f64> {
    match (domain, target) {
        (Domain::Parallelogram(r), Target::Move(m)) => {
            let (s, t) = r.coords(m.reference);
            vec![s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]
        }
        // A lamp starts at its authored aim, the cone's axis.
        (Domain::Hemisphere(_), Target::Aim { .. }) => vec![0.0, 0.0],
        (Domain::Hemisphere(h), Target::Sun { light }) => {
            let d = scene.lights[*light]
                .kind
                .direction()
                .map(|d| d.as_dvec3())
                .unwrap_or(-h.up);
            let (p, t) = h.coords(d);
            vec![p, t]
        }
        (Domain::Segment { min, max }, Target::Colour { materials, .. }) => {
            let v = materials
                .first()
                .map(|&m| scene.materials[m].diffuse.max_element() as f64)
                .unwrap_or(*max);
            vec![((v - min) / (max - min)).clamp(0.0, 1.0)]
        }
        (Domain::Segment { min, max } | Domain::Turn { min, max }, Target::Rotate { .. }) => {
            // As authored: turned by 0° (or the nearest end of the range).
            vec![((0.0 - min) / (max - min)).clamp(0.0, 1.0)]
        }
        (Domain::Segment { min, max }, Target::Power { .. } | Target::Scale { .. }) => {
            // The scene as authored is at level 1, its holes at scale 1.
            let x = if max > min {
                (1.0 - min) / (max - min)
            } else {
                0.0
            };
            vec![x.clamp(0.0, 1.0)]
        }
        // An array starts as the one of most lamps, half a spacing from the walls.
        (Domain::Array(a), _) => a
            .starts()
            .first()
            .and_then(|shape| a.coords(shape))
            .unwrap_or_else(|| vec![0.5; a.dimensions()]),
        (d, _) => vec![0.5; d.dimensions()],
    }
}

#[cfg(test)]
mod tests;
