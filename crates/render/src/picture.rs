//! A picture of a scene from start to end, as `invlight render` makes one and `solve`
//! makes one per ISOC member: the view chosen from a camera name and an image size, the
//! photon maps built, the pixels computed. One place, so that the two commands cannot
//! render the same scene differently.

use crate::camera::View;
use crate::false_colour::{auto_scale, false_colour};
use crate::integrator::{
    AreaLights, IlluminanceImage, Image, Integrator, RenderSettings, render, render_illuminance,
};
use crate::photon_map::{Paths, PhotonMap, PhotonSettings, Store};
use crate::tonemap::{ToneMap, tone_map};
use image::{ImageFormat, RgbImage};
use invlight_scene::Scene;
use invlight_trace::Accel;
use std::fmt;
use std::path::Path;

/// The largest image invlight renders, in pixels (2²⁸: 16 384 × 16 384).
pub const MAX_PIXELS: u64 = 1 << 28;

/// Why a view cannot be chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum ViewError {
    /// No camera has this name; the scene's cameras are listed.
    NoCamera {
        /// The name asked for.
        name: String,
        /// The cameras there are.
        cameras: Vec<String>,
    },
    /// The image would have no pixels or more than [`MAX_PIXELS`].
    Size(u32, u32),
    /// The scene is empty: there is nothing to look at.
    Empty,
}

impl fmt::Display for ViewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ViewError::NoCamera { name, cameras } if cameras.is_empty() => write!(
                f,
                "no camera named '{name}' (the scene has no camera; leave out --camera for a default view)"
            ),
            ViewError::NoCamera { name, cameras } => write!(
                f,
                "no camera named '{name}'\n  hint: its cameras are {}",
                cameras
                    .iter()
                    .map(|c| format!("'{c}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            ViewError::Size(w, h) => write!(
                f,
                "an image of {w}×{h} pixels cannot be rendered (1 to {MAX_PIXELS} pixels)"
            ),
            ViewError::Empty => write!(f, "the scene is empty"),
        }
    }
}

impl std::error::Error for ViewError {}

/// The view from camera `camera` (the scene's first when `None`, else a view of the
/// whole scene) and the image size: `width`, and `height` or the camera's aspect ratio
/// (4:3 without one).
pub fn choose_view(
    scene: &Scene,
    camera: Option<&str>,
    width: u32,
    height: Option<u32>,
) -> Result<(View, u32, u32), ViewError> {
    let camera = match camera {
        Some(name) => Some(
            scene
                .cameras
                .iter()
                .find(|c| c.name == name)
                .ok_or_else(|| ViewError::NoCamera {
                    name: name.to_string(),
                    cameras: scene.cameras.iter().map(|c| c.name.clone()).collect(),
                })?,
        ),
        None => scene.cameras.first(),
    };
    let height = height.unwrap_or_else(|| {
        let aspect = camera.and_then(|c| c.aspect).unwrap_or(4.0 / 3.0);
        ((width as f32 / aspect).round() as u32).max(1)
    });
    if width == 0 || height == 0 || width as u64 * height as u64 > MAX_PIXELS {
        return Err(ViewError::Size(width, height));
    }
    let aspect = width as f32 / height as f32;
    let view = match camera {
        Some(c) => View::from_camera(c, aspect),
        None => View::default_for(scene, aspect).ok_or(ViewError::Empty)?,
    };
    Ok((view, width, height))
}

/// How a picture is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PictureSettings {
    /// Image width and height, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Photons of the photon map; 0 renders direct light (and what mirrors and glass
    /// show of it) only.
    pub photons: u64,
    /// Photon gather radius, m; `None` from the mean photon density.
    pub radius: Option<f32>,
    /// Final-gather rays per visible diffuse point (0: the photon density there).
    pub final_gather: u32,
    /// Camera rays per pixel.
    pub samples: u32,
    /// Shadow rays to area lights per shading point.
    pub light_samples: u32,
    /// Mirror and glass bounces followed from the camera.
    pub max_depth: u32,
    /// Bounce cap of the photon paths.
    pub max_bounces: u32,
    /// Seed of photons and pixels.
    pub seed: u64,
    /// Store every photon (false colour: illuminance counts all arrivals) instead of
    /// diffuse arrivals only.
    pub illuminance: bool,
}

/// Figures of a renderer's photon maps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MapFigures {
    /// Photons traced.
    pub traced: u64,
    /// Photons stored.
    pub stored: usize,
    /// Gather radius, m.
    pub radius: f32,
    /// Seconds tracing, seconds building the grid.
    pub seconds: (f64, f64),
}

impl fmt::Display for MapFigures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "photon map: {} photons traced in {:.2} s, {} stored, grid built in {:.3} s (radius {:.4} m)",
            self.traced, self.seconds.0, self.stored, self.seconds.1, self.radius
        )
    }
}

/// How radiance becomes a picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Look {
    /// Tone-mapped to sRGB ([`crate::tone_map`]).
    Tone(ToneMap),
    /// The illuminance seen through each pixel in false colour, the scale's top at the
    /// given lux (`None`: the 99th percentile of what is seen).
    FalseColour(Option<f64>),
}

/// A scene ready to render: its acceleration structure, lights and photon maps.
pub struct Renderer<'s> {
    scene: &'s Scene,
    accel: Accel,
    lights: AreaLights,
    /// Without a final gather: the one map of indirect light. With one: the caustics.
    map: Option<PhotonMap>,
    /// The global map's precomputed irradiance, for the final gather.
    gather: Option<PhotonMap>,
    figures: MapFigures,
    settings: PictureSettings,
}

