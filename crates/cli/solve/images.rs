//! The pictures `invlight solve` leaves beside its files (issue 5 item 3): every ISOC
//! member rendered from the scene's camera with photon mapping (`isoc-NN.png`, as the
//! thesis' tool showed each optimal configuration, §2.6.3), and a plot of the
//! configurations the search visited (`search.png`, the thesis' figures 5.6, 5.8, 5.11).

use crate::progress;
use anyhow::{Context, Result};
use invlight_ilp::{Binding, Configuration, Domain, Interval, Isoc, Record, Verdict};
use invlight_render::{
    Exposure, Integrator, Lights, Mark, Paths, PhotonMap, PhotonSettings, PlotKind, PlotPoint,
    RenderSettings, SearchPlot, Store, ToneMap, View, log_average, render, tone_map,
};
use invlight_scene::Scene;
use invlight_trace::Accel;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// How the ISOC pictures are rendered: modest by default, so that a five-member ISOC
/// takes seconds, not minutes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageSettings {
    /// Width, pixels; the height follows the camera's aspect ratio (else 4:3).
    pub width: u32,
    /// Photons of each picture's photon map (indirect light).
    pub photons: u64,
    /// Camera rays per pixel.
    pub samples: u32,
    /// Seed of the photons and the pixels: the same for every member, so that their
    /// differences are the configuration's, not the noise's.
    pub seed: u64,
    /// Bounce cap of the photon paths.
    pub max_bounces: u32,
}

/// The view of the scene's first camera (a view of the whole scene when it has none) and
/// the image height for `width`.
fn view(scene: &Scene, width: u32) -> Result<(View, u32)> {
    let camera = scene.cameras.first();
    let aspect = camera.and_then(|c| c.aspect).unwrap_or(4.0 / 3.0);
    let height = ((width as f32 / aspect).round() as u32).max(1);
    let aspect = width as f32 / height as f32;
    let view = match camera {
        Some(c) => View::from_camera(c, aspect),
        None => View::default_for(scene, aspect).context("the scene is empty")?,
    };
    Ok((view, height))
}

/// Renders every configuration of `members` (the ISOC, in result.json's order: highest mean first) into
/// `dir/isoc-NN.png` and returns the paths. `scene` is the scene as bound to the problem;
/// each member is applied to a copy. All pictures share the first one's exposure, so a
/// brighter configuration looks brighter.
pub fn write_isoc_images(
    dir: &Path,
    scene: &Scene,
    binding: &Binding,
    members: &[Configuration],
    settings: &ImageSettings,
) -> Result<Vec<PathBuf>> {
    let mut scene = scene.clone();
    let (view, height) = view(&scene, settings.width)?;
    let bar = progress::bar(height as u64 * members.len() as u64, "rows");
    let mut exposure = None;
    let mut written = Vec::with_capacity(members.len());
    for (k, config) in members.iter().enumerate() {
        binding.apply(&mut scene, config);
        let accel = Accel::new(&scene);
        let map = (settings.photons > 0).then(|| {
            PhotonMap::build(
                &scene,
                &accel,
                &PhotonSettings {
                    photons: settings.photons,
                    seed: settings.seed,
                    max_bounces: settings.max_bounces,
                    store: Store::Diffuse,
                    radius: None,
                    paths: Paths::Indirect,
                    ..PhotonSettings::default()
                },
                None,
            )
        });
        let lights = Lights::new(&scene);
        let integrator = Integrator::new(
            &scene,
            &accel,
            &lights,
            map.as_ref(),
            RenderSettings {
                width: settings.width,
                height,
                samples: settings.samples.max(1),
                light_samples: 2,
                max_depth: 8,
                seed: settings.seed,
            },
        );
        let offset = k as u64 * height as u64;
        let report = |done: u64| bar.set_position(offset + done);
        let image = render(&integrator, &view, Some(&report));
        let exposure = *exposure
            .get_or_insert_with(|| log_average(&image).map_or(Exposure::Auto, Exposure::Luminance));
        let picture = tone_map(
            &image,
            &ToneMap {
                exposure,
                compensation: 0.0,
            },
        );
        let path = dir.join(format!("isoc-{:02}.png", k + 1));
        crate::render::save_png(&picture, &path)?;
        written.push(path);
    }
    bar.finish_and_clear();
    Ok(written)
}

