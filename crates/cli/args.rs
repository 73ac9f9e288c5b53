//! Options shared by several subcommands.

use crate::InputError;
use clap::{Args, ValueEnum};
use invlight_photon::{DEFAULT_MAX_BOUNCES, Emitters, TraceSettings};
use invlight_scene::{LoadOptions, Scene, SurfaceId, UpAxis};
use invlight_trace::Accel;
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
    /// Memory the scene may take, loading and tracing: 8G, 512M, 64K or bytes (powers of
    /// 1024). A file whose declared sizes (buffers, vertex counts, texture pixels), or
    /// whose ray-tracing structure, would need more is refused with the figure before
    /// anything is allocated. Default: half of this machine's memory.
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
    /// Let the scene file read files anywhere: absolute paths, `..` out of its folder,
    /// links that lead out. Without it only files in the scene's folder tree are read,
    /// as a scene file may come from anyone; use it for files you trust. Devices and
    /// pipes are never read.
    #[arg(long)]
    pub allow_outside_paths: bool,
}

/// A byte count: digits with an optional K, M, G or T (×1024ⁿ), e.g. `8G`, `1.5G`.
fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let (number, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => (
            &t[..i],
            t[i..].trim_end_matches(['B', 'b']).trim_end_matches('i'),
        ),
        None => (t, ""),
    };
    let shift = match unit.to_ascii_uppercase().as_str() {
        "" => 0,
        "K" => 10,
        "M" => 20,
        "G" => 30,
        "T" => 40,
        _ => return Err(format!("'{s}': the unit must be K, M, G or T")),
    };
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a size such as 8G, 512M or 1000000"))?;
    let bytes = value * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(format!("'{s}' is not a size between 1 byte and 16 EiB"));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod parse_size_tests {
    use super::parse_size;

    #[test]
    fn test_max_memory() {
        assert_eq!(parse_size("8G"), Ok(8 << 30));
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("1.5g"), Ok(3 << 29));
        assert_eq!(parse_size("64KiB"), Ok(64 << 10));
        assert_eq!(parse_size("1000000"), Ok(1_000_000));
        for bad in ["", "G", "8X", "-1G", "0", "1e30T", "nan"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }
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
        let defaults = LoadOptions::default();
        let options = LoadOptions {
            scale: self.scale,
            up: self.up.map(|u| match u {
                Up::Y => UpAxis::Y,
                Up::Z => UpAxis::Z,
            }),
            max_memory: self.max_memory.unwrap_or(defaults.max_memory),
            allow_outside_paths: self.allow_outside_paths,
        };
        let scene = invlight_scene::load(path, &options)?;
        let need = Accel::estimated_bytes(&scene);
        if need > options.max_memory {
            return Err(InputError(format!(
                "{}: tracing the scene would need {:.1} GB for its ray-tracing structure, past \
                 the {:.1} GB limit\n  hint: raise --max-memory (e.g. --max-memory {}G) if the \
                 machine has the memory",
                path.display(),
                need as f64 / 1e9,
                options.max_memory as f64 / 1e9,
                need.div_ceil(1 << 30) + 1
            ))
            .into());
        }
        Ok(scene)
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
