//! The pictures of a solve: the ISOC members rendered, the search plotted.

use crate::describe::{self, compass, subject};
use crate::plots::search_plot;
use invlight_ilp::{Binding, ObjectiveInfo, Record, Standing, VariableValue, is_run_picture};
use invlight_render::{
    Exposure, PictureSettings, Renderer, SaveError, ToneMap, View, ViewError, captioned,
    choose_view, log_average, save_picture, tone_map,
};
use invlight_scene::Scene;
use invlight_stats::significant;
use std::fmt;
use std::path::{Path, PathBuf};

/// A name as a file name: anything but letters, digits, '-' and '_' becomes '_'.
pub fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Why the pictures cannot be made.
#[derive(Debug)]
pub enum PictureError {
    /// No view of the scene at that width.
    View(ViewError),
    /// A picture could not be written.
    Save(PathBuf, SaveError),
    /// The folder could not be read or cleaned.
    Io(PathBuf, std::io::Error),
}

impl fmt::Display for PictureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PictureError::View(e) => write!(f, "{e}"),
            PictureError::Save(p, e) => write!(f, "cannot write {}: {e}", p.display()),
            PictureError::Io(p, e) => write!(f, "{}: {e}", p.display()),
        }
    }
}

impl std::error::Error for PictureError {}

/// What the pictures are made from: the scene as bound to the problem (each member is
/// applied to a copy), the view and the settings, modest by default so that a
/// five-member ISOC takes seconds, not minutes.
pub struct Pictures {
    scene: Scene,
    objective: ObjectiveInfo,
    view: View,
    settings: PictureSettings,
}

impl Pictures {
    /// Pictures `width` pixels wide (the height from the camera's aspect) of `scene`
    /// (captioned with the goal's value, `objective` as result.json gives it),
    /// before the search changes it, with photon maps of `photons` photons, traced with
    /// `seed` (the same for every member, so that their differences are the
    /// configurations', not the noise's) and `max_bounces`.
    pub fn new(
        scene: &Scene,
        objective: &ObjectiveInfo,
        width: u32,
        photons: u64,
        seed: u64,
        max_bounces: u32,
    ) -> Result<Pictures, PictureError> {
        let (view, width, height) =
            choose_view(scene, None, width, None).map_err(PictureError::View)?;
        Ok(Pictures {
            scene: scene.clone(),
            objective: objective.clone(),
            view,
            settings: PictureSettings {
                width,
                height,
                photons,
                radius: None,
                final_gather: 0,
                samples: 2,
                light_samples: 2,
                max_depth: 8,
                max_bounces,
                seed,
                illuminance: false,
            },
        })
    }

    /// Renders the ISOC's members (highest mean first, result.json's order) into
    /// `dir/isoc-NN.png` after removing every picture of an earlier run, each captioned
    /// with its number, its estimate and where what moved is (circled on the picture),
    /// and plots the search over `records` into `search.png` (the first variable) and
    /// `search-<id>.png` (`search-<id>-<element>.png` when two variables share the id,
    /// as a lamp's placement and dimming do). All members share the first one's exposure, so a brighter
    /// configuration looks brighter. `progress(done, total)` counts rows of the ISOC
    /// pictures. Returns what was written, in words, with the seconds it took.
    pub fn write(
        &self,
        dir: &Path,
        binding: &Binding,
        records: &[Record],
        standing: Standing<'_>,
        progress: Option<&(dyn Fn(u64, u64) + Sync)>,
    ) -> Result<String, PictureError> {
        let isoc = standing.isoc;
        let started = std::time::Instant::now();
        let io = |e| PictureError::Io(dir.to_path_buf(), e);
        for entry in std::fs::read_dir(dir).map_err(io)? {
            let entry = entry.map_err(io)?;
            if entry.file_name().to_str().is_some_and(is_run_picture) {
                std::fs::remove_file(entry.path()).map_err(io)?;
            }
        }
        let save = |image, path: PathBuf| {
            save_picture(&image, &path).map_err(|e| PictureError::Save(path, e))
        };
        let chart = |path: &Path, e| PictureError::Save(path.to_path_buf(), SaveError::Chart(e));
        // The ISOC best first; when no configuration met the constraints, the closest.
        let members = match isoc.best_first() {
            m if m.is_empty() => standing.closest.iter().map(|(_, m)| m).collect(),
            m => m,
        };
        let mut scene = self.scene.clone();
        let rows = self.settings.height as u64;
        let total = rows * members.len() as u64;
        let mut exposure = None;
        let start = binding.values(&binding.initial);
        let compass = compass(&self.scene);
        for (k, member) in members.iter().enumerate() {
            binding.apply(&mut scene, &member.config);
            let renderer = Renderer::new(&scene, &self.settings, None);
            let report = |done: u64| {
                if let Some(p) = progress {
                    p(k as u64 * rows + done, total);
                }
            };
            let image = renderer.radiance(&self.view, Some(&report));
            let exposure = *exposure.get_or_insert_with(|| {
                log_average(&image).map_or(Exposure::Auto, Exposure::Luminance)
            });
            let tone = ToneMap {
                exposure,
                compensation: 0.0,
            };
            let goal = &member.evaluation.goal;
            let interval = goal.interval(isoc.z());
            let on = self
                .objective
                .surface
                .as_ref()
                .map_or(String::new(), |s| format!(" on {s}"));
            let which = if isoc.members().is_empty() {
                "Closest to feasible"
            } else {
                "ISOC member"
            };
            let mut lines = vec![format!(
                "{which} {} of {}: {}{} [{}, {}]{on}",
                k + 1,
                members.len(),
                significant(goal.mean),
                self.objective.unit_suffix(),
                significant(interval.low),
                significant(interval.high),
            )];
            let mut marks = Vec::new();
            let values = binding.values(&member.config);
            for ((spec, value), from) in binding.specs.iter().zip(&values).zip(&start) {
                let moved = describe::moved(from, value);
                let moved = moved.split(" (Δ").next().unwrap_or_default();
                let what = describe::value(value, compass.as_ref());
                lines.push(format!("{} {what}, {moved}", subject(spec)));
                if let VariableValue::Position { anchor, .. } = value {
                    let p = anchor.as_vec3();
                    if let Some(px) = self
                        .view
                        .pixel(p, self.settings.width, self.settings.height)
                    {
                        marks.push((px, spec.id.clone()));
                    }
                }
            }
            let path = dir.join(format!("isoc-{:02}.png", k + 1));
            let picture =
                captioned(&tone_map(&image, &tone), &lines, &marks).map_err(|e| chart(&path, e))?;
            save(picture, path)?;
        }
        let variables = binding.space.variables();
        for (i, v) in variables.iter().enumerate() {
            // A lamp placed and dimmed has two variables of one id: each its own file.
            let shared = variables.iter().filter(|w| w.id == v.id).count() > 1;
            let name = match i {
                0 => "search.png".to_string(),
                _ if shared => format!(
                    "search-{}-{}.png",
                    file_safe(&v.id),
                    binding.specs[i].kind.name()
                ),
                _ => format!("search-{}.png", file_safe(&v.id)),
            };
            let path = dir.join(name);
            search_plot(&self.scene, binding, self.objective.cap, i, records, isoc)
                .write(&path)
                .map_err(|e| PictureError::Save(path, e))?;
        }
        Ok(format!(
            "{} ISOC pictures and {} search plots in {:.1} s",
            members.len(),
            binding.space.variables().len(),
            started.elapsed().as_secs_f64()
        ))
    }
}
