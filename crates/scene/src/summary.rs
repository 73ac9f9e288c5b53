//! What a scene holds, as `invlight scene` shows it and `--json` writes it: surfaces
//! with their materials, lights with their flux and aim (emissive surfaces among them,
//! with the way they face; luminaires with their file, the flux of its table beside the
//! file's own figure, watts and aim), cameras and bounds, and warnings about what a file's units
//! suggest. One [`SceneSummary`] is both the table's data and the JSON's schema.

use crate::light::{LightKind, luminance};
use crate::model::{Scene, SurfaceId};
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::f32::consts::PI;

/// The scene size past which a file was probably authored in millimetres or
/// centimetres, m (10 km: no building is larger).
pub const SUSPICIOUS_SIZE: f32 = 1e4;
/// The luminous flux past which a single light was probably authored in other units,
/// lm (a million: a stadium floodlight gives about 200 000).
pub const SUSPICIOUS_FLUX: f32 = 1e6;

/// A named surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceSummary {
    /// Its name, as `--surface` and problem files take it.
    pub name: String,
    /// Number of triangles.
    pub triangles: usize,
    /// World-space area, m².
    pub area: f32,
    /// Up to three material names (`+N more` after them).
    pub material: String,
    /// The materials' kinds: `diffuse`, `mirror`, `glass`, `emitter`, `hole`, or
    /// `placement` for a placement rectangle.
    pub kind: String,
    /// Whether any of its triangles emits.
    pub emissive: bool,
    /// Whether it is a placement rectangle (`*__Geometry`), not lit.
    pub placement: bool,
    /// Whether it is a calculation surface: it receives light without touching it
    /// (`--calculation-surface`, `<calculationSurface>`, `<workplane>`).
    #[serde(default)]
    pub calculation: bool,
    /// A placement rectangle's vertices, in the order problem files index them.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub vertices: Option<Vec<[f32; 3]>>,
}

/// A light: a point, spot or directional light, or an emissive surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LightSummary {
    /// Its name.
    pub name: String,
    /// `point`, `spot`, `directional` or `area`.
    pub kind: String,
    /// Position (an area light's centroid), m.
    pub position: Option<[f32; 3]>,
    /// The direction a spot or the sun shines along; for an area light, the way its
    /// front faces (the area-weighted mean front normal): it emits from that side only.
    pub direction: Option<[f32; 3]>,
    /// Luminous flux, lm (none for the sun).
    pub power_lm: Option<f32>,
    /// The sun's illuminance on a plane facing it, lx.
    pub illuminance_lx: Option<f32>,
    /// For a luminaire (a goniometric light), its photometric file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminaire: Option<LuminaireSummary>,
}

/// What a luminaire's photometric file says, beside what invlight makes of it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LuminaireSummary {
    /// The file's name.
    pub file: String,
    /// Its format: `IES LM-63-2002`, `EULUMDAT`, ….
    pub format: String,
    /// The luminous flux of its candela table, lm: the integral over the sphere of the
    /// table as interpolated, before the light's multiplier (`power_lm` is after it).
    pub table_lm: f64,
    /// The flux the file states, lm: EULUMDAT's lamp flux × light output ratio (the
    /// luminaire's); IES LM-63's lamps × lumens per lamp (the bare lamps', more than
    /// the luminaire sends); none for absolute photometry.
    pub file_lm: Option<f64>,
    /// What `file_lm` is the flux of: `luminaire` or `lamps`.
    pub file_lm_of: Option<String>,
    /// Electrical power, W, as the light is scaled ([`LightKind::watts`]); none when
    /// the file gives no watts.
    pub watts: Option<f64>,
    /// The luminance of the factor on the table (a problem's or glTF's multiplier and
    /// colour, dimming) times the IES tilt factor at the light's aim.
    pub multiplier: f32,
    /// The aim, where γ = 0 points, unit.
    pub aim: [f32; 3],
    /// The C0 axis (C = 0°, γ = 90°), unit.
    pub c0: [f32; 3],
    /// The luminous opening in words with the scene axis its length lies along
    /// ("1500 × 60 mm, length along X"), as the light is turned.
    #[serde(default)]
    pub opening: String,
}

/// A camera.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CameraSummary {
    /// Its name, as `render --camera` takes it.
    pub name: String,
    /// Eye position, m.
    pub position: [f32; 3],
    /// Viewing direction.
    pub forward: [f32; 3],
    /// Vertical field of view, degrees.
    pub yfov_deg: f32,
}

