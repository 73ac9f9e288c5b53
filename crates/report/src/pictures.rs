//! The pictures of a solve: the ISOC members rendered, the search plotted.

use invlight_ilp::{Axes, Binding, Configuration, Isoc, Record, Role, is_run_picture, visits};
use invlight_render::{
    Exposure, Mark, PictureSettings, PlotKind, PlotPoint, Renderer, SaveError, SearchPlot, ToneMap,
    View, ViewError, choose_view, log_average, save_picture, tone_map,
};
use invlight_scene::Scene;
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
    view: View,
    settings: PictureSettings,
}

impl Pictures {
    /// Pictures `width` pixels wide (the height from the camera's aspect) of `scene`,
    /// before the search changes it, with photon maps of `photons` photons, traced with
    /// `seed` (the same for every member, so that their differences are the
    /// configurations', not the noise's) and `max_bounces`.
    pub fn new(
        scene: &Scene,
        width: u32,
        photons: u64,
        seed: u64,
        max_bounces: u32,
    ) -> Result<Pictures, PictureError> {
        let (view, width, height) =
            choose_view(scene, None, width, None).map_err(PictureError::View)?;
        Ok(Pictures {
            scene: scene.clone(),
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

    /// Renders `members` (the ISOC in result.json's order) into `dir/isoc-NN.png` after
    /// removing every picture of an earlier one, and plots the search over `records`
    /// into `search.png` (the first variable) and `search-<id>.png`. All members share
    /// the first one's exposure, so a brighter configuration looks brighter.
    /// `progress(done, total)` counts rows of the ISOC pictures.
    pub fn write(
        &self,
        dir: &Path,
        binding: &Binding,
        members: &[Configuration],
        records: &[Record],
        isoc: &Isoc,
        progress: Option<&(dyn Fn(u64, u64) + Sync)>,
    ) -> Result<(), PictureError> {
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
        let mut scene = self.scene.clone();
        let rows = self.settings.height as u64;
        let total = rows * members.len() as u64;
        let mut exposure = None;
        for (k, config) in members.iter().enumerate() {
            binding.apply(&mut scene, config);
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
            save(
                tone_map(&image, &tone),
                dir.join(format!("isoc-{:02}.png", k + 1)),
            )?;
        }
        for (i, v) in binding.space.variables().iter().enumerate() {
            let name = match i {
                0 => "search.png".to_string(),
                _ => format!("search-{}.png", file_safe(&v.id)),
            };
            let path = dir.join(name);
            search_plot(binding, i, records, isoc)
                .write(&path)
                .map_err(|e| PictureError::Save(path, e))?;
        }
        Ok(())
    }
}

/// The plot of variable `i`'s visits.
fn search_plot(binding: &Binding, i: usize, records: &[Record], isoc: &Isoc) -> SearchPlot {
    let (axes, cell, visited) = visits(binding, i, records, isoc);
    SearchPlot {
        kind: match axes {
            Axes::Placement { width, height } => PlotKind::Position { width, height },
            Axes::Direction => PlotKind::Direction,
            Axes::Value { min, max } => PlotKind::Value { min, max },
        },
        cell,
        points: visited
            .into_iter()
            .map(|p| PlotPoint {
                coords: p.coords,
                mean: p.mean,
                low: p.low,
                high: p.high,
                mark: match p.role {
                    Role::Start => Mark::Start,
                    Role::Improvement => Mark::Improvement,
                    Role::Visited => Mark::Visited,
                    Role::Invalid => Mark::Invalid,
                },
                isoc: p.isoc,
            })
            .collect(),
    }
}
