//! Finding what a user names — a surface to measure, a light — with a message that
//! helps when the name is wrong: the names that are close to it, else the names there
//! are, and how to list them all.

use crate::error::Diagnostic;
use crate::light::luminance;
use crate::model::{Scene, SurfaceId};
use std::path::Path;

/// A hint listing up to 12 of `names`, "the scene's {what}: a, b, …" (or that there
/// are none).
pub fn known_names<'n>(names: impl Iterator<Item = &'n str>, what: &str) -> String {
    let v: Vec<&str> = names.collect();
    if v.is_empty() {
        return format!("the scene has no {what}");
    }
    let more = if v.len() > 12 { ", …" } else { "" };
    format!(
        "the scene's {what}: {}{more}",
        quoted(&v[..v.len().min(12)])
    )
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("'{n}'"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The name of `known` nearest to `name` when it is close enough to be what was meant
/// — another case, a British spelling (`minimise` for `minimize`), a typo of a letter
/// or two (one in a name of four letters or fewer) — for "did you mean" hints.
pub fn nearest<'k>(name: &str, known: &[&'k str]) -> Option<&'k str> {
    let lower = name.to_lowercase();
    known
        .iter()
        .map(|k| (edit_distance(&k.to_lowercase(), &lower), *k))
        .filter(|(d, k)| *d <= if k.chars().count() > 4 { 2 } else { 1 })
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Levenshtein distance, for "did you mean" hints.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

impl Scene {
    /// The surface `name` of the scene read from `path`, with area to be lit; else an
    /// error with the names close to it (case, a typo of two letters, a part of it) or
    /// those the scene has.
    pub fn find_surface(&self, path: &Path, name: &str) -> Result<SurfaceId, Diagnostic> {
        if let Some(id) = self.surface(name) {
            // Illuminance is flux over area: a surface without area has none.
            if self.surface_area(id) <= 0.0 {
                return Err(Diagnostic::at(
                    path,
                    format!("surface '{name}'"),
                    "it has no area (its triangles are degenerate), expected a surface to light",
                ));
            }
            return Ok(id);
        }
        let lower = name.to_lowercase();
        let names = self.surfaces.iter().map(|s| s.name.as_str());
        let close: Vec<&str> = names
            .clone()
            .filter(|s| {
                let s = s.to_lowercase();
                s.contains(&lower) || lower.contains(&s) || edit_distance(&s, &lower) <= 2
            })
            .take(5)
            .collect();
        let mut hint = if close.is_empty() {
            format!(
                "{}; `invlight scene {}` lists them all",
                known_names(names, "surfaces"),
                path.display()
            )
        } else {
            format!("did you mean {}?", quoted(&close))
        };
        if self.placement(name).is_some() {
            hint += "; it is a placement rectangle (*__Geometry), which is not lit: to measure a task area, build a calculation rectangle with <workplane> or name one with --calculation-surface";
        }
        Err(Diagnostic::new(path, format!("no surface named '{name}'")).with_hint(hint))
    }

    /// Refuses a scene with nothing to trace photons from, naming the lights that emit
    /// nothing.
    pub fn require_light(&self, path: &Path) -> Result<(), Diagnostic> {
        let lit = self.lights.iter().any(|l| luminance(l.kind.flux()) > 0.0)
            || self
                .all_world_triangles()
                .any(|(_, t)| self.materials[t.material].is_emissive() && t.area() > 0.0)
            || self
                .sky
                .as_ref()
                .is_some_and(|s| s.horizontal_illuminance() > 0.0);
        if lit {
            return Ok(());
        }
        let dark: Vec<&str> = self.lights.iter().map(|l| l.name.as_str()).collect();
        let why = if dark.is_empty() {
            "no point, spot or directional light, no emissive surface and no sky".to_string()
        } else {
            format!("its lights {} emit no luminous flux", quoted(&dark))
        };
        Err(
            Diagnostic::new(path, format!("the scene has no light: {why}"))
                .with_hint("give a light a positive intensity, a material an emission, or the scene a sky (--sky cie-overcast:10000)"),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Light, LightKind, Material, Mesh};
    use glam::{Mat4, Vec3};

    #[test]
    fn the_nearest_known_name_is_suggested() {
        let goals = ["maximizeRadiance", "minimizePower", "targetRadiance"];
        assert_eq!(nearest("minimisePower", &goals), Some("minimizePower"));
        assert_eq!(
            nearest("MAXIMIZERADIANCE", &goals),
            Some("maximizeRadiance")
        );
        assert_eq!(nearest("targtRadiace", &goals), Some("targetRadiance"));
        assert_eq!(nearest("uniformity", &goals), None);
        assert_eq!(nearest("id", &["ids", "lights"]), Some("ids"));
        assert_eq!(nearest("x", &["id"]), None);
    }

    #[test]
    fn wrong_names_get_close_ones_or_the_list() {
        let mut s = Scene::default();
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let quad = s.add_mesh(Mesh::quad(
            [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            grey,
        ));
        s.add_instance("Floor", quad, Mat4::IDENTITY);
        s.add_instance("Desk", quad, Mat4::IDENTITY);
        let p = Path::new("room.gltf");
        assert_eq!(s.find_surface(p, "Desk"), Ok(SurfaceId::from_index(1)));
        let e = s.find_surface(p, "floor").unwrap_err();
        assert!(
            e.hint.as_ref().unwrap().contains("did you mean 'Floor'"),
            "{e}"
        );
        let e = s.find_surface(p, "Ceiling").unwrap_err();
        assert!(e.hint.as_ref().unwrap().contains("'Floor', 'Desk'"), "{e}");
        let e = s.require_light(p).unwrap_err();
        assert!(e.message.contains("no point, spot"), "{e}");
        s.lights.push(Light {
            c0: glam::Vec3::X,
            name: "Off".into(),
            kind: LightKind::Point {
                position: Vec3::Z,
                intensity: Vec3::ZERO,
            },
        });
        let e = s.require_light(p).unwrap_err();
        assert!(e.message.contains("'Off' emit no"), "{e}");
    }
}