/// `invlight scene`'s report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneSummary {
    /// Named surfaces, then placement rectangles.
    pub surfaces: Vec<SurfaceSummary>,
    /// Lights, then emissive surfaces.
    pub lights: Vec<LightSummary>,
    /// Cameras.
    pub cameras: Vec<CameraSummary>,
    /// World bounds of the lit scene and its point lights, m.
    pub bounds: Option<[[f32; 3]; 2]>,
    /// The up axis.
    pub up: [f32; 3],
    /// What the user may want to know: a size or flux that suggests other units.
    pub warnings: Vec<String>,
}

impl Scene {
    /// What the scene holds.
    pub fn summary(&self) -> SceneSummary {
        let mut surfaces: Vec<SurfaceSummary> = (0..self.surfaces.len())
            .map(|i| self.surface_summary(SurfaceId::from_index(i)))
            .collect();
        for p in &self.placements {
            surfaces.push(SurfaceSummary {
                name: p.name.clone(),
                triangles: 2,
                area: placement_area(&p.vertices),
                material: String::new(),
                kind: "placement".into(),
                emissive: false,
                placement: true,
                calculation: false,
                vertices: Some(p.vertices.iter().map(|v| v.to_array()).collect()),
            });
        }
        let mut lights: Vec<LightSummary> = self
            .lights
            .iter()
            .map(|l| LightSummary {
                name: l.name.clone(),
                kind: l.kind.name().into(),
                position: l.kind.position().map(|p| p.to_array()),
                direction: l.kind.direction().map(|d| d.to_array()),
                power_lm: match l.kind {
                    LightKind::Directional { .. } => None,
                    _ => Some(luminance(l.kind.flux())),
                },
                illuminance_lx: match l.kind {
                    LightKind::Directional { illuminance, .. } => Some(luminance(illuminance)),
                    _ => None,
                },
                luminaire: self.luminaire_summary(&l.kind),
            })
            .collect();
        // Emissive surfaces are area lights: flux π·L·A from their front faces. A
        // surface covering several instances (a parent node) is listed by its parts.
        for s in &self.surfaces {
            if s.instances.len() != 1 {
                continue;
            }
            let (mut flux, mut area) = (0.0f64, 0.0f32);
            let (mut centroid, mut facing) = (Vec3::ZERO, Vec3::ZERO);
            for t in self.world_triangles(s.instances[0]) {
                let m = &self.materials[t.material];
                let a = t.area();
                if !m.is_emissive() || a <= 0.0 || a.is_nan() {
                    continue;
                }
                let [p, q, r] = t.corners;
                flux += (PI * luminance(m.emission) * a) as f64;
                centroid += (p + q + r) / 3.0 * a;
                facing += t.cross * 0.5;
                area += a;
            }
            if flux > 0.0 {
                lights.push(LightSummary {
                    name: s.name.clone(),
                    kind: "area".into(),
                    position: Some((centroid / area).to_array()),
                    direction: Some(facing.normalize_or_zero().to_array()),
                    power_lm: Some(flux as f32),
                    illuminance_lx: None,
                    luminaire: None,
                });
            }
        }
        let cameras = self
            .cameras
            .iter()
            .map(|c| CameraSummary {
                name: c.name.clone(),
                position: c.position.to_array(),
                forward: c.forward.to_array(),
                yfov_deg: c.yfov.to_degrees(),
            })
            .collect();
        let bounds = self.bounds();
        let mut warnings = Vec::new();
        if let Some((lo, hi)) = bounds {
            let size = (hi - lo).max_element();
            if size > SUSPICIOUS_SIZE {
                warnings.push(format!(
                    "the scene spans {size:.0} m: if its file is in millimetres or centimetres, read it with --scale 0.001 or --scale 0.01 (or scale=\"…\" on a problem file's <scene>)"
                ));
            }
        }
        for l in &self.lights {
            if let LightKind::Goniometric { photometry, .. } = &l.kind {
                for w in &photometry.warnings {
                    warnings.push(format!("the light '{}' ({}): {w}", l.name, photometry.file));
                }
            }
        }
        for l in &lights {
            if let Some(flux) = l.power_lm.filter(|&f| f > SUSPICIOUS_FLUX) {
                warnings.push(format!(
                    "the light '{}' emits {flux:.3e} lm, more than any real luminaire: check its units (an emissive surface's luminance grows with the square of a wrong --scale)",
                    l.name
                ));
            }
        }
        SceneSummary {
            surfaces,
            lights,
            cameras,
            bounds: bounds.map(|(lo, hi)| [lo.to_array(), hi.to_array()]),
            up: self.up.to_array(),
            warnings,
        }
    }

