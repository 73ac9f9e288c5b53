//! Options shared by several subcommands.

use crate::InputError;
use clap::{Args, ValueEnum};
use invlight_scene::{LoadOptions, Scene, SurfaceId, UpAxis};
use std::path::Path;

/// How to read a scene file.
#[derive(Args, Debug, Clone)]
pub struct LoadArgs {
    /// Metres per file unit, for files authored in other units (e.g. 0.001 for mm). Applied
    /// after the file's own unit declaration (COLLADA <unit meter>).
    #[arg(long, default_value_t = 1.0, value_name = "M")]
    pub scale: f32,
    /// The file's up axis when it does not say (OBJ) or says wrongly. Positions are never
    /// swapped; this orients sun directions in problem files.
    #[arg(long, value_enum, value_name = "AXIS")]
    pub up: Option<Up>,
}

/// An up axis on the command line.
#[derive(ValueEnum, Debug, Clone, Copy)]
pub enum Up {
    /// +Y is up.
    Y,
    /// +Z is up.
    Z,
}

impl LoadArgs {
    /// Loads `path` with these options.
    pub fn load(&self, path: &Path) -> anyhow::Result<Scene> {
        if !(self.scale.is_finite() && self.scale > 0.0) {
            return Err(InputError(format!(
                "--scale {} is not a positive number of metres per unit",
                self.scale
            ))
            .into());
        }
        let options = LoadOptions {
            scale: self.scale,
            up: self.up.map(|u| match u {
                Up::Y => UpAxis::Y,
                Up::Z => UpAxis::Z,
            }),
        };
        Ok(invlight_scene::load(path, &options)?)
    }
}

/// Finds the surface `name`, or explains which names exist.
pub fn find_surface(scene: &Scene, path: &Path, name: &str) -> anyhow::Result<SurfaceId> {
    if let Some(id) = scene.surface(name) {
        // Illuminance is flux over area: a surface without area has none.
        if scene.surface_area(id) <= 0.0 {
            return Err(InputError(format!(
                "{}: the surface '{name}' has no area (its triangles are degenerate)",
                path.display()
            ))
            .into());
        }
        return Ok(id);
    }
    let mut msg = format!("{}: no surface named '{name}'", path.display());
    let lower = name.to_lowercase();
    let close: Vec<&str> = scene
        .surfaces
        .iter()
        .map(|s| s.name.as_str())
        .filter(|s| {
            let s = s.to_lowercase();
            s.contains(&lower) || lower.contains(&s) || edit_distance(&s, &lower) <= 2
        })
        .take(5)
        .collect();
    if !close.is_empty() {
        msg += &format!("\n  hint: did you mean {}?", quoted(&close));
    } else {
        let all: Vec<&str> = scene
            .surfaces
            .iter()
            .map(|s| s.name.as_str())
            .take(12)
            .collect();
        msg += &format!(
            "\n  hint: the scene's surfaces include {}{}; `invlight scene {}` lists them all",
            quoted(&all),
            if scene.surfaces.len() > all.len() {
                ", …"
            } else {
                ""
            },
            path.display()
        );
    }
    if scene.placement(name).is_some() {
        msg += "\n  note: it is a placement rectangle (*__Geometry), which is not lit";
    }
    Err(InputError(msg).into())
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

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("'{n}'"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Checks a confidence level.
pub fn check_confidence(c: f64) -> anyhow::Result<()> {
    if c > 0.0 && c < 1.0 {
        Ok(())
    } else {
        Err(InputError(format!(
            "--confidence {c} must lie strictly between 0 and 1 (e.g. 0.95)"
        ))
        .into())
    }
}