/// The plot of variable `i`'s coordinates over the evaluations `records` (in order;
/// rows of a resumed run first), with the final ISOC marked. A fast estimate that was
/// refined shows its full re-evaluation, and a re-evaluated cell its latest estimate.
pub fn search_plot(
    binding: &Binding,
    i: usize,
    records: &[Record],
    isoc: &Isoc,
    z: f64,
) -> SearchPlot {
    let space = &binding.space;
    let cells = space.cells_per_dimension();
    let first = (0..i)
        .map(|j| space.variables()[j].domain.dimensions())
        .sum::<usize>();
    let domain = &space.variables()[i].domain;
    let (kind, cell) = match domain {
        Domain::Rectangle(r) => {
            let (w, h) = (r.e1.length(), r.e2.length());
            (
                PlotKind::Position {
                    width: w,
                    height: h,
                },
                [w / cells[first] as f64, h / cells[first + 1] as f64],
            )
        }
        Domain::Hemisphere(_) => (
            PlotKind::Direction,
            [90.0 / cells[first + 1] as f64, 360.0 / cells[first] as f64],
        ),
        &Domain::Segment { min, max } => (
            PlotKind::Value { min, max },
            [(max - min) / cells[first] as f64, 0.0],
        ),
    };
    let mut points: Vec<PlotPoint> = Vec::new();
    let mut index: HashMap<Vec<u64>, usize> = HashMap::new();
    for r in records.iter().filter(|r| r.verdict != Verdict::Refine) {
        let key: Vec<u64> = r.config.coords.iter().map(|c| c.to_bits()).collect();
        let interval = Interval::of(&r.estimate, z);
        let mark = match r.verdict {
            Verdict::Initial => Mark::Start,
            Verdict::Better => Mark::Improvement,
            Verdict::Invalid => Mark::Invalid,
            _ => Mark::Visited,
        };
        let point = PlotPoint {
            coords: plot_coords(domain, space.slice(&r.config, i)),
            mean: r.estimate.mean,
            low: interval.low,
            high: interval.high,
            mark,
            isoc: isoc.members().iter().any(|m| m.config == r.config),
        };
        match index.get(&key) {
            // A later estimate of the same cell keeps the earlier role unless it is a
            // move of the search.
            Some(&j) => {
                let role = points[j].mark;
                points[j] = PlotPoint {
                    mark: if mark == Mark::Visited { role } else { mark },
                    ..point
                };
            }
            None => {
                index.insert(key, points.len());
                points.push(point);
            }
        }
    }
    // An invalid start is still where the search started.
    if let Some(p) = records.iter().find(|r| r.iteration == 0).and_then(|r| {
        index.get(
            &r.config
                .coords
                .iter()
                .map(|c| c.to_bits())
                .collect::<Vec<_>>(),
        )
    }) {
        points[*p].mark = Mark::Start;
    }
    SearchPlot { kind, cell, points }
}

/// A variable's normalised coordinates `x` in the units of its [`PlotKind`]: metres
/// from vertex A along AB and AD; (θ, φ) in degrees; the colour value V.
fn plot_coords(domain: &Domain, x: &[f64]) -> [f64; 2] {
    match domain {
        Domain::Rectangle(r) => [x[0] * r.e1.length(), x[1] * r.e2.length()],
        Domain::Hemisphere(_) => [x[1] * 90.0, x[0] * 360.0],
        Domain::Segment { min, max } => [min + x[0] * (max - min), 0.0],
    }
}

/// Writes `search.png` for the first variable and `search-<id>.png` for each further
/// one; returns the paths.
pub fn write_search_plots(
    dir: &Path,
    binding: &Binding,
    records: &[Record],
    isoc: &Isoc,
    z: f64,
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (i, v) in binding.space.variables().iter().enumerate() {
        let name = if i == 0 {
            "search.png".to_string()
        } else {
            format!("search-{}.png", file_safe(&v.id))
        };
        let path = dir.join(name);
        search_plot(binding, i, records, isoc, z)
            .write(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// A variable id as a file name: anything but letters, digits, '-' and '_' becomes '_'.
fn file_safe(id: &str) -> String {
    id.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