    /// A goniometric light's file, flux, watts and aim.
    fn luminaire_summary(&self, kind: &LightKind) -> Option<LuminaireSummary> {
        let LightKind::Goniometric {
            frame,
            photometry: p,
            multiplier,
            tilt,
            ..
        } = kind
        else {
            return None;
        };
        let (file_lm, of) = match (p.stated_flux, p.lumens_per_lamp) {
            (Some(f), _) => (Some(f), Some("luminaire")),
            (None, Some(per_lamp)) => (Some(per_lamp * p.lamps as f64), Some("lamps")),
            (None, None) => (None, None),
        };
        Some(LuminaireSummary {
            file: p.file.clone(),
            format: p.format.name().into(),
            table_lm: p.flux(),
            file_lm,
            file_lm_of: of.map(String::from),
            watts: kind.watts(),
            multiplier: luminance(*multiplier) * tilt,
            aim: (-frame.z_axis).to_array(),
            c0: frame.x_axis.to_array(),
            opening: p.opening.words(|k| axis_words(frame.col(k))),
        })
    }

    fn surface_summary(&self, i: SurfaceId) -> SurfaceSummary {
        let mut names = BTreeSet::new();
        let mut kinds = BTreeSet::new();
        let mut emissive = false;
        for &inst in &self.surfaces[i].instances {
            let mesh = &self.meshes[self.instances[inst].mesh];
            for &m in &mesh.materials {
                let m = &self.materials[m];
                emissive |= m.is_emissive();
                names.insert(m.name.as_str());
                kinds.insert(m.kind_name());
            }
        }
        let mut material = names.iter().copied().take(3).collect::<Vec<_>>().join(", ");
        if names.len() > 3 {
            material += &format!(" +{} more", names.len() - 3);
        }
        SurfaceSummary {
            name: self.surfaces[i].name.clone(),
            triangles: self.surface_triangles(i),
            area: self.surface_area(i),
            material,
            kind: kinds.into_iter().collect::<Vec<_>>().join(", "),
            emissive,
            placement: false,
            calculation: self.is_calculation_surface(i),
            vertices: None,
        }
    }
}

impl SceneSummary {
    /// The summary as tables for people: surfaces, lights, cameras, bounds.
    pub fn tables(&self) -> String {
        use invlight_stats::significant;
        use std::fmt::Write;
        let num = |x: f32| format!("{x:.4}");
        let v3 = |x: Option<[f32; 3]>| {
            x.map_or("-".into(), |a| {
                format!("({}, {}, {})", num(a[0]), num(a[1]), num(a[2]))
            })
        };
        let mut out = String::new();
        let w = self
            .surfaces
            .iter()
            .map(|s| s.name.len())
            .max()
            .unwrap_or(4)
            .max(7);
        let _ = writeln!(
            out,
            "{:<w$}  {:>9}  {:>12}  material",
            "surface", "triangles", "area m²"
        );
        for f in &self.surfaces {
            let material = if f.placement {
                "placement rectangle (not lit)".to_string()
            } else if f.calculation {
                "calculation surface (receives, does not touch the light)".to_string()
            } else {
                format!("{} ({})", f.material, f.kind)
            };
            let _ = writeln!(
                out,
                "{:<w$}  {:>9}  {:>12}  {material}",
                f.name,
                f.triangles,
                num(f.area)
            );
        }
        out.push('\n');
        if self.lights.is_empty() {
            out += "no lights\n";
        } else {
            let _ = writeln!(
                out,
                "{:<20}  {:<11}  {:<32}  {:<28}  power",
                "light", "kind", "position", "direction (area: facing)"
            );
            for l in &self.lights {
                let power = match (l.power_lm, l.illuminance_lx) {
                    (Some(lm), _) => format!("{} lm", significant(lm as f64)),
                    (None, Some(lx)) => format!("{} lx", significant(lx as f64)),
                    _ => "-".into(),
                };
                let (p, d) = (v3(l.position), v3(l.direction));
                let _ = writeln!(
                    out,
                    "{:<20}  {:<11}  {p:<32}  {d:<28}  {power}",
                    l.name, l.kind
                );
                if let Some(m) = &l.luminaire {
                    let file = match (m.file_lm, m.file_lm_of.as_deref()) {
                        (Some(f), Some(of)) => {
                            format!("the file says {} lm of {of}", significant(f))
                        }
                        _ => "absolute photometry".into(),
                    };
                    let watts = m
                        .watts
                        .map_or("no watts".into(), |w| format!("{} W", significant(w)));
                    let _ = writeln!(
                        out,
                        "{:<20}  {} ({}): table {} lm ({file}) × {}, {watts}, aim {}, C0 {}",
                        "",
                        m.file,
                        m.format,
                        significant(m.table_lm),
                        significant(m.multiplier as f64),
                        v3(Some(m.aim)),
                        v3(Some(m.c0))
                    );
                    let _ = writeln!(out, "{:<20}  luminous opening {}", "", m.opening);
                }
            }
            if self.lights.iter().any(|l| l.kind == "area") {
                out += "area lights emit from their front side only, the side their direction points to\n";
            }
        }
        out.push('\n');
        for c in &self.cameras {
            let (p, f) = (v3(Some(c.position)), v3(Some(c.forward)));
            let _ = writeln!(out, "camera {} at {p} looking {f}", c.name);
        }
        if let Some([lo, hi]) = self.bounds {
            let _ = writeln!(
                out,
                "bounds {} – {}, up {}",
                v3(Some(lo)),
                v3(Some(hi)),
                v3(Some(self.up))
            );
        }
        out
    }
}

