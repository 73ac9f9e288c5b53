//! Dimming (`<lightPower id min max>`): a light's or an emissive object's authored
//! output times a level. The search never traces a dimming: the photon evaluator keeps
//! each dimmed light's light apart ([`invlight_photon::Components`]) and weighs it by
//! the level. Applying a level to the scene is for everything else that reads a
//! configuration (`render`, `measure` and `map --config`), which must see the lamps as
//! dimmed.

use super::Target;
use crate::problem::{LightGroup, VariableSpec};
use crate::space::Domain;
use invlight_scene::{
    Diagnostic, InstanceId, LightId, LightKind, MaterialId, Rgb, Scene, SurfaceId, known_names,
};

/// What a `lightPower` variable dims, with its authored output.
#[derive(Debug, Clone)]
pub enum Dimmed {
    /// `scene.lights[light]`, of authored strength `authored`
    /// ([`LightKind::strength_mut`]).
    Light {
        /// The light.
        light: LightId,
        /// Its authored strength.
        authored: Rgb,
    },
    /// The lamps of a `<lightGroup>`, each with its authored strength: one level dims
    /// them all, as one circuit does.
    Group(Vec<(LightId, Rgb)>),
    /// The emissive materials of a surface's instances (private copies, so that other
    /// objects sharing a material stay lit), each with its authored emission.
    Emissive {
        /// The instances dimmed.
        instances: Vec<InstanceId>,
        /// The copies and their authored emission.
        materials: Vec<(MaterialId, Rgb)>,
    },
}

impl Dimmed {
    /// Whether it dims `light`.
    pub fn holds(&self, light: LightId) -> bool {
        match self {
            Dimmed::Light { light: l, .. } => *l == light,
            Dimmed::Group(g) => g.iter().any(|(l, _)| *l == light),
            Dimmed::Emissive { .. } => false,
        }
    }

    /// Whether two dim the same light or object.
    pub fn same(&self, other: &Dimmed) -> bool {
        match (self, other) {
            (Dimmed::Light { light: a, .. }, Dimmed::Light { light: b, .. }) => a == b,
            (Dimmed::Group(a), Dimmed::Group(b)) => {
                a.iter().any(|(l, _)| b.iter().any(|(m, _)| l == m))
            }
            (Dimmed::Group(g), Dimmed::Light { light, .. })
            | (Dimmed::Light { light, .. }, Dimmed::Group(g)) => g.iter().any(|(l, _)| l == light),
            (Dimmed::Emissive { instances: a, .. }, Dimmed::Emissive { instances: b, .. }) => {
                a.iter().any(|i| b.contains(i))
            }
            _ => false,
        }
    }
}

/// Binds the light, the `<lightGroup>` of `groups` or the emissive object `id`. An
/// object's emissive materials are copied for its instances alone.
pub fn bind(
    scene: &mut Scene,
    id: &str,
    groups: &[LightGroup],
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<Dimmed, Diagnostic> {
    if let Some(group) = groups.iter().find(|g| g.id == id) {
        let lights = group_lights(scene, group, err)?;
        return Ok(Dimmed::Group(
            lights
                .into_iter()
                .map(|l| (l, *scene.lights[l].kind.clone().strength_mut()))
                .collect(),
        ));
    }
    if let Some(light) = scene.light(id) {
        let authored = *scene.lights[light].kind.clone().strength_mut();
        return Ok(Dimmed::Light { light, authored });
    }
    let surface: SurfaceId = scene.surface(id).ok_or_else(|| {
        err(format!(
            "no light or surface named '{id}' in the scene, expected the light or emissive object to dim"
        ))
        .with_hint(known_names(
            scene.lights.iter().map(|l| l.name.as_str()),
            "lights",
        ))
    })?;
    let instances = scene.surfaces[surface].instances.clone();
    let mut copies: Vec<(MaterialId, MaterialId)> = Vec::new();
    for &i in &instances {
        let mesh = scene.instances[i].mesh;
        if !scene.meshes[mesh]
            .materials
            .iter()
            .any(|&m| scene.materials[m].is_emissive())
        {
            continue;
        }
        let mut copy = scene.meshes[mesh].clone();
        for m in copy.materials.iter_mut() {
            if !scene.materials[*m].is_emissive() {
                continue;
            }
            let own = match copies.iter().find(|(from, _)| from == m) {
                Some(&(_, to)) => to,
                None => {
                    let mut material = scene.materials[*m].clone();
                    material.name = format!("{} ({id})", material.name);
                    let to = scene.add_material(material);
                    copies.push((*m, to));
                    to
                }
            };
            *m = own;
        }
        scene.instances[i].mesh = scene.add_mesh(copy);
    }
    if copies.is_empty() {
        return Err(err(format!(
            "'{id}' emits no light, expected a light or an emissive object to dim"
        )));
    }
    let materials = copies
        .into_iter()
        .map(|(_, m)| (m, scene.materials[m].emission))
        .collect();
    Ok(Dimmed::Emissive {
        instances,
        materials,
    })
}

/// Sets what `dimmed` dims to `level` times its authored output.
pub fn apply(scene: &mut Scene, dimmed: &Dimmed, level: f64) {
    let level = level as f32;
    match dimmed {
        Dimmed::Light { light, authored } => {
            *scene.lights[*light].kind.strength_mut() = *authored * level;
        }
        Dimmed::Group(lights) => {
            for &(light, authored) in lights {
                *scene.lights[light].kind.strength_mut() = authored * level;
            }
        }
        Dimmed::Emissive { materials, .. } => {
            for &(m, emission) in materials {
                scene.materials[m].emission = emission * level;
            }
        }
    }
}

/// The lamps of `group` in `scene`: each must be a light, and the group's id must name
/// none (a `<lightPower>` of it would be ambiguous).
pub(super) fn group_lights(
    scene: &Scene,
    group: &LightGroup,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<Vec<LightId>, Diagnostic> {
    if scene.light(&group.id).is_some() {
        return Err(err(format!(
            "the <lightGroup> id '{}' is also a light's name, expected an id of its own",
            group.id
        )));
    }
    group
        .lights
        .iter()
        .map(|name| {
            scene.light(name).ok_or_else(|| {
                err(format!(
                    "no light named '{name}' in the scene, expected the lamps of <lightGroup id=\"{}\">",
                    group.id
                ))
                .with_hint(known_names(scene.lights.iter().map(|l| l.name.as_str()), "lights"))
            })
        })
        .collect()
}

/// Whether `kind` is daylight, which costs no power (the sun; the sky is not a light of
/// the list but [`invlight_scene::Scene::sky`], daylight too).
pub fn is_daylight(kind: &LightKind) -> bool {
    matches!(kind, LightKind::Directional { .. })
}

/// A `lightPower` of `spec.id` from level `min` to `max`: its light kept apart as the
/// next component after those of `targets`, the earlier variables' (component 0 is the
/// undimmed lights').
pub(super) fn variable(
    scene: &mut Scene,
    spec: &VariableSpec,
    (min, max): (f64, f64),
    targets: &[Target],
    groups: &[LightGroup],
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let dimmed = bind(scene, &spec.id, groups, err)?;
    let component = 1 + targets
        .iter()
        .filter(|t| matches!(t, Target::Power { .. }))
        .count();
    Ok((
        Domain::Segment { min, max },
        Target::Power { dimmed, component },
    ))
}
