//! Options shared by several subcommands.

use crate::InputError;
use clap::{Args, ValueEnum};
use invlight_photon::{DEFAULT_MAX_BOUNCES, Emitters, TraceSettings};
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

/// Options of every command that traces photons.
#[derive(Args, Debug, Clone)]
pub struct TraceArgs {
    /// Seed of the random streams: the same seed gives the same numbers on any number
    /// of threads.
    #[arg(long, default_value_t = 1, value_name = "S")]
    pub seed: u64,
    /// Surface interactions followed after the first hit. Russian roulette ends paths
    /// without bias; this is a safety cap. 4 reproduces the thesis, which under-counts
    /// light in bright rooms.
    #[arg(long, default_value_t = DEFAULT_MAX_BOUNCES, value_name = "K")]
    pub max_bounces: u32,
    /// Confidence level of the reported intervals.
    #[arg(long, default_value_t = 0.95, value_name = "C")]
    pub confidence: f64,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T")]
    pub threads: Option<usize>,
}

impl TraceArgs {
    /// Checks the options together with the photon count, before anything is loaded.
    pub fn check(&self, photons: u64) -> anyhow::Result<()> {
        check_confidence(self.confidence)?;
        if photons == 0 {
            return Err(InputError("--photons must be at least 1".into()).into());
        }
        Ok(())
    }

    /// The tracing settings for `photons` photons.
    pub fn settings(&self, photons: u64) -> TraceSettings {
        TraceSettings {
            photons,
            seed: self.seed,
            max_bounces: self.max_bounces,
            connect: true,
        }
    }

    /// The thread pool to trace in.
    pub fn pool(&self) -> anyhow::Result<rayon::ThreadPool> {
        Ok(rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .build()?)
    }
}

/// Refuses a scene that has nothing to trace photons from.
pub fn require_light(scene: &Scene, path: &Path) -> anyhow::Result<()> {
    if Emitters::new(scene).is_empty() {
        return Err(InputError(format!(
            "{}: the scene has no light: no point, spot or directional light and no emissive surface",
            path.display()
        ))
        .into());
    }
    Ok(())
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