/// Area of a placement rectangle from its first four vertices (A, B, C, D in order
/// around it, or A B D C: the larger reading is the rectangle).
fn placement_area(vertices: &[Vec3]) -> f32 {
    if vertices.len() < 4 {
        return 0.0;
    }
    let [a, b, c, d] = [vertices[0], vertices[1], vertices[2], vertices[3]];
    let quad = |p: Vec3, q: Vec3, r: Vec3, s: Vec3| 0.5 * (r - p).cross(s - q).length();
    quad(a, b, c, d).max(quad(a, b, d, c))
}

/// A scene direction a length lies along, in words: the axis it is within half a degree
/// of (a length has no sign: "X"), else its components.
fn axis_words(d: Vec3) -> String {
    let d = d.normalize_or_zero();
    let a = d.abs();
    let k = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    if a[k] > 0.5f32.to_radians().cos() {
        ["X", "Y", "Z"][k].to_string()
    } else {
        let d = if d[k] < 0.0 { -d } else { d };
        // No "-0.00": what rounds to zero is printed as zero.
        let c = |x: f32| if x.abs() < 0.005 { 0.0 } else { x };
        format!("({:.2}, {:.2}, {:.2})", c(d.x), c(d.y), c(d.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Material, Mesh};
    use glam::Mat4;

    /// An emissive panel facing down (clockwise seen from above) is listed as an area
    /// light facing −z with flux π·L·A; a scene 20 km wide gets the units warning.
    #[test]
    fn area_lights_say_which_way_they_face() {
        let mut s = Scene::default();
        let mut glow = Material::diffuse("Glow", Vec3::ZERO);
        glow.emission = Vec3::splat(10.0);
        let glow = s.add_material(glow);
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let down = s.add_mesh(Mesh::quad(
            [
                Vec3::new(0.0, 0.0, 3.0),
                Vec3::new(0.0, 1.0, 3.0),
                Vec3::new(1.0, 1.0, 3.0),
                Vec3::new(1.0, 0.0, 3.0),
            ],
            glow,
        ));
        s.add_instance("Panel", down, Mat4::IDENTITY);
        let summary = s.summary();
        let panel = summary.lights.iter().find(|l| l.name == "Panel").unwrap();
        assert_eq!(panel.kind, "area");
        assert_eq!(panel.direction, Some([0.0, 0.0, -1.0]));
        assert!((panel.power_lm.unwrap() - PI * 10.0).abs() < 1e-4);
        assert!(summary.warnings.is_empty(), "{:?}", summary.warnings);
        let floor = s.add_mesh(Mesh::quad(
            [
                Vec3::ZERO,
                Vec3::new(2e4, 0.0, 0.0),
                Vec3::new(2e4, 2e4, 0.0),
                Vec3::new(0.0, 2e4, 0.0),
            ],
            grey,
        ));
        s.add_instance("Floor", floor, Mat4::IDENTITY);
        let w = s.summary().warnings;
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("--scale 0.001"), "{}", w[0]);
    }

    /// A length's axis has no sign; off the axes it is given by its components, turned
    /// so that its largest one is positive.
    #[test]
    fn axes_are_named_without_sign() {
        assert_eq!(axis_words(Vec3::NEG_Z), "Z");
        assert_eq!(axis_words(Vec3::new(0.0, 2.0, 0.001)), "Y");
        assert_eq!(axis_words(Vec3::new(-1.0, 1.0, 0.0)), "(0.71, -0.71, 0.00)");
    }
}
