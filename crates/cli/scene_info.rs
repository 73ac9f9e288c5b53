//! `invlight scene`: what a scene file holds.

use crate::args::LoadArgs;
use clap::Args;
use invlight_scene::{Scene, Vec3, luminance};
use serde_json::{Value, json};
use std::collections::BTreeSet;
use std::path::PathBuf;

/// Options of `invlight scene`.
#[derive(Args, Debug)]
pub struct SceneArgs {
    /// Scene file: glTF 2.0 (.gltf, .glb), COLLADA (.dae) or Wavefront OBJ (.obj).
    pub scene: PathBuf,
    /// Print one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub load: LoadArgs,
}

fn v(p: Vec3) -> Value {
    json!([p.x, p.y, p.z])
}

/// The distinct material names of a surface's triangles, their kinds (`diffuse`,
/// `mirror`, `glass`, `emitter`, `hole`), and whether any emits.
fn materials_of(scene: &Scene, surface: usize) -> (String, String, bool) {
    let mut names = BTreeSet::new();
    let mut kinds = BTreeSet::new();
    let mut emissive = false;
    for &i in &scene.surfaces[surface].instances {
        let mesh = &scene.meshes[scene.instances[i as usize].mesh as usize];
        for &m in &mesh.materials {
            let m = &scene.materials[m as usize];
            emissive |= m.is_emissive();
            names.insert(m.name.as_str());
            kinds.insert(m.kind_name());
        }
    }
    let list: Vec<&str> = names.iter().copied().take(3).collect();
    let mut s = list.join(", ");
    if names.len() > 3 {
        s += &format!(" +{} more", names.len() - 3);
    }
    (
        s,
        kinds.into_iter().collect::<Vec<_>>().join(", "),
        emissive,
    )
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

/// Runs `invlight scene`.
pub fn run(args: SceneArgs) -> anyhow::Result<()> {
    let scene = args.load.load(&args.scene)?;
    let mut surfaces = Vec::new();
    for (i, s) in scene.surfaces.iter().enumerate() {
        let (material, kind, emissive) = materials_of(&scene, i);
        surfaces.push(
            json!({"name": s.name, "triangles": scene.surface_triangles(i as u32),
            "area": scene.surface_area(i as u32), "material": material, "kind": kind,
            "emissive": emissive, "placement": false}),
        );
    }
    for p in &scene.placements {
        surfaces.push(
            json!({"name": p.name, "triangles": 2, "area": placement_area(&p.vertices),
            "material": "", "kind": "placement", "emissive": false, "placement": true, "vertices":
            p.vertices.iter().map(|&x| v(x)).collect::<Vec<_>>()}),
        );
    }
    let mut lights = Vec::new();
    for l in &scene.lights {
        lights.push(json!({"name": l.name, "kind": l.kind.name(),
            "position": l.kind.position().map(v), "direction": l.kind.direction().map(v),
            "power_lm": match l.kind { invlight_scene::LightKind::Directional { .. } => Value::Null,
                                       _ => json!(luminance(l.kind.flux())) },
            "illuminance_lx": match l.kind { invlight_scene::LightKind::Directional { illuminance, .. } =>
                                       json!(luminance(illuminance)), _ => Value::Null }}));
    }
    // Emissive surfaces are area lights: flux π·L·A from their front faces.
    for s in &scene.surfaces {
        let mut flux = 0.0f64;
        let mut centroid = Vec3::ZERO;
        let mut area_sum = 0.0f32;
        for &i in &s.instances {
            let inst = &scene.instances[i as usize];
            let mesh = &scene.meshes[inst.mesh as usize];
            for (t, &m) in mesh.materials.iter().enumerate() {
                let m = &scene.materials[m as usize];
                if !m.is_emissive() {
                    continue;
                }
                let a = mesh.triangle_area(t, &inst.transform);
                let [p, q, r] = mesh.triangle(t).map(|x| inst.transform.transform_point3(x));
                flux += (std::f32::consts::PI * luminance(m.emission) * a) as f64;
                centroid += (p + q + r) / 3.0 * a;
                area_sum += a;
            }
        }
        if flux > 0.0 && s.instances.len() == 1 {
            lights.push(
                json!({"name": s.name, "kind": "area", "position": v(centroid / area_sum),
                "direction": Value::Null, "power_lm": flux, "illuminance_lx": Value::Null}),
            );
        }
    }
    let cameras: Vec<_> = scene
        .cameras
        .iter()
        .map(|c| {
            json!({"name": c.name, "position": v(c.position), "forward": v(c.forward),
                        "yfov_deg": c.yfov.to_degrees()})
        })
        .collect();
    let bounds = scene.bounds().map(|(lo, hi)| json!([v(lo), v(hi)]));
    let out = json!({"surfaces": surfaces, "lights": lights, "cameras": cameras,
                     "bounds": bounds, "up": v(scene.up)});
    if args.json {
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    print_tables(&out);
    Ok(())
}

fn num(x: &Value) -> String {
    x.as_f64()
        .map(|x| format!("{x:.4}"))
        .unwrap_or_else(|| "-".into())
}

fn vec3(x: &Value) -> String {
    match x.as_array() {
        Some(a) => format!("({}, {}, {})", num(&a[0]), num(&a[1]), num(&a[2])),
        None => "-".into(),
    }
}

fn print_tables(out: &Value) {
    let surfaces = out["surfaces"].as_array().expect("built above");
    let w = surfaces
        .iter()
        .map(|s| s["name"].as_str().unwrap_or("").len())
        .max()
        .unwrap_or(4)
        .max(7);
    println!(
        "{:<w$}  {:>9}  {:>12}  material",
        "surface", "triangles", "area m²"
    );
    for s in surfaces {
        let mut material = format!(
            "{} ({})",
            s["material"].as_str().unwrap_or(""),
            s["kind"].as_str().unwrap_or("")
        );
        if s["placement"].as_bool() == Some(true) {
            material = "placement rectangle (not lit)".into();
        }
        println!(
            "{:<w$}  {:>9}  {:>12}  {material}",
            s["name"].as_str().unwrap_or(""),
            s["triangles"].as_u64().unwrap_or(0),
            num(&s["area"])
        );
    }
    println!();
    let lights = out["lights"].as_array().expect("built above");
    if lights.is_empty() {
        println!("no lights");
    } else {
        println!(
            "{:<20}  {:<11}  {:<32}  {:<28}  power",
            "light", "kind", "position", "direction"
        );
        for l in lights {
            let power = if l["power_lm"].is_null() {
                format!("{} lx", num(&l["illuminance_lx"]))
            } else {
                format!("{} lm", num(&l["power_lm"]))
            };
            println!(
                "{:<20}  {:<11}  {:<32}  {:<28}  {power}",
                l["name"].as_str().unwrap_or(""),
                l["kind"].as_str().unwrap_or(""),
                vec3(&l["position"]),
                vec3(&l["direction"])
            );
        }
    }
    println!();
    for c in out["cameras"].as_array().expect("built above") {
        println!(
            "camera {} at {} looking {}",
            c["name"].as_str().unwrap_or(""),
            vec3(&c["position"]),
            vec3(&c["forward"])
        );
    }
    if let Some(b) = out["bounds"].as_array() {
        println!(
            "bounds {} – {}, up {}",
            vec3(&b[0]),
            vec3(&b[1]),
            vec3(&out["up"])
        );
    }
}