impl<'s> Renderer<'s> {
    /// Builds what `settings` ask for in `scene`; `progress(done, total)` receives the
    /// photons traced (in the calling thread pool).
    pub fn new(
        scene: &'s Scene,
        settings: &PictureSettings,
        progress: Option<&(dyn Fn(u64, u64) + Sync)>,
    ) -> Renderer<'s> {
        let accel = Accel::new(scene);
        let gathering = settings.final_gather > 0;
        let photon_settings = PhotonSettings {
            photons: settings.photons,
            seed: settings.seed,
            max_bounces: settings.max_bounces,
            store: if settings.illuminance {
                Store::All
            } else {
                Store::Diffuse
            },
            radius: settings.radius,
            paths: if gathering {
                Paths::All
            } else {
                Paths::Indirect
            },
            ..PhotonSettings::default()
        };
        let maps = if gathering { 2 } else { 1 };
        let build = |s: &PhotonSettings, k: u64| {
            let report = |done: u64| {
                if let Some(p) = progress {
                    p(k * s.photons + done, maps * s.photons);
                }
            };
            PhotonMap::build(scene, &accel, s, Some(&report))
        };
        let first = (settings.photons > 0).then(|| build(&photon_settings, 0));
        let mut figures = first
            .as_ref()
            .map_or(MapFigures::default(), |m| MapFigures {
                traced: settings.photons,
                stored: m.len(),
                radius: m.radius(),
                seconds: m.seconds(),
            });
        let (map, gather) = match first {
            // A final gather reads the global map at precomputed points (a sixteenth of
            // the photons), thousands of times faster per lookup than the density
            // estimate; caustics get their own map, gathered within the same radius.
            Some(global) if gathering => {
                let caustics = build(
                    &PhotonSettings {
                        paths: Paths::Caustic,
                        radius: Some(global.radius()),
                        ..photon_settings
                    },
                    1,
                );
                figures.traced += settings.photons;
                (Some(caustics), Some(global.precompute(16)))
            }
            other => (other, None),
        };
        Renderer {
            scene,
            lights: AreaLights::new(scene),
            accel,
            map,
            gather,
            figures,
            settings: *settings,
        }
    }

    /// The photon maps' figures.
    pub fn figures(&self) -> MapFigures {
        self.figures
    }

    fn integrator(&self) -> Integrator<'_> {
        let s = &self.settings;
        let integrator = Integrator::new(
            self.scene,
            &self.accel,
            &self.lights,
            self.map.as_ref(),
            RenderSettings {
                width: s.width,
                height: s.height,
                samples: s.samples.max(1),
                light_samples: s.light_samples,
                max_depth: s.max_depth,
                seed: s.seed,
            },
        );
        match &self.gather {
            Some(global) => integrator.with_final_gather(global, s.final_gather),
            None => integrator,
        }
    }

    /// The radiance picture from `view`; `progress` receives the rows done.
    pub fn radiance(&self, view: &View, progress: Option<&(dyn Fn(u64) + Sync)>) -> Image {
        render(&self.integrator(), view, progress)
    }

    /// The picture from `view` as `look` says; `progress` receives the rows done.
    pub fn picture(
        &self,
        view: &View,
        look: &Look,
        progress: Option<&(dyn Fn(u64) + Sync)>,
    ) -> Result<RgbImage, crate::ChartError> {
        match look {
            Look::Tone(tone) => Ok(tone_map(&self.radiance(view, progress), tone)),
            Look::FalseColour(max) => {
                let lux = self.illuminance(view, progress);
                false_colour(&lux, &auto_scale(&lux.lux, *max))
            }
        }
    }

    /// The illuminance seen through every pixel, for false colour.
    pub fn illuminance(
        &self,
        view: &View,
        progress: Option<&(dyn Fn(u64) + Sync)>,
    ) -> IlluminanceImage {
        render_illuminance(&self.integrator(), view, progress)
    }
}

/// Why a picture cannot be written.
#[derive(Debug)]
pub enum SaveError {
    /// The file name's extension names no format invlight writes.
    Format(String),
    /// Encoding or writing failed.
    Io(std::io::Error),
    /// A chart could not be drawn.
    Chart(crate::ChartError),
}

impl fmt::Display for SaveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SaveError::Format(ext) => write!(
                f,
                "cannot write pictures of type '{ext}', expected .png, .jpg or .jpeg"
            ),
            SaveError::Io(e) => write!(f, "{e}"),
            SaveError::Chart(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SaveError {}

/// The format a picture's file name asks for: PNG, or JPEG (quality 90).
pub fn picture_format(path: &Path) -> Result<ImageFormat, SaveError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match ext.as_str() {
        "png" => Ok(ImageFormat::Png),
        "jpg" | "jpeg" => Ok(ImageFormat::Jpeg),
        _ => Err(SaveError::Format(ext)),
    }
}

/// Writes a picture in the format its extension names, through a temporary file, so
/// that a failed write (a full disk) leaves no truncated picture behind.
pub fn save_picture(image: &RgbImage, path: &Path) -> Result<(), SaveError> {
    let format = picture_format(path)?;
    invlight_scene::write_atomically(path, |w| {
        image
            .write_to(w, format)
            .map_err(|e| std::io::Error::other(e.to_string()))
    })
    .map_err(SaveError::Io)
}
